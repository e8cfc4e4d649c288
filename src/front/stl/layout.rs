//! Layout colours as STL writes them (Delphi names from the stdlib table,
//! or `$00BBGGRR`); the shapes' geometry is the layout module's
//! ([`crate::layout::shapes`]).

use crate::ir::Rgb;
pub use crate::layout::shapes::*;

/// The colour `$00BBGGRR` (Delphi's TColor: red in the low byte), if the
/// text is `$` and one to eight hex digits whose top byte is zero.
pub fn hex_colour(text: &str) -> Option<Rgb> {
    let hex = text.strip_prefix('$')?;
    if hex.is_empty() || hex.len() > 8 {
        return None;
    }
    let v = u32::from_str_radix(hex, 16).ok()?;
    if v > 0x00ff_ffff {
        return None;
    }
    Some(Rgb(
        (v & 0xff) as u8,
        ((v >> 8) & 0xff) as u8,
        ((v >> 16) & 0xff) as u8,
    ))
}

/// The Delphi colour called `name` (case-insensitive, as Delphi is).
pub fn named_colour(name: &str) -> Option<Rgb> {
    crate::ir::colours::delphi()
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(name))
        .map(|(_, c)| *c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_colours_are_blue_green_red() {
        assert_eq!(hex_colour("$000000FF"), Some(Rgb(255, 0, 0)));
        assert_eq!(hex_colour("$00FF0000"), Some(Rgb(0, 0, 255)));
        assert_eq!(hex_colour("$00804020"), Some(Rgb(0x20, 0x40, 0x80)));
        assert_eq!(hex_colour("$01000000"), None);
        assert_eq!(hex_colour("$xyz"), None);
        assert_eq!(named_colour("clgreen"), Some(Rgb(0, 128, 0)));
    }
}
