//! `.gft` `graph { … }` blocks (docs/gft.md §13), Bekaert & Willems'
//! object-instancing graphs: every transform form lowered to the matrix of
//! the IR's constructors, every shape, alternatives, axioms with
//! transforms, the order of symbols; every diagnostic with its code and
//! exact span; the emitter's round trip (the stdlib's `std:bekaert/…`
//! entries, and graphs of every kind of value); `graftal fmt` on a graph.

use graftal::back::{self, Request};
use graftal::diagnostics::Diagnostics;
use graftal::driver::{self, compile, Compiled};
use graftal::format::{format, Outcome};
use graftal::ir::graph::{
    Affine, Alternative, Finish, GraphSymbol, Instance, InstancingGraph, Primitive, Shape,
    DEFAULT_SHAPE_COLOUR,
};
use graftal::ir::{Rgb, System};
use graftal::source::SourceFile;
use graftal::stdlib::{self, ENTRIES};
use std::ops::Range;

fn compiled(text: &str) -> Compiled {
    compile(SourceFile::new("t.gft", text))
}

/// The graph of a text that reads without any diagnostic.
fn graph(text: &str) -> InstancingGraph {
    let c = compiled(text);
    let d: Vec<String> = (c.diagnostics.iter())
        .map(|d| format!("{} {}", d.code, d.message))
        .collect();
    assert!(d.is_empty(), "{text}\n{d:#?}");
    c.system.unwrap().graph.expect("a graph")
}

/// The transforms of symbol `name`'s rule.
fn rule(g: &InstancingGraph, name: &str) -> Vec<Affine> {
    let s = g.find(name).unwrap();
    let rule = g.symbols[s].rule.as_ref().expect("a rule");
    rule.iter().map(|i| i.transform).collect()
}

fn same(a: &Affine, b: &Affine) -> bool {
    a.same_bits(b)
}

#[test]
fn every_transform_form_lowers_to_the_matrix_of_its_constructor() {
    let g = graph(
        "graph {
  transform h = scale 0.5
  transform t1 = translate (1, 0, 0) scale 0.5
  transform r = rotate y 30 translate (0, 1, 0)
  transform s2 = scale (1, 0.5, 2)
  transform k = shear x y 0.5
  transform m = matrix (0.5 0 0 1, 0 0.5 0 0, 0 0 0.5 0)
  transform both = t1 h
  axiom O
  O -> h(B) t1(B) r(B) s2(B) k(B) m(B) both(B) [rotate (1, 1, 0) 0.52rad](B)
       [rotate x 30deg](B) [translate (1/3, -0.5) scale 1/4](B) B [translate (0, 1, 0) scale 0.5](B)
       [rotate z -90 deg](B)
  geometry B = sphere (0, 0, 0) 1
}
",
    );
    let half = Affine::scale([0.5; 3]);
    let t1 = Affine::compose(&[Affine::translate([1.0, 0.0, 0.0]), half]);
    let y30 = Affine::rotate([0.0, 1.0, 0.0], 30f64.to_radians()).unwrap();
    let expected = [
        half,
        t1,
        Affine::compose(&[y30, Affine::translate([0.0, 1.0, 0.0])]),
        Affine::scale([1.0, 0.5, 2.0]),
        Affine::shear(0, 1, 0.5),
        Affine([
            [0.5, 0.0, 0.0, 1.0],
            [0.0, 0.5, 0.0, 0.0],
            [0.0, 0.0, 0.5, 0.0],
        ]),
        Affine::compose(&[t1, half]),
        Affine::rotate([1.0, 1.0, 0.0], 0.52).unwrap(),
        Affine::rotate([1.0, 0.0, 0.0], 30f64.to_radians()).unwrap(),
        Affine::compose(&[
            Affine::translate([1.0 / 3.0, -0.5, 0.0]),
            Affine::scale([0.25; 3]),
        ]),
        Affine::IDENTITY,
        Affine::compose(&[Affine::translate([0.0, 1.0, 0.0]), half]),
        Affine::rotate([0.0, 0.0, 1.0], (-90f64).to_radians()).unwrap(),
    ];
    let got = rule(&g, "O");
    assert_eq!(got.len(), expected.len());
    for (k, (a, b)) in got.iter().zip(&expected).enumerate() {
        assert!(same(a, b), "couple {k}: {a:?} against {b:?}");
    }
    // Right to left, as in mathematics: `t1` scales, then translates.
    assert_eq!(got[1].apply([2.0, 0.0, 0.0]), [2.0, 0.0, 0.0]);
    assert_eq!(got[1].apply([0.0, 0.0, 0.0]), [1.0, 0.0, 0.0]);
    // `rotate y 30 translate (0, 1, 0)` lifts, then turns about y.
    let lifted = got[2].apply([0.0, 0.0, 0.0]);
    assert!((lifted[1] - 1.0).abs() < 1e-15 && lifted[0].abs() < 1e-15);
    assert_eq!(got[4].apply([0.0, 2.0, 0.0]), [1.0, 2.0, 0.0]);
}

fn shape(primitive: Primitive, colour: Rgb, finish: Finish) -> Shape {
    Shape {
        primitive,
        colour,
        finish,
    }
}

#[test]
fn shapes_colours_finishes_and_alternatives_are_read() {
    let g = graph(
        "graph {
  axiom S
  S -> A
  geometry A = sphere (1, 2, 3) 0.5
  geometry A = box (0, 0) (1, 1, 1) #8b5a2b
  geometry A = cylinder (0, 0, 0) (0, 1, 0) 0.05 #6d4c41 specular 0.3 shininess 30
  geometry A = cone (0, 0, 0) (0, 2, 0) 0.5
  geometry A = cone (0, 0, 0) (0, 2, 0) 0.5 0.25 ambient 0.1 diffuse 0.9
  geometry A = disc (0, 0, 0) (0, 0, 1) 2
  geometry A = triangle (0, 0) (1, 0) (0, 1)
  geometry A = polygon (0, 0) (1, 0) (1, 1) (0, 1) #ffffff
  alternative A below 2 = sphere (0, 1, 0) 0.2 #2e7d32
  alternative A = disc (0, 1, 0) (0, 1, 0) 0.3 #2e7d32
}
",
    );
    let grey = DEFAULT_SHAPE_COLOUR;
    let plain = Finish::default();
    let shiny = Finish {
        specular: 0.3,
        shininess: 30.0,
        ..plain
    };
    let matte = Finish {
        ambient: 0.1,
        diffuse: 0.9,
        ..plain
    };
    let expected = vec![
        shape(
            Primitive::Sphere {
                centre: [1.0, 2.0, 3.0],
                radius: 0.5,
            },
            grey,
            plain,
        ),
        shape(
            Primitive::Box {
                min: [0.0; 3],
                max: [1.0; 3],
            },
            Rgb(0x8b, 0x5a, 0x2b),
            plain,
        ),
        shape(
            Primitive::Cylinder {
                base: [0.0; 3],
                top: [0.0, 1.0, 0.0],
                radius: 0.05,
            },
            Rgb(0x6d, 0x4c, 0x41),
            shiny,
        ),
        shape(
            Primitive::Cone {
                base: [0.0; 3],
                top: [0.0, 2.0, 0.0],
                base_radius: 0.5,
                top_radius: 0.0,
            },
            grey,
            plain,
        ),
        shape(
            Primitive::Cone {
                base: [0.0; 3],
                top: [0.0, 2.0, 0.0],
                base_radius: 0.5,
                top_radius: 0.25,
            },
            grey,
            matte,
        ),
        shape(
            Primitive::Disc {
                centre: [0.0; 3],
                normal: [0.0, 0.0, 1.0],
                radius: 2.0,
            },
            grey,
            plain,
        ),
        shape(
            Primitive::Triangle([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
            grey,
            plain,
        ),
        shape(
            Primitive::Polygon(vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ]),
            Rgb(255, 255, 255),
            plain,
        ),
    ];
    let a = &g.symbols[g.find("A").unwrap()];
    assert_eq!(a.geometry, expected);
    let leaf = Rgb(0x2e, 0x7d, 0x32);
    assert_eq!(
        a.alternative,
        Some(Alternative {
            shapes: vec![
                shape(
                    Primitive::Sphere {
                        centre: [0.0, 1.0, 0.0],
                        radius: 0.2
                    },
                    leaf,
                    plain
                ),
                shape(
                    Primitive::Disc {
                        centre: [0.0, 1.0, 0.0],
                        normal: [0.0, 1.0, 0.0],
                        radius: 0.3
                    },
                    leaf,
                    plain
                ),
            ],
            below_pixels: 2.0,
        })
    );
    assert!(a.rule.is_none(), "a symbol without a rule is a terminal");
    // Without `below`, an alternative is drawn below one pixel.
    let g = graph("graph {\n  axiom A\n  alternative A = sphere (0, 0, 0) 1\n}\n");
    assert_eq!(g.symbols[0].alternative.as_ref().unwrap().below_pixels, 1.0);
}

#[test]
fn an_axiom_places_its_couples_by_their_transforms() {
    let g = graph(
        "graph {
  transform h = scale 0.5
  axiom [translate (1, 0, 0)](A) h(B) B
  A -> h(A) [translate (0.5, 0, 0) h](A)
  geometry B = sphere (0, 0, 0) 1
}
",
    );
    let (a, b) = (g.find("A").unwrap(), g.find("B").unwrap());
    let axiom: Vec<(usize, Affine)> = g.axiom.iter().map(|i| (i.symbol, i.transform)).collect();
    assert_eq!(axiom.len(), 3);
    assert_eq!(axiom[0].0, a);
    assert!(same(&axiom[0].1, &Affine::translate([1.0, 0.0, 0.0])));
    assert_eq!((axiom[1].0, axiom[2].0), (b, b));
    assert!(same(&axiom[1].1, &Affine::scale([0.5; 3])));
    assert!(same(&axiom[2].1, &Affine::IDENTITY));
}

#[test]
fn symbols_are_numbered_by_the_lines_that_introduce_them() {
    let g = graph(
        "graph {
  axiom O
  symbol Z
  geometry B = sphere (0, 0, 0) 1
  O -> [scale 0.5](B) A
  A -> B [translate (1, 0, 0) scale 0.5](Z)
  geometry Z = box (0, 0, 0) (1, 1, 1)
}
",
    );
    let names: Vec<&str> = g.symbols.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Z", "B", "O", "A"]);
    // Backquoted names, and a rule with no couple (an empty successor).
    let g = graph("graph {\n  axiom `a b`\n  `a b` -> [scale 0.5](`a b`) E\n  E ->\n}\n");
    let names: Vec<&str> = g.symbols.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["a b", "E"]);
    assert_eq!(g.symbols[1].rule, Some(Vec::new()));
}

#[test]
fn a_long_rule_goes_on_on_lines_that_start_with_a_bracket() {
    let g = graph(
        "graph {\n  axiom A\n  A -> [scale 0.5](A)\n\n       [translate (1, 0, 0) scale 0.5](A) /* more */\n       [translate (0, 1, 0) scale 0.5](A)\n}\n",
    );
    assert_eq!(rule(&g, "A").len(), 3);
}

/// The span of the `nth` (from 0) occurrence of `needle` in `text`.
fn at(text: &str, needle: &str, nth: usize) -> Range<usize> {
    let start = text
        .match_indices(needle)
        .nth(nth)
        .unwrap_or_else(|| panic!("`{needle}` {nth} not in {text}"))
        .0;
    start..start + needle.len()
}

/// Each mistake: the text, the code it gives, where (a needle and which
/// occurrence, or an empty span at a byte), and the codes of all the
/// text's diagnostics in order.
#[test]
fn each_problem_has_its_code_and_exact_span() {
    struct Case {
        text: &'static str,
        code: &'static str,
        needle: &'static str,
        nth: usize,
        all: &'static [&'static str],
    }
    let case = |text, code, needle, nth, all| Case {
        text,
        code,
        needle,
        nth,
        all,
    };
    let cases = [
        // E0920: a malformed line of the block.
        case("graph {\n  axoim A\n  A -> [scale 0.5](A)\n}\n", "E0920", "axoim", 0, &["W0900", "E0920"]),
        case("graph {\n  axiom A\n  A B -> [scale 0.5](A)\n}\n", "E0920", "A B", 0, &["E0920"]),
        case("graph {\n  transform scale = scale 0.5\n  axiom A\n  A -> [scale 0.5](A)\n}\n", "E0920", "scale", 0, &["E0920"]),
        case("graph tree {\n  axiom A\n  A -> [scale 0.5](A)\n}\n", "E0920", "tree", 0, &["E0920"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  geometry B sphere (0, 0, 0) 1\n}\n", "E0920", "sphere", 0, &["E0920"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) 2\n}\n", "E0920", "2", 0, &["E0920"]),
        // E0921: an unknown transform.
        case("graph {\n  axiom A\n  A -> [scale 0.5 trnaslate (1, 0, 0)](A)\n}\n", "E0921", "trnaslate", 0, &["E0921"]),
        case("graph {\n  axiom A\n  A -> [0.5](A)\n}\n", "E0921", "0.5", 0, &["E0921"]),
        case("graph {\n  axiom A\n  A -> [zz scale 0.5](A)\n}\n", "E0921", "zz", 0, &["E0921"]),
        // E0922: a malformed number, point, angle or matrix.
        case("graph {\n  axiom A\n  A -> [translate (1, 0, 0, 2) scale 0.5](A)\n}\n", "E0922", ",", 2, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [rotate w 30 scale 0.5](A)\n}\n", "E0922", "w", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [scale (0.5, 0.5)](A)\n}\n", "E0922", "(0.5, 0.5)", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [shear x x 0.5 scale 0.5](A)\n}\n", "E0922", "x x", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [rotate (0, 0, 0) 30 scale 0.5](A)\n}\n", "E0922", "(0, 0, 0)", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [scale 1/0](A)\n}\n", "E0922", "1/0", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [matrix (0.5 0 0, 0 0.5 0 0, 0 0 0.5 0)](A)\n}\n", "E0922", ",", 0, &["E0922"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  alternative B below -1 = sphere (0, 0, 0) 1\n}\n", "E0922", "-1", 0, &["E0922"]),
        // E0923: a malformed shape.
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  geometry B = cube (0, 0, 0) 1\n}\n", "E0923", "cube", 0, &["E0923"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  geometry B = sphere (0, 0, 0) 1 #ff0000 glossy 2\n}\n", "E0923", "glossy", 0, &["E0923"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  geometry B = sphere (0, 0, 0) 1 specular 0.1 specular 0.2\n}\n", "E0923", "specular", 1, &["E0923"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  geometry B = box (0, 0, 0) 1\n}\n", "E0923", "1", 0, &["E0923"]),
        // E0924: a symbol no line introduces.
        case("graph {\n  transform h = scale 0.5\n  axiom Fern\n  Fern -> h(Fern) [translate (1, 0, 0) h](fern)\n}\n", "E0924", "fern", 0, &["E0924"]),
        // E0925: given twice.
        case("graph {\n  transform h = scale 0.5\n  axiom A\n  A -> h(A)\n  A -> [translate (1, 0, 0) h](A)\n}\n", "E0925", "A", 3, &["E0925"]),
        case("graph {\n  transform q = scale 0.5\n  transform q = scale 0.25\n  axiom A\n  A -> q(A)\n}\n", "E0925", "q", 1, &["E0925"]),
        case("graph {\n  axiom A\n  axiom A\n  A -> [scale 0.5](A)\n}\n", "E0925", "axiom A", 1, &["E0925"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) B\n  alternative B below 2 = sphere (0, 0, 0) 1\n  alternative B below 3 = sphere (0, 1, 0) 1\n}\n", "E0925", "3", 0, &["E0925"]),
        // E0926: an unknown transform name.
        case("graph {\n  transform half = scale 0.5\n  axiom A\n  A -> half(A) hlaf(A)\n}\n", "E0926", "hlaf", 0, &["E0926"]),
        case("graph {\n  transform a = b\n  transform b = scale 0.5\n  axiom A\n  A -> a(A)\n}\n", "E0926", "b", 0, &["E0926"]),
        // The graph's own checks.
        case("graph {\n  axiom A\n  A -> [scale 0.5](B)\n  B -> [translate (1, 0, 0) scale 2.5](A)\n}\n", "E1001", "[scale 0.5](B)", 0, &["E1001"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) [translate (1, 0, 0) scale 0.5](B) C\n  geometry C = sphere (0, 0, 0) 0.2\n}\n", "E1002", "B", 0, &["E1002"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) [translate (1, 0, 0) scale (0.5, 0.5, 0)](A)\n}\n", "W1003", "[translate (1, 0, 0) scale (0.5, 0.5, 0)]", 0, &["W1003"]),
        case("graph {\n  axiom A\n  A -> [scale 0.5](A) [translate (1, 0, 0) scale 0.5](A)\n  B -> [scale 0.5](B)\n}\n", "W1004", "B", 0, &["W1004"]),
        case("graph {\n  A -> [scale 0.5](A)\n}\n", "W0900", "graph", 0, &["W0900"]),
    ];
    let mut failures = Vec::new();
    for c in cases {
        let compiled = compiled(c.text);
        let codes: Vec<&str> = compiled.diagnostics.iter().map(|d| d.code.0).collect();
        let d = compiled.diagnostics.iter().find(|d| d.code.0 == c.code);
        let want = at(c.text, c.needle, c.nth);
        let span = d.and_then(|d| d.span.clone());
        if codes != c.all || span != Some(want.clone()) {
            failures.push(format!(
                "{:?}\n  expected {} at {want:?} ({:?}) of {:?}\n  got {codes:?}, span {span:?}",
                c.text, c.code, c.needle, c.all
            ));
        }
        if let Some(d) = d {
            if d.code.0.starts_with('E') && d.help.is_none() {
                failures.push(format!("{:?}: {} has no help", c.text, c.code));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn mistakes_suggest_the_nearest_word_or_name() {
    let help = |text: &str, code: &str| {
        let c = compiled(text);
        let d = c.diagnostics.iter().find(|d| d.code.0 == code);
        d.and_then(|d| d.help.clone())
            .unwrap_or_else(|| panic!("no {code}"))
    };
    let g = |body: &str| format!("graph {{\n  transform half = scale 0.5\n{body}\n}}\n");
    assert_eq!(
        help(&g("  axoim A\n  A -> half(A)"), "E0920"),
        "did you mean `axiom`?"
    );
    assert_eq!(
        help(&g("  axiom A\n  A -> [scal 0.5](A)"), "E0921"),
        "did you mean `scale`?"
    );
    assert_eq!(
        help(&g("  axiom A\n  A -> hlaf(A)"), "E0926"),
        "did you mean `half`?"
    );
    assert_eq!(
        help(&g("  axiom A\n  A -> half(A) half(a)"), "E0924"),
        "did you mean `A`?"
    );
    assert_eq!(
        help(
            &g("  axiom A\n  A -> half(A) B\n  geometry B = shpere (0, 0, 0) 1"),
            "E0923"
        ),
        "did you mean `sphere`?"
    );
}

#[test]
fn a_cycle_of_two_symbols_that_stretches_is_named_with_its_factor() {
    let text =
        "graph {\n  axiom A\n  A -> [scale 0.5](B)\n  B -> [translate (1, 0, 0) scale 2.5](A)\n}\n";
    let c = compiled(text);
    let d: Vec<_> = c.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(
        d[0].message,
        "the cycle `A -> B -> A` does not shrink: it stretches by 1.25"
    );
    assert_eq!(d[0].span, Some(at(text, "[scale 0.5](B)", 0)));
    assert!(d[0].help.as_deref().unwrap().contains("below 1"));
    assert!(c.system.is_none(), "an error");
    // Shrunk below 1, it is the graph's limit object.
    let shrunk = text.replace("2.5", "1.5");
    assert!(compiled(&shrunk).diagnostics.is_empty());
    // A cycle that keeps its size (a rotation) does not converge either.
    let turning = "graph {\n  axiom A\n  A -> [rotate z 90](A)\n}\n";
    let c = compiled(turning);
    assert_eq!(c.diagnostics.iter().next().unwrap().code.0, "E1001");
    assert!(c
        .diagnostics
        .iter()
        .next()
        .unwrap()
        .message
        .contains("factor 1"));
}

#[test]
fn a_singular_transform_is_a_warning_that_says_it_is_thickened() {
    let c = compiled("graph {\n  axiom A\n  A -> [scale 0.5](A) [matrix (0 0 0 0.5, 0 0.16 0 0, 0 0 0 0)](A)\n}\n");
    let d: Vec<_> = c.diagnostics.iter().collect();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0].code.0, "W1003");
    assert!(d[0].notes.iter().any(|n| n.contains("1/1000")), "{d:#?}");
    assert!(c.system.is_some(), "a warning");
}

#[test]
fn a_graph_and_the_files_other_items_live_side_by_side() {
    let c = compiled(
        "view 30 20\nbackground #000000\ncolours #c0803a\nangle 90\naxiom F\nF -> F+F\ngraph {\n  axiom A\n  A -> [scale 0.5](A) [translate (1, 0, 0) scale 0.5](A)\n}\n",
    );
    assert!(c.diagnostics.is_empty(), "{:#?}", c.diagnostics);
    let sys = c.system.unwrap();
    assert_eq!(
        sys.settings.view.map(|v| v.0.to_degrees().round()),
        Some(30.0)
    );
    assert_eq!(sys.look.background, Some(Rgb(0, 0, 0)));
    assert_eq!(sys.productions.len(), 1);
    assert_eq!(sys.graph.unwrap().symbols.len(), 1);
    // A file of a graph alone needs no top-level axiom; a second graph
    // is a setting given twice.
    assert!(compiled("graph {\n  axiom A\n  A -> [scale 0.5](A)\n}\n")
        .diagnostics
        .is_empty());
    let twice = "graph {\n  axiom A\n  A -> [scale 0.5](A)\n}\ngraph {\n  axiom A\n  A -> [scale 0.5](A)\n}\n";
    let codes: Vec<&str> = compiled(twice)
        .diagnostics
        .iter()
        .map(|d| d.code.0)
        .collect();
    assert_eq!(codes, ["E0905"]);
}

/// The `.gft` text of `sys`, read back: the same system, without an error.
fn round_trip(sys: &System) -> Result<String, String> {
    let text = back::gft::write(sys, None);
    let mut diags = Diagnostics::default();
    let again = graftal::front::gft::read(&text, &mut diags);
    if diags.has_errors() {
        let d: Vec<String> = diags
            .iter()
            .map(|d| format!("{} {}", d.code, d.message))
            .collect();
        return Err(format!("{text}\n{d:#?}"));
    }
    again
        .system
        .same_as(sys)
        .map_err(|e| format!("{text}\n{e}"))?;
    Ok(text)
}

#[test]
fn every_bekaert_entry_reads_cleanly_and_translates_back_to_itself() {
    let entries: Vec<_> = ENTRIES
        .iter()
        .filter(|e| e.name.starts_with("bekaert/"))
        .collect();
    let names: Vec<&str> = entries.iter().map(|e| e.name).collect();
    assert_eq!(
        names,
        [
            "bekaert/fern",
            "bekaert/menger",
            "bekaert/temple",
            "bekaert/tetrahedron",
            "bekaert/tree"
        ]
    );
    for e in entries {
        let c = driver::compile(driver::load(&format!("std:{}", e.name)).unwrap());
        assert!(c.diagnostics.is_empty(), "{}: {:#?}", e.name, c.diagnostics);
        let sys = c.system.as_ref().unwrap();
        assert!(sys.graph.is_some(), "{}", e.name);
        assert!(sys.settings.view.is_some(), "{} has a view", e.name);
        assert!(e.file.ends_with(".gft"));
        assert!(e.text.contains("prints no"), "{}", e.name);
        let fig = e.figure();
        assert!(
            fig.contains("Fig.") || fig.contains('§'),
            "{}: {fig}",
            e.name
        );
        let req = Request {
            target: back::by_name("gft").unwrap(),
            lossy: false,
            steps: None,
        };
        let t = driver::translate(&c, sys, &req);
        let text = t.text.expect("gft never refuses");
        let mut diags = Diagnostics::default();
        let again = graftal::front::gft::read(&text, &mut diags);
        assert!(diags.is_empty(), "{}:\n{text}\n{diags:#?}", e.name);
        again
            .system
            .same_as(sys)
            .unwrap_or_else(|d| panic!("{}: {d}\n{text}", e.name));
        // The translation is in the canonical layout.
        match format(SourceFile::new("t.gft", text.as_str())).outcome {
            Outcome::Formatted(f) => assert_eq!(f, text, "{}", e.name),
            _ => panic!("{}: not formatted", e.name),
        }
    }
}

#[test]
fn the_bekaert_entries_are_designed_to_the_papers_descriptions() {
    let g = |name: &str| {
        let c = driver::compile(driver::load(&format!("std:bekaert/{name}")).unwrap());
        c.system.unwrap().graph.unwrap()
    };
    let transforms = |g: &InstancingGraph| {
        let edges = g.symbols.iter().flat_map(|s| s.rule.iter().flatten());
        edges
            .filter(|i| !i.transform.same_bits(&Affine::IDENTITY))
            .count()
    };
    // Sierpinski: 4 maps of scale 1/2, no geometry.
    let t = g("tetrahedron");
    assert_eq!((t.symbols.len(), transforms(&t)), (1, 4));
    assert!(rule(&t, "T")
        .iter()
        .all(|a| (a.contraction() - 0.5).abs() < 1e-12));
    assert!(!t.has_geometry());
    // Menger: 20 maps of scale 1/3, no geometry.
    let m = g("menger");
    assert_eq!((m.symbols.len(), transforms(&m)), (1, 20));
    assert!(rule(&m, "M")
        .iter()
        .all(|a| (a.contraction() - 1.0 / 3.0).abs() < 1e-12));
    assert!(!m.has_geometry());
    // Fern: a HIFS of 6 transforms in 3 levels, no geometry.
    let f = g("fern");
    assert_eq!((f.symbols.len(), transforms(&f)), (3, 6));
    assert!(!f.has_geometry());
    // Temple: a CIFS of 4 transforms and a composite condensation set.
    let t = g("temple");
    assert_eq!(transforms(&t), 4);
    let b = &t.symbols[t.find("B").unwrap()];
    assert!(b.rule.is_none() && b.geometry.len() >= 5);
    // Tree: 3 levels, 4 transforms, a branch and a leaf as alternative.
    let t = g("tree");
    assert_eq!((t.symbols.len(), transforms(&t)), (3, 4));
    let b = &t.symbols[t.find("B").unwrap()];
    assert!(b.rule.is_none());
    assert!(matches!(
        b.geometry[0].primitive,
        Primitive::Cone { .. } | Primitive::Cylinder { .. }
    ));
    let leaf = b.alternative.as_ref().expect("a leaf");
    assert!(leaf.shapes[0].colour.1 > leaf.shapes[0].colour.0, "green");
}

/// Expanded to the pixel of a 1024x1024 picture (the object's volume
/// 1024 pixels across), the trees hold at least 10^9 primitive instances.
#[test]
fn the_trees_hold_a_billion_instances_at_1024_pixels() {
    let c = driver::compile(driver::load("std:bekaert/tree").unwrap());
    let g = c.system.unwrap().graph.unwrap();
    let bounds = graftal::raytrace::bounds::Bounds::of(&g).unwrap();
    let axiom = &g.axiom[0];
    let size = bounds.volumes[axiom.symbol].unwrap().size() * axiom.transform.contraction();
    let n = graftal::raytrace::graph::count_instances(&g, &bounds, size / 1024.0);
    assert!(n >= 1_000_000_000, "{n}");
}

/// A graph with every kind of value the emitter must write exactly:
/// transforms it writes in steps and ones it writes as matrices, `-0`,
/// angles no decimal of degrees gives back, names to backquote, a
/// terminal with nothing of its own, an empty rule, every shape.
#[test]
fn graphs_of_every_kind_of_value_are_written_back_exactly() {
    let mut sys = System::new();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut random = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let contractive = |random: &mut dyn FnMut() -> f64| {
        let mut a = Affine([[0.0; 4]; 3]);
        for row in a.0.iter_mut() {
            for v in row.iter_mut() {
                *v = random();
            }
        }
        let k = 0.5 / a.norm_bound();
        for row in a.0.iter_mut() {
            for v in row[..3].iter_mut() {
                *v *= k;
            }
        }
        a
    };
    let mut edges = vec![
        Affine::scale([0.5; 3]),
        Affine::compose(&[Affine::translate([0.1, 0.0, 3.0]), Affine::scale([0.25; 3])]),
        Affine::compose(&[
            Affine::rotate([0.0, 0.0, 1.0], 1.0).unwrap(),
            Affine::scale([0.3; 3]),
        ]),
        Affine::compose(&[
            Affine::translate([0.0, 1.0, 0.0]),
            Affine::rotate([0.0, 1.0, 0.0], 137.5f64.to_radians()).unwrap(),
            Affine::rotate([0.0, 0.0, 1.0], 12f64.to_radians()).unwrap(),
            Affine::scale([0.78; 3]),
        ]),
        Affine::scale([0.5, -0.25, 0.125]),
        Affine([
            [-0.0, 0.1, 0.0, 1.0],
            [0.2, 0.0, 0.0, -0.0],
            [0.0, 0.0, 0.3, 0.0],
        ]),
    ];
    for _ in 0..8 {
        edges.push(contractive(&mut random));
    }
    let couples = |edges: &[Affine], symbol: usize| {
        edges
            .iter()
            .map(|&transform| Instance { transform, symbol })
            .collect::<Vec<_>>()
    };
    let leaf = Shape {
        primitive: Primitive::Disc {
            centre: [0.0, 1.0, -0.0],
            normal: [0.0, 1.0, 0.0],
            radius: 0.3,
        },
        colour: Rgb(46, 125, 50),
        finish: Finish {
            ambient: 0.1,
            diffuse: 0.7,
            specular: 0.25,
            shininess: 7.5,
        },
    };
    let shapes = vec![
        Shape {
            primitive: Primitive::Cone {
                base: [0.0; 3],
                top: [0.0, 1.0, 0.0],
                base_radius: 0.1,
                top_radius: -0.0,
            },
            colour: DEFAULT_SHAPE_COLOUR,
            finish: Finish::default(),
        },
        Shape {
            primitive: Primitive::Polygon(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.5, 0.8, 0.1]]),
            colour: Rgb(1, 2, 3),
            finish: Finish::default(),
        },
        Shape {
            primitive: Primitive::Triangle([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.1, 0.2]]),
            colour: Rgb(1, 2, 3),
            finish: Finish::default(),
        },
    ];
    let mut rule = couples(&edges, 0);
    rule.extend(couples(&[Affine::IDENTITY, Affine::scale([0.5; 3])], 1));
    sys.graph = Some(InstancingGraph {
        symbols: vec![
            GraphSymbol {
                name: "tree".into(),
                geometry: shapes,
                alternative: None,
                rule: Some(rule),
            },
            GraphSymbol {
                name: "leaf 1".into(),
                geometry: Vec::new(),
                alternative: Some(Alternative {
                    shapes: vec![leaf.clone(), leaf],
                    below_pixels: 2.5,
                }),
                rule: None,
            },
            GraphSymbol {
                name: "Empty".into(),
                geometry: Vec::new(),
                alternative: None,
                rule: Some(Vec::new()),
            },
        ],
        axiom: vec![
            Instance {
                transform: Affine::translate([-1.0, 0.0, 0.0]),
                symbol: 0,
            },
            Instance {
                transform: Affine::IDENTITY,
                symbol: 2,
            },
        ],
    });
    let text = round_trip(&sys).unwrap();
    for written in [
        "[scale 0.5](tree)",
        "[translate (0.1, 0, 3) scale 0.25](tree)",
        "`leaf 1`\n          [scale 0.5](`leaf 1`)",
        "[scale (0.5, -0.25, 0.125)](tree)",
        "[matrix (-0 0.1 0 1, 0.2 0 0 -0, 0 0 0.3 0)](tree)",
        "  Empty ->\n",
        "  alternative `leaf 1` below 2.5 = disc (0, 1, -0) (0, 1, 0) 0.3 #2e7d32 ambient 0.1 diffuse 0.7 specular 0.25 shininess 7.5\n",
        "  alternative `leaf 1` = disc",
        "geometry tree = cone (0, 0, 0) (0, 1, 0) 0.1 -0\n",
    ] {
        assert!(text.contains(written), "`{written}` not in\n{text}");
    }
    // A long rule goes on on lines that start with `[`.
    assert!(
        text.lines()
            .any(|l| l.starts_with("     ") && l.trim_start().starts_with('[')),
        "{text}"
    );
    // A terminal with nothing of its own, in a graph without geometry, is
    // declared with `symbol`.
    let mut pure = System::new();
    pure.graph = Some(InstancingGraph {
        symbols: vec![
            GraphSymbol {
                name: "A".into(),
                geometry: Vec::new(),
                alternative: None,
                rule: Some(vec![
                    Instance {
                        transform: Affine::scale([0.5; 3]),
                        symbol: 0,
                    },
                    Instance {
                        transform: Affine::translate([1.0, 0.0, 0.0]),
                        symbol: 1,
                    },
                ]),
            },
            GraphSymbol {
                name: "X".into(),
                geometry: Vec::new(),
                alternative: None,
                rule: None,
            },
        ],
        axiom: vec![Instance {
            transform: Affine::IDENTITY,
            symbol: 0,
        }],
    });
    let text = round_trip(&pure).unwrap();
    assert!(text.contains("  symbol X\n"), "{text}");
}

#[test]
fn fmt_keeps_the_comments_of_a_graph_and_formats_once() {
    let text = "/* Sierpinski */\nview 30 20\ngraph {\n  /* the axiom */\n  axiom T\n  /* four corners */\n  T -> [translate (0.5, 0.5, 0.5) scale 0.5](T) [translate (0.5, -0.5, -0.5) scale 0.5](T) /* two */\n  geometry L = sphere (0, 0, 0) 1 /* unused */\n}\n";
    let formatted = match format(SourceFile::new("t.gft", text)).outcome {
        Outcome::Formatted(f) => f,
        _ => panic!("not formatted"),
    };
    for kept in [
        "/* Sierpinski */\nview 30 20\n",
        "  /* the axiom */\n  axiom T\n",
        "  /* four corners */\n  T -> ",
        "(T) /* two */\n",
        "geometry L = sphere (0, 0, 0) 1 /* unused */\n",
    ] {
        assert!(formatted.contains(kept), "`{kept}` not in\n{formatted}");
    }
    match format(SourceFile::new("t.gft", formatted.as_str())).outcome {
        Outcome::Formatted(again) => assert_eq!(again, formatted),
        _ => panic!("not formatted again"),
    }
}

#[test]
fn the_collection_folder_names_its_entries() {
    let e = stdlib::get("bekaert/tree").expect("std:bekaert/tree");
    assert_eq!(e.file, "std:bekaert/tree.gft");
    assert_eq!(e.kind(), stdlib::Kind::Drawing);
    assert_eq!(e.figure(), "Fig. 9");
    assert!(stdlib::get("gft/bekaert/tree").is_none());
    assert!(stdlib::get("bekaert/tree.gft").is_some());
}

#[test]
fn a_graph_is_refused_by_every_other_notation() {
    let c = driver::compile(driver::load("std:bekaert/fern").unwrap());
    let sys = c.system.as_ref().unwrap();
    for to in ["pfg", "linf", "stl"] {
        for lossy in [false, true] {
            let req = Request {
                target: back::by_name(to).unwrap(),
                lossy,
                steps: None,
            };
            let t = driver::translate(&c, sys, &req);
            assert!(t.text.is_none(), "{to}");
            let codes: Vec<&str> = t.diagnostics.iter().map(|d| d.code.0).collect();
            assert_eq!(codes, ["E0616"], "{to}");
        }
    }
}
