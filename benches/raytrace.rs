//! Ray tracing (issue 33): Bekaert & Willems' tracer of instancing graphs
//! and the flat hierarchy of a turtle's geometry, with throughput (rays a
//! second) and peak memory (printed as `peak memory: …` before each
//! group's timings), each against a baseline measured in the same run.
//!
//! * One-shot figures at the sizes (printed, not sampled: each
//!   takes seconds): `std:bekaert/tree` and `std:bekaert/fern` at 1024²
//!   with shadows and 4 samples a pixel, and a cpfg plant of about 10⁵
//!   cylinders (`PLANT`, a parametric ternary tree: flat hierarchy), each
//!   with 1 and 2 threads. Baseline: one thread. `GRAFTAL_BENCH_QUICK=1`
//!   leaves them out.
//! * `raytrace/tetrahedron` (sampled): Sierpinski's tetrahedron at 256²,
//!   one sample a pixel, traced from the graph, against a flat hierarchy
//!   over the graph expanded to the same pixel cut (262 144 boxes): rays a
//!   second of each, and the memory each holds.

#[path = "common/alloc.rs"]
mod alloc;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use graftal::driver::picture::{self, Format, Method, Quiet, Request, Target};
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::raytrace::{bvh::Bvh, graph::GraphScene, trace, Eye, Options, Scene};
use std::hint::black_box;
use std::time::Instant;

fn load(spec: &str) -> System {
    driver::compile(driver::load(spec).expect("loads"))
        .system
        .unwrap_or_else(|| panic!("{spec} does not compile"))
}

/// A cpfg plant of 1 + 3 + … + 3^10 = 88 573 internodes drawn as cylinders with
/// round joints (≈ 1.8 × 10⁵ primitives): parametric, so it is traced
/// through the flat hierarchy.
const PLANT: &str = "#define N 11
Lsystem: 1
derivation length: N
Axiom: A(N)
A(n) : n > 0 --> !(n*0.4) F(n*0.3) [ &(35) A(n-1) ] [ /(120) &(35) A(n-1) ] [ /(240) &(35) A(n-1) ]
endlsystem
";

/// A picture of `sys` at `size`² with `threads`, and how it was made.
fn render(sys: &System, size: u32, threads: usize) -> (Vec<u8>, Method) {
    let mut req = Request::new(Target::Still(Format::Png));
    (req.width, req.height) = (size, size);
    req.tracing.raytrace = Some(true);
    req.tracing.threads = threads;
    req.run = RunOptions::default();
    let p = picture::draw_system(sys, &req, &mut Quiet).expect("draws");
    (p.bytes, p.method)
}

fn one_shot(name: &str, sys: &System, size: u32) {
    let mut times = Vec::new();
    for threads in [1, 2] {
        let t = Instant::now();
        let ((_, method), peak) = peak_during(|| render(sys, size, threads));
        let secs = t.elapsed().as_secs_f64();
        assert_eq!(method, Method::RayTraced);
        times.push(secs);
        println!(
            "peak memory: {name} {size}x{size}, shadows, 4 samples, {threads} thread(s): {} in {secs:.2} s",
            mib(peak)
        );
    }
    println!("{name}: 2 threads {:.2}x one thread", times[0] / times[1]);
}

fn bench_one_shots(_: &mut Criterion) {
    // Minutes in all: `GRAFTAL_BENCH_QUICK=1` leaves them out.
    if std::env::var_os("GRAFTAL_BENCH_QUICK").is_some() {
        return;
    }
    one_shot("std:bekaert/fern", &load("std:bekaert/fern"), 1024);
    one_shot("std:bekaert/tree", &load("std:bekaert/tree"), 1024);
    let plant = driver::compile(graftal::source::SourceFile::new("plant.l", PLANT))
        .system
        .expect("the plant compiles");
    let run = RunOptions::default();
    let (_, g) = driver::geometry(&plant, &run).expect("derives");
    println!("the cpfg plant: {} segments", g.segments.len());
    one_shot("cpfg plant", &plant, 1024);
}

fn bench_tetrahedron(c: &mut Criterion) {
    const SIZE: u32 = 256;
    let sys = load("std:bekaert/tetrahedron");
    let graph = sys.graph.as_ref().expect("a graph");
    let scene = GraphScene::new(graph, [0.7, 0.5, 0.3]).expect("bounded");
    let mut opts = Options::new(
        SIZE,
        SIZE,
        Eye::View {
            azimuth: 0.4,
            elevation: 0.35,
        },
    );
    (opts.samples, opts.threads, opts.shadows) = (1, 1, false);
    let points = scene.fit_points();
    let pixel = graftal::raytrace::pixel_size(&points, &opts);
    let (flat, flat_peak) =
        peak_during(|| Bvh::new(scene.expand(pixel, 20_000_000).expect("fits")));
    let (_, graph_peak) = peak_during(|| trace(&scene, &opts));
    println!(
        "peak memory: tetrahedron {SIZE}x{SIZE}: the graph tracer {} (the graph and its tables, \
         per-ray lists) vs a flat hierarchy of {} boxes, {} to build ({} held)",
        mib(graph_peak),
        flat.len(),
        mib(flat_peak),
        mib(flat.memory()),
    );
    let mut group = c.benchmark_group("raytrace/tetrahedron");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.throughput(Throughput::Elements(u64::from(SIZE * SIZE)));
    group.bench_function("graph", |b| b.iter(|| trace(black_box(&scene), &opts)));
    group.bench_function("flat-bvh", |b| b.iter(|| trace(black_box(&flat), &opts)));
    group.finish();
}

criterion_group!(benches, bench_one_shots, bench_tetrahedron);
criterion_main!(benches);
