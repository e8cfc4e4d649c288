//! User-defined functions (manual §5.5, §8.1.6): the `.func` files of vlab's
//! funcedit and the `.fset` function sets of its gallery, evaluated as
//! cpfg's `func(id, x)` does.
//!
//! A function is a cubic B-spline curve (x(t), y(t)) in the plane, with a
//! clamped uniform knot vector (cpfg's `Uk`: knots 0,0,0,0,1,2,…,n−2,
//! n−2,n−2,n−2 for n+1 control points), drawn so that it has one y for each
//! x in [0, 1]. `func(id, x)`:
//!
//! - clamps x to [0, 1];
//! - with `samples: n > 2` (in the file, or `function: file n` in the view
//!   file for old-format files), interpolates linearly between n values
//!   precomputed at i/(n−1);
//! - otherwise finds t by bisection until |x(t) − x| ≤ 0.001 and returns
//!   y(t) — cpfg's tolerance, so results match cpfg's, not the exact curve.
//!
//! File layout (`fver 1 1`): `name:`, `samples:`, optional `background…` and
//! `markers:` lines, `flip:` (ignored by cpfg), `points: n`, then n lines
//! `x y [multiplicity]` (a point with multiplicity k counts k times). The
//! older layout is `range: a b`, `points: n`, n lines `x y`. Control points
//! are read as single-precision floats, as cpfg reads them.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use std::ops::Range;

/// cpfg's bisection tolerance on x.
const MAX_ERROR: f64 = 0.001;
/// Bisection steps at most (cpfg loops until the tolerance is met, which
/// never happens for an x the curve does not reach).
const MAX_BISECTION: usize = 100;
/// cpfg reads the point count into a fixed array; more is not a function.
const MAX_POINTS: usize = 100_000;
const MAX_SAMPLES: usize = 1_000_000;

/// A user-defined function.
#[derive(Clone, Debug, PartialEq)]
pub struct Function {
    /// `name:` (the fver layout); `FUNCNAME` in `func(FUNCNAME, x)`.
    pub name: Option<String>,
    /// Control points after multiplicities are expanded.
    pub points: Vec<[f64; 2]>,
    /// `flip:` as written (cpfg ignores it).
    pub flip: bool,
    /// Precomputed sample count (0 or ≤ 2: evaluated exactly each time).
    pub samples: usize,
    values: Vec<f64>,
}

impl Function {
    /// Builds a function from control points (at least 4) and a sample count.
    pub fn new(points: Vec<[f64; 2]>, samples: usize) -> Option<Function> {
        if points.len() < 4 {
            return None;
        }
        let mut f = Function {
            name: None,
            points,
            flip: false,
            samples: 0,
            values: Vec::new(),
        };
        f.set_samples(samples);
        Some(f)
    }

    /// Sets the precomputed sample count (the view file's `function: file n`
    /// for old-format files; fver files carry their own).
    pub fn set_samples(&mut self, samples: usize) {
        let samples = samples.min(MAX_SAMPLES);
        self.samples = 0;
        self.values.clear();
        if samples > 2 {
            self.values = (0..samples)
                .map(|i| self.exact(i as f64 / (samples - 1) as f64))
                .collect();
            self.samples = samples;
        }
    }

    /// `func(id, x)` for this function.
    pub fn eval(&self, x: f64) -> f64 {
        let v = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        if self.samples > 2 {
            let index = v * (self.samples - 1) as f64;
            let i = (index.floor() as usize).min(self.samples - 1);
            if i == self.samples - 1 {
                return self.values[i];
            }
            let w2 = index - i as f64;
            (1.0 - w2) * self.values[i] + w2 * self.values[i + 1]
        } else {
            self.exact(v)
        }
    }

    /// The bisection cpfg uses when nothing is precomputed.
    fn exact(&self, v: f64) -> f64 {
        let (mut low, mut high) = (0.0f64, 1.0f64);
        let mut tst = [0.0, 0.0];
        for _ in 0..MAX_BISECTION {
            let check = (low + high) / 2.0;
            tst = self.point(check);
            if tst[0] > v {
                high = check;
            } else {
                low = check;
            }
            if (tst[0] - v).abs() <= MAX_ERROR {
                break;
            }
        }
        tst[1]
    }

    /// The curve at parameter d in [0, 1]. At d = 1 this is the last
    /// control point (the limit; cpfg's half-open basis would give (0, 0)
    /// there, a value its bisection never asks for).
    pub fn point(&self, d: f64) -> [f64; 2] {
        let n = self.points.len() as i64 - 1;
        let u = d.clamp(0.0, 1.0) * (n - 2) as f64;
        if u >= (n - 2) as f64 {
            return self.points[self.points.len() - 1];
        }
        let mut sum = [0.0, 0.0];
        for (k, p) in self.points.iter().enumerate() {
            let w = basis(k as i64, 4, u, n);
            sum[0] += p[0] * w;
            sum[1] += p[1] * w;
        }
        sum
    }

    /// Whether x grows along the control polygon (then the curve is a
    /// function of x, as funcedit means it to be).
    pub fn is_monotone(&self) -> bool {
        self.points.windows(2).all(|w| w[1][0] >= w[0][0])
    }
}

/// cpfg's knot `Uk(j)` for n+1 control points, order 4.
fn knot(j: i64, n: i64) -> i64 {
    if j < 4 {
        0
    } else if j > n {
        n - 2
    } else {
        j - 3
    }
}

/// Cox–de Boor, as cpfg's `N(k, t, u)`.
fn basis(k: i64, t: i64, u: f64, n: i64) -> f64 {
    if t == 1 {
        return if knot(k, n) as f64 <= u && u < knot(k + 1, n) as f64 {
            1.0
        } else {
            0.0
        };
    }
    let mut sum = 0.0;
    let div = knot(k + t - 1, n) - knot(k, n);
    if div != 0 {
        sum = (u - knot(k, n) as f64) / div as f64 * basis(k, t - 1, u, n);
    }
    let div = knot(k + t, n) - knot(k + 1, n);
    if div != 0 {
        sum += (knot(k + t, n) as f64 - u) / div as f64 * basis(k + 1, t - 1, u, n);
    }
    sum
}

/// Lines of a text with their byte spans (line break excluded).
struct Lines<'a> {
    text: &'a str,
    at: usize,
}

impl<'a> Lines<'a> {
    fn next_line(&mut self) -> Option<(&'a str, Range<usize>)> {
        if self.at >= self.text.len() {
            return None;
        }
        let rest = &self.text[self.at..];
        let len = rest.find('\n').map_or(rest.len(), |k| k + 1);
        let line = rest[..len].trim_end_matches(['\n', '\r']);
        let span = self.at..self.at + line.len();
        self.at += len;
        Some((line, span))
    }
    /// The next line that is not blank.
    fn next_nonblank(&mut self) -> Option<(&'a str, Range<usize>)> {
        loop {
            let (l, s) = self.next_line()?;
            if !l.trim().is_empty() {
                return Some((l, s));
            }
        }
    }
    fn peek_nonblank(&self) -> Option<&'a str> {
        let mut copy = Lines {
            text: self.text,
            at: self.at,
        };
        copy.next_nonblank().map(|(l, _)| l)
    }
    fn end_span(&self) -> Range<usize> {
        self.text.len()..self.text.len()
    }
}

fn error(span: Range<usize>, msg: impl Into<String>, expected: &str) -> Diagnostics {
    Diagnostics(vec![Diagnostic::at(codes::CPFG_FUNCTION_FILE, span, msg)
        .with_label(format!("expected {expected}"))])
}

/// `key: value` on a line, the value trimmed.
fn keyed<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    line.trim().strip_prefix(key).map(str::trim)
}

fn f32_num(s: &str) -> Option<f64> {
    s.parse::<f32>()
        .ok()
        .filter(|x| x.is_finite())
        .map(f64::from)
}

/// Reads one function starting at the cursor.
fn read_one(lines: &mut Lines) -> Result<Function, Diagnostics> {
    let Some((first, span)) = lines.next_nonblank() else {
        return Err(error(
            lines.end_span(),
            "the function file is empty",
            "`fver 1 1`",
        ));
    };
    let fver = first.split_whitespace().collect::<Vec<_>>();
    let (name, samples, flip) = if keyed(first, "range:").is_some() {
        (None, 0, false)
    } else if fver.first() == Some(&"fver") {
        if fver.get(1..3) != Some(&["1", "1"][..]) {
            return Err(error(
                span,
                format!("unsupported function format `{}`", first.trim()),
                "`fver 1 1`",
            ));
        }
        let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
        let Some(name) = keyed(l, "name:").filter(|n| !n.is_empty()) else {
            return Err(error(s, "missing `name:` line", "`name: NAME`"));
        };
        let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
        let Some(samples) = keyed(l, "samples:").and_then(|v| v.parse::<i64>().ok()) else {
            return Err(error(s, "missing `samples:` line", "`samples: N`"));
        };
        // Optional lines cpfg skips: a background image and markers.
        if lines
            .peek_nonblank()
            .is_some_and(|l| l.trim_start().starts_with('b'))
        {
            lines.next_nonblank();
            lines.next_nonblank();
        }
        if let Some(m) = lines.peek_nonblank().and_then(|l| keyed(l, "markers:")) {
            let m: usize = m.parse().unwrap_or(0);
            lines.next_nonblank();
            for _ in 0..m.min(MAX_POINTS) {
                lines.next_nonblank();
            }
        }
        let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
        let Some(flip) = keyed(l, "flip:") else {
            return Err(error(
                s,
                "missing `flip:` line",
                "`flip: on` or `flip: off`",
            ));
        };
        (
            Some(name.to_string()),
            samples.max(0) as usize,
            flip == "on",
        )
    } else {
        return Err(error(
            span,
            "not a function file",
            "`fver 1 1` or `range: 0 1`",
        ));
    };
    let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
    let Some(n) = keyed(l, "points:").and_then(|v| v.parse::<usize>().ok()) else {
        return Err(error(s, "missing `points:` line", "`points: N`"));
    };
    if !(4..=MAX_POINTS).contains(&n) {
        return Err(error(
            s,
            format!("{n} control points; cpfg needs at least 4"),
            "4 or more points",
        ));
    }
    let mut points = Vec::with_capacity(n);
    for _ in 0..n {
        let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
        let w: Vec<&str> = l.split_whitespace().collect();
        let parsed = match w.as_slice() {
            [x, y] => f32_num(x).zip(f32_num(y)).map(|p| (p, 1)),
            [x, y, m] if name.is_some() => f32_num(x)
                .zip(f32_num(y))
                .zip(f32_num(m))
                .map(|(p, m)| (p, m.clamp(0.0, MAX_POINTS as f64) as usize)),
            _ => None,
        };
        let Some(((x, y), mult)) = parsed else {
            return Err(error(
                s,
                "malformed control point",
                "`x y` (or `x y multiplicity`)",
            ));
        };
        for _ in 0..mult {
            points.push([x, y]);
        }
        if points.len() > MAX_POINTS {
            return Err(error(s, "too many control points", "fewer points"));
        }
    }
    let mut f = Function::new(points, samples).ok_or_else(|| {
        error(
            lines.end_span(),
            "fewer than 4 control points",
            "4 or more points",
        )
    })?;
    f.name = name;
    f.flip = flip;
    Ok(f)
}

/// Where the names of the functions of a `.func` or `.fset` text are
/// written (the values of its `name:` lines), in order.
pub fn name_spans(text: &str) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let start = at + line.len() - line.trim_start().len();
        at += line.len();
        if let Some(value) = line.trim_start().strip_prefix("name:") {
            let from = start + "name:".len() + value.len() - value.trim_start().len();
            out.push(from..from + value.trim().len());
        }
    }
    out
}

/// Reads a `.func` file.
pub fn read_func(text: &str) -> Result<Function, Diagnostics> {
    read_one(&mut Lines { text, at: 0 })
}

/// Reads a `.fset` function set: the functions with their names, in order
/// (`func(k, x)` is the k-th, from 1).
pub fn read_fset(text: &str) -> Result<Vec<(String, Function)>, Diagnostics> {
    let mut lines = Lines { text, at: 0 };
    let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
    if l.split_whitespace().collect::<Vec<_>>() != ["funcgalleryver", "1", "1"] {
        return Err(error(s, "not a function set", "`funcgalleryver 1 1`"));
    }
    let (l, s) = lines.next_nonblank().unwrap_or(("", lines.end_span()));
    let Some(items) = keyed(l, "items:").and_then(|v| v.parse::<usize>().ok()) else {
        return Err(error(s, "missing `items:` line", "`items: N`"));
    };
    let mut out = Vec::new();
    for k in 0..items.min(MAX_POINTS) {
        let f = read_one(&mut lines)?;
        let name = f
            .name
            .clone()
            .unwrap_or_else(|| format!("function{}", k + 1));
        out.push((name, f));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINEAR: &str = "fver 1 1\nname: ramp\nsamples: 0\nflip: off\npoints: 4\n0 0\n0.333333 0.333333\n0.666667 0.666667\n1 1\n";

    #[test]
    fn reads_the_fver_layout() {
        let f = read_func(LINEAR).unwrap();
        assert_eq!(f.name.as_deref(), Some("ramp"));
        assert_eq!(f.points.len(), 4);
        assert!(!f.flip && f.is_monotone());
        // Collinear, evenly spaced control points: the curve is y = x, up
        // to cpfg's bisection tolerance.
        for i in 0..=20 {
            let x = i as f64 / 20.0;
            assert!(
                (f.eval(x) - x).abs() <= 2.0 * MAX_ERROR,
                "{x}: {}",
                f.eval(x)
            );
        }
        // Clamped outside [0, 1].
        assert_eq!(f.eval(-3.0), f.eval(0.0));
        assert_eq!(f.eval(7.0), f.eval(1.0));
    }

    #[test]
    fn multiplicity_repeats_points() {
        let f = read_func("fver 1 1\nname: m\nsamples: 10\nflip: on\npoints: 4\n0 0 1\n0.5 1 3\n1 0 1\n0.9 0.2 0\n").unwrap();
        assert_eq!(
            f.points,
            [[0.0, 0.0], [0.5, 1.0], [0.5, 1.0], [0.5, 1.0], [1.0, 0.0]]
        );
        assert!(f.flip);
        assert_eq!(f.samples, 10);
        // A triple control point: the cubic curve passes through it.
        let p = f.point(0.5);
        assert!(
            (p[0] - 0.5).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12,
            "{p:?}"
        );
    }

    #[test]
    fn samples_interpolate_linearly() {
        let exact = read_func(&LINEAR.replace("samples: 0", "samples: 2")).unwrap();
        assert_eq!(exact.samples, 0);
        let mut f = read_func("range: 0.0 1.0\npoints: 4\n0 0\n0.2 1\n0.8 1\n1 0\n").unwrap();
        assert_eq!(f.name, None);
        let before = f.eval(0.37);
        f.set_samples(3);
        // Three samples: at 0, 0.5 and 1, linear between.
        let (a, b) = (f.eval(0.0), f.eval(0.5));
        assert!((f.eval(0.25) - (a + b) / 2.0).abs() < 1e-12);
        assert!((f.eval(0.37) - before).abs() > 1e-3);
    }

    #[test]
    fn sets_and_errors() {
        let set = format!(
            "funcgalleryver 1 1\nitems: 2\n{LINEAR}{}",
            LINEAR.replace("ramp", "two")
        );
        let fs = read_fset(&set).unwrap();
        assert_eq!(
            fs.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
            ["ramp", "two"]
        );

        let e =
            read_func("fver 1 1\nname: x\nsamples: 10\nflip: off\npoints: 3\n0 0\n0.5 1\n1 0\n")
                .unwrap_err();
        assert_eq!(e.0[0].code, codes::CPFG_FUNCTION_FILE);
        let src = "fver 1 1\nname: x\nsamples: 10\nflip: off\npoints: 4\n0 0\n0.5 oops\n";
        let e = read_func(src).unwrap_err();
        assert_eq!(&src[e.0[0].span.clone().unwrap()], "0.5 oops");
        assert!(read_func("").is_err());
        assert!(read_fset("funcgalleryver 1 1\nitems: 3\n").is_err());
        assert!(read_func("garbage\n").is_err());
    }

    proptest::proptest! {
        #[test]
        fn never_panics(s in "[a-z: 0-9.\\n-]{0,200}") {
            let _ = read_func(&s);
            let _ = read_fset(&s);
            if let Ok(f) = read_func(&format!("fver 1 1\nname: a\nsamples: 5\nflip: off\n{s}")) {
                f.eval(0.5);
            }
        }
    }
}
