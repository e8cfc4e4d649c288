//! What a lit picture is made of, each drawn into the samples: polygons
//! (lit per corner), lines by the look's style (pixel lines, ribbons,
//! cylinders), and discs and spheres.

use super::target::{SVert, Target};
use super::tessellate::Tessellated;
use super::Scene;
use crate::ir::look::{LineStyle, Shading};
use crate::render::camera::{cross, dot, sub, unit};
use crate::render::shade::{Colour, Kind, Paint};
use crate::turtle::{Disc, Polygon, Segment, Vec3};

/// Polygons, lines and discs.
impl Scene<'_> {
    /// Adds to `out` where `p`'s corners fall in samples, when it can show
    /// in the band `t` (else adds nothing and says so): every corner in front of the eye, and some sample's centre
    /// within its box (a triangle is drawn at the centres it covers, so one
    /// between centres draws nothing). A wireframe's outlines are lines of
    /// a pixel or more: every polygon shows (with no corners given).
    pub(super) fn corners_shown(&self, t: &Target, p: &Polygon, out: &mut Vec<[f64; 3]>) -> bool {
        if self.lighting.shading == Shading::Wireframe {
            return true;
        }
        let at = out.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &q in &p.points {
            let Some(c) = self.to_samples(q) else {
                out.truncate(at);
                return false;
            };
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
            out.push(c);
        }
        let first_x = ((lo[0] - 0.5).ceil() as i64).max(0);
        let last_x = ((hi[0] - 0.5).floor() as i64).min(t.width - 1);
        let shown = first_x <= last_x && !t.rows_between(lo[1], hi[1]).is_empty();
        if !shown {
            out.truncate(at);
        }
        shown
    }

    /// Draws `p`, its corners in samples `corners` ([`Scene::corners_shown`];
    /// none for a wireframe).
    pub(super) fn polygon(
        &self,
        t: &mut Target,
        p: &Polygon,
        tess: &Tessellated,
        corners: &[[f64; 3]],
    ) {
        if tess.triangles.is_empty() {
            return;
        }
        let pts = &p.points;
        if self.lighting.shading == Shading::Wireframe {
            let c = self.shader.unlit(p.colour, p.index);
            let width = self.fit.line_width(1.0, false);
            for (i, &a) in pts.iter().enumerate() {
                self.pixel_line(t, a, pts[(i + 1) % pts.len()], width, c);
            }
            return;
        }
        // Two-sided: the face's normal turned towards the viewer.
        let centre = pts
            .iter()
            .fold([0.0; 3], |s, q| [s[0] + q[0], s[1] + q[1], s[2] + q[2]]);
        let centre = centre.map(|c| c / pts.len() as f64);
        let facing = dot(tess.normal, self.proj.towards_viewer(centre)) >= 0.0;
        let turn = |n: Vec3| if facing { n } else { n.map(|c| -c) };
        let paint = Paint::own(p.colour, p.index);
        let colours: Vec<Colour> = match &tess.corner_normals {
            Some(normals) => pts
                .iter()
                .zip(normals)
                .map(|(&q, &n)| self.colour(Kind::of(p), paint, q, turn(n)))
                .collect(),
            None => {
                let c = self.colour(Kind::of(p), paint, centre, turn(tess.normal));
                vec![c; pts.len()]
            }
        };
        let textured = p.texture.as_ref().and_then(|tx| {
            let texture = self.lighting.textures.get(usize::from(tx.texture))?;
            let has_uvs = texture.image.is_some() && tx.uvs.len() == pts.len();
            has_uvs.then_some((texture, &tx.uvs))
        });
        let vert = |i: usize| SVert {
            x: corners[i][0],
            y: corners[i][1],
            z: corners[i][2],
            c: colours[i],
            uv: textured.map_or([0.0; 2], |(_, uvs)| uvs[i]),
        };
        for &[a, b, c] in &tess.triangles {
            let v = [vert(a), vert(b), vert(c)];
            match textured {
                Some((texture, _)) => t.textured_triangle(v, texture),
                None => t.triangle(v),
            }
        }
    }

    pub(super) fn segment(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        if self.lighting.shading == Shading::Wireframe {
            let c = self.shader.flat(paint);
            return self.pixel_line(t, s.a, s.b, self.fit.line_width(1.0, false), c);
        }
        match self.lighting.line_style {
            LineStyle::Pixel => {
                let c = self.shader.flat(paint);
                let width = self.fit.line_width(s.width, self.world_widths);
                self.pixel_line(t, s.a, s.b, width, c);
            }
            LineStyle::Polygon => self.ribbon(t, s, paint, end_width),
            LineStyle::Cylinder => {
                let r = s.width.max(end_width).abs() / 2.0;
                if r * self.samples_per_unit(s.a) < 1.5 {
                    self.ribbon(t, s, paint, end_width);
                } else {
                    self.cylinder(t, s, paint, end_width);
                }
            }
        }
    }

    /// A flat band of the segment's width facing the viewer (cpfg's
    /// `polygon` line style; also a cylinder too thin to show its sides).
    fn ribbon(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        let Some(axis) = unit(sub(s.b, s.a)) else {
            return;
        };
        let mid = [0, 1, 2].map(|k| (s.a[k] + s.b[k]) / 2.0);
        let v = self.proj.towards_viewer(mid);
        // Seen end on, a ribbon shows nothing (as in cpfg).
        let Some(side) = unit(cross(axis, v)) else {
            return;
        };
        let n = cross(side, axis);
        let c = self.colour(Kind::Line, paint, mid, n);
        let (ra, rb) = (s.width.abs() / 2.0, end_width.abs() / 2.0);
        let at = |p: Vec3, r: f64| {
            (
                self.vert([0, 1, 2].map(|k| p[k] - side[k] * r), c),
                self.vert([0, 1, 2].map(|k| p[k] + side[k] * r), c),
            )
        };
        let ((Some(a0), Some(a1)), (Some(b0), Some(b1))) = (at(s.a, ra), at(s.b, rb)) else {
            return;
        };
        let lo = [a0.y, a1.y, b0.y, b1.y]
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let hi = [a0.y, a1.y, b0.y, b1.y]
            .into_iter()
            .fold(f64::NEG_INFINITY, f64::max);
        if t.meets(lo, hi) {
            t.triangle([a0, a1, b1]);
            t.triangle([a0, b1, b0]);
        }
    }

    /// A cylinder (a cone when tapered) from the segment's width to
    /// `end_width`, its sides lit smooth around the axis (or one colour per
    /// side when shading is flat); sides facing away are not drawn.
    fn cylinder(&self, t: &mut Target, s: &Segment, paint: Paint, end_width: f64) {
        let Some(axis) = unit(sub(s.b, s.a)) else {
            return;
        };
        let (Some(pa), Some(pb)) = (self.to_samples(s.a), self.to_samples(s.b)) else {
            return;
        };
        let (ra, rb) = (s.width.abs() / 2.0, end_width.abs() / 2.0);
        let reach = ra.max(rb) * self.samples_per_unit(s.a).max(self.samples_per_unit(s.b));
        if !t.meets(pa[1].min(pb[1]) - reach, pa[1].max(pb[1]) + reach) {
            return;
        }
        let helper = if axis[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let Some(u) = unit(cross(axis, helper)) else {
            return;
        };
        let w = cross(axis, u);
        let sides = if reach < 8.0 { 8 } else { 12 };
        let around = |k: f64| {
            let (sn, cs) = (k * std::f64::consts::TAU / sides as f64).sin_cos();
            [0, 1, 2].map(|i| u[i] * cs + w[i] * sn)
        };
        let mid = [0, 1, 2].map(|k| (s.a[k] + s.b[k]) / 2.0);
        let v = self.proj.towards_viewer(mid);
        let smooth = self.lighting.shading == Shading::Smooth;
        let ring = |p: Vec3, r: f64, k: usize, n: Vec3| {
            let q = [0, 1, 2].map(|i| p[i] + around(k as f64)[i] * r);
            self.vert(q, self.colour(Kind::Line, paint, q, n))
        };
        for k in 0..sides {
            let face = around(k as f64 + 0.5);
            if dot(face, v) < -0.3 {
                continue;
            }
            let (n0, n1) = if smooth {
                (around(k as f64), around(k as f64 + 1.0))
            } else {
                (face, face)
            };
            let corners = (
                ring(s.a, ra, k, n0),
                ring(s.a, ra, k + 1, n1),
                ring(s.b, rb, k + 1, n1),
                ring(s.b, rb, k, n0),
            );
            if let (Some(a0), Some(a1), Some(b1), Some(b0)) = corners {
                t.triangle([a0, a1, b1]);
                t.triangle([a0, b1, b0]);
            }
        }
    }

    pub(super) fn disc(&self, t: &mut Target, d: &Disc) {
        let Some(c) = self.to_samples(d.centre) else {
            return;
        };
        let r_world = d.diameter.abs() / 2.0;
        let r = if d.pixels {
            r_world * self.fit.line_unit * self.ss
        } else {
            r_world * self.samples_per_unit(d.centre)
        };
        if !r.is_finite() || r <= 0.0 || !t.meets(c[1] - r, c[1] + r) {
            return;
        }
        let unlit = self.shader.unlit(d.colour, d.index);
        let lit = matches!(self.lighting.shading, Shading::Flat | Shading::Smooth);
        if self.lighting.shading == Shading::Wireframe {
            let width = self.fit.line_width(1.0, false) * self.ss;
            let n = 32;
            for k in 0..n {
                let at = |k: usize| {
                    let (sn, cs) = (k as f64 * std::f64::consts::TAU / n as f64).sin_cos();
                    [c[0] + r * cs, c[1] + r * sn, c[2]]
                };
                t.line(at(k), at(k + 1), width, unlit);
            }
        } else if d.pixels || !lit {
            flat_disc(t, c, r, unlit);
        } else {
            self.sphere(t, d, c, r, r_world);
        }
    }

    /// A lit sphere of world radius `r_world` around `d.centre`, at `c` (samples)
    /// and `r` samples across: a normal and a depth per sample.
    fn sphere(&self, t: &mut Target, d: &Disc, c: [f64; 3], r: f64, r_world: f64) {
        let (right, up) = self.proj.screen_axes(d.centre);
        let back = self.proj.towards_viewer(d.centre);
        let centre_z = self.proj.project(d.centre).map_or(0.0, |p| p.1);
        let perspective = self.proj.perspective();
        for y in t.rows_between(c[1] - r, c[1] + r) {
            let dy = (y as f64 + 0.5 - c[1]) / r;
            let half = (1.0 - dy * dy).max(0.0).sqrt() * r;
            let first = ((c[0] - half - 0.5).ceil() as i64).max(0);
            let last = ((c[0] + half - 0.5).floor() as i64).min(t.width - 1);
            for x in first..=last {
                let dx = (x as f64 + 0.5 - c[0]) / r;
                let q = 1.0 - dx * dx - dy * dy;
                if q < 0.0 {
                    continue;
                }
                let nz = q.sqrt();
                let n = [0, 1, 2].map(|k| right[k] * dx - up[k] * dy + back[k] * nz);
                let p = [0, 1, 2].map(|k| d.centre[k] + n[k] * r_world);
                let z = if perspective {
                    -1.0 / (centre_z - nz * r_world).max(1e-300)
                } else {
                    c[2] - nz * r_world
                };
                let colour = self.colour(Kind::Line, Paint::own(d.colour, d.index), p, n);
                t.plot(x, y, z, colour);
            }
        }
    }
}

/// A flat disc at `c` (samples, depth), `r` samples across.
fn flat_disc(t: &mut Target, c: [f64; 3], r: f64, colour: Colour) {
    let n = ((r * 2.0).ceil() as usize).clamp(8, 64);
    let centre = SVert {
        x: c[0],
        y: c[1],
        z: c[2],
        c: colour,
        uv: [0.0; 2],
    };
    let at = |k: usize| {
        let (sn, cs) = (k as f64 * std::f64::consts::TAU / n as f64).sin_cos();
        SVert {
            x: c[0] + r * cs,
            y: c[1] + r * sn,
            ..centre
        }
    };
    for k in 0..n {
        t.triangle([centre, at(k), at(k + 1)]);
    }
}
