//! SVG output: one `<path>` per run of segments with the same colour and
//! width, one per filled polygon; coordinates in pixels of the fitted
//! picture, printed with at most 3 decimals so output is byte-stable.

use super::Picture;
use crate::ir::Rgb;
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

/// Appends `M x y L x y …` for the points to a path's `d`.
fn polyline(d: &mut String, pts: &[[f64; 2]]) {
    for (i, p) in pts.iter().enumerate() {
        let op = if i == 0 { 'M' } else { 'L' };
        let _ = write!(d, "{op}{} {}", num(p[0]), num(p[1]));
    }
}

/// The picture as an SVG document.
pub fn write(pic: &Picture) -> String {
    let mut out = String::new();
    let (w, h) = (pic.width, pic.height);
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    for (colour, pts) in &pic.polygons {
        let mut d = String::new();
        polyline(&mut d, pts);
        d.push('Z');
        let _ = writeln!(
            out,
            r#"<path d="{d}" fill="{}" fill-rule="evenodd"/>"#,
            hex(*colour)
        );
    }
    for run in &pic.runs {
        let mut d = String::new();
        for line in &run.lines {
            polyline(&mut d, line);
        }
        let _ = writeln!(
            out,
            r#"<path d="{d}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"/>"#,
            hex(run.colour),
            num(run.width)
        );
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(1.23456), "1.235");
    }
}
