//! Times the derivation of a stdlib system: `cargo run --release --example
//! derive_timing -- std:hogeweg-hesper-a 40 200`.

use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("std:hogeweg-hesper-a", String::as_str);
    let steps: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(40);
    let reps: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(100);
    let c = graftal::driver::compile(graftal::driver::load(name).expect("loads"));
    let sys = c.system.expect("compiles");
    let opts = graftal::driver::RunOptions {
        steps: Some(steps),
        ..Default::default()
    };
    let t = Instant::now();
    let mut len = 0;
    for _ in 0..reps {
        len = graftal::driver::derive(&sys, &opts).expect("derives").len();
    }
    let secs = t.elapsed().as_secs_f64() / reps as f64;
    println!(
        "{name} n={steps}: {len} symbols in {:.3} ms ({:.1} M symbols/s)",
        secs * 1e3,
        len as f64 / secs / 1e6
    );
}
