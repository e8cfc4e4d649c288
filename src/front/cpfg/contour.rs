//! Contour files (`.con`, manual §5.5 and §8.1.5): planar B-spline curves
//! written by vlab's cuspy, the cross-sections of generalized cylinders
//! (`contour:`) and the curves `curveX(id, t)` reads (`curve:`).
//!
//! Three layouts (cpfg's `process_contour_file` and `CCurveXYZ`):
//!
//! * `cver 1 1` … `cver 1 3`: `name:`, `points: n total`, `type:` (`open` or
//!   `closed` in 1.1; `or`, `cr`, `oe`, `ce` after: open or closed, regular
//!   or end-point — read as regular, as cpfg does), `samples: s` (1.3), an
//!   optional `background` line pair and `markers: k` with k lines (1.3),
//!   then n lines `x y z multiplicity`;
//! * `version: 1.4` (the curve gallery's): `key: value` lines (`points: n`,
//!   `type: bspline`, …) then n lines `x y z multiplicity`;
//! * the oldest: a line `n dim closed|open`, then n points of `dim`
//!   coordinates.
//!
//! A point of multiplicity m counts m times. The curve is the uniform cubic
//! B-spline of the points: `n − 3` segments when open, `n` (wrapping round)
//! when closed.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use std::ops::Range;

/// The most control points a contour may have, multiplicities counted.
const MAX_POINTS: usize = 10_000;

/// Samples per B-spline segment when measuring lengths.
const PER_SEGMENT: usize = 32;

/// A contour file: its control points (multiplicities expanded) and
/// whether the curve closes.
#[derive(Clone, Debug, PartialEq)]
pub struct ContourFile {
    pub points: Vec<[f64; 3]>,
    pub closed: bool,
    /// The points a cross-section has (`samples:` of `cver 1 3`): cpfg
    /// sweeps the curve sampled at that many points, so a file saying 8
    /// makes cylinders of 8 faces a ring, not [`crate::ir::look::CONTOUR_SAMPLES`].
    pub samples: Option<usize>,
}

fn error(span: Range<usize>, msg: impl Into<String>, expected: &str) -> Diagnostics {
    Diagnostics(vec![Diagnostic::at(codes::CPFG_CONTOUR_FILE, span, msg)
        .with_label(format!("expected {expected}"))])
}

/// The lines of a file with their spans, blank ones skipped.
fn lines(text: &str) -> Vec<(&str, Range<usize>)> {
    let mut out = Vec::new();
    let mut at = 0;
    for l in text.split_inclusive('\n') {
        let t = l.trim();
        if !t.is_empty() {
            let start = at + (l.len() - l.trim_start().len());
            out.push((t, start..start + t.len()));
        }
        at += l.len();
    }
    out
}

fn nums(s: &str) -> Option<Vec<f64>> {
    s.split_whitespace()
        .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect()
}

/// Reads a contour file.
pub fn read_contour(text: &str) -> Result<ContourFile, Diagnostics> {
    let ls = lines(text);
    let Some((first, span)) = ls.first().cloned() else {
        return Err(error(
            0..0,
            "empty contour file",
            "`cver 1 3` or `version: 1.4`",
        ));
    };
    let file = if let Some(v) = first.strip_prefix("cver") {
        read_cver(v.trim(), span, &ls[1..])?
    } else if first.starts_with("version:") {
        read_gallery(&ls[1..], span)?
    } else {
        read_oldest(&ls, span)?
    };
    let least = if file.closed { 3 } else { 4 };
    if file.points.len() < least {
        let end = ls.last().map_or(0..0, |l| l.1.clone());
        return Err(error(
            end,
            format!(
                "a contour of {} points (multiplicities counted)",
                file.points.len()
            ),
            &format!(
                "at least {least} for an {} B-spline",
                if file.closed { "closed" } else { "open" }
            ),
        ));
    }
    Ok(file)
}

/// The value after `key:` on line `l`, or an error naming `key`.
fn field<'t>(
    l: Option<&(&'t str, Range<usize>)>,
    key: &str,
    at: Range<usize>,
) -> Result<&'t str, Diagnostics> {
    match l {
        Some((t, _)) if t.starts_with(key) => Ok(t[key.len()..].trim()),
        Some((_, s)) => Err(error(
            s.clone(),
            format!("`{key}` line missing"),
            &format!("`{key} …`"),
        )),
        None => Err(error(
            at,
            format!("`{key}` line missing"),
            &format!("`{key} …`"),
        )),
    }
}

/// `cver M m` files.
fn read_cver(
    version: &str,
    span: Range<usize>,
    ls: &[(&str, Range<usize>)],
) -> Result<ContourFile, Diagnostics> {
    let v = nums(version).unwrap_or_default();
    let minor = match v.as_slice() {
        [1.0, m] if (1.0..=3.0).contains(m) => *m as u32,
        _ => {
            return Err(error(
                span,
                format!("unknown contour version `cver {version}`"),
                "`cver 1 1`, `cver 1 2` or `cver 1 3`",
            ))
        }
    };
    let mut k = 1; // past `name:`
    let counts = field(ls.get(k), "points:", span.clone())?;
    let n = match nums(counts).as_deref() {
        Some([n, _] | [n]) if *n >= 0.0 => *n as usize,
        _ => {
            return Err(error(
                ls[k].1.clone(),
                "malformed `points:` line",
                "`points: n total`",
            ))
        }
    };
    k += 1;
    let kind = field(ls.get(k), "type:", span.clone())?;
    let closed = match (minor, kind.chars().next()) {
        (1, _) => !kind.starts_with("open"),
        (_, Some('o')) => false,
        (_, Some('c')) => true,
        _ => {
            return Err(error(
                ls[k].1.clone(),
                format!("unknown contour type `{kind}`"),
                "`or`, `cr`, `oe` or `ce`",
            ))
        }
    };
    k += 1;
    let mut samples = None;
    if minor == 3 {
        let s = field(ls.get(k), "samples:", span.clone())?;
        samples = nums(s)
            .and_then(|v| v.first().copied())
            .filter(|n| *n >= 1.0)
            .map(|n| n.min(1e6) as usize);
        k += 1;
        if ls.get(k).is_some_and(|l| l.0.starts_with('b')) {
            k += 2;
        }
        if let Some(m) = ls.get(k).and_then(|l| l.0.strip_prefix("markers:")) {
            k += 1 + nums(m)
                .and_then(|v| v.first().copied())
                .unwrap_or(0.0)
                .clamp(0.0, 1e6) as usize;
        }
    }
    let points = control_points(ls.get(k..).unwrap_or(&[]), n, 4, span)?;
    Ok(ContourFile {
        points,
        closed,
        samples,
    })
}

/// `version: 1.4` files of the curve gallery: open B-splines.
fn read_gallery(
    ls: &[(&str, Range<usize>)],
    span: Range<usize>,
) -> Result<ContourFile, Diagnostics> {
    let header = ls.iter().take_while(|l| l.0.contains(':')).count();
    let mut n = None;
    for (t, s) in &ls[..header] {
        if let Some(v) = t.strip_prefix("points:") {
            n = nums(v)
                .and_then(|v| v.first().copied())
                .filter(|n| *n >= 0.0)
                .map(|n| n as usize);
        } else if let Some(v) = t.strip_prefix("type:") {
            if v.trim() != "bspline" {
                return Err(error(
                    s.clone(),
                    format!("curve type `{}` is not read", v.trim()),
                    "`type: bspline`",
                ));
            }
        }
    }
    let n = n.ok_or_else(|| error(span.clone(), "no `points:` line", "`points: n`"))?;
    let points = control_points(&ls[header..], n, 4, span)?;
    Ok(ContourFile {
        points,
        closed: false,
        samples: None,
    })
}

/// The oldest layout: `n dim closed|open`, then the points.
fn read_oldest(
    ls: &[(&str, Range<usize>)],
    span: Range<usize>,
) -> Result<ContourFile, Diagnostics> {
    let w: Vec<&str> = ls[0].0.split_whitespace().collect();
    let (n, dim) = match (
        w.first().and_then(|x| x.parse::<usize>().ok()),
        w.get(1).and_then(|x| x.parse::<usize>().ok()),
    ) {
        (Some(n), Some(d @ (2 | 3))) if w.len() == 3 => (n, d),
        _ => {
            return Err(error(
                span,
                "unknown contour layout",
                "`cver 1 3`, `version: 1.4` or `n dim closed|open`",
            ))
        }
    };
    let coords: Vec<f64> = ls[1..]
        .iter()
        .flat_map(|l| nums(l.0).unwrap_or_default())
        .collect();
    if n > MAX_POINTS || coords.len() < n * dim {
        let end = ls.last().map_or(span, |l| l.1.clone());
        return Err(error(
            end,
            format!("the file gives fewer than {n} points of {dim} coordinates"),
            "more points",
        ));
    }
    let points = coords
        .chunks(dim)
        .take(n)
        .map(|c| [c[0], c[1], c.get(2).copied().unwrap_or(0.0)])
        .collect();
    Ok(ContourFile {
        points,
        closed: w[2] == "closed",
        samples: None,
    })
}

/// `n` lines `x y z multiplicity`, expanded.
fn control_points(
    ls: &[(&str, Range<usize>)],
    n: usize,
    width: usize,
    span: Range<usize>,
) -> Result<Vec<[f64; 3]>, Diagnostics> {
    let mut out = Vec::new();
    for k in 0..n {
        let Some((t, s)) = ls.get(k) else {
            let at = ls.last().map_or(span, |l| l.1.clone());
            return Err(error(
                at,
                format!("the file ends after {k} of its {n} points"),
                "more points",
            ));
        };
        let v = nums(t)
            .filter(|v| v.len() == width)
            .ok_or_else(|| error(s.clone(), "malformed contour point", "`x y z multiplicity`"))?;
        let m = v[3].clamp(0.0, MAX_POINTS as f64 + 1.0) as usize;
        if out.len() + m > MAX_POINTS {
            return Err(error(
                s.clone(),
                format!("more than {MAX_POINTS} points"),
                "fewer points",
            ));
        }
        out.extend(std::iter::repeat_n([v[0], v[1], v[2]], m));
    }
    Ok(out)
}

impl ContourFile {
    /// The point at B-spline parameter `t` (segment `⌊t⌋`).
    fn at(&self, t: f64) -> [f64; 3] {
        let n = self.points.len();
        let segments = self.segments();
        let first = (t.floor().max(0.0) as usize).min(segments - 1);
        let u = t - first as f64;
        let (u2, u3) = (u * u, u * u * u);
        let b = [
            (1.0 - u).powi(3) / 6.0,
            (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0,
            (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0,
            u3 / 6.0,
        ];
        let mut p = [0.0; 3];
        for (k, w) in b.iter().enumerate() {
            let q = self.points[(first + k) % n];
            for c in 0..3 {
                p[c] += w * q[c];
            }
        }
        p
    }

    fn segments(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len() - 3
        }
    }

    /// `samples + 1` points at equal arc length along the curve (for a
    /// closed one the last is the first), and the curve's length (in the
    /// xy plane, as cpfg measures it).
    pub fn sample(&self, samples: usize) -> (Vec<[f64; 3]>, f64) {
        let samples = samples.max(1);
        let steps = self.segments() * PER_SEGMENT;
        let dense: Vec<[f64; 3]> = (0..=steps)
            .map(|k| self.at(k as f64 / PER_SEGMENT as f64))
            .collect();
        let mut lengths = vec![0.0];
        for w in dense.windows(2) {
            let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
            lengths.push(lengths.last().copied().unwrap_or(0.0) + d);
        }
        let total = lengths.last().copied().unwrap_or(0.0);
        let mut out = Vec::with_capacity(samples + 1);
        let mut j = 0;
        for k in 0..=samples {
            let target = total * k as f64 / samples as f64;
            while j + 1 < lengths.len() - 1 && lengths[j + 1] < target {
                j += 1;
            }
            let span = lengths[j + 1] - lengths[j];
            let f = if span > 0.0 {
                ((target - lengths[j]) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            out.push(std::array::from_fn(|c| {
                dense[j][c] + (dense[j + 1][c] - dense[j][c]) * f
            }));
        }
        if self.closed {
            out[samples] = out[0];
        }
        (out, total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LEAF: &str = "cver 1 3\nname: leaf.con\npoints: 4 8\ntype: or\nsamples: 8\n\
                        -1 -2 0 3\n-1 0 0 1\n1 0 0 1\n1 -2 0 3\n";

    #[test]
    fn cver_files_expand_multiplicities() {
        let c = read_contour(LEAF).unwrap();
        assert!(!c.closed);
        assert_eq!(c.points.len(), 8);
        assert_eq!(c.points[..3], [[-1.0, -2.0, 0.0]; 3]);
        // A tripled end point is where an open uniform B-spline starts.
        let (pts, _) = c.sample(16);
        assert_eq!(pts.len(), 17);
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9);
        assert!(close(pts[0], [-1.0, -2.0, 0.0]), "{:?}", pts[0]);
        assert!(close(pts[16], [1.0, -2.0, 0.0]), "{:?}", pts[16]);
    }

    #[test]
    fn samples_are_equally_spaced_and_closed_curves_close() {
        let square = "4 2 closed\n1 1\n-1 1\n-1 -1\n1 -1\n";
        let c = read_contour(square).unwrap();
        assert!(c.closed);
        let (pts, len) = c.sample(40);
        assert_eq!(pts[0], pts[40]);
        let d = |a: [f64; 3], b: [f64; 3]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
        let steps: Vec<f64> = pts.windows(2).map(|w| d(w[0], w[1])).collect();
        let (lo, hi) = steps
            .iter()
            .fold((f64::MAX, 0.0f64), |(l, h), &s| (l.min(s), h.max(s)));
        assert!(hi - lo < 0.01 * hi, "{lo} {hi}");
        // The curve lies inside the control square: shorter than its 8.
        assert!(len > 4.0 && len < 8.0, "{len}");
    }

    #[test]
    fn gallery_curves_read() {
        let src = "version: 1.4\ncontact: 0 0 0\nend: 0 0 0\nheading: 0 1 0\nup: 0 0 -1\nsize: 1\n\
                   points: 4\nrange: 0.0 1.0\ndimension: 4\ntype: bspline\n\
                   0.27 -0.45 0 3\n0.27 -0.11 0 1\n0.17 0.18 0 1\n0.0 0.2 0 3\n";
        let c = read_contour(src).unwrap();
        assert_eq!((c.points.len(), c.closed), (8, false));
        let (pts, len) = c.sample(10);
        assert!(
            (pts[10][1] - 0.2).abs() < 1e-9 && len > 0.7 && len < 0.85,
            "{len}"
        );
    }

    #[test]
    fn bad_files_say_where() {
        let cases = [
            ("", "empty"),
            ("cver 2 0\n", "unknown contour version"),
            (
                "cver 1 3\nname: x\npoints: 3 3\ntype: or\nsamples: 8\n0 0 0 1\n1 0 0 1\n",
                "ends after 2",
            ),
            (
                "cver 1 3\nname: x\npoints: 2 2\ntype: xx\n",
                "unknown contour type",
            ),
            (
                "cver 1 3\nname: x\npoints: 1 1\ntype: or\nsamples: 8\n0 0 zero 1\n",
                "malformed contour point",
            ),
            (
                "cver 1 2\nname: x\npoints: 2 2\ntype: or\n0 0 0 1\n1 0 0 1\n",
                "a contour of 2 points",
            ),
            ("version: 1.4\npoints: 4\ntype: bezier\n", "not read"),
            ("hello\n", "unknown contour layout"),
            (
                "cver 1 2\nname: x\npoints: 1 1\ntype: or\n0 0 0 99999999\n",
                "more than",
            ),
        ];
        for (src, msg) in cases {
            let d = read_contour(src).unwrap_err();
            assert_eq!(d.0[0].code, codes::CPFG_CONTOUR_FILE);
            assert!(d.0[0].message.contains(msg), "{src:?}: {}", d.0[0].message);
            let span = d.0[0].span.clone().unwrap();
            assert!(span.end <= src.len(), "{src:?}");
        }
    }
}
