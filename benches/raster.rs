//! Drawing a model that must be drawn segment by segment (issue 21, item
//! 1): Fig. 3.11a (`std:hogeweg-hesper-a`, context-sensitive) at 60 steps,
//! 3.36 M segments, to a 1024x1024 PNG, derivation included.
//!
//! * `raster/streamed`: [`driver::derive_symbols`] then
//!   `driver::picture`'s streamed way: the word kept a byte a symbol, the
//!   turtle run twice over it (bounds, then drawing), each segment drawn
//!   into the coverage buffer as it is made; no segment is stored.
//! * the baseline, measured once in the same run (it takes seconds): the
//!   stored way, [`driver::geometry`] + [`render::layout`] +
//!   [`render::png::encode`], which keeps every segment (about 150 bytes
//!   each with the layout). That way stays for what needs storage: a 3D
//!   drawing seen from the side (the painter's order sorts every segment
//!   by depth), polygons and discs (drawn under all the lines), splines
//!   and palettes that need the totals; lit looks go through the z-buffer
//!   ([`render::raster`]).
//! * `lit/lychnis/600`: the cpfg Lychnis (tests/corpus/cpfg/
//!   10-GettingStarted-01-Lychnis) at 600 steps, 3.05 M polygons lit and
//!   z-buffered, to a 1024x1024 PNG, derivation included:
//!   `driver::picture`'s lit way, the turtle run once for the framing and once
//!   per thread's share of the picture, nothing drawn stored; against the
//!   stored way ([`driver::interpret`] + [`driver::render_bytes`]), which
//!   keeps every polygon, measured once in the same run. A z-buffer needs
//!   no order, so nothing of a lit picture needs storing.
//! * `derive-pipe`: the derived word written to a sink as `graftal derive
//!   … | …` writes it, and the peak heap per symbol of the final word.
//!
//! Peak memory is the peak of live heap bytes (a counting allocator, as in
//! `benches/throughput.rs`), printed as `peak memory: …` lines.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use graftal::driver::picture::{self, Format, Method, Quiet, Request, Target};
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::render::{self, RenderOptions};
use std::hint::black_box;
use std::time::Instant;

#[path = "common/alloc.rs"]
mod alloc;
#[path = "common/config.rs"]
mod config;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

const STEPS: u64 = 60;

fn load(name: &str) -> System {
    let file = driver::load(&format!("std:{name}")).expect("stdlib entry");
    driver::compile(file)
        .system
        .unwrap_or_else(|| panic!("std:{name} does not compile"))
}

fn run_options() -> RunOptions {
    RunOptions {
        steps: Some(STEPS),
        ..RunOptions::default()
    }
}

fn render_options(sys: &System) -> RenderOptions {
    RenderOptions {
        scale: sys.settings.scale,
        ..RenderOptions::default()
    }
}

/// The streamed way, from the system to PNG bytes.
fn streamed(sys: &System) -> Vec<u8> {
    let req = Request {
        run: run_options(),
        ..Request::new(Target::Still(Format::Png))
    };
    let p = picture::draw_system(sys, &req, &mut Quiet).expect("draws");
    assert_eq!(p.method, Method::Streamed, "Fig. 3.11a is drawn streamed");
    p.bytes
}

/// The stored way: every segment kept, laid out, then stroked.
fn stored(sys: &System) -> (Vec<u8>, usize) {
    let (_, g) = driver::geometry(sys, &run_options()).expect("derives");
    let pic = render::layout(&g, &render_options(sys));
    (render::png::encode(&pic).expect("png"), g.segments.len())
}

fn bench_raster(c: &mut Criterion) {
    let sys = load("hogeweg-hesper-a");
    let t = Instant::now();
    let ((_, segments), stored_peak) = peak_during(|| stored(&sys));
    let stored_time = t.elapsed();
    let t = Instant::now();
    let (_, streamed_peak) = peak_during(|| streamed(&sys));
    let streamed_time = t.elapsed();
    println!(
        "peak memory: hogeweg-hesper-a n={STEPS} 1024x1024 PNG, {segments} segments: \
         {} in {:.2} s (streamed) vs {} in {:.2} s (baseline: stored)",
        mib(streamed_peak),
        streamed_time.as_secs_f64(),
        mib(stored_peak),
        stored_time.as_secs_f64(),
    );
    let mut group = c.benchmark_group("raster");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(segments as u64));
    group.bench_function("streamed/hogeweg-hesper-a/60", |b| {
        b.iter(|| streamed(black_box(&sys)))
    });
    group.finish();
}

fn lychnis() -> System {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/cpfg/10-GettingStarted-01-Lychnis/plant.l"
    );
    let file = graftal::source::SourceFile::read(std::path::Path::new(path)).expect("Lychnis");
    driver::compile(file).system.expect("Lychnis compiles")
}

const LYCHNIS_STEPS: u64 = 600;

/// The Lychnis's word and the values its homomorphism reads.
fn lychnis_word(sys: &System) -> (graftal::ir::Word, driver::Globals, RunOptions) {
    let opts = RunOptions {
        steps: Some(LYCHNIS_STEPS),
        ..RunOptions::default()
    };
    let (word, values) = driver::derive_values(sys, &opts, |_, _| {}).expect("derives");
    (word, values, opts)
}

/// Derived and drawn straight from the turtle.
fn lit_streamed(sys: &System) -> Vec<u8> {
    let req = Request {
        run: RunOptions {
            steps: Some(LYCHNIS_STEPS),
            ..RunOptions::default()
        },
        ..Request::new(Target::Still(Format::Png))
    };
    let p = picture::draw_system(sys, &req, &mut Quiet).expect("draws");
    assert_eq!(p.method, Method::Lit, "drawn from the turtle");
    p.bytes
}

/// Derived, every polygon stored, then drawn.
fn lit_stored(sys: &System) -> (Vec<u8>, usize) {
    let (word, values, opts) = lychnis_word(sys);
    let g = driver::interpret(sys, &word, &values, &opts, false).expect("draws");
    let png = driver::render_bytes(sys, &g, driver::Format::Png, RenderOptions::default());
    (png.expect("png"), g.polygons.len())
}

fn bench_lit(c: &mut Criterion) {
    let sys = lychnis();
    let t = Instant::now();
    let ((stored_png, polygons), stored_peak) = peak_during(|| lit_stored(&sys));
    let stored_time = t.elapsed();
    let t = Instant::now();
    let (streamed_png, streamed_peak) = peak_during(|| lit_streamed(&sys));
    let streamed_time = t.elapsed();
    assert!(
        streamed_png == stored_png,
        "the two ways draw the same picture"
    );
    println!(
        "peak memory: lychnis n={LYCHNIS_STEPS} 1024x1024 PNG, {polygons} polygons: \
         {} in {:.2} s (from the turtle) vs {} in {:.2} s (baseline: stored)",
        mib(streamed_peak),
        streamed_time.as_secs_f64(),
        mib(stored_peak),
        stored_time.as_secs_f64(),
    );
    let mut group = c.benchmark_group("lit");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(polygons as u64));
    group.bench_function("lychnis/600", |b| b.iter(|| lit_streamed(black_box(&sys))));
    group.finish();
}

fn bench_derive_pipe(c: &mut Criterion) {
    let sys = load("hogeweg-hesper-a");
    let file = driver::load("std:hogeweg-hesper-a").expect("stdlib entry");
    let compiled = driver::compile(file);
    let write = || {
        let mut out = std::io::sink();
        driver::write_derived(compiled.front, &sys, &run_options(), &mut out, |_, _| {})
            .expect("derives");
    };
    let ((), peak) = peak_during(write);
    let symbols = driver::derive_symbols(&sys, &run_options(), |_, _| {})
        .expect("derives")
        .len();
    println!(
        "peak memory: derive hogeweg-hesper-a n={STEPS} to a pipe: {}, {symbols} symbols, \
         {:.2} bytes per symbol",
        mib(peak),
        peak as f64 / symbols as f64
    );
    let mut group = c.benchmark_group("derive-pipe");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(symbols as u64));
    group.bench_function("hogeweg-hesper-a/60", |b| b.iter(write));
    group.finish();
}

criterion_group! {
    name = benches;
    config = config::seconds_long();
    targets = bench_raster, bench_lit, bench_derive_pipe
}
criterion_main!(benches);
