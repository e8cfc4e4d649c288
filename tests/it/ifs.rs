//! Fractint's IFS libraries: the corpus (every entry of `fractint.ifs`
//! reads, with its maps and dimension), each diagnostic with its code and
//! span, the attractor drawn at pixel resolution (Sierpinski's triangle
//! against an independent plot of its points, the square that four
//! halves fill, every 2D corpus entry the same bytes twice), and the
//! commands on a graph.

use graftal::driver::picture::{self, Format, Quiet, Request, Source, Target};
use graftal::driver::{compile, compile_entry};
use graftal::ir::graph::InstancingGraph;
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

use crate::common::{graftal, temp};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/fractint/fractint.ifs")
}

fn corpus_text() -> String {
    std::fs::read_to_string(corpus()).unwrap()
}

/// Every entry of `fractint.ifs`: its name, its maps and whether it is 3D.
const ENTRIES: [(&str, usize, bool); 20] = [
    ("binary", 3, false),
    ("coral", 3, false),
    ("crystal", 2, false),
    ("dragon", 2, false),
    ("fern", 4, false),
    ("3dfern", 4, true),
    ("floor", 3, false),
    ("koch3", 5, false),
    ("spiral", 3, false),
    ("swirl5", 2, false),
    ("tree", 4, false),
    ("triangle", 3, false),
    ("zigzag2", 2, false),
    ("3dTetrahedron", 4, true),
    ("3d5Tetrahedron", 5, true),
    ("3dHexahedron", 5, true),
    ("3dCube", 8, true),
    ("3dOctahedron", 6, true),
    ("3dDuodecahedron", 12, true),
    ("fractint", 22, false),
];

fn graph_of(text: &str, name: &str, entry: Option<&str>) -> InstancingGraph {
    let c = compile_entry(SourceFile::new(name, text), entry);
    assert!(c.diagnostics.is_empty(), "{name}: {:#?}", c.diagnostics);
    let sys = c.system.expect("a system");
    assert!(sys.productions.is_empty() && sys.axiom.is_empty());
    sys.graph.expect("a graph")
}

#[test]
fn every_corpus_entry_reads_with_its_maps_and_dimension() {
    let text = corpus_text();
    let c = compile(SourceFile::new("fractint.ifs", text.as_str()));
    assert_eq!(c.front.name(), "ifs");
    assert!(c.diagnostics.is_empty(), "{:#?}", c.diagnostics);
    let lib = c.library.as_ref().expect("a library");
    assert!(c.needs_entry());
    let names: Vec<&str> = lib.entries.iter().map(|e| e.name.as_str()).collect();
    let expected: Vec<&str> = ENTRIES.iter().map(|e| e.0).collect();
    assert_eq!(names, expected);
    assert_eq!(
        lib.summary,
        "Fractint IFS, 20 entries (choose one with FILE:NAME or --entry NAME; 7 of them 3D)"
    );
    for (name, maps, three_d) in ENTRIES {
        // Names are chosen in any case, as in Fractint.
        let g = graph_of(&text, "fractint.ifs", Some(&name.to_uppercase()));
        assert_eq!(g.symbols.len(), 1, "{name}");
        let s = &g.symbols[0];
        assert_eq!(s.name, "A");
        assert!(s.geometry.is_empty() && s.alternative.is_none());
        let rule = s.rule.as_ref().expect("a rule");
        assert_eq!(rule.len(), maps, "{name}");
        assert!(rule.iter().all(|i| i.symbol == 0));
        assert_eq!(g.axiom.len(), 1);
        assert_eq!(g.is_planar(), !three_d, "{name}");
        assert!(g.divergent_cycles().is_empty(), "{name}");
    }
}

#[test]
fn maps_keep_their_numbers_in_place() {
    let g = graph_of(&corpus_text(), "fractint.ifs", Some("fern"));
    let rule = g.symbols[0].rule.as_ref().unwrap();
    // `.85 .04 -.04 .85 0 1.6 .85`: x' = .85x + .04y, y' = -.04x + .85y + 1.6.
    let m = rule[1].transform.0;
    assert_eq!(m[0], [0.85, 0.04, 0.0, 0.0]);
    assert_eq!(m[1], [-0.04, 0.85, 0.0, 1.6]);
    // z scaled by the largest singular value: sqrt(.85² + .04²).
    assert!((m[2][2] - 0.85f64.hypot(0.04)).abs() < 1e-12, "{m:?}");
    assert_eq!([m[2][0], m[2][1], m[2][3]], [0.0; 3]);
    let g = graph_of(&corpus_text(), "fractint.ifs", Some("3dfern"));
    // `.85 .00 0 .0 .85 .1 0 -0.1 0.85 0 1.6 0 .85`: rows, then (j, k, l).
    let m = g.symbols[0].rule.as_ref().unwrap()[1].transform.0;
    assert_eq!(
        m,
        [
            [0.85, 0.0, 0.0, 0.0],
            [0.0, 0.85, 0.1, 1.6],
            [0.0, -0.1, 0.85, 0.0]
        ]
    );
}

#[test]
fn check_lists_every_entry_with_no_error() {
    let path = corpus();
    let out = graftal(&["check", path.to_str().unwrap()]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert!(out.stderr.is_empty(), "{}", out.stderr);
    assert!(
        out.stdout.contains("dialect: Fractint IFS, 20 entries"),
        "{}",
        out.stdout
    );
    assert_eq!(out.stdout.matches(" ok\n").count(), 20, "{}", out.stdout);
}

/// The diagnostics of `text` read as an `.ifs` file: code and the text
/// of its span.
fn diagnostics(text: &str, entry: Option<&str>) -> Vec<(String, String)> {
    let c = compile_entry(SourceFile::new("t.ifs", text), entry);
    c.diagnostics
        .iter()
        .map(|d| {
            let at = d
                .span
                .clone()
                .map_or(String::new(), |s| text[s].to_string());
            (d.code.0.to_string(), at)
        })
        .collect()
}

/// A source, the entry chosen, and the codes it gives with their spans'
/// text.
type Case<'a> = (&'a str, Option<&'a str>, &'a [(&'a str, &'a str)]);

#[test]
fn each_mistake_has_its_code_and_its_place() {
    let cases: &[Case<'_>] = &[
        (
            "a {\n .5 0 0 .5 0 0 1\nb {\n .5 0 0 .5 0 0 1\n}\n",
            Some("a"),
            &[("E1101", "a")],
        ),
        ("a {\n .5 0 0 .5 0 0 1\n", None, &[("E1101", "a")]),
        (
            "fern\n .5 0 0 .5 0 0 1\n}\nb {\n .5 0 0 .5 0 0 1\n}\n",
            Some("b"),
            &[("E1102", ".5 0 0 .5 0 0 1")],
        ),
        ("a {\n .5 0 zero .5 0 0 1\n}\n", None, &[("E1103", "zero")]),
        (
            "a {\n .5 0 0 .5 0 0 1e999\n}\n",
            None,
            &[("E1103", "1e999")],
        ),
        (
            "a {\n .5 0 0 .5 0 0 1\n .5 0 0 .5 1 0\n}\n",
            None,
            &[("E1104", ".5 0 0 .5 1 0")],
        ),
        (
            "a {\n .5 0 0 0 .5 0 0 0 .5 0 0 1 1\n}\n",
            None,
            &[("E1104", ".5 0 0 0 .5 0 0 0 .5 0 0 1 1")],
        ),
        (
            "a (3D) {\n .5 0 0 .5 0 0 1\n}\n",
            None,
            &[("E1104", ".5 0 0 .5 0 0 1")],
        ),
        ("empty { }\n", None, &[("E1105", "empty")]),
        (
            "a {\n 1.5 0 0 .5 0 0 1\n}\n",
            None,
            &[("E1106", "1.5 0 0 .5")],
        ),
        (
            "a (3D) {\n .5 0 0 0 1 0 0 0 .5 0 0 0 1\n}\n",
            None,
            &[("E1106", ".5 0 0 0 1 0 0 0 .5")],
        ),
        ("comment {\n none\n}\n", None, &[("E1108", "")]),
        (
            "a {\n .5 0 0 .5 0 0 .5\n .5 0 0 .5 1 0 .4\n}\n",
            None,
            &[("W1101", "a")],
        ),
        (
            "a {\n .5 0 0 .5 0 0 0\n .5 0 0 .5 1 0 1\n}\n",
            None,
            &[("W1101", "0")],
        ),
        (
            "a {\n .5 0 0 .5 0 0 1\n}\nA {\n .5 0 0 .5 0 0 1\n}\n",
            Some("a"),
            &[("W1102", "A")],
        ),
    ];
    for (text, entry, expected) in cases {
        let got = diagnostics(text, *entry);
        let expected: Vec<(String, String)> = expected
            .iter()
            .map(|(c, s)| (c.to_string(), s.to_string()))
            .collect();
        assert_eq!(got, expected, "{text:?}");
    }
    let many = format!("a {{\n{}}}\n", ".1 0 0 .1 0 0 .01\n".repeat(65));
    let mut got: Vec<String> = diagnostics(&many, None).into_iter().map(|d| d.0).collect();
    got.sort();
    assert_eq!(got, ["E1107", "W1101"]);
}

#[test]
fn a_missing_3d_mark_and_a_missing_probability_are_named() {
    let c = compile(SourceFile::new(
        "t.ifs",
        "a {\n .5 0 0 0 .5 0 0 0 .5 0 0 1 1\n .5 0 0 .5 0 0\n}\n",
    ));
    let helps: Vec<&str> = c
        .diagnostics
        .iter()
        .filter_map(|d| d.help.as_deref())
        .collect();
    assert_eq!(helps.len(), 2);
    assert!(helps[0].contains("`Name (3D) {`"), "{helps:?}");
    assert!(helps[1].contains("probability"), "{helps:?}");
    let c = compile(SourceFile::new("t.ifs", "a {\n 1.5 0 0 .5 0 0 1\n}\n"));
    let d = &c.diagnostics.0[0];
    assert!(d.message.contains("no attractor"), "{}", d.message);
    let label = d.label.as_deref().unwrap_or_default();
    assert!(label.contains("1.5"), "{label}");
}

#[test]
fn good_entries_beside_a_bad_one_keep_working() {
    let text = "bad {\n .5 0 x .5 0 0 1\n}\ngood {\n .5 0 0 .5 0 0 .5\n .5 0 0 .5 1 0 .5\n}\n";
    let c = compile(SourceFile::new("t.ifs", text));
    let lib = c.library.as_ref().unwrap();
    assert_eq!((lib.entries[0].errors, lib.entries[1].errors), (1, 0));
    let g = graph_of(text, "t.ifs", Some("good"));
    assert_eq!(g.symbols[0].rule.as_ref().unwrap().len(), 2);
}

#[test]
fn an_ifs_saved_as_l_says_so() {
    let text = std::fs::read_to_string(corpus()).unwrap();
    let c = compile(SourceFile::new("fractint.l", text.as_str()));
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert_eq!(codes, ["E0015"], "{:#?}", c.diagnostics);
    assert!(c.diagnostics.0[0]
        .help
        .as_deref()
        .unwrap()
        .contains("`.ifs`"));
    // By content, where no extension decides.
    assert_eq!(graftal::front::detect("txt", &text).name(), "ifs");
    assert_eq!(graftal::front::detect("l", &text).name(), "fractint");
}

#[test]
fn the_language_server_is_told_the_entries() {
    let text = corpus_text();
    let ifs = graftal::front::by_name("ifs").unwrap();
    let names: Vec<String> = ifs
        .declarations(&text)
        .into_iter()
        .map(|d| d.name)
        .collect();
    assert_eq!(names.len(), 20);
    assert_eq!(names[4], "fern");
    assert!(!ifs.comment_spans(&text).is_empty());
}

/// The picture of `text` (an `.ifs` file of one entry, or `entry` of
/// it) drawn to `format` at `w` x `h`.
fn draw(text: &str, entry: Option<&str>, format: Format, w: u32, h: u32) -> picture::Picture {
    let source = Source::Text {
        name: "t.ifs".into(),
        text: text.into(),
    };
    let req = Request {
        width: w,
        height: h,
        ..Request::new(Target::Still(format))
    };
    let made = picture::make(&source, entry, None, &req, &mut Quiet);
    let p = made.picture.unwrap_or_else(|e| panic!("{entry:?}: {e}"));
    assert_eq!(p.method, picture::Method::Attractor);
    p
}

/// Which pixels of a PNG are dark (y down).
fn dark(png: &[u8]) -> (u32, u32, Vec<bool>) {
    let p = tiny_skia::Pixmap::decode_png(png).expect("a PNG");
    let set = p.pixels().iter().map(|c| c.red() < 128).collect();
    (p.width(), p.height(), set)
}

/// Sierpinski's triangle with corners (0, 0), (1, 0), (.5, .8): its
/// sides cross the pixels at slopes that pass no row of pixel corners.
const SIERPINSKI: &str =
    "sierpinski {\n .5 0 0 .5 0 0 .33\n .5 0 0 .5 .5 0 .33\n .5 0 0 .5 .25 .4 .34\n}\n";
const CORNERS: [(f64, f64); 3] = [(0.0, 0.0), (1.0, 0.0), (0.5, 0.8)];

/// The pixel of a point of the triangle drawn into 1024 x 1024 with the
/// default margins: its box [0, 1] x [0, .8] fills 90% of the width,
/// centred.
fn pixel_of(x: f64, y: f64) -> (i64, i64) {
    let s = 0.9 * 1024.0;
    let px = 512.0 + (x - 0.5) * s;
    let py = 512.0 - (y - 0.4) * s;
    (px.floor() as i64, py.floor() as i64)
}

/// The point of the plane at the centre of pixel (x, y).
fn point_of(x: i64, y: i64) -> (f64, f64) {
    let s = 0.9 * 1024.0;
    (
        (x as f64 + 0.5 - 512.0) / s + 0.5,
        (512.0 - y as f64 - 0.5) / s + 0.4,
    )
}

/// The centre and radius of the circle inscribed in a triangle.
fn incircle([p, q, r]: [(f64, f64); 3]) -> ((f64, f64), f64) {
    let d = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let (a, b, c) = (d(q, r), d(p, r), d(p, q));
    let area = ((q.0 - p.0) * (r.1 - p.1) - (r.0 - p.0) * (q.1 - p.1)).abs() / 2.0;
    let sum = a + b + c;
    let centre = (
        (a * p.0 + b * q.0 + c * r.0) / sum,
        (a * p.1 + b * q.1 + c * r.1) / sum,
    );
    (centre, 2.0 * area / sum)
}

/// How far `p` is inside the triangle (negative outside): the least
/// distance to the line of a side, signed.
fn depth_in([p, q, r]: [(f64, f64); 3], x: (f64, f64)) -> f64 {
    let side = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        let (nx, ny) = (b.1 - a.1, a.0 - b.0);
        let len = nx.hypot(ny);
        let s = ((x.0 - a.0) * nx + (x.1 - a.1) * ny) / len;
        let inward = ((c.0 - a.0) * nx + (c.1 - a.1) * ny).signum();
        s * inward
    };
    side(p, q, r).min(side(q, r, p)).min(side(r, p, q))
}

#[test]
fn sierpinskis_triangle_covers_the_pixels_it_should() {
    let p = draw(SIERPINSKI, None, Format::Png, 1024, 1024);
    let (w, h, set) = dark(&p.bytes);
    assert_eq!((w, h), (1024, 1024));
    let at = |(x, y): (i64, i64)| set[(y * 1024 + x) as usize];
    // The corners, and a point of each side.
    for (x, y) in CORNERS
        .into_iter()
        .chain([(0.3, 0.0), (0.2, 0.32), (0.7, 0.48)])
    {
        let (x, y) = (x.clamp(0.0005, 0.9995), y.clamp(0.0005, 0.7995));
        assert!(at(pixel_of(x, y)), "({x}, {y})");
    }
    // Each corner triangle holds pixels set near its own middle, the
    // middle triangle removed first none within its inscribed circle
    // (a margin of 10 pixels left), and nothing is outside the triangle.
    let [a, b, c] = CORNERS;
    let mid = |p: (f64, f64), q: (f64, f64)| ((p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0);
    let (centre, radius) = incircle([mid(a, b), mid(b, c), mid(c, a)]);
    let margin = 10.0 / 921.6;
    let mut empty = 0;
    for y in 0..1024i64 {
        for x in 0..1024i64 {
            let (u, v) = point_of(x, y);
            let middle = (u - centre.0).hypot(v - centre.1) < radius - margin;
            let outside = depth_in(CORNERS, (u, v)) < -margin;
            if middle || outside {
                assert!(!at((x, y)), "pixel ({x}, {y}) = ({u:.3}, {v:.3})");
                empty += middle as usize;
            }
        }
    }
    assert!(empty > 20_000, "{empty}");
    for corner in CORNERS {
        let third = [corner, mid(corner, b), mid(corner, c)];
        let (x, y) = (
            (third[0].0 + mid(corner, a).0) / 2.0,
            (third[0].1 + mid(corner, a).1) / 2.0,
        );
        let near = (-8..=8).any(|dy| {
            (-8..=8).any(|dx| {
                let (px, py) = pixel_of(x, y);
                at((px + dx, py + dy))
            })
        });
        assert!(near, "the corner triangle at {corner:?}");
    }
    // Against an independent plot: the corners of the triangles of 11
    // halvings (under half a pixel a side), each a point of the triangle.
    let mut reference = vec![false; 1024 * 1024];
    let mut stack = vec![(a, b, c, 0u32)];
    while let Some((p, q, r, depth)) = stack.pop() {
        if depth == 11 {
            for (x, y) in [p, q, r] {
                let (px, py) = pixel_of(x, y);
                reference[(py.clamp(0, 1023) * 1024 + px.clamp(0, 1023)) as usize] = true;
            }
            continue;
        }
        let (pq, qr, rp) = (mid(p, q), mid(q, r), mid(r, p));
        stack.extend([
            (p, pq, rp, depth + 1),
            (pq, q, qr, depth + 1),
            (rp, qr, r, depth + 1),
        ]);
    }
    let count = |v: &[bool]| v.iter().filter(|&&s| s).count();
    let (ours, theirs) = (count(&set), count(&reference));
    let missed = (0..set.len()).filter(|&i| reference[i] && !set[i]).count();
    // Every pixel set is within a pixel of one the plot sets.
    let near_reference = |i: usize| {
        let (x, y) = ((i % 1024) as i64, (i / 1024) as i64);
        (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                let (u, v) = (x + dx, y + dy);
                (0..1024).contains(&u)
                    && (0..1024).contains(&v)
                    && reference[(v * 1024 + u) as usize]
            })
        })
    };
    assert!((0..set.len()).filter(|&i| set[i]).all(near_reference));
    assert!(
        missed * 100 <= theirs * 3,
        "missed {missed} of {theirs} (drew {ours})"
    );
    assert!(
        ours.abs_diff(theirs) * 100 <= theirs * 3,
        "{ours} against {theirs}"
    );
}

#[test]
fn four_halves_towards_the_corners_fill_the_square() {
    let text = "square {\n .5 0 0 .5 0 0 .25\n .5 0 0 .5 .5 0 .25\n .5 0 0 .5 0 .5 .25\n .5 0 0 .5 .5 .5 .25\n}\n";
    let p = draw(text, None, Format::Png, 200, 200);
    let (_, _, set) = dark(&p.bytes);
    // 90% of 200 pixels: from 10 to 190 (and the pixel the far edge
    // touches).
    for y in 0..200usize {
        for x in 0..200usize {
            let inside = (10..190).contains(&x) && (10..190).contains(&y);
            let edge = (10..=190).contains(&x) && (10..=190).contains(&y);
            if inside {
                assert!(set[y * 200 + x], "({x}, {y}) not set");
            } else if !edge {
                assert!(!set[y * 200 + x], "({x}, {y}) set");
            }
        }
    }
}

#[test]
fn every_2d_corpus_entry_draws_the_same_bytes_twice() {
    let text = corpus_text();
    for (name, _, _) in ENTRIES.iter().filter(|e| !e.2) {
        let a = draw(&text, Some(name), Format::Png, 256, 256);
        let (_, _, set) = dark(&a.bytes);
        let n = set.iter().filter(|&&s| s).count();
        assert!(n > 500, "{name}: {n} pixels");
        // Again, on another thread.
        let b = std::thread::scope(|s| {
            s.spawn(|| draw(&text, Some(name), Format::Png, 256, 256))
                .join()
                .unwrap()
        });
        assert!(a.bytes == b.bytes, "{name}: the bytes differ");
        let svg = draw(&text, Some(name), Format::Svg, 256, 256);
        let svg = String::from_utf8(svg.bytes).unwrap();
        assert!(
            svg.starts_with("<svg ") && svg.contains("<path d=\"M"),
            "{name}"
        );
    }
}

#[test]
fn render_draws_a_2d_entry_flat_and_ray_traces_a_3d_one() {
    let path = corpus();
    let path = path.to_str().unwrap();
    let png = temp("fern.png");
    let out = graftal(&[
        "render",
        path,
        "--entry",
        "fern",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let (w, h, set) = dark(&std::fs::read(&png).unwrap());
    assert_eq!((w, h), (1024, 1024));
    assert!(set.iter().filter(|&&s| s).count() > 50_000);
    let svg = temp("fern.svg");
    let spec = format!("{path}:fern");
    let out = graftal(&[
        "render",
        &spec,
        "--size",
        "300x200",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains(r#"width="300" height="200""#), "{text:.200}");
    // A 3D entry is ray traced (as a 2D one is when asked), and shows.
    for (entry, extra) in [("3dfern", None), ("fern", Some("--raytrace"))] {
        let mut args = vec![
            "render", path, "--entry", entry, "--size", "96x96", "--format", "json",
        ];
        args.extend(extra);
        args.extend(["-o", png.to_str().unwrap()]);
        let out = graftal(&args);
        assert_eq!(out.status, 0, "{entry}: {}", out.stderr);
        let p = tiny_skia::Pixmap::decode_png(&std::fs::read(&png).unwrap()).unwrap();
        let white = |c: &tiny_skia::PremultipliedColorU8| {
            c.red() == 255 && c.green() == 255 && c.blue() == 255
        };
        let drawn = p.pixels().iter().filter(|c| !white(c)).count();
        assert!(drawn > 300, "{entry}: {drawn} pixels drawn");
    }
    let obj = temp("fern.obj");
    let out = graftal(&["render", &spec, "-o", obj.to_str().unwrap()]);
    assert_eq!(out.status, 2, "{}", out.stderr);
    assert!(out.stderr.contains("still picture"), "{}", out.stderr);
}

#[test]
fn derive_refuses_a_graph_and_stats_counts_its_instances() {
    let spec = format!("{}:triangle", corpus().display());
    let out = graftal(&["derive", &spec]);
    assert_eq!(out.status, 1, "{}", out.stderr);
    assert!(out.stderr.contains("E0305"), "{}", out.stderr);
    assert!(out.stdout.is_empty(), "{}", out.stdout);
    // Sierpinski's triangle: 3 maps of 1/2, so 3^k volumes at the cut, k
    // the levels down to a pixel of a 1024x1024 picture (about 10).
    let out = graftal(&["stats", &spec, "--format", "json"]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let v: serde_json::Value = serde_json::from_str(out.stdout.trim()).unwrap();
    let n = v["instances"].as_u64().unwrap();
    assert!((9..=12).any(|k| n == 3u64.pow(k)), "{n} instances");
    assert_eq!(v["method"], "instancing graph");
}

#[test]
fn every_entry_translates_to_gft_and_reads_back_the_same_graph() {
    let path = corpus();
    let c = compile(SourceFile::read(&path).unwrap());
    let names: Vec<String> = c
        .library
        .as_ref()
        .unwrap()
        .entries
        .iter()
        .map(|e| e.name.clone())
        .collect();
    assert_eq!(names.len(), 20);
    for name in names {
        let spec = format!("{}:{name}", path.display());
        let out = graftal(&["translate", &spec, "--to", "gft"]);
        assert_eq!(out.status, 0, "{name}: {}", out.stderr);
        let back = compile(SourceFile::new("back.gft", out.stdout.as_str()));
        assert!(
            back.diagnostics.iter().all(|d| !d.is_error()),
            "{name}: {:?}",
            back.diagnostics
        );
        let original = compile_entry(SourceFile::read(&path).unwrap(), Some(&name));
        let (a, b) = (
            original.system.as_ref().unwrap(),
            back.system.as_ref().unwrap(),
        );
        a.same_as(b)
            .unwrap_or_else(|e| panic!("{name}: {e}\n{}", out.stdout));
    }
}
