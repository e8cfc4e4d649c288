//! Every core (issue 38): the same work on 1, 2, 4, … threads, up to the
//! machine's cores, one thread the baseline measured in the same run.
//!
//! * `threads/png/hogeweg-hesper-a/60`: Fig. 3.11a (context-sensitive) at
//!   60 steps to a 1024x1024 PNG, derivation included: the word rewritten
//!   in chunks, interpreted in pieces, drawn in stripes of the picture.
//! * `threads/png/lychnis/600`: the cpfg Lychnis at 600 steps, 3.05 M
//!   polygons lit and z-buffered, derivation included: each thread draws a
//!   run of the word's pieces into a band of its own.
//! * `threads/derive/hogeweg-hesper-a/60` and `threads/derive/koch-island/8`:
//!   the derived word written out as `graftal derive … | …` writes it (into
//!   a sink here).
//!
//! Each group also times `copies-of-1/N`: N one-thread copies of the work
//! at once, one a core (N the most threads timed). One copy's time over
//! it, times N, is what the machine allows N threads at most on this work
//! (memory, caches and cores shared as the threads share them), the
//! ceiling the N-thread speedup is read against.
//!
//! Each picture and word is checked to be the same bytes on every thread
//! count before it is timed. Peak memory (a counting allocator) is printed
//! as `peak memory: …` lines, for one thread and for the most.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use graftal::driver::picture::{self, Format, Quiet, Request, Target};
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use std::hint::black_box;

#[path = "common/alloc.rs"]
mod alloc;
#[path = "common/config.rs"]
mod config;
use alloc::{mib, peak_during, start_counting, stop_counting};

// Counting only while a peak is measured: counters shared by every thread
// would slow the timings of many threads (a plant allocates per polygon).
#[global_allocator]
static ALLOC: alloc::CountingWhenStarted = alloc::CountingWhenStarted;

/// 1, 2, 4, … threads, up to the machine's cores (and 16).
fn counts() -> Vec<usize> {
    let cores = graftal::parallel::threads(0);
    let mut counts: Vec<usize> = [1, 2, 4, 8, 16]
        .into_iter()
        .filter(|&n| n <= cores)
        .collect();
    if !counts.contains(&cores) && cores < 16 {
        counts.push(cores);
    }
    counts
}

fn compile(spec: &str) -> (System, &'static dyn graftal::front::Front) {
    let file = driver::load(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
    let compiled = driver::compile(file);
    let front = compiled.front;
    (compiled.system.expect("compiles"), front)
}

fn lychnis() -> (System, &'static dyn graftal::front::Front) {
    compile(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/cpfg/10-GettingStarted-01-Lychnis/plant.l"
    ))
}

fn run(steps: u64, threads: usize) -> RunOptions {
    RunOptions {
        steps: Some(steps),
        threads,
        max_symbols: usize::MAX / 8,
        ..RunOptions::default()
    }
}

/// The PNG of `sys` at `steps` on `threads` threads.
fn png(sys: &System, steps: u64, threads: usize) -> Vec<u8> {
    let mut req = Request {
        run: run(steps, threads),
        ..Request::new(Target::Still(Format::Png))
    };
    req.tracing.threads = threads;
    picture::draw_system(sys, &req, &mut Quiet)
        .expect("draws")
        .bytes
}

/// The derived word of `sys` at `steps` on `threads` threads, as `graftal
/// derive` writes it.
fn derived(sys: &System, front: &dyn graftal::front::Front, steps: u64, threads: usize) -> Vec<u8> {
    let mut out = Vec::new();
    driver::write_derived(front, sys, &run(steps, threads), &mut out, |_, _| {}).expect("derives");
    out
}

/// Times `work` on each thread count, after checking that every count
/// gives what one thread gives and printing the peak memory of one thread
/// and of the most.
fn bench_counts(c: &mut Criterion, name: &str, work: impl Fn(usize) -> Vec<u8> + Sync) {
    let counts = counts();
    start_counting();
    let (one, one_peak) = peak_during(|| work(1));
    let most = *counts.last().expect("one thread at least");
    let (_, most_peak) = peak_during(|| work(most));
    stop_counting();
    for &n in &counts {
        assert!(work(n) == one, "{name}: {n} threads give other bytes");
    }
    println!(
        "peak memory: {name}: {} on 1 thread, {} on {most}",
        mib(one_peak),
        mib(most_peak)
    );
    let mut group = c.benchmark_group(format!("threads/{name}"));
    group.sampling_mode(SamplingMode::Flat);
    for n in counts {
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| black_box(work(n)))
        });
    }
    if most > 1 {
        let copies = BenchmarkId::new("copies-of-1", most);
        group.bench_with_input(copies, &most, |b, &most| {
            b.iter(|| {
                std::thread::scope(|s| {
                    let others: Vec<_> = (1..most).map(|_| s.spawn(|| work(1))).collect();
                    black_box(work(1));
                    for t in others {
                        black_box(t.join().expect("a copy panicked"));
                    }
                })
            })
        });
    }
    group.finish();
}

fn bench_pictures(c: &mut Criterion) {
    let (fig, _) = compile("std:hogeweg-hesper-a");
    bench_counts(c, "png/hogeweg-hesper-a/60", |n| png(&fig, 60, n));
    let (lychnis, _) = lychnis();
    bench_counts(c, "png/lychnis/600", |n| png(&lychnis, 600, n));
}

fn bench_derive(c: &mut Criterion) {
    let (fig, front) = compile("std:hogeweg-hesper-a");
    bench_counts(c, "derive/hogeweg-hesper-a/60", |n| {
        derived(&fig, front, 60, n)
    });
    let (koch, front) = compile("std:koch-island");
    bench_counts(c, "derive/koch-island/8", |n| derived(&koch, front, 8, n));
}

criterion_group! {
    name = benches;
    config = config::seconds_long();
    targets = bench_pictures, bench_derive
}
criterion_main!(benches);
