//! Words into geometry: the turtle run over a derived word (through the
//! system's homomorphism where it has one), within the limit on moves;
//! query modules answered with what the turtle finds; an STL layout's
//! shapes added under the tree.

use super::derive::{derive_values, RunOptions};
use crate::diagnostics::{codes, Diagnostic};
use crate::eval;
use crate::eval::parametric::Globals;
use crate::eval::tree::{Tree, MAX_TREE_DEPTH};
use crate::ir::{System, TurtleOp, Word};
use crate::turtle::{self, Geometry};

/// The most turtle moves a word may have to be interpreted: each becomes a
/// segment or a point kept in memory (about 64 bytes, and as much again to
/// draw it), so 30 million stay within a few GB.
pub const MAX_MOVES: usize = 30_000_000;

/// Interprets `word`, refusing words whose geometry would not fit in memory
/// ([`MAX_MOVES`]), in pieces on the threads `opts` asks for
/// ([`turtle::Pieces`]). With `paths`, the turtle's paths are recorded too
/// (by one turtle). A
/// system whose rewriting needs modules draws its word through its
/// homomorphism, which reads the program's globals and arrays as `values`
/// holds them ([`derive_values`]).
pub fn interpret(
    sys: &System,
    word: &Word,
    values: &Globals,
    opts: &RunOptions,
    paths: bool,
) -> Result<Geometry, Diagnostic> {
    let drawn = drawn_word(sys, word, values, opts)?;
    if paths {
        // Paths are recorded branch by branch, by one turtle.
        let run = turtle::Run::word(sys, &drawn, opts.seed);
        return Ok(turtle::Run { paths, ..run }.geometry());
    }
    let params = drawn.has_params().then_some(&*drawn);
    let pieces = turtle::Pieces::plan(sys, &drawn.0[..], params, opts.seed, opts.threads);
    let mut g = turtle::pieces::geometry(&pieces, opts.threads);
    g.world_widths = sys.settings.world_widths;
    Ok(g)
}

/// The word the turtle draws for `word`: itself, or what the system's
/// homomorphism makes of it (reading the program's globals and arrays as
/// `values` holds them); refused when its geometry would not fit in
/// memory ([`MAX_MOVES`]).
pub(super) fn drawn_word<'w>(
    sys: &System,
    word: &'w Word,
    values: &Globals,
    opts: &RunOptions,
) -> Result<std::borrow::Cow<'w, Word>, Diagnostic> {
    if sys.rewrites_modules() {
        let dopts = opts.derive_options(sys);
        let (drawn, _) = eval::parametric::homomorphism(sys, word, values, &dopts)?;
        let moves = turtle::drawn_cost(sys, &drawn);
        if moves > opts.max_moves as u64 {
            return Err(too_much_geometry(moves, opts.max_moves).with_note(
                "each triangle of a surface and face of a generalized cylinder counts as a move",
            ));
        }
        return Ok(std::borrow::Cow::Owned(drawn));
    }
    let moves = turtle::drawn_cost(sys, word);
    if moves > opts.max_moves as u64 {
        return Err(too_much_geometry(moves, opts.max_moves)
            .with_note(format!("the derived word has {} symbols", word.len())));
    }
    Ok(std::borrow::Cow::Borrowed(word))
}

/// Fills the query modules (`?P`, `?H`, …) of `word` with what the turtle
/// finds there, drawing the word through the homomorphism.
/// With `environment`, the `?E` modules met are the environment's
/// queries, and its answers are written back too ([`super::environment`]).
pub(super) fn answer_queries(
    sys: &System,
    word: &mut Word,
    values: &Globals,
    opts: &RunOptions,
    environment: Option<&mut dyn crate::enviro::Pass>,
) {
    let dopts = opts.derive_options(sys);
    let Ok((drawn, origins)) = eval::parametric::homomorphism(sys, word, values, &dopts) else {
        return;
    };
    let run = turtle::Run {
        queries: true,
        ..turtle::Run::word(sys, &drawn, opts.seed)
    };
    let mut asked = super::environment::Asked::default();
    let env = sys.environment.as_ref().filter(|_| environment.is_some());
    // `interpretation past %: off`: the queries of a cut branch are not sent.
    let cut = (env.filter(|e| !e.past_cut).zip(sys.cut))
        .map(|(_, c)| eval::parametric::cut_mask(&drawn.0, c))
        .unwrap_or_default();
    for (i, v) in turtle::run(run, &mut Geometry::default()).answers {
        // Only a query module the homomorphism kept writes back.
        let Some(&o) = origins.get(i) else { continue };
        let o = o as usize;
        let kept = word.0.get(o) == drawn.0.get(i);
        if is_environment_query(sys, drawn.0[i]) {
            if let Some(env) = env.filter(|_| !cut.get(i).copied().unwrap_or(false)) {
                asked.push(env, kept.then_some(o), drawn.args(i), v);
            }
        } else if kept {
            word.set_args(o, &v);
        }
    }
    if let Some(program) = environment {
        asked.answer(program, word);
    }
}

/// Whether the turtle leaves the picture's plane, so that turning the view
/// shows more: a symbol of the axiom or of a successor rolls or pitches
/// (a rotation about H or L, or back to vertical), tropisms bend it, or
/// the system is a 3D instancing graph.
pub fn turns_in_space(sys: &System) -> bool {
    let leaves_plane = |&s: &crate::ir::SymbolId| {
        matches!(
            sys.op(s),
            Some(
                TurtleOp::Rotate {
                    axis: crate::ir::Axis::Heading | crate::ir::Axis::Left,
                    ..
                } | TurtleOp::RollToVertical
            )
        )
    };
    let mut written = sys.axiom.0.iter().chain(
        (sys.every_production())
            .flat_map(|p| p.alternatives.iter().flat_map(|a| a.successor.0.iter())),
    );
    written.any(leaves_plane)
        || !sys.settings.tropisms.is_empty()
        || sys.graph.as_ref().is_some_and(|g| !g.is_planar())
}

/// Whether `s` is a `?E` module, which the environment answers.
pub(super) fn is_environment_query(sys: &System, s: crate::ir::SymbolId) -> bool {
    sys.op(s) == Some(TurtleOp::Query(crate::ir::QueryKind::Environment))
}

/// Derives and interprets: the geometry of the system, with its look's
/// scene ([`add_fixed`]).
pub fn geometry(sys: &System, opts: &RunOptions) -> Result<(Word, Geometry), Diagnostic> {
    let (word, values) = derive_values(sys, opts, |_, _| {})?;
    let mut g = interpret(sys, &word, &values, opts, false)?;
    add_fixed(sys, &mut g, false);
    Ok((word, g))
}

/// What is drawn beside the turtle's geometry, added to `g`: the look's
/// scene (cpfg's background scenes, drawn after the model as cpfg draws
/// them), and with `layout` an STL system's layout ([`add_layout`]).
pub fn add_fixed(sys: &System, g: &mut Geometry, layout: bool) {
    if layout {
        add_layout(sys, g);
    }
    let scene = sys.look.scene.iter().map(|p| turtle::Polygon {
        points: p.points.clone(),
        colour: p.colour,
        index: p.index,
        surface: false,
        texture: None,
    });
    g.polygons.extend(scene);
}

/// Adds an STL system's layout shapes to `g` as filled polygons drawn
/// first, so the tree is drawn over them (PNG and SVG draw polygons before
/// segments). Systems without a layout are left as they are.
pub fn add_layout(sys: &System, g: &mut Geometry) {
    let Some(st) = &sys.structure else { return };
    let shapes: Vec<turtle::Polygon> = st
        .constraint
        .outline
        .iter()
        .map(|s| turtle::Polygon {
            points: crate::layout::shapes::outline(s)
                .into_iter()
                .map(|p| [p[0], p[1], 0.0])
                .collect(),
            colour: crate::layout::shapes::colour(s),
            index: 0,
            surface: false,
            texture: None,
        })
        .filter(|p| p.points.len() >= 3)
        .collect();
    g.polygons.splice(0..0, shapes);
}

/// Refuses, before deriving, to draw a system whose word would move the
/// turtle more than [`RunOptions::max_moves`] times when it must be drawn
/// segment by segment: counted on the shared derivation tree of a
/// context-free deterministic system, and bounded from below for the
/// others ([`eval::fewest_at`]: the fewest moves any choices can make).
pub(super) fn check_moves_up_front(sys: &System, opts: &RunOptions) -> Result<(), Diagnostic> {
    let steps = opts.derive_options(sys).steps;
    let is_move = |s: crate::ir::SymbolId| {
        u128::from(matches!(
            sys.op(s),
            Some(TurtleOp::Forward { .. } | TurtleOp::ForwardReal { .. })
        ))
    };
    let max = opts.max_moves as u128;
    if let Some(t) = (steps <= MAX_TREE_DEPTH).then(|| Tree::new(sys)).flatten() {
        let moves: Vec<u128> = (0..sys.symbols.len() as u32)
            .map(|i| is_move(crate::ir::SymbolId(i)))
            .collect();
        let Err(step) = t.weighed(steps, &moves, max) else {
            return Ok(());
        };
        // How many, exactly, when that is quick to add up.
        let many = t.count(steps, &moves);
        let many = many.map_or_else(|| format!("more than {max}"), |c| c.short());
        return Err(too_much_geometry(many, opts.max_moves).with_note(format!(
            "known before deriving: the word of step {step} of {steps} already moves it more than {max} times"
        )));
    }
    // A homomorphism decides what draws: the word's own moves tell nothing.
    if !sys.homomorphism.productions.is_empty() {
        return Ok(());
    }
    let refused = match eval::fewest_at(sys, steps, is_move, u128::from(u64::MAX)) {
        Some(fewest) if fewest > max => {
            too_much_geometry(format!("at least {fewest}"), opts.max_moves).with_note(
                "known before deriving: whatever the contexts, conditions and random choices",
            )
        }
        _ => return Ok(()),
    };
    // A context-free system is drawn from its shared subtrees, without this
    // limit, up to the depth of its tree: beyond, the limit is why not.
    Err(match crate::ir::D0l::of(sys) {
        Some(_) if steps > MAX_TREE_DEPTH => refused.with_note(format!(
            "pictures of more than {MAX_TREE_DEPTH} steps are drawn segment by segment, not from shared subtrees"
        )),
        _ => refused,
    })
}

fn too_much_geometry(moves: impl std::fmt::Display, max: usize) -> Diagnostic {
    Diagnostic::global(
        codes::TOO_MUCH_GEOMETRY,
        format!("the word moves the turtle {moves} times, more than can be drawn segment by segment ({max})"),
    )
    .with_help("draw fewer steps with `-n`; `derive` and `stats` have no such limit")
}
/// Whether an STL layout would draw an outline under the system's picture.
pub(super) fn has_outline(sys: &System) -> bool {
    sys.structure
        .as_ref()
        .is_some_and(|st| !st.constraint.outline.is_empty())
}
