//! Every core, the same output (issue 38): pictures drawn on 1, 2 and 3
//! threads are the same bytes over the standard library, the Fractint
//! corpus and the cpfg corpus, and so are words big enough to be drawn in
//! pieces; `graftal check` of many files says the same on any number of
//! threads.

use crate::common::{corpus, graftal, main_l};
use graftal::driver::picture::{self, Request, Source, Target, Tracing};
use graftal::driver::Format;

/// The PNG of `spec` on `threads` threads, at a size small enough to
/// sweep the corpora and large enough for every thread to draw stripes
/// (32 rows each); `None` when nothing is drawn.
fn png(spec: &str, threads: usize) -> Option<Vec<u8>> {
    png_at(spec, None, threads)
}

/// [`png`] after `steps` steps (`None`: the file's).
fn png_at(spec: &str, steps: Option<u64>, threads: usize) -> Option<Vec<u8>> {
    let mut req = Request {
        width: 96,
        height: 96,
        tracing: Tracing {
            threads,
            samples: 1,
            ..Tracing::default()
        },
        ..Request::new(Target::Still(Format::Png))
    };
    req.run.steps = steps;
    req.run.threads = threads;
    let made = picture::make(
        &Source::Spec(spec.to_string()),
        None,
        None,
        &req,
        &mut picture::Quiet,
    );
    made.picture.ok().map(|p| p.bytes)
}

/// Asserts that each of `specs` draws the same bytes on 1, 2 and 3
/// threads; how many drew.
fn same_on_every_count(specs: &[String]) -> usize {
    let mut drawn = 0;
    for spec in specs {
        let one = png(spec, 1);
        for threads in [2, 3] {
            assert!(
                png(spec, threads) == one,
                "{spec}: {threads} threads draw other bytes"
            );
        }
        drawn += usize::from(one.is_some());
    }
    drawn
}

#[test]
fn a_lit_picture_is_the_same_on_every_count() {
    // Lit, with surfaces and cylinders: drawn in bands shared by threads.
    let specs = ["std:plant-e".to_string()];
    let lilac = corpus("cpfg").join("11-CPFG-Lilac");
    let lilac = main_l(&lilac).unwrap().display().to_string();
    assert_eq!(same_on_every_count(&[specs[0].clone(), lilac]), 2);
}

#[test]
fn words_drawn_in_pieces_are_the_same_on_every_count() {
    // Fig. 3.11a at 46 steps: 0.32 M symbols, streamed, cut into pieces.
    let spec = "std:hogeweg-hesper-a";
    let sys = graftal::driver::compile(graftal::driver::load(spec).unwrap())
        .system
        .unwrap();
    let opts = graftal::driver::RunOptions {
        steps: Some(46),
        ..Default::default()
    };
    let word = graftal::driver::derive(&sys, &opts).unwrap();
    let pieces = graftal::turtle::Pieces::plan(&sys, &word.0[..], None, 0, 1);
    assert!(graftal::turtle::Pieced::count(&pieces) > 4);
    let one = png_at(spec, Some(46), 1).expect("drawn");
    for threads in [2, 3] {
        assert!(
            png_at(spec, Some(46), threads) == Some(one.clone()),
            "{threads} threads"
        );
    }
    // Lit: sympodial-asym's 0.12 M polygons, in pieces.
    let dir = corpus("cpfg").join("02-Mod-vis-3D-11-sympodial-asym");
    let lit = main_l(&dir).unwrap().display().to_string();
    let one = png(&lit, 1).expect("drawn");
    for threads in [2, 3] {
        assert!(png(&lit, threads) == Some(one.clone()), "{threads} threads");
    }
}

#[test]
fn every_picture_of_the_corpora_is_the_same_on_every_count() {
    if !crate::common::slow("the stdlib and corpora drawn on 1, 2 and 3 threads") {
        return;
    }
    let stdlib: Vec<String> = graftal::stdlib::ENTRIES
        .iter()
        .map(|e| format!("std:{}", e.name))
        .collect();
    assert!(same_on_every_count(&stdlib) > stdlib.len() / 2);
    let fractint: Vec<String> = crate::common::fractint_corpus_entries()
        .into_iter()
        .map(|(name, _)| corpus("fractint").join(name).display().to_string())
        .collect();
    assert!(same_on_every_count(&fractint) > fractint.len() / 2);
    let cpfg: Vec<String> = crate::common::cpfg_object_dirs()
        .iter()
        .filter_map(|d| main_l(d))
        .map(|p| p.display().to_string())
        .collect();
    assert!(same_on_every_count(&cpfg) > cpfg.len() / 2);
}

#[test]
fn check_says_the_same_on_every_count() {
    let mut files: Vec<String> = crate::common::cpfg_object_dirs()
        .iter()
        .filter_map(|d| main_l(d))
        .map(|p| p.display().to_string())
        .collect();
    files.push(corpus("fractint").join("fractint.l").display().to_string());
    files.push("std:algae".to_string());
    files.push("no-such-file.l".to_string());
    let args = |threads: &'static str, format: &'static str| {
        let mut a = vec!["check", "--format", format, "--threads", threads];
        a.extend(files.iter().map(String::as_str));
        graftal(&a)
    };
    for format in ["human", "json"] {
        let one = args("1", format);
        assert!(one.stderr.contains("E0"), "{format}: errors are reported");
        for threads in ["2", "3"] {
            let many = args(threads, format);
            assert_eq!(many.stdout, one.stdout, "{format}, {threads} threads");
            assert_eq!(many.stderr, one.stderr, "{format}, {threads} threads");
            assert_eq!(many.status, one.status);
        }
    }
}

/// The Koch island at 6 steps (2 M symbols, past the length from which a
/// shared-subtree word is split among threads): the same word written on
/// 1, 2 and 3 threads, and the same as the word stepwise rewriting gives.
#[test]
fn a_word_derived_on_several_threads_is_the_same() {
    let derived = |threads: &str| {
        let out = graftal(&["derive", "std:koch-island", "-n", "6", "--threads", threads]);
        assert_eq!(out.status, 0, "{}", out.stderr);
        out.stdout
    };
    let one = derived("1");
    assert!(one.len() > 1 << 20, "{} bytes", one.len());
    for threads in ["2", "3"] {
        assert!(
            derived(threads) == one,
            "{threads} threads write another word"
        );
    }
    let c = graftal::driver::compile(graftal::driver::load("std:koch-island").unwrap());
    let sys = c.system.unwrap();
    for threads in [1, 2, 3] {
        let opts = graftal::driver::RunOptions {
            steps: Some(6),
            threads,
            ..Default::default()
        };
        let word = graftal::driver::derive(&sys, &opts).unwrap();
        let stepwise = graftal::eval::Deriver::new(&sys)
            .derive_stepwise(&opts.derive_options(&sys), |_, _| {})
            .unwrap();
        assert!(word == stepwise, "{threads} threads");
        assert_eq!(format!("{}\n", word.display(&sys.symbols)), one);
    }
}

/// Words whose steps are cut into pieces: the cpfg Lychnis at 520 steps
/// (24 K modules; a parametric step is cut from 4 Ki) and Fig. 3.11a at 46
/// steps (0.32 M symbols; a step of a context-sensitive table system is
/// cut from 64 Ki). The same word written on 1, 2 and 3 threads.
#[test]
fn words_rewritten_in_pieces_are_the_same_on_every_count() {
    let lychnis = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/cpfg/10-GettingStarted-01-Lychnis/plant.l"
    );
    for (spec, steps, least) in [
        (lychnis, "520", 50_000),
        ("std:hogeweg-hesper-a", "46", 300_000),
    ] {
        let derived = |threads: &str| {
            let out = graftal(&["derive", spec, "-n", steps, "--threads", threads]);
            assert_eq!(out.status, 0, "{}", out.stderr);
            out.stdout
        };
        let one = derived("1");
        assert!(one.len() > least, "{spec}: {} bytes", one.len());
        for threads in ["2", "3"] {
            assert!(
                derived(threads) == one,
                "{spec}: {threads} threads write another word"
            );
        }
    }
}
