//! `graftal render`'s style options (`--background`, `--stroke-width`,
//! `--margin`, `--rotate`, `--palette`), each checked on the pixels of the
//! PNG and on the SVG of the same picture.

use crate::common;
use common::{graftal_bytes, temp};
use tiny_skia::Pixmap;

/// A system file `name` of `text`, its path.
fn system(name: &str, text: &str) -> String {
    let p = temp(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// The picture of `file` with `args`, as PNG and as SVG, 200×200.
fn draw(file: &str, args: &[&str]) -> (Pixmap, String) {
    let run = |to: &str| {
        let mut argv = vec!["render", file, "-o", "-", "--to", to, "--size", "200x200"];
        argv.extend_from_slice(args);
        // Every point, absolute, as `svg_points` reads them.
        argv.extend_from_slice(&["--detail", "full"]);
        let (status, out, err) = graftal_bytes(&argv, false);
        assert_eq!(status, 0, "{}", String::from_utf8_lossy(&err));
        out
    };
    let png = Pixmap::decode_png(&run("png")).expect("a PNG");
    (png, String::from_utf8(run("svg")).unwrap())
}

/// The box `[x0, y0, x1, y1]` of the pixels that are not the background's
/// (pixel `(0, 0)`).
fn ink(pm: &Pixmap) -> [u32; 4] {
    let bg = pm.pixel(0, 0).unwrap();
    let mut b = [u32::MAX, u32::MAX, 0, 0];
    for y in 0..pm.height() {
        for x in 0..pm.width() {
            if pm.pixel(x, y).unwrap() != bg {
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
        }
    }
    b
}

/// The numbers of every `M`/`L` point of the SVG's paths.
fn svg_points(svg: &str) -> Vec<[f64; 2]> {
    let mut pts = Vec::new();
    for d in svg.split(" d=\"").skip(1) {
        let d = &d[..d.find('"').unwrap()];
        for p in d.split(['M', 'L']).filter(|p| !p.is_empty()) {
            let mut it = p.trim_end_matches('Z').split(' ');
            let x = it.next().unwrap().parse().unwrap();
            let y = it.next().unwrap().parse().unwrap();
            pts.push([x, y]);
        }
    }
    pts
}

/// `attr="…"` values of the SVG's paths.
fn attrs<'s>(svg: &'s str, attr: &str) -> Vec<&'s str> {
    let key = format!(" {attr}=\"");
    svg.split(key.as_str())
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect()
}

#[test]
fn a_transparent_background_has_alpha_0_and_no_rect() {
    let (png, svg) = draw("std:koch-island", &["--background", "none"]);
    assert_eq!(png.pixel(0, 0).unwrap().alpha(), 0);
    assert!(!svg.contains("<rect"), "{svg}");
    let (png, svg) = draw("std:koch-island", &["--background", "#ff000080"]);
    let p = png.pixel(0, 0).unwrap().demultiply();
    assert_eq!((p.red(), p.green(), p.blue(), p.alpha()), (255, 0, 0, 128));
    assert!(
        svg.contains(r##"<rect width="200" height="200" fill="#ff0000" fill-opacity="0.502"/>"##)
    );
    let (png, svg) = draw("std:koch-island", &["--background", "navy"]);
    let p = png.pixel(0, 0).unwrap();
    assert_eq!((p.red(), p.green(), p.blue(), p.alpha()), (0, 0, 128, 255));
    assert!(svg.contains(r##"fill="#000080""##));
    let (status, _, err) = graftal_bytes(
        &[
            "render",
            "std:koch-island",
            "-o",
            "x.png",
            "--background",
            "mauve",
        ],
        false,
    );
    assert_eq!(status, 2);
    assert!(String::from_utf8_lossy(&err).contains("unknown colour `mauve`"));
}

#[test]
fn a_margin_leaves_a_blank_border() {
    for margin in ["50", "25%", "0.25"] {
        let (png, svg) = draw("std:koch-island", &["--margin", margin]);
        let [x0, y0, x1, y1] = ink(&png);
        assert!(
            x0 >= 50 && y0 >= 50 && x1 < 150 && y1 < 150,
            "{margin}: {:?}",
            [x0, y0, x1, y1]
        );
        // The figure reaches the margin on one side at least.
        assert!(x0 <= 51 || y0 <= 51, "{margin}: {:?}", [x0, y0, x1, y1]);
        let pts = svg_points(&svg);
        assert!(pts
            .iter()
            .all(|p| (50.0..=150.0).contains(&p[0]) && (50.0..=150.0).contains(&p[1])));
    }
}

#[test]
fn rotate_90_turns_a_horizontal_line_vertical() {
    let line = system(
        "line.l",
        "derivation length: 0\nangle factor: 4\naxiom: +FFFF\n",
    );
    let (png, svg) = draw(&line, &[]);
    let [x0, y0, x1, y1] = ink(&png);
    assert!(x1 - x0 > 10 * (y1 - y0 + 1), "{:?}", [x0, y0, x1, y1]);
    let (png, rotated) = draw(&line, &["--rotate", "90"]);
    let [x0, y0, x1, y1] = ink(&png);
    assert!(y1 - y0 > 10 * (x1 - x0 + 1), "{:?}", [x0, y0, x1, y1]);
    // Fitted after turning: it fills 90% of the height as it filled the width.
    assert!(y1 - y0 >= 175, "{:?}", [x0, y0, x1, y1]);
    let (a, b) = (svg_points(&svg), svg_points(&rotated));
    assert!((a[0][1] - a[1][1]).abs() < 1e-9 && (b[0][0] - b[1][0]).abs() < 1e-9);
}

#[test]
fn the_depth_palette_colours_branches_by_depth() {
    let tree = system(
        "tree.l",
        "derivation length: 0\nangle factor: 8\naxiom: F[+F[+F]][-F]\n",
    );
    let (png, svg) = draw(&tree, &["--palette", "depth", "--stroke-width", "5"]);
    let mut colours = attrs(&svg, "stroke");
    colours.dedup();
    assert_eq!(colours.len(), 4, "{svg}");
    let (mono_png, mono) = draw(&tree, &["--palette", "mono"]);
    assert!(attrs(&mono, "stroke").iter().all(|c| *c == "#000000"));
    // The PNG has each colour the SVG strokes with.
    for c in &colours {
        let rgb = u32::from_str_radix(&c[1..], 16).unwrap();
        let [r, g, b] = [(rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8];
        assert!(
            png.pixels()
                .iter()
                .any(|p| (p.red(), p.green(), p.blue()) == (r, g, b)),
            "{c}"
        );
    }
    assert_ne!(png.data(), mono_png.data());
    let (_, rainbow) = draw(&tree, &["--palette", "rainbow"]);
    let mut hues = attrs(&rainbow, "stroke");
    hues.sort();
    hues.dedup();
    assert_eq!(hues.len(), 4, "{rainbow}");
}

#[test]
fn a_stroke_width_sets_the_lines_pixels() {
    let line = system(
        "wide.l",
        "derivation length: 0\nangle factor: 4\naxiom: +FFFF\n",
    );
    let (png, svg) = draw(&line, &["--stroke-width", "12"]);
    assert_eq!(attrs(&svg, "stroke-width"), ["12"]);
    let [_, y0, _, y1] = ink(&png);
    assert!((11..=13).contains(&(y1 - y0 + 1)), "{}", y1 - y0 + 1);
}

/// The distinct stroke colours of an SVG.
fn strokes(svg: &str) -> Vec<&str> {
    let mut colours = attrs(svg, "stroke");
    colours.sort();
    colours.dedup();
    colours
}

#[test]
fn the_depth_palette_colours_splines_by_depth() {
    let tree = system(
        "spline-tree.l",
        "derivation length: 0\nangle factor: 8\naxiom: F[+F[+F]][-F]\n",
    );
    let (png, svg) = draw(&tree, &["--spline", "--palette", "depth"]);
    // Trunk, branches and the branch's branch: three depths.
    assert_eq!(strokes(&svg).len(), 3, "{svg}");
    let (mono, _) = draw(&tree, &["--spline", "--palette", "mono"]);
    assert_ne!(png.data(), mono.data());
}

/// How many pixels of `pm` pass `test` on their red, green and blue.
fn count(pm: &Pixmap, test: impl Fn(i32, i32, i32) -> bool) -> usize {
    pm.pixels()
        .iter()
        .filter(|p| {
            let c = p.demultiply();
            test(
                i32::from(c.red()),
                i32::from(c.green()),
                i32::from(c.blue()),
            )
        })
        .count()
}

#[test]
fn a_palette_recolours_a_lit_cpfg_look() {
    // Cylinders lit by one light, coloured from cpfg's colour map.
    let tree = system(
        "lit-tree.l",
        "Lsystem: 1\nderivation length: 0\nAxiom: F[+F[+F]][-F]\nendlsystem\n",
    );
    system(
        "lit-tree.v",
        "angle factor: 8\ninitial line width: 0.2\nrender mode: shaded\n\
         line style: cylinder\nlight: V: 0 0 1\n",
    );
    let white = ["--background", "white"];
    let not_grey = |r: i32, g: i32, b: i32| r.max(g).max(b) - r.min(g).min(b) > 8;
    let (own, own_svg) = draw(&tree, &white);
    assert!(count(&own, not_grey) > 100, "the look's own colours");
    // Mono: black lines, lit or not; only grey where they meet the white.
    let (mono, mono_svg) = draw(&tree, &[&white[..], &["--palette", "mono"]].concat());
    assert_eq!(count(&mono, not_grey), 0);
    assert_eq!(strokes(&mono_svg), ["#000000"], "{mono_svg}");
    // Depth: a brown trunk and green tips, in the PNG and the SVG scene.
    let (depth, depth_svg) = draw(&tree, &[&white[..], &["--palette", "depth"]].concat());
    assert!(count(&depth, |r, g, b| r > b + 30 && r > g) > 50, "brown");
    assert!(
        count(&depth, |r, g, b| g > r + 30 && g > b + 30) > 50,
        "green"
    );
    assert!(strokes(&depth_svg).len() >= 3, "{depth_svg}");
    assert_ne!(strokes(&own_svg), strokes(&depth_svg), "{depth_svg}");
}
