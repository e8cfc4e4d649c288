//! SVG output: one `<path>` per run of segments with the same colour and
//! width, one per filled polygon; coordinates in pixels of the fitted
//! picture, printed with at most 3 decimals so output is byte-stable.

use super::camera::{cross, dot, sub, unit, Projector};
use super::shade::{Colour, Kind, Paint, Shader};
use super::{Detail, Palette, Picture, RenderOptions, Run};
use crate::ir::look::{Lighting, LineStyle, Shading};
use crate::ir::Rgb;
use crate::turtle::{Disc, Geometry, Polygon, Segment, Vec3};
use std::fmt::Write;

fn num(x: f64) -> String {
    let s = format!("{:.3}", x);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// The background's fill: `white` as before for white, else its hex.
fn background(c: Rgb) -> String {
    if c == super::WHITE {
        "white".to_string()
    } else {
        hex(c)
    }
}

/// The background rectangle of a `w` × `h` picture: none when it is
/// transparent, with its opacity when it is translucent.
fn background_rect(out: &mut String, (w, h): (u32, u32), c: Rgb, alpha: u8) {
    let opacity = match alpha {
        0 => return,
        255 => String::new(),
        a => format!(r#" fill-opacity="{}""#, num(f64::from(a) / 255.0)),
    };
    let _ = writeln!(
        out,
        r#"<rect width="{w}" height="{h}" fill="{}"{opacity}/>"#,
        background(c)
    );
}

/// Appends `M x y L x y …` for the points to a path's `d`.
fn polyline(d: &mut String, pts: &[[f64; 2]]) {
    for (i, p) in pts.iter().enumerate() {
        let op = if i == 0 { 'M' } else { 'L' };
        let _ = write!(d, "{op}{} {}", num(p[0]), num(p[1]));
    }
}

/// `x` pixels in tenths, as written by [`tenths`].
fn to_tenths(x: f64) -> i64 {
    (x * 10.0).round() as i64
}

/// `t` tenths of a pixel, shortest: `12` is `1.2`, `-3` is `-.3`, `10` is `1`.
fn tenths(t: i64) -> String {
    let (sign, t) = if t < 0 { ("-", -t) } else { ("", t) };
    match (t / 10, t % 10) {
        (0, 0) => "0".to_string(),
        (0, f) => format!("{sign}.{f}"),
        (i, 0) => format!("{sign}{i}"),
        (i, f) => format!("{sign}{i}.{f}"),
    }
}

/// Appends numbers to a path's `d`, a space between them where a minus
/// sign does not already part them.
fn numbers(d: &mut String, ts: [i64; 2]) {
    for t in ts {
        let text = tenths(t);
        if !(d.is_empty() || text.starts_with('-') || d.ends_with(['M', 'l'])) {
            d.push(' ');
        }
        d.push_str(&text);
    }
}

/// Appends `M x y l dx dy dx dy …` for the points, to a tenth of a pixel:
/// each step is the difference of rounded points, so that rounding errors
/// do not add up along the line.
fn compact_polyline(d: &mut String, pts: &[[f64; 2]]) {
    let mut at: Option<[i64; 2]> = None;
    for p in pts {
        let t = [to_tenths(p[0]), to_tenths(p[1])];
        match at {
            None => {
                d.push('M');
                numbers(d, t);
                d.push('l');
            }
            Some(a) => numbers(d, [t[0] - a[0], t[1] - a[1]]),
        }
        at = Some(t);
    }
}

/// ` data-src="…"` for a part of a linked picture that a module drew
/// (the names are made of digits and `-`: nothing to escape).
fn source_attribute(name: Option<&str>) -> String {
    name.map_or_else(String::new, |n| format!(r#" data-src="{n}""#))
}

/// The picture as an SVG document, its sub-pixel detail merged
/// ([`Detail::Merged`]).
pub fn write(pic: &Picture) -> String {
    write_with(pic, Detail::Merged)
}

/// The picture as an SVG document with `detail`: every segment at three
/// decimals, or where anything merges ([`super::simplify`]), what is
/// visible at a tenth of a pixel.
pub fn write_with(pic: &Picture, detail: Detail) -> String {
    let merged = match detail {
        Detail::Full => None,
        Detail::Merged => super::simplify::merged_runs(pic),
    };
    let mut out = String::new();
    let (w, h) = (pic.width, pic.height);
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    background_rect(&mut out, (w, h), pic.background, pic.background_alpha);
    for (i, (colour, pts)) in pic.polygons.iter().enumerate() {
        let mut d = String::new();
        polyline(&mut d, pts);
        d.push('Z');
        let src = source_attribute(pic.links.name(pic.links.polygons.get(i)));
        let _ = writeln!(
            out,
            r#"<path d="{d}" fill="{}" fill-rule="evenodd"{src}/>"#,
            hex(*colour)
        );
    }
    let runs: &[Run] = merged.as_deref().unwrap_or(&pic.runs);
    for (i, run) in runs.iter().enumerate() {
        let mut d = String::new();
        for line in run.lines.iter().filter(|l| !l.is_empty()) {
            match merged {
                Some(_) => compact_polyline(&mut d, line),
                None => polyline(&mut d, line),
            }
        }
        if d.is_empty() {
            continue;
        }
        // Merged runs are not the picture's own: no tag is theirs.
        let tag = merged.is_none().then(|| pic.links.runs.get(i)).flatten();
        let src = source_attribute(pic.links.name(tag));
        let _ = writeln!(
            out,
            r#"<path d="{d}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"{src}/>"#,
            hex(run.colour),
            num(run.width)
        );
    }
    for l in &pic.labels {
        out.push_str(&super::text::svg(l));
        out.push('\n');
    }
    out.push_str("</svg>\n");
    out
}

fn rgb(c: Colour) -> Rgb {
    let q = |x: f32| (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    Rgb(q(c[0]), q(c[1]), q(c[2]))
}

/// One thing drawn by [`write_scene`], with its distance from the viewer.
struct Item {
    depth: f64,
    svg: String,
}

/// What [`write_scene`] draws with.
struct Scene<'a> {
    proj: Projector,
    fit: super::Fit,
    shader: Shader<'a>,
    lighting: Option<&'a Lighting>,
    world_lines: bool,
}

impl Scene<'_> {
    /// A primitive's one colour: lit at `p` with normal `n` when the look
    /// is lit and shaded, else flat.
    fn colour(&self, kind: Kind, paint: Paint, p: Vec3, n: Vec3) -> Rgb {
        match (self.lighting, paint) {
            (None, _) => paint.colour(),
            (Some(l), _) if matches!(l.shading, Shading::Flat | Shading::Smooth) => {
                let v = self.proj.towards_viewer(p);
                rgb(self.shader.shade(kind, paint, p, n, v))
            }
            (Some(_), _) => rgb(self.shader.flat(paint)),
        }
    }

    fn polygon(&self, p: &Polygon) -> Option<Item> {
        let pts: Vec<([f64; 2], f64)> = p
            .points
            .iter()
            .map(|&q| self.proj.project(q))
            .collect::<Option<_>>()?;
        let n = unit(super::raster::newell(&p.points))?;
        let mid = p
            .points
            .iter()
            .fold([0.0; 3], |s, q| [s[0] + q[0], s[1] + q[1], s[2] + q[2]]);
        let mid = mid.map(|c| c / p.points.len() as f64);
        let facing = dot(n, self.proj.towards_viewer(mid)) >= 0.0;
        let n = if facing { n } else { n.map(|c| -c) };
        let mut d = String::new();
        let px: Vec<[f64; 2]> = pts.iter().map(|(xy, _)| self.fit.to_px(*xy)).collect();
        polyline(&mut d, &px);
        d.push('Z');
        // Translucent materials show what lies behind (drawn first, as the
        // items are painted farthest first).
        let opacity = self.lighting.map_or(1.0, |l| l.opacity(p.index));
        let opacity = if opacity < 1.0 {
            format!(r#" fill-opacity="{opacity}""#)
        } else {
            String::new()
        };
        let colour = self.colour(Kind::of(p), Paint::own(p.colour, p.index), mid, n);
        Some(Item {
            depth: pts.iter().map(|r| r.1).sum::<f64>() / pts.len() as f64,
            svg: format!(
                r#"<path d="{d}" fill="{}" fill-rule="evenodd"{opacity}/>"#,
                hex(self.textured(p, colour))
            ),
        })
    }

    /// The colour of a textured polygon: its lit colour combined, as the
    /// z-buffer combines a texel, with the mean colour of the texels that
    /// show ([`crate::ir::texture::Image::mean_shown`]); an SVG path has
    /// one fill, so the image itself is not mapped.
    fn textured(&self, p: &Polygon, lit: Rgb) -> Rgb {
        let texture = p.texture.as_ref().and_then(|tx| {
            let t = self.lighting?.textures.get(usize::from(tx.texture))?;
            Some((t.mode, t.image.as_ref()?.mean_shown()))
        });
        let Some((mode, texel)) = texture else {
            return lit;
        };
        let unit = |c: u8| f32::from(c) / 255.0;
        let c = mode.apply([unit(lit.0), unit(lit.1), unit(lit.2), 1.0], texel);
        rgb([c[0], c[1], c[2]])
    }

    fn segment(&self, s: &Segment, paint: Paint, world_widths: bool) -> Option<Item> {
        let ((a, za), (b, zb)) = (self.proj.project(s.a)?, self.proj.project(s.b)?);
        let mid = [0, 1, 2].map(|k| (s.a[k] + s.b[k]) / 2.0);
        let v = self.proj.towards_viewer(mid);
        // Lit as the side of a cylinder facing the viewer.
        let n = unit(sub(s.b, s.a))
            .and_then(|axis| unit(cross(axis, v)).map(|side| cross(side, axis)))
            .unwrap_or(v);
        let width = if self.world_lines {
            s.width.abs() * self.proj.pixels_per_unit(&self.fit, (za + zb) / 2.0)
        } else {
            self.fit.line_width(s.width, world_widths)
        };
        let (a, b) = (self.fit.to_px(a), self.fit.to_px(b));
        Some(Item {
            depth: (za + zb) / 2.0,
            svg: format!(
                r#"<path d="M{} {}L{} {}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round"/>"#,
                num(a[0]),
                num(a[1]),
                num(b[0]),
                num(b[1]),
                hex(self.colour(Kind::Line, paint, mid, n)),
                num(width)
            ),
        })
    }

    fn disc(&self, d: &Disc) -> Option<Item> {
        let (c, z) = self.proj.project(d.centre)?;
        let r = d.diameter.abs() / 2.0;
        let r = if d.pixels {
            r * self.fit.line_unit
        } else {
            r * self.proj.pixels_per_unit(&self.fit, z)
        };
        let v = self.proj.towards_viewer(d.centre);
        let c = self.fit.to_px(c);
        Some(Item {
            depth: z,
            svg: format!(
                r#"<circle cx="{}" cy="{}" r="{}" fill="{}"/>"#,
                num(c[0]),
                num(c[1]),
                num(r),
                hex(self.colour(Kind::Line, Paint::own(d.colour, d.index), d.centre, v))
            ),
        })
    }
}

/// The SVG of a geometry seen through a camera or lit (a cpfg object):
/// every polygon, line and disc on its own, farther first (the painter's
/// order by each one's mean depth), in the colour the look gives it (one
/// per primitive: lit at its middle unless the shading is flat colours).
pub fn write_scene(
    g: &Geometry,
    lighting: Option<&Lighting>,
    palette: &[Rgb],
    opts: &RenderOptions,
) -> String {
    let proj = Projector::new(opts);
    let default_lighting = Lighting::default();
    let look = lighting.unwrap_or(&default_lighting);
    let survey = super::raster::survey(&super::raster::Drawing::stored(g), look, opts);
    let scene = Scene {
        proj,
        fit: survey.fit(opts),
        shader: Shader::new(look, palette, proj.towards_viewer(survey.centre())),
        lighting,
        world_lines: lighting.is_some_and(|l| l.line_style != LineStyle::Pixel),
    };
    let mut items: Vec<Item> = g.polygons.iter().filter_map(|p| scene.polygon(p)).collect();
    items.extend(g.segments.iter().enumerate().filter_map(|(i, s)| {
        let paint = Palette::segment_paint(opts.style.palette, g, i);
        scene.segment(s, paint, g.world_widths)
    }));
    items.extend(g.discs.iter().filter_map(|d| scene.disc(d)));
    // Farther first; a stable sort keeps the turtle's order among equals.
    items.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    let (w, h) = (opts.width, opts.height);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    background_rect(&mut out, (w, h), opts.background, opts.background_alpha);
    for item in items {
        out.push_str(&item.svg);
        out.push('\n');
    }
    for l in &g.labels {
        if let Some((xy, _)) = scene.proj.project(l.at) {
            let placed = super::text::Placed {
                at: scene.fit.to_px(xy),
                text: l.text.clone(),
                colour: l.colour,
            };
            out.push_str(&super::text::svg(&placed));
            out.push('\n');
        }
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_is_drawn_farther_first_on_its_background() {
        use crate::ir::look::Camera;
        let square = |z: f64, grey: u8| Polygon {
            points: vec![[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]],
            colour: Rgb(grey, grey, grey),
            index: 0,
            surface: false,
            texture: None,
        };
        let g = Geometry {
            polygons: vec![square(1.0, 1), square(-1.0, 2)],
            segments: vec![Segment {
                a: [0.0, 0.0, 0.0],
                b: [1.0, 1.0, 0.0],
                width: 1.0,
                colour: Rgb(3, 3, 3),
                index: 0,
                depth: 0,
            }],
            ..Geometry::default()
        };
        let order = |eye_z: f64| {
            let opts = RenderOptions {
                camera: Some(Camera {
                    eye: [0.5, 0.5, eye_z],
                    target: [0.5, 0.5, 0.0],
                    up: [0.0, 1.0, 0.0],
                    perspective: None,
                }),
                background: Rgb(9, 8, 7),
                ..RenderOptions::default()
            };
            let svg = write_scene(&g, None, &[Rgb(0, 0, 0)], &opts);
            assert!(svg.contains(r##"fill="#090807""##));
            ["#010101", "#020202", "#030303"].map(|c| svg.find(c).unwrap())
        };
        // From +z the square at z = 1 is nearest: drawn last.
        let [near, far, line] = order(10.0);
        assert!(far < line && line < near);
        let [near, far, line] = order(-10.0);
        assert!(near < line && line < far);
    }

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(1.23456), "1.235");
    }

    #[test]
    fn compact_paths_step_between_rounded_points() {
        assert_eq!(tenths(12), "1.2");
        assert_eq!(tenths(-3), "-.3");
        assert_eq!(tenths(-10), "-1");
        assert_eq!(tenths(0), "0");
        let mut d = String::new();
        compact_polyline(&mut d, &[[10.04, 5.0], [10.46, 4.72], [10.88, 4.44]]);
        // 10.5 - 10 = .5, then 10.9 - 10.5 = .4: the rounding does not drift.
        assert_eq!(d, "M10 5l.5-.3 .4-.3");
    }
}
