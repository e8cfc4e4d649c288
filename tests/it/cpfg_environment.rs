//! Open L-systems in the cpfg corpus (Měch & Prusinkiewicz 1996): every
//! object whose `.e` file names an environment program gets it built in,
//! and the answers are the programs' own.

use graftal::driver::{self, RunOptions};
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg")
}

/// The `.l` of an object folder: the one named like its `.e`, else the
/// folder's first.
fn l_file(dir: &Path) -> PathBuf {
    let mut ls: Vec<PathBuf> = (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "l"))
        .collect();
    ls.sort();
    let e_stem = (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "e"))
        .and_then(|p| p.file_stem().map(|s| s.to_owned()));
    let named = ls
        .iter()
        .find(|l| Some(l.file_stem().unwrap().to_owned()) == e_stem);
    named.cloned().unwrap_or_else(|| ls[0].clone())
}

/// The sixteen objects with an environment program: the 07-Open-*
/// objects but 07-Open-05, and the 20-EnviroPgms-* objects.
#[test]
fn every_open_l_system_of_the_corpus_runs_its_program_built_in() {
    let mut dirs: Vec<PathBuf> = (std::fs::read_dir(corpus()).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name.starts_with("07-Open-") && !name.starts_with("07-Open-05"))
                || name.starts_with("20-EnviroPgms-")
        })
        .collect();
    dirs.sort();
    assert_eq!(dirs.len(), 16, "{dirs:?}");
    for dir in &dirs {
        let c = driver::compile(SourceFile::read(&l_file(dir)).unwrap());
        let name = dir.file_name().unwrap().to_string_lossy();
        let w0821: Vec<_> = c
            .diagnostics
            .iter()
            .filter(|d| d.code.0 == "W0821")
            .collect();
        assert!(w0821.is_empty(), "{name}: {w0821:?}");
        let sys = c.system.unwrap_or_else(|| panic!("{name} compiles"));
        assert!(sys.environment.is_some(), "{name}: no environment");
        // It derives and draws at its own steps.
        driver::geometry(&sys, &RunOptions::default()).unwrap_or_else(|d| panic!("{name}: {d:?}"));
    }
}

/// 07-Open-10: three spheres of radius 0.9, one above the other, under
/// one source (50, 100, 0), opaque. chiba answers each the light that
/// reaches it past the discs of the spheres above, asked of the axiom at
/// the start of step 1; the production writes it into `S(r)`.
#[test]
fn three_spheres_get_the_light_that_passes_the_ones_above() {
    let dir = corpus().join("07-Open-10-light-three-spheres");
    let c = driver::compile(SourceFile::read(&dir.join("balls.l")).unwrap());
    let sys = c.system.unwrap();
    let word = driver::derive(&sys, &RunOptions::default()).unwrap();
    let s = sys.symbols.get("S").expect("S is a module");
    let light: Vec<f64> = (0..word.len())
        .filter(|&i| word.0[i] == s)
        .map(|i| word.args(i)[0])
        .collect();
    // Bottom to top: the light the lens-shaped overlaps with the discs
    // above leave (1 − A/πR² with t = 0), printed `%g` by the program.
    let want = [0.189579, 0.313054, 1.0];
    assert_eq!(light.len(), 3, "{light:?}");
    for (got, want) in light.iter().zip(want) {
        assert!((got - want).abs() < 1e-6, "{light:?}");
    }
}

/// 20-EnviroPgms-CPFG-Sierpinski: a tip that meets another at once stops
/// (`?E(0)` for good), the rest grow: honda81 decides the growth, so the
/// triangle grows to many segments, and far fewer than the same object
/// with every tip allowed.
#[test]
fn honda81_stops_the_tips_that_meet() {
    let dir = corpus().join("20-EnviroPgms-CPFG-Sierpinski");
    let c = driver::compile(SourceFile::read(&dir.join("fractal.l")).unwrap());
    let sys = c.system.unwrap();
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    assert!(g.segments.len() > 100, "{} segments", g.segments.len());
    let mut silent = sys.clone();
    silent.environment = None;
    let (_, none) = driver::geometry(&silent, &RunOptions::default()).unwrap();
    // Nothing answers: every `?E(0)` stays 0, and nothing grows.
    assert!(
        none.segments.len() < g.segments.len() / 10,
        "{}",
        none.segments.len()
    );
}

/// 07-Open-12: two trees compete for chiba's light. Each year ends with
/// `stop(1)`, which in cpfg's Run draws the frame and goes on (its manual:
/// "If n=1, and Run or Forever is selected from the menu, draw the
/// current string and continue"); the animation runs 183 frames. With
/// chiba answering, leaves in each other's shade make less product than
/// the same leaves unanswered (each `?E` keeping the value its module
/// carries, half its vigour, everywhere): the trees grow a quarter less.
#[test]
fn two_trees_grow_year_after_year_in_each_others_shade() {
    let dir = corpus().join("07-Open-12-two-trees");
    let c = driver::compile(SourceFile::read(&dir.join("tree.l")).unwrap());
    let sys = c.system.unwrap();
    let at = |sys: &graftal::ir::System, steps| {
        let opts = RunOptions {
            steps: Some(steps),
            ..RunOptions::default()
        };
        driver::derive(sys, &opts).unwrap().len()
    };
    let (year, later) = (at(&sys, 4), at(&sys, 120));
    let mut unshaded = sys.clone();
    unshaded.environment = None;
    let alone = at(&unshaded, 120);
    assert!(
        later > 5 * year,
        "{year} modules at 4 steps, {later} at 120"
    );
    assert!(
        4 * alone > 5 * later,
        "{alone} unanswered, {later} in the light"
    );
}

/// `stop()` or `stop(0)` ends the derivation after the step; `stop(1)`
/// marks a frame and the derivation goes on.
#[test]
fn stop_ends_the_derivation_and_stop_1_marks_a_frame() {
    let steps = |call: &str| {
        let text = format!(
            "Lsystem: 1\nStart: {{n=0;}}\nEndEach: {{n=n+1; if(n==2){{{call};}}}}\n\
             derivation length: 6\nAxiom: A\nA --> AB\nendlsystem\n"
        );
        let file = crate::common::object_file("stop-calls", "stop.l", &text);
        let c = driver::compile(SourceFile::read(&file).unwrap());
        let word = driver::derive(&c.system.unwrap(), &RunOptions::default()).unwrap();
        word.len() - 1
    };
    assert_eq!(steps("stop(1)"), 6);
    assert_eq!(steps("stop(0)"), 2);
    assert_eq!(steps("stop()"), 2);
}
