//! The sentences of a hover: what a symbol does to the turtle and which
//! productions rewrite it, and what a cpfg user function holds.

use crate::driver::Compiled;
use crate::front::FunctionSite;
use crate::ir::{Angle, Axis, Rotation, SymbolId, System, TurtleOp};

/// The most productions a hover lists.
const HOVER_PRODUCTIONS: usize = 10;

/// The most control points a hover lists.
const HOVER_POINTS: usize = 12;

/// A symbol's hover: what the turtle does for it, and the productions that
/// rewrite it (their lines).
pub(super) fn symbol_text(c: &Compiled, sys: &System, symbol: SymbolId) -> String {
    let name = sys.symbols.name(symbol);
    let does = sys.op(symbol).map_or_else(
        || "nothing to the turtle".to_string(),
        |op| what_it_does(&sys.rotations, op),
    );
    let mut text = format!("`{name}`: {does}");
    let rewriting: Vec<_> = (sys.productions.iter().enumerate())
        .filter(|(_, p)| p.predecessor.contains(&symbol))
        .filter_map(|(i, _)| c.spans.productions.get(i))
        .collect();
    if rewriting.is_empty() {
        text.push_str("\n\nNo production rewrites it.");
        return text;
    }
    text.push_str("\n\nRewritten by:\n");
    let file = &c.file;
    for span in rewriting.iter().take(HOVER_PRODUCTIONS) {
        let line = file.line_index(span.start);
        let written = file.text.get((*span).clone()).unwrap_or("").trim();
        let shown = crate::diagnostics::shortened(written, 120);
        text.push_str(&format!("- line {}: `{shown}`\n", line + 1));
    }
    if rewriting.len() > HOVER_PRODUCTIONS {
        let more = rewriting.len() - HOVER_PRODUCTIONS;
        text.push_str(&format!("- … and {more} more\n"));
    }
    text
}

/// What `op` does to the turtle, in words (`rotations`: the system's
/// named rotations, which a Frenet turn names).
pub fn what_it_does(rotations: &[Rotation], op: TurtleOp) -> String {
    match op {
        TurtleOp::Forward { draw: true } => "moves one step forward, drawing a line".into(),
        TurtleOp::Forward { draw: false } => "moves one step forward without drawing".into(),
        TurtleOp::Rotate { axis, angle } => {
            let about = match axis {
                Axis::Heading => "rolls about its heading H",
                Axis::Left => "pitches about its left axis L",
                Axis::Up => "turns about its up axis U",
            };
            format!("{about} by {}", angle_text(angle))
        }
        TurtleOp::Frenet { rotation, negate } => {
            let r = rotations.get(rotation.0 as usize);
            let name = r.map_or("?", |r| r.name.as_str());
            let sign = if negate { "the inverse of " } else { "" };
            format!("applies {sign}the rotation `{name}` (torsion, then curvature)")
        }
        TurtleOp::TurnAround => "turns around (180° about U)".into(),
        TurtleOp::Push => "starts a branch: pushes the turtle's state".into(),
        TurtleOp::Pop => "ends a branch: pops the turtle's state".into(),
        TurtleOp::PolygonBegin => "starts a filled polygon".into(),
        TurtleOp::PolygonEnd => "closes and fills the polygon".into(),
        TurtleOp::DecrementWidth => "decrements the line width".into(),
        TurtleOp::NextColour => "takes the next colour".into(),
        TurtleOp::PreviousColour => "goes back to the previous colour".into(),
        TurtleOp::SwapTurns => "exchanges positive and negative turns".into(),
        TurtleOp::ScaleLength(x) => format!("multiplies the step length by {x}"),
        other => format!("{other:?}"),
    }
}

fn angle_text(angle: Angle) -> String {
    match angle {
        Angle::Delta(1.0) => "the angle increment δ".into(),
        Angle::Delta(f) => format!("{f} × the angle increment δ"),
        Angle::Radians(r) => format!("{}°", r.to_degrees()),
        Angle::Uniform { lo, hi } => format!(
            "a random angle in [{}°, {}°]",
            lo.to_degrees(),
            hi.to_degrees()
        ),
    }
}

/// A user function's hover: its name, number, file, samples and points.
pub(super) fn function_text(f: &FunctionSite) -> String {
    let name = f.name.as_deref().unwrap_or("(unnamed)");
    let file = f
        .path
        .file_name()
        .map_or("?".into(), |n| n.to_string_lossy());
    let points = &f.points;
    let shown: Vec<String> = (points.iter().take(HOVER_POINTS))
        // Read as single precision, as cpfg reads them: shown so, as written.
        .map(|[x, y]| format!("({}, {})", *x as f32, *y as f32))
        .collect();
    let more = points.len().saturating_sub(HOVER_POINTS);
    let more = if more > 0 {
        format!(", … and {more} more")
    } else {
        String::new()
    };
    format!(
        "cpfg user function `{name}` (function {} of `{file}`)\n\nsamples: {}; {} points: {}{more}",
        f.number,
        f.samples,
        points.len(),
        shown.join(", ")
    )
}
