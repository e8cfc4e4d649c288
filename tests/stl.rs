//! The STL front end against the paper (Yeh, Chien & Lee): its example
//! strings, stem parameters, layouts, outline growth under BFS and DFS, and
//! the Branch-Expansion Description round trip.

use graftal::diagnostics::Diagnostics;
use graftal::driver::{self, RunOptions};
use graftal::ir::System;
use graftal::stl;
use graftal::turtle::Geometry;

/// The derived string (the expanded drawing components) of an STL text.
fn expand(src: &str) -> String {
    let sys = stl::read_ok(src);
    sys.axiom.display(&sys.symbols)
}

fn geometry(sys: &System) -> Geometry {
    driver::geometry(sys, &RunOptions::default()).unwrap().1
}

fn codes(src: &str) -> Vec<&'static str> {
    let mut d = Diagnostics::default();
    stl::read(src, &mut d);
    d.iter().map(|d| d.code.0).collect()
}

const PAPER_RULES: &str = "R1 = [F][+F][-F]\nR2 = [++F][-F]\n";

#[test]
fn paper_rn_expands_to_its_printed_string() {
    let src = format!("{PAPER_RULES}SEED\nR1{{R1, R2, R1}}\nENDSEED\n");
    assert_eq!(expand(&src), "[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]");
    // The paper's complete form `{R1{,}, R2{,}, R1{,}}` is the same tree.
    let full = format!("{PAPER_RULES}SEED\nR1{{R1{{,}}, R2{{,}}, R1{{,}}}}\nENDSEED\n");
    assert_eq!(expand(&full), expand(&src));
}

#[test]
fn paper_rm_expands_to_its_printed_string() {
    let src = format!(
        "{PAPER_RULES}SEED\nR1{{R1{{R2{{,}}, R2{{,}}, R2{{,}}}}, R2{{R2{{,}}, }}, R1{{R2{{,}}, R2{{,}}, R2{{,}}}}}}\nENDSEED\n"
    );
    let s = expand(&src);
    // The paper prints the second and third branches (its typesetting lost
    // the first, which is the third with `F` for `-F`).
    let second = "[+F[++F[++F][-F]][-F]]";
    let third = "[-F[F[++F][-F]][+F[++F][-F]][-F[++F][-F]]]";
    let first = "[F[F[++F][-F]][+F[++F][-F]][-F[++F][-F]]]";
    assert_eq!(s, format!("{first}{second}{third}"));
}

#[test]
fn seed_t_and_seed_t_prime_derive_the_same_string() {
    let t = expand("SEED\n[FFF][F[+F][-F]F][F[+F][-F]F]\nENDSEED\n");
    let t2 = expand("R1 = [FFF]\nR2 = [F[+F][-F]F]\nSEED\nR1R2R2\nENDSEED\n");
    assert_eq!(t, "[FFF][F[+F][-F]F][F[+F][-F]F]");
    assert_eq!(t, t2);
}

#[test]
fn self_resemblance_counts_as_spec_defines_them() {
    assert_eq!(expand("Rs = [I 1 F[+F]]\nSEED\nRs\nENDSEED"), "F[+F]");
    assert_eq!(
        expand("Rs = [I 2 F[+F]]\nSEED\nRs\nENDSEED"),
        "F[+F][+F[+F]]"
    );
    assert_eq!(expand("SEED\n[I 2 F[+F]]\nENDSEED"), "F[+F][+F[+F]]");
    assert_eq!(
        expand("R1 = F[RF]\nR3 = [I 3 R1]\nSEED\nR3\nENDSEED"),
        "F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]".replace(
            "F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]F[RF]",
            &{
                // F -> F[RF] three times, computed by hand: 1 -> 2 -> 4 -> 8 F's.
                let one = "F[RF]";
                let two = one.replace('F', one);
                two.replace('F', one)
            }
        )
    );
}

#[test]
fn failed_branches_are_not_drawn() {
    let src = format!("{PAPER_RULES}SEED\nR1{{R2, ~, ~}}\nENDSEED\n");
    assert_eq!(expand(&src), "[F[++F][-F]]");
    let sys = stl::read_ok(&src);
    assert_eq!(geometry(&sys).segments.len(), 3);
}

#[test]
fn entries_beyond_the_branches_and_terms_without_branches_are_errors() {
    assert_eq!(
        codes(&format!("{PAPER_RULES}SEED\nR2{{R2, R2, R2}}\nENDSEED\n")),
        vec!["E0502"]
    );
    assert_eq!(codes("R5 = FF\nSEED\nR5{R5}\nENDSEED\n"), vec!["E0503"]);
    assert_eq!(
        codes("R1 = [F]R2\nR2 = [+F]R1\nSEED\nR1\nENDSEED\n"),
        vec!["E0509"]
    );
    assert_eq!(
        codes(&format!("{PAPER_RULES}SEED\nR3\nENDSEED\n")),
        vec!["E0501"]
    );
}

#[test]
fn stem_parameters_show_as_widths_and_lengths() {
    let src = "B = 8 (2)\nL = 40 (10)\nR1 = [F][+F]\nSEED\nF R1{R1, R1{R1}}\nENDSEED\n";
    let sys = stl::read_ok(src);
    let g = geometry(&sys);
    let len = |s: &graftal::turtle::Segment| {
        ((s.b[0] - s.a[0]).powi(2) + (s.b[1] - s.a[1]).powi(2)).sqrt()
    };
    let measured: Vec<(f64, f64)> = g.segments.iter().map(|s| (s.width, len(s))).collect();
    // Level 0 trunk, level 1 (R1), level 2 (entries), level 3.
    let expect = [
        (8.0, 40.0),
        (6.0, 30.0),
        (4.0, 20.0),
        (4.0, 20.0),
        (6.0, 30.0),
        (4.0, 20.0),
        (2.0, 10.0),
        (2.0, 10.0),
        (4.0, 20.0),
    ];
    assert_eq!(measured.len(), expect.len(), "{measured:?}");
    for (m, e) in measured.iter().zip(expect) {
        assert!(
            (m.0 - e.0).abs() < 1e-9 && (m.1 - e.1).abs() < 1e-9,
            "{measured:?}"
        );
    }
}
