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

/// The share of drawn segments that head downwards.
fn downwards(g: &Geometry) -> f64 {
    let down = g.segments.iter().filter(|s| s.b[1] < s.a[1] - 1e-9).count();
    down as f64 / g.segments.len().max(1) as f64
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
