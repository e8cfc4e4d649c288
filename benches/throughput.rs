//! Throughput and peak-memory benchmarks (README, "Speed and scale").
//!
//! On growing inputs of three stdlib systems:
//!
//! * `derive/<system>`: derivation throughput in symbols/s (throughput is the
//!   length of the final word), graftal (`driver::derive`) against a simple
//!   string-rewriting baseline written here:
//!   - context-free `koch-island`: a `HashMap<char, String>` expansion on
//!     `String`s;
//!   - context-sensitive bracketed `hogeweg-hesper-a`: a naive scan of a
//!     `String` that looks for the left/right context by walking over the
//!     bytes (skipping ignored symbols and whole branches, entering parents),
//!     with the file's eight rules written out as a `match`;
//!   - stochastic `stochastic-bush`: a `HashMap<char, Vec<(weight, String)>>`
//!     expansion drawing from graftal's own `random::Rng` (the derivation stream), in word order, so it
//!     makes the very same word as graftal for the same seed.
//!
//!   Before timing, every baseline's word is checked to be identical to
//!   graftal's, so both sides do the same work.
//! * `interpret`: `turtle::Run::word(…).geometry()` on the derived words, in segments/s.
//! * `render-png` / `render-svg`: `render::layout` + `render::png::encode` /
//!   `render::svg::write` at 1024x1024, in segments/s.
//!
//! Peak memory: a counting global allocator wraps `std::alloc::System`;
//! outside criterion's timing loop each input is run once and the peak of
//! live heap bytes above what was live before is printed, e.g.
//! `peak memory: derive koch-island n=5: 2.1 MiB (graftal) vs 1.0 MiB (baseline)`.
//! The counter costs every allocation a few relaxed atomic operations, in
//! graftal and the baselines alike.

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use graftal::driver::{self, RunOptions};
use graftal::ir::{System, Word};
use graftal::random::{Rng, Stream};
use graftal::render::{self, RenderOptions};
use graftal::turtle::{self, Geometry};
use std::collections::HashMap;
use std::hint::black_box;
use std::sync::OnceLock;
use std::time::Duration;

#[path = "common/alloc.rs"]
mod alloc;
#[path = "common/hogeweg.rs"]
mod hogeweg;
use alloc::{mib, peak_during};

#[global_allocator]
static ALLOC: alloc::Counting = alloc::Counting;

// ---------------------------------------------------------------------------
// Baselines

/// Context-free: each step rebuilds the string, expanding through the map.
fn baseline_context_free(axiom: &str, rules: &HashMap<char, String>, steps: u64) -> String {
    let mut cur = axiom.to_string();
    for _ in 0..steps {
        let mut next = String::new();
        for c in cur.chars() {
            match rules.get(&c) {
                Some(s) => next.push_str(s),
                None => next.push(c),
            }
        }
        cur = next;
    }
    cur
}

/// Stochastic: one draw from graftal's generator per rewritten symbol with
/// several alternatives, in word order, alternatives chosen by cumulative
/// weight (the same scheme as graftal, so the same word for the same seed).
fn baseline_stochastic(
    axiom: &str,
    rules: &HashMap<char, Vec<(f64, String)>>,
    steps: u64,
    seed: u64,
) -> String {
    let mut rng = Rng::new(seed, Stream::Derivation);
    let mut cur = axiom.to_string();
    for _ in 0..steps {
        let mut next = String::new();
        for c in cur.chars() {
            match rules.get(&c) {
                Some(alts) if alts.len() == 1 => next.push_str(&alts[0].1),
                Some(alts) => {
                    let r = rng.next_f64();
                    let mut acc = 0.0;
                    let mut chosen = &alts[alts.len() - 1].1;
                    for (w, s) in alts {
                        acc += w;
                        if r < acc {
                            chosen = s;
                            break;
                        }
                    }
                    next.push_str(chosen);
                }
                None => next.push(c),
            }
        }
        cur = next;
    }
    cur
}

enum Baseline {
    ContextFree {
        axiom: &'static str,
        rules: HashMap<char, String>,
    },
    Stochastic {
        axiom: &'static str,
        rules: HashMap<char, Vec<(f64, String)>>,
    },
    /// `benches/common/hogeweg.rs`, from the axiom `F1F1F1`.
    Hogeweg,
}

impl Baseline {
    fn derive(&self, steps: u64) -> String {
        match self {
            Baseline::ContextFree { axiom, rules } => baseline_context_free(axiom, rules, steps),
            Baseline::Stochastic { axiom, rules } => baseline_stochastic(axiom, rules, steps, SEED),
            Baseline::Hogeweg => hogeweg::plain_hogeweg(steps)
                .into_iter()
                .map(char::from)
                .collect(),
        }
    }
}

// ---------------------------------------------------------------------------
// Inputs

const SEED: u64 = 0;

struct Family {
    name: &'static str,
    steps: &'static [u64],
    sys: System,
    baseline: Baseline,
}

fn load(name: &str) -> System {
    let file = driver::load(&format!("std:{name}")).expect("stdlib entry");
    driver::compile(file)
        .system
        .unwrap_or_else(|| panic!("std:{name} does not compile"))
}

fn families() -> &'static [Family] {
    static FAMILIES: OnceLock<Vec<Family>> = OnceLock::new();
    FAMILIES.get_or_init(|| {
        vec![
            Family {
                name: "koch-island",
                steps: &[3, 4, 5],
                sys: load("koch-island"),
                baseline: Baseline::ContextFree {
                    axiom: "F+F+F+F",
                    rules: HashMap::from([('F', "F+F-F-FF+F+F-F".to_string())]),
                },
            },
            Family {
                name: "hogeweg-hesper-a",
                steps: &[20, 30, 40],
                sys: load("hogeweg-hesper-a"),
                baseline: Baseline::Hogeweg,
            },
            Family {
                name: "stochastic-bush",
                steps: &[4, 5, 6],
                sys: load("stochastic-bush"),
                baseline: Baseline::Stochastic {
                    axiom: "F",
                    rules: HashMap::from([(
                        'F',
                        vec![
                            (0.33, "F[+F]F[-F]F".to_string()),
                            (0.33, "F[+F]F".to_string()),
                            (0.34, "F[-F]F".to_string()),
                        ],
                    )]),
                },
            },
        ]
    })
}

fn run_options(steps: u64) -> RunOptions {
    RunOptions {
        steps: Some(steps),
        seed: SEED,
        ..Default::default()
    }
}

fn graftal_derive(sys: &System, steps: u64) -> Word {
    driver::derive(sys, &run_options(steps)).expect("derivation succeeds")
}

/// One input: a family at `steps`, derived and interpreted.
struct Case {
    family: &'static Family,
    steps: u64,
    word: Word,
    geometry: Geometry,
}

impl Case {
    fn label(&self) -> String {
        format!("{} n={}", self.family.name, self.steps)
    }
}

fn cases() -> Vec<Case> {
    families()
        .iter()
        .flat_map(|family| {
            family.steps.iter().map(move |&steps| {
                let word = graftal_derive(&family.sys, steps);
                let geometry = turtle::Run::word(&family.sys, &word, SEED).geometry();
                Case {
                    family,
                    steps,
                    word,
                    geometry,
                }
            })
        })
        .collect()
}

fn render_options(sys: &System) -> RenderOptions {
    RenderOptions {
        width: 1024,
        height: 1024,
        scale: sys.settings.scale,
        ..Default::default()
    }
}

// ---------------------------------------------------------------------------
// Benchmarks

fn bench_derive(c: &mut Criterion) {
    for family in families() {
        let mut group = c.benchmark_group(format!("derive/{}", family.name));
        for &steps in family.steps {
            // Outside the timing loop: check the baseline against graftal and
            // measure peak memory of one run of each.
            let (word, graftal_peak) = peak_during(|| graftal_derive(&family.sys, steps));
            let (text, baseline_peak) = peak_during(|| family.baseline.derive(steps));
            assert_eq!(
                word.display(&family.sys.symbols),
                text,
                "baseline and graftal differ on {} n={steps}",
                family.name
            );
            println!(
                "peak memory: derive {} n={steps}: {} (graftal) vs {} (baseline), {} symbols",
                family.name,
                mib(graftal_peak),
                mib(baseline_peak),
                word.len()
            );
            drop((word, text));

            let symbols = graftal_derive(&family.sys, steps).len() as u64;
            group.throughput(Throughput::Elements(symbols));
            let opts = run_options(steps);
            group.bench_with_input(BenchmarkId::new("graftal", steps), &opts, |b, opts| {
                b.iter(|| driver::derive(black_box(&family.sys), black_box(opts)).unwrap())
            });
            group.bench_with_input(BenchmarkId::new("baseline", steps), &steps, |b, &steps| {
                b.iter(|| family.baseline.derive(black_box(steps)))
            });
        }
        group.finish();
    }
}

fn bench_interpret(c: &mut Criterion) {
    let cases = cases();
    let mut group = c.benchmark_group("interpret");
    for case in &cases {
        let sys = &case.family.sys;
        let (g, peak) = peak_during(|| turtle::Run::word(sys, &case.word, SEED).geometry());
        println!(
            "peak memory: interpret {}: {}, {} segments",
            case.label(),
            mib(peak),
            g.segments.len()
        );
        drop(g);
        group.throughput(Throughput::Elements(case.geometry.segments.len() as u64));
        group.bench_with_input(
            BenchmarkId::new(case.family.name, case.steps),
            &case.word,
            |b, word| b.iter(|| turtle::Run::word(sys, black_box(word), SEED).geometry()),
        );
    }
    group.finish();
}

fn bench_render(c: &mut Criterion) {
    let cases = cases();
    for format in ["png", "svg"] {
        let mut group = c.benchmark_group(format!("render-{format}"));
        // A PNG of a large input takes ~0.5 s: one iteration per sample.
        group.sampling_mode(SamplingMode::Flat);
        for case in &cases {
            let opts = render_options(&case.family.sys);
            let render = |g: &Geometry| -> usize {
                let pic = render::layout(g, &opts);
                match format {
                    "png" => render::png::encode(&pic).expect("png").len(),
                    _ => render::svg::write(&pic).len(),
                }
            };
            let (bytes, peak) = peak_during(|| render(&case.geometry));
            println!(
                "peak memory: render-{format} {} 1024x1024: {}, {} segments, {} bytes of output",
                case.label(),
                mib(peak),
                case.geometry.segments.len(),
                bytes
            );
            group.throughput(Throughput::Elements(case.geometry.segments.len() as u64));
            group.bench_with_input(
                BenchmarkId::new(case.family.name, case.steps),
                &case.geometry,
                |b, g| b.iter(|| render(black_box(g))),
            );
        }
        group.finish();
    }
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1000))
}

criterion_group! {
    name = benches;
    config = config();
    targets = bench_derive, bench_interpret, bench_render
}
criterion_main!(benches);
