//! `graftal gallery OUT_DIR`: every standard-library entry drawn at a
//! modest size, as PNG and SVG, with an index (`index.html`, and
//! `README.md` for a repository's file view) giving each entry's name, the
//! figure it reproduces and its pictures. `docs/gallery/` is its output;
//! the output is deterministic, so a test can redraw a few entries and
//! compare bytes to show the committed gallery is current.

use crate::diagnostics::codes;
use crate::driver::picture::{self, Format};
use crate::stdlib::{self, Entry};
use std::fmt::Write as _;
use std::path::Path;

/// The pictures' side in pixels: enough to see a plant, small enough that
/// the repository's copy stays a few megabytes.
pub const SIZE: u32 = 384;

/// The largest SVG the gallery keeps: a bigger one (a dense plant, a
/// segment per element) is left out, and the index links its PNG only.
pub const MAX_SVG: usize = 400_000;

/// What the gallery shows of one entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Item {
    /// `std:NAME`.
    pub name: String,
    pub figure: String,
    /// The pictures' file names, without folder; `None` when not drawn.
    pub png: Option<String>,
    pub svg: Option<String>,
    /// Why a picture is missing, when one is.
    pub note: Option<String>,
}

/// An entry's pictures: PNG and SVG bytes (each `None` when not drawn),
/// and why one is missing.
pub struct Pictures {
    pub png: Option<Vec<u8>>,
    pub svg: Option<Vec<u8>>,
    pub note: Option<String>,
}

/// The file name an entry's pictures take, `ext` their extension: its
/// name with folders joined by `-` (`smith/senstree` → `smith-senstree`).
pub fn file_name(entry: &Entry, ext: &str) -> String {
    format!("{}.{ext}", entry.name.replace('/', "-"))
}

/// Draws `entry` at its defaults in `format`, by the one call
/// `graftal render` draws through ([`picture::make`]); `Ok(None)` when it
/// draws nothing.
fn draw(entry: &Entry, format: Format, threads: usize) -> Result<Option<Vec<u8>>, String> {
    let source = picture::Source::Spec(format!("std:{}", entry.name));
    let mut req = picture::Request {
        width: SIZE,
        height: SIZE,
        ..picture::Request::new(picture::Target::Still(format))
    };
    req.tracing.threads = threads;
    let made = picture::make(&source, None, None, &req, &mut picture::Quiet);
    let p = match made.picture {
        Ok(p) => p,
        Err(picture::DrawError::NotCompiled) => return Err("the entry does not compile".into()),
        Err(e) => return Err(e.to_string()),
    };
    let empty = p.warnings.iter().any(|d| d.code == codes::NOTHING_DRAWN);
    Ok((!empty).then_some(p.bytes))
}

/// The pictures of `entry` ([`SIZE`], an SVG only up to [`MAX_SVG`]).
pub fn pictures(entry: &Entry) -> Pictures {
    pictures_on(entry, 0)
}

/// [`pictures`], each drawn on `threads` threads (0: every core).
fn pictures_on(entry: &Entry, threads: usize) -> Pictures {
    let png = match draw(entry, Format::Png, threads) {
        Ok(Some(png)) => png,
        Ok(None) => {
            let why = match entry.schema_reason() {
                Some(r) => format!("a schema ({r}): `graftal derive std:{}`", entry.name),
                None => "draws nothing at its defaults".to_string(),
            };
            return Pictures {
                png: None,
                svg: None,
                note: Some(why),
            };
        }
        Err(e) => {
            return Pictures {
                png: None,
                svg: None,
                note: Some(format!("not drawn: {e}")),
            }
        }
    };
    let (svg, note) = match draw(entry, Format::Svg, threads) {
        Ok(Some(svg)) if svg.len() <= MAX_SVG => (Some(svg), None),
        Ok(Some(svg)) => (
            None,
            Some(format!(
                "its SVG ({} kB) is left out: PNG only",
                svg.len() / 1000
            )),
        ),
        Ok(None) | Err(_) => (None, Some("no SVG: PNG only".to_string())),
    };
    Pictures {
        png: Some(png),
        svg,
        note,
    }
}

/// Writes every entry's pictures and the index into `dir`, drawing on
/// `threads` threads (0: every core; the same files for every count) and
/// calling `progress(done, total)` as each entry is drawn; the items
/// listed.
pub fn write(
    dir: &Path,
    threads: usize,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<Item>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create `{}`: {e}", dir.display()))?;
    let put = |name: &str, bytes: &[u8]| {
        std::fs::write(dir.join(name), bytes).map_err(|e| format!("cannot write `{name}`: {e}"))
    };
    let entries = stdlib::ENTRIES;
    let total = entries.len() as u64;
    let drawn = crate::parallel::map_in_order(
        entries.len(),
        threads,
        // Each picture may share its own work among the threads too (a
        // ray-traced entry takes longest).
        |k| pictures_on(&entries[k], threads),
        |done| progress(done as u64, total),
    );
    let mut items = Vec::new();
    for (entry, p) in entries.iter().zip(drawn) {
        let mut item = Item {
            name: format!("std:{}", entry.name),
            figure: entry.figure(),
            png: None,
            svg: None,
            note: p.note,
        };
        if let Some(png) = p.png {
            let f = file_name(entry, "png");
            put(&f, &png)?;
            item.png = Some(f);
        }
        if let Some(svg) = p.svg {
            let f = file_name(entry, "svg");
            put(&f, &svg)?;
            item.svg = Some(f);
        }
        items.push(item);
    }
    put("README.md", readme(&items).as_bytes())?;
    put("index.html", html(&items).as_bytes())?;
    Ok(items)
}

const INTRO: &str = "Every entry of graftal's standard library (`std:NAME`), drawn at its \
defaults by `graftal gallery docs/gallery`";

/// The index as Markdown: a table of name, figure and pictures.
pub fn readme(items: &[Item]) -> String {
    let mut s = format!(
        "# graftal gallery\n\n{INTRO} ({SIZE}x{SIZE} pixels). Regenerate it after changing \
         the library or the renderer; `tests/it/gallery.rs` fails when it is out of date.\n\n\
         | entry | figure | picture | files |\n|---|---|---|---|\n"
    );
    for it in items {
        let picture = it.png.as_ref().map_or(String::new(), |p| {
            format!("<img src=\"{p}\" width=\"160\" alt=\"{}\">", it.name)
        });
        let mut files: Vec<String> = [&it.png, &it.svg]
            .into_iter()
            .flatten()
            .map(|f| format!("[{}]({f})", f.rsplit('.').next().unwrap_or(f)))
            .collect();
        files.extend(it.note.clone());
        let _ = writeln!(
            s,
            "| `{}` | {} | {picture} | {} |",
            it.name,
            cell(&it.figure),
            cell(&files.join(" · "))
        );
    }
    s
}

/// `text` safe in a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// `text` safe in HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The index as a web page: a card per entry.
pub fn html(items: &[Item]) -> String {
    let mut s = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>graftal gallery</title>\n<style>\nbody {{ font-family: sans-serif; margin: 2em; }}\n\
         .grid {{ display: flex; flex-wrap: wrap; gap: 1em; }}\n\
         figure {{ width: 240px; margin: 0; }}\nimg {{ width: 240px; height: 240px; border: 1px solid #ddd; }}\n\
         figcaption {{ font-size: 0.85em; }}\n</style>\n</head>\n<body>\n<h1>graftal gallery</h1>\n\
         <p>{} ({SIZE}&times;{SIZE} pixels).</p>\n<div class=\"grid\">\n",
        escape(INTRO)
    );
    for it in items {
        let name = escape(&it.name);
        let _ = writeln!(s, "<figure>");
        if let Some(p) = &it.png {
            let _ = writeln!(s, "<a href=\"{p}\"><img src=\"{p}\" alt=\"{name}\"></a>");
        }
        let mut links: Vec<String> = [&it.png, &it.svg]
            .into_iter()
            .flatten()
            .map(|f| format!("<a href=\"{f}\">{}</a>", f.rsplit('.').next().unwrap_or(f)))
            .collect();
        links.extend(it.note.as_deref().map(escape));
        let _ = writeln!(
            s,
            "<figcaption><code>{name}</code><br>{}<br>{}</figcaption>\n</figure>",
            escape(&it.figure),
            links.join(" · ")
        );
    }
    s.push_str("</div>\n</body>\n</html>\n");
    s
}
