//! Smith's "35-45 generations typically suffice": the WITH.WITHOUT system
//! (`std:smith/with-without`, 0.1[1].1.1.0.11.1.0) derived to generation
//! 45 (target under 0.1 s) and drawn: turtle, layout and PNG at 1024x1024
//! (target under 1 s).
//!
//! Throughput is in symbols (derive) and segments (draw) per second. The
//! baseline, timed in the same run, is Smith's rule applied to a plain byte
//! string of 0 1 [ ] (neighbours found by scanning, invisible 1's at the
//! ends), checked to give graftal's word before timing. Peak memory (the
//! counting allocator of benches/common/alloc.rs) is printed for one run of
//! each, e.g. `peak memory: derive n=45: 9.1 MiB (graftal) vs 0.4 MiB
//! (baseline)`.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use graftal::driver::{self, RunOptions};
use graftal::render::{self, RenderOptions};
use std::hint::black_box;
use std::time::Duration;

#[path = "common/alloc.rs"]
mod alloc;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

/// The symbol left of `i` as Smith defines it: back over `[` into the
/// parent, over whole earlier branches; an invisible 1 at the start.
fn left(w: &[u8], i: usize) -> u8 {
    let mut depth = 0usize;
    for &c in w[..i].iter().rev() {
        match c {
            b']' => depth += 1,
            b'[' => depth = depth.saturating_sub(1),
            c if depth == 0 => return c,
            _ => {}
        }
    }
    b'1'
}

/// The next symbol at the same level, over whole branches; an invisible 1
/// at a `]` or the end.
fn right(w: &[u8], i: usize) -> u8 {
    let mut depth = 0usize;
    for &c in &w[i + 1..] {
        match c {
            b'[' => depth += 1,
            b']' if depth == 0 => return b'1',
            b']' => depth -= 1,
            c if depth == 0 => return c,
            _ => {}
        }
    }
    b'1'
}

/// Generation `n` of the rule string `images` (the eight images of 000 …
/// 111) from `axiom`, by plain string rewriting.
fn baseline(images: &[&[u8]; 8], axiom: &[u8], n: u64) -> Vec<u8> {
    let mut cur = axiom.to_vec();
    let mut next = Vec::new();
    for _ in 0..n {
        next.clear();
        for (i, &c) in cur.iter().enumerate() {
            match c {
                b'0' | b'1' => {
                    let bit = |b: u8| usize::from(b == b'1');
                    let triple = 4 * bit(left(&cur, i)) + 2 * bit(c) + bit(right(&cur, i));
                    next.extend_from_slice(images[triple]);
                }
                _ => next.push(c),
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    cur
}

const IMAGES: [&[u8]; 8] = [b"0", b"1[1]", b"1", b"1", b"0", b"11", b"1", b"0"];

fn smith(c: &mut Criterion) {
    let entry = graftal::stdlib::get("smith/with-without").expect("the stdlib entry");
    let sys = graftal::front::smith::read_ok(entry.text);
    assert!(entry.text.contains("rules: 0.1[1].1.1.0.11.1.0"));
    let opts = RunOptions {
        steps: Some(45),
        ..RunOptions::default()
    };
    let (word, graftal_peak) = peak_during(|| driver::derive(&sys, &opts).expect("derives"));
    let (plain, baseline_peak) = peak_during(|| baseline(&IMAGES, b"1", 45));
    let text = graftal::front::smith::smith_text(&sys, word.symbols());
    assert_eq!(
        text.as_bytes(),
        plain.as_slice(),
        "baseline and graftal differ"
    );
    let ropts = RenderOptions {
        width: 1024,
        height: 1024,
        ..Default::default()
    };
    let draw = || {
        let (_, g) = driver::geometry(&sys, &opts).expect("draws");
        let png = render::png::encode(&render::layout(&g, &ropts)).map(|p| p.len());
        (g.segments.len(), g.discs.len(), png)
    };
    let ((segments, discs, _), draw_peak) = peak_during(draw);
    println!(
        "smith with-without n=45: {} modules ({} in Smith's word), {segments} segments, {discs} discs",
        word.len(),
        plain.len()
    );
    println!(
        "peak memory: derive n=45: {} (graftal) vs {} (baseline); draw: {}",
        mib(graftal_peak),
        mib(baseline_peak),
        mib(draw_peak)
    );
    drop((word, plain, text));
    let mut group = c.benchmark_group("smith-with-without-45");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    let symbols = baseline(&IMAGES, b"1", 45).len() as u64;
    group.throughput(Throughput::Elements(symbols));
    group.bench_function("derive", |b| {
        b.iter(|| driver::derive(black_box(&sys), &opts).map(|w| w.len()).ok())
    });
    group.bench_function("derive-baseline", |b| {
        b.iter(|| baseline(&IMAGES, black_box(b"1"), 45).len())
    });
    group.throughput(Throughput::Elements(segments as u64));
    group.bench_function("draw-png", |b| b.iter(draw));
    group.finish();
}

criterion_group!(benches, smith);
criterion_main!(benches);
