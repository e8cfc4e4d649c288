//! Meshes (issue 21, item 3): what `graftal render FILE -o OUT.glb|OUT.obj`
//! costs, with throughput in triangles per second and peak heap.
//!
//! * `glb/instanced`: a context-free tree (`std:plant-e` at 9 steps, 460 k
//!   triangles once placed) through [`picture::draw_system`]: one mesh per
//!   repeated subtree of the shared derivation tree, placed by glTF nodes.
//!   Baseline, measured once in the same run: the same glTF without
//!   instancing — derive the word, interpret it, one tube per segment
//!   ([`mesh::of_geometry`]), one flat mesh.
//! * `obj/lychnis`: a lit cpfg object (the cpfg Lychnis at the file's 300
//!   steps: tubes, polygons and surfaces, several materials) to OBJ and
//!   its material library, from the derived word (OBJ has no instancing).
//!   Baseline, measured once: deriving and interpreting alone
//!   ([`driver::geometry`]), the work every output of the model shares, so
//!   the difference is what meshing and writing the text cost.
//!
//! Peak memory is the peak of live heap bytes (a counting allocator, as in
//! `benches/raster.rs`), printed as `peak memory: …` lines.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use graftal::driver::picture::{self, Picture, Quiet, Request, Target};
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::mesh::{self, MeshFormat, Scene};
use std::hint::black_box;
use std::time::Instant;

#[path = "common/alloc.rs"]
mod alloc;
#[path = "common/config.rs"]
mod config;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

const TREE_STEPS: u64 = 9;
const LYCHNIS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/corpus/cpfg/10-GettingStarted-01-Lychnis/plant.l"
);

fn load(spec: &str) -> System {
    let file = driver::load(spec).expect("loads");
    driver::compile(file)
        .system
        .unwrap_or_else(|| panic!("{spec} does not compile"))
}

fn steps(n: Option<u64>) -> RunOptions {
    RunOptions {
        steps: n,
        ..RunOptions::default()
    }
}

/// graftal's own way to a mesh file, as the CLI writes it.
fn to_mesh(sys: &System, opts: &RunOptions, format: MeshFormat) -> Picture {
    let req = Request {
        run: opts.clone(),
        material_library: "plant.mtl".into(),
        ..Request::new(Target::Mesh(format))
    };
    picture::draw_system(sys, &req, &mut Quiet).expect("meshes")
}

/// The glTF without instancing: every segment's tube in one mesh.
fn flat_glb(sys: &System, opts: &RunOptions) -> Vec<u8> {
    let (_, g) = driver::geometry(sys, opts).expect("derives");
    let lighting = sys.look.lighting.as_ref();
    mesh::glb(&Scene::single(mesh::of_geometry(
        &g,
        lighting,
        &mut |_, _| {},
    )))
}

/// Runs `f` once, timed, with its peak heap.
fn once<T>(f: impl FnOnce() -> T) -> (T, usize, f64) {
    let t = Instant::now();
    let (out, peak) = peak_during(f);
    (out, peak, t.elapsed().as_secs_f64())
}

fn bench_glb(c: &mut Criterion) {
    let sys = load("std:plant-e");
    let opts = steps(Some(TREE_STEPS));
    let (flat, flat_peak, flat_time) = once(|| flat_glb(&sys, &opts));
    let (ours, peak, time) = once(|| to_mesh(&sys, &opts, MeshFormat::Glb));
    let s = ours.mesh.as_ref().expect("a mesh");
    assert!(s.nodes > 1, "plant-e is instanced");
    println!(
        "peak memory: plant-e n={TREE_STEPS} to glTF, {} triangles placed: {} in {time:.3} s, \
         {} bytes, {} meshes placed {} times (instanced) vs {} in {flat_time:.3} s, {} bytes \
         (baseline: one flat mesh)",
        s.triangles,
        mib(peak),
        ours.bytes.len(),
        s.meshes,
        s.nodes,
        mib(flat_peak),
        flat.len(),
    );
    let mut group = c.benchmark_group("mesh");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(s.triangles));
    group.bench_function("glb/instanced/plant-e/9", |b| {
        b.iter(|| to_mesh(black_box(&sys), &opts, MeshFormat::Glb))
    });
    group.finish();
}

fn bench_obj(c: &mut Criterion) {
    let sys = load(LYCHNIS);
    let opts = steps(None);
    let (_, geometry_peak, geometry_time) =
        once(|| driver::geometry(&sys, &opts).expect("derives"));
    let (ours, peak, time) = once(|| to_mesh(&sys, &opts, MeshFormat::Obj));
    let s = ours.mesh.as_ref().expect("a mesh");
    println!(
        "peak memory: cpfg Lychnis to OBJ, {} vertices, {} triangles, {} materials: {} in \
         {time:.3} s, {} bytes (OBJ) vs {} in {geometry_time:.3} s (baseline: derive and \
         interpret alone)",
        s.vertices,
        s.triangles,
        s.materials,
        mib(peak),
        ours.bytes.len(),
        mib(geometry_peak),
    );
    let mut group = c.benchmark_group("mesh");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(s.triangles));
    group.bench_function("obj/lychnis", |b| {
        b.iter(|| to_mesh(black_box(&sys), &opts, MeshFormat::Obj))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = config::seconds_long();
    targets = bench_glb, bench_obj
}
criterion_main!(benches);
