//! The JSON of the large results (every place a symbol is written, the
//! outline of a file of ten thousand productions), written by hand: serde's
//! serializer, instantiated in this crate, runs unoptimized in the debug
//! build and took a quarter of a second for 40,000 locations.

use lsp_types::{Position, Range, SymbolKind, Uri};
use std::fmt::Write;

/// `text` as a JSON string.
fn string(out: &mut String, text: &str) {
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn position(out: &mut String, p: Position) {
    let _ = write!(out, r#"{{"line":{},"character":{}}}"#, p.line, p.character);
}

fn range(out: &mut String, r: Range) {
    out.push_str(r#"{"start":"#);
    position(out, r.start);
    out.push_str(r#","end":"#);
    position(out, r.end);
    out.push('}');
}

/// `Location[]`: each of `ranges` in the document at `uri`.
pub fn locations(uri: &Uri, ranges: impl Iterator<Item = Range>) -> String {
    let mut uri_json = String::new();
    string(&mut uri_json, uri.as_str());
    let mut out = String::from("[");
    for (i, r) in ranges.enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(out, r#"{{"uri":{uri_json},"range":"#);
        range(&mut out, r);
        out.push('}');
    }
    out.push(']');
    out
}

/// `DocumentSymbol[]` without children: a name, a kind and a range (also
/// the selection range) each.
pub fn outline(symbols: impl Iterator<Item = (String, SymbolKind, Range)>) -> String {
    let mut out = String::from("[");
    for (i, (name, kind, r)) in symbols.enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(r#"{"name":"#);
        string(&mut out, &name);
        let kind = serde_json::to_string(&kind).unwrap_or_else(|_| "null".into());
        let _ = write!(out, r#","kind":{kind},"range":"#);
        range(&mut out, r);
        out.push_str(r#","selectionRange":"#);
        range(&mut out, r);
        out.push('}');
    }
    out.push(']');
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use lsp_types::{DocumentSymbol, Location};

    fn r(a: u32, b: u32, c: u32, d: u32) -> Range {
        Range::new(Position::new(a, b), Position::new(c, d))
    }

    #[test]
    fn locations_are_what_serde_writes() {
        let uri: Uri = "file:///tmp/a%20b.l".parse().unwrap();
        let ranges = [r(0, 1, 0, 2), r(3, 4, 5, 6)];
        let by_serde: Vec<_> = (ranges.iter())
            .map(|&x| Location::new(uri.clone(), x))
            .collect();
        let mine: serde_json::Value =
            serde_json::from_str(&locations(&uri, ranges.into_iter())).unwrap();
        assert_eq!(mine, serde_json::to_value(by_serde).unwrap());
    }

    #[test]
    #[allow(deprecated)] // `DocumentSymbol::deprecated` must still be given.
    fn the_outline_is_what_serde_writes() {
        let name = "F \"q\" \\ é\u{1}".to_string();
        let by_serde = vec![DocumentSymbol {
            name: name.clone(),
            detail: None,
            kind: SymbolKind::FUNCTION,
            tags: None,
            deprecated: None,
            range: r(1, 2, 3, 4),
            selection_range: r(1, 2, 3, 4),
            children: None,
        }];
        let symbols = [(name, SymbolKind::FUNCTION, r(1, 2, 3, 4))];
        let mine: serde_json::Value = serde_json::from_str(&outline(symbols.into_iter())).unwrap();
        assert_eq!(mine, serde_json::to_value(by_serde).unwrap());
    }
}
