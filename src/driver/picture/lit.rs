//! Lit pictures drawn straight from the turtle: the word interpreted in
//! pieces on every thread, once to survey the framing, then once per band
//! of rows; no more than a round of pieces' drawing is stored.

use super::stored::{apply_look, palette, too_large};
use super::{DrawError, Format};
use crate::driver::derive::RunOptions;
use crate::driver::empty::NEARLY_NOTHING;
use crate::driver::interpret::{drawn_word, has_outline};
use crate::driver::Globals;
use crate::ir::{System, Word};
use crate::render::{self, RenderOptions};
use crate::turtle;

/// Whether [`draw`] may draw `sys` to `format` with `ropts`: a PNG
/// of a lit look, without splines or an STL layout (`layout`: one would be
/// added).
pub(super) fn streams_lit(
    sys: &System,
    format: Format,
    ropts: &RenderOptions,
    layout: bool,
) -> bool {
    format == Format::Png
        && sys.look.lighting.is_some()
        && !ropts.spline
        && !(layout && has_outline(sys))
        // A scene is geometry beside the word's, and labels are written
        // over the picture: drawn from what is stored.
        && sys.look.scene.is_empty()
        && !sys.writes_labels()
}

/// Draws a lit system's word to a PNG straight from the turtle
/// ([`render::raster::png_surveyed`]): the word is interpreted in pieces
/// ([`turtle::Pieces`]) on every thread, once for the framing and once per
/// band of rows, and only a round of pieces' drawing is held at a time, so
/// a plant of millions of polygons draws in the memory of its picture. The picture is
/// the one [`super::render_bytes`] draws from the stored geometry. `Ok(None)` when
/// nearly nothing is drawn, which the stored way explains. Call it where
/// [`streams_lit`] holds.
pub(super) fn draw(
    sys: &System,
    word: &Word,
    values: &Globals,
    opts: &RunOptions,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Option<Vec<u8>>, DrawError> {
    let drawn = drawn_word(sys, word, values, opts)?;
    apply_look(sys, &mut ropts);
    ropts.thin_dense = true;
    let Some(lighting) = sys.look.lighting.as_ref() else {
        return Ok(None);
    };
    let params = drawn.has_params().then_some(&*drawn);
    let pieces = turtle::Pieces::plan(sys, &drawn.0[..], params, opts.seed, ropts.threads);
    let drawing = render::raster::Drawing::pieces(&pieces, sys.settings.world_widths);
    let survey = render::raster::survey(&drawing, lighting, &ropts);
    if survey.pixels_across(&ropts) < NEARLY_NOTHING {
        return Ok(None);
    }
    let png =
        render::raster::png_surveyed(&drawing, &survey, lighting, palette(sys), &ropts, progress);
    png.ok_or(too_large(&ropts)).map(Some)
}
