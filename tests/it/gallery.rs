//! `docs/gallery/` is `graftal gallery`'s output and stays true: every
//! standard-library entry is in its index, every file the index names is
//! there, and a few entries drawn anew are byte for byte the committed
//! pictures (the output is deterministic).

use graftal::gallery;
use graftal::stdlib;
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/gallery")
}

/// The file names an index links to: `](NAME)` in Markdown, `src="NAME"`
/// and `href="NAME"` in HTML.
fn linked(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for open in ["](", "src=\"", "href=\""] {
        for part in text.split(open).skip(1) {
            let end = part.find([')', '"']).unwrap_or(part.len());
            out.push(part[..end].to_string());
        }
    }
    out
}

#[test]
fn every_entry_is_in_the_gallery_and_every_linked_file_exists() {
    let redo = "run `graftal gallery docs/gallery`";
    for index in ["README.md", "index.html"] {
        let text = std::fs::read_to_string(dir().join(index))
            .unwrap_or_else(|e| panic!("docs/gallery/{index}: {e}; {redo}"));
        for e in stdlib::ENTRIES {
            let name = format!("std:{}", e.name);
            assert!(
                text.contains(&format!("<code>{name}</code>"))
                    || text.contains(&format!("`{name}`")),
                "{name} is missing from docs/gallery/{index}; {redo}"
            );
        }
        let links = linked(&text);
        assert!(links.len() >= stdlib::ENTRIES.len(), "{index}: {links:?}");
        for f in links {
            assert!(
                dir().join(&f).is_file(),
                "{index} links `{f}`, which is not there; {redo}"
            );
        }
    }
    // Every entry that draws has its PNG.
    for e in stdlib::ENTRIES
        .iter()
        .filter(|e| e.kind() != stdlib::Kind::Schema)
    {
        let png = gallery::file_name(e, "png");
        assert!(
            dir().join(&png).is_file(),
            "docs/gallery/{png} is missing; {redo}"
        );
    }
}

#[test]
fn entries_drawn_anew_are_the_committed_pictures() {
    for name in ["koch-island", "smith/senstree", "stl/fig04-plant"] {
        let e = stdlib::get(name).unwrap();
        let p = gallery::pictures(e);
        let committed = |ext| std::fs::read(dir().join(gallery::file_name(e, ext))).ok();
        assert!(p.png.is_some(), "{name} draws");
        assert!(
            p.png == committed("png"),
            "docs/gallery's {name} PNG is out of date"
        );
        assert!(
            p.svg == committed("svg"),
            "docs/gallery's {name} SVG is out of date"
        );
    }
}
