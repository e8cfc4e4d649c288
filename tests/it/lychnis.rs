//! The cpfg Lychnis (`tests/corpus/cpfg/10-GettingStarted-01-Lychnis`,
//! issue 21): what it draws at a step count the test profile affords, and
//! the bound that stops a model drawing more than fits in memory, and its
//! picture drawn straight from the turtle in the memory of the picture.
//!
//! Peak memory is measured with a counting allocator (the test binary's
//! global allocator), each test alone in its process ([`alone`]).

use graftal::driver::picture::{self, Method, Quiet, Request, Target};
use graftal::driver::{self, Format, RunOptions};
use graftal::ir::System;
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use std::path::PathBuf;

use crate::alloc;
use crate::common::alone;

fn lychnis() -> System {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/cpfg/10-GettingStarted-01-Lychnis/plant.l"
    ));
    driver::compile(SourceFile::read(&path).unwrap())
        .system
        .expect("a system")
}

fn at(steps: u64) -> RunOptions {
    RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    }
}

/// At 50 steps the plant has 4 leaves (leaf.s: one patch at precision 6×10,
/// 128 triangles), 2 flower buds of 5 sepals each, and 60 internode
/// segments. A sepal is a generalized cylinder of calyx.con (`samples: 8`:
/// 8 faces a ring) through 11 control points `@Gc(1)` (one ring each) and
/// `@Ge(1)`, so about a hundred quadrilaterals, as cpfg draws it; sampling
/// the contour at 64 points and each piece in 4 rings made 26,832 polygons.
#[test]
fn lychnis_at_50_steps_draws_what_cpfg_draws() {
    let Some(_alone) = alone() else {
        return;
    };
    let sys = lychnis();
    let (_, g) = driver::geometry(&sys, &at(50)).unwrap();
    assert_eq!(g.segments.len(), 60);
    let leaves = 4 * 128;
    let sepals = g.polygons.len() - leaves;
    assert!(
        (10 * 80..=10 * 160).contains(&sepals),
        "{} polygons",
        g.polygons.len()
    );
    // Each sepal's quadrilaterals: 8 a ring.
    let cross_sections: Vec<usize> = sys.contours.iter().map(|c| c.points.len()).collect();
    assert_eq!(cross_sections, vec![9]);
}

/// A model whose surfaces and cylinders would draw more than the move
/// limit is refused with E0303 before anything is drawn, although it moves
/// the turtle far fewer times than the limit.
#[test]
fn surfaces_and_cylinders_count_against_the_move_limit() {
    let Some(_alone) = alone() else {
        return;
    };
    let sys = lychnis();
    let opts = RunOptions {
        max_moves: 2_000,
        ..at(100)
    };
    let (word, values) = driver::derive_values(&sys, &opts, |_, _| {}).unwrap();
    let code = match driver::interpret(&sys, &word, &values, &opts, false) {
        Ok(g) => format!("drawn: {} polygons", g.polygons.len()),
        Err(e) => e.code.0.to_string(),
    };
    assert_eq!(code, "E0303");
    // Under the limit of moves alone: 120 segments at 100 steps.
    let (_, g) = driver::geometry(&sys, &at(100)).unwrap();
    assert!(g.segments.len() < 2_000 && g.polygons.len() > 2_000);
}

/// A lit plant drawn straight from the turtle (`render` of a lit look: the
/// turtle runs once for the framing and once per band, nothing drawn is
/// stored) is the picture drawn from its stored geometry, byte for byte,
/// and takes the memory of its picture rather than of its polygons.
#[test]
fn a_lit_plant_draws_from_the_turtle_as_from_its_stored_geometry_in_little_memory() {
    let Some(_alone) = alone() else {
        return;
    };
    let sys = lychnis();
    let opts = at(430);
    let ropts = RenderOptions {
        width: 300,
        height: 300,
        ..RenderOptions::default()
    };
    // Derived in each way's measure: what the derivation alone holds.
    let (_, word_peak) =
        alloc::peak_during(|| driver::derive_values(&sys, &opts, |_, _| {}).unwrap());
    let (stored, stored_peak) = alloc::peak_during(|| {
        let (word, values) = driver::derive_values(&sys, &opts, |_, _| {}).unwrap();
        let g = driver::interpret(&sys, &word, &values, &opts, false).unwrap();
        let polygons = g.polygons.len();
        (
            driver::render_bytes(&sys, &g, Format::Png, ropts).unwrap(),
            polygons,
        )
    });
    let req = Request {
        run: opts.clone(),
        width: ropts.width,
        height: ropts.height,
        ..Request::new(Target::Still(Format::Png))
    };
    let (drawn, streamed_peak) =
        alloc::peak_during(|| picture::draw_system(&sys, &req, &mut Quiet).unwrap());
    assert_eq!(
        drawn.method,
        Method::Lit,
        "a lit picture is drawn from the turtle"
    );
    let streamed = drawn.bytes;
    let (stored, polygons) = stored;
    assert!(polygons > 100_000, "{polygons} polygons");
    assert!(streamed == stored, "the streamed picture differs");
    // The stored way holds every polygon; the streamed one a band of
    // 900x900 samples (colour and depth: 6.5 MB) a thread, and the word.
    let band_bytes = 900 * 900 * 8;
    assert!(
        streamed_peak < word_peak + 3 * band_bytes && streamed_peak * 4 < stored_peak,
        "streamed {streamed_peak} bytes, stored {stored_peak} bytes, \
         the derivation alone {word_peak} bytes"
    );
}
