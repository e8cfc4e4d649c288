//! A ray tracer for graftal's 3D models: instancing graphs traced without
//! being expanded ([`graph`], Bekaert & Willems §3), and everything a
//! turtle draws through a flat bounding volume hierarchy ([`bvh`]). Both
//! are a [`Scene`]; [`trace`] shoots the rays: a camera (orthographic from
//! an azimuth/elevation view fitted to the scene, or a file's camera,
//! orthographic or perspective), several samples per pixel on a fixed
//! pattern, Lambert and Phong shading under one or more lights, shadow
//! rays, a background. Rows are shared among threads band by band and each
//! pixel depends on nothing but its own rays, so the bytes are the same
//! for every thread count.

pub mod bounds;
pub mod bvh;
pub mod graph;
pub mod pov;
pub mod primitive;
pub mod subtrees;
pub mod vec;

use crate::ir::graph::Finish;
use crate::ir::look::{Camera, Light};
use crate::ir::Rgb;
use primitive::Ray;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::atomic::{AtomicUsize, Ordering};
use vec::{add, cross, dot, mad, mul, normalize, sub, V3};

/// What a ray met: where along it, the unit normal facing the ray, the
/// surface's colour (linear, 0..1) and finish, and on a textured
/// triangle the texel there and how it combines with the lit colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    pub t: f64,
    pub normal: V3,
    pub colour: [f64; 3],
    pub finish: Finish,
    pub texel: Option<([f32; 4], crate::ir::texture::TextureMode)>,
}

/// The width a pixel's beam has at distance `t` along a ray from the
/// camera: `base + per_unit * t` world units (constant for an orthographic
/// camera). What is smaller is not resolved: the pixel cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    pub base: f64,
    pub per_unit: f64,
}

impl Cut {
    pub fn at(&self, t: f64) -> f64 {
        self.base + self.per_unit * t.max(0.0)
    }
}

/// A thread's working memory, reused ray after ray.
#[derive(Default)]
pub struct Scratch {
    /// A ray's list of couples, in the order they were made.
    pub(crate) couples: Vec<graph::Couple>,
    /// The couples not yet opened, nearest entry first.
    pub(crate) heap: BinaryHeap<Reverse<u128>>,
    /// A shadow ray's couples still to open, nearest last.
    pub(crate) pending: Vec<(graph::Couple, f64)>,
    /// The children of the couple just opened.
    pub(crate) children: Vec<(graph::Couple, f64)>,
    /// Nodes of a hierarchy still to visit; a couple's ancestors.
    pub(crate) stack: Vec<u32>,
}

/// Something rays can be shot at.
pub trait Scene: Sync {
    /// A box holding everything.
    fn world_box(&self) -> (V3, V3);
    /// Points whose hull holds everything, as tight as is cheap: what a
    /// parallel view is fitted to (a box's corners stick out of most
    /// figures, and off-centre them).
    fn fit_points(&self) -> Vec<V3> {
        let (lo, hi) = self.world_box();
        box_corners(lo, hi).to_vec()
    }
    /// The nearest hit with `t` in `(t_min, t_max)`.
    fn hit(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        cut: Cut,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit>;
    /// Whether anything lies on the ray between `t_min` and `t_max` (a
    /// shadow ray: the first hit will do).
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, cut: Cut, scratch: &mut Scratch) -> bool;
}

/// Where the picture is seen from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Eye {
    /// Azimuth and elevation in radians, as `--view` gives them (the
    /// rasterised pictures' projection), orthographic, fitted.
    View { azimuth: f64, elevation: f64 },
    /// A file's camera.
    Camera(Camera),
}

/// How to trace a picture.
#[derive(Clone, Debug)]
pub struct Options {
    pub width: u32,
    pub height: u32,
    pub eye: Eye,
    /// Share of the picture the scene fills, 0..=100, inside a 5% margin.
    pub scale: f64,
    /// Samples per pixel: 1, 4, 9 or 16 (a square count; others round
    /// down to one).
    pub samples: u32,
    pub background: Rgb,
    /// The lights; none: a light over the viewer's left shoulder.
    pub lights: Vec<Light>,
    pub shadows: bool,
    /// Threads; 0: every core.
    pub threads: usize,
}

impl Options {
    pub fn new(width: u32, height: u32, eye: Eye) -> Options {
        Options {
            width,
            height,
            eye,
            scale: 100.0,
            samples: 4,
            background: Rgb(255, 255, 255),
            lights: Vec::new(),
            shadows: true,
            threads: 0,
        }
    }
}

/// A camera's rays.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayCamera {
    origin: V3,
    right: V3,
    up: V3,
    forward: V3,
    /// Orthographic: world units per pixel. Perspective: the tangent of
    /// the angle a pixel spans.
    per_pixel: f64,
    perspective: bool,
    /// The picture's centre, in pixels.
    centre: [f64; 2],
}

impl RayCamera {
    /// The camera of `eye`, a parallel one fitted to hold `points`.
    pub(crate) fn new(eye: Eye, opts: &Options, points: &[V3]) -> RayCamera {
        let centre = [opts.width as f64 / 2.0, opts.height as f64 / 2.0];
        let (forward, up, eye_point, fov): (V3, V3, Option<V3>, Option<f64>) = match eye {
            Eye::View { azimuth, elevation } => {
                let (sa, ca) = azimuth.sin_cos();
                let (se, ce) = elevation.sin_cos();
                // The rasteriser's projection: right = (ca, 0, sa), up =
                // (sa se, ce, −ca se), towards the viewer (−sa ce, se, ca ce).
                let toward = [-sa * ce, se, ca * ce];
                (mul(toward, -1.0), [sa * se, ce, -ca * se], None, None)
            }
            Eye::Camera(c) => {
                let forward = normalize(sub(c.target, c.eye));
                let forward = if forward == [0.0; 3] {
                    [0.0, 0.0, -1.0]
                } else {
                    forward
                };
                let mut right = normalize(cross(forward, c.up));
                if right == [0.0; 3] {
                    right = vec::basis(forward).0;
                }
                (forward, cross(right, forward), Some(c.eye), c.perspective)
            }
        };
        let right = normalize(cross(forward, up));
        let up = cross(right, forward);
        let (lo, hi) = bounds::points_box(points.iter().copied());
        let corners = points;
        let share = opts.scale.clamp(1.0, 100.0) / 100.0;
        let room = [
            opts.width as f64 * 0.9 * share,
            opts.height as f64 * 0.9 * share,
        ];
        if let (Some(eye_point), Some(fov)) = (eye_point, fov) {
            let per_pixel = (fov.to_radians() / 2.0).tan() * 2.0 / opts.height.max(1) as f64;
            return RayCamera {
                origin: eye_point,
                right,
                up,
                forward,
                per_pixel,
                perspective: true,
                centre,
            };
        }
        let span = |axis: V3| {
            let d: Vec<f64> = corners.iter().map(|p| dot(*p, axis)).collect();
            let (a, b) = d
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(*x), b.max(*x))
                });
            (a, b)
        };
        let (x0, x1) = span(right);
        let (y0, y1) = span(up);
        let (z0, _) = span(forward);
        let per_pixel = ((x1 - x0) / room[0]).max((y1 - y0) / room[1]);
        let per_pixel = if per_pixel > 0.0 && per_pixel.is_finite() {
            per_pixel
        } else {
            1.0
        };
        // Parallel rays start on a plane behind everything, their axis
        // through the middle of the scene as the view sees it.
        let mid = add(mul(right, (x0 + x1) / 2.0), mul(up, (y0 + y1) / 2.0));
        let depth = vec::length(sub(hi, lo)).max(1e-9);
        let origin = mad(mid, forward, z0 - 0.01 * depth);
        RayCamera {
            origin,
            right,
            up,
            forward,
            per_pixel,
            perspective: false,
            centre,
        }
    }

    /// The ray through the picture point (x right, y down, in pixels).
    fn ray(&self, x: f64, y: f64) -> Ray {
        let dx = (x - self.centre[0]) * self.per_pixel;
        let dy = (self.centre[1] - y) * self.per_pixel;
        if self.perspective {
            let dir = add(self.forward, add(mul(self.right, dx), mul(self.up, dy)));
            Ray {
                origin: self.origin,
                dir: normalize(dir),
            }
        } else {
            let origin = add(self.origin, add(mul(self.right, dx), mul(self.up, dy)));
            Ray {
                origin,
                dir: self.forward,
            }
        }
    }

    pub(crate) fn cut(&self) -> Cut {
        if self.perspective {
            Cut {
                base: 0.0,
                per_unit: self.per_pixel,
            }
        } else {
            Cut {
                base: self.per_pixel,
                per_unit: 0.0,
            }
        }
    }
}

/// A colour from 0..255 to 0..1 (graftal's pictures mix colours in the
/// space they are given in, as the rasteriser does).
pub fn linear(c: Rgb) -> [f64; 3] {
    [c.0, c.1, c.2].map(|v| v as f64 / 255.0)
}

/// The lights of a picture: the file's, else a white light over the
/// viewer's left shoulder with a little ambient.
pub(crate) fn lights_for(opts: &Options, cam: &RayCamera) -> Vec<Light> {
    if !opts.lights.is_empty() {
        return opts.lights.clone();
    }
    let toward = mul(cam.forward, -1.0);
    let dir = normalize(add(toward, add(mul(cam.up, 0.9), mul(cam.right, -0.6))));
    vec![Light {
        vector: dir,
        directional: true,
        ambient: [1.0; 3],
        diffuse: [0.85; 3],
        specular: [0.6; 3],
    }]
}

/// The colour a hit shows: each light's ambient part, and its diffuse
/// (Lambert) and specular (Phong) parts where no shadow ray is blocked.
fn shade(
    scene: &dyn Scene,
    ray: &Ray,
    hit: &SurfaceHit,
    lights: &[Light],
    shadows: bool,
    cut: Cut,
    scratch: &mut Scratch,
) -> [f64; 3] {
    let dir = normalize(ray.dir);
    let p = mad(ray.origin, ray.dir, hit.t);
    let n = primitive::facing(hit.normal, dir);
    let scale = vec::length(p).max(1.0);
    let eps = 1e-7 * scale + cut.at(hit.t) * 1e-3;
    let from = mad(p, n, eps);
    let f = hit.finish;
    let mut out = [0.0; 3];
    for light in lights {
        for (k, o) in out.iter_mut().enumerate() {
            *o += f.ambient * light.ambient[k] as f64 * hit.colour[k];
        }
        let (to_light, distance) = if light.directional {
            (normalize(light.vector), f64::INFINITY)
        } else {
            let d = sub(light.vector, p);
            (normalize(d), vec::length(d))
        };
        let lambert = dot(n, to_light);
        if lambert <= 0.0 {
            continue;
        }
        if shadows {
            let shadow = Ray {
                origin: from,
                dir: to_light,
            };
            if scene.occluded(&shadow, 0.0, distance, cut, scratch) {
                continue;
            }
        }
        let reflected = sub(mul(n, 2.0 * lambert), to_light);
        let phong = dot(reflected, mul(dir, -1.0))
            .max(0.0)
            .powf(f.shininess.max(1.0));
        for (k, o) in out.iter_mut().enumerate() {
            *o += f.diffuse * lambert * light.diffuse[k] as f64 * hit.colour[k]
                + f.specular * phong * light.specular[k] as f64;
        }
    }
    match hit.texel {
        // The texel on the lit colour, as the z-buffer lays it.
        Some((texel, mode)) => {
            let lit = [out[0] as f32, out[1] as f32, out[2] as f32, 1.0];
            let c = mode.apply(lit, texel);
            [c[0], c[1], c[2]].map(f64::from)
        }
        None => out,
    }
}

/// The sample offsets within a pixel: a fixed `k × k` grid.
fn sample_offsets(samples: u32) -> Vec<[f64; 2]> {
    let k = (samples.max(1) as f64).sqrt().floor().max(1.0) as usize;
    (0..k * k)
        .map(|i| {
            [
                ((i % k) as f64 + 0.5) / k as f64,
                ((i / k) as f64 + 0.5) / k as f64,
            ]
        })
        .collect()
}

/// Rows a thread takes at a time.
const BAND: usize = 8;

/// The picture: RGBA, row by row.
pub fn trace(scene: &dyn Scene, opts: &Options) -> Vec<u8> {
    let (w, h) = (opts.width as usize, opts.height as usize);
    let cam = RayCamera::new(opts.eye, opts, &scene.fit_points());
    let lights = lights_for(opts, &cam);
    let offsets = sample_offsets(opts.samples);
    let bands = h.div_ceil(BAND);
    let next = AtomicUsize::new(0);
    let threads = crate::parallel::threads(opts.threads).min(bands.max(1));
    let bg = linear(opts.background);
    let work = || {
        let mut scratch = Scratch::default();
        let mut done: Vec<(usize, Vec<u8>)> = Vec::new();
        loop {
            let band = next.fetch_add(1, Ordering::Relaxed);
            if band >= bands {
                return done;
            }
            let rows = band * BAND..((band + 1) * BAND).min(h);
            let mut px = Vec::with_capacity(rows.len() * w * 4);
            for y in rows {
                for x in 0..w {
                    let mut sum = [0.0; 3];
                    for o in &offsets {
                        let ray = cam.ray(x as f64 + o[0], y as f64 + o[1]);
                        let c = match scene.hit(&ray, 0.0, f64::INFINITY, cam.cut(), &mut scratch) {
                            Some(hit) => shade(
                                scene,
                                &ray,
                                &hit,
                                &lights,
                                opts.shadows,
                                cam.cut(),
                                &mut scratch,
                            ),
                            None => bg,
                        };
                        sum = add(sum, c);
                    }
                    let n = offsets.len() as f64;
                    px.extend(sum.map(|c| (c / n).clamp(0.0, 1.0).mul_add(255.0, 0.5) as u8));
                    px.push(255);
                }
            }
            done.push((band, px));
        }
    };
    let mut parts: Vec<(usize, Vec<u8>)> = if threads <= 1 {
        work()
    } else {
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads).map(|_| s.spawn(work)).collect();
            handles
                .into_iter()
                .flat_map(|h| h.join().expect("a tracing thread panicked"))
                .collect()
        })
    };
    parts.sort_by_key(|(band, _)| *band);
    parts.into_iter().flat_map(|(_, px)| px).collect()
}

/// A traced picture as PNG bytes.
pub fn png(rgba: Vec<u8>, width: u32, height: u32) -> Option<Vec<u8>> {
    let size = tiny_skia::IntSize::from_wh(width, height)?;
    tiny_skia::Pixmap::from_vec(rgba, size)?.encode_png().ok()
}

/// The corners of a box.
pub fn box_corners(lo: V3, hi: V3) -> [V3; 8] {
    std::array::from_fn(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
}

/// The world size of a pixel at the middle of a scene that `points` hold,
/// seen as `opts` say: what widths given in pixels are made of.
pub fn pixel_size(points: &[V3], opts: &Options) -> f64 {
    let cam = RayCamera::new(opts.eye, opts, points);
    let (lo, hi) = bounds::points_box(points.iter().copied());
    let middle = mul(add(lo, hi), 0.5);
    let along = dot(sub(middle, cam.origin), cam.forward).max(0.0);
    cam.cut().at(along)
}

/// An SVG that shows a traced picture: the PNG inside, as a data URL.
pub fn svg_of_png(png: &[u8], width: u32, height: u32) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">\n<image width=\"{width}\" height=\"{height}\" \
         href=\"data:image/png;base64,{}\"/>\n</svg>\n",
        base64(png)
    )
}

/// Standard base64 with padding (RFC 4648).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_is_rfc_4648() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }
}
