//! `graftal translate FILE --to gft` is exact (issue 19, item 2): for every
//! stdlib entry, every Fractint entry and every cpfg object of the corpus
//! that compiles, random pfg and LinF systems, and LinF files with
//! intervals and guards, the `.gft` text read back by the `.gft` front end
//! (a) is the same system (`ir::System::same_as`), (b) derives the same
//! word at the file's steps, and (c) draws the same segments (every
//! coordinate within 1e-9 of the picture's size) with the same seed.
//!
//! Everything must read back: there is no list of exceptions.

use graftal::driver::{self, Compiled, RunOptions};
use graftal::ir::{System, Word};
use graftal::source::SourceFile;
use graftal::stdlib::ENTRIES;
use std::path::{Path, PathBuf};

use crate::common;
use common::random::{random_linf, random_pfg, Gen};
use common::{cpfg_object_dirs, fractint_corpus_entries, main_l};

const MAX_SYMBOLS: usize = 200_000;

fn options(seed: u64) -> RunOptions {
    RunOptions {
        seed,
        max_symbols: MAX_SYMBOLS,
        ..RunOptions::default()
    }
}

/// A derived word as names and bit-exact parameters (ids may differ).
fn named(sys: &System, w: &Word) -> Vec<(String, Vec<u64>)> {
    (0..w.len())
        .map(|i| {
            let id = w.0[i];
            let name = match sys.symbols.silent_key(id) {
                Some(k) => format!("`{k}`"),
                None => sys.symbols.name(id).to_string(),
            };
            (name, w.args(i).iter().map(|v| v.to_bits()).collect())
        })
        .collect()
}

/// The same segments within 1e-9 of the picture's size; `Err` says where
/// they first differ.
fn same_segments(a: &System, b: &System, seed: u64) -> Result<(), String> {
    let (ga, gb) = match (
        driver::geometry(a, &options(seed)),
        driver::geometry(b, &options(seed)),
    ) {
        (Ok((_, ga)), Ok((_, gb))) => (ga, gb),
        (Err(x), Err(y)) if x.code == y.code => return Ok(()),
        (x, y) => return Err(format!("evaluation: {:?} vs {:?}", x.err(), y.err())),
    };
    if ga.segments.len() != gb.segments.len() {
        let (x, y) = (ga.segments.len(), gb.segments.len());
        return Err(format!("{x} segments vs {y}"));
    }
    let size = ga.bbox().map_or(1.0, |bx| {
        (0..3).map(|i| bx[i + 3] - bx[i]).fold(1e-12f64, f64::max)
    });
    let tol = 1e-9 * size;
    for (k, (s, t)) in ga.segments.iter().zip(&gb.segments).enumerate() {
        let far = (0..3).any(|i| (s.a[i] - t.a[i]).abs() > tol || (s.b[i] - t.b[i]).abs() > tol);
        if far {
            return Err(format!("segment {k}: {s:?} vs {t:?}"));
        }
    }
    Ok(())
}

/// How the round trips of one collection went.
#[derive(Default, Debug)]
struct Tally {
    exact: usize,
}

/// Writes `c`'s system as `.gft`, reads it back and checks (a), (b), (c);
/// `Err` describes the first failure with the text.
fn round_trip(what: &str, sys: &System, seed: u64, tally: &mut Tally) -> Result<(), String> {
    let text = graftal::back::gft::write(sys, None);
    // Read as a `.gft` beside the source (the images its textures and
    // environment name are the folder's).
    let name = std::path::Path::new(what).with_extension("gft");
    let file = SourceFile::new(name.display().to_string(), text.as_str());
    let read = driver::compile_as(file, None, graftal::front::by_name("gft"));
    let fail = |e: String| Err(format!("{what}: {e}\n--- gft ---\n{text}"));
    let Some(back) = read.system else {
        let list: Vec<String> = read.diagnostics.iter().map(|d| format!("{d:?}")).collect();
        return fail(format!("read back with errors: {}", list.join("\n")));
    };
    if let Err(e) = sys.same_as(&back) {
        return fail(format!("not the same system: {e}"));
    }
    let wa = driver::derive(sys, &options(seed)).map(|w| named(sys, &w));
    let wb = driver::derive(&back, &options(seed)).map(|w| named(&back, &w));
    match (&wa, &wb) {
        (Ok(x), Ok(y)) if x == y => {}
        (Err(x), Err(y)) if x.code == y.code => {}
        _ => return fail("another derived word".into()),
    }
    if wa.is_ok() {
        same_segments(sys, &back, seed).or_else(fail)?;
    }
    tally.exact += 1;
    Ok(())
}

/// Runs `round_trip` over `systems`, collecting every failure.
fn check_all(systems: impl IntoIterator<Item = (String, Compiled)>) -> Tally {
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    for (what, c) in systems {
        let Some(sys) = c.system.as_ref() else {
            continue;
        };
        if let Err(e) = round_trip(&what, sys, 7, &mut tally) {
            failures.push(e);
        }
    }
    let first: Vec<&String> = failures.iter().take(40).collect();
    assert!(
        failures.is_empty(),
        "{} failures ({tally:?}); the first:\n{}",
        failures.len(),
        first
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n\n")
    );
    tally
}

fn corpus(part: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(part)
}

#[test]
fn every_stdlib_entry_reads_back_exactly() {
    let t = check_all(ENTRIES.iter().map(|e| {
        let c = driver::compile(SourceFile::new(e.file, e.text));
        (e.name.to_string(), c)
    }));
    eprintln!("stdlib: {t:?}");
    assert_eq!(t.exact, ENTRIES.len(), "{t:?}");
}

#[test]
fn every_fractint_entry_reads_back_exactly() {
    let systems = fractint_corpus_entries();
    assert_eq!(systems.len(), 271);
    let t = check_all(systems);
    eprintln!("fractint: {t:?}");
    assert_eq!(t.exact, 271);
}

#[test]
fn every_cpfg_object_that_compiles_reads_back_exactly() {
    let dirs = cpfg_object_dirs();
    let systems = dirs.iter().filter_map(|dir| {
        let l = main_l(dir)?;
        let c = driver::compile(SourceFile::read(&l).unwrap());
        Some((l.display().to_string(), c))
    });
    let t = check_all(systems);
    eprintln!("cpfg: {t:?}");
    assert_eq!(t.exact, 94, "{t:?}");
}

/// LinF files with intervals, guards, named rotations and length factors.
#[test]
fn linf_intervals_and_guards_read_back_exactly() {
    let files = [
        "lines f\nangles (0, [0 pi/2]) t = ([pi/4 pi/2], 0)\naxiom f\nrules\n  f = f +t 0.5?f [ - f ] -t f\n#: steps 3\n",
        "lines f g\nblanks b\nangles (0, pi/3) w = (0, [0 pi])\naxiom f\nrules\n  f = 0.5@ g [ +w f ] 0.25?b -w f\n  g = g g\n#: steps 3\n",
    ];
    let t = check_all(files.iter().enumerate().map(|(i, text)| {
        (
            format!("linf{i}"),
            driver::compile(SourceFile::new(format!("f{i}.linf"), *text)),
        )
    }));
    assert_eq!(t.exact, files.len(), "{t:?}");
}

/// The emitter chooses the turtle set that needs the fewest lines: the
/// book's Koch island is pfg's set, the default, and fits in five lines;
/// a Fractint entry says `turtle fractint` and `colours fractint`.
#[test]
fn the_turtle_set_and_the_palette_keep_files_short() {
    let e = ENTRIES.iter().find(|e| e.name == "koch-island").unwrap();
    let c = driver::compile(SourceFile::new(e.file, e.text));
    let text = graftal::back::gft::write(c.system.as_ref().unwrap(), None);
    assert_eq!(text, "steps 3\naxiom F+F+F+F\nF -> F+F-F-FF+F+F-F\n");
    let source = SourceFile::read(&corpus("fractint/fractint.l")).unwrap();
    let c = driver::compile_entry(source, Some("Dragon"));
    let text = graftal::back::gft::write(c.system.as_ref().unwrap(), None);
    assert!(
        text.contains("\ncolours fractint\nturtle fractint\n"),
        "{text}"
    );
    // Fractint's set says what every command does: no override line.
    assert!(!text.contains(" = "), "{text}");
}

/// A cpfg production comes out with its author's parameter names
/// (`Formals::names`), and reads back the same.
#[test]
fn a_cpfg_production_keeps_its_parameter_names() {
    let text = "#define N 3\nLsystem: 1\nderivation length: N\naxiom: A(1,2)\nA(len, n) : n > 0 --> F(len) A(len*0.5, n-1)\nendlsystem\n";
    let c = driver::compile(SourceFile::new("names.l", text));
    let sys = c.system.as_ref().expect("compiles");
    let gft = graftal::back::gft::write(sys, None);
    let line = "A(len, n) : n > 0 -> F(len)A(len * 0.5, n - 1)";
    assert!(gft.contains(line), "{gft}");
    // The reader keeps them (the rest of this file waits for g19c).
    let back = graftal::front::gft::read_ok(&format!("turtle cpfg\naxiom A(1, 2)\n{line}\n"));
    assert_eq!(back.productions[0].formals.names, ["len", "n"]);
    assert_eq!(sys.productions[0].formals.names, ["len", "n"]);
}

mod random {
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

    /// Random pfg and LinF systems, built as tests/it/translate.rs builds
    /// them, from proptest's seeds.
    #[test]
    fn random_systems_read_back_exactly() {
        let config = Config {
            cases: 200,
            failure_persistence: None,
            ..Config::default()
        };
        let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[19; 32]);
        let mut runner = TestRunner::new_with_rng(config, rng);
        let result = runner.run(&(any::<u64>(), any::<bool>()), |(seed, linf)| {
            let mut g = Gen(seed);
            let (name, text) = if linf {
                ("random.linf", random_linf(&mut g))
            } else {
                ("random.l", random_pfg(&mut g))
            };
            let c = driver::compile(SourceFile::new(name, text.as_str()));
            let Some(sys) = c.system.as_ref() else {
                return Ok(());
            };
            let mut tally = Tally::default();
            round_trip(&text, sys, seed, &mut tally).map_err(TestCaseError::fail)?;
            prop_assert_eq!(tally.exact, 1);
            Ok(())
        });
        if let Err(e) = result {
            panic!("{e}");
        }
    }
}

/// A small cpfg text (`name.l`) compiles and reads back exactly.
fn cpfg_reads_back(name: &str, text: &str) {
    let c = driver::compile(SourceFile::new(format!("{name}.l"), text));
    assert!(!c.diagnostics.has_errors(), "{name}: {:#?}", c.diagnostics);
    let sys = c.system.as_ref().expect("compiles");
    let mut tally = Tally::default();
    round_trip(name, sys, 7, &mut tally).unwrap_or_else(|e| panic!("{e}"));
}

/// cpfg's `*` (no condition) before statements reads back.
#[test]
fn a_star_condition_with_statements_reads_back() {
    let text = "Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) : * { y = x + 1; } --> F(y) A(y)\nendlsystem\n";
    cpfg_reads_back("star", text);
}

/// `printf` takes any number of arguments.
#[test]
fn printf_with_any_number_of_arguments_reads_back() {
    let text = "Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) : 1 { printf(\"x\"); printf(\"%f %f\", x, x); } --> F A(x + 1)\nendlsystem\n";
    cpfg_reads_back("printf", text);
}

/// Several globals (`globals a, b`) are all declared when read back.
#[test]
fn several_globals_read_back() {
    let text = "Lsystem: 1\nStart: {total=0; count=0;}\nStartEach: {total=total+1;}\nderivation length: 2\naxiom: A(1)\nA(x) : count == 0 --> F(total) A(x)\nendlsystem\n";
    cpfg_reads_back("globals", text);
}

/// A production that opens a branch another closes reads back as written.
#[test]
fn unbalanced_brackets_read_back() {
    let text = "Lsystem: 1\nderivation length: 2\naxiom: A\nA --> F[+A\nB --> F]B\nendlsystem\n";
    cpfg_reads_back("brackets", text);
}

/// A view with a negative angle keeps its sign.
#[test]
fn a_negative_view_reads_back() {
    let back = graftal::front::gft::read_ok("view -0.25 -0.5 rad\naxiom F\n");
    assert_eq!(back.settings.view, Some((-0.25, -0.5)));
}

/// Materials whose last slots are empty read back with the same length.
#[test]
fn empty_last_material_slots_read_back() {
    let mut sys = graftal::front::gft::read_ok("material 1 ambient (0, 0, 0) diffuse (1, 0, 0) specular (0, 0, 0) emission (0, 0, 0) shininess 20 transparency 0\naxiom F\n");
    let l = sys.look.lighting.as_mut().expect("lighting");
    l.materials.resize(4, None);
    let text = graftal::back::gft::write(&sys, None);
    let back = graftal::front::gft::read_ok(&text);
    sys.same_as(&back).unwrap_or_else(|e| panic!("{e}\n{text}"));
}

/// A function without a name (a `.func` file's) and with negative samples
/// reads back.
#[test]
fn an_unnamed_function_reads_back() {
    let back = graftal::front::gft::read_ok("function  = -0.5 0 1\naxiom F\n");
    let f = &back.program.functions[0];
    assert_eq!(
        (f.name.as_str(), f.samples.clone()),
        ("", vec![-0.5, 0.0, 1.0])
    );
}

/// A name cpfg never assigns (worth 0) reads back as the same local.
#[test]
fn a_name_never_assigned_reads_back() {
    let text = "Lsystem: 1\nderivation length: 2\naxiom: A(1)\nA(x) --> F(x + undefined) A(x)\nendlsystem\n";
    let c = driver::compile(SourceFile::new("unassigned.l", text));
    let sys = c.system.as_ref().expect("compiles");
    let mut tally = Tally::default();
    round_trip("unassigned", sys, 7, &mut tally).unwrap_or_else(|e| panic!("{e}"));
}

/// A constant cpfg probability (`: P1` with `#define P1 33`) reads back.
#[test]
fn a_constant_probability_reads_back() {
    let text = "#define P1 33\nLsystem: 1\nseed: 2\nderivation length: 2\naxiom: F\nF --> F[+F]F : P1\nF --> F : 33\nendlsystem\n";
    cpfg_reads_back("weights", text);
}
