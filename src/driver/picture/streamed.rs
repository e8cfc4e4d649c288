//! Pictures streamed: the word interpreted in pieces on every thread, each
//! piece's segments drawn into the picture's coverage a round of pieces at
//! a time, the whole drawing never stored.

use super::stored::{apply_look, too_large};
use super::{DrawError, Format};
use crate::driver::derive::RunOptions;
use crate::driver::empty::NEARLY_NOTHING;
use crate::driver::interpret::has_outline;
use crate::driver::Globals;
use crate::eval;
use crate::ir::{SymbolId, System, Word};
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

/// Draws `word` to a PNG streamed ([`render::coverage`]): the word is
/// interpreted in pieces on every thread ([`turtle::Pieces`]), once for
/// the bounds and once drawing each piece's segments into the picture a
/// round of pieces at a time; no more segments are stored than a round
/// draws. Call it where [`streams`] holds.
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
    let letters = Letters(&word);
    let pieces = turtle::Pieces::plan(sys, &letters, None, opts.seed, ropts.threads);
    let survey = || render::coverage::Survey::new(&ropts);
    let (parts, _) = turtle::pieces::each(&pieces, ropts.threads, survey);
    let mut survey = survey();
    for part in parts {
        survey.add(part);
    }
    if !survey.streams() {
        return Ok(unstreamed(word));
    }
    let world_widths = sys.settings.world_widths;
    let threads = ropts.threads;
    let Some(mut painter) =
        render::coverage::Painter::new(&survey, &ropts, world_widths, threads, progress)
    else {
        return Err(too_large(&ropts));
    };
    painter.draw(&pieces);
    if painter.overflow || painter.spread_width() < NEARLY_NOTHING {
        drop(pieces);
        return Ok(unstreamed(word));
    }
    let png = painter.png().ok_or(too_large(&ropts))?;
    Ok(Streamed::Picture(png))
}

/// A derived word's symbols as the turtle reads them in pieces.
struct Letters<'w>(&'w eval::Symbols);

/// A range of a derived word's symbols, in whichever width it keeps them.
enum Range<'w> {
    Bytes(std::slice::Iter<'w, u8>),
    Shorts(std::slice::Iter<'w, u16>),
    Wide(std::slice::Iter<'w, SymbolId>),
}

impl Iterator for Range<'_> {
    type Item = SymbolId;

    #[inline]
    fn next(&mut self) -> Option<SymbolId> {
        match self {
            Range::Bytes(i) => i.next().map(|&s| SymbolId(u32::from(s))),
            Range::Shorts(i) => i.next().map(|&s| SymbolId(u32::from(s))),
            Range::Wide(i) => i.next().copied(),
        }
    }
}

impl turtle::Letters for Letters<'_> {
    type Range<'s>
        = Range<'s>
    where
        Self: 's;

    fn count(&self) -> usize {
        self.0.len()
    }

    fn range(&self, r: std::ops::Range<usize>) -> Range<'_> {
        match self.0 {
            eval::Symbols::Bytes(w) => Range::Bytes(w[r].iter()),
            eval::Symbols::Shorts(w) => Range::Shorts(w[r].iter()),
            eval::Symbols::Wide(w) => Range::Wide(w[r].iter()),
        }
    }
}
