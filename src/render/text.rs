//! Text in pictures (cpfg's labels): an 8×8 bitmap font (`font8x8`, the
//! public-domain IBM PC glyphs), written into RGBA rows pixel for pixel,
//! as cpfg writes its labels with OpenGL bitmaps, unscaled and unlit. SVG
//! writes `<text>` instead.

use crate::ir::Rgb;
use font8x8::UnicodeFonts;

/// A glyph's size and advance in pixels.
pub const GLYPH: i64 = 8;

/// Text at a place in a picture: its baseline's left end, in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    pub at: [f64; 2],
    pub text: String,
    pub colour: Rgb,
}

/// Writes `label` into `rgba`, the rows `first..first + rows` of a picture
/// `width` pixels wide (4 bytes a pixel, opaque colours); what falls
/// outside those rows or the picture is left out. A character the font
/// lacks is a blank.
pub fn write(rgba: &mut [u8], width: u32, first: u32, label: &Placed) {
    let (width, first) = (i64::from(width), i64::from(first));
    let rows = rgba.len() as i64 / (4 * width.max(1));
    // Far off the picture (or not a number) is nowhere on it; within this
    // bound the arithmetic below cannot overflow.
    const FAR: f64 = 1e9;
    if !(label.at[0].abs() < FAR && label.at[1].abs() < FAR) {
        return;
    }
    let left = label.at[0].round() as i64;
    // The glyphs' bottom row sits on the baseline.
    let top = label.at[1].round() as i64 - (GLYPH - 1);
    let Rgb(r, g, b) = label.colour;
    for (k, c) in label.text.chars().enumerate() {
        let Some(glyph) = font8x8::BASIC_FONTS
            .get(c)
            .or_else(|| font8x8::LATIN_FONTS.get(c))
        else {
            continue;
        };
        let x0 = left + GLYPH * k.min(1 << 20) as i64;
        if x0 >= width {
            break;
        }
        for (dy, bits) in glyph.iter().enumerate() {
            let y = top + dy as i64 - first;
            if !(0..rows).contains(&y) {
                continue;
            }
            for dx in 0..GLYPH {
                let x = x0 + dx;
                if bits & (1 << dx) == 0 || !(0..width).contains(&x) {
                    continue;
                }
                let at = ((y * width + x) * 4) as usize;
                rgba[at..at + 4].copy_from_slice(&[r, g, b, 255]);
            }
        }
    }
}

/// `label` as an SVG `<text>` element (monospace, 10 pixels, as cpfg's
/// default label font).
pub fn svg(label: &Placed) -> String {
    let escaped: String = label
        .text
        .chars()
        .map(|c| match c {
            '<' => "&lt;".to_string(),
            '>' => "&gt;".to_string(),
            '&' => "&amp;".to_string(),
            c if c.is_control() => String::new(),
            c => c.to_string(),
        })
        .collect();
    let Rgb(r, g, b) = label.colour;
    format!(
        r##"<text x="{:.2}" y="{:.2}" fill="#{r:02x}{g:02x}{b:02x}" font-family="monospace" font-size="10" xml:space="preserve">{escaped}</text>"##,
        label.at[0], label.at[1]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn label(text: &str, at: [f64; 2]) -> Placed {
        Placed {
            at,
            text: text.into(),
            colour: Rgb(255, 0, 0),
        }
    }

    /// "1" in font8x8 is 0x0C 0x0E 0x0C 0x0C 0x0C 0x0C 0x3F 0x00: its
    /// pixels land on the rows above the baseline, left to right from the
    /// low bit.
    #[test]
    fn a_glyph_lands_on_its_pixels() {
        let (w, h) = (16u32, 16u32);
        let mut rgba = vec![0u8; (w * h * 4) as usize];
        write(&mut rgba, w, 0, &label("1", [2.0, 9.0]));
        let lit = |x: i64, y: i64| rgba[((y * i64::from(w) + x) * 4) as usize] == 255;
        // Row 0 of the glyph (0x0C: bits 2 and 3) is picture row 9 - 7 = 2.
        assert!(lit(2 + 2, 2) && lit(2 + 3, 2) && !lit(2 + 1, 2) && !lit(2 + 4, 2));
        // Row 6 (0x3F: bits 0 to 5) is row 8.
        assert!((0..6).all(|dx| lit(2 + dx, 8)) && !lit(2 + 6, 8));
        let count = rgba.chunks(4).filter(|p| p[3] == 255).count();
        let bits: u32 = [0x0Cu8, 0x0E, 0x0C, 0x0C, 0x0C, 0x0C, 0x3F]
            .iter()
            .map(|b| b.count_ones())
            .sum();
        assert_eq!(count, bits as usize);
        // Written in two bands, the same pixels.
        let mut banded = vec![0u8; (w * h * 4) as usize];
        let (top, bottom) = banded.split_at_mut((w * 5 * 4) as usize);
        write(top, w, 0, &label("1", [2.0, 9.0]));
        write(bottom, w, 5, &label("1", [2.0, 9.0]));
        assert_eq!(banded, rgba);
    }

    /// Text off the picture, far off or not finite, writes nothing and
    /// never panics.
    #[test]
    fn text_off_the_picture_is_left_out() {
        let mut rgba = vec![0u8; 8 * 8 * 4];
        for at in [
            [-100.0, 4.0],
            [4.0, 1e300],
            [f64::NAN, 0.0],
            [-1e300, -1e300],
        ] {
            write(&mut rgba, 8, 0, &label("ABC", at));
        }
        assert!(rgba.iter().all(|&b| b == 0));
        assert!(svg(&label("a<b&", [1.0, 2.0])).contains(">a&lt;b&amp;</text>"));
    }
}
