//! cpfg's random numbers (issue 34, item 8): a cpfg file draws from cpfg's
//! generators, seeded as cpfg seeds them. The expectations are computed
//! here from the published definition of `drand48` (POSIX: X ← (a·X + c)
//! mod 2^48, a = 0x5DEECE66D, c = 0xB, a draw X/2^48) and from cpfg's
//! rules as its source states them (`generate.c`'s `SelectProd`,
//! `control.c`'s `seed48`, `utility.c`'s `nran`), not from graftal's code.

use graftal::driver::{self, RunOptions};
use graftal::front::Front;
use graftal::source::SourceFile;

/// `drand48`, stepped from a state.
struct Drand48(u64);

impl Drand48 {
    fn next(&mut self) -> f64 {
        self.0 = (0x5DEECE66Du64.wrapping_mul(self.0).wrapping_add(0xB)) & ((1 << 48) - 1);
        self.0 as f64 / (1u64 << 48) as f64
    }
}

fn derive(src: &str, steps: u64) -> String {
    let c = driver::compile(SourceFile::new("test.l", src));
    let sys = c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let opts = RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    };
    let word = driver::derive(&sys, &opts).unwrap();
    graftal::front::cpfg::Cpfg.word_text(&sys, &word)
}

/// 11-CPFG-RandomMoss (`seed: 2454`, three productions of `F` at 33 each)
/// grows, step by step, the word cpfg's choice gives: cpfg seeds `drand48`
/// with `seed48({2454, 0, 155})`, draws one number for every module of the
/// word (brackets included, whether a production applies or not), and
/// takes, in single precision, the first production whose probability
/// brings `r = total · u` to 0 or below.
#[test]
fn a_seeded_cpfg_model_grows_the_plant_cpfg_grows() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/cpfg/11-CPFG-RandomMoss/plant.l"
    ))
    .unwrap();
    let successors = ["F[!,+F]F[!,-F]F", "F[!,+F]F", "F[!,-F]F"];
    let mut rng = Drand48(155 << 32 | 2454);
    let mut word = String::from("F");
    let mut chosen = [0; 3];
    for steps in 1..=4 {
        let mut next = String::new();
        for c in word.chars() {
            let u = rng.next();
            if c != 'F' {
                next.push(c);
                continue;
            }
            let total = 33f32 + 33f32 + 33f32;
            let mut r = (f64::from(total) * u) as f32;
            let pick = (0..3).find(|_| {
                r -= 33f32;
                r <= 0.0
            });
            let k = pick.expect("a production");
            chosen[k] += 1;
            next.push_str(successors[k]);
        }
        word = next;
        let ours: String = derive(&src, steps).split_whitespace().collect();
        assert_eq!(ours, word, "step {steps}");
    }
    assert!(
        chosen.iter().all(|&n| n > 3),
        "every production chosen: {chosen:?}"
    );
}

/// With `seed: 0` cpfg leaves libc's generator as it starts (0 in glibc):
/// its draws grow from 4e-14 to 0.36 over the first five modules, so the
/// fourth and fifth `A` choose `Y` where a seeded stream would differ.
#[test]
fn seed_zero_starts_from_libc_s_state() {
    let src = "Lsystem: 1\nseed: 0\nderivation length: 1\nAxiom: A A A A A A\n\
               A --> X : 0.1\nA --> Y : 0.9\nendlsystem\n";
    let mut rng = Drand48(0);
    let expected: String = (0..6)
        .map(|_| {
            let u = rng.next();
            if (f64::from(1f32) * u) as f32 - 0.1f32 <= 0.0 {
                'X'
            } else {
                'Y'
            }
        })
        .collect();
    assert_eq!(expected, "XXXYYX", "the draws of glibc's first state");
    let ours: String = derive(src, 1).split_whitespace().collect();
    assert_eq!(ours, expected);
}

/// `ran`, `nran` and `biran` draw from cpfg's second stream, the one
/// `srand(s)` restarts as `srand48(s)` does; before any `srand` it is
/// `srand48(0)`'s, and cpfg's first `nran` then returns its mean without
/// drawing. `nran` is Marsaglia's polar method, keeping the second deviate.
#[test]
fn ran_nran_and_biran_follow_cpfg_s_stream() {
    let src = "Lsystem: 1\nderivation length: 0\n\
               Start: {a = nran(5, 2); b = ran(10); srand(7); c = nran(1, 3); d = nran(1, 3); e = biran(20, 0.5);}\n\
               Axiom: A(a, b, c, d, e)\nendlsystem\n";
    let word = derive(src, 0);
    let numbers: Vec<f64> = word
        .trim()
        .trim_start_matches("A(")
        .trim_end_matches(')')
        .split(',')
        .map(|s| s.trim().parse().unwrap())
        .collect();
    let mut rng = Drand48(0x330E);
    let a = 5.0; // the first nran: the mean, nothing drawn
    let b = 10.0 * rng.next();
    let mut rng = Drand48(7 << 16 | 0x330E);
    let (first, second) = loop {
        let v1 = 2.0 * rng.next() - 1.0;
        let v2 = 2.0 * rng.next() - 1.0;
        let rsq: f64 = v1 * v1 + v2 * v2;
        if rsq < 1.0 && rsq != 0.0 {
            let fac = (-2.0 * rsq.ln() / rsq).sqrt();
            break (v2 * fac, v1 * fac);
        }
    };
    let (c, d) = (1.0 + 3.0 * first, 1.0 + 3.0 * second);
    let e = (0..20).filter(|_| rng.next() <= 0.5).count() as f64;
    let expected = [a, b, c, d, e];
    assert_eq!(numbers.len(), 5, "{word}");
    for (n, (ours, theirs)) in numbers.iter().zip(expected).enumerate() {
        // The word prints parameters to 6 significant digits.
        assert!(
            (ours - theirs).abs() <= 1e-5 * theirs.abs().max(1.0),
            "parameter {n}: {ours} against {theirs} ({word})"
        );
    }
}
