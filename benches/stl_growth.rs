//! Outline growth throughput (the STL Graphics Developer), in stems/s.
//!
//! A large ellipse outline with `R1 = [-F][+F][F]`, grown under BFS and
//! DFS for more and more levels (the tree's reach grows with the levels, so
//! the stem count does too: about 9k, 71k and 250k stems under BFS). Each
//! input is compiled once outside the timing loop to count its stems, which
//! is the throughput criterion reports; the timed work is
//! `driver::compile` (parse, lower, grow, expand).

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use graftal::driver;
use graftal::source::SourceFile;
use std::time::Duration;

fn outline(levels: u32, growth: &str) -> String {
    format!(
        "ANGLE 25\nB = 1\nL = 10\nLEVELS {levels}\nGROWTH {growth}\nR1 = [-F][+F][F]\nSEED\nF R1\nENDSEED\nLAYOUT\n(clGreen) Ellipse (-1500, 0), 3000, 3000\nENDLAYOUT\n"
    )
}

fn stems(text: &str) -> usize {
    let c = driver::compile(SourceFile::new("bench.stl", text.to_string()));
    let sys = c.system.expect("the bench outline compiles");
    driver::geometry(&sys, &driver::RunOptions::default())
        .expect("draws")
        .1
        .segments
        .len()
}

fn growth(c: &mut Criterion) {
    let mut group = c.benchmark_group("stl-growth");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    for growth in ["BFS", "DFS"] {
        for levels in [40u32, 120, 256] {
            let text = outline(levels, growth);
            let n = stems(&text);
            eprintln!("stl-growth {growth} levels={levels}: {n} stems");
            group.throughput(Throughput::Elements(n as u64));
            group.bench_with_input(
                BenchmarkId::new(growth, format!("{levels}-levels-{n}-stems")),
                &text,
                |b, text| b.iter(|| driver::compile(SourceFile::new("bench.stl", text.clone()))),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, growth);
criterion_main!(benches);
