//! Ray-traced pictures ([`crate::raytrace`]): an instancing graph traced
//! without being expanded, a turtle's geometry through a flat bounding
//! volume hierarchy. Chosen by the request (`--raytrace`) or by the model:
//! a 3D instancing graph, or a look whose lights cast shadows (cpfg's
//! `render mode: shadows`).

use super::stored::too_large;
use super::{DrawError, Format};
use crate::ir::graph::{Finish, InstancingGraph};
use crate::ir::{Rgb, System};
use crate::raytrace::{self, bvh, graph::GraphScene, Eye, Options, Scene};
use crate::render::RenderOptions;
use crate::turtle::Geometry;

/// How a ray-traced picture is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tracing {
    /// `Some(true)`: ray traced whatever the model; `None`: as the model's
    /// kind says ([`wanted`]).
    pub raytrace: Option<bool>,
    /// Samples per pixel (a square number: 1, 4, 9, 16).
    pub samples: u32,
    /// Threads; 0 for every core.
    pub threads: usize,
}

impl Default for Tracing {
    fn default() -> Self {
        Tracing {
            raytrace: None,
            samples: 4,
            threads: 0,
        }
    }
}

/// Whether `sys` is ray traced: when asked, or when it is a 3D instancing
/// graph (no other method draws one) or its lights cast shadows.
pub(super) fn wanted(sys: &System, tracing: &Tracing) -> bool {
    match &sys.graph {
        Some(g) => tracing.raytrace == Some(true) || !g.is_planar(),
        None => {
            let shadows = sys.look.lighting.as_ref().is_some_and(|l| l.shadows);
            tracing.raytrace.unwrap_or(shadows)
        }
    }
}

/// The tracer's options for a picture the renderer's options describe.
fn options(sys: &System, ropts: &RenderOptions, tracing: &Tracing) -> Options {
    let eye = match (ropts.view_given, sys.look.camera) {
        (false, Some(camera)) => Eye::Camera(camera),
        _ => Eye::View {
            azimuth: ropts.view.azimuth,
            elevation: ropts.view.elevation,
        },
    };
    let mut opts = Options::new(ropts.width, ropts.height, eye);
    opts.scale = sys.settings.scale;
    opts.samples = tracing.samples;
    opts.threads = tracing.threads;
    opts.background = ropts
        .style
        .background
        .map(|b| b.rgb)
        .or(sys.look.background)
        .unwrap_or(crate::render::WHITE);
    if let Some(l) = &sys.look.lighting {
        opts.lights = l.lights.clone();
    }
    opts
}

/// The colour of a graph drawn without geometry: the file's first colour,
/// else a warm grey.
fn volume_colour(sys: &System) -> Rgb {
    sys.colours.first().copied().unwrap_or(Rgb(196, 180, 150))
}

/// A ray-traced picture of an instancing graph.
pub(super) fn graph(
    sys: &System,
    graph: &InstancingGraph,
    format: Format,
    ropts: &RenderOptions,
    tracing: &Tracing,
) -> Result<Vec<u8>, DrawError> {
    let scene = GraphScene::new(graph, raytrace::linear(volume_colour(sys))).map_err(|why| {
        let message = match why {
            raytrace::bounds::Unbounded::NotContractive => {
                "the graph has no limit: a cycle of its rules does not contract (see `graftal check`)"
            }
            raytrace::bounds::Unbounded::Empty => "the graph draws nothing: no symbol the axiom reaches has a geometry",
        };
        DrawError::Stopped(Box::new(crate::diagnostics::Diagnostic::global(
            crate::diagnostics::codes::GRAPH_UNBOUNDED,
            message,
        )))
    })?;
    encode(&scene, &options(sys, ropts, tracing), format, ropts)
}

/// A ray-traced picture of what a turtle drew.
pub(super) fn geometry(
    sys: &System,
    g: &Geometry,
    format: Format,
    ropts: &RenderOptions,
    tracing: &Tracing,
) -> Result<Vec<u8>, DrawError> {
    let opts = options(sys, ropts, tracing);
    let world = g.bbox().map_or(([0.0; 3], [0.0; 3]), |b| {
        ([b[0], b[1], b[2]], [b[3], b[4], b[5]])
    });
    // Widths given in pixels are a line unit each, as the rasteriser
    // draws them.
    let line_unit = (ropts.width.min(ropts.height) as f64 / 600.0).max(1.0);
    let pixel = raytrace::pixel_size(world, &opts) * line_unit;
    let finish = Finish {
        specular: 0.2,
        ..Finish::default()
    };
    let scene = bvh::Bvh::new(bvh::from_geometry(g, pixel, finish));
    encode(&scene, &opts, format, ropts)
}

fn encode(
    scene: &dyn Scene,
    opts: &Options,
    format: Format,
    ropts: &RenderOptions,
) -> Result<Vec<u8>, DrawError> {
    let rgba = raytrace::trace(scene, opts);
    let png = raytrace::png(rgba, opts.width, opts.height).ok_or(too_large(ropts))?;
    Ok(match format {
        Format::Png => png,
        Format::Svg => raytrace::svg_of_png(&png, opts.width, opts.height).into_bytes(),
    })
}
