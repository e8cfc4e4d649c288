//! Translation: the system written in another notation, with the
//! source's comments and angle increment, and with `--lossy` a comparison
//! of the two pictures.

use super::derive::RunOptions;
use super::interpret::geometry;
use super::load::{compile, Compiled};
use crate::back;
use crate::diagnostics::{codes, Diagnostic};
use crate::ir::System;
use crate::source::SourceFile;

/// Translates the system `sys` of `c` as `req` asks: the emitter learns
/// from the source's front end what it knows of the source (comments, the
/// angle increment it states).
pub fn translate(c: &Compiled, sys: &System, req: &back::Request) -> back::Translation {
    let origin = back::Origin {
        title: c.front.title(),
        comments: c.front.comments(&c.file.text),
        angle_divisions: c.front.angle_divisions(sys),
    };
    let mut t = back::translate(sys, &c.spans, &c.file.text, &origin, req);
    // `.gft` writes textures (docs/gft.md §9), but for an image whose file
    // name it cannot quote; no other notation says textures: the
    // translation draws untextured, and says so.
    let textures = sys.look.textures();
    let unwritten = if req.target.name() == "gft" {
        (textures.iter())
            .filter(|t| !back::gft::names_file(&t.file))
            .count()
    } else {
        textures.len()
    };
    if unwritten > 0 {
        t.diagnostics.push(Diagnostic::global(
            codes::TR_TEXTURES_DROPPED,
            format!(
                "{unwritten} texture(s) of the source are not written: the translation draws them untextured"
            ),
        ));
    }
    if req.lossy && !t.diagnostics.is_empty() {
        compare_pictures(sys, req, &mut t);
    }
    t
}

/// The most symbols `--lossy`'s comparison derives for either picture: a
/// fraction of a second, so that `--lossy` stays quick.
pub const COMPARE_MAX_SYMBOLS: usize = 500_000;

/// What [`compare_pictures`] measures of a picture.
struct Drawn {
    steps: u64,
    segments: usize,
    /// Width, height and depth of the bounds (zeros when nothing is drawn).
    extents: [f64; 3],
}

/// Derives and draws `sys` within [`COMPARE_MAX_SYMBOLS`]: `None` when
/// that is not enough.
fn drawn(sys: &System, steps: Option<u64>) -> Option<Drawn> {
    let opts = RunOptions {
        steps,
        max_symbols: COMPARE_MAX_SYMBOLS,
        max_moves: COMPARE_MAX_SYMBOLS,
        ..RunOptions::default()
    };
    let (_, g) = geometry(sys, &opts).ok()?;
    let b = g.bbox().unwrap_or([0.0; 6]);
    Some(Drawn {
        steps: opts.derive_options(sys).steps,
        segments: g.segments.len(),
        extents: [b[3] - b[0], b[4] - b[1], b[5] - b[2]],
    })
}

/// Draws the source `sys` and its approximated translation `t` (bounded
/// by [`COMPARE_MAX_SYMBOLS`]) and, when they differ much, adds one
/// warning with both sets of figures; when either is too large to draw
/// quickly, a note on the first warning says they were not compared.
fn compare_pictures(sys: &System, req: &back::Request, t: &mut back::Translation) {
    let Some(text) = &t.text else { return };
    // The source first: reading a translation to STL expands its rules,
    // as large as the source's word.
    let source = drawn(sys, req.steps);
    let name = format!("translation.{}", req.target.extension());
    let out = match source {
        Some(_) => match compile(SourceFile::new(name, text.as_str())).system {
            Some(out) => Some(out),
            // Not read back (a bug the tests look for): nothing to compare.
            None => return,
        },
        None => None,
    };
    // The translation states its own derivation length (or, in STL, has
    // the steps written out).
    let translated = out.as_ref().and_then(|out| drawn(out, None));
    let (Some(source), Some(translated)) = (&source, translated) else {
        let large = if source.is_none() {
            "the source"
        } else {
            "the translation"
        };
        if let Some(first) = t.diagnostics.0.first_mut() {
            first.notes.push(format!(
                "the translation's picture was not compared with the source's: {large} \
                 derives more than {COMPARE_MAX_SYMBOLS} symbols, too many to draw quickly"
            ));
        }
        return;
    };
    if let Some(d) = picture_difference(source, &translated) {
        t.diagnostics.push(d);
    }
}

/// The warning that `translated` no longer draws `source`'s picture: the
/// segment counts differ by more than half, or the bounds' proportions by
/// more than a quarter of the picture's size (a uniform scale is no
/// difference: every picture is fitted to its frame). A source that draws
/// no segment (polygons only, or nothing) is not compared.
fn picture_difference(source: &Drawn, translated: &Drawn) -> Option<Diagnostic> {
    let (a, b) = (source.segments, translated.segments);
    if a == 0 {
        return None;
    }
    let counts_differ = a.max(b) as f64 > 1.5 * a.min(b) as f64;
    let size = |d: &Drawn| d.extents.iter().copied().fold(0.0, f64::max);
    let (sa, sb) = (size(source), size(translated));
    let proportion = |d: &Drawn, s: f64, i: usize| if s > 0.0 { d.extents[i] / s } else { 0.0 };
    let proportions_differ =
        (0..3).any(|i| (proportion(source, sa, i) - proportion(translated, sb, i)).abs() > 0.25);
    if !counts_differ && !proportions_differ {
        return None;
    }
    // Width x height (x depth, for a 3D picture), the largest side 1.
    let dims = if source.extents[2] == 0.0 && translated.extents[2] == 0.0 {
        2
    } else {
        3
    };
    let bounds = |d: &Drawn, s: f64| {
        let shown: Vec<String> = (0..dims)
            .map(|i| format!("{:.2}", proportion(d, s, i)))
            .collect();
        shown.join(" x ")
    };
    let (ba, bb) = (bounds(source, sa), bounds(translated, sb));
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let message = if counts_differ {
        format!(
            "the translation draws {b} segment{} where the source draws {a}",
            plural(b)
        )
    } else {
        format!("the translation's picture is {bb} (its largest side 1) where the source's is {ba}")
    };
    Some(
        Diagnostic::global(codes::TR_PICTURE_DIFFERS, message)
            .with_note(format!(
                "drawn with {} steps (the source) and {} (the translation): {a} and {b} \
                 segments; bounds {ba} and {bb}, as proportions of their largest side",
                source.steps, translated.steps
            ))
            .with_help(
                "the approximations above changed the picture: translate without `--lossy` \
                 to see what the target cannot express",
            ),
    )
}
