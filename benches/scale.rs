//! Speed and scale (issue 7): graftal against plain string rewriting, on
//! growing inputs, with throughput (symbols or segments per second) and
//! peak memory (printed as `peak memory: …` before each group's timings).
//!
//! * `print/koch-island` (n = 5, 6, 7; 15.6 M symbols at 7): the word
//!   derived and written out, as `graftal derive` writes it to a pipe
//!   ([`driver::write_derived`], into a buffer here). Baseline: the pfg
//!   listing's way — each step rewrites the whole string into a second
//!   buffer through a 256-entry table of successors (no hashing, buffers
//!   reused), then the last string is written out.
//! * `derive/hogeweg-hesper-a` (Fig. 3.11a; n = 40, 50, 60; 9.24 M symbols
//!   at 60): context-sensitive derivation with the listing's bracket-aware
//!   contexts. Baseline: the same rewriting into a second buffer, finding
//!   each symbol's contexts by scanning the string as the listing's
//!   `lcondiff`/`rcondiff` do (n = 40, 50; it is quadratic in the branch
//!   lengths).
//! * `stats/koch-island` (n = 6, 7, 12): segment count and bounding box.
//!   Baseline (n = 6, 7): rewrite the string, then walk it with an integer
//!   turtle. At 12 steps (2.7 × 10¹¹ segments) only graftal's shared
//!   subtrees can answer.
//! * `render/koch-island` (n = 6, 7, 8): a 1024² PNG. Baseline (n = 6):
//!   derive the word, keep every segment, draw every segment.

#[path = "common/alloc.rs"]
mod alloc;
#[path = "common/hogeweg.rs"]
mod hogeweg;
use alloc::{mib, peak_during};
use hogeweg::plain_hogeweg;

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use graftal::driver::picture::{self, Method, Quiet, Request, Target};
use graftal::driver::{self, Format, RunOptions};
use graftal::ir::System;
use graftal::render::RenderOptions;
use std::hint::black_box;
use std::time::Duration;

fn load(name: &str) -> System {
    driver::compile(driver::load(&format!("std:{name}")).expect("stdlib entry"))
        .system
        .unwrap_or_else(|| panic!("std:{name} does not compile"))
}

fn steps(n: u64) -> RunOptions {
    RunOptions {
        steps: Some(n),
        max_symbols: usize::MAX / 8,
        ..RunOptions::default()
    }
}

// ---------------------------------------------------------------------------
// Baselines

/// Plain rewriting into a second buffer: `table[c]` is the successor of
/// byte `c`, or `None` to copy it.
fn plain_rewrite(axiom: &[u8], table: &[Option<&[u8]>; 256], n: u64) -> Vec<u8> {
    let mut cur = axiom.to_vec();
    let mut next = Vec::new();
    for _ in 0..n {
        next.clear();
        for &c in &cur {
            match table[c as usize] {
                Some(s) => next.extend_from_slice(s),
                None => next.push(c),
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    cur
}

const KOCH_AXIOM: &[u8] = b"F+F+F+F";
const KOCH_RULE: &[u8] = b"F+F-F-FF+F+F-F";

fn koch_table() -> [Option<&'static [u8]>; 256] {
    let mut t = [None; 256];
    t[b'F' as usize] = Some(KOCH_RULE);
    t
}

/// The Koch island's segment count and bounding box from its string, with
/// an integer turtle (heading up, `+` turns right).
fn plain_turtle(w: &[u8]) -> (u64, [i64; 4]) {
    let (mut x, mut y, mut h) = (0i64, 0i64, 0u8);
    let mut b = [0i64; 4];
    let mut segments = 0;
    for &c in w {
        match c {
            b'F' => {
                let (dx, dy) = [(0, 1), (1, 0), (0, -1), (-1, 0)][h as usize];
                x += dx;
                y += dy;
                segments += 1;
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
            b'+' => h = (h + 1) % 4,
            b'-' => h = (h + 3) % 4,
            _ => {}
        }
    }
    (segments, b)
}

// ---------------------------------------------------------------------------
// Benchmarks

fn bench_print(c: &mut Criterion) {
    let sys = load("koch-island");
    let table = koch_table();
    let mut group = c.benchmark_group("print/koch-island");
    group.sampling_mode(SamplingMode::Flat);
    for n in [5u64, 6, 7] {
        let print = |out: &mut Vec<u8>| {
            out.clear();
            driver::write_derived(&graftal::front::pfg::Pfg, &sys, &steps(n), out, |_, _| {})
                .unwrap();
        };
        let plain = |out: &mut Vec<u8>| {
            out.clear();
            out.extend_from_slice(&plain_rewrite(KOCH_AXIOM, &table, n));
            out.push(b'\n');
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let ((), pa) = peak_during(|| print(&mut a));
        let ((), pb) = peak_during(|| plain(&mut b));
        assert_eq!(a, b, "graftal and the baseline print different words");
        println!(
            "peak memory: print koch-island n={n}: {} (graftal) vs {} (baseline), output {} included",
            mib(pa),
            mib(pb),
            mib(a.len())
        );
        group.throughput(Throughput::Elements(a.len() as u64 - 1));
        group.bench_function(BenchmarkId::new("graftal", n), |bch| {
            bch.iter(|| print(black_box(&mut a)))
        });
        group.bench_function(BenchmarkId::new("baseline", n), |bch| {
            bch.iter(|| plain(black_box(&mut b)))
        });
    }
    group.finish();
}

fn bench_context(c: &mut Criterion) {
    let sys = load("hogeweg-hesper-a");
    let mut group = c.benchmark_group("derive/hogeweg-hesper-a");
    group.sampling_mode(SamplingMode::Flat);
    for n in [40u64, 50, 60] {
        let (w, pa) = peak_during(|| driver::derive(&sys, &steps(n)).unwrap());
        let text = w.display(&sys.symbols);
        let baseline = n <= 50;
        if baseline {
            let (plain, pb) = peak_during(|| plain_hogeweg(n));
            assert_eq!(text.as_bytes(), plain, "n={n}");
            println!(
                "peak memory: derive hogeweg-hesper-a n={n}: {} (graftal) vs {} (baseline), {} symbols",
                mib(pa),
                mib(pb),
                w.len()
            );
        } else {
            println!(
                "peak memory: derive hogeweg-hesper-a n={n}: {} (graftal), {} symbols",
                mib(pa),
                w.len()
            );
        }
        group.throughput(Throughput::Elements(w.len() as u64));
        group.bench_function(BenchmarkId::new("graftal", n), |b| {
            b.iter(|| driver::derive(black_box(&sys), &steps(n)).unwrap())
        });
        if baseline {
            group.bench_function(BenchmarkId::new("baseline", n), |b| {
                b.iter(|| plain_hogeweg(black_box(n)))
            });
        }
    }
    group.finish();
}

fn bench_stats(c: &mut Criterion) {
    let sys = load("koch-island");
    let table = koch_table();
    let mut group = c.benchmark_group("stats/koch-island");
    for n in [6u64, 7, 12] {
        let (s, pa) = peak_during(|| driver::stats(&sys, &steps(n)).unwrap());
        let baseline = n <= 7;
        if baseline {
            let ((segments, b), pb) =
                peak_during(|| plain_turtle(&plain_rewrite(KOCH_AXIOM, &table, n)));
            assert_eq!(s.segments, u128::from(segments));
            assert_eq!(
                s.bbox,
                Some([b[0] as f64, b[1] as f64, 0.0, b[2] as f64, b[3] as f64, 0.0])
            );
            println!(
                "peak memory: stats koch-island n={n}: {} (graftal) vs {} (baseline), {} segments",
                mib(pa),
                mib(pb),
                s.segments
            );
        } else {
            println!(
                "peak memory: stats koch-island n={n}: {} (graftal), {} segments",
                mib(pa),
                s.segments
            );
        }
        group.throughput(Throughput::Elements(
            u64::try_from(s.segments.to_u128().unwrap_or(u128::MAX)).unwrap_or(u64::MAX),
        ));
        group.bench_function(BenchmarkId::new("graftal", n), |b| {
            b.iter(|| driver::stats(black_box(&sys), &steps(n)).unwrap())
        });
        if baseline {
            group.bench_function(BenchmarkId::new("baseline", n), |b| {
                b.iter(|| plain_turtle(&plain_rewrite(KOCH_AXIOM, &table, black_box(n))))
            });
        }
    }
    group.finish();
}

fn bench_render(c: &mut Criterion) {
    let sys = load("koch-island");
    let ropts = RenderOptions {
        width: 1024,
        height: 1024,
        ..RenderOptions::default()
    };
    let mut group = c.benchmark_group("render/koch-island");
    group.sampling_mode(SamplingMode::Flat);
    for n in [6u64, 7, 8] {
        let shared = || {
            let req = Request {
                run: steps(n),
                ..Request::new(Target::Still(Format::Png))
            };
            let p = picture::draw_system(&sys, &req, &mut Quiet).unwrap();
            assert_eq!(p.method, Method::SharedSubtrees);
            p.bytes
        };
        let every = || {
            let (_, g) = driver::geometry(&sys, &steps(n)).unwrap();
            driver::render_bytes(&sys, &g, Format::Png, ropts).unwrap()
        };
        let (png, pa) = peak_during(shared);
        let baseline = n <= 6;
        let segments = 4 * 8u64.pow(n as u32);
        if baseline {
            let (_, pb) = peak_during(every);
            println!(
                "peak memory: render koch-island n={n} 1024x1024: {} (graftal) vs {} (every segment), {segments} segments, {} bytes of PNG",
                mib(pa),
                mib(pb),
                png.len()
            );
        } else {
            println!(
                "peak memory: render koch-island n={n} 1024x1024: {} (graftal), {segments} segments, {} bytes of PNG",
                mib(pa),
                png.len()
            );
        }
        group.throughput(Throughput::Elements(segments));
        group.bench_function(BenchmarkId::new("graftal", n), |b| b.iter(shared));
        if baseline {
            group.bench_function(BenchmarkId::new("every-segment", n), |b| b.iter(every));
        }
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = benches;
    config = config();
    targets = bench_print, bench_context, bench_stats, bench_render
}
criterion_main!(benches);
