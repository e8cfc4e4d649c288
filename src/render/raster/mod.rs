//! A software z-buffer renderer for lit looks (cpfg objects): what cpfg
//! draws with OpenGL, drawn here the same way.
//!
//! Everything becomes screen-space triangles with a depth and a colour per
//! vertex (lighting per vertex, as OpenGL's fixed function lights), drawn
//! into a supersampled colour and depth buffer (the nearer sample wins; on
//! a tie the first drawn) and box-filtered down. Lines are drawn by the
//! look's line style: screen-space lines of a pixel width, flat ribbons
//! facing the viewer, or cylinders; spheres (`@O`) are lit per sample.
//!
//! Nothing drawn needs storing: a z-buffer needs no order. What is drawn
//! comes from a [`Drawing`], replayed: once to survey its framing, then
//! once per thread for each band of rows, each thread drawing every other
//! stripe of rows into its own buffers. The buffers cover a band at a time,
//! so that memory stays bounded at any picture size ([`MAX_BAND_SAMPLES`]);
//! each band's rows go to the PNG encoder as they are done. Every sample is
//! drawn from the same things in the same order whichever band, stripe or
//! thread holds it: the same input gives the same bytes on any machine.

mod bands;
mod painter;
mod primitives;
mod survey;
mod target;
mod tessellate;

use super::camera::Projector;
use super::shade::{Colour, Kind, Paint, Shader};
use super::{Fit, Palette, RenderOptions};
use crate::ir::look::{Lighting, Shading};
use crate::ir::Rgb;
use crate::turtle::{Geometry, Parts, Pieced, Segment, Vec3};
use bands::{png_in_bands, MAX_THREADS};
use target::{SVert, Target};

pub use survey::Survey;
pub(super) use tessellate::newell;

/// Samples across a pixel, each way: more in small pictures, where a pixel
/// is a larger share of the picture.
fn samples_per_pixel(width: u32, height: u32) -> u32 {
    match width.max(height) {
        0..=512 => 3,
        513..=2048 => 2,
        _ => 1,
    }
}

/// What a lit picture is drawn from: everything drawn, in pieces given to
/// a sink in the same order each time (once to find the framing, then once
/// per band of rows), each thread drawing a run of pieces. A stored
/// [`Geometry`] is cut into parts ([`Geometry::in_parts`]); a word in
/// pieces ([`crate::turtle::Pieces`]) is interpreted piece by piece, so
/// that nothing drawn is stored.
pub struct Drawing<'d> {
    source: Source<'d>,
    /// Whether segment widths are in turtle units ([`Geometry::world_widths`]).
    world_widths: bool,
}

enum Source<'d> {
    Stored(&'d Geometry, Parts<'d>),
    Pieces(&'d dyn Pieced),
}

/// Things drawn per part of a stored drawing.
const PART: usize = 1 << 16;

impl<'d> Drawing<'d> {
    /// The labels of a stored drawing (a word in pieces has none: a system
    /// with labels is drawn from what is stored).
    fn labels(&self) -> &'d [crate::turtle::Label] {
        match self.source {
            Source::Stored(g, _) => &g.labels,
            Source::Pieces(_) => &[],
        }
    }

    pub fn stored(g: &'d Geometry) -> Self {
        Drawing {
            source: Source::Stored(g, g.in_parts(PART)),
            world_widths: g.world_widths,
        }
    }

    /// The drawing of a word in pieces, its widths in turtle units when
    /// `world_widths`.
    pub fn pieces(word: &'d dyn Pieced, world_widths: bool) -> Self {
        Drawing {
            source: Source::Pieces(word),
            world_widths,
        }
    }

    /// The drawing's pieces.
    fn pieced(&self) -> &dyn Pieced {
        match &self.source {
            Source::Stored(_, parts) => parts,
            Source::Pieces(p) => *p,
        }
    }
}

/// What a lit picture is drawn with: the projection, the fit, the shading.
struct Scene<'a> {
    lighting: &'a Lighting,
    shader: Shader<'a>,
    proj: Projector,
    fit: Fit,
    /// Samples per pixel each way.
    ss: f64,
    /// The style's line colours (`--palette`), instead of the system's.
    palette: Option<Palette>,
    world_widths: bool,
    /// Segments in the drawing and its deepest nesting (for `--palette`).
    segments: usize,
    max_depth: usize,
    /// The index of each piece's first segment.
    first_segments: Vec<usize>,
}

/// Draws `g` as its look `lighting` says, `palette` its colour map (never
/// empty), into PNG bytes; `None` for a picture of no pixels or when the
/// encoder fails. `progress(done, total)` is told as things are drawn.
pub fn png(
    g: &Geometry,
    lighting: &Lighting,
    palette: &[Rgb],
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Vec<u8>> {
    let drawing = Drawing::stored(g);
    let survey = survey(&drawing, lighting, opts);
    png_surveyed(&drawing, &survey, lighting, palette, opts, progress)
}

/// The first pass over `drawing` ([`Survey`]).
pub fn survey(drawing: &Drawing<'_>, lighting: &Lighting, opts: &RenderOptions) -> Survey {
    Survey::of(drawing, lighting, opts)
}

/// [`png`] of a drawing replayed ([`Drawing`]), its first pass done
/// (`survey`, which found its framing): drawn into each band of rows as it
/// comes; only the bands and a run of polygons ([`MAX_RUN`]) are held.
pub fn png_surveyed(
    drawing: &Drawing<'_>,
    survey: &Survey,
    lighting: &Lighting,
    palette: &[Rgb],
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Vec<u8>> {
    if palette.is_empty() {
        return None;
    }
    let threads = crate::parallel::threads(opts.threads).clamp(1, MAX_THREADS);
    let scene = Scene::new(survey, drawing.world_widths, lighting, palette, opts);
    png_in_bands(drawing, &scene, survey.drawn, opts, threads, progress)
}

/// The framing [`png`] gives `g` lit by `lighting` (its extent includes
/// cylinders' and spheres' radii).
pub fn framing(g: &Geometry, lighting: &Lighting, opts: &RenderOptions) -> super::Framing {
    Survey::of(&Drawing::stored(g), lighting, opts)
        .fit(opts)
        .framing
}

impl<'a> Scene<'a> {
    fn new(
        survey: &Survey,
        world_widths: bool,
        lighting: &'a Lighting,
        palette: &'a [Rgb],
        opts: &RenderOptions,
    ) -> Scene<'a> {
        let proj = Projector::new(opts);
        Scene {
            lighting,
            shader: Shader::new(lighting, palette, proj.towards_viewer(survey.centre())),
            proj,
            fit: survey.fit(opts),
            ss: f64::from(samples_per_pixel(opts.width, opts.height)),
            palette: opts.style.palette,
            world_widths,
            segments: survey.segments,
            max_depth: survey.max_depth,
            first_segments: (survey.piece_segments.iter())
                .scan(0, |before, n| {
                    let first = *before;
                    *before += n;
                    Some(first)
                })
                .collect(),
        }
    }

    /// How opaque polygon `p` is drawn ([`Lighting::opacity`]).
    fn opacity(&self, p: &crate::turtle::Polygon) -> f32 {
        match self.palette {
            // A style's palette paints its own colours.
            Some(_) => 1.0,
            None => self.lighting.opacity(p.index),
        }
    }

    /// The paint of segment `s`, the `i`th drawn: its own, or the style's.
    fn segment_paint(&self, s: &Segment, i: usize) -> Paint {
        Palette::paint_of(self.palette, s, i, self.segments, self.max_depth)
    }

    /// `p` in samples, with its depth; `None` behind a perspective's eye.
    fn to_samples(&self, p: Vec3) -> Option<[f64; 3]> {
        let (xy, z) = self.proj.project(p)?;
        let px = self.fit.to_px(xy);
        let depth = if self.proj.perspective() { -1.0 / z } else { z };
        Some([px[0] * self.ss, px[1] * self.ss, depth])
    }

    /// The drawing's labels placed in the picture's pixels.
    fn placed_labels(&self, drawing: &Drawing<'_>) -> Vec<crate::render::text::Placed> {
        (drawing.labels().iter())
            .filter_map(|l| {
                let [x, y, _] = self.to_samples(l.at)?;
                Some(crate::render::text::Placed {
                    at: [x / self.ss, y / self.ss],
                    text: l.text.clone(),
                    colour: l.colour,
                })
            })
            .collect()
    }

    fn vert(&self, p: Vec3, c: Colour) -> Option<SVert> {
        let [x, y, z] = self.to_samples(p)?;
        Some(SVert {
            x,
            y,
            z,
            c,
            uv: [0.0; 2],
        })
    }

    /// Samples per world unit at `p`.
    fn samples_per_unit(&self, p: Vec3) -> f64 {
        let z = self.proj.project(p).map_or(1.0, |r| r.1);
        self.proj.pixels_per_unit(&self.fit, z) * self.ss
    }

    /// A colour for a primitive lit with normal `n` at `p`, by the look's
    /// shading.
    fn colour(&self, kind: Kind, paint: Paint, p: Vec3, n: Vec3) -> Colour {
        match self.lighting.shading {
            Shading::Filled | Shading::Wireframe => self.shader.flat(paint),
            Shading::Flat | Shading::Smooth => {
                let v = self.proj.towards_viewer(p);
                self.shader.shade(kind, paint, p, n, v)
            }
        }
    }

    /// A screen-space line `pixels` wide, unlit.
    fn pixel_line(&self, t: &mut Target, a: Vec3, b: Vec3, pixels: f64, c: Colour) {
        let (Some(pa), Some(pb)) = (self.to_samples(a), self.to_samples(b)) else {
            return;
        };
        let half = pixels * self.ss / 2.0 + 1.0;
        if t.meets(pa[1].min(pb[1]) - half, pa[1].max(pb[1]) + half) {
            t.line(pa, pb, pixels * self.ss, c);
        }
    }
}

#[cfg(test)]
mod tests;
