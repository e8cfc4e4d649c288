//! Surface files (`.s`, manual §6.7.1): bicubic Bézier patches written by
//! vlab's bezieredit, drawn by the module `~id`.
//!
//! Layout: a line with the bounding box (`xmin xmax ymin ymax zmin zmax`),
//! an optional `PRECISION S: s T: t`, `CONTACT POINT X: x Y: y Z: z`, `END POINT …`, `HEADING …`, `UP …`,
//! `SIZE: s`, then patches: a name line, a `TOP COLOR: …` line, three
//! neighbour lines (`AL: A: AR:`, `L: R:`, `BL: B: BR:`) and 4 rows of 4
//! control points `x y z`.
//!
//! Placing a surface: cpfg puts the contact point at the turtle's position
//! and turns the surface so that its heading and up vectors lie along the
//! turtle's H and U, then scales it by the view file's `surface:` scale (and
//! the `~id(s)` parameter). [`Surface::to_turtle`] gives a point in those
//! turtle coordinates (before scaling).

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use std::iter::Peekable;
use std::ops::Range;

/// One bicubic Bézier patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub name: String,
    /// `points[row][column]`.
    pub points: [[[f64; 3]; 4]; 4],
}

/// A surface file.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// `[xmin, xmax, ymin, ymax, zmin, zmax]` as the file gives it.
    pub bounds: [f64; 6],
    pub contact: [f64; 3],
    pub end: [f64; 3],
    pub heading: [f64; 3],
    pub up: [f64; 3],
    pub size: f64,
    /// The optional `PRECISION S: s T: t` line (some files give their own
    /// mesh density).
    pub precision: Option<(u32, u32)>,
    pub patches: Vec<Patch>,
}

/// A triangle's corners, and their texture coordinates.
pub type Triangle = [[f64; 3]; 3];
pub type TriangleUvs = [[f64; 2]; 3];

const MAX_PATCHES: usize = 100_000;

fn error(span: Range<usize>, msg: impl Into<String>, expected: &str) -> Diagnostics {
    Diagnostics(vec![Diagnostic::at(codes::CPFG_SURFACE_FILE, span, msg)
        .with_label(format!("expected {expected}"))])
}

fn nums(s: &str) -> Option<Vec<f64>> {
    s.split_whitespace()
        .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect()
}

/// `LABEL X: x Y: y Z: z` → [x, y, z].
fn labelled_point(line: &str, label: &str) -> Option<[f64; 3]> {
    let rest = line.trim().strip_prefix(label)?;
    let w: Vec<&str> = rest.split_whitespace().collect();
    match w.as_slice() {
        ["X:", x, "Y:", y, "Z:", z] => Some([x.parse().ok()?, y.parse().ok()?, z.parse().ok()?]),
        _ => None,
    }
}

/// Reads a surface file.
pub fn read_surface(text: &str) -> Result<Surface, Diagnostics> {
    let mut lines = Lines::new(text);
    let (l, s) = lines.next("the bounding box")?;
    let bounds: [f64; 6] = nums(l)
        .and_then(|v| v.try_into().ok())
        .ok_or_else(|| error(s, "malformed bounding box", "six numbers"))?;
    let precision = read_precision(&mut lines)?;
    let contact = lines.point("CONTACT POINT")?;
    let end_point = lines.point("END POINT")?;
    let heading = lines.point("HEADING")?;
    let up = lines.point("UP")?;
    let (l, s) = lines.next("`SIZE:`")?;
    let size = l
        .trim()
        .strip_prefix("SIZE:")
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|x| x.is_finite())
        .ok_or_else(|| error(s, "malformed `SIZE:` line", "`SIZE: s`"))?;
    let mut patches = Vec::new();
    while let Some((name, _)) = lines.it.next() {
        if patches.len() >= MAX_PATCHES {
            return Err(error(lines.end(), "too many patches", "fewer patches"));
        }
        patches.push(read_patch(&mut lines, name.trim().to_string())?);
    }
    if patches.is_empty() {
        return Err(error(
            lines.end(),
            "the surface has no patch",
            "a patch after `SIZE:`",
        ));
    }
    Ok(Surface {
        bounds,
        contact,
        end: end_point,
        heading,
        up,
        size,
        precision,
        patches,
    })
}

/// The non-blank lines of a surface file with their spans, read in order.
struct Lines<'a> {
    it: Peekable<std::vec::IntoIter<(&'a str, Range<usize>)>>,
    len: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Self {
        let mut lines = Vec::new();
        let mut at = 0;
        for l in text.split_inclusive('\n') {
            let body = l.trim_end_matches(['\n', '\r']);
            if !body.trim().is_empty() {
                lines.push((body, at..at + body.len()));
            }
            at += l.len();
        }
        Lines {
            it: lines.into_iter().peekable(),
            len: text.len(),
        }
    }

    /// The end of the file, where what is missing is reported.
    fn end(&self) -> Range<usize> {
        self.len..self.len
    }

    /// The next line; at the end of the file, the error that `expected` is
    /// missing.
    fn next(&mut self, expected: &str) -> Result<(&'a str, Range<usize>), Diagnostics> {
        let end = self.end();
        self.it
            .next()
            .ok_or_else(|| error(end, "the surface file ends too early", expected))
    }

    /// The next line, which must be `LABEL X: x Y: y Z: z`.
    fn point(&mut self, label: &str) -> Result<[f64; 3], Diagnostics> {
        let (l, s) = self.next(label)?;
        labelled_point(l, label).ok_or_else(|| {
            error(
                s,
                format!("malformed `{label}` line"),
                &format!("`{label} X: x Y: y Z: z`"),
            )
        })
    }
}

/// The optional `PRECISION S: s T: t` line.
fn read_precision(lines: &mut Lines) -> Result<Option<(u32, u32)>, Diagnostics> {
    let Some((l, s)) = lines
        .it
        .next_if(|(l, _)| l.trim_start().starts_with("PRECISION"))
    else {
        return Ok(None);
    };
    let w: Vec<&str> = l.split_whitespace().collect();
    let precision = match w.as_slice() {
        ["PRECISION", "S:", a, "T:", b] => a.parse::<u32>().ok().zip(b.parse::<u32>().ok()),
        _ => None,
    };
    precision
        .map(Some)
        .ok_or_else(|| error(s, "malformed `PRECISION` line", "`PRECISION S: s T: t`"))
}

/// The patch after its name line: colour and neighbour lines, then 16
/// control points.
fn read_patch(lines: &mut Lines, name: String) -> Result<Patch, Diagnostics> {
    // Colour and neighbour lines (not used for the geometry).
    while lines.it.peek().is_some_and(|(l, _)| {
        let t = l.trim_start();
        ["TOP COLOR:", "AL:", "L:", "BL:"]
            .iter()
            .any(|p| t.starts_with(p))
    }) {
        lines.it.next();
    }
    let mut values = Vec::with_capacity(48);
    while values.len() < 48 {
        let end = lines.end();
        let (l, s) = lines.it.next().ok_or_else(|| {
            error(
                end,
                format!("patch `{name}` ends too early"),
                "4 rows of 4 points",
            )
        })?;
        let v = nums(l).ok_or_else(|| {
            error(
                s.clone(),
                format!("malformed control points in patch `{name}`"),
                "numbers",
            )
        })?;
        if values.len() + v.len() > 48 {
            return Err(error(
                s,
                format!("too many numbers in patch `{name}`"),
                "4 rows of 4 points `x y z`",
            ));
        }
        values.extend(v);
    }
    let mut points = [[[0.0; 3]; 4]; 4];
    for (k, c) in values.chunks(3).enumerate() {
        points[k / 4][k % 4] = [c[0], c[1], c[2]];
    }
    Ok(Patch { name, points })
}

fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

impl Patch {
    /// The patch at (s, t) in \[0,1\]²: s along the rows, t along the columns.
    pub fn point(&self, s: f64, t: f64) -> [f64; 3] {
        let (bs, bt) = (bernstein(s), bernstein(t));
        let mut p = [0.0; 3];
        for (i, row) in self.points.iter().enumerate() {
            for (j, q) in row.iter().enumerate() {
                let w = bs[i] * bt[j];
                for k in 0..3 {
                    p[k] += w * q[k];
                }
            }
        }
        p
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    if n > 0.0 {
        [a[0] / n, a[1] / n, a[2] / n]
    } else {
        a
    }
}

impl Surface {
    /// The surface as triangles in its own frame: each patch is sampled on
    /// a (divisions+1)² grid (at least 1 division), two triangles a cell,
    /// so `patches × 2 × divisions²` triangles, consistently oriented.
    pub fn triangles(&self, divisions: u32) -> Vec<[[f64; 3]; 3]> {
        self.triangles_with_parameters(divisions)
            .into_iter()
            .map(|(t, _)| t)
            .collect()
    }

    /// [`Surface::triangles`], each with its corners' patch parameters
    /// (s, t), the texture coordinates of a texture laid on each patch.
    pub fn triangles_with_parameters(&self, divisions: u32) -> Vec<(Triangle, TriangleUvs)> {
        let d = divisions.clamp(1, 1024) as usize;
        let step = 1.0 / d as f64;
        let mut out = Vec::with_capacity(self.patches.len() * 2 * d * d);
        for p in &self.patches {
            let grid: Vec<Vec<[f64; 3]>> = (0..=d)
                .map(|i| {
                    (0..=d)
                        .map(|j| p.point(i as f64 * step, j as f64 * step))
                        .collect()
                })
                .collect();
            for i in 0..d {
                for j in 0..d {
                    let at = |i: usize, j: usize| (grid[i][j], [i as f64 * step, j as f64 * step]);
                    let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    out.push(([a.0, b.0, c.0], [a.1, b.1, c.1]));
                    out.push(([a.0, c.0, e.0], [a.1, c.1, e.1]));
                }
            }
        }
        out
    }

    /// A point of the surface in turtle coordinates `[h, l, u]` (u along
    /// cpfg's up), as cpfg's patches.c places it: relative to the contact
    /// point, its x, y and z are carried by left = heading × up, heading
    /// and left × heading, and the result's x, y, z are then drawn along the
    /// turtle's L, H and U. A file whose frame is cpfg's own (heading +y,
    /// up −z) therefore lies along the turtle as it lies along that frame.
    /// The turtle draws it at `position + h·H + l·L + u·U`, times the
    /// surface's scale.
    pub fn to_turtle(&self, p: [f64; 3]) -> [f64; 3] {
        let h = unit(self.heading);
        let l = cross(h, unit(self.up));
        let u = cross(l, h);
        let r = sub(p, self.contact);
        let carried: [f64; 3] = std::array::from_fn(|i| r[0] * l[i] + r[1] * h[i] + r[2] * u[i]);
        [carried[1], carried[0], carried[2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(z: f64) -> String {
        let mut s = String::from("-1 1 -1 1 0 0\nCONTACT POINT  X: 0.0 Y: -1.0 Z: 0.0\nEND POINT  X: 0 Y: 1 Z: 0\nHEADING  X: 0.00 Y: 1.00 Z: 0.00\nUP  X: 0.00 Y: 0.00 Z: 1.00\nSIZE: 2.00\npatch\nTOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00\nAL: ~ A: ~ AR: ~ \nL: ~ R: ~ \nBL: ~ B: ~ BR: ~ \n");
        for i in 0..4 {
            for j in 0..4 {
                // An uneven grid in x and y, all at height z.
                let x = -1.0 + (j as f64 / 3.0).powi(2) * 2.0;
                let y = -1.0 + i as f64 * 0.6 + 0.05 * j as f64;
                s.push_str(&format!("{x} {y} {z}  "));
            }
            s.push('\n');
        }
        s
    }

    #[test]
    fn reads_header_and_patch() {
        let s = read_surface(&flat(0.5)).unwrap();
        assert_eq!(s.contact, [0.0, -1.0, 0.0]);
        assert_eq!(s.heading, [0.0, 1.0, 0.0]);
        assert_eq!(s.up, [0.0, 0.0, 1.0]);
        assert_eq!(s.size, 2.0);
        assert_eq!(s.patches.len(), 1);
        assert_eq!(s.patches[0].points[0][0], [-1.0, -1.0, 0.5]);
        // Corners of a Bézier patch are its corner control points.
        assert_eq!(s.patches[0].point(1.0, 1.0), s.patches[0].points[3][3]);
    }

    #[test]
    fn flat_patch_gives_coplanar_triangles() {
        let s = read_surface(&flat(0.5)).unwrap();
        for d in [1, 3, 8] {
            let t = s.triangles(d);
            assert_eq!(t.len(), 2 * (d * d) as usize);
            for tri in t {
                for v in tri {
                    assert!((v[2] - 0.5).abs() < 1e-12);
                }
                // Non-degenerate and all facing the same way.
                let n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
                assert!(n[2] < 0.0, "{n:?}");
            }
        }
    }

    #[test]
    fn turtle_frame() {
        let s = read_surface(&flat(0.0)).unwrap();
        // The contact point is the origin; +y (heading) is h, +z (up) is u,
        // and left = heading × up = +x (cpfg's patches.c).
        assert_eq!(s.to_turtle([0.0, -1.0, 0.0]), [0.0, 0.0, 0.0]);
        assert_eq!(s.to_turtle([0.0, 1.0, 0.0]), [2.0, 0.0, 0.0]);
        assert_eq!(s.to_turtle([0.0, -1.0, 3.0]), [0.0, 0.0, 3.0]);
        assert_eq!(s.to_turtle([1.0, -1.0, 0.0]), [0.0, 1.0, 0.0]);
        // Most corpus surfaces are drawn in cpfg's own frame, up −z: left
        // is −x there, and a point along −x or −z lies along L or U.
        let s = read_surface(&flat(0.0).replace("Z: 1.00\nSIZE", "Z: -1.00\nSIZE")).unwrap();
        assert_eq!(s.up, [0.0, 0.0, -1.0]);
        assert_eq!(s.to_turtle([-1.0, -1.0, 0.0]), [0.0, 1.0, 0.0]);
        assert_eq!(s.to_turtle([0.0, -1.0, -3.0]), [0.0, 0.0, 3.0]);
    }

    #[test]
    fn errors() {
        let good = flat(0.0);
        let e = read_surface(&good.replace("SIZE: 2.00", "SIZE: big")).unwrap_err();
        assert_eq!(e.0[0].code, codes::CPFG_SURFACE_FILE);
        let src = good.replace("HEADING  X: 0.00", "HEADING  Q: 0.00");
        let e = read_surface(&src).unwrap_err();
        assert!(src[e.0[0].span.clone().unwrap()].starts_with("HEADING"));
        let cut: String = good.lines().take(13).collect::<Vec<_>>().join("\n");
        assert!(read_surface(&cut).is_err());
        assert!(read_surface("").is_err());
    }

    proptest::proptest! {
        #[test]
        fn never_panics(s in "[A-Z: 0-9.\\n~-]{0,300}") {
            let _ = read_surface(&s);
            let _ = read_surface(&format!("{}{s}", &flat(0.0)[..200]));
        }
    }
}
