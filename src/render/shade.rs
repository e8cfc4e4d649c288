//! Lighting as cpfg's OpenGL fixed function does it (manual §8.1.3).
//!
//! - Material mode (the look has materials): emission + global ambient ·
//!   material ambient + Σ over lights of ambient·ambient +
//!   diffuse·diffuse·max(0, N·L) + specular·specular·max(0, N·H)^shininess,
//!   clamped to 0..=1. The global ambient is OpenGL's default light-model
//!   ambient (0.2). An index without a material gets cpfg's default
//!   material (diffuse white, no ambient, specular or emission).
//!   Transparency is ignored: cpfg reads it but does not blend ("so far
//!   ignored" in its source), so neither does this.
//! - Colour-map mode (no materials): the colour index moves along the
//!   colour map: lines (cylinders, ribbons, spheres) by `index_shift·N·L`,
//!   surfaces to `64·int·(a + d·|N·L|)` within their block of 64 entries,
//!   int = col/64 − floor(col/64). Only the first light counts, as a
//!   direction (cpfg normalises its position).
//!
//! Normals arrive facing the viewer where the primitive is two-sided.

use super::camera::{dot, unit};
use crate::ir::look::{Light, Lighting, Material};
use crate::ir::Rgb;
use crate::turtle::Vec3;

/// An RGB colour, components 0..=1.
pub type Colour = [f32; 3];

/// OpenGL's default `GL_LIGHT_MODEL_AMBIENT`.
const GLOBAL_AMBIENT: f32 = 0.2;

/// What is being lit: the colour-map formulas differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Lines drawn as cylinders or ribbons, spheres, polygons and the
    /// tubes of generalized cylinders: the index moves by `index_shift · N·L`.
    Line,
    /// Surfaces (`~`): the index scales within its block of 64.
    Surface,
}

/// What a primitive is painted with: its own colour (and colour-map index
/// or material), or a colour the style gives it (`--palette`), which is
/// lit by how much it faces the first light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Paint {
    Own { colour: Rgb, index: u16 },
    Style(Rgb),
}

impl Paint {
    pub fn own(colour: Rgb, index: u16) -> Paint {
        Paint::Own { colour, index }
    }

    /// The colour painted where nothing is lit.
    pub fn colour(self) -> Rgb {
        match self {
            Paint::Own { colour, .. } | Paint::Style(colour) => colour,
        }
    }
}

/// The share of a style colour's brightness left on a side facing away
/// from the light, so that lit shapes keep their relief in any palette.
const STYLE_AMBIENT: f64 = 0.45;

impl Kind {
    /// How a polygon is lit.
    pub fn of(p: &crate::turtle::Polygon) -> Kind {
        if p.surface {
            Kind::Surface
        } else {
            Kind::Line
        }
    }
}

pub fn to_colour(c: Rgb) -> Colour {
    [c.0 as f32 / 255.0, c.1 as f32 / 255.0, c.2 as f32 / 255.0]
}

/// Colours of lit and unlit primitives.
pub struct Shader<'a> {
    lighting: &'a Lighting,
    palette: &'a [Rgb],
    /// The first light's direction (colour-map mode).
    first_light: Vec3,
    lights: Vec<Light>,
}

impl<'a> Shader<'a> {
    /// The shader of `lighting`, whose colour map is `palette` (never
    /// empty); with no light, one shines from `towards_viewer`.
    pub fn new(lighting: &'a Lighting, palette: &'a [Rgb], towards_viewer: Vec3) -> Self {
        let mut lights: Vec<Light> = lighting
            .lights
            .iter()
            .filter(|l| l.vector.iter().all(|c| c.is_finite()))
            .copied()
            .collect();
        if lights.is_empty() {
            lights.push(Light {
                vector: towards_viewer,
                directional: true,
                ..Light::default()
            });
        }
        let first_light = unit(lights[0].vector).unwrap_or(towards_viewer);
        Shader {
            lighting,
            palette,
            first_light,
            lights,
        }
    }

    fn palette_at(&self, index: i64) -> Colour {
        let last = self.palette.len() as i64 - 1;
        to_colour(self.palette[index.clamp(0, last.max(0)) as usize])
    }

    /// The unlit colour (cpfg `filled`): the material's diffuse colour, else
    /// the palette colour.
    pub fn unlit(&self, colour: Rgb, index: u16) -> Colour {
        match self.lighting.material(index) {
            Some(m) => m.diffuse,
            None => to_colour(colour),
        }
    }

    /// [`Shader::unlit`] of `paint`: a style colour as it is.
    pub fn flat(&self, paint: Paint) -> Colour {
        match paint {
            Paint::Own { colour, index } => self.unlit(colour, index),
            Paint::Style(c) => to_colour(c),
        }
    }

    /// [`Shader::lit`] of `paint`: a style colour dimmed by how far `n`
    /// turns from the first light.
    pub fn shade(&self, kind: Kind, paint: Paint, p: Vec3, n: Vec3, v: Vec3) -> Colour {
        match paint {
            Paint::Own { index, .. } => self.lit(kind, index, p, n, v),
            Paint::Style(c) => {
                let ndl = dot(n, self.first_light);
                let ndl = if ndl.is_finite() { ndl.max(0.0) } else { 0.0 };
                let k = (STYLE_AMBIENT + (1.0 - STYLE_AMBIENT) * ndl) as f32;
                to_colour(c).map(|x| x * k)
            }
        }
    }

    /// The lit colour at `p` with unit normal `n` (facing the viewer for a
    /// two-sided primitive), seen along `v` (unit, towards the viewer).
    pub fn lit(&self, kind: Kind, index: u16, p: Vec3, n: Vec3, v: Vec3) -> Colour {
        if let Some(m) = self.lighting.material(index) {
            return self.material_colour(m, p, n, v);
        }
        let ndl = dot(n, self.first_light);
        let index = i64::from(index);
        match kind {
            Kind::Line => {
                let shift = self.lighting.index_shift * ndl;
                let shift = if shift.is_finite() { shift as i64 } else { 0 };
                self.palette_at(index + shift)
            }
            Kind::Surface => {
                let (a, d) = (self.lighting.surface_ambient, self.lighting.surface_diffuse);
                let within = (index % 64) as f64 * (a + d * ndl.abs());
                let within = if within.is_finite() {
                    within.clamp(0.0, 63.0)
                } else {
                    0.0
                };
                self.palette_at(index - index % 64 + within as i64)
            }
        }
    }

    fn material_colour(&self, m: &Material, p: Vec3, n: Vec3, v: Vec3) -> Colour {
        let mut c: Colour = [0, 1, 2].map(|k| m.emission[k] + GLOBAL_AMBIENT * m.ambient[k]);
        for light in &self.lights {
            let l = if light.directional {
                unit(light.vector)
            } else {
                unit(super::camera::sub(light.vector, p))
            };
            let Some(l) = l else { continue };
            let ndl = dot(n, l).max(0.0) as f32;
            let spec = if ndl > 0.0 && m.specular.iter().any(|s| *s > 0.0) {
                let h = unit([l[0] + v[0], l[1] + v[1], l[2] + v[2]]).unwrap_or(n);
                (dot(n, h).max(0.0) as f32).powf(m.shininess.clamp(0.0, 128.0))
            } else {
                0.0
            };
            for (k, ck) in c.iter_mut().enumerate() {
                *ck += m.ambient[k] * light.ambient[k]
                    + m.diffuse[k] * light.diffuse[k] * ndl
                    + m.specular[k] * light.specular[k] * spec;
            }
        }
        c.map(|x| {
            if x.is_finite() {
                x.clamp(0.0, 1.0)
            } else {
                0.0
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Vec<Rgb> {
        (0..=255).map(|i| Rgb(i as u8, i as u8, i as u8)).collect()
    }

    fn colour_map(light: Vec3) -> Lighting {
        Lighting {
            lights: vec![Light {
                vector: light,
                directional: true,
                ..Light::default()
            }],
            ..Lighting::default()
        }
    }

    #[test]
    fn colour_map_lines_move_the_index_by_the_shift_times_n_dot_l() {
        let lighting = colour_map([0.0, 0.0, 1.0]);
        let palette = ramp();
        let sh = Shader::new(&lighting, &palette, [0.0, 0.0, 1.0]);
        let at = |n: Vec3| sh.lit(Kind::Line, 100, [0.0; 3], n, [0.0, 0.0, 1.0])[0] * 255.0;
        assert_eq!(at([0.0, 0.0, 1.0]).round(), 110.0);
        assert_eq!(at([1.0, 0.0, 0.0]).round(), 100.0);
        assert_eq!(at([0.0, 0.0, -1.0]).round(), 90.0);
    }

    #[test]
    fn polygons_are_lit_as_lines_and_surfaces_as_surfaces() {
        let lighting = colour_map([0.0, 0.0, 1.0]);
        let palette = ramp();
        let sh = Shader::new(&lighting, &palette, [0.0, 0.0, 1.0]);
        let polygon = |surface| crate::turtle::Polygon {
            points: Vec::new(),
            colour: Rgb(0, 0, 0),
            index: 63,
            surface,
            texture: None,
        };
        let lit = |p: &crate::turtle::Polygon| {
            let c = sh.lit(
                Kind::of(p),
                p.index,
                [0.0; 3],
                [0.0, 0.0, 1.0],
                [0.0, 0.0, 1.0],
            );
            (c[0] * 255.0).round()
        };
        // A `{…}` polygon facing the light: 63 + 10, past its block (cpfg's
        // mycelis petals stay yellow); a surface: 63 · 0.9 within it.
        assert_eq!(lit(&polygon(false)), 73.0);
        assert_eq!(lit(&polygon(true)), 56.0);
    }

    #[test]
    fn colour_map_surfaces_scale_the_index_within_its_block() {
        let lighting = colour_map([0.0, 0.0, 1.0]);
        let palette = ramp();
        let sh = Shader::new(&lighting, &palette, [0.0, 0.0, 1.0]);
        // Index 64 + 40: lit face on, 40 · (0.15 + 0.75) = 36 into the block.
        let c = sh.lit(
            Kind::Surface,
            104,
            [0.0; 3],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
        );
        assert_eq!((c[0] * 255.0).round(), 100.0);
        // Edge on: only the ambient share, 40 · 0.15 = 6.
        let c = sh.lit(
            Kind::Surface,
            104,
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        );
        assert_eq!((c[0] * 255.0).round(), 70.0);
    }

    #[test]
    fn materials_follow_opengl() {
        let red = Material {
            ambient: [0.0; 3],
            diffuse: [1.0, 0.0, 0.0],
            specular: [0.0; 3],
            emission: [0.0, 0.0, 0.25],
            shininess: 0.0,
            transparency: 0.0,
        };
        let lighting = Lighting {
            materials: vec![None, Some(red)],
            ..colour_map([0.0, 0.0, 1.0])
        };
        let palette = ramp();
        let sh = Shader::new(&lighting, &palette, [0.0, 0.0, 1.0]);
        let n = unit([0.0, 1.0, 1.0]).unwrap();
        let c = sh.lit(Kind::Surface, 1, [0.0; 3], n, [0.0, 0.0, 1.0]);
        assert!(
            (c[0] - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-5,
            "{c:?}"
        );
        assert_eq!((c[1], c[2]), (0.0, 0.25));
        // Index 0 has no material: cpfg's default, diffuse white.
        let c = sh.lit(Kind::Surface, 0, [0.0; 3], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]);
        assert_eq!(c, [1.0; 3]);
        assert_eq!(sh.unlit(Rgb(1, 2, 3), 1), [1.0, 0.0, 0.0]);
    }

    #[test]
    fn without_lights_the_light_is_at_the_viewer() {
        let lighting = Lighting {
            lights: Vec::new(),
            materials: vec![None],
            ..Lighting::default()
        };
        let palette = ramp();
        let sh = Shader::new(&lighting, &palette, [1.0, 0.0, 0.0]);
        let facing = sh.lit(Kind::Line, 0, [0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let away = sh.lit(Kind::Line, 0, [0.0; 3], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        assert!(facing[0] > away[0]);
    }
}
