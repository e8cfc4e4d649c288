//! Named colours: the Delphi colour names STL layouts use (`clGreen`, …),
//! from `stdlib/stl/delphi-colours.txt`, and the colour arguments of the
//! command line ([`parse`]). Any front end may read them and any emitter
//! write them. And the colour table a system without colours is drawn
//! with ([`DEFAULT_PALETTE`]): the IR's, beside its colours, so that the
//! turtle, the renderers and the emitters read one table.

use super::Rgb;

/// The colour table `'` steps through when a system gives none (it wraps
/// around): black for index 0, as the listing draws, then leaf green and
/// flower colours, so that the book's plants (Fig. 3.4: leaves one step up
/// the table, flowers two) come out as plants.
pub const DEFAULT_PALETTE: [Rgb; 8] = [
    Rgb(0, 0, 0),
    Rgb(34, 139, 34),
    Rgb(218, 165, 32),
    Rgb(199, 21, 133),
    Rgb(85, 107, 47),
    Rgb(139, 69, 19),
    Rgb(154, 205, 50),
    Rgb(106, 90, 205),
];

/// Each Delphi colour name with its RGB value, in the file's order.
pub fn delphi() -> &'static [(&'static str, Rgb)] {
    static TABLE: std::sync::OnceLock<Vec<(&'static str, Rgb)>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        include_str!("../../stdlib/stl/delphi-colours.txt")
            .lines()
            .filter(|l| !l.trim_start().starts_with('#'))
            .filter_map(|l| {
                let mut it = l.split_whitespace();
                let name = it.next()?;
                let mut c = it.map(|v| v.parse::<u8>().ok());
                Some((name, Rgb(c.next()??, c.next()??, c.next()??)))
            })
            .collect()
    })
}

/// A colour with an opacity: 0 is transparent, 255 opaque.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgba {
    pub rgb: Rgb,
    pub alpha: u8,
}

/// The colour names [`parse`] knows besides the Delphi ones: the sixteen
/// of HTML 4 and a few that plants need.
const NAMES: [(&str, Rgb); 22] = [
    ("black", Rgb(0, 0, 0)),
    ("silver", Rgb(192, 192, 192)),
    ("gray", Rgb(128, 128, 128)),
    ("grey", Rgb(128, 128, 128)),
    ("white", Rgb(255, 255, 255)),
    ("maroon", Rgb(128, 0, 0)),
    ("red", Rgb(255, 0, 0)),
    ("purple", Rgb(128, 0, 128)),
    ("fuchsia", Rgb(255, 0, 255)),
    ("green", Rgb(0, 128, 0)),
    ("lime", Rgb(0, 255, 0)),
    ("olive", Rgb(128, 128, 0)),
    ("yellow", Rgb(255, 255, 0)),
    ("navy", Rgb(0, 0, 128)),
    ("blue", Rgb(0, 0, 255)),
    ("teal", Rgb(0, 128, 128)),
    ("aqua", Rgb(0, 255, 255)),
    ("orange", Rgb(255, 165, 0)),
    ("brown", Rgb(139, 69, 19)),
    ("forestgreen", Rgb(34, 139, 34)),
    ("skyblue", Rgb(135, 206, 235)),
    ("ivory", Rgb(255, 255, 240)),
];

/// A colour argument: a name (`white`, `forestgreen`, a Delphi name like
/// `clMoneyGreen`; any case), `#rrggbb`, `#rrggbbaa`, or `none` /
/// `transparent` (alpha 0). The one parser of every colour option.
pub fn parse(s: &str) -> Result<Rgba, String> {
    let t = s.trim();
    let opaque = |rgb| Rgba { rgb, alpha: 255 };
    if t.eq_ignore_ascii_case("none") || t.eq_ignore_ascii_case("transparent") {
        return Ok(Rgba {
            rgb: Rgb(255, 255, 255),
            alpha: 0,
        });
    }
    if let Some(hex) = t.strip_prefix('#') {
        let byte = |i: usize| {
            hex.get(i..i + 2)
                .and_then(|h| u8::from_str_radix(h, 16).ok())
        };
        let bad = || format!("`{s}` is not #rrggbb or #rrggbbaa");
        if !hex.is_ascii() || (hex.len() != 6 && hex.len() != 8) {
            return Err(bad());
        }
        let rgb = Rgb(
            byte(0).ok_or_else(bad)?,
            byte(2).ok_or_else(bad)?,
            byte(4).ok_or_else(bad)?,
        );
        let alpha = if hex.len() == 8 {
            byte(6).ok_or_else(bad)?
        } else {
            255
        };
        return Ok(Rgba { rgb, alpha });
    }
    NAMES
        .iter()
        .copied()
        .chain(delphi().iter().copied())
        .find(|(name, _)| name.eq_ignore_ascii_case(t))
        .map(|(_, rgb)| opaque(rgb))
        .ok_or_else(|| {
            format!("unknown colour `{s}`: use a name like `white`, #rrggbb, #rrggbbaa or `none`")
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_arguments_parse() {
        let c = |r, g, b, alpha| {
            Ok(Rgba {
                rgb: Rgb(r, g, b),
                alpha,
            })
        };
        assert_eq!(parse("White"), c(255, 255, 255, 255));
        assert_eq!(parse("#1a2B3c"), c(0x1a, 0x2b, 0x3c, 255));
        assert_eq!(parse("#1a2b3c80"), c(0x1a, 0x2b, 0x3c, 0x80));
        assert_eq!(parse("clMoneyGreen"), c(192, 220, 192, 255));
        assert_eq!(parse("none").map(|c| c.alpha), Ok(0));
        assert_eq!(parse("transparent").map(|c| c.alpha), Ok(0));
        for bad in ["#12345", "#1234567", "#gg0000", "#ééé", "mauve", ""] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_delphi_colour_table_is_complete() {
        let t = delphi();
        assert_eq!(t.len(), 22);
        let get = |n: &str| t.iter().find(|(k, _)| *k == n).map(|(_, c)| *c);
        assert_eq!(get("clMaroon"), Some(Rgb(128, 0, 0)));
        assert_eq!(get("clMoneyGreen"), Some(Rgb(192, 220, 192)));
        assert_eq!(get("clSkyBlue"), Some(Rgb(166, 202, 240)));
    }
}
