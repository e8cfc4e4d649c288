//! Ray-traced pictures ([`crate::raytrace`]): an instancing graph traced
//! without being expanded, a turtle's geometry through a flat bounding
//! volume hierarchy. Chosen by the request (`--raytrace`) or by the model:
//! a 3D instancing graph, or a look whose lights cast shadows (cpfg's
//! `render mode: shadows`).

use super::stored::too_large;
use super::{DrawError, Format};
use crate::driver::derive::RunOptions;
use crate::eval::tree::MAX_TREE_DEPTH;
use crate::ir::graph::{Finish, InstancingGraph};
use crate::ir::{Rgb, System};
use crate::raytrace::{self, bvh, graph::GraphScene, Eye, Options, Scene};
use crate::render::RenderOptions;
use crate::turtle::instanced::Instanced;
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

/// Why a graph has no picture, as the error E0016.
fn unbounded(why: raytrace::bounds::Unbounded) -> DrawError {
    let message = match why {
        raytrace::bounds::Unbounded::NotContractive => {
            "the graph has no limit: a cycle of its rules does not contract (see `graftal check`)"
        }
        raytrace::bounds::Unbounded::Empty => {
            "the graph draws nothing: no symbol the axiom reaches has a geometry"
        }
    };
    DrawError::Stopped(Box::new(crate::diagnostics::Diagnostic::global(
        crate::diagnostics::codes::GRAPH_UNBOUNDED,
        message,
    )))
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
    let opts = options(sys, ropts, tracing);
    let pov = || raytrace::pov::graph_scene(&scene, &opts);
    encode(&scene, &opts, format, ropts, &pov)
}

/// A ray-traced picture of a context-free system from its shared
/// subtrees ([`raytrace::subtrees`]): the derivation tree is the
/// instancing graph, traced without deriving the word. `Ok(None)` when
/// the system is not one the shared subtrees draw (in one colour and
/// width, with turns that repeat).
pub(super) fn shared(
    sys: &System,
    run: &RunOptions,
    format: Format,
    ropts: &RenderOptions,
    tracing: &Tracing,
) -> Result<Option<Vec<u8>>, DrawError> {
    let steps = run.derive_options(sys).steps;
    // A scene beside the word is traced from the stored geometry.
    if steps > MAX_TREE_DEPTH || !sys.look.scene.is_empty() {
        return Ok(None);
    }
    let Some(mut inst) = Instanced::new(sys) else {
        return Ok(None);
    };
    let palette = super::stored::palette(sys);
    let colour = palette[sys.settings.colour.min(palette.len() - 1)];
    // The lines' width is in pixels (or world units): the picture's
    // framing, found from the graph with lines of no width, says how wide.
    let Some(bare) = raytrace::subtrees::graph(&mut inst, steps, 0.0, colour) else {
        return Ok(None);
    };
    let opts = options(sys, ropts, tracing);
    let Ok(bare_scene) = GraphScene::new(&bare, raytrace::linear(colour)) else {
        return Ok(None);
    };
    let pixel = raytrace::pixel_size(&bare_scene.fit_points(), &opts);
    let radius = line_radius(sys, ropts, pixel) / sys.settings.step.abs().max(f64::MIN_POSITIVE);
    let Some(g) = raytrace::subtrees::graph(&mut inst, steps, radius, colour) else {
        return Ok(None);
    };
    let scene = GraphScene::new(&g, raytrace::linear(colour)).map_err(unbounded)?;
    let pov = || raytrace::pov::graph_scene(&scene, &opts);
    encode(&scene, &opts, format, ropts, &pov).map(Some)
}

/// The radius of a line of the system's initial width, in world units:
/// widths in pixels are a line unit each, as the rasteriser draws them;
/// at least half a pixel.
fn line_radius(sys: &System, ropts: &RenderOptions, pixel: f64) -> f64 {
    let width = sys.settings.width.abs();
    let world = if sys.settings.world_widths {
        width
    } else {
        let line_unit = (ropts.width.min(ropts.height) as f64 / 600.0).max(1.0);
        width * line_unit * pixel
    };
    (world / 2.0).max(pixel / 2.0)
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
    let corners = raytrace::box_corners(world.0, world.1);
    let pixel = raytrace::pixel_size(&corners, &opts) * line_unit;
    let finish = Finish {
        specular: 0.2,
        ..Finish::default()
    };
    let items = bvh::from_geometry(g, pixel, finish, sys.look.textures());
    let scene = bvh::Bvh::new(items);
    if format == Format::Pov {
        let points = scene.fit_points();
        return Ok(raytrace::pov::items_scene(scene.items(), &opts, &points).into_bytes());
    }
    encode(&scene, &opts, format, ropts, &String::new)
}

/// The picture in `format`; a POV-Ray scene is `pov`'s.
fn encode(
    scene: &dyn Scene,
    opts: &Options,
    format: Format,
    ropts: &RenderOptions,
    pov: &dyn Fn() -> String,
) -> Result<Vec<u8>, DrawError> {
    if format == Format::Pov {
        return Ok(pov().into_bytes());
    }
    let rgba = raytrace::trace(scene, opts);
    let png = raytrace::png(rgba, opts.width, opts.height).ok_or(too_large(ropts))?;
    Ok(match format {
        Format::Svg => raytrace::svg_of_png(&png, opts.width, opts.height).into_bytes(),
        Format::Png | Format::Pov => png,
    })
}
