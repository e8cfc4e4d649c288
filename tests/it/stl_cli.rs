//! The STL front end through the command line: derive, stats, render (with
//! and without the layout), translate to a Branch-Expansion Description,
//! and every STL stdlib entry (the paper's figures).

use graftal::driver::{self, Format, RunOptions};
use graftal::render::RenderOptions;
use graftal::stdlib::ENTRIES;

use crate::common;
use common::{graftal, temp};

#[test]
fn derive_prints_the_expanded_drawing_components() {
    let o = graftal(&["derive", "std:stl/fig06-rn"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(o.stdout, "F[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]\n");
    let o = graftal(&["derive", "std:stl/fig04-plant-2"]);
    let one = "F[RF]F[LF]F";
    assert_eq!(o.stdout.trim(), one.replace('F', one));
}

#[test]
fn stats_counts_stems_as_segments() {
    let o = graftal(&["stats", "std:stl/fig06-rn", "--format", "json"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    // The trunk, three level-1 stems, 3 + 2 + 3 level-2 stems.
    assert_eq!(v["segments"], 12);
}

#[test]
fn every_stl_stdlib_entry_checks_derives_and_renders() {
    let stl: Vec<_> = ENTRIES
        .iter()
        .filter(|e| e.name.starts_with("stl/"))
        .collect();
    assert!(stl.len() >= 10);
    for e in stl {
        let c = driver::compile(graftal::source::SourceFile::new(e.file, e.text));
        assert!(c.diagnostics.is_empty(), "{}: {:?}", e.name, c.diagnostics);
        let sys = c.system.unwrap();
        let (word, mut g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
        assert!(!word.is_empty() && !g.segments.is_empty(), "{}", e.name);
        driver::add_layout(&sys, &mut g);
        let layout = sys.structure.as_ref().unwrap().constraint.outline.len();
        assert_eq!(g.polygons.len(), layout, "{}", e.name);
        let opts = RenderOptions {
            width: 64,
            height: 64,
            ..RenderOptions::default()
        };
        let png = driver::render_bytes(&sys, &g, Format::Png, opts).unwrap();
        assert_eq!(&png[..4], b"\x89PNG");
        let svg =
            String::from_utf8(driver::render_bytes(&sys, &g, Format::Svg, opts).unwrap()).unwrap();
        assert!(svg.contains("<svg"), "{}", e.name);
    }
}

#[test]
fn render_draws_the_layout_under_the_tree_unless_told_not_to() {
    let with = temp("with.svg");
    let without = temp("without.svg");
    let o = graftal(&[
        "render",
        "std:stl/fig09-outline-bfs",
        "-o",
        with.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let o = graftal(&[
        "render",
        "std:stl/fig09-outline-bfs",
        "--no-layout",
        "-o",
        without.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let (with, without) = (
        std::fs::read_to_string(with).unwrap(),
        std::fs::read_to_string(without).unwrap(),
    );
    // clMoneyGreen (192, 220, 192) and clOlive (128, 128, 0) fill the shapes,
    // before (under) the stems.
    let money = ["#c0dcc0", "rgb(192,220,192)", "rgb(192, 220, 192)"];
    let at = money
        .iter()
        .find_map(|m| with.find(m))
        .expect("the crown's colour is in the SVG");
    let stem = with
        .find("stroke-width")
        .or_else(|| with.find("stroke"))
        .unwrap();
    assert!(at < stem, "the layout comes before the stems");
    assert!(money.iter().all(|m| !without.contains(m)));
    // A PNG: the crown's colour is in the picture only with the layout.
    let png_with = temp("with.png");
    let png_without = temp("without.png");
    graftal(&[
        "render",
        "std:stl/fig09-outline-bfs",
        "--size",
        "200x200",
        "-o",
        png_with.to_str().unwrap(),
    ]);
    graftal(&[
        "render",
        "std:stl/fig09-outline-bfs",
        "--size",
        "200x200",
        "--no-layout",
        "-o",
        png_without.to_str().unwrap(),
    ]);
    let money_pixels = |p: &std::path::Path| {
        let pm = tiny_skia::Pixmap::load_png(p).unwrap();
        pm.pixels()
            .iter()
            .filter(|c| (c.red(), c.green(), c.blue()) == (192, 220, 192))
            .count()
    };
    assert!(
        money_pixels(&png_with) > 5000,
        "{}",
        money_pixels(&png_with)
    );
    assert_eq!(money_pixels(&png_without), 0);
}

#[test]
fn render_draws_widths_from_b() {
    let sys = graftal::front::stl::read_ok("B = 8 (3)\nR1 = [F][+F]\nSEED\nF R1\nENDSEED\n");
    let g = driver::geometry(&sys, &RunOptions::default()).unwrap().1;
    let opts = RenderOptions {
        width: 600,
        height: 600,
        ..RenderOptions::default()
    };
    let pic = graftal::render::layout(&g, &opts);
    let mut widths: Vec<f64> = pic.runs.iter().map(|r| r.width).collect();
    widths.dedup();
    assert_eq!(widths, vec![8.0, 5.0]);
}

#[test]
fn translate_writes_a_bed_that_renders_the_same() {
    let bed = temp("tree-bed.stl");
    let o = graftal(&[
        "translate",
        "std:stl/fig10-outline-dfs",
        "--to",
        "stl",
        "-o",
        bed.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let text = std::fs::read_to_string(&bed).unwrap();
    assert!(
        text.contains("SEED\nF R1{R1{") && text.contains("LAYOUT"),
        "{text}"
    );
    let a = graftal(&[
        "render",
        "std:stl/fig10-outline-dfs",
        "-o",
        temp("a.svg").to_str().unwrap(),
    ]);
    let b = graftal(&[
        "render",
        bed.to_str().unwrap(),
        "-o",
        temp("b.svg").to_str().unwrap(),
    ]);
    assert_eq!((a.status, b.status), (0, 0), "{}{}", a.stderr, b.stderr);
    assert_eq!(
        std::fs::read(temp("a.svg")).unwrap(),
        std::fs::read(temp("b.svg")).unwrap()
    );
    // To stdout without -o.
    let o = graftal(&["translate", "std:stl/fig06-rn", "--to", "stl"]);
    assert!(o.stdout.contains("R1{R1{}, R2{}, R1{}}"), "{}", o.stdout);
}
