//! The stored way: the word interpreted into geometry kept in memory,
//! then drawn (the painter's order, a camera, splines, polygons and
//! discs need it all), and what every way shares: the look a system gives
//! its picture, its colour map, the encoders.

use super::{DrawError, Format};
use crate::ir::System;
use crate::render::{self, RenderOptions};
use crate::turtle::Geometry;

/// Renders a geometry to bytes of `format`.
pub fn render_bytes(
    sys: &System,
    g: &Geometry,
    format: Format,
    opts: RenderOptions,
) -> Result<Vec<u8>, DrawError> {
    render_bytes_with(sys, g, format, opts, &mut |_, _| {})
}

/// [`render_bytes`], calling `progress(drawn, total)` as segments are
/// drawn.
pub fn render_bytes_with(
    sys: &System,
    g: &Geometry,
    format: Format,
    mut opts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<u8>, DrawError> {
    if format == Format::Pov {
        return super::traced::geometry(sys, g, format, &opts, &super::Tracing::default());
    }
    apply_look(sys, &mut opts);
    opts.thin_dense = format == Format::Png;
    let lighting = sys.look.lighting.as_ref();
    match (format, lighting) {
        (Format::Png, Some(lighting)) => {
            render::raster::png(g, lighting, palette(sys), &opts, progress).ok_or(too_large(&opts))
        }
        (Format::Svg, _) if lighting.is_some() || opts.camera.is_some() => {
            Ok(render::svg::write_scene(g, lighting, palette(sys), &opts).into_bytes())
        }
        _ => encode(&render::layout(g, &opts), format, &opts, progress),
    }
}

/// What the system's settings and look say of the picture: the share it
/// fills, its background, and its camera unless a view was asked for.
pub(in crate::driver) fn apply_look(sys: &System, opts: &mut RenderOptions) {
    opts.scale = sys.settings.scale;
    opts.background = sys.look.background.unwrap_or(render::WHITE);
    opts.background_alpha = 255;
    if let Some(bg) = opts.style.background {
        opts.background = bg.rgb;
        opts.background_alpha = bg.alpha;
    }
    opts.base_width = sys.settings.width;
    opts.camera = if opts.view_given {
        None
    } else {
        sys.look.camera
    };
}

/// The colour map: the system's colours, else the IR's default palette.
pub(super) fn palette(sys: &System) -> &[crate::ir::Rgb] {
    if sys.colours.is_empty() {
        &crate::ir::colours::DEFAULT_PALETTE
    } else {
        &sys.colours
    }
}

/// A picture as bytes of `format`.
pub(super) fn encode(
    pic: &render::Picture,
    format: Format,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<u8>, DrawError> {
    match format {
        Format::Svg => Ok(render::svg::write_with(pic, opts.detail).into_bytes()),
        Format::Png => render::png::encode_with(pic, progress).ok_or(too_large(opts)),
        // A scene is written from the geometry (`render_bytes_with`), never
        // from a flat picture.
        Format::Pov => Err(DrawError::NoScene),
    }
}
/// The error for a picture too large to encode.
pub(super) fn too_large(opts: &RenderOptions) -> DrawError {
    DrawError::Encode {
        width: opts.width,
        height: opts.height,
    }
}
