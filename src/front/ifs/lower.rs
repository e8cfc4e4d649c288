//! Lowering one IFS entry to the IR: an object-instancing graph of one
//! symbol `A` and one rule `A -> w1(A) … wn(A)` (Bekaert & Willems §2.3.1),
//! axiom `A`, no geometry, with Fractint's checks and the attractor's.
//!
//! A 2D map `a b c d e f` is `x' = a x + b y + e`, `y' = c x + d y + f`:
//! it keeps the plane z = 0 and scales z by its largest singular value
//! ([`Affine::planar`]), so that it shrinks as much in space as in the
//! plane. A 3D map `a b c d e f g h i j k l` is `x' = a x + b y + c z + j`,
//! `y' = d x + e y + f z + k`, `z' = g x + h y + i z + l`. The last number
//! of a map is its probability in Fractint's chaos game: graftal draws
//! every map, so probabilities are checked (W1101) and not kept.

use super::ast::{Entry, Line, Number};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::graph::{stretch_2d, Affine, GraphSymbol, Instance, InstancingGraph};
use crate::ir::{Lowered, Span, SpanTable, System};

/// The most maps Fractint 19.6 reads in an entry (`NUMIFS`).
pub const MAX_MAPS: usize = 64;

/// Numbers of a 2D map and of a 3D one.
pub const NUMBERS_2D: usize = 7;
pub const NUMBERS_3D: usize = 13;

/// How far from 1 the probabilities may add up to.
const PROBABILITY_SLACK: f64 = 0.01;

/// The name of the graph's one symbol.
pub const SYMBOL: &str = "A";

/// One map of an entry.
struct Map<'e> {
    transform: Affine,
    /// The most it stretches a length (its largest singular value).
    stretch: f64,
    probability: &'e Number,
    /// From the first number to the last of its linear part.
    linear: Span,
}

/// Whether the text between an entry's name and its `{` marks it 3D
/// (Fractint: `(3d)` anywhere on the line, in any case).
pub fn is_3d(src: &str, e: &Entry) -> bool {
    e.header
        .as_ref()
        .and_then(|h| src.get(h.clone()))
        .is_some_and(|h| h.to_ascii_lowercase().contains("(3d)"))
}

/// Lowers the entry `e` of the library `src` into a system whose graph is
/// its IFS.
pub fn lower_entry(src: &str, e: &Entry, diags: &mut Diagnostics) -> Lowered {
    lowered(lower_graph(src, e, diags))
}

/// The system of an IFS's graph.
pub fn lowered(graph: InstancingGraph) -> Lowered {
    let mut system = System::new();
    system.graph = Some(graph);
    Lowered {
        system,
        spans: SpanTable::default(),
    }
}

/// The IFS of the entry `e` of the library `src`, with its checks: what
/// [`lower_entry`] makes a system of (a library checks every entry, and
/// makes a system of the one chosen).
pub fn lower_graph(src: &str, e: &Entry, diags: &mut Diagnostics) -> InstancingGraph {
    let three_d = is_3d(src, e);
    let mut maps = Vec::new();
    let mut bad_lines = false;
    for line in &e.lines {
        if line.broken {
            bad_lines = true;
            continue;
        }
        match map(line, three_d) {
            Ok(m) => maps.push(m),
            Err(d) => {
                bad_lines = true;
                diags.push(d);
            }
        }
    }
    if maps.is_empty() && !bad_lines {
        diags.push(
            Diagnostic::at(
                codes::IFS_EMPTY_ENTRY,
                e.name_span.clone(),
                format!("the entry `{}` has no maps", e.name),
            )
            .with_label("an IFS of no maps has no attractor")
            .with_help(if three_d {
                "write one map a line: `a b c d e f g h i j k l p`"
            } else {
                "write one map a line: `a b c d e f p`"
            }),
        );
    }
    if let Some(extra) = maps.get(MAX_MAPS) {
        diags.push(
            Diagnostic::at(
                codes::IFS_TOO_MANY_MAPS,
                extra.linear.start..extra.probability.span.end,
                format!("the entry `{}` has {} maps", e.name, maps.len()),
            )
            .with_label(format!("map {} of at most {MAX_MAPS}", MAX_MAPS + 1))
            .with_help("Fractint reads at most 64 maps an entry: split the IFS or merge maps"),
        );
    }
    if !bad_lines && !maps.is_empty() {
        probabilities(e, &maps, diags);
    }
    // The cycles of the graph are its loops, one a map: each must shrink,
    // as `InstancingGraph::divergent_cycles` says (at its threshold), found
    // here in closed form for a 2D map (a library may hold thousands).
    for (k, m) in maps.iter().enumerate() {
        let stretch = m.stretch;
        if !(stretch.is_nan() || stretch >= 1.0 - 1e-12) {
            continue;
        }
        let factor = if stretch.is_finite() {
            crate::number::readable(stretch)
        } else {
            "more than floating point holds".into()
        };
        diags.push(
            Diagnostic::at(
                codes::IFS_NOT_CONTRACTIVE,
                maps[k].linear.clone(),
                format!("map {} does not shrink: the IFS has no attractor", k + 1),
            )
            .with_label(format!("stretches some direction by {factor}"))
            .with_help(
                "every map of an IFS must shrink every direction (its largest singular value \
                 below 1): scale its matrix down",
            ),
        );
    }
    graph(&maps)
}

/// The graph of the maps: one symbol, its rule every map.
fn graph(maps: &[Map<'_>]) -> InstancingGraph {
    let rule = maps
        .iter()
        .map(|m| Instance {
            transform: m.transform,
            symbol: 0,
        })
        .collect();
    InstancingGraph {
        symbols: vec![GraphSymbol {
            name: SYMBOL.into(),
            geometry: Vec::new(),
            alternative: None,
            rule: Some(rule),
        }],
        axiom: vec![Instance {
            transform: Affine::IDENTITY,
            symbol: 0,
        }],
    }
}

/// The map of a line of numbers, or E1104 for a line of the wrong length.
fn map(line: &Line, three_d: bool) -> Result<Map<'_>, Diagnostic> {
    let n = &line.numbers;
    let v = |k: usize| n[k].value;
    match (three_d, n.len()) {
        (false, NUMBERS_2D) => Ok(Map {
            transform: Affine::planar([[v(0), v(1), v(4)], [v(2), v(3), v(5)]]),
            stretch: stretch_2d(v(0), v(1), v(2), v(3)),
            probability: &n[6],
            linear: n[0].span.start..n[3].span.end,
        }),
        (true, NUMBERS_3D) => {
            let transform = Affine([
                [v(0), v(1), v(2), v(9)],
                [v(3), v(4), v(5), v(10)],
                [v(6), v(7), v(8), v(11)],
            ]);
            Ok(Map {
                transform,
                stretch: transform.contraction(),
                probability: &n[12],
                linear: n[0].span.start..n[8].span.end,
            })
        }
        (_, count) => Err(wrong_count(line, three_d, count)),
    }
}

/// E1104 for a line of `count` numbers.
fn wrong_count(line: &Line, three_d: bool, count: usize) -> Diagnostic {
    let expected = if three_d { NUMBERS_3D } else { NUMBERS_2D };
    let d = Diagnostic::at(
        codes::IFS_NUMBER_COUNT,
        line.span.clone(),
        format!("a map of {count} numbers: {expected} expected"),
    );
    match (three_d, count) {
        (false, NUMBERS_3D) => d
            .with_label("13 numbers: a 3D map, in an entry not marked `(3D)`")
            .with_help("mark the entry 3D after its name: `Name (3D) {`"),
        (true, NUMBERS_2D) => d
            .with_label("7 numbers: a 2D map, in an entry marked `(3D)`")
            .with_help(
                "a 3D map is `a b c d e f g h i j k l p`; drop `(3D)` if every map is 2D",
            ),
        (false, _) => d
            .with_label("a 2D map is `a b c d e f p`")
            .with_help(if count == NUMBERS_2D - 1 {
                "is its probability, the last number, missing?"
            } else {
                "write one map a line: x' = a x + b y + e, y' = c x + d y + f, and p its probability"
            }),
        (true, _) => d
            .with_label("a 3D map is `a b c d e f g h i j k l p`")
            .with_help(if count == NUMBERS_3D - 1 {
                "is its probability, the last number, missing?"
            } else {
                "write one map a line: x' = a x + b y + c z + j, y' = d x + e y + f z + k, \
                 z' = g x + h y + i z + l, and p its probability"
            }),
    }
}

/// W1101: a probability below 0, a probability 0 (Fractint never applies
/// that map nor the ones after it), or probabilities that do not add up
/// to 1.
fn probabilities(e: &Entry, maps: &[Map<'_>], diags: &mut Diagnostics) {
    for (k, m) in maps.iter().enumerate() {
        let p = m.probability;
        let label = if p.value < 0.0 {
            "a negative probability"
        } else if p.value == 0.0 {
            "Fractint's chaos game never applies this map, nor any after it"
        } else {
            continue;
        };
        diags.push(
            Diagnostic::at(
                codes::IFS_PROBABILITIES,
                p.span.clone(),
                format!(
                    "map {} has the probability {}",
                    k + 1,
                    crate::number::readable(p.value)
                ),
            )
            .with_label(label)
            .with_help("graftal draws every map; give it a probability above 0 for Fractint"),
        );
        return;
    }
    let sum: f64 = maps.iter().map(|m| m.probability.value).sum();
    if (sum - 1.0).abs() > PROBABILITY_SLACK {
        diags.push(
            Diagnostic::at(
                codes::IFS_PROBABILITIES,
                e.name_span.clone(),
                format!(
                    "the probabilities of `{}` add up to {}, not 1",
                    e.name,
                    crate::number::readable(sum)
                ),
            )
            .with_label("its maps' last numbers")
            .with_help(
                "scale them to add up to 1: Fractint's chaos game picks maps by them; graftal \
                 draws every map whatever they are",
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::ifs::parser::parse;

    fn lowered(src: &str) -> (Option<InstancingGraph>, Vec<&'static str>) {
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        let l = lower_entry(src, &f.entries[0], &mut d);
        (l.system.graph, d.iter().map(|d| d.code.0).collect())
    }

    #[test]
    fn a_2d_map_keeps_the_plane_and_shrinks_as_much_in_space() {
        let (g, codes) = lowered("t {\n .5 0 0 .25 1 2 .5\n 0 -.5 .5 0 0 0 .5\n}\n");
        assert!(codes.is_empty(), "{codes:?}");
        let g = g.unwrap();
        assert!(g.is_planar());
        let rule = g.symbols[0].rule.as_ref().unwrap();
        assert_eq!(
            rule[0].transform.0,
            [
                [0.5, 0.0, 0.0, 1.0],
                [0.0, 0.25, 0.0, 2.0],
                [0.0, 0.0, 0.5, 0.0]
            ]
        );
        assert!((rule[1].transform.contraction() - 0.5).abs() < 1e-12);
        assert_eq!(g.axiom.len(), 1);
        assert!(!g.has_geometry());
    }

    #[test]
    fn a_3d_map_reads_rows_then_the_translation() {
        let src = "t (3d) {\n 1 2 3 4 5 6 7 8 9 10 11 12 1\n}\n";
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        let l = lower_entry(src, &f.entries[0], &mut d);
        let g = l.system.graph.unwrap();
        assert_eq!(
            g.symbols[0].rule.as_ref().unwrap()[0].transform.0,
            [
                [1.0, 2.0, 3.0, 10.0],
                [4.0, 5.0, 6.0, 11.0],
                [7.0, 8.0, 9.0, 12.0]
            ]
        );
        // It stretches: no attractor.
        assert_eq!(d.iter().map(|d| d.code.0).collect::<Vec<_>>(), ["E1106"]);
        assert_eq!(&src[d.0[0].span.clone().unwrap()], "1 2 3 4 5 6 7 8 9");
    }

    #[test]
    fn checks_of_counts_probabilities_and_emptiness() {
        assert_eq!(lowered("t {\n.5 0 0 .5 0 0\n}").1, ["E1104"]);
        assert_eq!(lowered("t {\n.5 0 0 0 .5 0 0 0 .5 0 0 0 1\n}").1, ["E1104"]);
        assert_eq!(lowered("t (3D) {\n.5 0 0 .5 0 0 1\n}").1, ["E1104"]);
        assert_eq!(lowered("t {\n.5 0 0 .5 0 0 .5\n}").1, ["W1101"]);
        assert_eq!(
            lowered("t {\n.5 0 0 .5 0 0 0\n.5 0 0 .5 1 0 1\n}").1,
            ["W1101"]
        );
        assert_eq!(lowered("t {\n}").1, ["E1105"]);
        assert_eq!(lowered("t {\n1 0 0 .5 0 0 1\n}").1, ["E1106"]);
        let many = format!("t {{\n{}}}", ".1 0 0 .1 0 0 .01\n".repeat(65));
        assert_eq!(lowered(&many).1, ["E1107", "W1101"]);
    }
}
