//! Textures: images mapped on surfaces, polygons and cylinders (cpfg's
//! `texture:` view command and `@Tx` module, manual §6.7.4 and §8.1.7).
//!
//! An [`Image`] is decoded pixels; a [`Texture`] is an image with the way
//! cpfg applies it (its filter, how it combines with the lit colour, how
//! surfaces and cylinders spread it). Texture coordinates (u, v) follow
//! OpenGL's: u along a row from the image's left edge, v up from its
//! bottom row, the image repeated outside 0..1 (cpfg's `GL_REPEAT`).
//! Every notation could carry textures: they live in the look
//! ([`super::look::Look::textures`]), primitives name one by index.

use serde::{Serialize, Serializer};
use std::sync::Arc;

/// Decoded pixels, RGBA with 8 bits a channel, rows from the bottom of
/// the picture up (as OpenGL and SGI files keep them).
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

impl Image {
    /// An image of `width × height` pixels from its RGBA bytes, bottom
    /// row first; `None` when the sizes do not match or either is 0.
    pub fn new(width: u32, height: u32, rgba: Vec<u8>) -> Option<Image> {
        let len = (width as usize)
            .checked_mul(height as usize)?
            .checked_mul(4)?;
        (width > 0 && height > 0 && rgba.len() == len).then_some(Image {
            width,
            height,
            rgba,
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The RGBA bytes, bottom row first.
    pub fn rgba(&self) -> &[u8] {
        &self.rgba
    }

    /// The texel in column `x`, row `y` counted from the bottom, each
    /// wrapped into the image (cpfg repeats its textures).
    pub fn texel(&self, x: i64, y: i64) -> [u8; 4] {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = y.rem_euclid(i64::from(self.height)) as usize;
        let at = (y * self.width as usize + x) * 4;
        let mut px = [0; 4];
        px.copy_from_slice(&self.rgba[at..at + 4]);
        px
    }

    /// The colour at texture coordinates (u, v), components 0..=1:
    /// the nearest texel, or bilinear between the four nearest, the image
    /// repeated in both directions. Coordinates that are not finite read
    /// the texel at the origin.
    pub fn sample(&self, u: f64, v: f64, filter: Filter) -> [f32; 4] {
        let (u, v) = (finite_or_zero(u), finite_or_zero(v));
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let unit = |px: [u8; 4]| px.map(|c| f32::from(c) / 255.0);
        match filter {
            Filter::Nearest => unit(self.texel(
                wrapped_floor(u * w, self.width),
                wrapped_floor(v * h, self.height),
            )),
            Filter::Linear => {
                // Texel centres lie at half-integers: OpenGL's linear filter.
                let (x, y) = (u * w - 0.5, v * h - 0.5);
                let (x0, y0) = (wrapped_floor(x, self.width), wrapped_floor(y, self.height));
                let (fx, fy) = ((x - x.floor()) as f32, (y - y.floor()) as f32);
                let (a, b) = (self.texel(x0, y0), self.texel(x0 + 1, y0));
                let (c, d) = (self.texel(x0, y0 + 1), self.texel(x0 + 1, y0 + 1));
                std::array::from_fn(|k| {
                    let low = f32::from(a[k]) * (1.0 - fx) + f32::from(b[k]) * fx;
                    let high = f32::from(c[k]) * (1.0 - fx) + f32::from(d[k]) * fx;
                    (low * (1.0 - fy) + high * fy) / 255.0
                })
            }
        }
    }

    /// The mean colour of the image (0..=1), alpha included: what a
    /// picture that cannot map the image shows instead.
    pub fn mean(&self) -> [f32; 4] {
        let mut sum = [0u64; 4];
        for px in self.rgba.chunks_exact(4) {
            for k in 0..4 {
                sum[k] += u64::from(px[k]);
            }
        }
        let n = (self.rgba.len() / 4).max(1) as f64;
        sum.map(|s| (s as f64 / n / 255.0) as f32)
    }

    /// The mean colour of the texels that show (alpha 0.5 or more: those
    /// the alpha test keeps), opaque; [`Image::mean`] when none shows.
    pub fn mean_shown(&self) -> [f32; 4] {
        let mut sum = [0u64; 3];
        let mut n = 0u64;
        for px in self.rgba.chunks_exact(4).filter(|px| px[3] >= 128) {
            for k in 0..3 {
                sum[k] += u64::from(px[k]);
            }
            n += 1;
        }
        if n == 0 {
            return self.mean();
        }
        let [r, g, b] = sum.map(|s| (s as f64 / n as f64 / 255.0) as f32);
        [r, g, b, 1.0]
    }
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

/// `floor(x)` as a texel index, reduced into `0..size` first so that huge
/// coordinates cannot overflow.
fn wrapped_floor(x: f64, size: u32) -> i64 {
    let size = f64::from(size);
    (x.rem_euclid(size).floor() as i64).min(size as i64 - 1)
}

/// How a texture's texels are read between their centres (cpfg's `H:`,
/// OpenGL's magnification filter).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum Filter {
    /// The nearest texel: texels show as squares (cpfg `near`, the default).
    #[default]
    Nearest,
    /// Bilinear between the four nearest texels (cpfg `linear`).
    Linear,
}

/// How a texel combines with the colour of what it lies on (cpfg's `E:`,
/// OpenGL's texture environment).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum TextureMode {
    /// Texel times the lit colour, alphas multiplied (cpfg `modulate`,
    /// the default).
    #[default]
    Modulate,
    /// The texel over the lit colour by the texel's alpha (cpfg `decal`).
    Decal,
    /// The lit colour darkened by the texel: `lit × (1 − texel)`, OpenGL's
    /// blend with its default (black) environment colour (cpfg `blend`).
    Blend,
}

impl TextureMode {
    /// The colour of a lit fragment `lit` (RGBA, 0..=1) under `texel`.
    pub fn apply(self, lit: [f32; 4], texel: [f32; 4]) -> [f32; 4] {
        match self {
            TextureMode::Modulate => std::array::from_fn(|k| lit[k] * texel[k]),
            TextureMode::Decal => {
                let a = texel[3];
                let mut out: [f32; 4] = std::array::from_fn(|k| lit[k] * (1.0 - a) + texel[k] * a);
                out[3] = lit[3];
                out
            }
            TextureMode::Blend => {
                let mut out: [f32; 4] = std::array::from_fn(|k| lit[k] * (1.0 - texel[k]));
                out[3] = lit[3] * texel[3];
                out
            }
        }
    }
}

/// A texture: an image and how it is applied.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Texture {
    /// The image's file, as the source names it.
    pub file: String,
    /// The decoded image; `None` when the file is missing or unreadable
    /// (what it textures is then drawn untextured, as cpfg draws it).
    #[serde(serialize_with = "image_size")]
    pub image: Option<Arc<Image>>,
    pub filter: Filter,
    pub mode: TextureMode,
    /// Whether a surface takes the image once across its whole extent
    /// (cpfg's `S:`) rather than once on each of its patches.
    pub per_surface: bool,
    /// The aspect ratio on cylinders (cpfg's `R:`): greater stretches the
    /// image along the cylinder.
    pub ratio: f64,
}

impl Texture {
    /// A texture of `file` with cpfg's defaults: nearest texels, modulate,
    /// per patch, ratio 1.
    pub fn new(file: impl Into<String>, image: Option<Arc<Image>>) -> Texture {
        Texture {
            file: file.into(),
            image,
            filter: Filter::Nearest,
            mode: TextureMode::Modulate,
            per_surface: false,
            ratio: 1.0,
        }
    }

    /// The lit colour `lit` of a fragment at (u, v) with this texture on
    /// it; `lit` itself when the image is missing.
    pub fn shade(&self, lit: [f32; 4], u: f64, v: f64) -> [f32; 4] {
        match &self.image {
            Some(image) => self.mode.apply(lit, image.sample(u, v, self.filter)),
            None => lit,
        }
    }

    /// How far along a cylinder of `width` the image's v moves over
    /// `length`: once around the cylinder's girth spans the image's width,
    /// so the image keeps its proportions, stretched by [`Texture::ratio`]
    /// (cpfg's texture step along generalized cylinders).
    pub fn v_along(&self, width: f64, length: f64) -> f64 {
        let Some(image) = &self.image else {
            return 0.0;
        };
        let girth = std::f64::consts::PI * width;
        if girth <= 0.0 || self.ratio.is_nan() || self.ratio <= 0.0 {
            return 0.0;
        }
        let v = length / girth * f64::from(image.width) / f64::from(image.height) / self.ratio;
        finite_or_zero(v)
    }
}

/// A texture's image is written out as its size only (the pixels stay in
/// the image file).
fn image_size<S: Serializer>(image: &Option<Arc<Image>>, s: S) -> Result<S::Ok, S::Error> {
    image.as_ref().map(|i| [i.width, i.height]).serialize(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2: black, white / red, green (bottom row first).
    fn checker() -> Image {
        let rgba = vec![
            0, 0, 0, 255, 255, 255, 255, 255, // bottom: black, white
            255, 0, 0, 255, 0, 255, 0, 255, // top: red, green
        ];
        Image::new(2, 2, rgba).unwrap()
    }

    #[test]
    fn nearest_reads_the_texel_under_the_coordinates_and_repeats() {
        let im = checker();
        let px = |u, v| im.sample(u, v, Filter::Nearest);
        assert_eq!(px(0.25, 0.25), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(px(0.75, 0.25), [1.0, 1.0, 1.0, 1.0]);
        assert_eq!(px(0.25, 0.75), [1.0, 0.0, 0.0, 1.0]);
        // GL_REPEAT: one image further along in each direction, and back.
        assert_eq!(px(1.75, -0.75), px(0.75, 0.25));
        assert_eq!(px(-0.25, 2.75), [0.0, 1.0, 0.0, 1.0]);
        // Not finite: the origin's texel, never a panic.
        assert_eq!(px(f64::NAN, f64::INFINITY), px(0.0, 0.0));
        assert_eq!(px(1e300, -1e300).len(), 4);
    }

    #[test]
    fn linear_blends_the_four_nearest_texels_across_the_seam() {
        let im = checker();
        let px = |u, v| im.sample(u, v, Filter::Linear);
        // On a texel's centre: that texel exactly.
        assert_eq!(px(0.25, 0.25), [0.0, 0.0, 0.0, 1.0]);
        // Half way between the bottom row's centres: grey.
        let mid = px(0.5, 0.25);
        assert!((mid[0] - 0.5).abs() < 1e-6 && (mid[2] - 0.5).abs() < 1e-6);
        // The middle of the image: the mean of all four.
        let all = px(0.5, 0.5);
        let want = [0.5, 0.5, 0.25, 1.0];
        assert!((0..4).all(|k| (all[k] - want[k]).abs() < 1e-6), "{all:?}");
        // At u = 0 the left column blends with the right one (repeat).
        let edge = px(0.0, 0.25);
        assert!((edge[0] - 0.5).abs() < 1e-6, "{edge:?}");
    }

    #[test]
    fn modes_combine_as_opengl_texture_environments() {
        let lit = [0.5, 1.0, 0.2, 1.0];
        let texel = [0.5, 0.5, 1.0, 0.5];
        assert_eq!(
            TextureMode::Modulate.apply(lit, texel),
            [0.25, 0.5, 0.2, 0.5]
        );
        assert_eq!(TextureMode::Decal.apply(lit, texel), [0.5, 0.75, 0.6, 1.0]);
        assert_eq!(TextureMode::Blend.apply(lit, texel), [0.25, 0.5, 0.0, 0.5]);
    }

    #[test]
    fn images_of_the_wrong_size_are_refused_and_missing_ones_leave_the_colour() {
        assert!(Image::new(2, 2, vec![0; 15]).is_none());
        assert!(Image::new(0, 2, Vec::new()).is_none());
        assert!(Image::new(u32::MAX, u32::MAX, Vec::new()).is_none());
        let im = Image::new(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 0]).unwrap();
        assert_eq!(im.mean_shown(), [1.0, 0.0, 0.0, 1.0]);
        let missing = Texture::new("gone.png", None);
        assert_eq!(
            missing.shade([0.1, 0.2, 0.3, 1.0], 0.5, 0.5),
            [0.1, 0.2, 0.3, 1.0]
        );
        assert_eq!(missing.v_along(1.0, 1.0), 0.0);
    }

    #[test]
    fn cylinders_keep_the_image_proportions_stretched_by_the_ratio() {
        let mut t = Texture::new("c.png", Some(Arc::new(checker())));
        let girth = std::f64::consts::PI;
        assert!((t.v_along(1.0, girth) - 1.0).abs() < 1e-12);
        t.ratio = 2.0;
        assert!((t.v_along(1.0, girth) - 0.5).abs() < 1e-12);
        assert_eq!(t.v_along(0.0, 1.0), 0.0);
    }
}
