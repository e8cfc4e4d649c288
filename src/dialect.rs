//! Which notation a file is in: by extension for `.linf` and `.stl`, by
//! content for `.l` (and anything else), since pfg (1988), cpfg and
//! Fractint all use `.l`. The one place that decides; [`crate::driver`]
//! dispatches on it.
//!
//! The content rule (from the survey of the three dialects' corpora):
//! with `;` comments removed, a line `Name {` (a name, optionally text,
//! then `{`) and no `-->` anywhere is Fractint — pfg and cpfg productions
//! always have `-->`, and Fractint never does. Otherwise a line starting
//! with `lsystem:`, `endlsystem` or a `#define`/`#include`/`#if` directive
//! is cpfg. Everything else is pfg, graftal's oldest front end.

/// The notations and `.l` dialects graftal tells apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    Pfg,
    Cpfg,
    Fractint,
    Linf,
    Stl,
}

impl Dialect {
    /// The name shown to people.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Pfg => "pfg",
            Dialect::Cpfg => "cpfg",
            Dialect::Fractint => "Fractint",
            Dialect::Linf => "LinF",
            Dialect::Stl => "STL",
        }
    }
}

/// The dialect of a file with extension `ext` (lowercase, without the dot)
/// and content `text`.
pub fn detect(ext: &str, text: &str) -> Dialect {
    match ext {
        "linf" => return Dialect::Linf,
        "stl" => return Dialect::Stl,
        _ => {}
    }
    if looks_fractint(text) {
        return Dialect::Fractint;
    }
    let text = strip_block_comments(text);
    let cpfg = text.lines().any(|l| {
        let l = l.trim_start().to_ascii_lowercase();
        let word = |w: &str| {
            l.strip_prefix(w)
                .is_some_and(|r| r.trim_start().starts_with(':'))
        };
        word("lsystem")
            || l.starts_with("endlsystem")
            || ["define", "include", "if"].iter().any(|d| {
                l.strip_prefix('#')
                    .is_some_and(|r| r.trim_start().starts_with(d))
            })
    });
    if cpfg {
        Dialect::Cpfg
    } else {
        Dialect::Pfg
    }
}

/// A `Name {` line, no `-->` and no pfg header (`axiom:`, …), `;`
/// comments left out.
fn looks_fractint(text: &str) -> bool {
    let mut header = false;
    for line in text.lines() {
        let line = line.split(';').next().unwrap_or("");
        if line.contains("-->") || pfg_header(line) {
            return false;
        }
        if !header {
            let t = line.trim_start();
            let name_end = t
                .find(|c: char| c.is_whitespace() || c == '(' || c == '{')
                .unwrap_or(t.len());
            let (name, rest) = t.split_at(name_end);
            header = !name.is_empty() && !name.contains(':') && rest.contains('{');
        }
    }
    header
}

/// A pfg header line: one of the Appendix A keywords and a colon. A
/// Fractint reader would reject `axiom:` as an unknown keyword.
fn pfg_header(line: &str) -> bool {
    let l = line.trim_start().to_ascii_lowercase();
    crate::front::pfg::parser::HEADERS.iter().any(|h| {
        l.strip_prefix(h)
            .is_some_and(|r| r.trim_start().starts_with(':'))
    })
}

fn strip_block_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(k) = rest.find("/*") {
        out.push_str(&rest[..k]);
        match rest[k + 2..].find("*/") {
            Some(e) => rest = &rest[k + 2 + e + 2..],
            None => rest = "",
        }
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tells_the_l_dialects_apart_by_content() {
        let fr = "; comment\nKoch1 { ; by X\n  Angle 6\n  Axiom F--F--F\n  F=F+F--F+F\n}\n";
        assert_eq!(detect("l", fr), Dialect::Fractint);
        assert_eq!(
            detect("l", "Lars1{\nangle 4\naxiom f\n}"),
            Dialect::Fractint
        );
        let pfg = "derivation length: 2\naxiom: {f+f}F\nF --> F+F\n";
        assert_eq!(detect("l", pfg), Dialect::Pfg);
        // A pfg header with a brace in its value is not an entry.
        assert_eq!(detect("l", "axiom: {F}\n"), Dialect::Pfg);
        // Nor a brace in a pfg comment, in a file without productions.
        assert_eq!(detect("l", "/* lines {\n */\naxiom: A\n"), Dialect::Pfg);
        let cpfg = "#define N 3\nlsystem: 1\naxiom: A\nA --> B\nendlsystem\n";
        assert_eq!(detect("l", cpfg), Dialect::Cpfg);
        assert_eq!(detect("l", "/* x */\nLsystem : 1\nA-->B\n"), Dialect::Cpfg);
        // cpfg blocks `{ … }` come with productions.
        assert_eq!(
            detect("l", "lsystem: 1\nA --> B\nS {\n}\nendlsystem\n"),
            Dialect::Cpfg
        );
        assert_eq!(detect("linf", fr), Dialect::Linf);
        assert_eq!(detect("stl", fr), Dialect::Stl);
        assert_eq!(detect("l", ""), Dialect::Pfg);
    }
}
