//! How a picture looks beyond its lines: background, light, materials,
//! camera, tropisms and contours. The book's notations say none of this
//! (their pictures are black lines on white, seen face on); cpfg's view
//! file, colour map and material file say all of it, and the renderer
//! draws what is here whatever notation it came from.
//!
//! Colours are indexed: the turtle's colour index picks `System::colours`
//! for flat drawing and, when the look is lit, the material of the same
//! index ([`Lighting::materials`]); without materials the lit colour moves
//! along the colour map (cpfg's colour-map mode, manual §8.1.3).

use super::Rgb;
use serde::Serialize;

/// The look of a system's pictures. [`Default`] is the book's: white
/// background, flat colours, the default view.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Look {
    /// The background; `None` is white.
    pub background: Option<Rgb>,
    /// How drawn things are lit; `None` draws flat colours.
    pub lighting: Option<Lighting>,
    /// Where the picture is seen from; `None` is the default view (or
    /// [`super::Settings::view`]).
    pub camera: Option<Camera>,
    /// A scene drawn with the model, fixed in the world (cpfg's
    /// `background scene:` files).
    pub scene: Vec<ScenePolygon>,
}

impl Look {
    /// The textures of a lit look ([`Lighting::textures`]); none unlit.
    pub fn textures(&self) -> &[super::texture::Texture] {
        self.lighting.as_ref().map_or(&[], |l| &l.textures)
    }
}

/// A polygon of a [`Look::scene`], in world coordinates, with the colour
/// it has unlit and the colour index (a material of [`Lighting`]) it is
/// lit with.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScenePolygon {
    pub points: Vec<[f64; 3]>,
    pub colour: Rgb,
    pub index: u16,
}

/// How lines are drawn when the look is lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum LineStyle {
    /// Flat lines, widths in pixels (not lit).
    Pixel,
    /// Flat ribbons facing the viewer, widths in turtle units.
    Polygon,
    /// Cylinders, widths in turtle units.
    Cylinder,
}

/// How surfaces are shaded (cpfg `render mode:`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Shading {
    /// One colour per primitive, no light (cpfg `filled`, `fast`).
    Filled,
    /// Outlines only (cpfg `wireframe`).
    Wireframe,
    /// One lit colour per polygon (cpfg `flat`).
    Flat,
    /// Lit per vertex and interpolated (cpfg `shaded`, `interpolated`,
    /// `shadows`).
    Smooth,
}

/// Light and materials.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Lighting {
    pub shading: Shading,
    pub line_style: LineStyle,
    /// Whether lines and cylinders taper from one width to the next
    /// (cpfg `tapered lines:`).
    pub tapered: bool,
    pub lights: Vec<Light>,
    /// Materials by colour index; empty in colour-map mode.
    pub materials: Vec<Option<Material>>,
    /// Colour-map mode: how many colour-map entries a lit cylinder's
    /// colour moves per unit of `N·L` (cpfg `diffuse reflection:`).
    pub index_shift: f64,
    /// Colour-map mode: ambient and diffuse share of a lit surface
    /// (cpfg `surface ambient:`, `surface diffuse:`).
    pub surface_ambient: f64,
    pub surface_diffuse: f64,
    /// Whether lights cast shadows (cpfg `render mode: shadows`): such a
    /// picture is ray traced.
    pub shadows: bool,
    /// Textures, numbered from 1 by the modules that choose them (cpfg's
    /// `@Tx(n)` takes `textures[n - 1]`); cpfg maps them only on lit
    /// pictures (material mode, manual §6.7.4).
    pub textures: Vec<super::texture::Texture>,
}

impl Lighting {
    /// How opaque what is drawn with colour index `index` is: 1 but for a
    /// material with a transparency, and only where materials are lit
    /// (cpfg blends only with OpenGL's lighting on).
    pub fn opacity(&self, index: u16) -> f32 {
        let lit = matches!(self.shading, Shading::Flat | Shading::Smooth);
        match self.material(index) {
            Some(m) if lit => (1.0 - m.transparency).clamp(0.0, 1.0),
            _ => 1.0,
        }
    }

    /// The material colour index `index` is lit with, as the renderer
    /// picks it: in material mode the index's material, or cpfg's default
    /// ([`Material::CPFG_DEFAULT`]) for an index the file leaves out;
    /// `None` in colour-map mode (no materials).
    pub fn material(&self, index: u16) -> Option<&Material> {
        if self.materials.is_empty() {
            return None;
        }
        match self.materials.get(usize::from(index)) {
            Some(Some(m)) => Some(m),
            _ => Some(&Material::CPFG_DEFAULT),
        }
    }
}

impl Default for Lighting {
    fn default() -> Self {
        Lighting {
            shading: Shading::Filled,
            line_style: LineStyle::Pixel,
            tapered: true,
            lights: vec![Light::default()],
            materials: Vec::new(),
            index_shift: 10.0,
            surface_ambient: 0.15,
            surface_diffuse: 0.75,
            shadows: false,
            textures: Vec::new(),
        }
    }
}

/// A light (cpfg `light:`; `light direction:` in colour-map mode).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Light {
    /// Towards the light (directional) or the light's position (point), in
    /// world coordinates.
    pub vector: [f64; 3],
    pub directional: bool,
    pub ambient: [f32; 3],
    pub diffuse: [f32; 3],
    pub specular: [f32; 3],
}

impl Default for Light {
    fn default() -> Self {
        Light {
            vector: [0.0, 0.0, 1.0],
            directional: false,
            ambient: [1.0; 3],
            diffuse: [1.0; 3],
            specular: [1.0; 3],
        }
    }
}

/// A material (cpfg `.mat`, one entry of 15 bytes: OpenGL's material
/// model, components 0..=1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Material {
    pub ambient: [f32; 3],
    pub diffuse: [f32; 3],
    pub specular: [f32; 3],
    pub emission: [f32; 3],
    /// Specular exponent, 0..=128.
    pub shininess: f32,
    /// 0 opaque .. 1 invisible.
    pub transparency: f32,
}

impl Material {
    /// cpfg's material for an index the material file leaves out: diffuse
    /// white, no ambient, specular or emission.
    pub const CPFG_DEFAULT: Material = Material {
        ambient: [0.0; 3],
        diffuse: [1.0; 3],
        specular: [0.0; 3],
        emission: [0.0; 3],
        shininess: 0.0,
        transparency: 0.0,
    };
}

/// A camera (cpfg `viewpoint:`, `view reference point:`, `twist:`,
/// `projection:`, `view angle:`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Camera {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    /// Roughly up in the picture (made perpendicular to the view).
    pub up: [f64; 3],
    /// Perspective with this full view angle in degrees; `None` is a
    /// parallel projection.
    pub perspective: Option<f64>,
}

impl Camera {
    /// A camera at `eye` looking at `target`, world y up (z when looking
    /// along y), the picture turned clockwise on the screen by
    /// `twist_degrees` about the line of sight (cpfg's `twist:`, whose up
    /// vector `ReadViewData` turns counter-clockwise about the view normal,
    /// so that what was up leans to the right).
    pub fn aimed(
        eye: [f64; 3],
        target: [f64; 3],
        twist_degrees: f64,
        perspective: Option<f64>,
    ) -> Camera {
        let d = normalised(sub(target, eye)).unwrap_or([0.0, 0.0, -1.0]);
        // Up is world y as seen across the line of sight, however steeply
        // the view looks along y (cpfg's ReadViewData): a view from just
        // below has up nearly along x. Only a view exactly along y, where
        // y has no such part, takes z.
        let right = normalised(cross(d, [0.0, 1.0, 0.0]))
            .or_else(|| normalised(cross(d, [0.0, 0.0, -d[1].signum()])))
            .unwrap_or([1.0, 0.0, 0.0]);
        let up0 = cross(right, d);
        let (s, c) = twist_degrees.to_radians().sin_cos();
        let up = [0, 1, 2].map(|k| up0[k] * c - right[k] * s);
        Camera {
            eye,
            target,
            up,
            perspective,
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalised(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n.is_finite() && n > 1e-12).then(|| v.map(|x| x / n))
}

/// A tropism (cpfg `tropism:`, `torque:`, manual §8.1.8; the book's §2.4):
/// a pull on the turtle's frame at every step, of a strength the turtle's
/// elasticity for it gives (its state, saved and restored by branches).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tropism {
    /// The direction pulled towards (normalised when used).
    pub vector: [f64; 3],
    /// The angle to the vector, in degrees, the heading tends to (0:
    /// towards it, orthotropism; 90: across it, plagiotropism). Only
    /// [`TropismKind::Bend`] uses it.
    pub angle: f64,
    /// How strongly the vector pulls: the pull is the unit vector times
    /// this (may be negative: a pull away).
    pub intensity: f64,
    /// The initial elasticity.
    pub elasticity: f64,
    /// What an elasticity change without a value adds or takes away.
    pub step: f64,
    pub kind: TropismKind,
}

/// How a [`Tropism`] moves the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum TropismKind {
    /// Before each step, the tropisms of this kind together turn H towards
    /// their summed pull `D` (each term its elasticity times its pull,
    /// tilted by its angle) about `H × D`, by `|H × D|` radians, at most
    /// one; U and L then follow H without twisting (cpfg's movements).
    Bend,
    /// Before each step, a twist about H bringing U towards the pull's
    /// part across H, by at most one radian; H is unchanged (cpfg
    /// `torque:`).
    Torque,
    /// After each step, H turns towards the vector in the HU plane by the
    /// angle whose sine is `e (T·U)`, then in the HL plane by `e (T·L)`
    /// (cpfg's older `tropism direction:` with `initial elasticity:`).
    BendAfterStep,
}
/// A contour (cpfg `.con`): a planar curve, the cross-section of
/// generalized cylinders ([`ContourRole::CrossSection`]) or a curve
/// expressions read ([`ContourRole::Curve`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contour {
    /// The id `@#(id)` selects, or `curveX(id, t)` reads (one numbering per
    /// role).
    pub id: u32,
    pub role: ContourRole,
    /// The curve sampled at equal steps of arc length, [`CONTOUR_SAMPLES`]
    /// of them (a cross-section: as many as its file says, at most that):
    /// one point more (x, y, z) in the contour's plane (z is 0 for planar
    /// contours); a closed curve's last point is its first.
    pub points: Vec<[f64; 3]>,
    pub closed: bool,
    /// The curve's length (`curveGAL`).
    pub length: f64,
}

/// What a [`Contour`] is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ContourRole {
    /// The cross-section of generalized cylinders: a point (x, y) of it
    /// lies at `x U − y L` from the axis, times the cylinder's radius.
    CrossSection,
    /// A curve `curveX`, `curveY`, `curveZ` and `curveGAL` read.
    Curve,
}

/// How many steps of arc length a [`Contour`]'s points are apart.
pub const CONTOUR_SAMPLES: usize = 64;

impl Contour {
    /// The point at `t` of the curve's length, `t` clamped to 0..=1.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let last = self.points.len().saturating_sub(1);
        if last == 0 {
            return self.points.first().copied().unwrap_or([0.0; 3]);
        }
        let x = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) } * last as f64;
        let k = (x.floor() as usize).min(last - 1);
        let f = x - k as f64;
        let (a, b) = (self.points[k], self.points[k + 1]);
        std::array::from_fn(|i| a[i] + (b[i] - a[i]) * f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-3)
    }

    #[test]
    fn up_is_world_y_seen_across_the_line_of_sight() {
        let front = Camera::aimed([0.0, 0.0, 1.0], [0.0; 3], 0.0, None);
        assert!(close(front.up, [0.0, 1.0, 0.0]));
        // Nearly from below (07-Open-09-two-tiers): up is nearly +x.
        let below = Camera::aimed([1.1, -60.0, 0.0], [0.0; 3], 0.0, None);
        assert!(close(below.up, [0.9998, 0.0183, 0.0]), "{:?}", below.up);
        // Exactly along y: some up across the view, never NaN.
        let along = Camera::aimed([0.0, -5.0, 0.0], [0.0; 3], 0.0, None);
        let dot = along.up[1];
        assert!(along.up.iter().all(|v| v.is_finite()) && dot.abs() < 1e-9);
    }
}
