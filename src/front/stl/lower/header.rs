//! What a file gives besides its rules and seed's body: the settings
//! (ANGLE, LEVELS, GROWTH, B, L), each given once, and the layout.

use super::shapes::shape;
use super::{Ctx, DEFAULT_ANGLE, DEFAULT_BROADNESS, DEFAULT_LENGTH, DEFAULT_LEVELS, MAX_LEVELS};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::stl::ast::{File, Item, Num, Str};
use crate::ir::{Shape, Span};
use std::collections::HashMap;

pub(super) fn nonneg(diags: &mut Diagnostics, n: &Num, what: &str) -> Option<f64> {
    if !n.value.is_finite() || n.value < 0.0 {
        diags.push(
            Diagnostic::at(
                codes::STL_NEGATIVE,
                n.span.clone(),
                format!("{what} cannot be negative"),
            )
            .with_label(format!("{} is less than zero", n.value))
            .with_help("write a number of zero or more"),
        );
        return None;
    }
    Some(n.value)
}

/// The settings a file gives.
pub(super) struct Settings {
    pub(super) angle: f64,
    pub(super) levels: u32,
    pub(super) depth_first: bool,
    pub(super) b: (f64, f64),
    pub(super) l: (f64, f64),
    pub(super) b_span: Option<Span>,
    pub(super) l_span: Option<Span>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            angle: DEFAULT_ANGLE,
            levels: DEFAULT_LEVELS,
            depth_first: false,
            b: (DEFAULT_BROADNESS, 0.0),
            l: (DEFAULT_LENGTH, 0.0),
            b_span: None,
            l_span: None,
        }
    }
}

/// What a file's items say besides its rules (which go into [`Ctx`]), read
/// in file order.
#[derive(Default)]
pub(super) struct Header<'f> {
    pub(super) st: Settings,
    /// Where each setting and the seed was first given: each is given once.
    seen: HashMap<&'static str, Span>,
    pub(super) seed: Option<&'f Str>,
    pub(super) shapes: Vec<Shape>,
    /// The first LAYOUT: the file is an Outline Description.
    pub(super) layout_span: Option<Span>,
    /// No item had an error that keeps the file from being drawn.
    pub(super) ok: bool,
}

impl<'f> Header<'f> {
    /// Reads the items of `file`, declaring its rules in `ctx`.
    pub(super) fn read(ctx: &mut Ctx<'_>, file: &'f File) -> Self {
        let mut hd = Header {
            ok: true,
            ..Header::default()
        };
        for item in &file.items {
            hd.ok &= hd.item(ctx, item);
        }
        hd
    }

    /// Reads one item; false if it has an error that keeps the file from
    /// being drawn.
    pub(super) fn item(&mut self, ctx: &mut Ctx<'_>, item: &'f Item) -> bool {
        match item {
            Item::Angle { value, span } => {
                if !self.first_given(ctx.diags, "ANGLE", span) {
                    return true;
                }
                if !value.value.is_finite() {
                    return false;
                }
                self.st.angle = value.value;
                true
            }
            Item::Levels { value, span } => {
                if !self.first_given(ctx.diags, "LEVELS", span) {
                    return true;
                }
                let Some(levels) = levels(ctx.diags, value) else {
                    return false;
                };
                self.st.levels = levels;
                true
            }
            Item::Growth { depth_first, span } => {
                if self.first_given(ctx.diags, "GROWTH", span) {
                    self.st.depth_first = *depth_first;
                }
                true
            }
            Item::Param {
                param,
                value,
                decrement,
                span,
            } => self.param(ctx.diags, *param, value, decrement.as_ref(), span),
            Item::Rule {
                name,
                name_span,
                body,
                span,
            } => ctx.declare_rule(name, name_span, body, span),
            Item::Seed { body, span } => {
                if !self.first_given(ctx.diags, "SEED", span) {
                    return false;
                }
                self.seed = Some(body);
                true
            }
            Item::Layout { shapes, span } => {
                self.layout_span.get_or_insert(span.clone());
                let mut ok = true;
                for s in shapes {
                    match shape(ctx.diags, s) {
                        Some(sh) => self.shapes.push(sh),
                        None => ok = false,
                    }
                }
                ok
            }
        }
    }

    /// Whether `key` is given at `span` for the first time; a second one is
    /// reported.
    fn first_given(&mut self, diags: &mut Diagnostics, key: &'static str, span: &Span) -> bool {
        let Some(first) = self.seen.get(key) else {
            self.seen.insert(key, span.clone());
            return true;
        };
        diags.push(
            Diagnostic::at(
                codes::STL_DUPLICATE,
                span.clone(),
                format!("`{key}` given twice"),
            )
            .with_label("given again here")
            .with_secondary(first.clone(), "first given here")
            .with_help("keep one of them"),
        );
        false
    }

    /// `B = value (decrement)` or `L = value (decrement)`.
    fn param(
        &mut self,
        diags: &mut Diagnostics,
        param: char,
        value: &Num,
        decrement: Option<&Num>,
        span: &Span,
    ) -> bool {
        let key = if param == 'B' { "B" } else { "L" };
        if !self.first_given(diags, key, span) {
            return true;
        }
        let what = if param == 'B' {
            "the broadness B"
        } else {
            "the length L"
        };
        let v = nonneg(diags, value, what);
        let d = match decrement {
            Some(d) => nonneg(diags, d, "a decrement per level"),
            None => Some(0.0),
        };
        if param == 'L' && v == Some(0.0) {
            diags.push(
                Diagnostic::at(
                    codes::STL_NEGATIVE,
                    value.span.clone(),
                    "the length L must be more than zero",
                )
                .with_label("stems of length 0 draw nothing")
                .with_help("write e.g. `L = 40 (4)`"),
            );
            return false;
        }
        let (Some(v), Some(d)) = (v, d) else {
            return false;
        };
        // The clamping warning points at the decrement, or at the whole
        // parameter when it has none.
        let dspan = decrement.map_or(span.clone(), |d| d.span.clone());
        if param == 'B' {
            self.st.b = (v, d);
            self.st.b_span = Some(dspan);
        } else {
            self.st.l = (v, d);
            self.st.l_span = Some(dspan);
        }
        true
    }
}

/// The value of `LEVELS`: a whole number up to [`MAX_LEVELS`].
pub(super) fn levels(diags: &mut Diagnostics, value: &Num) -> Option<u32> {
    let v = value.value;
    if v < 0.0 || v.fract() != 0.0 || !v.is_finite() {
        diags.push(
            Diagnostic::at(
                codes::STL_NEGATIVE,
                value.span.clone(),
                format!("LEVELS must be a whole number of 0 or more, not {v}"),
            )
            .with_label("not a count")
            .with_help("write e.g. `LEVELS 12`"),
        );
        return None;
    }
    if v > MAX_LEVELS as f64 {
        diags.push(
            Diagnostic::at(
                codes::STL_TOO_DEEP,
                value.span.clone(),
                format!("LEVELS {v} is more than the {MAX_LEVELS} graftal grows"),
            )
            .with_label("too many levels")
            .with_help(format!("use at most `LEVELS {MAX_LEVELS}`")),
        );
        return None;
    }
    Some(v as u32)
}
