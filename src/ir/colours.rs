//! Named colours: the Delphi colour names STL layouts use (`clGreen`, …),
//! from `stdlib/stl/delphi-colours.txt`. Any front end may read them and
//! any emitter write them.

use super::Rgb;

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

#[cfg(test)]
mod tests {
    use super::*;

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
