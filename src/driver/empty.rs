//! The warnings for a picture that shows nothing, or nearly nothing, with
//! the likely cause.

use super::derive::RunOptions;
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::{System, TurtleOp, Word};
use crate::render::axes::{principal_spreads, view_along, world_points};
use crate::render::{self, RenderOptions, View};
use crate::stdlib;
use crate::turtle::{self, Geometry};

/// The warning for a picture with nothing in it, naming the likely cause
/// ([`why_nothing_drawn`]). When the file's own `diagnostics` say the
/// model waits on an environment that never answers (W0821), the warning
/// says that this is why.
pub fn nothing_drawn(
    sys: &System,
    word: &Word,
    file: &str,
    opts: &RunOptions,
    diagnostics: &Diagnostics,
) -> Diagnostic {
    let mut d = Diagnostic::global(
        codes::NOTHING_DRAWN,
        "nothing is drawn: the picture is empty",
    )
    .with_note(format!(
        "the derived word has {} symbols and none of them draws",
        word.len()
    ));
    match diagnostics
        .iter()
        .find(|d| d.code == codes::CPFG_NO_ENVIRONMENT)
    {
        Some(env) => {
            d = d.with_note(
                "the model draws only what its environment answers to `?E`, \
                 and no environment program graftal runs answers them (W0821)",
            );
            d.notes.extend(env.notes.iter().cloned());
        }
        None => {
            let steps = opts.derive_options(sys).steps;
            if let Some(why) = why_nothing_drawn(sys, word, file, steps) {
                d = d.with_note(why);
            }
        }
    }
    d
}

/// The likely cause of an empty picture, checked in this order: a stdlib
/// schema (its source prints words, not a picture); a word whose turtle
/// only moves without drawing (`f`: a kolam, drawn with `--spline`); a
/// word with no symbol that moves the turtle at all (a string example);
/// no derivation steps, so only the axiom was drawn.
pub fn why_nothing_drawn(sys: &System, word: &Word, file: &str, steps: u64) -> Option<String> {
    if let Some(e) = stdlib::by_file(file).filter(|e| e.kind() == stdlib::Kind::Schema) {
        return Some(format!(
            "`std:{}` is a schema, not a drawing ({}): `graftal derive std:{}` prints its words",
            e.name,
            e.schema_reason().unwrap_or_default(),
            e.name
        ));
    }
    let (mut moves, mut draws) = (false, false);
    for &s in word.symbols() {
        if let Some(TurtleOp::Forward { draw }) = sys.op(s) {
            moves = true;
            draws |= draw;
        }
    }
    if moves && !draws {
        return Some(
            "the turtle only moves without drawing (`f`): a kolam is drawn as a \
             B-spline through its positions; try `--spline`"
                .into(),
        );
    }
    if !moves && steps > 0 {
        return Some(
            "no symbol of the derived word moves the turtle: a string example is \
             read with `graftal derive`, or its symbols need `F` to draw"
                .into(),
        );
    }
    (steps == 0)
        .then(|| "the derivation has 0 steps, so only the axiom is drawn: try `-n 4`".into())
}

/// Pixels under which a picture's width (or length) counts as nothing:
/// a line drawn one or two pixels wide shows no shape.
pub const NEARLY_NOTHING: f64 = 2.0;

/// The warning for a picture that draws nearly nothing at the view and
/// size of `ropts` (W0009): what it draws is under [`NEARLY_NOTHING`]
/// pixels across ([`render::drawn_spread`]), a line or a point. A note
/// says why: geometry in a plane seen edge-on (with the `--view` that
/// looks straight at it), geometry on one line, or a picture too long for
/// its width at this size.
pub fn nearly_nothing_drawn(
    sys: &System,
    g: &Geometry,
    ropts: &RenderOptions,
) -> Option<Diagnostic> {
    let mut opts = *ropts;
    super::picture::apply_look(sys, &mut opts);
    let drawn = render::drawn_spread(g, &opts);
    if drawn.width >= NEARLY_NOTHING {
        return None;
    }
    let (w, h) = (opts.width, opts.height);
    if drawn.length < NEARLY_NOTHING {
        return Some(
            Diagnostic::global(codes::NEARLY_NOTHING_DRAWN, "nearly nothing is drawn: the picture is a point")
                .with_note(format!(
                    "what is drawn covers under {NEARLY_NOTHING} pixels of the {w}x{h} picture: its segments have no length, or all lie at one point"
                )),
        );
    }
    let d = Diagnostic::global(
        codes::NEARLY_NOTHING_DRAWN,
        format!(
            "nearly nothing is drawn: the picture is a line {:.0} pixels long and {:.1} wide",
            drawn.length, drawn.width
        ),
    );
    let points = world_points(g, opts.spline);
    let axes = principal_spreads(&points).map(|(_, axis)| axis);
    let range = |axis: turtle::Vec3| {
        let along = points
            .iter()
            .map(|p| p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2]);
        let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        (hi - lo).max(0.0)
    };
    let (long, wide) = (range(axes[0]), range(axes[1]));
    let longer = format!(
        "the picture is {:.0} times longer than it is wide",
        drawn.length / drawn.width.max(1e-3)
    );
    if wide <= 1e-9 * long {
        return Some(d.with_note(
            "every segment lies on one line, so the picture is a line from every view",
        ));
    }
    // Even seen straight on, the widest view, the width would be lost.
    if wide / long * drawn.length < NEARLY_NOTHING {
        return Some(d.with_note(format!(
            "{longer}, from every view: draw it larger with `--size`"
        )));
    }
    let (az, el) = view_along(axes[2]);
    let face_on = RenderOptions {
        view: View::degrees(az, el),
        camera: None,
        ..opts
    };
    if render::drawn_spread(g, &face_on).width >= NEARLY_NOTHING {
        return Some(
            d.with_note("the geometry lies in a plane, and this view sees it edge-on")
                .with_help(format!(
                    "try `--view {az:.0},{el:.0}`, which looks straight at that plane"
                )),
        );
    }
    Some(d.with_note(format!("{longer}: draw it larger with `--size`")))
}
