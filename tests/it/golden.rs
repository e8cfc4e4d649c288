//! Golden outputs in naga's style: every tests/in/NAME.l (or .linf) is derived and
//! rendered; tests/out/NAME.txt (the derived word and stats) and
//! tests/out/NAME.svg must equal the output byte for byte. Regenerate on
//! purpose with `GRAFTAL_BLESS=1 cargo test golden`.

use graftal::driver::{compile, geometry, render_bytes, Format, RunOptions};
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use std::path::Path;

use crate::common;
use common::check_golden;

#[test]
fn golden_words_and_svgs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let mut inputs: Vec<_> = std::fs::read_dir(root.join("in"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    inputs.sort();
    assert!(inputs.len() >= 7);
    let mut failures = Vec::new();
    for input in inputs {
        let stem = input.file_stem().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(&input).unwrap();
        let name = input.file_name().unwrap().to_string_lossy().to_string();
        let c = compile(SourceFile::new(name, text));
        let sys = c
            .system
            .clone()
            .unwrap_or_else(|| panic!("{stem}: {:#?}", c.diagnostics));
        let opts = RunOptions {
            seed: 42,
            ..RunOptions::default()
        };
        let (word, g) = geometry(&sys, &opts).unwrap();
        let b = g.bbox().unwrap_or([0.0; 6]);
        let txt = format!(
            "symbols {}\nsegments {}\npolygons {}\nmax_depth {}\nbbox {:.6} {:.6} {:.6} {:.6} {:.6} {:.6}\n{}\n",
            word.len(),
            g.segments.len(),
            g.polygons.len(),
            g.max_depth,
            b[0], b[1], b[2], b[3], b[4], b[5],
            c.word_text(&sys, &word)
        );
        let (azimuth, elevation) = sys.settings.view.unwrap_or((0.0, 0.0));
        let ropts = RenderOptions {
            width: 400,
            height: 400,
            view: graftal::render::View { azimuth, elevation },
            ..RenderOptions::default()
        };
        let svg = String::from_utf8(render_bytes(&sys, &g, Format::Svg, ropts).unwrap()).unwrap();
        for (ext, actual) in [("txt", txt), ("svg", svg)] {
            let out = root.join("out").join(format!("{stem}.{ext}"));
            if let Err(e) = check_golden(&out, &actual) {
                failures.push(e);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
