//! Instancing graphs drawn flat: the attractor of a planar IFS at pixel
//! resolution ([`render::attractor`]), the same pixels every run. A graph
//! that leaves the plane, or has several symbols or geometries, is ray
//! traced (`traced.rs`).

use super::stored::{apply_look, palette, too_large};
use super::{DrawError, Format, Target};
use crate::ir::graph::InstancingGraph;
use crate::ir::System;
use crate::render::{self, attractor, RenderOptions};

/// Draws the graph of `sys` as `target` asks: a PNG or an SVG of its
/// attractor, when the graph is planar.
pub(super) fn draw(
    sys: &System,
    graph: &InstancingGraph,
    target: Target,
    mut ropts: RenderOptions,
) -> Result<Vec<u8>, DrawError> {
    let Target::Still(format) = target else {
        return Err(DrawError::NotDrawable(format!(
            "an instancing graph (an IFS) is drawn as a still picture, not as {}: write a PNG \
             or an SVG",
            target.name()
        )));
    };
    if !graph.is_planar() {
        return Err(DrawError::NotDrawable(
            "a 3D instancing graph (a 3D IFS) is ray traced: only a graph whose maps keep the \
             plane (a 2D IFS) is drawn flat"
                .into(),
        ));
    }
    let not_drawn = |e: attractor::NotDrawn| DrawError::NotDrawable(e.to_string());
    let maps = attractor::planar_ifs(graph).map_err(not_drawn)?;
    apply_look(sys, &mut ropts);
    let ink = match ropts.style.palette {
        Some(render::Palette::Mono) => crate::ir::Rgb(0, 0, 0),
        _ => {
            let colours = palette(sys);
            colours[sys.settings.colour % colours.len()]
        }
    };
    let px = attractor::pixels(&maps, &ropts).map_err(not_drawn)?;
    match format {
        Format::Png => attractor::png(&px, ink, &ropts).ok_or(too_large(&ropts)),
        Format::Svg => Ok(attractor::svg(&px, ink, &ropts).into_bytes()),
        Format::Pov => Err(DrawError::NoScene),
    }
}

/// Whether the graph is drawn flat: a plane IFS (one symbol, no geometry).
pub(super) fn draws(graph: &InstancingGraph) -> bool {
    graph.is_planar() && attractor::planar_ifs(graph).is_ok()
}
