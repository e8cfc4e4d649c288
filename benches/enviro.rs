//! Open L-systems: the price of the environment. Each object is derived
//! with its environment answering every step, against a baseline timed in
//! the same run: the same derivation with no environment (its `?E`
//! modules keep their parameters). std:gft/light-competition (two trees
//! of chiba's light, 9 steps); 07-Open-12 (two trees competing for
//! light; vlab's `chiba`, nine sources, a 32³ grid) through the 183
//! frames its animation runs (its `derivation length: 0` draws the axiom;
//! each year's `stop(1)` draws a frame and goes on; the goal: under 2 s on
//! 2 cores); 20-EnviroPgms-CPFG-Sierpinski and
//! 07-Open-01 (honda81, collision by vigor) at their own steps and 16
//! frames. (Clover and Ecosystem are not here: without their environment
//! they grow without end, so there is no baseline to time them against.)
//!
//! Throughput is in modules of the final word per second; peak memory
//! (benches/common/alloc.rs) is printed for one run of each.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use graftal::driver::{self, RunOptions};
use graftal::source::SourceFile;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

#[path = "common/alloc.rs"]
mod alloc;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

/// The object's system, and the same without its environment.
fn object(dir: &str, file: &str) -> (graftal::ir::System, graftal::ir::System) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus/cpfg")
        .join(dir)
        .join(file);
    let c = driver::compile(SourceFile::read(&path).expect("the corpus object"));
    let sys = c.system.expect("it compiles");
    assert!(sys.environment.is_some(), "{dir} has its environment");
    let mut bare = sys.clone();
    bare.environment = None;
    (sys, bare)
}

fn bench_object(c: &mut Criterion, name: &str, dir: &str, file: &str, steps: Option<u64>) {
    let (sys, bare) = object(dir, file);
    let opts = RunOptions {
        steps,
        ..RunOptions::default()
    };
    let steps = steps.map_or("its own".to_string(), |n| n.to_string());
    let (word, with_peak) = peak_during(|| driver::derive(&sys, &opts).expect("derives"));
    let (bare_word, bare_peak) = peak_during(|| driver::derive(&bare, &opts).expect("derives"));
    println!(
        "peak memory: {name} n={steps}: {} (with the environment, {} modules) vs {} (without, {} modules)",
        mib(with_peak),
        word.len(),
        mib(bare_peak),
        bare_word.len()
    );
    let mut g = c.benchmark_group(name);
    g.sampling_mode(SamplingMode::Flat);
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(3));
    g.throughput(Throughput::Elements(word.len() as u64));
    g.bench_function("with the environment", |b| {
        b.iter(|| driver::derive(black_box(&sys), &opts).expect("derives"))
    });
    g.throughput(Throughput::Elements(bare_word.len() as u64));
    g.bench_function("baseline: without it", |b| {
        b.iter(|| driver::derive(black_box(&bare), &opts).expect("derives"))
    });
    g.finish();
}

fn enviro(c: &mut Criterion) {
    let lit = ("../../../stdlib/gft", "light-competition.gft");
    bench_object(c, "light-competition", lit.0, lit.1, None);
    let two_trees = ("07-Open-12-two-trees", "tree.l");
    bench_object(c, "two-trees-light", two_trees.0, two_trees.1, Some(183));
    let sierpinski = ("20-EnviroPgms-CPFG-Sierpinski", "fractal.l");
    bench_object(c, "sierpinski-collide", sierpinski.0, sierpinski.1, None);
    let ulam = ("07-Open-01-ulam-collide", "fractal.l");
    bench_object(c, "ulam-collide", ulam.0, ulam.1, Some(16));
}

criterion_group!(benches, enviro);
criterion_main!(benches);
