//! Palettes that name a notation: Fractint's, which its front end gives
//! every system it reads and the `.gft` front end and emitter know by name
//! (`colours fractint`). The IR's own default palette is beside its
//! colours ([`crate::ir::colours::DEFAULT_PALETTE`]).

use crate::ir::Rgb;

/// Fractint's default 256-colour palette (the VGA default): the 16 EGA
/// colours, a grey ramp, hue circles at three intensities and saturations,
/// then black. graftal draws on white where Fractint draws on black, so
/// the two ends of the EGA greys are exchanged: the default colour 15
/// (white on Fractint's screen) is black, and colour 0 (Fractint's
/// background) is white.
pub fn fractint_palette() -> Vec<Rgb> {
    // Built once: every entry of a library of thousands gets a copy.
    static PALETTE: std::sync::LazyLock<Vec<Rgb>> = std::sync::LazyLock::new(build_palette);
    PALETTE.clone()
}

fn build_palette() -> Vec<Rgb> {
    const EGA: [(u8, u8, u8); 16] = [
        (255, 255, 255),
        (0, 0, 170),
        (0, 170, 0),
        (0, 170, 170),
        (170, 0, 0),
        (170, 0, 170),
        (170, 85, 0),
        (170, 170, 170),
        (85, 85, 85),
        (85, 85, 255),
        (85, 255, 85),
        (85, 255, 255),
        (255, 85, 85),
        (255, 85, 255),
        (255, 255, 85),
        (0, 0, 0),
    ];
    let mut p: Vec<Rgb> = EGA.iter().map(|&(r, g, b)| Rgb(r, g, b)).collect();
    // 16..32: grey ramp (VGA levels 0..63 scaled to 0..255).
    const GREYS: [u8; 16] = [0, 5, 8, 11, 14, 17, 20, 24, 28, 32, 36, 40, 45, 50, 56, 63];
    p.extend(GREYS.iter().map(|&g| {
        let v = (u16::from(g) * 255 / 63) as u8;
        Rgb(v, v, v)
    }));
    // 32..248: for each intensity (high, medium, low) and saturation (full,
    // half, low), the 24 hues of the VGA circle.
    for (hi, lo_sat) in [(63u16, [0u16, 31, 45]), (28, [0, 14, 20]), (16, [0, 8, 11])] {
        for lo in lo_sat {
            // The circle: blue -> magenta -> red -> yellow -> green -> cyan -> blue.
            let steps = [
                lo,
                lo + (hi - lo) / 4,
                lo + (hi - lo) / 2,
                lo + 3 * (hi - lo) / 4,
                hi,
            ];
            let mut circle: Vec<(u16, u16, u16)> = Vec::new();
            for &r in &steps[..4] {
                circle.push((r, lo, hi));
            }
            for &b in steps[1..].iter().rev() {
                circle.push((hi, lo, b));
            }
            for &g in &steps[..4] {
                circle.push((hi, g, lo));
            }
            for &r in steps[1..].iter().rev() {
                circle.push((r, hi, lo));
            }
            for &b in &steps[..4] {
                circle.push((lo, hi, b));
            }
            for &g in steps[1..].iter().rev() {
                circle.push((lo, g, hi));
            }
            let scale = |v: u16| (v * 255 / 63) as u8;
            p.extend(
                circle
                    .iter()
                    .take(24)
                    .map(|&(r, g, b)| Rgb(scale(r), scale(g), scale(b))),
            );
        }
    }
    p.resize(256, Rgb(0, 0, 0));
    p
}
