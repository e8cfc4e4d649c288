//! A picture linked to its source: an SVG whose every drawn part names,
//! in its `data-src`, the bytes of the source that wrote the module that
//! drew it (a successor's symbol, or the axiom's). What the live page
//! highlights when a part of the picture is pointed at.
//!
//! Drawn from stored geometry as the stored way draws a flat picture, with
//! every segment kept ([`Detail::Full`]); the word is derived with the
//! origin of each symbol ([`Deriver::derive_traced`]), the same word every
//! other way derives.

use super::stored::apply_look;
use super::DrawError;
use crate::driver::derive::RunOptions;
use crate::driver::interpret::{add_fixed, check_moves_up_front, drawn_word};
use crate::eval::parametric::Globals;
use crate::eval::provenance::Origin;
use crate::eval::Deriver;
use crate::ir::{Span, SpanTable, System};
use crate::render::{self, Detail, Links, RenderOptions, UNTAGGED};
use crate::turtle;
use std::collections::HashMap;

/// The linked SVG of `sys`, or `None` where its picture is not drawn
/// flat from plain symbols (modules, a lit look, a camera): those are
/// drawn unlinked.
pub(super) fn draw(
    sys: &System,
    spans: &SpanTable,
    run: &RunOptions,
    mut ropts: RenderOptions,
    layout: bool,
) -> Result<Option<Vec<u8>>, DrawError> {
    apply_look(sys, &mut ropts);
    if sys.rewrites_modules() || sys.look.lighting.is_some() || ropts.camera.is_some() {
        return Ok(None);
    }
    check_moves_up_front(sys, run)?;
    let (word, origins) = Deriver::new(sys).derive_traced(&run.derive_options(sys))?;
    // The limit on moves, as every other way checks it.
    drawn_word(sys, &word, &Globals::default(), run)?;
    let mut g = turtle::Run {
        origins: true,
        paths: ropts.spline,
        ..turtle::Run::word(sys, &word, run.seed)
    }
    .geometry();
    add_fixed(sys, &mut g, layout);
    ropts.linked = true;
    ropts.detail = Detail::Full;
    ropts.thin_dense = false;
    let mut pic = render::layout(&g, &ropts);
    name_sources(&mut pic.links, &origins, spans);
    Ok(Some(
        render::svg::write_with(&pic, Detail::Full).into_bytes(),
    ))
}

/// Turns the links' word positions into the source spans they came from:
/// each distinct span named once (`FROM-TO`, bytes), the tags renumbered
/// to index those names; a position whose origin has no span is untagged.
fn name_sources(links: &mut Links, origins: &[Origin], spans: &SpanTable) {
    let mut index: HashMap<Span, u32> = HashMap::new();
    let mut names = Vec::new();
    let mut rename = |tag: &mut u32| {
        let span = origins.get(*tag as usize).and_then(|&o| span_of(o, spans));
        *tag = match span {
            Some(span) => *index.entry(span.clone()).or_insert_with(|| {
                names.push(format!("{}-{}", span.start, span.end));
                names.len() as u32 - 1
            }),
            None => UNTAGGED,
        };
    };
    links.runs.iter_mut().for_each(&mut rename);
    links.polygons.iter_mut().for_each(&mut rename);
    links.names = names;
}

/// Where `origin` is written in the source.
fn span_of(origin: Origin, spans: &SpanTable) -> Option<&Span> {
    match origin {
        Origin::Axiom(i) => spans.axiom.get(i),
        Origin::Successor {
            production,
            alternative,
            symbol,
        } => spans
            .successors
            .get(production)?
            .get(alternative)?
            .get(symbol),
    }
}
