//! Declarations: names and the role each plays (line, blank, rule head),
//! rotations with their angles, colours, and the warnings where one is
//! given again.

use super::{Cx, Role};
use crate::diagnostics::{codes, nearest, Diagnostic};
use crate::front::linf::ast::{BinOp, ColourDecl, Component, Expr, ExprKind, Name, RotationDecl};
use crate::ir::{Angle, Rgb, Rotation, RotationId, Span, TurtleOp};
use crate::number::radians;

pub(super) fn redefined(cx: &mut Cx<'_>, what: &str, now: Span, before: Span) {
    cx.diags.push(
        Diagnostic::at(
            codes::LINF_REDEFINED,
            now,
            format!("{what} defined twice; this later definition is used"),
        )
        .with_label("used")
        .with_secondary(before, "ignored")
        .with_help("remove one of the two definitions"),
    );
}

fn conflict(cx: &mut Cx<'_>, name: &Name, role: Role, before: Role, before_span: Span) {
    cx.diags.push(
        Diagnostic::at(
            codes::LINF_NAME_CONFLICT,
            name.span.clone(),
            format!(
                "`{}` is declared as {} and as {}",
                name.text,
                before.describe(),
                role.describe()
            ),
        )
        .with_label(format!("declared as {} here", role.describe()))
        .with_secondary(
            before_span,
            format!("declared as {} here", before.describe()),
        )
        .with_help("a name has one meaning; rename one of them"),
    );
}

fn set_role(cx: &mut Cx<'_>, name: &Name, role: Role) {
    cx.longest = cx.longest.max(name.text.len());
    cx.roles
        .insert(name.text.clone(), (role, name.span.clone()));
}

pub(super) fn declare_names(cx: &mut Cx<'_>, names: &[Name], role: Role) {
    for n in names {
        match cx.roles.get(&n.text).cloned() {
            Some((before, span)) if before == role => {
                redefined(cx, &format!("`{}`", n.text), n.span.clone(), span)
            }
            Some((before, span)) => {
                conflict(cx, n, role, before, span);
                continue;
            }
            None => {}
        }
        set_role(cx, n, role);
        let id = cx.sys.intern(&n.text);
        cx.spans.symbols.entry(id).or_insert(n.span.clone());
        cx.sys.set_interpretation(
            id,
            TurtleOp::Forward {
                draw: role == Role::Line,
            },
        );
    }
}

pub(super) fn declare_rotations(cx: &mut Cx<'_>, decls: &[RotationDecl]) {
    let mut default_span: Option<Span> = None;
    for d in decls {
        // A rotation in error is still declared (as no rotation at all), so
        // that its uses are not reported again; the file has an error and is
        // not drawn anyway.
        let (torsion, curvature) =
            rotation_pair(cx, d).unwrap_or((Angle::Radians(0.0), Angle::Radians(0.0)));
        let name = d.name.as_ref().map_or(String::new(), |n| n.text.clone());
        let rotation = Rotation {
            name: name.clone(),
            torsion,
            curvature,
        };
        match &d.name {
            None => {
                if let Some(before) = default_span.replace(d.span.clone()) {
                    redefined(cx, "the default rotation", d.span.clone(), before);
                }
                let id = RotationId(cx.sys.rotations.len() as u32);
                cx.sys.rotations.push(rotation);
                cx.default_rotation = Some(id);
            }
            Some(n) => {
                match cx.roles.get(&n.text).cloned() {
                    Some((Role::Angle(id), span)) => {
                        redefined(
                            cx,
                            &format!("the rotation `{}`", n.text),
                            n.span.clone(),
                            span,
                        );
                        cx.sys.rotations[id.0 as usize] = rotation;
                        set_role(cx, n, Role::Angle(id));
                        continue;
                    }
                    Some((before, span)) => {
                        let id = RotationId(0);
                        conflict(cx, n, Role::Angle(id), before, span);
                        continue;
                    }
                    None => {}
                }
                let id = RotationId(cx.sys.rotations.len() as u32);
                cx.sys.rotations.push(rotation);
                set_role(cx, n, Role::Angle(id));
            }
        }
    }
}

/// The (torsion, curvature) of a declaration, or `None` after reporting why
/// it has none.
fn rotation_pair(cx: &mut Cx<'_>, d: &RotationDecl) -> Option<(Angle, Angle)> {
    if d.recovered {
        return None;
    }
    if d.components.len() != 2 {
        let n = d.components.len();
        let help = match n {
            1 => "a rotation is a pair (torsion, curvature); for a turn in the plane write `(0, angle)`",
            _ => "a rotation is a pair (torsion, curvature), e.g. `(0, pi/3)`",
        };
        cx.diags.push(
            Diagnostic::at(
                codes::LINF_NOT_A_PAIR,
                d.span.clone(),
                format!("a rotation needs two components, torsion and curvature; this one has {n}"),
            )
            .with_label(format!("{n} component{}", if n == 1 { "" } else { "s" }))
            .with_help(help),
        );
        return None;
    }
    let t = angle(cx, &d.components[0]);
    let c = angle(cx, &d.components[1]);
    Some((t?, c?))
}

pub(super) fn angle(cx: &mut Cx<'_>, c: &Component) -> Option<Angle> {
    match c {
        Component::Value(e) => value(cx, e).map(Angle::Radians),
        Component::Interval { lo, hi, span } => {
            let (l, h) = (value(cx, lo), value(cx, hi));
            let (l, h) = (l?, h?);
            if l > h {
                let (l, h) = (radians(l), radians(h));
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_EMPTY_INTERVAL,
                        span.clone(),
                        format!("interval from {l} down to {h}: its low end exceeds its high end"),
                    )
                    .with_label("empty interval")
                    .with_secondary(lo.span.clone(), format!("low end {l}"))
                    .with_secondary(hi.span.clone(), format!("high end {h}"))
                    .with_help("write the low end first: `[lo hi]`"),
                );
                return None;
            }
            Some(Angle::Uniform { lo: l, hi: h })
        }
    }
}

/// The value of `e`, or `None` after reporting why it has none.
pub(super) fn value(cx: &mut Cx<'_>, e: &Expr) -> Option<f64> {
    match eval(e) {
        Ok(v) => Some(v),
        Err(d) => {
            cx.diags.push(d);
            None
        }
    }
}

/// Evaluates an expression over numbers and `pi` (by recursion, as deep as
/// the tree, which the parser keeps within [`crate::ir::MAX_NESTING`]).
pub fn eval(e: &Expr) -> Result<f64, Diagnostic> {
    let bad = |msg: String| Diagnostic::at(codes::LINF_BAD_EXPRESSION, e.span.clone(), msg);
    let v = match &e.kind {
        ExprKind::Number(v) => *v,
        ExprKind::Name(n) if n == "pi" => std::f64::consts::PI,
        ExprKind::Name(n) => {
            let d = bad(format!("unknown name `{n}` in an expression")).with_label("not a number");
            return Err(if nearest(n, &["pi"]).is_empty() {
                d.with_help("expressions are made of numbers, `pi`, `+ - * /` and parentheses")
            } else {
                d.with_help("did you mean `pi`?")
            });
        }
        ExprKind::Neg(x) => -eval(x)?,
        ExprKind::Binary(op, a, b) => {
            let (a, b) = (eval(a)?, eval(b)?);
            match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div if b == 0.0 => {
                    return Err(bad("division by zero".to_string())
                        .with_label("the divisor is 0")
                        .with_help("a rotation component must be a finite number"))
                }
                BinOp::Div => a / b,
            }
        }
    };
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad("this expression has no finite value".to_string())
            .with_label("too large")
            .with_help("angles are in radians; use numbers of a sensible size"))
    }
}

pub(super) fn declare_head(cx: &mut Cx<'_>, head: &Name) {
    cx.has_rule.insert(head.text.clone(), head.span.clone());
    match cx.roles.get(&head.text).cloned() {
        Some((Role::Angle(_), span)) => cx.diags.push(
            Diagnostic::at(
                codes::LINF_NAME_CONFLICT,
                head.span.clone(),
                format!("a rule for `{}`, which is an angle", head.text),
            )
            .with_label("angles cannot be rewritten")
            .with_secondary(span, "declared as an angle here")
            .with_help("rename the angle or the rule head"),
        ),
        Some(_) => {}
        None => {
            set_role(cx, head, Role::NonTerminal);
            let id = cx.sys.intern(&head.text);
            cx.spans.symbols.entry(id).or_insert(head.span.clone());
        }
    }
}

pub(super) fn lower_colours(cx: &mut Cx<'_>, decls: &[ColourDecl]) {
    for (i, d) in decls.iter().enumerate() {
        if let Some((label, span)) = &d.label {
            if *label != i as f64 {
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_COLOUR_LABEL,
                        span.clone(),
                        format!("colour labelled {label} is number {i} in the list"),
                    )
                    .with_label(format!("this is colour {i}"))
                    .with_help("colours are used in the order they are listed; labels are only for reading"),
                );
            }
        }
        if d.components.len() != 3 {
            cx.diags.push(
                Diagnostic::at(
                    codes::LINF_COLOUR_ARITY,
                    d.span.clone(),
                    format!(
                        "a colour has three components (red, green, blue); this one has {}",
                        d.components.len()
                    ),
                )
                .with_label("not an (r, g, b) triple")
                .with_help("write each colour as `(r, g, b)` with components from 0 to 255"),
            );
            continue;
        }
        let mut rgb = [0u8; 3];
        let mut ok = true;
        for (k, e) in d.components.iter().enumerate() {
            let Some(v) = value(cx, e) else {
                ok = false;
                continue;
            };
            if !(0.0..=255.0).contains(&v) || v.fract() != 0.0 {
                ok = false;
                cx.diags.push(
                    Diagnostic::at(
                        codes::LINF_COLOUR_RANGE,
                        e.span.clone(),
                        format!("colour component {v} is not a whole number from 0 to 255"),
                    )
                    .with_label("out of range")
                    .with_help("components are 0..255, e.g. `(120, 120, 120)`"),
                );
            } else {
                rgb[k] = v as u8;
            }
        }
        if ok {
            cx.sys.colours.push(Rgb(rgb[0], rgb[1], rgb[2]));
        }
    }
    if cx.sys.colours.is_empty() {
        cx.sys.colours.push(Rgb(0, 0, 0));
    }
}
