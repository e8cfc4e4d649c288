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
    /// along y), the picture turned by `twist_degrees` about the line of
    /// sight.
    pub fn aimed(
        eye: [f64; 3],
        target: [f64; 3],
        twist_degrees: f64,
        perspective: Option<f64>,
    ) -> Camera {
        let d = normalised(sub(target, eye)).unwrap_or([0.0, 0.0, -1.0]);
        // World y is up unless the view looks along it; then z is.
        let world_up = if d[1].abs() > 0.999 {
            [0.0, 0.0, -d[1].signum()]
        } else {
            [0.0, 1.0, 0.0]
        };
        let right = normalised(cross(d, world_up)).unwrap_or([1.0, 0.0, 0.0]);
        let up0 = cross(right, d);
        let (s, c) = twist_degrees.to_radians().sin_cos();
        let up = [0, 1, 2].map(|k| up0[k] * c + right[k] * s);
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

/// A tropism (cpfg `tropism:`, manual §8.1.8): every step bends the heading
/// towards (or, with a negative elasticity, away from) `vector`, by the
/// turtle's elasticity times `|H × T|` (the book's §2.4: α = e |H × T|).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tropism {
    /// `T:` the direction bent towards (normalised when used).
    pub vector: [f64; 3],
    /// `A:` the angle to the vector, in degrees, the heading tends to
    /// (0: along it).
    pub angle: f64,
    /// `I:` intensity: multiplies the elasticity.
    pub intensity: f64,
    /// `E:` the initial elasticity.
    pub elasticity: f64,
    /// `S:` what `@Ts`-style modules (cpfg `@Ts(n)`/`@Te`) step the
    /// elasticity by.
    pub step: f64,
    /// A torque (`torque:`): twists the frame about H instead of bending.
    pub torque: bool,
}

/// A contour (cpfg `.con`, `contour:`): a closed (or open) planar curve,
/// the cross-section of generalized cylinders and the curve `curveX`,
/// `curveY` and `curveGAL` read.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contour {
    /// The id `@#(id)` selects.
    pub id: u32,
    /// The curve, sampled densely, as (x, y, z) in the contour's plane
    /// (z is 0 for planar contours).
    pub points: Vec<[f64; 3]>,
    pub closed: bool,
}
