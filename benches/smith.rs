//! Smith's "35-45 generations typically suffice": the WITH.WITHOUT system
//! (`std:smith/with-without`, 0.1[1].1.1.0.11.1.0) derived to generation
//! 45 (target under 0.1 s) and drawn: turtle, layout and PNG at 1024x1024
//! (target under 1 s).

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use graftal::driver::{self, RunOptions};
use graftal::render::{self, RenderOptions};
use std::time::Duration;

fn smith(c: &mut Criterion) {
    let entry = graftal::stdlib::get("smith/with-without").expect("the stdlib entry");
    let sys = graftal::front::smith::read_ok(entry.text);
    let opts = RunOptions {
        steps: Some(45),
        ..RunOptions::default()
    };
    let word = driver::derive(&sys, &opts).expect("derives");
    let (_, g) = driver::geometry(&sys, &opts).expect("draws");
    eprintln!(
        "smith with-without n=45: {} modules, {} segments, {} discs",
        word.len(),
        g.segments.len(),
        g.discs.len()
    );
    let mut group = c.benchmark_group("smith-with-without-45");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    group.bench_function("derive", |b| {
        b.iter(|| driver::derive(&sys, &opts).map(|w| w.len()).ok())
    });
    let ropts = RenderOptions {
        width: 1024,
        height: 1024,
        ..Default::default()
    };
    group.bench_function("draw-png", |b| {
        b.iter(|| {
            let (_, g) = driver::geometry(&sys, &opts).expect("draws");
            render::png::encode(&render::layout(&g, &ropts)).map(|p| p.len())
        })
    });
    group.finish();
}

criterion_group!(benches, smith);
criterion_main!(benches);
