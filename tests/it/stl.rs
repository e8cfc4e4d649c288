//! The STL front end against the paper (Yeh, Chien & Lee): its example
//! strings, stem parameters, layouts, outline growth under BFS and DFS, and
//! the Branch-Expansion Description round trip.

use graftal::diagnostics::Diagnostics;
use graftal::driver::{self, RunOptions};
use graftal::front::stl;
use graftal::ir::System;
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
    // F -> F[RF] three times: 1, 2, 4, then 8 F's, each step substituting
    // every F of the previous string in parallel.
    let one = "F[RF]";
    let two = one.replace('F', one);
    let three = two.replace('F', one);
    assert_eq!(three.matches('F').count(), 8);
    assert_eq!(
        expand("R1 = F[RF]\nR3 = [I 3 R1]\nSEED\nR3\nENDSEED"),
        three
    );
    // `[I 0 X]` is F itself.
    assert_eq!(expand("SEED\n[I 0 F[+F]]\nENDSEED"), "F");
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

// ---------------------------------------------------------------------------
// Outline growth (the paper's section IV) on one outline.

/// A crown (ellipse) over a trunk (rectangle); `R1 = [-F][+F]` as in the
/// paper's Fig. 9 (the right branch `[-F]` has the first priority).
const OUTLINE: &str = "ANGLE 30\nB = 4 (0.3)\nL = 30 (2)\nGROWTH BFS\nLEVELS 12\nR1 = [-F][+F]\nSEED\nF R1\nENDSEED\nLAYOUT\n(clGreen) Ellipse (-150, 20), 300, 260\n(clMaroon) Rectangle (-10, 0), 20, 40\nENDLAYOUT\n";

fn grown(strategy: &str) -> System {
    stl::read_ok(&OUTLINE.replace("GROWTH BFS", &format!("GROWTH {strategy}")))
}

/// Inside the crown or the trunk, computed here independently of
/// `stl::layout` (with a tolerance of 1e-9).
fn in_outline(p: [f64; 3]) -> bool {
    let (u, v) = ((p[0] - 0.0) / 150.0, (p[1] - 150.0) / 130.0);
    let ellipse = u * u + v * v <= 1.0 + 1e-9;
    let rect =
        (-10.0 - 1e-9..=10.0 + 1e-9).contains(&p[0]) && (-1e-9..=40.0 + 1e-9).contains(&p[1]);
    ellipse || rect
}

fn point_seg(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let e = [b[0] - a[0], b[1] - a[1]];
    let l2 = e[0] * e[0] + e[1] * e[1];
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a[0] + t * e[0] - p[0]).powi(2) + (a[1] + t * e[1] - p[1]).powi(2)).sqrt()
}

fn same(p: [f64; 3], q: [f64; 3]) -> bool {
    (p[0] - q[0]).abs() < 1e-7 && (p[1] - q[1]).abs() < 1e-7
}

/// Descendant counts (rule applications) under each entry of the seed's
/// first term: the first-priority branch and the last.
fn sides(sys: &System) -> Vec<usize> {
    use graftal::ir::{BranchEntry, BranchTerm, SeedItem};
    fn count(t: &BranchTerm) -> usize {
        t.entries
            .iter()
            .map(|e| match e {
                BranchEntry::Term(c) => 1 + count(c),
                _ => 0,
            })
            .sum()
    }
    let st = sys.structure.as_ref().unwrap();
    let root = st
        .seed
        .iter()
        .find_map(|s| match s {
            SeedItem::Term(t) => Some(t),
            _ => None,
        })
        .unwrap();
    root.entries
        .iter()
        .map(|e| match e {
            BranchEntry::Term(c) => 1 + count(c),
            _ => 0,
        })
        .collect()
}

#[test]
fn every_grown_stem_stays_inside_the_layout() {
    for strategy in ["BFS", "DFS"] {
        let g = geometry(&grown(strategy));
        assert!(g.segments.len() > 300, "{strategy}: {}", g.segments.len());
        for s in &g.segments {
            for k in 0..=200 {
                let t = k as f64 / 200.0;
                let p = [
                    s.a[0] + t * (s.b[0] - s.a[0]),
                    s.a[1] + t * (s.b[1] - s.a[1]),
                    0.0,
                ];
                assert!(
                    in_outline(p),
                    "{strategy}: {s:?} leaves the layout at {p:?}"
                );
            }
        }
    }
}

#[test]
fn no_two_stems_are_closer_than_their_broadness_except_at_a_joint() {
    for strategy in ["BFS", "DFS"] {
        let g = geometry(&grown(strategy));
        let segs = &g.segments;
        let mut joints = 0;
        let mut closest = f64::INFINITY;
        for i in 0..segs.len() {
            for j in 0..i {
                let (s, t) = (&segs[i], &segs[j]);
                let need = (s.width + t.width) / 2.0;
                let pairs = [(s.a, t.a), (s.a, t.b), (s.b, t.a), (s.b, t.b)];
                let d = if let Some(k) = pairs.iter().position(|&(p, q)| same(p, q)) {
                    joints += 1;
                    // At a joint, each stem's free end keeps clear of the other.
                    let sf = if k < 2 { s.b } else { s.a };
                    let tf = if k % 2 == 0 { t.b } else { t.a };
                    point_seg(sf, t.a, t.b).min(point_seg(tf, s.a, s.b))
                } else {
                    // No crossing (checked by the endpoint distances being
                    // positive and the segments not intersecting).
                    let cross = |o: [f64; 3], p: [f64; 3], q: [f64; 3]| {
                        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
                    };
                    let x = cross(s.a, s.b, t.a) * cross(s.a, s.b, t.b) < 0.0
                        && cross(t.a, t.b, s.a) * cross(t.a, t.b, s.b) < 0.0;
                    assert!(!x, "{strategy}: stems cross: {s:?} {t:?}");
                    point_seg(s.a, t.a, t.b)
                        .min(point_seg(s.b, t.a, t.b))
                        .min(point_seg(t.a, s.a, s.b))
                        .min(point_seg(t.b, s.a, s.b))
                };
                closest = closest.min(d - need);
                assert!(
                    d >= need - 1e-7,
                    "{strategy}: {s:?} and {t:?} are {d} apart, need {need}"
                );
            }
        }
        assert!(joints >= segs.len() - 1, "{strategy}: {joints} joints");
        // The constraint is active: some pair is close to the limit.
        assert!(closest < 1.0, "{strategy}: closest margin {closest}");
    }
}

#[test]
fn bfs_and_dfs_grow_different_trees_with_the_papers_bias() {
    let (bfs, dfs) = (grown("BFS"), grown("DFS"));
    let (gb, gd) = (geometry(&bfs), geometry(&dfs));
    assert_ne!(gb.segments, gd.segments);
    let (b, d) = (sides(&bfs), sides(&dfs));
    let ratio = |v: &[usize]| v[0] as f64 / v[1] as f64;
    // Table 2: under DFS the first-priority (right) branch dominates ...
    assert!(ratio(&d) > 1.5, "DFS sides {d:?}");
    // ... under BFS the two sides are balanced.
    assert!((ratio(&b) - 1.0).abs() < 0.15, "BFS sides {b:?}");
    // Measured on this outline: BFS 157 vs 149, DFS 156 vs 77.
    assert_eq!((b.clone(), d.clone()), (vec![157, 149], vec![156, 77]));
}

#[test]
fn growth_stops_at_the_resemblance_count_and_at_levels() {
    fn depth(sys: &System) -> usize {
        use graftal::ir::{BranchEntry, BranchTerm, SeedItem};
        fn d(t: &BranchTerm) -> usize {
            1 + t
                .entries
                .iter()
                .map(|e| match e {
                    BranchEntry::Term(c) => d(c),
                    _ => 0,
                })
                .max()
                .unwrap_or(0)
        }
        sys.structure
            .as_ref()
            .unwrap()
            .seed
            .iter()
            .map(|s| match s {
                SeedItem::Term(t) => d(t),
                _ => 0,
            })
            .max()
            .unwrap_or(0)
    }
    let big = "LAYOUT\n(clWhite) Ellipse (-5000, 0), 10000, 10000\nENDLAYOUT\n";
    let levels = stl::read_ok(&format!(
        "L = 10\nLEVELS 4\nR1 = [-F][+F]\nSEED\nF R1\nENDSEED\n{big}"
    ));
    assert_eq!(depth(&levels), 4);
    // At most the full binary tree of 4 levels over the trunk; a few
    // level-4 tips collide with their cousins.
    let n = geometry(&levels).segments.len();
    assert!((1 + 2 + 4 + 8 + 1..=1 + 2 + 4 + 8 + 16).contains(&n), "{n}");
    let counted = stl::read_ok(&format!(
        "L = 10\nR1 = [-F][+F]\nR2 = [I 3 R1]\nSEED\nF R2\nENDSEED\n{big}"
    ));
    assert_eq!(depth(&counted), 3);
    let default = stl::read_ok(&format!(
        "L = 10\nANGLE 20\nR1 = [-F][+F]\nSEED\nF R1\nENDSEED\n{big}"
    ));
    assert_eq!(depth(&default), 12);
}

#[test]
fn the_grown_bed_reads_back_to_the_same_stems() {
    for strategy in ["BFS", "DFS"] {
        let sys = grown(strategy);
        let bed = graftal::back::stl::write(&sys).unwrap();
        assert!(bed.contains("R1{") && bed.contains('~'), "{bed}");
        let back = stl::read_ok(&bed);
        let (a, b) = (geometry(&sys), geometry(&back));
        assert_eq!(a.segments.len(), b.segments.len());
        for (s, t) in a.segments.iter().zip(&b.segments) {
            assert!(
                same(s.a, t.a) && same(s.b, t.b) && s.width == t.width,
                "{s:?} {t:?}"
            );
        }
        // Written again, the BED is unchanged (a fixed point).
        assert_eq!(graftal::back::stl::write(&back).unwrap(), bed);
    }
}

#[test]
fn each_stl_problem_has_its_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/diagnostics");
    let cases: [(&str, &[&str]); 11] = [
        ("stl-unknown-rule.stl", &["E0501"]),
        ("stl-too-many-entries.stl", &["E0502"]),
        ("stl-no-branches.stl", &["E0503"]),
        ("stl-unterminated-seed.stl", &["E0504"]),
        ("stl-unterminated-layout.stl", &["E0504"]),
        ("stl-unknown-shape-colour.stl", &["E0505", "E0506", "E0506"]),
        ("stl-polygon-points.stl", &["E0507"]),
        ("stl-negative.stl", &["E0508", "E0508", "E0508", "E0508"]),
        ("stl-cycle.stl", &["E0509"]),
        ("stl-clamped.stl", &["W0501", "W0501"]),
        (
            "stl-many-errors.stl",
            &[
                "E0512", "E0003", "E0516", "E0003", "E0501", "E0516", "E0003", "E0511",
            ],
        ),
    ];
    for (name, expected) in cases {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let c = driver::compile(graftal::source::SourceFile::new(name, text));
        let got: Vec<&str> = c.diagnostics.iter().map(|d| d.code.0).collect();
        assert_eq!(got, expected, "{name}");
        for d in c.diagnostics.iter() {
            assert!(d.span.is_some() && d.help.is_some(), "{name}: {d:?}");
        }
    }
    // The warnings clamp: the tree still compiles, and its thinnest stems
    // are a tenth of B.
    let text = std::fs::read_to_string(dir.join("stl-clamped.stl")).unwrap();
    let c = driver::compile(graftal::source::SourceFile::new("c.stl", text));
    let g = geometry(c.system.as_ref().unwrap());
    let thinnest = g
        .segments
        .iter()
        .map(|s| s.width)
        .fold(f64::INFINITY, f64::min);
    assert!((thinnest - 0.8).abs() < 1e-12, "{thinnest}");
    let shortest = g
        .segments
        .iter()
        .map(|s| ((s.b[0] - s.a[0]).powi(2) + (s.b[1] - s.a[1]).powi(2)).sqrt())
        .fold(f64::INFINITY, f64::min);
    assert!((shortest - 4.0).abs() < 1e-9, "{shortest}");
}

#[test]
fn a_large_outline_grows_tens_of_thousands_of_stems_quickly() {
    // The tree reaches 120 levels of 10 units into a 3000-unit ellipse.
    let src = "ANGLE 25\nB = 1\nL = 10\nLEVELS 120\nR1 = [-F][+F][F]\nSEED\nF R1\nENDSEED\nLAYOUT\n(clGreen) Ellipse (-1500, 0), 3000, 3000\nENDLAYOUT\n";
    let t = std::time::Instant::now();
    let sys = stl::read_ok(src);
    let grow = t.elapsed();
    let n = geometry(&sys).segments.len();
    eprintln!(
        "grew {n} stems in {grow:?} ({:.0} stems/s)",
        n as f64 / grow.as_secs_f64()
    );
    assert!(n > 60_000, "{n} stems");
    // A scan of all stems per candidate would take minutes here; the grid
    // takes well under a second in release and a few in the test profile.
    assert!(grow.as_secs_f64() < 30.0, "{grow:?}");
}

#[test]
fn a_counted_rule_of_a_literal_string_grows_and_round_trips() {
    // `[I 3 X]` with X a string: growth uses X for at most 3 levels, and
    // the BED names X as a rule of its own (`Rc_unit`).
    let src = "L = 20\nRc = [I 3 [-F][+F]]\nSEED\nF Rc\nENDSEED\nLAYOUT\n(clWhite) Ellipse (-500, 0), 1000, 1000\nENDLAYOUT\n";
    let sys = stl::read_ok(src);
    let g = geometry(&sys);
    assert_eq!(g.segments.len(), 1 + 2 + 4 + 8);
    let bed = graftal::back::stl::write(&sys).unwrap();
    assert!(
        bed.contains("Rc_unit = [-F][+F]") && bed.contains("F Rc_unit{Rc_unit{Rc_unit{}"),
        "{bed}"
    );
    let back = geometry(&stl::read_ok(&bed));
    assert_eq!(back.segments, g.segments);
}
