//! Speed and scale: measuring and drawing context-free systems from their
//! shared derivation tree gives exactly what deriving the word and
//! interpreting it gives, at sizes the word could never be built, in
//! bounded time and memory; limits are errors said up front.
//!
//! A slow suite: it runs when `GRAFTAL_SLOW=1`.
//!
//! Peak memory is measured with a counting allocator (the test binary's
//! global allocator), so the figures are what graftal itself allocates.

use crate::common;
use common::{graftal, slow, temp};

use graftal::driver::picture::{self, Method, Quiet, Request, Target};
use graftal::driver::{self, compile, compile_entry, Format, RunOptions};
use graftal::ir::System;
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use graftal::turtle;
use std::path::Path;
use std::time::Instant;

use crate::alloc;
/// Each test of this file runs alone in its process ([`alone`]).
use common::alone;

/// The most heap `f` had live at once (other tests' threads included, so
/// tests that measure run [`alone`]).
fn peak<T>(f: impl FnOnce() -> T) -> (T, usize) {
    alloc::peak_during(f)
}

fn std_system(name: &str) -> System {
    let c = compile(driver::load(&format!("std:{name}")).unwrap());
    c.system.unwrap_or_else(|| panic!("std:{name}"))
}

fn steps(n: u64) -> RunOptions {
    RunOptions {
        steps: Some(n),
        ..RunOptions::default()
    }
}

/// Written symbols, segments, polygons, bounding box and deepest nesting.
type Figures = (usize, usize, usize, Option<[f64; 6]>, usize);

/// The reference: derive the word, interpret it into stored geometry.
fn reference(sys: &System, n: u64) -> Option<Figures> {
    let opts = RunOptions {
        max_symbols: 2_000_000,
        ..steps(n)
    };
    let word = driver::derive(sys, &opts).ok()?;
    let g = turtle::Run::word(sys, &word, 0).geometry();
    let written = word
        .0
        .iter()
        .filter(|&&s| !sys.symbols.name(s).is_empty())
        .count();
    Some((
        written,
        g.segments.len(),
        g.polygons.len(),
        g.bbox(),
        g.max_depth,
    ))
}

/// `stats` against the reference for one system at `n` steps; the method
/// `stats` used.
fn check_stats(what: &str, sys: &System, n: u64) -> Option<&'static str> {
    let (symbols, segments, polygons, bbox, depth) = reference(sys, n)?;
    let s = driver::stats(sys, &steps(n)).unwrap_or_else(|d| panic!("{what}: {d:?}"));
    assert_eq!(s.symbols, symbols as u128, "{what} n={n} ({})", s.method);
    assert_eq!(s.segments, segments as u128, "{what} n={n} ({})", s.method);
    assert_eq!(s.polygons, polygons as u128, "{what} n={n} ({})", s.method);
    assert_eq!(s.max_depth, depth, "{what} n={n} ({})", s.method);
    let want = bbox.unwrap_or([0.0; 6]);
    let got = s.bbox.unwrap_or_else(|| panic!("{what} n={n}: no box"));
    let size = (0..3).map(|k| want[k + 3] - want[k]).fold(1.0f64, f64::max);
    for k in 0..6 {
        assert!(
            (got[k] - want[k]).abs() <= 1e-9 * size,
            "{what} n={n} ({}): bbox {got:?} vs {want:?}",
            s.method,
        );
    }
    Some(s.method)
}

#[test]
fn stats_agree_with_interpreting_the_derived_word_for_every_stdlib_system() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    let mut shared = 0;
    let mut checked = 0;
    for name in graftal::stdlib::names() {
        let sys = std_system(name);
        // An instancing graph has no word: its stats count instances
        // (tests/it/ifs.rs, tests/it/gft_graph.rs).
        if sys.rewrites_modules() || sys.graph.is_some() {
            continue;
        }
        let top = sys.settings.steps.unwrap_or(4).min(8);
        for n in [1, top / 2, top] {
            if let Some(method) = check_stats(name, &sys, n) {
                checked += 1;
                shared += usize::from(method == "shared subtrees");
            }
        }
    }
    assert!(checked >= 150, "{checked} checked");
    assert!(shared >= 90, "{shared} of {checked} on shared subtrees");
}

#[test]
fn stats_agree_with_interpreting_the_derived_word_for_fractint_entries() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/fractint");
    let mut shared = 0;
    let mut checked = 0;
    for file in ["fractint.l", "penrose.l", "tiling.l"] {
        let path = dir.join(file);
        let names: Vec<String> = compile(SourceFile::read(&path).unwrap())
            .library
            .expect("a library")
            .entries
            .iter()
            .map(|e| e.name.clone())
            .collect();
        for name in names {
            let c = compile_entry(SourceFile::read(&path).unwrap(), Some(&name));
            let sys = c.system.unwrap();
            for n in [2, 4] {
                if let Some(method) = check_stats(&format!("{file}:{name}"), &sys, n) {
                    checked += 1;
                    shared += usize::from(method == "shared subtrees");
                }
            }
        }
    }
    assert!(checked >= 150, "{checked} checked");
    assert!(shared >= 60, "{shared} of {checked} on shared subtrees");
}

/// The quadratic Koch island after `n` steps, in closed form: 4·8ⁿ
/// segments; from the start (0, 0), heading up, the island spans
/// −(4ⁿ − 1)/3 .. (4ⁿ⁺¹ − 1)/3 on both axes (each step scales the
/// generator by 4; the sums are geometric).
fn koch_island(n: u32) -> (u128, f64, f64) {
    let p = 4f64.powi(n as i32);
    (4 * 8u128.pow(n), -(p - 1.0) / 3.0, (4.0 * p - 1.0) / 3.0)
}

#[test]
fn the_koch_island_closed_form_is_what_the_turtle_draws() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    let sys = std_system("koch-island");
    for n in 0..=5 {
        let (segments, lo, hi) = koch_island(n);
        let (_, segs, _, bbox, _) = reference(&sys, u64::from(n)).unwrap();
        assert_eq!(segs as u128, segments, "n={n}");
        // The turtle adds up rounding errors step by step.
        let want = [lo, lo, 0.0, hi, hi, 0.0];
        for (got, want) in bbox.unwrap().iter().zip(want) {
            assert!((got - want).abs() < 1e-9 * hi, "n={n}: {bbox:?}");
        }
    }
}

#[test]
fn koch_island_at_12_steps_is_counted_and_boxed_exactly_in_little_time_and_memory() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    let sys = std_system("koch-island");
    let t = Instant::now();
    let (s, bytes) = peak(|| driver::stats(&sys, &steps(12)).unwrap());
    let secs = t.elapsed().as_secs_f64();
    let (segments, lo, hi) = koch_island(12);
    assert_eq!(s.method, "shared subtrees");
    assert_eq!(s.segments, segments);
    assert_eq!(s.segments, 274_877_906_944);
    assert_eq!(s.bbox, Some([lo, lo, 0.0, hi, hi, 0.0]));
    // 4 (1 + 13 (8^12 − 1) / 7) + 3 symbols.
    assert_eq!(s.symbols, 4 * (1 + 13 * (8u128.pow(12) - 1) / 7) + 3);
    assert!(secs < 2.0, "{secs} s");
    assert!(bytes < 100 << 20, "{bytes} bytes");
    // Memory grows with the depth, not the word: 24 steps (10²² segments)
    // take no more than a few times what 12 took.
    let (s24, bytes24) = peak(|| driver::stats(&sys, &steps(24)).unwrap());
    assert_eq!(s24.segments, koch_island(24).0);
    assert!(bytes24 < 4 * bytes.max(64 << 10), "{bytes24} vs {bytes}");
}

fn dark(png: &[u8]) -> Vec<bool> {
    let p = tiny_skia::Pixmap::decode_png(png).unwrap();
    p.pixels()
        .iter()
        .map(|c| u32::from(c.red()) + u32::from(c.green()) + u32::from(c.blue()) < 3 * 128)
        .collect()
}

fn render_both(name: &str, n: u64, size: u32) -> (Vec<u8>, Vec<u8>) {
    let sys = std_system(name);
    let ropts = RenderOptions {
        width: size,
        height: size,
        ..RenderOptions::default()
    };
    let req = Request {
        run: steps(n),
        width: size,
        height: size,
        ..Request::new(Target::Still(Format::Png))
    };
    let drawn = picture::draw_system(&sys, &req, &mut Quiet).unwrap();
    assert_eq!(drawn.method, Method::SharedSubtrees, "{name}");
    let shared = drawn.bytes;
    let (_, g) = driver::geometry(&sys, &steps(n)).unwrap();
    let full = driver::render_bytes(&sys, &g, Format::Png, ropts).unwrap();
    (shared, full)
}

#[test]
fn pictures_from_shared_subtrees_match_pictures_of_every_segment() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    // Segments of several pixels: nothing is within a pixel, the same
    // polylines are drawn.
    for (name, n) in [("koch-island", 3), ("dragon", 8), ("hilbert", 4)] {
        let (a, b) = render_both(name, n, 512);
        let (a, b) = (dark(&a), dark(&b));
        let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
        assert!(differ <= a.len() / 2000, "{name}: {differ} pixels differ");
    }
    // Segments of a fraction of a pixel: subtrees within a pixel are drawn
    // as one line each; the same pixels are inked.
    for (name, n, size) in [("koch-island", 5, 256), ("dragon", 14, 256)] {
        let (a, b) = render_both(name, n, size);
        let (a, b) = (dark(&a), dark(&b));
        let both = a.iter().zip(&b).filter(|(x, y)| **x && **y).count();
        let either = a.iter().zip(&b).filter(|(x, y)| **x || **y).count();
        assert!(
            both as f64 >= 0.9 * either as f64,
            "{name} n={n}: {both} of {either} dark pixels shared"
        );
    }
}

#[test]
fn koch_island_at_8_steps_renders_in_bounded_time_and_memory() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    let out = temp("koch8.png");
    let t = Instant::now();
    let (o, bytes) = peak(|| {
        graftal(&[
            "render",
            "std:koch-island",
            "-n",
            "8",
            "-o",
            out.to_str().unwrap(),
        ])
    });
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(o.status, 0, "{}", o.stderr);
    // No progress bar in a pipe.
    assert!(o.stderr.is_empty(), "{}", o.stderr);
    assert!(secs < 10.0, "{secs} s");
    assert!(bytes < 400 << 20, "{bytes} bytes");
    let inked = dark(&std::fs::read(&out).unwrap())
        .iter()
        .filter(|&&d| d)
        .count();
    assert!(inked > 50_000, "{inked} dark pixels");
}

#[test]
fn limits_are_said_before_the_work_starts() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    // 8 · 10¹⁰ symbols: the exact length is known before deriving.
    let t = Instant::now();
    let o = graftal(&["derive", "std:koch-island", "-n", "12"]);
    assert_eq!(o.status, 1);
    assert!(o.stderr.contains("E0301"), "{}", o.stderr);
    assert!(o.stderr.contains("step 9 of 12"), "{}", o.stderr);
    assert!(o.stdout.is_empty());
    assert!(t.elapsed().as_secs_f64() < 1.0);
}

#[test]
fn a_picture_too_big_to_draw_segment_by_segment_is_refused_before_deriving() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    // A colour change keeps it off the shared-subtree renderer; 2^26 · 2
    // moves are over the drawing limit, and the tree knows it at once.
    let f = temp("big.l");
    std::fs::write(&f, "axiom: F'F\nF --> FF\n").unwrap();
    let out = temp("big.png");
    let t = Instant::now();
    let o = graftal(&[
        "render",
        f.to_str().unwrap(),
        "-n",
        "26",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(o.stderr.contains("E0303"), "{}", o.stderr);
    assert!(o.stderr.contains("known before deriving"), "{}", o.stderr);
    assert!(t.elapsed().as_secs_f64() < 1.0);
    // A polygon keeps `stats` off shared subtrees: the word is streamed
    // through the turtle, nothing kept.
    let f = temp("polygon.l");
    std::fs::write(&f, "axiom: F{F+F+F}\nF --> FF\n").unwrap();
    let o = graftal(&["stats", f.to_str().unwrap(), "-n", "12", "--format", "json"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    assert_eq!(v["method"], "streamed");
    assert_eq!(v["segments"], 4096);
    assert_eq!(v["polygons"], 1);
}

#[test]
fn derive_prints_the_word_of_step_by_step_rewriting() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    // Written from the shared tree (Koch), through the look-up table
    // (Fig. 3.11a) and by the general matcher (a two-symbol predecessor).
    let ab = temp("ab.l");
    std::fs::write(&ab, "axiom: ab\nab --> aab\na --> b\n").unwrap();
    for (file, n) in [
        ("std:koch-island", 4),
        ("std:hogeweg-hesper-a", 30),
        (ab.to_str().unwrap(), 6),
    ] {
        let c = compile(driver::load(file).unwrap());
        let sys = c.system.unwrap();
        let d = graftal::eval::Deriver::new(&sys);
        let want = d
            .derive_stepwise(&graftal::eval::DeriveOptions::new(n), |_, _| {})
            .unwrap()
            .display(&sys.symbols);
        let o = graftal(&["derive", file, "-n", &n.to_string()]);
        assert_eq!(o.status, 0, "{}", o.stderr);
        assert_eq!(o.stdout, format!("{want}\n"), "{file}");
    }
}

/// A sink that counts the bytes written to it: a pipe that keeps nothing.
struct CountingSink(usize);

impl std::io::Write for CountingSink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0 += buf.len();
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_context_sensitive_derivation_to_a_pipe_holds_at_most_two_bytes_a_symbol() {
    if !slow("scale: speed and memory bounds at scale") {
        return;
    }
    let Some(_one) = alone() else {
        return;
    };
    // Fig. 3.11a: one-symbol contexts, brackets, 7 symbols; 4.5 M symbols
    // at 57 steps. A step holds the word it rewrites and the word it
    // writes (1.27 times as long): 1.8 bytes a symbol of the final word,
    // where a right-neighbour array beside them made 2.6, and a doubling
    // output vector up to 3.3.
    let c = compile(driver::load("std:hogeweg-hesper-a").unwrap());
    let sys = c.system.as_ref().unwrap();
    let mut sink = CountingSink(0);
    let (done, bytes) =
        peak(|| driver::write_derived(c.front, sys, &steps(57), &mut sink, |_, _| {}).is_ok());
    assert!(done);
    let symbols = sink.0 - 1;
    assert!(symbols > 4_000_000, "{symbols} symbols");
    let per_symbol = bytes as f64 / symbols as f64;
    assert!(
        per_symbol <= 2.0,
        "{bytes} bytes at peak for {symbols} symbols: {per_symbol:.2} a symbol"
    );
}
