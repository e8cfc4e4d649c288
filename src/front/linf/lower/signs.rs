//! Runs of signs (`++t`, `-`): the rotation each names, or the default one.

use super::strings::{push_op, push_pieces, split, StringOut};
use super::{Cx, Role};
use crate::diagnostics::{codes, nearest, Diagnostic};
use crate::front::linf::ast::Item;
use crate::front::name_list;
use crate::ir::{RotationId, Span, TurtleOp};

/// A run of adjacent signs: each sign (`true` for `-`) and the run's
/// span and text.
pub(super) struct SignRun {
    pub(super) signs: Vec<(bool, Span)>,
    pub(super) span: Span,
    pub(super) text: String,
}

impl SignRun {
    /// The run starting at `items[i]`, and the index of the item after it.
    fn read(items: &[Item], mut i: usize) -> (Self, usize) {
        let mut signs: Vec<(bool, Span)> = Vec::new();
        while let Some(Item::Sign { minus, span }) = items.get(i) {
            if signs.last().is_some_and(|(_, s)| s.end != span.start) {
                break;
            }
            signs.push((*minus, span.clone()));
            i += 1;
        }
        let span = signs[0].1.start..signs[signs.len() - 1].1.end;
        let text = signs
            .iter()
            .map(|(m, _)| if *m { '-' } else { '+' })
            .collect();
        (SignRun { signs, span, text }, i)
    }
}

/// A run of adjacent signs and the angle named right after it; returns the
/// index of the next item.
pub(super) fn lower_signs(cx: &mut Cx<'_>, out: &mut StringOut, items: &[Item], i: usize) -> usize {
    let (run, mut i) = SignRun::read(items, i);
    // The name right after the run, split.
    let mut rest: Vec<(Result<Role, ()>, &str, Span)> = Vec::new();
    let mut whole = "";
    if let Some(Item::Name(n)) = items.get(i) {
        if n.span.start == run.span.end {
            rest = split(cx, &n.text, n.span.start);
            whole = &n.text;
            i += 1;
        }
    }
    let (rotation, suffix) = match rest.first() {
        Some((Ok(Role::Angle(id)), text, _)) => {
            let r = (Some(*id), text.to_string());
            let _ = rest.remove(0);
            r
        }
        Some((Err(()), text, span)) => {
            unknown_angle(cx, &run, text, span);
            return i;
        }
        _ => (default_rotation(cx, &run), String::new()),
    };
    if let Some(rotation) = rotation {
        push_rotations(cx, out, &run, rotation, &suffix);
    }
    push_pieces(cx, out, &rest, whole);
    i
}

/// An undeclared name `text` right after the signs of `run`.
fn unknown_angle(cx: &mut Cx<'_>, run: &SignRun, text: &str, span: &Span) {
    cx.report(codes::LINF_UNKNOWN_ANGLE, |cx| {
        unknown_angle_diagnostic(cx, run, text, span)
    });
}

fn unknown_angle_diagnostic(cx: &mut Cx<'_>, run: &SignRun, text: &str, span: &Span) -> Diagnostic {
    let run_text = &run.text;
    let affordable = cx.suggester.afford(text.len(), cx.roles.len(), cx.longest);
    let angles: Vec<&str> = match affordable {
        true => cx.angle_names.iter().map(String::as_str).collect(),
        false => Vec::new(),
    };
    // Rotation names only: a line or rule name after the signs would be
    // another reading of the text (the default rotation, then the name),
    // not the rotation the writer misspelt.
    let mut near: Vec<String> = nearest(text, &angles)
        .into_iter()
        .map(|n| format!("{run_text}{n}"))
        .collect();
    near.sort();
    if near.len() > 3 {
        near.clear();
    }
    let d = Diagnostic::at(
        codes::LINF_UNKNOWN_ANGLE,
        span.clone(),
        format!("unknown angle `{text}` after `{run_text}`"),
    )
    .with_label("not a declared angle")
    .with_secondary(run.span.clone(), "rotates by the angle named here");
    match (near.first(), cx.angle_names.is_empty()) {
        (Some(n), _) => d.suggesting(n),
        (None, true) => d.with_help(format!(
            "declare it in the angles block: `angles {text} = (0, pi/2)`"
        )),
        (None, false) => d.with_help(format!(
            "declared angles: {}; or declare `{text} = (…, …)` in the angles block",
            name_list(cx.angle_names.iter().map(String::as_str), false)
        )),
    }
}

/// The default rotation, for signs that name no angle; reported when
/// there is none.
pub(super) fn default_rotation(cx: &mut Cx<'_>, run: &SignRun) -> Option<RotationId> {
    if cx.default_rotation.is_some() {
        return cx.default_rotation;
    }
    cx.report(codes::LINF_NO_DEFAULT_ROTATION, |cx| {
        let run_text = &run.text;
        let help = match cx.angle_names.first() {
            Some(a) => format!("name the angle right after the signs, e.g. `{run_text}{a}`, or declare a default rotation: `angles (0, pi/2)`"),
            None => "declare a default rotation in the angles block, e.g. `angles (0, pi/2)`".to_string(),
        };
        Diagnostic::at(
            codes::LINF_NO_DEFAULT_ROTATION,
            run.span.clone(),
            format!("`{run_text}` names no angle and no default rotation is declared"),
        )
        .with_label("rotates by what?")
        .with_help(help)
    });
    None
}

/// One symbol per sign of `run`: `+suffix` or `-suffix`, turning by
/// `rotation` (the angle named `suffix`, or the default rotation when it
/// is empty).
fn push_rotations(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    run: &SignRun,
    rotation: RotationId,
    suffix: &str,
) {
    for (minus, span) in &run.signs {
        let name = format!("{}{suffix}", if *minus { '-' } else { '+' });
        let op = TurtleOp::Frenet {
            rotation,
            negate: *minus,
        };
        // Each symbol spans its sign and the angle's name.
        let end = if suffix.is_empty() {
            span.end
        } else {
            run.span.end + suffix.len()
        };
        push_op(cx, out, &name, op, span.start..end);
    }
}
