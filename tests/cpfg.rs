//! The cpfg dialect of `.l`: parametric derivation checked by hand, and the
//! 95 objects of `../shared/corpus/cpfg` read, derived and drawn.

use graftal::diagnostics::Diagnostic;
use graftal::driver::{self, Derived, RunOptions};
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

fn compile_text(src: &str) -> driver::Compiled {
    driver::compile(SourceFile::new("test.l", src))
}

fn derive_text(src: &str, steps: u64) -> String {
    let c = compile_text(src);
    let sys = c.system.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    let opts = RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    };
    driver::derive_any(&sys, &opts, |_, _| {})
        .unwrap()
        .text(&sys)
}

#[test]
fn parametric_productions_compute_parameters() {
    // The manual's compound leaf with parameters (01-Introduction-06).
    let src = "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> I(1)[+A][-A]I(1)A\nI(x) --> I(2*x)\nendlsystem\n";
    assert_eq!(
        derive_text(src, 2),
        "I(2)[+I(1)[+A][-A]I(1)A][-I(1)[+A][-A]I(1)A]I(2)I(1)[+A][-A]I(1)A"
    );
}

#[test]
fn conditions_statements_and_context() {
    let src = "lsystem: 1
derivation length: 3
axiom: B(0)A(1)
B(t) < A(x) : {y = x + t;} y < 3 {z = y * 10;} --> A(y)C(z)
A(x) --> D
B(t) --> B(t+1)
endlsystem
";
    // Step 1: A(1) has left context B(0): y = 1 < 3, A(1)C(10).
    assert_eq!(derive_text(src, 1), "B(1)A(1)C(10)");
    // Step 2: y = 1 + 1 = 2 < 3.
    assert_eq!(derive_text(src, 2), "B(2)A(2)C(20)C(10)");
    // Step 3: y = 2 + 2 = 4, the condition fails: the next production.
    assert_eq!(derive_text(src, 3), "B(3)DC(20)C(10)");
}

#[test]
fn cut_decomposition_homomorphism_and_blocks() {
    let src = "lsystem: 1
derivation length: 2
Start: {n = 5;}
EndEach: {n = n + 1;}
axiom: A(0)[X%Y]Z
A(k) --> A(k+n)
decomposition
maximum depth: 3
Z --> QZ
homomorphism
A(k) --> F(k)
endlsystem
";
    // `%` cuts the rest of its branch in every step; Z decomposes three
    // times per step; n is 5 in step 1 and 6 in step 2.
    assert_eq!(derive_text(src, 1), "A(5)[X]QQQZ");
    assert_eq!(derive_text(src, 2), "A(11)[X]QQQQQQZ");
    // The homomorphism draws A(k) as F(k): one segment of length 11.
    let c = compile_text(src);
    let sys = c.system.unwrap();
    let opts = RunOptions {
        steps: Some(2),
        ..RunOptions::default()
    };
    let w = driver::derive_any(&sys, &opts, |_, _| {}).unwrap();
    let g = driver::interpret_any(&sys, &w, &opts, false).unwrap();
    assert_eq!(g.segments.len(), 1);
    let s = &g.segments[0];
    let len = (0..3)
        .map(|k| (s.b[k] - s.a[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((len - 11.0).abs() < 1e-9, "{len}");
}

#[test]
fn stochastic_choice_follows_the_weights_and_the_seed() {
    let src = "lsystem: 1\nseed: 1\nderivation length: 1\naxiom: AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA\nA --> B : 1\nA --> C : 3\nendlsystem\n";
    let t = derive_text(src, 1);
    let (b, c) = (t.matches('B').count(), t.matches('C').count());
    assert_eq!(b + c, 120);
    assert!((15..=45).contains(&b), "B {b}, C {c}");
    assert_eq!(derive_text(src, 1), t, "same seed, same word");
}

#[test]
fn plus_turns_left_and_parameters_set_angles_and_lengths() {
    let src = "lsystem: 1\nderivation length: 0\naxiom: F(2)+(90)F(1)-F\nendlsystem\n";
    let c = compile_text(src);
    let sys = c.system.unwrap();
    let opts = RunOptions::default();
    let w = driver::derive_any(&sys, &opts, |_, _| {}).unwrap();
    let g = driver::interpret_any(&sys, &w, &opts, false).unwrap();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9);
    assert!(close(g.segments[0].b, [0.0, 2.0, 0.0]));
    // +(90) turns left: towards −x.
    assert!(
        close(g.segments[1].b, [-1.0, 2.0, 0.0]),
        "{:?}",
        g.segments[1]
    );
    // `-` without a parameter turns right by the default 45°.
    let d = 45f64.to_radians();
    assert!(close(g.segments[2].b, [-1.0 - d.cos(), 2.0 + d.sin(), 0.0]));
}

#[test]
fn errors_have_codes_and_spans_and_all_are_reported() {
    let src = "lsystem: 1\naxiom: A(1)\nA(x+1) --> B\nB --> C(foo(2))\nC -> D\nendlsystem\n";
    let c = compile_text(src);
    assert!(c.system.is_none());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert!(codes.contains(&"E0831"), "{codes:?}");
    assert!(codes.contains(&"E0832"), "{codes:?}");
    assert!(codes.contains(&"E0003"), "{codes:?}");
    let at =
        |code: &str| -> &Diagnostic { c.diagnostics.iter().find(|d| d.code.0 == code).unwrap() };
    let span = at("E0831").span.clone().unwrap();
    assert_eq!(&src[span], "x+1");
    let span = at("E0832").span.clone().unwrap();
    assert_eq!(&src[span], "foo");
}

/// The `.l` file of a corpus object: the one its `specifications` names
/// on the `cpfg` line, else the only one.
fn main_l(dir: &Path) -> Option<PathBuf> {
    let spec = std::fs::read_to_string(dir.join("specifications")).unwrap_or_default();
    for line in spec.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"cpfg") {
            if let Some(l) = words.iter().find(|w| w.ends_with(".l")) {
                return Some(dir.join(l));
            }
        }
    }
    let mut ls: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "l"))
        .collect();
    ls.sort();
    ls.into_iter().next()
}

fn corpus() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus/cpfg");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .expect("../shared/corpus/cpfg beside the repository")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs
}

/// What happened to one object.
enum Outcome {
    Drawn { modules: usize, segments: usize },
    Refused(Vec<String>),
}

fn run_object(dir: &Path) -> Outcome {
    let Some(l) = main_l(dir) else {
        return Outcome::Refused(vec!["no .l file".into()]);
    };
    let file = SourceFile::read(&l).unwrap();
    let c = driver::compile(file);
    let errors: Vec<String> = c
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{} {}", d.code, d.message))
        .collect();
    let Some(sys) = c.system else {
        // Every refusal names its construct at a span.
        assert!(
            c.diagnostics
                .iter()
                .filter(|d| d.is_error())
                // A problem in a file beside the `.l` names that file.
                .all(|d| d.span.is_some() || d.message.contains(", line ")),
            "{}: an error without a span: {errors:?}",
            dir.display()
        );
        return Outcome::Refused(errors);
    };
    let opts = RunOptions {
        max_symbols: 2_000_000,
        ..RunOptions::default()
    };
    let w = match driver::derive_any(&sys, &opts, |_, _| {}) {
        Ok(w) => w,
        Err(d) => return Outcome::Refused(vec![format!("{} {}", d.code, d.message)]),
    };
    let g = match driver::interpret_any(&sys, &w, &opts, false) {
        Ok(g) => g,
        Err(d) => return Outcome::Refused(vec![format!("{} {}", d.code, d.message)]),
    };
    let _: &Derived = &w;
    Outcome::Drawn {
        modules: w.len(),
        segments: g.segments.len() + g.polygons.len() + g.discs.len(),
    }
}

#[test]
fn at_least_ninety_percent_of_the_corpus_objects_render() {
    let dirs = corpus();
    assert_eq!(dirs.len(), 95);
    let mut drawn = 0;
    let mut refused = Vec::new();
    for d in &dirs {
        match run_object(d) {
            Outcome::Drawn {
                segments: 0,
                modules,
            } => refused.push(format!(
                "{}: {modules} modules and nothing drawn",
                d.file_name().unwrap().to_string_lossy()
            )),
            Outcome::Drawn { .. } => drawn += 1,
            Outcome::Refused(why) => refused.push(format!(
                "{}: {}",
                d.file_name().unwrap().to_string_lossy(),
                why.join("; ")
            )),
        }
    }
    eprintln!("{drawn}/95 drawn; refused:\n{}", refused.join("\n"));
    assert!(
        drawn * 10 >= 95 * 9,
        "{drawn}/95 drawn:\n{}",
        refused.join("\n")
    );
}

/// Damaged cpfg files (bytes cut, doubled or replaced at random, from
/// real corpus files) never make graftal panic or hang: each is compiled,
/// and what compiles is derived a few steps and drawn.
#[test]
fn damaged_files_never_panic() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let texts: Vec<String> = corpus()
        .iter()
        .filter_map(|d| main_l(d))
        .take(40)
        .map(|p| std::fs::read_to_string(p).unwrap_or_default())
        .collect();
    let mut runner = TestRunner::new(Config {
        cases: 300,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (
        0..texts.len(),
        proptest::collection::vec((any::<u16>(), 0u8..3, any::<u8>()), 1..6),
    );
    runner
        .run(&strategy, |(k, edits)| {
            let mut bytes = texts[k].clone().into_bytes();
            for (at, kind, b) in edits {
                if bytes.is_empty() {
                    break;
                }
                let i = at as usize % bytes.len();
                match kind {
                    0 => {
                        bytes.remove(i);
                    }
                    1 => bytes.insert(i, bytes[i]),
                    _ => {
                        let alphabet = b" ()[]{}:;,*<>-+=%?@~#!.0123456789Ax\n\t";
                        bytes[i] = alphabet[b as usize % alphabet.len()];
                    }
                }
            }
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let c = compile_text(&text);
            if let Some(sys) = c.system {
                let opts = RunOptions {
                    steps: Some(sys.settings.steps.unwrap_or(0).min(4)),
                    max_symbols: 200_000,
                    ..RunOptions::default()
                };
                if let Ok(w) = driver::derive_any(&sys, &opts, |_, _| {}) {
                    let _ = driver::interpret_any(&sys, &w, &opts, false);
                }
            }
            Ok(())
        })
        .unwrap();
}
