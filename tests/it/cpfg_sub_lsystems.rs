//! cpfg's sub-L-systems (manual §7.2): `?(n, s)` hands the modules after
//! it, up to the matching `$`, to L-system `n` of the file, whose own
//! productions, context filter and homomorphism rewrite and draw them, at
//! `s` times the size (cpfg's `generate.c`, `CheckPred`, and
//! `interpret.c`, `UpdateCurrentLsystem`).

use crate::common;
use graftal::driver::{self, RunOptions};
use graftal::source::SourceFile;

/// Two L-systems: the main one (1) rewrites `A`, the called one (2)
/// rewrites `A` otherwise and ignores `+` in its contexts.
const TWO: &str = "\
lsystem: 1
derivation length: 2
axiom: A?(2,0.5)A+B$A
A --> AB
B --> C
endlsystem
lsystem: 2
derivation length: 50
ignore: +
axiom: Z
A < B --> D
A --> E
endlsystem
";

fn derived(text: &str, steps: &str) -> String {
    let l = common::object_file("sub", "plant.l", text);
    let out = common::graftal(&["derive", l.to_str().unwrap(), "-n", steps]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    out.stdout.trim().to_string()
}

/// Each module is rewritten by the L-system it belongs to, and contexts
/// are matched with that L-system's `ignore:`; the called L-system's
/// axiom and derivation length are not used.
#[test]
fn each_part_of_the_word_is_rewritten_by_its_own_lsystem() {
    // Step 1: the main A → AB; inside the call, A → E and B (after A,
    // `+` ignored) → D; after `$` the main L-system again.
    assert_eq!(derived(TWO, "1"), "AB?(2,0.5)E+D$AB");
    // Step 2: in the main L-system B → C; E and D have no production in
    // L-system 2 and stay.
    assert_eq!(derived(TWO, "2"), "ABC?(2,0.5)E+D$ABC");
    // The file's own derivation length is the main L-system's (2).
    let l = common::object_file("sub-default", "plant.l", TWO);
    let out = common::graftal(&["derive", l.to_str().unwrap()]);
    assert_eq!(out.stdout.trim(), "ABC?(2,0.5)E+D$ABC");
}

/// Calls nest, and `$` goes back to the L-system that made the call.
#[test]
fn calls_nest_and_return_to_their_caller() {
    let text = "\
lsystem: 1
derivation length: 1
axiom: A?(2,1)A?(3,1)A$A$A
A --> B
endlsystem
lsystem: 2
axiom: Z
A --> C
endlsystem
lsystem: 3
axiom: Z
A --> D
endlsystem
";
    assert_eq!(derived(text, "1"), "B?(2,1)C?(3,1)D$C$B");
}

/// Inside a call, step lengths and the line width are `s` times what they
/// would be, and `$` gives back the caller's; a call's scale multiplies
/// the enclosing call's.
#[test]
fn a_call_scales_lengths_and_widths_until_its_return() {
    let text = "\
lsystem: 1
derivation length: 0
axiom: #(2)F(4)?(2,0.5)F(4)?(3,0.5)F(4)$F(4)$F(4)
endlsystem
lsystem: 2
axiom: Z
endlsystem
lsystem: 3
axiom: Z
endlsystem
";
    let l = common::object_file("sub-scale", "plant.l", text);
    std::fs::write(
        l.parent().unwrap().join("plant.v"),
        "initial line width: 1 pixels\n",
    )
    .unwrap();
    let c = driver::compile(SourceFile::read(&l).unwrap());
    assert!(!c.diagnostics.has_errors(), "{:#?}", c.diagnostics);
    let sys = c.system.unwrap();
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    let lengths: Vec<f64> = g
        .segments
        .iter()
        .map(|s| {
            (0..3)
                .map(|k| (s.b[k] - s.a[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let widths: Vec<f64> = g.segments.iter().map(|s| s.width).collect();
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    assert!(close(&lengths, &[4.0, 2.0, 1.0, 2.0, 4.0]), "{lengths:?}");
    assert!(close(&widths, &[2.0, 1.0, 0.5, 1.0, 2.0]), "{widths:?}");
}

/// A call naming no L-system of the file is an error at the call (its
/// `$` is that call's, not reported again); a `$` in a file with a single
/// L-system and no call returns from nothing (a warning whose fix writes
/// cpfg's roll to horizontal, `@v`).
#[test]
fn a_call_to_no_lsystem_and_a_stray_return_are_reported() {
    let text = "lsystem: 1\nderivation length: 1\naxiom: A\nA --> F?(7,1)F$\nendlsystem\n";
    let l = common::object_file("sub-missing", "plant.l", text);
    let c = driver::compile(SourceFile::read(&l).unwrap());
    let d: Vec<_> = c.diagnostics.iter().collect();
    let e0839 = d.iter().find(|d| d.code.0 == "E0839").expect("E0839");
    assert_eq!(&text[e0839.span.clone().unwrap()], "?(7,1)");
    assert!(e0839.message.contains("labelled 7"), "{}", e0839.message);
    assert!(d.iter().all(|d| d.code.0 != "W0825"), "{d:#?}");

    let text = "lsystem: 1\nderivation length: 1\naxiom: A\nA --> F$F\nendlsystem\n";
    let l = common::object_file("sub-stray", "plant.l", text);
    let c = driver::compile(SourceFile::read(&l).unwrap());
    let w0825 = (c.diagnostics.iter().find(|d| d.code.0 == "W0825")).expect("W0825");
    assert_eq!(&text[w0825.span.clone().unwrap()], "$");
    assert_eq!(w0825.fix.as_ref().unwrap().replacement, "@v");

    let two = "lsystem: 1\nderivation length: 1\naxiom: A\nA --> F?(2,1)F$\nendlsystem\n\
               lsystem: 2\naxiom: Z\nendlsystem\n";
    let l = common::object_file("sub-fine", "plant.l", two);
    let c = driver::compile(SourceFile::read(&l).unwrap());
    let codes: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
    assert_eq!(codes, ["W0810"], "only the missing view file");
}

/// 11-CPFG-Sedge is drawn from `sedge.l` and the three L-systems it
/// includes: the male spike (L-system 3, `~n` surfaces scaled by the
/// call's 1.25) tops the stem, the female spikes (2) and leaves (4) grow
/// from the nodes. Translated to `.gft` and back, it derives the same word.
#[test]
fn sedge_is_drawn_with_its_sub_lsystems() {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg/11-CPFG-Sedge");
    let c = driver::compile(SourceFile::read(&dir.join("sedge.l")).unwrap());
    assert!(!c.diagnostics.has_errors(), "{:#?}", c.diagnostics);
    let sys = c.system.unwrap();
    assert_eq!(sys.sub_lsystems.len(), 3);
    let labels: Vec<u32> = sys.sub_lsystems.iter().map(|s| s.label).collect();
    assert_eq!(labels, [2, 3, 4]);
    let word = graftal::eval::derive(&sys, &graftal::eval::DeriveOptions::new(95)).unwrap();
    let count = |name: &str| {
        let id = sys.symbols.get(name).unwrap();
        word.0.iter().filter(|&&s| s == id).count()
    };
    // L-system 3 rewrote `spikem` (modules s p i k e m, which L-system 1
    // has no production for) into the male spike: its 55 internodes, each
    // with a `~n` floret.
    assert_eq!(count("~n"), 55);
    // L-system 2 rewrote `spikef` into the two female spikes: two `~f`
    // bracts at each spike's base, and a chaff scale `~c` between two
    // `~f` in every floret.
    assert!(count("~c") > 100, "{}", count("~c"));
    assert_eq!(count("~f"), 2 * count("~c") + 4);
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    assert!(g.polygons.len() > 1000, "{}", g.polygons.len());
}

/// Every part of a sub-L-system (its label, productions, `ignore:`,
/// decomposition and homomorphism, and the main L-system's own label)
/// goes through `.gft` and reads back the same system, and the word
/// derived and drawn from the `.gft` is the cpfg file's.
#[test]
fn sub_lsystems_read_back_from_gft() {
    let text = "\
lsystem: 5
derivation length: 2
axiom: A?(2,0.5)A+B$A
A --> AB
endlsystem
lsystem: 2
ignore: +
axiom: Z
A < B --> D
A --> E?(5,2)A$
decomposition
E --> GG
homomorphism
seed: 3
D --> F(ran(1))
endlsystem
";
    let l = common::object_file("sub-gft", "plant.l", text);
    let c = driver::compile(SourceFile::read(&l).unwrap());
    assert!(!c.diagnostics.has_errors(), "{:#?}", c.diagnostics);
    let sys = c.system.as_ref().unwrap();
    assert_eq!(sys.label, 5);
    let sub = &sys.sub_lsystems[0];
    assert_eq!((sub.label, sub.productions.len()), (2, 2));
    assert_eq!(sub.decomposition.productions.len(), 1);
    assert_eq!(sub.homomorphism.seed, Some(3));
    let gft = common::graftal(&["translate", l.to_str().unwrap(), "--to", "gft"]);
    assert_eq!(gft.status, 0, "{}", gft.stderr);
    for line in [
        "label 5",
        "sub-lsystem 2 {\n  ignore +",
        "decomposition lsystem 2 depth 1 {",
        "homomorphism lsystem 2 depth 1 seed 3 {",
    ] {
        assert!(
            gft.stdout.contains(line),
            "`{line}` missing from\n{}",
            gft.stdout
        );
    }
    let back = common::object_file("sub-gft-back", "plant.gft", &gft.stdout);
    let c2 = driver::compile(SourceFile::read(&back).unwrap());
    assert!(!c2.diagnostics.has_errors(), "{:#?}", c2.diagnostics);
    sys.same_as(c2.system.as_ref().unwrap()).unwrap();
    let words: Vec<String> = [&l, &back]
        .iter()
        .map(|f| common::graftal(&["derive", f.to_str().unwrap()]).stdout)
        .collect();
    assert_eq!(words[0], words[1]);
    // Inside the call the decomposition of L-system 2 turned E into GG,
    // and the nested call back into L-system 5 rewrote its A by 5's rule.
    assert_eq!(words[0].trim(), "ABB?(2,0.5)GG?(5,2)AB$+D$ABB");
}
