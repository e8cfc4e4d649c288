//! cpfg's background scenes (`background scene:` in a view file): a small
//! OpenGL-like language of materials, a matrix stack and primitives, read
//! after the C preprocessor as cpfg's `background.c` reads it, and turned
//! into world-space polygons drawn with the model.
//!
//! Keywords are matched exactly; each takes the numbers that follow it up
//! to the next word. Transforms compose as OpenGL's do (the last written
//! applies to an object first). `sphere r` is centred at the origin;
//! `cylinder r h` and `cone r1 r2 h` run along +y from 0 to h, capped;
//! `prism w h d` (or `box`) is the box [0,w]×[0,h]×[0,d]; `polygon` and
//! `polygonuv` (with a normal per vertex) take their points; `rectangle w h
//! [x y [k]]` lies in z = 0; `mesh` reads points in pairs `a0 b0 a1 b1 …`,
//! a strip of quads `(a_k, a_k+1, b_k+1, b_k)`.

use super::look::flat_colour;
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::look::{Material, ScenePolygon};
use crate::ir::Span;
use crate::scene;

/// The polygons of a scene, and the materials they use (each polygon's
/// `index` counts from `first_index` up over `materials`).
#[derive(Debug, Default)]
pub struct Scene {
    pub polygons: Vec<ScenePolygon>,
    pub materials: Vec<Material>,
}

/// One keyword and the numbers after it.
struct Command<'a> {
    word: &'a str,
    numbers: Vec<f64>,
    span: Span,
}

/// The words of `text` with their byte spans.
fn words(text: &str) -> impl Iterator<Item = (&str, Span)> {
    text.split_ascii_whitespace().map(move |w| {
        let start = w.as_ptr() as usize - text.as_ptr() as usize;
        (w, start..start + w.len())
    })
}

fn commands(text: &str) -> Vec<Command<'_>> {
    let mut out: Vec<Command> = Vec::new();
    for (w, span) in words(text) {
        match (w.parse::<f64>(), out.last_mut()) {
            (Ok(x), Some(c)) if x.is_finite() => {
                c.numbers.push(x);
                c.span.end = span.end;
            }
            _ => out.push(Command {
                word: w,
                numbers: Vec::new(),
                span,
            }),
        }
    }
    out
}

/// What a scene is being drawn with: the shapes so far and the
/// materials.
struct Drawing {
    shapes: scene::Builder,
    materials: Vec<Material>,
    /// The colour index of the first material of this scene.
    first_index: u16,
    /// The material in force (its index), `None` before the first.
    material: Option<u16>,
    tapered: bool,
}

impl Drawing {
    fn material(&mut self, n: &[f64]) {
        let mut m = self
            .material
            .and_then(|i| self.materials.get(usize::from(i - self.first_index)))
            .copied()
            .unwrap_or(Material::CPFG_DEFAULT);
        let group = |k: usize| -> Option<[f32; 3]> {
            let g = n.get(4 * k..4 * k + 3)?;
            Some([g[0] as f32, g[1] as f32, g[2] as f32])
        };
        m.ambient = group(0).unwrap_or(m.ambient);
        m.diffuse = group(1).unwrap_or(m.diffuse);
        m.specular = group(2).unwrap_or(m.specular);
        m.emission = group(3).unwrap_or(m.emission);
        if let Some(&s) = n.get(16) {
            m.shininess = s as f32;
        }
        // cpfg blends a material whose diffuse alpha is under 1.
        if let Some(&a) = n.get(7) {
            m.transparency = (1.0 - a as f32).clamp(0.0, 1.0);
        }
        self.materials.push(m);
        let index = self.first_index as usize + self.materials.len() - 1;
        let index = index.min(u16::MAX as usize) as u16;
        self.material = Some(index);
        self.shapes.paint = (flat_colour(&m), index);
    }

    /// Draws one command; a problem with its numbers is the message.
    fn command(&mut self, c: &Command) -> Result<(), String> {
        let n = &c.numbers;
        let need = |k: usize, what: &str| {
            if n.len() < k {
                Err(format!("`{}` takes {what}", c.word))
            } else {
                Ok(())
            }
        };
        let points = |stride: usize| -> Vec<[f64; 3]> {
            n.chunks_exact(stride).map(|p| [p[0], p[1], p[2]]).collect()
        };
        match c.word {
            "material" => self.material(n),
            "pushmatrix" => self.shapes.push(),
            "popmatrix" => {
                if !self.shapes.pop() {
                    return Err("`popmatrix` without a `pushmatrix`".into());
                }
            }
            "translate" => {
                need(3, "x y z")?;
                self.shapes
                    .transform(scene::translation([n[0], n[1], n[2]]));
            }
            "rotate" => {
                need(4, "an angle and an axis x y z")?;
                let m = scene::rotation(n[0], [n[1], n[2], n[3]]).ok_or("a zero axis")?;
                self.shapes.transform(m);
            }
            "scale" => {
                need(3, "x y z")?;
                self.shapes.transform(scene::scaling([n[0], n[1], n[2]]));
            }
            "multmatrix" => {
                need(16, "16 numbers")?;
                // cpfg's order is OpenGL's: column by column.
                let m: [f64; 16] = std::array::from_fn(|k| n[k]);
                self.shapes.transform(scene::from_columns(&m));
            }
            "sphere" => {
                need(1, "a radius")?;
                self.shapes.sphere(n[0]);
            }
            "cylinder" => {
                need(2, "a radius and a height")?;
                self.shapes.frustum(n[0], n[0], n[1]);
            }
            "cone" => {
                need(3, "two radii and a height")?;
                let top = if self.tapered { n[1] } else { n[0] };
                self.shapes.frustum(n[0], top, n[2]);
            }
            "prism" | "box" => {
                need(3, "a width, a height and a depth")?;
                self.shapes.prism([n[0], n[1], n[2]]);
            }
            "polygon" => {
                need(9, "three points or more")?;
                self.shapes.polygon(&points(3));
            }
            "polygonuv" => {
                need(18, "three points or more, each with its normal")?;
                self.shapes.polygon(&points(6));
            }
            "rectangle" => {
                need(2, "a width and a height")?;
                let (x, y) = (
                    n.get(2).copied().unwrap_or(0.0),
                    n.get(3).copied().unwrap_or(0.0),
                );
                let (w, h) = (n[0], n[1]);
                self.shapes.polygon(&[
                    [x, y, 0.0],
                    [x + w, y, 0.0],
                    [x + w, y + h, 0.0],
                    [x, y + h, 0.0],
                ]);
            }
            "mesh" => {
                need(12, "four points or more, in pairs")?;
                self.shapes.strip(&points(3));
            }
            _ => return Err(format!("`{}` is no command of a background scene", c.word)),
        }
        Ok(())
    }
}

/// The scene of a preprocessed scene file. Its materials take the colour
/// indices from `first_index` on; `tapered` is the view's `tapered lines:`
/// (a cone's top radius counts only with it, as in cpfg). Problems are
/// warnings at their spans of `text`.
pub fn read_scene(text: &str, first_index: u16, tapered: bool, diags: &mut Diagnostics) -> Scene {
    let mut d = Drawing {
        shapes: scene::Builder::new((flat_colour(&Material::CPFG_DEFAULT), 0)),
        materials: Vec::new(),
        first_index,
        material: None,
        tapered,
    };
    // Lines the preprocessor left with `#` (line markers) are skipped.
    let kept: String = text
        .lines()
        .map(|l| {
            if l.trim_start().starts_with('#') {
                ""
            } else {
                l
            }
        })
        .flat_map(|l| [l, "\n"])
        .collect();
    for c in commands(&kept) {
        if let Err(why) = d.command(&c) {
            diags.push(
                Diagnostic::at(codes::CPFG_VIEW_VALUE, c.span.clone(), why.clone())
                    .with_label("not drawn")
                    .with_help("cpfg reads `material`, `pushmatrix`, `popmatrix`, `translate`, `rotate`, `scale`, `multmatrix`, `sphere`, `cylinder`, `cone`, `prism`, `box`, `polygon`, `polygonuv`, `rectangle` and `mesh`, each followed by its numbers"),
            );
        }
    }
    Scene {
        polygons: d.shapes.polygons,
        materials: d.materials,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> (Scene, Diagnostics) {
        let mut d = Diagnostics::default();
        let s = read_scene(text, 256, true, &mut d);
        (s, d)
    }

    fn bounds(s: &Scene) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in s.polygons.iter().flat_map(|p| &p.points) {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    fn near(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    #[test]
    fn a_prism_spans_from_the_origin_and_transforms_apply_last_first() {
        let (s, d) = scene("prism 1 2 3");
        assert!(d.is_empty());
        assert_eq!(s.polygons.len(), 6);
        assert_eq!(bounds(&s), ([0.0; 3], [1.0, 2.0, 3.0]));
        // translate, then scale: the scale applies to the box first.
        let (s, _) = scene("translate 10 0 0 scale 2 1 1 prism 1 1 1");
        assert!(near(bounds(&s).0, [10.0, 0.0, 0.0]) && near(bounds(&s).1, [12.0, 1.0, 1.0]));
        // rotate 90 about z takes +x to +y.
        let (s, _) = scene("rotate 90 0 0 1 prism 1 1 1");
        let (lo, hi) = bounds(&s);
        assert!(
            near(lo, [-1.0, 0.0, 0.0]) && near(hi, [0.0, 1.0, 1.0]),
            "{lo:?} {hi:?}"
        );
        // pushmatrix/popmatrix keep what was before.
        let (s, _) = scene("pushmatrix translate 5 5 5 popmatrix prism 1 1 1");
        assert_eq!(bounds(&s), ([0.0; 3], [1.0; 3]));
    }

    #[test]
    fn multmatrix_is_read_column_by_column() {
        // OpenGL order: the translation is the 13th to 15th number.
        let (s, _) = scene("multmatrix 1 0 0 0  0 1 0 0  0 0 1 0  0 2 0 1 prism 1 1 1");
        assert!(near(bounds(&s).0, [0.0, 2.0, 0.0]));
    }

    #[test]
    fn round_primitives_stand_on_y_and_spheres_are_centred() {
        let (s, _) = scene("cylinder 0.5 2");
        let (lo, hi) = bounds(&s);
        assert!((lo[1], hi[1]) == (0.0, 2.0) && (hi[0] - 0.5).abs() < 1e-9);
        assert_eq!(s.polygons.len(), scene::SIDES + 2, "sides and two caps");
        let (s, _) = scene("sphere 2");
        let (lo, hi) = bounds(&s);
        assert!(near(lo.map(|x| x.round()), [-2.0; 3]) && near(hi, [2.0, 2.0, hi[2]]));
        let (s, _) = scene("cone 1 0.25 3");
        let top: Vec<f64> = s
            .polygons
            .last()
            .unwrap()
            .points
            .iter()
            .map(|p| p[0].hypot(p[2]))
            .collect();
        assert!(top.iter().all(|r| (r - 0.25).abs() < 1e-9), "{top:?}");
    }

    #[test]
    fn materials_take_indices_and_colours_in_order() {
        let (s, d) = scene(
            "material 0.1 0.1 0 1  0 0.5 0 1  0 0 0 1  0 0 0 1  0.9\npolygon -1 0 -1  -1 0 1  1 0 1\n\
             material 0 0 0 1  1 0 0 0.5  0 0 0 1  0 0 0 1  1\nmesh 0 0 0 1 0 0  0 1 0 1 1 0  0 2 0 1 2 0",
        );
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(s.materials.len(), 2);
        assert_eq!(s.materials[0].diffuse, [0.0, 0.5, 0.0]);
        assert_eq!(s.materials[1].transparency, 0.5);
        let indices: Vec<u16> = s.polygons.iter().map(|p| p.index).collect();
        assert_eq!(
            indices,
            [256, 257, 257],
            "one polygon, then two quads of the mesh"
        );
        assert_eq!(s.polygons[1].colour, crate::ir::Rgb(255, 0, 0));
        assert_eq!(
            s.polygons[1].points,
            [[0.0; 3], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
        );
    }

    #[test]
    fn unknown_words_and_short_commands_are_warnings_at_their_spans() {
        let text = "prism 1 1\ntorus 3 1\nsphere 1";
        let (s, d) = scene(text);
        let spans: Vec<&str> = d.iter().map(|x| &text[x.span.clone().unwrap()]).collect();
        assert_eq!(spans, ["prism 1 1", "torus 3 1"]);
        assert!(d.iter().all(|x| x.code == codes::CPFG_VIEW_VALUE));
        assert!(!s.polygons.is_empty(), "the sphere is drawn");
    }
}
