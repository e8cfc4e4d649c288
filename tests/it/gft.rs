//! The `.gft` front end (docs/gft.md): each construct read from a small
//! file, derived, and compared with the same model in the notation it
//! comes from; every diagnostic code with its span; every error of a file
//! in one run.

use graftal::diagnostics::codes;
use graftal::driver::{self, compile, Compiled, RunOptions};
use graftal::ir::{Angle, RulePolicy, TurtleOp};
use graftal::source::SourceFile;

fn compiled(name: &str, text: &str) -> Compiled {
    compile(SourceFile::new(name.to_string(), text))
}

/// The word `text` (a file called `name`) derives in `steps` steps.
fn word(name: &str, text: &str, steps: u64) -> String {
    let c = compiled(name, text);
    assert!(!c.diagnostics.has_errors(), "{name}: {:#?}", c.diagnostics);
    let sys = c.system.expect("a system");
    let opts = RunOptions {
        steps: Some(steps),
        ..RunOptions::default()
    };
    let w = driver::derive(&sys, &opts).expect("derives");
    c.front.word_text(&sys, &w)
}

fn corpus(name: &str) -> String {
    let path = format!("{}/tests/corpus/gft/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).expect("corpus file")
}

/// The codes of the diagnostics of a `.gft` text, in order.
fn codes_of(text: &str) -> Vec<&'static str> {
    compiled("t.gft", text)
        .diagnostics
        .iter()
        .map(|d| d.code.0)
        .collect()
}

#[test]
fn the_koch_island_fits_in_five_lines_and_derives_as_in_pfg() {
    let gft = corpus("koch-island.gft");
    assert!(gft.lines().count() <= 5);
    let pfg = "angle factor: 4\naxiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\n";
    assert_eq!(word("k.gft", &gft, 2), word("k.l", pfg, 2));
    let gft_sys = compiled("k.gft", &gft).system.unwrap();
    let pfg_sys = compiled("k.l", pfg).system.unwrap();
    assert_eq!(gft_sys.settings.delta, pfg_sys.settings.delta);
    assert_eq!(gft_sys.settings.steps, Some(2));
}

#[test]
fn a_parametric_tree_derives_as_in_cpfg() {
    let cpfg =
        "lsystem: 1\naxiom: A(1)\nA(x) : x < 10 --> F(x) [+(30) A(x*0.7)] A(x+1)\nendlsystem\n";
    assert_eq!(word("t.gft", &corpus("tree.gft"), 6), word("t.l", cpfg, 6));
}

#[test]
fn continuation_alternatives_are_one_stochastic_production() {
    let gft =
        "angle 360/14\naxiom F\nF -> F[+F]F[-F]F : 0.33\n  -> F[+F]F : 0.33\n  -> F[-F]F : 0.34\n";
    let sys = compiled("b.gft", gft).system.unwrap();
    let weights: Vec<f64> = sys.productions[0]
        .alternatives
        .iter()
        .map(|a| a.weight)
        .collect();
    assert_eq!(
        (sys.productions.len(), weights),
        (1, vec![0.33, 0.33, 0.34])
    );
    let pfg = "angle factor: 14\naxiom: F\nF --> F[+F]F[-F]F : 0.33\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.34\n";
    assert_eq!(word("b.gft", gft, 4), word("b.l", pfg, 4));
}

#[test]
fn contexts_with_ignored_symbols_derive_as_in_pfg() {
    let gft = corpus("signal.gft");
    let body: String = gft
        .lines()
        .filter(|l| l.contains("->"))
        .map(|l| l.replace("->", "-->") + "\n")
        .collect();
    let pfg = format!("angle factor: 16\nignore: +-F\naxiom: F1F1F1\n{body}");
    for n in 0..8 {
        assert_eq!(word("s.gft", &gft, n), word("s.l", &pfg, n), "step {n}");
    }
}

#[test]
fn frenet_rotations_intervals_and_guards_read_as_in_linf() {
    let gft = corpus("frenet.gft");
    let linf =
        "lines f\nangles t = (0, pi/3) w = (0, [0 2*pi])\naxiom f\nrules\n  f = f+t-t[0.5?f]+w\n";
    for n in 0..5 {
        assert_eq!(word("f.gft", &gft, n), word("f.linf", linf, n), "step {n}");
    }
    let sys = compiled("f.gft", &gft).system.unwrap();
    assert_eq!(
        sys.rotations[1].curvature,
        Angle::Uniform {
            lo: 0.0,
            hi: std::f64::consts::TAU
        }
    );
    let minus_t = sys.symbols.get("-t").unwrap();
    assert!(matches!(
        sys.op(minus_t),
        Some(TurtleOp::Frenet { negate: true, .. })
    ));
    assert!(sys.symbols.get("0.5?f").is_some());
}

#[test]
fn fractint_commands_take_their_numbers() {
    let gft = corpus("fractint.gft");
    let fractint = "X {\n  Angle 8\n  Axiom FX\n  X=C12F+X-C3F\n}\n";
    assert_eq!(word("x.gft", &gft, 3), word("x.l", fractint, 3));
    let sys = compiled("x.gft", &gft).system.unwrap();
    assert_eq!(sys.colours.len(), 256);
    let c12 = sys.symbols.get("c12").unwrap();
    assert_eq!(sys.op(c12), Some(TurtleOp::SetColour(12)));
}

#[test]
fn programs_and_phases_derive_as_in_cpfg() {
    let gft = "turtle cpfg\nsteps 3\naxiom A\nA -> AB\ndecomposition depth 2 {\nB -> F\n}\nhomomorphism {\nA -> +F\n}\n";
    let cpfg = "lsystem: 1\naxiom: A\nA --> AB\ndecomposition\nmaximum depth: 2\nB --> F\nhomomorphism\nA --> +F\nendlsystem\n";
    assert_eq!(word("d.gft", gft, 3), word("d.l", cpfg, 3));
    let sys = compiled("d.gft", gft).system.unwrap();
    assert_eq!(
        (sys.decomposition.depth, sys.homomorphism.productions.len()),
        (2, 1)
    );
    // Globals and the blocks around the derivation: `n` counts the steps.
    assert_eq!(word("p.gft", &corpus("program.gft"), 4), "AFF");
}

#[test]
fn statements_conditions_and_policy_reach_the_ir() {
    let gft = "turtle cpfg\nchoose weighted\nseed 7\nring\ncut %\naxiom A(1)\nA(x) : { y = x * 2; } y < 8 -> A(y)\n";
    let sys = compiled("c.gft", gft).system.unwrap();
    let p = &sys.productions[0];
    assert_eq!(
        (p.before.len(), p.condition.is_some(), p.formals.locals),
        (1, true, 2)
    );
    assert_eq!(sys.policy, RulePolicy::Weighted);
    assert_eq!(sys.settings.seed, Some(7));
    assert!(sys.ring && sys.cut == sys.symbols.get("%"));
    assert_eq!(word("c.gft", gft, 3), "A(4)");
}

#[test]
fn definitions_override_the_turtle_set_and_declare_long_names() {
    let gft = "symbol Apex\nG = move\nX = nothing\nF = turn 30deg\naxiom ApexGXF\n";
    let sys = compiled("n.gft", gft).system.unwrap();
    assert_eq!(sys.axiom.len(), 4);
    let op = |n: &str| sys.op(sys.symbols.get(n).unwrap());
    assert_eq!(op("G"), Some(TurtleOp::Forward { draw: false }));
    assert_eq!(op("X"), None);
    assert!(
        matches!(op("F"), Some(TurtleOp::Rotate { angle: Angle::Radians(a), .. }) if (a - 30f64.to_radians()).abs() < 1e-15)
    );
    assert_eq!(op("Apex"), None);
}

#[test]
fn arrays_and_globals_are_declared_wherever_they_are_written() {
    let gft = "turtle cpfg\naxiom A(0)\nA(i) : i < 3 -> F(lengths[i] + n) A(i+1)\narray lengths[3] = 1, 2.5, -3\nglobals n\nstart { n = 10; }\n";
    assert_eq!(word("a.gft", gft, 3), "F(11)F(12.5)F(7)A(3)");
    assert_eq!(codes_of("array a[1][2] = 1, 2, 3\naxiom F\n"), ["E0903"]);
}

#[test]
fn silent_symbols_act_without_a_name() {
    let gft = "silent s1 = stem 8 40\naxiom `s1`F\n";
    let sys = compiled("s.gft", gft).system.unwrap();
    let s1 = sys.symbols.get("s1").unwrap();
    assert_eq!(sys.symbols.name(s1), "");
    assert_eq!(sys.axiom.symbols(), [s1, sys.symbols.get("F").unwrap()]);
    assert_eq!(
        sys.op(s1),
        Some(TurtleOp::Stem {
            width: 8.0,
            length: 40.0
        })
    );
    assert_eq!(word("s.gft", gft, 0), "F");
}

#[test]
fn each_problem_has_its_code_and_exact_span() {
    let cases: &[(&str, &str, std::ops::Range<usize>)] = &[
        ("axoim F\naxiom F\n", "E0900", 0..5),
        ("axiom F\n[F]\n", "E0901", 8..11),
        ("X = forwrd\naxiom X\n", "E0902", 4..10),
        ("steps ten\naxiom F\n", "E0903", 0..9),
        ("axiom F]\n", "W0901", 7..8),
        ("angle 90\nangle 60\naxiom F\n", "E0905", 9..14),
        ("axiom A(1)\nA(x) -> F(y)\n", "W0902", 21..22),
        ("axiom A(1)\nA(x) -> F(sin(x, 2))\n", "E0907", 21..30),
        ("axiom A\nA(1) -> B\n", "E0907", 10..11),
    ];
    for (text, code, span) in cases {
        let c = compiled("t.gft", text);
        let d: Vec<_> = c.diagnostics.iter().collect();
        assert_eq!(d.len(), 1, "{text:?}: {d:#?}");
        assert_eq!(
            (d[0].code.0, d[0].span.clone()),
            (*code, Some(span.clone())),
            "{text:?}"
        );
    }
    assert_eq!(codes_of("F -> F+F\n"), ["W0900"]);
}

#[test]
fn unknown_keywords_and_operations_suggest_the_nearest() {
    let c = compiled("t.gft", "axiom F\nwidht 2\nX = forwrd\n");
    let helps: Vec<String> = c
        .diagnostics
        .iter()
        .filter_map(|d| d.help.clone())
        .collect();
    assert_eq!(helps, ["did you mean `width`?", "did you mean `forward`?"]);
}

#[test]
fn every_error_of_a_file_in_one_run() {
    let text = "axoim F\nangle 90\nangle 60\nF -> F[+F\nX = forwrd\nturtle lsys\nA(x) -> F(y)\nsteps ten\n";
    assert_eq!(
        codes_of(text),
        ["E0900", "E0905", "W0901", "E0902", "E0902", "W0902", "E0903", "W0900"]
    );
}

#[test]
fn junk_never_panics() {
    let pieces = [
        "->",
        "(",
        ")",
        "{",
        "}",
        "[",
        "]",
        ":",
        "<",
        ">",
        "?",
        "`",
        "\"",
        "/*",
        "=",
        "axiom",
        "start",
        "decomposition",
        "turtle",
        "rotation",
        "1e999",
        "-",
        "F",
        "\n",
        " ",
        ",",
        ";",
    ];
    let mut state = 12345u64;
    for _ in 0..500 {
        let mut text = String::new();
        for _ in 0..40 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            text.push_str(pieces[(state >> 33) as usize % pieces.len()]);
        }
        let c = compiled("j.gft", &text);
        if let (Some(sys), false) = (&c.system, c.diagnostics.has_errors()) {
            let opts = RunOptions {
                steps: Some(3),
                ..RunOptions::default()
            };
            let _ = driver::derive(sys, &opts);
        }
    }
    let _ = codes::GFT_UNKNOWN_KEYWORD;
}

#[test]
fn a_file_without_a_turtle_line_draws_with_pfgs_turtle() {
    let c = compiled("k.gft", "steps 1\nangle 90\naxiom F+F\n");
    let sys = c.system.expect("a system");
    let f = sys.symbols.get("F").unwrap();
    assert_eq!(sys.op(f), Some(TurtleOp::Forward { draw: true }));
    let (_, g) = driver::geometry(&sys, &RunOptions::default()).unwrap();
    assert_eq!(g.segments.len(), 2);
}

#[test]
fn a_declared_name_written_without_spaces_is_one_module() {
    let text = "rotation b = (0, 1)\n+b = frenet b\naxiom F+bF[+bF]\n";
    let c = compiled("b.gft", text);
    assert!(!c.diagnostics.has_errors(), "{:#?}", c.diagnostics);
    let sys = c.system.expect("a system");
    let word = driver::derive(&sys, &RunOptions::default()).unwrap();
    let b = sys.symbols.get("+b").unwrap();
    assert_eq!(word.symbols().iter().filter(|&&s| s == b).count(), 2);
    assert!(sys.symbols.get("b").is_none(), "no stray `b`");
}

/// `text` (a file called `name`) read, written as `.gft`, and read back:
/// the `.gft` text and the system read from it, checked the same as the
/// source's.
fn through_gft(name: &str, text: &str) -> (String, graftal::ir::System) {
    let c = compiled(name, text);
    assert!(!c.diagnostics.has_errors(), "{name}: {:#?}", c.diagnostics);
    let sys = c.system.expect("a system");
    let gft = graftal::back::gft::write(&sys, None);
    let back = compiled("back.gft", &gft);
    assert!(
        !back.diagnostics.has_errors(),
        "{gft}\n{:#?}",
        back.diagnostics
    );
    let back = back.system.expect("a system");
    if let Err(e) = sys.same_as(&back) {
        panic!("{name}: {e}\n{gft}");
    }
    (gft, back)
}

fn stdlib(path: &str) -> String {
    let path = format!("{}/stdlib/{path}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).expect("stdlib file")
}

#[test]
fn an_outline_is_written_planted_and_grown_when_read() {
    for (file, strategy) in [
        ("stl/fig09-outline-bfs.stl", "breadth-first"),
        ("stl/fig10-outline-dfs.stl", "depth-first"),
        ("stl/fig07-layout.stl", ""),
    ] {
        let (gft, back) = through_gft(file, &stdlib(file));
        assert!(gft.contains(&format!("growth {strategy}")), "{gft}");
        let st = back.structure.as_ref().expect("a structure");
        if !st.planted.is_empty() {
            // The seed is written as planted (a growth point is a bare
            // rule name), and reading it grew the same tree.
            let seed = gft.lines().find(|l| l.starts_with("seed ")).unwrap();
            assert!(seed.len() < 40, "{seed}");
            assert!(st.seed.len() == st.planted.len() && st.seed != st.planted);
        }
        // The same stems as STL draws.
        let opts = RunOptions::default();
        let stl = compiled(file, &stdlib(file)).system.unwrap();
        let a = driver::derive(&stl, &opts).unwrap();
        let b = driver::derive(&back, &opts).unwrap();
        assert_eq!(a.display(&stl.symbols), b.display(&back.symbols), "{file}");
    }
}

#[test]
fn a_branch_expansion_seed_is_expanded_into_the_axiom() {
    let file = "stl/fig03-koch-curve.stl";
    let (gft, back) = through_gft(file, &stdlib(file));
    assert!(!gft.contains("\naxiom "), "{gft}");
    assert!(gft.contains("\nseed "), "{gft}");
    assert!(!back.axiom.is_empty());
    let gft = "rule R1 = [+F][-F]\nstems broadness 2 1 length 10 2\nseed F R1{R1{}, ~}\ngrowth breadth-first levels 3\n";
    let sys = graftal::front::gft::read_ok(gft);
    let names: Vec<&str> = (sys.axiom.symbols().iter())
        .map(|&s| sys.symbols.name(s))
        .collect();
    // Level markers are silent (empty names); the failed branch is gone.
    assert_eq!(names.concat(), "F[+F[+F][-F]]");
    let k2 = sys.symbols.get("stl-level-2").unwrap();
    // B = 2 - 2·1 is not positive: a tenth of the first value, as STL.
    assert_eq!(
        sys.op(k2),
        Some(TurtleOp::Stem {
            width: 0.2,
            length: 6.0
        })
    );
}

#[test]
fn the_look_functions_tropisms_and_their_operations_are_read() {
    let text = "axiom A B C D\n\
        A = query heading\nB = colour-shift -3\nC = elasticity increase tropism 2\nD = surface ~l\n\
        function leaf = 0 0.25 1\n\
        tropism (0, -1, 0) angle 0 intensity 1 elasticity 0.25 step 0.1 torque\n\
        background #102030\n\
        camera eye (0, 0, 10) target (0, 0, 0) up (0, 1, 0) perspective 45\n\
        lighting flat line-style cylinder index-shift 10 surface-ambient 0.15 surface-diffuse 0.75\n\
        light (0, 0, 1) directional ambient (0.1, 0.2, 0.3) diffuse (1, 1, 1) specular (1, 1, 1)\n\
        material 2 ambient (0.1, 0.1, 0.1) diffuse (0.7, 0.2, 0) specular (0, 0, 0) emission (0, 0, 0) shininess 20 transparency 0.5\n\
        surface ~l {\n  (0, 0, 0) (1, 0, 0) (0, 1, 0)\n}\n\
        contour 1 cross-section closed length 1 {\n  (1, 0, 0) (0, 1, 0)\n}\n";
    let sys = graftal::front::gft::read_ok(text);
    let op = |n: &str| sys.op(sys.symbols.get(n).unwrap());
    use graftal::ir::{ElasticityChange, QueryKind};
    assert_eq!(op("A"), Some(TurtleOp::Query(QueryKind::Heading)));
    assert_eq!(op("B"), Some(TurtleOp::ShiftColour { by: 3, up: false }));
    assert_eq!(
        op("C"),
        Some(TurtleOp::Elasticity {
            tropism: Some(1),
            change: ElasticityChange::Increase
        })
    );
    assert_eq!(op("D"), Some(TurtleOp::Surface(0)));
    assert_eq!(sys.program.functions[0].samples, [0.0, 0.25, 1.0]);
    assert_eq!(sys.settings.tropisms[0].step, 0.1);
    let look = &sys.look;
    assert_eq!(look.background, Some(graftal::ir::Rgb(0x10, 0x20, 0x30)));
    assert_eq!(look.camera.unwrap().perspective, Some(45.0));
    let lighting = look.lighting.as_ref().unwrap();
    // f32 fields read as f32: 0.1 is the f32 nearest 0.1.
    assert_eq!(lighting.lights[0].ambient, [0.1f32, 0.2, 0.3]);
    assert!(lighting.materials[..2].iter().all(Option::is_none));
    assert_eq!(lighting.materials[2].unwrap().transparency, 0.5);
    assert_eq!(sys.surfaces[0].triangles.len(), 1);
    assert_eq!(sys.contours[0].points.len(), 2);
    // And what is read is written back the same.
    through_gft("t.gft", text);
}

#[test]
fn a_declared_name_of_several_tokens_is_found_in_a_spaced_word() {
    let sys = graftal::front::gft::read_ok(
        "rotation a = (0, 1)\n+a = frenet a\nX = forward\naxiom X [ +a X ] +aX\n",
    );
    let names: Vec<&str> = (sys.axiom.symbols().iter())
        .map(|&s| sys.symbols.name(s))
        .collect();
    assert_eq!(names, ["X", "[", "+a", "X", "]", "+a", "X"]);
}

/// A misspelt turtle set, rotation or symbol name gets the nearest
/// declared one as its help (a misspelt setting: the test above).
#[test]
fn misspelt_declared_names_suggest_the_nearest() {
    let cases = [
        ("turtle lnif\naxiom F\n", "E0902", "did you mean `linf`?"),
        (
            "turtle linf\nrotation leaf = (0, pi/18)\nX = frenet lef\naxiom FX\n",
            "E0906",
            "did you mean `leaf`?",
        ),
        ("symbol apex\naxiom apx\n", "W0903", "did you mean `apex`?"),
    ];
    for (text, code, help) in cases {
        let c = compiled("t.gft", text);
        let d: Vec<_> = c.diagnostics.iter().collect();
        assert_eq!(d.len(), 1, "{text:?}: {d:#?}");
        assert_eq!((d[0].code.0, d[0].help.as_deref()), (code, Some(help)));
    }
    // Letters no declared name is near, and a declared name, are no warning.
    assert!(codes_of("symbol apex\naxiom FFF apex\n").is_empty());
}
