//! An SVG of a big drawing stays usable (issue 21, item 2): what adds
//! nothing visible at the picture's size is merged away, and the picture
//! stays the same; `--detail full` keeps every segment.

use graftal::driver::{compile, geometry, load, RunOptions};
use graftal::render::{self, Detail, Picture, RenderOptions, Run};
use std::time::Instant;

/// Fig. 3.11a's picture at `steps`, 1024 pixels square, and its segments.
fn fig_3_11a(steps: u64) -> (Picture, usize) {
    let c = compile(load("std:hogeweg-hesper-a").unwrap());
    let sys = c.system.clone().expect("the stdlib entry compiles");
    let opts = RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    };
    let (_, g) = geometry(&sys, &opts).unwrap();
    // Laid out as `render` lays out an SVG: widths kept.
    let ropts = RenderOptions {
        scale: sys.settings.scale,
        thin_dense: false,
        ..RenderOptions::default()
    };
    (render::layout(&g, &ropts), g.segments.len())
}

/// The numbers of a path's `d` after `M`, `L` or `l`, as the ops they follow.
fn ops(d: &str) -> Vec<(char, f64)> {
    let mut out = Vec::new();
    let (mut op, mut number) = ('M', String::new());
    let mut flush = |op: char, number: &mut String| {
        if !number.is_empty() {
            out.push((op, number.parse::<f64>().unwrap()));
            number.clear();
        }
    };
    for ch in d.chars() {
        match ch {
            'M' | 'L' | 'l' => {
                flush(op, &mut number);
                op = ch;
            }
            ' ' => flush(op, &mut number),
            '-' => {
                flush(op, &mut number);
                number.push(ch);
            }
            // A second point in `.5.3` starts a number.
            '.' if number.contains('.') => {
                flush(op, &mut number);
                number.push(ch);
            }
            _ => number.push(ch),
        }
    }
    flush(op, &mut number);
    out
}

/// The polylines of a path's `d` (`M x y L x y …` or `M x y l dx dy …`).
fn polylines(d: &str) -> Vec<Vec<[f64; 2]>> {
    let ops = ops(d);
    let mut lines: Vec<Vec<[f64; 2]>> = Vec::new();
    for pair in ops.chunks(2) {
        let [(op, x), (_, y)] = [pair[0], pair[1]];
        let at = lines.last().and_then(|l| l.last().copied());
        match (op, at) {
            ('M', _) | (_, None) => lines.push(vec![[x, y]]),
            ('l', Some(a)) => lines.last_mut().unwrap().push([a[0] + x, a[1] + y]),
            (_, Some(_)) => lines.last_mut().unwrap().push([x, y]),
        }
    }
    lines
}

/// The value of `name="…"` in `tag`.
fn attribute<'t>(tag: &'t str, name: &str) -> &'t str {
    let start = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    &tag[start..start + tag[start..].find('"').unwrap()]
}

/// The stroked runs an SVG of [`render::svg::write_with`] draws, read back.
fn runs_of(svg: &str, like: &Picture) -> Picture {
    let runs = svg
        .lines()
        .filter(|l| l.starts_with("<path") && l.contains("stroke="))
        .map(|tag| {
            let hex = attribute(tag, "stroke");
            let c = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).unwrap();
            Run {
                colour: graftal::ir::Rgb(c(1), c(3), c(5)),
                width: attribute(tag, "stroke-width").parse().unwrap(),
                lines: polylines(attribute(tag, "d")),
            }
        })
        .collect();
    Picture {
        runs,
        ..like.clone()
    }
}

/// The picture drawn, as the darkness of each 8 × 8 block of pixels.
fn ink(pic: &Picture) -> Vec<f64> {
    let pixmap = render::png::draw(pic).unwrap();
    let (w, h) = (pic.width as usize, pic.height as usize);
    let data = pixmap.data();
    let mut blocks = vec![0.0; (w / 8) * (h / 8)];
    for y in 0..h / 8 * 8 {
        for x in 0..w / 8 * 8 {
            let p = &data[(y * w + x) * 4..][..3];
            let dark = 1.0 - p.iter().map(|&c| f64::from(c)).sum::<f64>() / (3.0 * 255.0);
            blocks[(y / 8) * (w / 8) + x / 8] += dark / 64.0;
        }
    }
    blocks
}

/// Whether python3 reads `svg` as XML; `None` without python3.
fn python_parses(svg: &str) -> Option<bool> {
    use std::io::Write;
    let mut child = std::process::Command::new("python3")
        .args([
            "-c",
            "import sys, xml.etree.ElementTree as E; E.parse(sys.stdin.buffer)",
        ])
        .stdin(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .ok()?;
    child.stdin.take()?.write_all(svg.as_bytes()).ok()?;
    Some(child.wait().ok()?.success())
}

#[test]
fn fig_3_11a_at_60_steps_is_a_small_svg_of_the_same_picture() {
    let t = Instant::now();
    let (pic, segments) = fig_3_11a(60);
    let laid_out = t.elapsed();
    let t = Instant::now();
    let merged = render::svg::write_with(&pic, Detail::Merged);
    let merging = t.elapsed();
    let full = render::svg::write_with(&pic, Detail::Full);
    eprintln!(
        "{segments} segments, laid out in {laid_out:?}; merged SVG {} bytes in {merging:?}, full {} bytes",
        merged.len(),
        full.len()
    );
    assert!(segments > 3_000_000, "{segments}");
    assert!(merged.len() < 5_000_000, "{} bytes", merged.len());
    assert!(full.len() > 50_000_000, "{} bytes", full.len());
    match python_parses(&merged) {
        Some(ok) => assert!(ok, "python3 does not read the merged SVG as XML"),
        None => eprintln!("no python3: the SVG's XML is not checked"),
    }
    // The merged SVG, read back and drawn, has the full picture's ink.
    let (a, b) = (ink(&runs_of(&merged, &pic)), ink(&pic));
    let mean = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64;
    let off = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| (*x - *y).abs() > 0.1)
        .count();
    eprintln!(
        "mean ink difference {mean:.4}, {off} of {} blocks off by > 0.1",
        a.len()
    );
    assert!(mean < 0.01, "{mean}");
    assert!(off * 100 < a.len(), "{off}");
}

#[test]
fn the_full_svg_reads_back_as_the_picture() {
    let (pic, segments) = fig_3_11a(12);
    let full = render::svg::write_with(&pic, Detail::Full);
    let back = runs_of(&full, &pic);
    let count = |p: &Picture| -> usize {
        p.runs
            .iter()
            .flat_map(|r| &r.lines)
            .map(|l| l.len() - 1)
            .sum()
    };
    assert_eq!(count(&back), segments);
    assert!(count(&runs_of(&render::svg::write(&pic), &pic)) < segments);
}

#[test]
fn detail_full_on_the_command_line_keeps_every_segment() {
    let dir = std::env::temp_dir().join(format!("graftal-svg-detail-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let size = |extra: &[&str]| {
        let out = dir.join(format!("{}.svg", extra.len()));
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_graftal"))
            .args(["render", "std:hogeweg-hesper-a", "-n", "20", "-o"])
            .arg(&out)
            .args(extra)
            .status()
            .unwrap();
        assert!(status.success());
        std::fs::metadata(&out).unwrap().len()
    };
    let (merged, full) = (size(&[]), size(&["--detail", "full"]));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(merged * 2 < full, "{merged} {full}");
}
