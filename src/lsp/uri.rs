//! `file:` URIs and the paths graftal reads: a document's path is the name
//! its diagnostics show, and what cpfg's side files are found beside.

use lsp_types::Uri;
use std::str::FromStr;

/// The path a `file:` URI names (percent-decoded); any other URI is kept
/// as it is, a name without a directory to read beside.
pub fn to_path(uri: &Uri) -> String {
    let s = uri.as_str();
    let Some(rest) = s.strip_prefix("file://") else {
        return s.to_string();
    };
    // `file://host/path`: only the local host (empty) is a path here.
    let path = rest.strip_prefix("localhost").unwrap_or(rest);
    decode(path)
}

/// The `file:` URI of absolute path `path`; `None` for a relative one.
pub fn from_path(path: &str) -> Option<Uri> {
    if !path.starts_with('/') {
        return None;
    }
    let mut s = String::from("file://");
    for b in path.bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    Uri::from_str(&s).ok()
}

fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = (b[i] == b'%')
            .then(|| s.get(i + 1..i + 3))
            .flatten()
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match hex {
            Some(v) => {
                out.push(v);
                i += 3;
            }
            None => {
                out.push(b[i]);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_and_uris_round_trip_with_escapes() {
        let uri = from_path("/tmp/a b/é.l").unwrap();
        assert_eq!(uri.as_str(), "file:///tmp/a%20b/%C3%A9.l");
        assert_eq!(to_path(&uri), "/tmp/a b/é.l");
        assert!(from_path("relative.l").is_none());
        let other = Uri::from_str("untitled:Untitled-1").unwrap();
        assert_eq!(to_path(&other), "untitled:Untitled-1");
    }
}
