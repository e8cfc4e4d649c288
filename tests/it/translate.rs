//! Translation between pfg, LinF and STL (`graftal translate`).
//!
//! The central property: a translation without warnings draws the same
//! segments as its source (same count, every endpoint within 1e-9 of the
//! picture's size) when both are evaluated with the same steps and seed.
//! It is checked over every stdlib entry and every target, and over random
//! pfg and LinF systems. Translations the target cannot express must name
//! each construct (E06xx) and write nothing; under `--lossy` they are
//! written, pass `check`, and carry one warning per approximation.

use graftal::back::{self, Request, Translation};
use graftal::driver::{self, Compiled, RunOptions};
use graftal::ir::System;
use graftal::source::SourceFile;
use graftal::stdlib::ENTRIES;
use graftal::turtle::Geometry;

use crate::common;
use common::random::{random_linf, random_pfg, Gen};
use common::{check_golden, graftal, read_back_targets, temp};

/// A notation graftal writes.
type Target = &'static dyn back::Back;

fn target(name: &str) -> Target {
    back::by_name(name).expect("a registered emitter")
}

fn ext(n: Target) -> &'static str {
    n.extension()
}

fn compile(name: &str, text: &str) -> Compiled {
    driver::compile(SourceFile::new(name, text))
}

fn translate(c: &Compiled, to: Target, lossy: bool) -> Translation {
    let sys = c.system.as_ref().expect("compiles");
    driver::translate(
        c,
        sys,
        &Request {
            target: to,
            lossy,
            steps: None,
        },
    )
}

fn geometry(sys: &System, seed: u64) -> Geometry {
    let opts = RunOptions {
        seed,
        ..RunOptions::default()
    };
    driver::geometry(sys, &opts).expect("evaluates").1
}

/// Same segments, in the same order, within 1e-9 of the picture's size:
/// the same coordinates, not only the same shape fitted to a frame (an
/// exact translation keeps bounds, statistics and meshes).
fn same_drawing(a: &Geometry, b: &Geometry) -> Result<(), String> {
    if a.segments.len() != b.segments.len() {
        return Err(format!(
            "{} segments, translation {}",
            a.segments.len(),
            b.segments.len()
        ));
    }
    let (Some(ba), Some(bb)) = (a.bbox(), b.bbox()) else {
        return Ok(());
    };
    let size = (0..3).map(|i| ba[i + 3] - ba[i]).fold(0.0f64, f64::max);
    let tol = 1e-9 * size.max(1.0);
    if (0..6).any(|i| (ba[i] - bb[i]).abs() > tol) {
        return Err(format!("bounding boxes differ: {ba:?} vs {bb:?}"));
    }
    for (k, (s, t)) in a.segments.iter().zip(&b.segments).enumerate() {
        for i in 0..3 {
            if (s.a[i] - t.a[i]).abs() > tol || (s.b[i] - t.b[i]).abs() > tol {
                return Err(format!("segment {k} differs: {s:?} vs {t:?}"));
            }
        }
    }
    Ok(())
}

/// Checks what every translation must satisfy, returning the compiled
/// output when it was written. An exact translation must draw the same.
fn check_translation(name: &str, c: &Compiled, to: Target, seed: u64) -> Option<(bool, Compiled)> {
    let t = translate(c, to, false);
    let out_name = format!("{name}.{}", ext(to));
    match &t.text {
        Some(text) => {
            assert!(
                t.diagnostics.is_empty(),
                "{name} -> {to:?}: written with diagnostics"
            );
            let out = compile(&out_name, text);
            // A grown outline's BED keeps its layout, which has nothing
            // left to grow (W0502); nothing else is allowed.
            assert!(
                out.diagnostics
                    .iter()
                    .all(|d| d.code.0 == "W0502" && to.name() == "stl"),
                "{name} -> {to:?}: the translation does not pass check: {:#?}\n{text}",
                out.diagnostics
            );
            let a = geometry(c.system.as_ref().unwrap(), seed);
            let b = geometry(out.system.as_ref().unwrap(), seed);
            if let Err(e) = same_drawing(&a, &b) {
                panic!("{name} -> {to:?} claims to be exact but: {e}\n{text}");
            }
            Some((true, out))
        }
        None => {
            assert!(!t.diagnostics.is_empty());
            for d in t.diagnostics.iter() {
                assert!(
                    d.code.0.starts_with("E06") && d.is_error(),
                    "{name} -> {to:?}: {d:?}"
                );
            }
            let errors = t.diagnostics.len();
            let lossy = translate(c, to, true);
            // A parametric system (std:gft/stochastic-tree) is refused even
            // under --lossy: no emitter but gft's writes one yet; so is an
            // object-instancing graph (std:bekaert/…), which only gft says.
            let refused =
                |d: &graftal::diagnostics::Diagnostic| matches!(d.code.0, "E0615" | "E0616");
            if lossy.text.is_none() && lossy.diagnostics.iter().any(refused) {
                return None;
            }
            let text = lossy.text.as_ref().unwrap_or_else(|| {
                // Only what cannot be approximated at all blocks --lossy.
                assert!(lossy.diagnostics.iter().any(|d| d.code.0 == "E0613"));
                panic!("{name} -> {to:?}: too large even with --lossy")
            });
            // W0614 is about the whole picture, not a construct.
            let per_construct = lossy.diagnostics.iter().filter(|d| d.code.0 != "W0614");
            assert_eq!(
                per_construct.count(),
                errors,
                "{name} -> {to:?}: one warning per construct"
            );
            assert!(lossy
                .diagnostics
                .iter()
                .all(|d| d.code.0.starts_with("W06")));
            let out = compile(&out_name, text);
            assert!(
                !out.diagnostics.has_errors(),
                "{name} -> {to:?} --lossy does not pass check: {:#?}\n{text}",
                out.diagnostics
            );
            Some((false, out))
        }
    }
}

/// `a` and `b` are the same strings up to a one-to-one renaming of
/// symbols.
fn same_up_to_renaming(
    a: &System,
    wa: &graftal::ir::Word,
    b: &System,
    wb: &graftal::ir::Word,
) -> Result<(), String> {
    let na: Vec<&str> =
        wa.0.iter()
            .map(|&s| a.symbols.name(s))
            .filter(|n| !n.is_empty())
            .collect();
    let nb: Vec<&str> =
        wb.0.iter()
            .map(|&s| b.symbols.name(s))
            .filter(|n| !n.is_empty())
            .collect();
    if na.len() != nb.len() {
        return Err(format!("{} symbols vs {}", na.len(), nb.len()));
    }
    let mut fwd = std::collections::HashMap::new();
    let mut back = std::collections::HashMap::new();
    for (x, y) in na.iter().zip(&nb) {
        if *fwd.entry(*x).or_insert(*y) != *y || *back.entry(*y).or_insert(*x) != *x {
            return Err(format!("`{x}` and `{y}` do not correspond one to one"));
        }
    }
    Ok(())
}

#[test]
fn every_stdlib_entry_translates_exactly_where_it_can_and_lossily_elsewhere() {
    let mut exact: std::collections::BTreeMap<String, usize> = Default::default();
    let mut round_trips = 0;
    for e in ENTRIES {
        let c = compile(e.file, e.text);
        assert!(c.system.is_some(), "{}", e.name);
        // A notation graftal reads but does not write (Smith's) is checked
        // one way only.
        let from = back::by_name(c.front.name());
        for to in read_back_targets() {
            let Some((is_exact, out)) = check_translation(e.name, &c, to, 0) else {
                continue;
            };
            if !is_exact {
                continue;
            }
            *exact
                .entry(format!("{} -> {}", c.front.name(), to.name()))
                .or_default() += 1;
            // Back again: the same strings (pfg and LinF), the same drawing.
            let Some(from) = from else { continue };
            let back = translate(&out, from, false);
            let Some(text) = back.text else {
                continue;
            };
            let again = compile(&format!("back.{}", ext(from)), &text);
            assert!(
                again.diagnostics.iter().all(|d| d.code.0 == "W0502"),
                "{}: {:?}",
                e.name,
                again.diagnostics
            );
            let (sa, sb) = (c.system.as_ref().unwrap(), again.system.as_ref().unwrap());
            if sa.graph.is_some() {
                // An instancing graph has no word to draw: it comes back
                // the same graph.
                sa.same_as(sb)
                    .unwrap_or_else(|err| panic!("{} -> {to:?} -> back: {err}", e.name));
                continue;
            }
            same_drawing(&geometry(sa, 0), &geometry(sb, 0))
                .unwrap_or_else(|err| panic!("{} -> {to:?} -> back: {err}\n{text}", e.name));
            // A symbol the target writes as several (a pfg pitch is a LinF
            // roll, turn and roll; a drawing `L` is pfg's `LF`) comes back
            // as several: same drawing, longer string.
            let one_to_one = translate(&c, to, false)
                .names
                .iter()
                .all(|(_, t)| !t.contains(' ') && (to.name() != "pfg" || t.chars().count() == 1));
            if from.name() != "stl" && to.name() != "stl" && one_to_one {
                let wa = driver::derive(sa, &RunOptions::default()).unwrap();
                let wb = driver::derive(sb, &RunOptions::default()).unwrap();
                same_up_to_renaming(sa, &wa, sb, &wb)
                    .unwrap_or_else(|err| panic!("{} -> {to:?} -> back: {err}\n{text}", e.name));
                if from.name() == "pfg" {
                    assert_eq!(
                        wa.display(&sa.symbols),
                        wb.display(&sb.symbols),
                        "{}: pfg -> {to:?} -> pfg keeps every symbol",
                        e.name
                    );
                }
                round_trips += 1;
            }
        }
    }
    eprintln!("exact translations of stdlib entries: {exact:?}; round trips with the same strings: {round_trips}");
    // The classic systems are mostly context-free, 2D, one angle.
    let count = |k: &str| exact.get(k).copied().unwrap_or(0);
    assert!(count("pfg -> pfg") >= 45, "{exact:?}");
    assert!(count("pfg -> linf") >= 25, "{exact:?}");
    assert!(count("pfg -> stl") >= 10, "{exact:?}");
    assert!(count("linf -> linf") >= 10, "{exact:?}");
    assert!(count("linf -> pfg") >= 3, "{exact:?}");
    assert!(count("linf -> stl") >= 3, "{exact:?}");
    assert!(count("stl -> stl") >= 10, "{exact:?}");
    assert!(count("stl -> linf") >= 3, "{exact:?}");
    assert!(round_trips >= 40, "{round_trips}");
}

#[test]
fn random_systems_translate_exactly_or_say_why() {
    let mut g = Gen(5);
    let mut exact = 0;
    let mut tried = 0;
    for i in 0..400 {
        let (name, text) = if i % 2 == 0 {
            (format!("random{i}.l"), random_pfg(&mut g))
        } else {
            (format!("random{i}.linf"), random_linf(&mut g))
        };
        let c = compile(&name, &text);
        if c.system.is_none() {
            continue;
        }
        for to in read_back_targets() {
            tried += 1;
            let seed = i as u64;
            if let Some((true, _)) = check_translation(&format!("{name}\n{text}"), &c, to, seed) {
                exact += 1;
            }
        }
    }
    eprintln!("random systems: {exact} of {tried} translations exact");
    assert!(exact * 3 > tried, "{exact} of {tried}");
}

#[test]
fn three_d_pfg_turns_become_linf_rotation_pairs_that_draw_the_same() {
    let src = "derivation length: 3\nangle factor: 8\nscale factor: 100\naxiom: F\nignore:\nF --> F[&F][^F][\\F/F]F[+&F]|F\n";
    let c = compile("t.l", src);
    let t = translate(&c, target("linf"), false);
    let text = t.text.clone().expect("pfg's 3D turtle is LinF pairs");
    let out = compile("t.linf", &text);
    assert!(out.diagnostics.is_empty(), "{:?}\n{text}", out.diagnostics);
    let (a, b) = (
        geometry(c.system.as_ref().unwrap(), 0),
        geometry(out.system.as_ref().unwrap(), 0),
    );
    same_drawing(&a, &b).unwrap();
    let bb = a.bbox().unwrap();
    assert!(bb[5] - bb[2] > 0.5, "the test system is really 3D: {bb:?}");
    // Rolls and turns come back as pfg's own symbols; a pitch comes back
    // as the roll, turn and roll LinF wrote, which draws the same.
    let back = translate(&out, target("pfg"), false).text.unwrap();
    assert!(back.contains("[\\F/F]"), "{back}");
    assert!(back.contains("|F"), "{back}");
    let again = compile("t2.l", &back);
    same_drawing(&a, &geometry(again.system.as_ref().unwrap(), 0)).unwrap();
    // STL cannot draw it.
    let stl = translate(&c, target("stl"), false);
    assert!(stl.text.is_none());
    assert!(stl.diagnostics.iter().all(|d| d.code.0 == "E0605"));
    assert_eq!(stl.diagnostics.len(), 4, "one per 3D symbol: & ^ \\ /");
}

#[test]
fn several_linf_line_symbols_become_markers_before_pfg_f() {
    let src = "lines f g\nblanks b h\nangles (0, pi/2)\naxiom f g\nrules\n  f = f+g b\n  g = g-f h f\n#: steps 4\n";
    let c = compile("t.linf", src);
    let t = translate(&c, target("pfg"), false);
    let text = t.text.expect("exact");
    assert!(text.contains("\nF --> *\n"), "{text}");
    assert!(text.contains("\nf --> *"), "{text}");
    let out = compile("t.l", &text);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    same_drawing(
        &geometry(c.system.as_ref().unwrap(), 0),
        &geometry(out.system.as_ref().unwrap(), 0),
    )
    .unwrap();
    // Moving symbols keep moving: the picture has gaps.
    assert!(geometry(out.system.as_ref().unwrap(), 0).segments.len() > 10);
}

#[test]
fn untranslatable_constructs_are_errors_with_spans_and_nothing_is_written() {
    let out = temp("hh.linf");
    let _ = std::fs::remove_file(&out);
    let o = graftal(&[
        "translate",
        "std:hogeweg-hesper-a",
        "--to",
        "linf",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(!out.exists(), "nothing is written");
    // One error per context-sensitive production, each at its line.
    assert_eq!(o.stderr.matches("[E0601]").count(), 8, "{}", o.stderr);
    for line in 6..=13 {
        assert!(
            o.stderr.contains(&format!("hogeweg-hesper-a.l:{line}:1")),
            "{}",
            o.stderr
        );
    }
    // pfg can rewrite `+` and `-`; LinF cannot.
    assert!(o.stderr.contains("[E0611]"), "{}", o.stderr);
    // --lossy writes it, with one warning each.
    let o = graftal(&[
        "translate",
        "std:hogeweg-hesper-a",
        "--to",
        "linf",
        "--lossy",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert_eq!(o.stderr.matches("[W0601]").count(), 8, "{}", o.stderr);
    assert_eq!(o.stderr.matches("[W0611]").count(), 2, "{}", o.stderr);
    let check = graftal(&["check", out.to_str().unwrap()]);
    assert_eq!(check.status, 0, "{}", check.stderr);
}

#[test]
fn linf_randomness_is_an_error_for_pfg_and_stl() {
    for (entry, code) in [
        ("std:linf/fig10-brownian-motion", "[E0604]"),
        ("std:linf/fig09-stochastic-plant", "[E0603]"),
    ] {
        for to in ["pfg", "stl"] {
            let o = graftal(&["translate", entry, "--to", to]);
            assert_eq!(o.status, 1, "{entry} -> {to}");
            assert!(o.stdout.is_empty());
            assert!(o.stderr.contains(code), "{entry} -> {to}: {}", o.stderr);
        }
    }
    // LinF to LinF keeps the randomness, and the same seed gives the same
    // picture.
    let c = compile(
        "b.linf",
        ENTRIES
            .iter()
            .find(|e| e.name == "linf/fig10-brownian-motion")
            .unwrap()
            .text,
    );
    for seed in [0, 7] {
        let t = translate(&c, target("linf"), false);
        let out = compile("b2.linf", t.text.as_ref().unwrap());
        same_drawing(
            &geometry(c.system.as_ref().unwrap(), seed),
            &geometry(out.system.as_ref().unwrap(), seed),
        )
        .unwrap();
    }
}

#[test]
fn json_reports_each_construct_with_its_span() {
    let o = graftal(&[
        "translate",
        "std:koch-island",
        "--to",
        "linf",
        "--format",
        "json",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    assert_eq!(v["from"], "pfg");
    assert_eq!(v["to"], "linf");
    assert_eq!(v["exact"], true);
    assert!(v["text"].as_str().unwrap().contains("F = F+F-F-FF+F+F-F"));
    let cs = v["constructs"].as_array().unwrap();
    let prod = cs
        .iter()
        .find(|c| c["construct"].as_str().unwrap().starts_with("production"))
        .unwrap();
    assert_eq!(prod["status"], "exact");
    assert_eq!(prod["target"], "F = F+F-F-FF+F+F-F");
    let span = &prod["span"];
    let text = ENTRIES
        .iter()
        .find(|e| e.name == "koch-island")
        .unwrap()
        .text;
    let (s, e) = (
        span["start"].as_u64().unwrap() as usize,
        span["end"].as_u64().unwrap() as usize,
    );
    assert!(
        text[s..e].contains("F --> F+F-F-FF+F+F-F"),
        "{}",
        &text[s..e]
    );

    // Approximations under --lossy, with their spans.
    let o = graftal(&[
        "translate",
        "std:hogeweg-hesper-a",
        "--to",
        "stl",
        "--lossy",
        "--format",
        "json",
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    assert_eq!(v["exact"], false);
    let approx: Vec<&serde_json::Value> = v["constructs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["status"] == "approximated")
        .collect();
    assert!(approx.len() >= 8);
    assert!(approx.iter().all(|c| c["note"].is_string()));
    assert!(approx.iter().filter(|c| c["span"]["line"].is_u64()).count() >= 8);
    // Without --lossy: "impossible", nothing written.
    let o = graftal(&[
        "translate",
        "std:hogeweg-hesper-a",
        "--to",
        "stl",
        "--format",
        "json",
    ]);
    assert_eq!(o.status, 1);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    assert_eq!(v["written"], false);
    assert!(v["text"].is_null());
}

#[test]
fn comments_are_carried_over_where_they_attach() {
    let src = "/* A bush. */\nderivation length: 2\nangle factor: 8\naxiom: X\n/* the stem doubles */\nF --> FF\nX --> F[+X][-X]FX /* apex */\n";
    let c = compile("bush.l", src);
    let linf = translate(&c, target("linf"), false).text.unwrap();
    assert!(linf.contains("# A bush."), "{linf}");
    assert!(linf.contains("# the stem doubles\n  F = FF"), "{linf}");
    assert!(linf.contains("X = F[+X][-X]FX  # apex"), "{linf}");
    let pfg = translate(&c, target("pfg"), false).text.unwrap();
    assert!(pfg.contains("/* the stem doubles */\nF --> FF"), "{pfg}");
    assert!(pfg.contains("X --> F[+X][-X]FX /* apex */"), "{pfg}");
    // Formatting is canonical: translating the output again changes nothing
    // but the first line.
    let again = translate(&compile("b2.l", &pfg), target("pfg"), false)
        .text
        .unwrap();
    assert_eq!(pfg, again);
}

#[test]
fn stl_structure_becomes_bracketed_productions() {
    // Rn of Fig. 6: F R1{R1, R2, R1} with R1 = [F][+F][-F], R2 = [++F][-F].
    let c = compile(
        "rn.stl",
        ENTRIES
            .iter()
            .find(|e| e.name == "stl/fig06-rn")
            .unwrap()
            .text,
    );
    // Fig. 6 narrows its stems per level (B = 6 (2)): LinF has no widths.
    let t = translate(&c, target("linf"), false);
    assert!(t.text.is_none());
    assert!(t.diagnostics.iter().all(|d| d.code.0 == "E0608"));
    let t = translate(&c, target("linf"), true);
    let text = t.text.expect("written with --lossy");
    assert!(t.diagnostics.iter().all(|d| d.code.0 == "W0608"));
    assert!(text.contains("R1 = "), "{text}");
    let out = compile("rn.linf", &text);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let word = driver::derive(out.system.as_ref().unwrap(), &RunOptions::default()).unwrap();
    let src_word = driver::derive(c.system.as_ref().unwrap(), &RunOptions::default()).unwrap();
    assert_eq!(
        c.word_text(c.system.as_ref().unwrap(), &src_word),
        "F[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]"
    );
    // The LinF word, drawing symbols only, reads as STL's with the turns
    // written LinF's way.
    let linf_word = out.word_text(out.system.as_ref().unwrap(), &word);
    let drawn: String = linf_word.chars().filter(|c| "F[]+-".contains(*c)).collect();
    assert_eq!(drawn.matches('F').count(), 12, "{linf_word}");
    same_drawing(
        &geometry(c.system.as_ref().unwrap(), 0),
        &geometry(out.system.as_ref().unwrap(), 0),
    )
    .unwrap();
    // A grown outline: the explicit tree, the layout reported.
    let od = compile(
        "od.stl",
        ENTRIES
            .iter()
            .find(|e| e.name == "stl/fig09-outline-bfs")
            .unwrap()
            .text,
    );
    let t = translate(&od, target("linf"), false);
    assert!(t.text.is_none());
    assert!(
        t.diagnostics.iter().any(|d| d.code.0 == "E0610"),
        "{:?}",
        t.diagnostics
    );
    let lossy = translate(&od, target("linf"), true);
    let out = compile("od.linf", lossy.text.as_ref().unwrap());
    assert!(!out.diagnostics.has_errors());
    let a = geometry(od.system.as_ref().unwrap(), 0);
    let b = geometry(out.system.as_ref().unwrap(), 0);
    // Only widths and the layout were approximated: the stems are the same.
    assert!(lossy
        .diagnostics
        .iter()
        .all(|d| d.code.0 == "W0610" || d.code.0 == "W0608"));
    same_drawing(&a, &b).unwrap();
}

#[test]
fn pfg_to_stl_writes_the_derivation_into_rules() {
    // Only F is rewritten: the paper's self-resemblance count.
    let o = graftal(&["translate", "std:plant-a", "--to", "stl"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(
        o.stdout.contains("Plant = [I 5 F[RF]F[LF]F]"),
        "{}",
        o.stdout
    );
    // Several rewritten symbols: one rule per symbol and step; -n chooses
    // the steps.
    let o = graftal(&["translate", "std:hilbert", "--to", "stl", "-n", "3"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let c = compile("h.stl", &o.stdout);
    assert!(
        c.diagnostics.is_empty(),
        "{:?}\n{}",
        c.diagnostics,
        o.stdout
    );
    let src = driver::compile(driver::load("std:hilbert").unwrap());
    let opts = RunOptions {
        steps: Some(3),
        ..RunOptions::default()
    };
    let a = driver::geometry(src.system.as_ref().unwrap(), &opts)
        .unwrap()
        .1;
    let b = geometry(c.system.as_ref().unwrap(), 0);
    same_drawing(&a, &b).unwrap();
    assert_eq!(b.segments.len(), 63);
}

/// tests/diagnostics/translate/NAME--TARGET.EXT -> NAME--TARGET.txt: the
/// diagnostics (colour off) and the text written, then the same with
/// `--lossy` when the plain translation is refused. Regenerate on purpose
/// with `GRAFTAL_BLESS=1`.
#[test]
fn translations_and_their_diagnostics_match_their_snapshots() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/diagnostics/translate");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "txt"))
        .collect();
    files.sort();
    assert!(files.len() >= 6);
    let mut failures = Vec::new();
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let target = match name.split("--").nth(1).and_then(|t| t.split('.').next()) {
            Some(t @ ("pfg" | "linf" | "stl")) => target(t),
            other => panic!("{name}: no target in the name ({other:?})"),
        };
        let c = compile(&name, &std::fs::read_to_string(&path).unwrap());
        let mut snap = String::new();
        for lossy in [false, true] {
            let t = translate(&c, target, lossy);
            if lossy {
                snap.push_str("\n===== with --lossy =====\n");
            }
            snap.push_str(&t.diagnostics.render(&c.file, false));
            match &t.text {
                Some(text) => {
                    snap.push_str("----- written -----\n");
                    snap.push_str(text);
                    let out = compile(&format!("out.{}", ext(target)), text);
                    assert!(
                        !out.diagnostics.has_errors(),
                        "{name}: {:?}",
                        out.diagnostics
                    );
                    if !lossy {
                        same_drawing(
                            &geometry(c.system.as_ref().unwrap(), 0),
                            &geometry(out.system.as_ref().unwrap(), 0),
                        )
                        .unwrap_or_else(|e| panic!("{name}: {e}"));
                        break;
                    }
                }
                None => snap.push_str("----- nothing written -----\n"),
            }
        }
        if let Err(e) = check_golden(&path.with_extension("txt"), &snap) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// An STL seed length (`L = 10`) keeps its coordinates in LinF (a length
/// factor at the start of the axiom), exactly; pfg, whose steps are 1
/// long, draws the same shape ten times smaller, which it says and does
/// only when asked (`--lossy`).
#[test]
fn a_constant_stl_length_keeps_its_coordinates() {
    let src = "ANGLE 30\nL = 10\nR1 = [I 3 F[LF][RF]]\nSEED\nR1\nENDSEED\n";
    let c = compile("plant.stl", src);
    let t = translate(&c, target("linf"), false);
    assert!(t.diagnostics.is_empty(), "{:?}", t.diagnostics);
    let text = t.text.expect("written");
    assert!(text.contains("axiom 10@ R1"), "{text}");
    let out = compile("plant.linf", &text);
    let (a, b) = (
        geometry(c.system.as_ref().unwrap(), 0),
        geometry(out.system.as_ref().unwrap(), 0),
    );
    same_drawing(&a, &b).unwrap();
    let right = a.bbox().unwrap()[3];
    assert!((right - 23.660254037844386).abs() < 1e-9, "{right}");
    let t = translate(&c, target("pfg"), false);
    assert!(t.text.is_none());
    let d = &t.diagnostics.0[0];
    assert_eq!(d.message, "the step length 10: pfg's steps are 1 long");
    let t = translate(&c, target("pfg"), true);
    assert!(t.text.is_some());
    let said = &t.diagnostics.0[0].message;
    assert!(said.contains("its coordinates divided by 10"), "{said}");
}

/// Lengths that differ from level to level are still refused by pfg, in
/// one diagnostic that quotes the STL line, not LinF's `0.8@`.
#[test]
fn stl_level_lengths_are_reported_in_stl_syntax_once() {
    let src = "ANGLE 30\nL = 10 (2)\nP = [I 3 F[RF]F[LF]F]\nSEED\nP\nENDSEED\n";
    let c = compile("plant.stl", src);
    for lossy in [false, true] {
        let t = translate(&c, target("pfg"), lossy);
        let lengths: Vec<_> = t
            .diagnostics
            .iter()
            .filter(|d| d.code.0 == if lossy { "W0607" } else { "E0607" })
            .filter(|d| d.message.contains("differ from level to level"))
            .collect();
        assert_eq!(lengths.len(), 1, "{:?}", t.diagnostics);
        let d = lengths[0];
        assert!(d.message.contains("`L = 10 (2)`"), "{}", d.message);
        assert!(!d.message.contains('@'), "{}", d.message);
        let span = d.span.clone().expect("a span");
        assert_eq!(&src[span], "L = 10 (2)");
    }
}

/// A step length other than 1 is not pfg's: a translation that kept only
/// the shape would not be exact.
#[test]
fn a_step_length_pfg_cannot_keep_makes_it_inexact() {
    let c = compile("k.l", "angle factor: 4\naxiom: F+F-F\n");
    let mut sys = c.system.clone().expect("compiles");
    sys.settings.step = 10.0;
    let t = driver::translate(
        &c,
        &sys,
        &Request {
            target: target("pfg"),
            lossy: true,
            steps: None,
        },
    );
    assert!(!t.is_exact(), "{:?}", t.mapping);
    assert_eq!(t.diagnostics.0[0].code.0, "W0607");
}

/// The stdlib entry `name`, compiled as a file named `file`.
fn std_entry(name: &str, file: &str) -> Compiled {
    let entry = ENTRIES.iter().find(|e| e.name == name).expect("an entry");
    compile(file, entry.text)
}

/// The segments `c`'s system draws, and those of `text` read as `to`.
fn segment_counts(c: &Compiled, text: &str, to: Target) -> (usize, usize) {
    let out = compile(&format!("out.{}", ext(to)), text);
    (
        geometry(c.system.as_ref().unwrap(), 0).segments.len(),
        geometry(out.system.as_ref().unwrap(), 0).segments.len(),
    )
}

/// Fig. 3.11a without its contexts is three segments: `--lossy` says so in
/// one warning with both counts.
#[test]
fn a_lossy_translation_that_draws_another_picture_says_so_with_the_figures() {
    let c = std_entry("hogeweg-hesper-a", "a.l");
    let t = translate(&c, target("linf"), true);
    let text = t.text.as_deref().expect("written with --lossy");
    let (source, translated) = segment_counts(&c, text, target("linf"));
    assert!(source > 10 * translated, "{source} vs {translated}");
    let differs: Vec<_> = t
        .diagnostics
        .iter()
        .filter(|d| d.code.0 == "W0614")
        .collect();
    assert_eq!(differs.len(), 1, "{:?}", t.diagnostics);
    assert!(!differs[0].is_error());
    assert_eq!(
        differs[0].message,
        format!("the translation draws {translated} segments where the source draws {source}")
    );
}

/// Dropping what does not change the drawing (here widths and colours)
/// adds no such warning; nor does a translation without `--lossy`.
#[test]
fn a_lossy_translation_of_the_same_segments_gets_no_picture_warning() {
    let c = std_entry("fibonacci-bush", "b.l");
    let t = translate(&c, target("linf"), true);
    let text = t.text.as_deref().expect("written with --lossy");
    assert!(!t.diagnostics.is_empty());
    let (source, translated) = segment_counts(&c, text, target("linf"));
    assert_eq!(source, translated);
    assert!(t.diagnostics.iter().all(|d| d.code.0 != "W0614"));
    let strict = translate(
        &compile("a.l", "axiom: F\nF < F --> FF\n"),
        target("linf"),
        false,
    );
    assert!(strict.diagnostics.iter().all(|d| d.code.0 != "W0614"));
}

/// A source too large to draw quickly is not compared, and a note says so.
#[test]
fn a_source_too_large_to_compare_is_skipped_with_a_note() {
    let c = compile(
        "big.l",
        "derivation length: 40\naxiom: F\nA < F --> F\nF --> FF\n",
    );
    let t = translate(&c, target("linf"), true);
    assert!(t.text.is_some());
    assert!(t.diagnostics.iter().all(|d| d.code.0 != "W0614"));
    let notes: Vec<&String> = t.diagnostics.iter().flat_map(|d| &d.notes).collect();
    assert!(
        notes
            .iter()
            .any(|n| n.contains("not compared") && n.contains("the source")),
        "{notes:?}"
    );
}

/// A LinF axiom that starts with a length factor scales the whole picture:
/// STL says it as its `L`, exactly, with the same coordinates; pfg, whose
/// steps are 1 long, only with `--lossy`.
#[test]
fn a_length_factor_starting_the_axiom_is_the_step_length() {
    let src = "lines f\nangles (0, pi/2)\naxiom 10@ f + f\nrules\n  f = f - f\n";
    let c = compile("s.linf", src);
    let t = translate(&c, target("stl"), false);
    assert!(t.is_exact(), "{:?}", t.diagnostics);
    let text = t.text.unwrap();
    assert!(text.contains("L = 10"), "{text}");
    let out = compile("s.stl", &text);
    same_drawing(
        &geometry(c.system.as_ref().unwrap(), 1),
        &geometry(out.system.as_ref().unwrap(), 1),
    )
    .unwrap();
    let t = translate(&c, target("pfg"), false);
    let d = &t.diagnostics.0[0];
    assert_eq!(d.message, "the step length 10: pfg's steps are 1 long");
    // Elsewhere a factor changes the picture's proportions: still refused.
    let c = compile("t.linf", "lines f\nangles (0, pi/2)\naxiom f + 10@ f\n");
    let t = translate(&c, target("pfg"), false);
    assert!(t.diagnostics.iter().any(|d| d.code.0 == "E0607"));
}

/// An interval angle is reported with its middle in degrees only when it
/// has one to give.
#[test]
fn interval_messages_have_no_empty_degrees() {
    let c = std_entry("linf/fig12-trees", "t.linf");
    let t = translate(&c, target("pfg"), true);
    for d in t.diagnostics.iter() {
        let all = format!("{} {:?}", d.message, d.help);
        assert!(!all.contains("( degrees)"), "{all}");
    }
}

#[test]
fn linf_angles_are_written_back_as_they_were_written() {
    // `e` is one bit above pi/3: a decimal, or it would not read back.
    let src = "angles d = (0, pi/3) t = (-pi/2, 0.3) w = (0, [0 2*pi]) c = (3*pi/4, 0.7639*pi)\n\
               e = (0, 1.0471975511965979)\n\
               axiom f\nrules f = f +t f -w f +c f -d f +e f\nlines f\n";
    let c = compile("as-written.linf", src);
    let t = translate(&c, target("linf"), false);
    let text = t.text.expect("translates");
    for written in [
        "pi/3",
        "-pi/2",
        "0.3",
        "[0 2*pi]",
        "3*pi/4",
        "0.7639*pi",
        "1.0471975511965979",
    ] {
        assert!(text.contains(written), "{written} in\n{text}");
    }
    assert!(
        !text.contains("6.28") && !text.contains("1.0471975511965976"),
        "{text}"
    );
    // And reads back to the same angles, bit for bit.
    let back = compile("back.linf", &text);
    let rotations = |c: &Compiled| {
        let sys = c.system.as_ref().expect("compiles");
        let mut r: Vec<String> = sys
            .rotations
            .iter()
            .map(|r| format!("{:?} {:?}", r.torsion, r.curvature))
            .collect();
        r.sort();
        r
    };
    assert_eq!(rotations(&c), rotations(&back));
}

#[test]
fn a_refused_interval_is_quoted_as_written() {
    let file = temp("interval.linf");
    std::fs::write(
        &file,
        "angles w = (0, [0 2*pi])\naxiom f\nrules f = f +w f\nlines f\n",
    )
    .unwrap();
    let o = graftal(&["translate", file.to_str().unwrap(), "--to", "pfg"]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(
        o.stderr.contains("the interval angle `[0 2*pi]` of `+w`"),
        "{}",
        o.stderr
    );
}

/// pfg written by `translate` is the book's short form where a production
/// has no context (`F --> …`), and has no `ignore:` line when nothing is
/// ignored; with contexts, the full form and the ignore list stay.
#[test]
fn pfg_is_written_in_the_books_short_form_without_contexts() {
    let c = std_entry("koch-island", "k.l");
    let text = translate(&c, target("pfg"), false).text.unwrap();
    assert!(text.contains("\nF --> F+F-F-FF+F+F-F\n"), "{text}");
    assert!(!text.contains("* <") && !text.contains("ignore:"), "{text}");
    let c = std_entry("hogeweg-hesper-a", "h.l");
    let text = translate(&c, target("pfg"), false).text.unwrap();
    assert!(text.contains("\n1 < 1 > 0 --> 0\n"), "{text}");
    assert!(text.contains("\n+ --> -\n"), "{text}");
    assert!(text.contains("\nignore: "), "{text}");
}
