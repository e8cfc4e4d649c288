//! cpfg's generalized cylinders whose width comes from their radius
//! tangents (`@Gr`): the fern leaflets of the corpus are swept contours of
//! width 0 at both ends.

use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::source::SourceFile;
use graftal::turtle::Geometry;
use std::path::PathBuf;

/// A diagnostic's code and span.
type Said = (String, Option<std::ops::Range<usize>>);

fn compile(src: SourceFile) -> (System, Vec<Said>) {
    let c = driver::compile(src);
    let said = c
        .diagnostics
        .iter()
        .map(|d| (d.code.0.to_string(), d.span.clone()))
        .collect();
    (c.system.expect("a system"), said)
}

fn draw(sys: &System) -> Geometry {
    driver::geometry(sys, &RunOptions::default()).unwrap().1
}

/// The area the polygons cover seen along z (each counted on its own).
fn polygon_area(g: &Geometry) -> f64 {
    g.polygons
        .iter()
        .map(|p| {
            let n = p.points.len();
            let twice: f64 = (0..n)
                .map(|i| {
                    let (a, b) = (p.points[i], p.points[(i + 1) % n]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum();
            twice.abs() / 2.0
        })
        .sum()
}

/// The area the segments cover: length times width.
fn segment_area(g: &Geometry) -> f64 {
    g.segments
        .iter()
        .map(|s| {
            let d: f64 = (0..3).map(|i| (s.b[i] - s.a[i]).powi(2)).sum();
            d.sqrt() * s.width
        })
        .sum()
}

#[test]
fn the_fern_leaf_draws_its_leaflets() {
    for dir in ["03-inverse-modeling-02-fern-leaf", "15-VlabTools-FernLeaf"] {
        let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/corpus/cpfg"))
            .join(dir)
            .join("plant.l");
        let (sys, said) = compile(SourceFile::read(&path).unwrap());
        assert!(!said.iter().any(|(c, _)| c == "W0823"), "{dir}: {said:?}");
        let g = draw(&sys);
        // The leaflets (cylinders of width 0 at both ends, widened by
        // `@Gr`) cover many times what the midrib does.
        let (leaflets, midrib) = (polygon_area(&g), segment_area(&g));
        assert!(
            leaflets > 5.0 * midrib,
            "{dir}: leaflets {leaflets}, midrib {midrib}"
        );
    }
}

const CYLINDER: &str = "Lsystem: 1\nderivation length: 1\n\
    Axiom: @#(1) !(0) @Gr(0,0,90,1) @Gs F(2) @Gr(-90,1,0,0) @Ge(8)\nendlsystem\n";

/// An open contour straight from (−1, 0) to (1, 0): its end points thrice,
/// so that the B-spline runs through them.
const FLAT: &str = "cver 1 3\nname: flat\npoints: 2 6\ntype: o\nsamples: 4\n\
    -1 0 0 3\n1 0 0 3\n";

/// `src` with contour 1 the flat ribbon `FLAT`.
fn with_ribbon(src: &str) -> System {
    let dir = std::env::temp_dir().join(format!("graftal-gr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("flat.con"), FLAT).unwrap();
    std::fs::write(dir.join("a.v"), "contour: 1 flat.con\n").unwrap();
    std::fs::write(dir.join("a.l"), src).unwrap();
    let (sys, said) = compile(SourceFile::read(&dir.join("a.l")).unwrap());
    std::fs::remove_dir_all(&dir).ok();
    assert!(said.is_empty(), "{said:?}");
    sys
}

#[test]
fn radius_tangents_widen_a_cylinder_from_the_l_system() {
    let widest = |sys: &System| {
        draw(sys)
            .polygons
            .iter()
            .flat_map(|p| p.points.iter())
            .fold(0.0f64, |w, p| w.max(p[0].abs().max(p[2].abs())))
    };
    // Rising straight up at the start, falling straight down at the end.
    let wide = widest(&with_ribbon(CYLINDER));
    assert!(wide > 0.2, "{wide}");
    // Without `@Gr` the radius stays 0.
    let plain = CYLINDER
        .replace("@Gr(0,0,90,1) ", "")
        .replace("@Gr(-90,1,0,0) ", "");
    let thin = widest(&with_ribbon(&plain));
    assert!(thin < 1e-9, "{thin}");
}

#[test]
fn an_unknown_cylinder_command_is_a_warning_at_its_span() {
    let src = "Lsystem: 1\nderivation length: 1\nAxiom: F @Gx F\nendlsystem\n";
    let (_, said) = compile(SourceFile::new("test.l", src));
    let at = src.find("@G").unwrap();
    assert_eq!(said, [("W0823".to_string(), Some(at..at + 2))]);
}

/// The end of the first of four pieces of the axis of `axiom`'s cylinder
/// (drawn after the segment of its `F`).
fn first_piece_end(axiom: &str) -> [f64; 3] {
    let src = format!("Lsystem: 1\nderivation length: 1\nAxiom: {axiom}\nendlsystem\n");
    let (sys, said) = compile(SourceFile::new("test.l", src));
    assert!(said.is_empty(), "{said:?}");
    let g = draw(&sys);
    assert_eq!(g.segments.len(), 5);
    g.segments[1].b
}

#[test]
fn tangent_factors_belong_to_the_control_points() {
    // From (0,0) heading +y to (1,0) heading +x. cpfg's `@Gt(a,b)` gives
    // the points that follow a factor for the piece arriving (a) and one
    // for the piece leaving (b): set before `@Gs`, b is the start's.
    let leaving_flat = first_piece_end("@Gt(1,0)@Gs-(90)F@Ge(4)");
    assert!(leaving_flat[1].abs() < 1e-9, "{leaving_flat:?}");
    let leaving_steep = first_piece_end("@Gt(0,1)@Gs-(90)F@Ge(4)");
    assert!(leaving_steep[1] > 0.05, "{leaving_steep:?}");
    // The default, 1.2 both ways.
    let plain = first_piece_end("@Gs-(90)F@Ge(4)");
    assert!(plain[1] > leaving_steep[1], "{plain:?}");
}
