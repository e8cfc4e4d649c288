//! cpfg's turtle frame: H = +y, L = −x, U = −z at the start (interpret.c,
//! left-handed); `+` turns H towards L, `&` tilts H towards U, `/` rolls L
//! towards U. graftal's turtle is right-handed, its U is cpfg's −U; what
//! cpfg places along its U (surfaces, `?U`, `@R`'s up) lands where cpfg
//! puts it.

use graftal::driver::{self, RunOptions};
use graftal::front::Front;
use graftal::ir::System;
use graftal::source::SourceFile;
use graftal::turtle::Geometry;

fn system(axiom: &str) -> System {
    let src = format!("Lsystem: 1\nderivation length: 1\nAxiom: {axiom}\nendlsystem\n");
    let c = driver::compile(SourceFile::new("test.l", src));
    c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics))
}

fn draw(sys: &System) -> Geometry {
    driver::geometry(sys, &RunOptions::default()).unwrap().1
}

/// Where the last segment of `axiom` ends, turns of 90°.
fn end_of(axiom: &str) -> [f64; 3] {
    let mut sys = system(axiom);
    sys.settings.delta = 90f64.to_radians();
    let g = draw(&sys);
    g.segments.last().expect("a segment").b
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9)
}

#[test]
fn rolls_turn_the_way_cpfgs_do() {
    // `/` brings L onto cpfg's U (−z), then `+` turns H onto it.
    let e = end_of("/+F");
    assert!(close(e, [0.0, 0.0, -1.0]), "{e:?}");
    let e = end_of("\\+F");
    assert!(close(e, [0.0, 0.0, 1.0]), "{e:?}");
    // Unchanged: `&` tilts H onto cpfg's U, `+` turns left (−x).
    let e = end_of("&F");
    assert!(close(e, [0.0, 0.0, -1.0]), "{e:?}");
    let e = end_of("FF+F");
    assert!(e[0] <= 0.0 && close(e, [-1.0, 2.0, 0.0]), "{e:?}");
    // A roll then a pitch: `/` makes cpfg's U +x, `&` tilts H onto it.
    let e = end_of("/&F");
    assert!(close(e, [1.0, 0.0, 0.0]), "{e:?}");
}

/// The word after one step, queries answered.
fn derived(axiom: &str) -> String {
    let sys = system(axiom);
    let word = driver::derive(&sys, &RunOptions::default()).unwrap();
    graftal::front::cpfg::Cpfg.word_text(&sys, &word)
}

/// The answer of the `?U` of `axiom`.
fn up_answer(axiom: &str) -> [f64; 3] {
    let text = derived(axiom);
    let args = text.split("?U(").nth(1).and_then(|r| r.split(')').next());
    let v: Vec<f64> = args
        .unwrap_or_else(|| panic!("{text}"))
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    [v[0], v[1], v[2]]
}

#[test]
fn the_up_query_answers_cpfgs_up() {
    assert_eq!(derived("?U(9,9,9)"), "?U(0,0,-1)");
    // After a quarter roll cpfg's U is where L was: +x.
    let up = up_answer("/(90)?U(9,9,9)");
    assert!(close(up, [1.0, 0.0, 0.0]), "{up:?}");
}

#[test]
fn set_heading_takes_cpfgs_up() {
    // `@R(0,1,0, 0,0,1)`: cpfg's U = +z, L = H × U = +x; `&` tilts H onto
    // U, `+` turns it onto L.
    let e = end_of("@R(0,1,0,0,0,1)&F");
    assert!(close(e, [0.0, 0.0, 1.0]), "{e:?}");
    let e = end_of("@R(0,1,0,0,0,1)+F");
    assert!(close(e, [1.0, 0.0, 0.0]), "{e:?}");
}

/// A surface of one flat patch at height `z` of its own frame (heading +y,
/// up +z), size 2.
fn flat_surface(z: f64) -> String {
    let mut s = String::from(
        "-1 1 -1 1 0 0\nCONTACT POINT  X: 0.0 Y: -1.0 Z: 0.0\nEND POINT  X: 0 Y: 1 Z: 0\n\
         HEADING  X: 0.00 Y: 1.00 Z: 0.00\nUP  X: 0.00 Y: 0.00 Z: 1.00\nSIZE: 2.00\npatch\n\
         TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00\n\
         AL: ~ A: ~ AR: ~ \nL: ~ R: ~ \nBL: ~ B: ~ BR: ~ \n",
    );
    for i in 0..4 {
        for j in 0..4 {
            let (x, y) = (-1.0 + j as f64 * 2.0 / 3.0, -1.0 + i as f64 * 2.0 / 3.0);
            s.push_str(&format!("{x} {y} {z}  "));
        }
        s.push('\n');
    }
    s
}

/// The points of the surface `~s` drawn after `before`.
fn surface_points(before: &str) -> Vec<[f64; 3]> {
    let dir = std::env::temp_dir().join(format!(
        "graftal-frame-{}-{}",
        std::process::id(),
        before.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("flat.s"), flat_surface(1.0)).unwrap();
    std::fs::write(dir.join("a.v"), "surface: s flat.s 1\n").unwrap();
    let src = format!("Lsystem: 1\nderivation length: 0\nAxiom: {before}~s\nendlsystem\n");
    std::fs::write(dir.join("a.l"), src).unwrap();
    let c = driver::compile(SourceFile::read(&dir.join("a.l")).unwrap());
    std::fs::remove_dir_all(&dir).ok();
    let sys = c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let g = draw(&sys);
    assert!(!g.polygons.is_empty());
    g.polygons.iter().flat_map(|p| p.points.clone()).collect()
}

#[test]
fn a_surface_lies_along_cpfgs_up() {
    // The patch is 1 above its frame's origin along its up, half that
    // drawn (size 2, scale 1): along cpfg's U, −z at the start …
    let points = surface_points("");
    assert!(
        points.iter().all(|p| (p[2] + 0.5).abs() < 1e-9),
        "{points:?}"
    );
    // … and +x after a quarter roll `/(90)`.
    let points = surface_points("/(90)");
    assert!(
        points.iter().all(|p| (p[0] - 0.5).abs() < 1e-9),
        "{points:?}"
    );
}

/// The first segment an object's SVG draws, `[x0, y0, x1, y1]` in
/// pixels of a `size`² picture, drawn with `view` as its view file.
fn first_segment_on_screen(l: &std::path::Path, view: &str, size: u32) -> [f64; 4] {
    std::fs::write(l.with_extension("v"), view).unwrap();
    let sys = driver::compile(SourceFile::read(l).unwrap())
        .system
        .unwrap();
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    let ropts = graftal::render::RenderOptions {
        width: size,
        height: size,
        ..Default::default()
    };
    let svg = driver::render_bytes(&sys, &g, driver::Format::Svg, ropts).unwrap();
    let svg = String::from_utf8(svg).unwrap();
    // The path: `M x0 y0 L x1 y1`.
    let d = svg.split("d=\"M").nth(1).expect("a path");
    let n: Vec<f64> = d
        .split(['L', ' ', '"'])
        .take(4)
        .map(|x| x.parse().unwrap())
        .collect();
    [n[0], n[1], n[2], n[3]]
}

/// cpfg's `twist: N` turns the picture N/10 degrees clockwise on the
/// screen (`ReadViewData` turns the view's up vector about the view normal
/// by +N/10 degrees, `rot_by_quat` being q⁻¹vq with a negated half-angle,
/// then `gluLookAt`): at `twist: 900` a segment along +y points right.
#[test]
fn a_positive_twist_turns_the_picture_clockwise() {
    let l = crate::common::object_file(
        "object",
        "plant.l",
        "Lsystem: 1\nderivation length: 0\nAxiom: F(1)\nendlsystem\n",
    );
    for (twist, right) in [(900, true), (-900, false), (2700, false)] {
        let view = format!("viewpoint: 0,0,1\nview reference point: 0,0,0\ntwist: {twist}\n");
        let [x0, y0, x1, y1] = first_segment_on_screen(&l, &view, 200);
        let (dx, dy) = (x1 - x0, y1 - y0);
        assert!(dy.abs() < 1e-6 * dx.abs().max(1.0), "horizontal at {twist}");
        assert_eq!(dx > 0.0, right, "twist {twist}: {dx}");
    }
}

/// `projection: perspective` fits nothing: cpfg's `gluPerspective` spans
/// the picture's height with the viewing angle, and `scale factor` moves
/// the eye to vrp + (viewpoint − vrp) / scale. A segment from y = −5 to 5
/// seen from 10 away under 90° spans half the picture; at scale factor 2
/// (the eye 5 away) the whole of it.
#[test]
fn a_perspective_is_the_view_files_alone() {
    let l = crate::common::object_file(
        "object",
        "plant.l",
        "Lsystem: 1\nderivation length: 0\nAxiom: f(-5) F(10)\nendlsystem\n",
    );
    for (scale, span) in [(1.0, 100.0), (2.0, 200.0)] {
        let view = format!(
            "viewpoint: 0,0,10\nview reference point: 0,0,0\nprojection: perspective\n\
             viewing angle: 90\nscale factor: {scale}\nfront distance: 0.1\nback distance: 100\n"
        );
        let [x0, y0, x1, y1] = first_segment_on_screen(&l, &view, 200);
        assert!((y0 - y1 - span).abs() < 1e-6, "scale {scale}: {y0} to {y1}");
        assert!((x0 - 100.0).abs() < 1e-6 && x1 == x0 && ((y0 + y1) / 2.0 - 100.0).abs() < 1e-6);
    }
}
