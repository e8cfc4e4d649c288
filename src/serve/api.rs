//! The page's requests, answered with the library's calls: compile the
//! text (its diagnostics), the one call for a picture (linked SVG, its
//! growth's frames, PNG/SVG/OBJ to download), hover, translation. Each
//! answer is JSON; nothing here decides how a picture is made.

use super::json::{self, Positions};
use super::pages::{Kept, Turn};
use super::Served;
use crate::back;
use crate::driver::picture::{self, DrawError, Format, Quiet, Request, Target};
use crate::driver::{self, Compiled, RunOptions};
use crate::front::{self, Front};
use crate::mesh::MeshFormat;
use crate::render::View;
use crate::source::SourceFile;
use serde::Deserialize;
use serde_json::{json, Value};
use std::sync::Arc;

/// The most symbols a page's derivation makes: a model past it answers
/// with the limit's diagnostic in well under a second.
pub const PAGE_MAX_SYMBOLS: usize = 1_000_000;
/// The most turtle moves a page's picture draws: each is a part of the
/// SVG the browser keeps.
pub const PAGE_MAX_MOVES: usize = 100_000;
/// The most frames of growth a page is sent…
pub const MAX_FRAMES: u64 = 64;
/// …and the most bytes of SVG they add up to.
pub const MAX_FRAME_BYTES: usize = 24 << 20;
/// The sides a picture may ask for, in pixels.
const SIZES: std::ops::RangeInclusive<u32> = 64..=2048;

/// What a request says of the model and its picture; each request reads
/// the fields it needs.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
pub struct Model {
    pub text: String,
    pub notation: Option<String>,
    pub page: Option<String>,
    pub seq: u64,
    pub steps: Option<u64>,
    pub seed: u64,
    pub azimuth: Option<f64>,
    pub elevation: Option<f64>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    /// `hover`: where, in UTF-16 units.
    pub offset: Option<usize>,
    /// `translate`: the target notation.
    pub to: Option<String>,
    /// `std`: the entry.
    pub name: Option<String>,
    /// `export`: png, svg or obj.
    pub format: Option<String>,
}

/// An answer that is not JSON success: a status and a message.
#[derive(Debug)]
pub struct Refusal {
    pub status: u16,
    pub message: String,
}

impl Refusal {
    pub fn new(status: u16, message: impl Into<String>) -> Refusal {
        Refusal {
            status,
            message: message.into(),
        }
    }
}

/// A file to download: its bytes, media type and name.
pub struct Download {
    pub bytes: Vec<u8>,
    pub media_type: &'static str,
    pub name: String,
}

/// The page's first request: the served file's text and notation, the
/// notations, the stdlib's entries, whether the text can be saved.
pub fn start(s: &Served) -> Value {
    let notations: Vec<Value> = (front::FRONTS.iter())
        .map(|f| json!({ "id": f.name(), "name": f.title(), "extensions": f.extensions() }))
        .collect();
    let entries: Vec<String> = crate::stdlib::names().map(|n| format!("std:{n}")).collect();
    json!({
        "file": s.name,
        "text": s.text,
        "notation": s.notation.name(),
        "notations": notations,
        "entries": entries,
        "can_save": s.path.is_some(),
        "steps": Value::Null,
    })
}

/// A stdlib entry's text and notation.
pub fn std_entry(m: &Model) -> Result<Value, Refusal> {
    let name = m.name.as_deref().unwrap_or("");
    let spec = if name.starts_with("std:") {
        name.to_string()
    } else {
        format!("std:{name}")
    };
    let file = driver::load(&spec).map_err(|e| Refusal::new(404, e.to_string()))?;
    let notation = driver::compile(file.clone()).front.name();
    Ok(json!({ "text": file.text, "notation": notation }))
}

/// The notation a request names, else the served file's.
fn notation(s: &Served, m: &Model) -> Result<&'static dyn Front, Refusal> {
    match m.notation.as_deref() {
        None => Ok(s.notation),
        Some(name) => front::by_name(name)
            .ok_or_else(|| Refusal::new(400, format!("no notation named `{name}`"))),
    }
}

/// The request's text compiled in its notation, named as the served file
/// when the notation is the file's (so that what a file name decides,
/// such as a stdlib kolam drawn as splines, holds on the page too).
fn compile(s: &Served, m: &Model) -> Result<Compiled, Refusal> {
    let front = notation(s, m)?;
    let name = if std::ptr::addr_eq(front, s.notation) {
        s.name.clone().unwrap_or_else(|| "page".into())
    } else {
        format!("page.{}", front.extensions().first().unwrap_or(&"txt"))
    };
    let file = SourceFile::new(name, m.text.as_str());
    Ok(driver::compile_as(file, None, Some(front)))
}

/// The page's kept compile of `m`'s text, compiled anew when the text or
/// the notation changed.
fn compiled(s: &Served, m: &Model, kept: &mut Kept) -> Result<Arc<Compiled>, Refusal> {
    let front = notation(s, m)?.name();
    if let Some((text, n, c)) = &kept.compiled {
        if *text == m.text && *n == front {
            return Ok(c.clone());
        }
    }
    let c = Arc::new(compile(s, m)?);
    kept.compiled = Some((m.text.clone(), front, c.clone()));
    Ok(c)
}

/// The request for `m`'s picture as `target`, within the page's limits.
fn picture_request(m: &Model, target: Target, steps: Option<u64>) -> Request {
    let mut req = Request::new(target);
    req.run = RunOptions {
        steps,
        seed: m.seed,
        max_symbols: PAGE_MAX_SYMBOLS,
        max_moves: PAGE_MAX_MOVES,
        ..RunOptions::default()
    };
    req.width = m.width.unwrap_or(600).clamp(*SIZES.start(), *SIZES.end());
    req.height = m.height.unwrap_or(600).clamp(*SIZES.start(), *SIZES.end());
    req.view = match (m.azimuth, m.elevation) {
        (None, None) => None,
        (az, el) => Some(View::degrees(az.unwrap_or(0.0), el.unwrap_or(0.0))),
    };
    req.linked = true;
    req
}

/// A page's request, run in its turn: `work` with the page's kept state,
/// or `{"seq", "superseded": true}` when a newer request came first.
pub fn in_turn(
    s: &Served,
    m: &Model,
    work: impl FnOnce(&mut Kept) -> Result<Value, Refusal>,
) -> Result<Value, Refusal> {
    let page = s.pages.page(m.page.as_deref().unwrap_or(""));
    let mut kept = match page.turn(m.seq) {
        Turn::Superseded => return Ok(json!({ "seq": m.seq, "superseded": true })),
        Turn::Go(kept) => kept,
    };
    let mut answer = work(&mut kept)?;
    answer["seq"] = json!(m.seq);
    answer["superseded"] = json!(false);
    Ok(answer)
}

/// The text's diagnostics and its linked picture (`null` while it has
/// errors, or when a limit stopped it: the limit's diagnostic says so).
pub fn update(s: &Served, m: &Model, kept: &mut Kept) -> Result<Value, Refusal> {
    let c = compiled(s, m, kept)?;
    let at = Positions::of(&c.file.text);
    let mut diags: Vec<Value> = json::diagnostics(&c.diagnostics.0, &c.file, &at);
    let req = picture_request(m, Target::Still(Format::Svg), m.steps);
    let (svg, steps) = match picture::draw(&c, &req, &mut Quiet) {
        Ok(p) => {
            diags.extend(json::diagnostics(&p.warnings, &c.file, &at));
            let steps = c
                .system
                .as_ref()
                .map(|sys| req.run.derive_options(sys).steps);
            (String::from_utf8(p.bytes).ok(), steps)
        }
        Err(e) => {
            diags.extend(stopped(&e, &c.file, &at));
            (None, None)
        }
    };
    let sys = c.system_or_recovered();
    let axiom = (c.spans.axiom.first()).zip(c.spans.axiom.last());
    Ok(json!({
        "diagnostics": diags,
        "picture": svg,
        "steps": steps,
        "is3d": sys.is_some_and(driver::turns_in_space),
        "productions": c.spans.productions.iter().map(|p| at.range(p)).collect::<Vec<_>>(),
        "axiom": axiom.map(|(a, b)| at.range(&(a.start..b.end))),
    }))
}

/// Why a picture was not made, as the page lists it: the limit's or the
/// program's diagnostic; a problem of the picture itself (its size) said
/// without a code; `None` when the text's own diagnostics say why.
fn stopped(e: &DrawError, file: &SourceFile, at: &Positions) -> Option<Value> {
    match e {
        DrawError::Stopped(d) => Some(json::diagnostic(d, file, at)),
        DrawError::NotCompiled | DrawError::NotRead(_) => None,
        other => Some(json!({
            "code": null, "severity": "error", "message": other.to_string(),
            "from": 0, "to": 0, "line": null, "help": [], "notes": [], "fixes": [],
        })),
    }
}

/// The linked SVG of every step from 0 to the picture's, from the page's
/// kept compile: at most [`MAX_FRAMES`] frames and [`MAX_FRAME_BYTES`]
/// bytes, `stopped` saying why when fewer were drawn.
pub fn frames(s: &Served, m: &Model, kept: &mut Kept) -> Result<Value, Refusal> {
    let c = compiled(s, m, kept)?;
    let Some(sys) = &c.system else {
        return Ok(json!({ "frames": [], "stopped": "the text has errors" }));
    };
    let last = picture_request(m, Target::Still(Format::Svg), m.steps)
        .run
        .derive_options(sys)
        .steps;
    let mut frames = Vec::new();
    let mut bytes = 0;
    let mut stop = None;
    for step in 0..=last.min(MAX_FRAMES - 1) {
        let req = picture_request(m, Target::Still(Format::Svg), Some(step));
        match picture::draw(&c, &req, &mut Quiet) {
            Ok(p) if bytes + p.bytes.len() <= MAX_FRAME_BYTES => {
                bytes += p.bytes.len();
                frames.push(String::from_utf8_lossy(&p.bytes).into_owned());
            }
            Ok(_) => {
                stop = Some(format!(
                    "step {step} and on are not shown: the frames would pass {} MB",
                    MAX_FRAME_BYTES >> 20
                ));
                break;
            }
            Err(e) => {
                stop = Some(format!("step {step}: {e}"));
                break;
            }
        }
    }
    if stop.is_none() && last >= MAX_FRAMES {
        stop = Some(format!("the first {MAX_FRAMES} steps are shown"));
    }
    Ok(json!({ "frames": frames, "stopped": stop }))
}

/// What hovering at a place says, as the language server says it.
pub fn hover(s: &Served, m: &Model) -> Result<Value, Refusal> {
    let c = compile(s, m)?;
    let at = Positions::of(&c.file.text);
    let offset = at.byte(m.offset.unwrap_or(0));
    Ok(match driver::hover(&c, offset) {
        None => Value::Null,
        Some(h) => {
            let span = h.span.unwrap_or(offset..offset);
            json!({
                "markdown": h.markdown,
                "from": at.utf16(span.start),
                "to": at.utf16(span.end),
            })
        }
    })
}

/// The text translated to another notation, or the target's errors.
pub fn translate(s: &Served, m: &Model) -> Result<Value, Refusal> {
    let to = m.to.as_deref().unwrap_or("");
    let target =
        back::by_name(to).ok_or_else(|| Refusal::new(400, format!("no emitter named `{to}`")))?;
    let c = compile(s, m)?;
    let at = Positions::of(&c.file.text);
    let Some(sys) = &c.system else {
        let diags = json::diagnostics(&c.diagnostics.0, &c.file, &at);
        return Ok(json!({ "text": null, "diagnostics": diags }));
    };
    let req = back::Request {
        target,
        lossy: false,
        steps: None,
    };
    let t = driver::translate(&c, sys, &req);
    let diags = json::diagnostics(&t.diagnostics.0, &c.file, &at);
    Ok(json!({ "text": t.text, "diagnostics": diags }))
}

/// Writes the text to the served file (and nowhere else).
pub fn save(s: &Served, m: &Model) -> Result<Value, Refusal> {
    let Some(path) = &s.path else {
        return Err(Refusal::new(
            403,
            "this page serves no file to save to: start `graftal serve FILE`",
        ));
    };
    std::fs::write(path, &m.text)
        .map_err(|e| Refusal::new(500, format!("cannot write {}: {e}", path.display())))?;
    Ok(json!({ "saved": path.display().to_string() }))
}

/// The picture as a file to download: PNG, SVG or OBJ.
pub fn export(s: &Served, m: &Model) -> Result<Download, Refusal> {
    let format = m.format.as_deref().unwrap_or("png");
    let (target, media_type) = match format {
        "png" => (Target::Still(Format::Png), "image/png"),
        "svg" => (Target::Still(Format::Svg), "image/svg+xml"),
        "obj" => (Target::Mesh(MeshFormat::Obj), "model/obj"),
        other => return Err(Refusal::new(400, format!("no download as `{other}`"))),
    };
    let c = compile(s, m)?;
    let mut req = picture_request(m, target, m.steps);
    req.linked = false;
    let p = picture::draw(&c, &req, &mut Quiet).map_err(|e| Refusal::new(422, e.to_string()))?;
    let stem = (s.name.as_deref())
        .and_then(|n| std::path::Path::new(n).file_stem()?.to_str())
        .unwrap_or("graftal")
        .trim_start_matches("std:");
    Ok(Download {
        bytes: p.bytes,
        media_type,
        name: format!("{stem}.{format}"),
    })
}
