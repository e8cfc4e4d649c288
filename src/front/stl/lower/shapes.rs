//! The shapes of a LAYOUT: their kinds, colours and arguments.

use super::did_you_mean;
use super::header::nonneg;
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::stl::ast::{Arg, ColourAst, Num, ShapeAst};
use crate::front::stl::layout;
use crate::ir::{Rgb, Shape, Span};

/// The layout shapes: a shape's name, matched without regard to case.
const SHAPE_KINDS: [&str; 4] = ["Rectangle", "RoundRect", "Ellipse", "Polygon"];

/// A layout shape. The colour and the kind are both checked (and both
/// reported) before the arguments.
pub(super) fn shape(diags: &mut Diagnostics, s: &ShapeAst) -> Option<Shape> {
    let colour = shape_colour(diags, &s.colour);
    let kind = shape_kind(diags, s)?;
    let colour = colour?;
    if kind == "Polygon" {
        return polygon(diags, s, colour);
    }
    sized_shape(diags, s, kind, colour)
}

/// A shape's colour: a Delphi colour name or `$00BBGGRR`.
fn shape_colour(diags: &mut Diagnostics, colour: &ColourAst) -> Option<Rgb> {
    match colour {
        ColourAst::Name(n, span) => {
            let c = layout::named_colour(n);
            if c.is_none() {
                unknown_colour_name(diags, n, span);
            }
            c
        }
        ColourAst::Hex(h, span) => {
            let c = layout::hex_colour(h);
            if c.is_none() {
                diags.push(
                    Diagnostic::at(
                        codes::STL_UNKNOWN_COLOUR,
                        span.clone(),
                        format!("`{h}` is not a colour"),
                    )
                    .with_label("expected `$00BBGGRR`")
                    .with_help(
                        "write up to eight hex digits with a zero top byte: `$0000FF00` is green",
                    ),
                );
            }
            c
        }
    }
}

fn unknown_colour_name(diags: &mut Diagnostics, n: &str, span: &Span) {
    let names: Vec<&str> = crate::ir::colours::delphi()
        .iter()
        .map(|(n, _)| *n)
        .collect();
    let d = Diagnostic::at(
        codes::STL_UNKNOWN_COLOUR,
        span.clone(),
        format!("unknown colour `{n}`"),
    )
    .with_label("not a Delphi colour name");
    diags.push(did_you_mean(
        d,
        n,
        &names,
        "use a Delphi colour name (clGreen, clOlive, …; `graftal explain E0506` lists them) or `$00BBGGRR`",
    ));
}

/// The shape's kind, spelled as in [`SHAPE_KINDS`].
fn shape_kind(diags: &mut Diagnostics, s: &ShapeAst) -> Option<&'static str> {
    if let Some(kind) = SHAPE_KINDS.iter().find(|k| k.eq_ignore_ascii_case(&s.kind)) {
        return Some(kind);
    }
    let d = Diagnostic::at(
        codes::STL_UNKNOWN_SHAPE,
        s.kind_span.clone(),
        format!("unknown shape `{}`", s.kind),
    )
    .with_label("not a layout shape");
    diags.push(did_you_mean(
        d,
        &s.kind,
        &SHAPE_KINDS,
        "the shapes are Rectangle, RoundRect, Ellipse and Polygon",
    ));
    None
}

/// How to write the arguments of a shape of `kind`.
fn shape_args_help(kind: &str) -> String {
    match kind {
        "Rectangle" | "Ellipse" => format!("write `{kind} (x, y), width, height`"),
        "RoundRect" => "write `RoundRect (x, y), width, height, corner`".to_string(),
        _ => "write `Polygon (x1, y1), (x2, y2), (x3, y3), …`".to_string(),
    }
}

/// A polygon: three points or more.
fn polygon(diags: &mut Diagnostics, s: &ShapeAst, colour: Rgb) -> Option<Shape> {
    let mut points = Vec::new();
    for a in &s.args {
        match a {
            Arg::Point(x, y, _) => points.push((x.value, y.value)),
            Arg::Num(n) => {
                diags.push(
                    Diagnostic::at(
                        codes::STL_SHAPE_ARGS,
                        n.span.clone(),
                        "a polygon takes points, not numbers",
                    )
                    .with_label("expected a point `(x, y)`")
                    .with_help(shape_args_help("Polygon")),
                );
                return None;
            }
        }
    }
    if points.len() < 3 {
        diags.push(
            Diagnostic::at(
                codes::STL_FEW_POINTS,
                s.span.clone(),
                format!(
                    "a polygon needs at least three points, this one has {}",
                    points.len()
                ),
            )
            .with_label("too few points")
            .with_help("add points: `(clGreen) Polygon (0,0), (100,0), (50,100)`"),
        );
        return None;
    }
    Some(Shape::Polygon { colour, points })
}

/// A Rectangle, Ellipse or RoundRect: a starting point, then its sizes
/// (width and height, and a RoundRect's corner), none negative.
fn sized_shape(diags: &mut Diagnostics, s: &ShapeAst, kind: &str, colour: Rgb) -> Option<Shape> {
    let ((x, y), nums) = start_and_sizes(diags, s, kind)?;
    let want = if kind == "RoundRect" { 4 } else { 3 };
    if nums.len() + 1 != want {
        diags.push(
            Diagnostic::at(
                codes::STL_SHAPE_ARGS,
                s.span.clone(),
                format!("{kind} takes {want} arguments, {} given", nums.len() + 1),
            )
            .with_label("wrong number of arguments")
            .with_help(shape_args_help(kind)),
        );
        return None;
    }
    let mut sizes = Vec::new();
    for n in &nums {
        sizes.push(nonneg(diags, n, "a size")?);
    }
    Some(match kind {
        "Rectangle" => Shape::Rectangle {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
        },
        "Ellipse" => Shape::Ellipse {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
        },
        _ => Shape::RoundRect {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
            corner: sizes[2],
        },
    })
}

/// A sized shape's arguments: the starting point and the numbers after it.
fn start_and_sizes<'s>(
    diags: &mut Diagnostics,
    s: &'s ShapeAst,
    kind: &str,
) -> Option<((f64, f64), Vec<&'s Num>)> {
    let (start, nums) = match s.args.split_first() {
        Some((Arg::Point(x, y, _), rest)) => (Some((x.value, y.value)), rest),
        _ => (None, &s.args[..]),
    };
    let nums: Option<Vec<&Num>> = nums
        .iter()
        .map(|a| match a {
            Arg::Num(n) => Some(n),
            _ => None,
        })
        .collect();
    let (Some(start), Some(nums)) = (start, nums) else {
        diags.push(
            Diagnostic::at(
                codes::STL_SHAPE_ARGS,
                s.span.clone(),
                format!("wrong arguments for {kind}"),
            )
            .with_label("expected a starting point, then sizes")
            .with_help(shape_args_help(kind)),
        );
        return None;
    };
    Some((start, nums))
}
