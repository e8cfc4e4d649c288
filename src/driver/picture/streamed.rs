//! Pictures streamed: each segment drawn into the picture's coverage as
//! the turtle makes it, none stored.

use super::stored::{apply_look, too_large};
use super::{DrawError, Format};
use crate::driver::derive::RunOptions;
use crate::driver::empty::NEARLY_NOTHING;
use crate::driver::interpret::has_outline;
use crate::driver::Globals;
use crate::eval;
use crate::ir::{System, Word};
use crate::render::{self, RenderOptions};
use crate::turtle;

/// Whether [`draw`] may draw `sys` to `format` with `ropts`:
/// a PNG of plain symbols (no modules, which draw through a
/// homomorphism), unlit, without a camera, splines, an STL layout or a
/// palette that needs the totals (by depth, along the path).
pub(super) fn streams(sys: &System, format: Format, ropts: &RenderOptions) -> bool {
    format == Format::Png
        && !sys.rewrites_modules()
        && !ropts.spline
        && !has_outline(sys)
        && sys.look.lighting.is_none()
        && sys.look.camera.is_none()
        && matches!(ropts.style.palette, None | Some(render::Palette::Mono))
}

/// What [`draw`] made: the PNG, or back the word when its
/// drawing needs the stored way (or draws nearly nothing, which the stored
/// way explains), with the values [`crate::driver::interpret`] reads.
pub(super) enum Streamed {
    Picture(Vec<u8>),
    Word(Word, Globals),
}

/// Draws `word` to a PNG streamed ([`render::coverage`]): the turtle runs
/// over the word twice, once for the bounds and once drawing each segment
/// into the picture as it is made; no segment is stored. Call it where
/// [`streams`] holds.
pub(super) fn draw(
    sys: &System,
    opts: &RunOptions,
    word: eval::Symbols,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Streamed, DrawError> {
    apply_look(sys, &mut ropts);
    let unstreamed =
        |w: eval::Symbols| Streamed::Word(w.into_word(), Globals::initial(&sys.program));
    let mut survey = render::coverage::Survey::new(&ropts);
    turtle::run(
        turtle::Run::symbols(sys, word.iter(), opts.seed),
        &mut survey,
    );
    if !survey.streams() {
        return Ok(unstreamed(word));
    }
    let world_widths = sys.settings.world_widths;
    let Some(mut painter) = render::coverage::Painter::new(&survey, &ropts, world_widths, progress)
    else {
        return Err(too_large(&ropts));
    };
    turtle::run(
        turtle::Run::symbols(sys, word.iter(), opts.seed),
        &mut painter,
    );
    if painter.overflow || painter.spread_width() < NEARLY_NOTHING {
        return Ok(unstreamed(word));
    }
    let png = painter.picture.png().ok_or(too_large(&ropts))?;
    Ok(Streamed::Picture(png))
}
