//! Real cpfg objects drawn with what their view files add to the L-system:
//! tropisms bending the branches and contours shaping generalized
//! cylinders.

use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::source::SourceFile;
use graftal::turtle::Geometry;
use std::path::PathBuf;

fn object(dir: &str, l: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/corpus/cpfg"))
        .join(dir)
        .join(l)
}

/// The system of an object's `.l`, read with its view file; the warnings
/// it gave.
fn compile(dir: &str, l: &str) -> (System, Vec<String>) {
    let c = driver::compile(SourceFile::read(&object(dir, l)).unwrap());
    let said: Vec<String> = c
        .diagnostics
        .iter()
        .map(|d| format!("{} {}", d.code, d.message))
        .collect();
    let sys = c.system.unwrap_or_else(|| panic!("{dir}: {said:#?}"));
    (sys, said)
}

fn draw(sys: &System) -> Geometry {
    driver::geometry(sys, &RunOptions::default()).unwrap().1
}

/// The share of the branches' segments (colours under 250; the leaves' edges,
/// which cpfg draws too, are colours 250 and up) that head downwards.
fn downwards(g: &Geometry) -> f64 {
    let branches: Vec<_> = g.segments.iter().filter(|s| s.index < 250).collect();
    let down = branches.iter().filter(|s| s.b[1] < s.a[1] - 1e-9).count();
    down as f64 / branches.len().max(1) as f64
}

#[test]
fn the_weeping_birch_weeps() {
    let (sys, said) = compile("11-CPFG-WeepingBirch", "fractal.l");
    assert!(!said.iter().any(|d| d.contains("tropism")), "{said:?}");
    // `tropism direction:`, `initial elasticity: 0.4`, `elasticity
    // increment: -0.06`, stepped by `_` at each branching.
    assert_eq!(sys.settings.tropisms.len(), 1);
    let bent = draw(&sys);
    let mut unbent_sys = sys.clone();
    unbent_sys.settings.tropisms.clear();
    let unbent = draw(&unbent_sys);
    assert_eq!(bent.segments.len(), unbent.segments.len());
    // About half the segments hang down, against one in twenty unbent.
    let (b, u) = (downwards(&bent), downwards(&unbent));
    assert!(b > 0.4 && u < 0.1, "downwards: bent {b:.3}, unbent {u:.3}");
}

/// The rings of a swept cross-section of `m` points: each quadrilateral
/// joins points i, i+1 of one ring to the same of the next.
fn rings(quads: &[Vec<[f64; 3]>], m: usize) -> Vec<Vec<[f64; 3]>> {
    quads
        .chunks(m - 1)
        .map(|c| {
            let mut ring: Vec<[f64; 3]> = c.iter().map(|q| q[3]).collect();
            ring.push(c[c.len() - 1][2]);
            ring
        })
        .collect()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// A polyline's length over the distance between its ends.
fn crookedness(p: &[[f64; 3]]) -> f64 {
    let along: f64 = p.windows(2).map(|w| dist(w[0], w[1])).sum();
    along / dist(p[0], p[p.len() - 1])
}

#[test]
fn the_herb_lily_leaf_has_its_contour() {
    let (sys, said) = compile("03-inverse-modeling-01-herb-lily", "plant.l");
    assert!(!said.iter().any(|d| d.contains("contour")), "{said:?}");
    assert_eq!(sys.contours.len(), 1);
    let g = draw(&sys);
    // Its leaf.con says `samples: 8`: 8 faces a ring, one ring per
    // `@Gc(1)` control point, as cpfg sweeps it.
    assert!(
        g.segments.is_empty() && g.polygons.len() >= 400,
        "{}",
        g.polygons.len()
    );
    // Without its contour the leaf is a line again.
    let mut bare = sys.clone();
    bare.contours.clear();
    let line = draw(&bare);
    assert!(line.polygons.is_empty() && !line.segments.is_empty());
    // Every ring across the leaf is the contour, scaled by the width there.
    let contour = &sys.contours[0].points;
    let quads: Vec<Vec<[f64; 3]>> = g.polygons.iter().map(|p| p.points.clone()).collect();
    let rings = rings(&quads, contour.len());
    let shape = crookedness(contour);
    for r in &rings {
        assert!(
            (crookedness(r) - shape).abs() < 1e-6 * shape,
            "{} vs {shape}",
            crookedness(r)
        );
    }
    // The width function swells the leaf and narrows it to its tip.
    let widths: Vec<f64> = rings.iter().map(|r| dist(r[0], r[r.len() - 1])).collect();
    let widest = widths.iter().copied().fold(0.0, f64::max);
    assert!(widest > 3.0 * widths[0] && widest > 10.0 * widths[widths.len() - 1]);
}

#[test]
fn ridley_reads_its_curve() {
    for dir in [
        "11-CPFG-Ridley",
        "03-inverse-modeling-06-phyllotaxis-ridley",
    ] {
        let (sys, said) = compile(dir, "spiral.l");
        assert!(!said.iter().any(|d| d.contains("curve")), "{dir}: {said:?}");
        let g = draw(&sys);
        // One primordium (a sphere) per step along the profile.
        assert!(g.discs.len() > 200, "{dir}: {}", g.discs.len());
        // They sit on the profile: the curve's y runs from −0.45 to 0.2.
        let lowest = g.discs.iter().map(|d| d.centre[1]).fold(f64::MAX, f64::min);
        assert!(lowest < -0.4, "{dir}: {lowest}");
    }
}

#[test]
fn a_curve_the_view_does_not_load_is_an_error_at_its_name() {
    let text = "Lsystem: 1\nStart: {L=curveGAL(1);}\nAxiom: A\nendlsystem\n";
    let c = driver::compile(SourceFile::new("spiral.l", text));
    let at = text.find("curveGAL").unwrap();
    let d = c
        .diagnostics
        .iter()
        .find(|d| d.message.contains("curve"))
        .unwrap_or_else(|| panic!("{:?}", c.diagnostics));
    assert_eq!(d.span.clone().unwrap(), at..at + "curveGAL".len());
    assert!(d.message.contains("loads no curve"), "{}", d.message);
}
