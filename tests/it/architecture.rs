//! The house rules, read from the source: which module may import which.
//!
//! Every `.rs` file under `src/` is read as text; the crate paths it names
//! outside its test module (`crate::x::y`, `use crate::{x, y::z}`, `super::`
//! paths) and the external crates it names (`clap::`, `ariadne::`, …) are
//! its imports. The rules (README, "How graftal is built"):
//!
//! * a front end (`src/front/<notation>/`, its rooms such as
//!   `stl/lower/` included) imports no other front end, no emitter, no
//!   turtle, render, eval, driver or cli; the rooms the front ends share
//!   (`src/front/*.rs`: comments, parse, depth, …) import no front end;
//! * an emitter (`src/back/`) imports no front end and no turtle (the
//!   default palette is the IR's);
//! * `ir` imports nothing above it (only `ir` itself and `number`, a leaf
//!   that imports nothing of the crate);
//! * `common` (what several front ends and emitters share about
//!   notations) imports only `ir` and `number`;
//! * `layout` (layout shapes and outline growth, computations over the
//!   IR) imports only `ir` and `number`;
//! * `decode` (image files into the IR's texture images) imports only
//!   `ir` and `number`;
//! * `enviro` (the environment programs of open L-systems: queries in,
//!   answers out) imports only `ir` and `number`;
//! * the turtle imports neither render nor eval (nor anything above them);
//! * the outputs of the turtle's geometry, render (pictures, animations),
//!   mesh (OBJ, PLY, glTF) and raytrace (ray-traced pictures of instancing
//!   graphs and of geometry), stand on `ir` and the turtle: they import
//!   no front end, emitter, eval, driver, cli, language server or gallery;
//! * the gallery draws through the driver, as a command would: it imports
//!   no front end, emitter, cli or language server, and only cli calls it;
//! * the language server is a face that only cli starts: nothing else
//!   imports it (what its hover and definitions say is the library's,
//!   `driver::explain`, which every face asks), and only it speaks the
//!   protocol (`lsp_types`, `lsp_server`);
//! * the live page's server (`serve`) is a face like the others, and the
//!   only module that speaks HTTP (`tiny_http`); it names no notation;
//! * the faces (cli, the language server, the gallery, the page's server) reach the layers
//!   under the library's calls only for plain data of a request (a view, a
//!   style, a mesh or animation format): never a way of drawing (the
//!   raster, the streamed painter, shared subtrees, encoders, mesh
//!   writers, the ray tracer), the turtle or eval, which `driver::picture` chooses between;
//! * `clap` only in `cli`, `ariadne` only in the diagnostics renderer,
//!   `chumsky` and `logos` only in front ends;
//! * a front end walks no turtle of its own;
//! * the language server names no notation (no `"pfg"`, no
//!   `front::cpfg::…`): what it needs of one, each front end answers
//!   through `Front`;
//! * the top-level modules form no import cycle;
//! * the Python module (`python/src/`, a crate of its own over this one) is
//!   a face like the others: it reaches the library as they do (no way of
//!   drawing, no turtle or eval, no other face), names no notation, and is
//!   the only code that speaks to Python (`pyo3`, `numpy`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A source file: its path under `src/` and its code without comments,
/// string literals and test module.
struct Source {
    path: String,
    code: String,
}

fn sources() -> Vec<Source> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    collect(&root, &mut files);
    files.sort();
    files
        .into_iter()
        .map(|p| Source {
            path: p
                .strip_prefix(&root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/"),
            code: without_tests(&strip(&std::fs::read_to_string(&p).unwrap())),
        })
        .collect()
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code with comments and the contents of string and char literals
/// removed (so a path in a doc comment or a message is not an import).
fn strip(src: &str) -> String {
    let b = src.as_bytes();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let mut depth = 0;
            while i < b.len() {
                if b[i..].starts_with(b"/*") {
                    depth += 1;
                    i += 2;
                } else if b[i..].starts_with(b"*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if let Some(end) = raw_string_end(b, i) {
            out.push_str("\"\"");
            i = end;
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if b[i] == b'\'' && char_literal_len(&b[i..]).is_some() {
            i += char_literal_len(&b[i..]).unwrap();
            out.push_str("' '");
        } else {
            let c = src[i..].chars().next().unwrap();
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// Where a raw string literal (`r"…"`, `r#"…"#`) starting at `i` ends.
fn raw_string_end(b: &[u8], i: usize) -> Option<usize> {
    if b[i] != b'r' || (i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) {
        return None;
    }
    let mut j = i + 1;
    while j < b.len() && b[j] == b'#' {
        j += 1;
    }
    if j >= b.len() || b[j] != b'"' {
        return None;
    }
    let hashes = j - i - 1;
    let mut close = vec![b'"'];
    close.extend(std::iter::repeat_n(b'#', hashes));
    let body = j + 1;
    (body..b.len())
        .find(|&k| b[k..].starts_with(&close))
        .map(|k| k + close.len())
}

/// The length of a char literal at the start of `b` (`'a'`, `'\n'`,
/// `'\u{..}'`), or `None` for a lifetime.
fn char_literal_len(b: &[u8]) -> Option<usize> {
    if b.len() >= 4 && b[1] == b'\\' {
        let end = b[2..].iter().position(|&c| c == b'\'')?;
        return Some(end + 3);
    }
    let s = std::str::from_utf8(&b[1..b.len().min(6)])
        .ok()
        .or_else(|| {
            // A multi-byte char cut short: take what decodes.
            (2..b.len().min(6))
                .rev()
                .find_map(|k| std::str::from_utf8(&b[1..k]).ok())
        })?;
    let c = s.chars().next()?;
    let n = c.len_utf8();
    (b.get(1 + n) == Some(&b'\'')).then_some(n + 2)
}

/// The code before the file's `#[cfg(test)]` module (by the house
/// convention the test module is the last item of a file).
fn without_tests(code: &str) -> String {
    match code.find("#[cfg(test)]") {
        Some(k) => code[..k].to_string(),
        None => code.to_string(),
    }
}

/// The module path of a file: `front/pfg/lower.rs` -> `["front", "pfg",
/// "lower"]`, `front/mod.rs` -> `["front"]`.
fn module_of(path: &str) -> Vec<String> {
    let mut parts: Vec<String> = path
        .trim_end_matches(".rs")
        .split('/')
        .map(String::from)
        .collect();
    if parts
        .last()
        .is_some_and(|p| p == "mod" || p == "lib" || p == "main")
    {
        parts.pop();
    }
    parts
}

/// The crate paths `code` names, as module paths (up to three segments).
fn crate_paths(module: &[String], code: &str) -> BTreeSet<Vec<String>> {
    let mut out = BTreeSet::new();
    let words: Vec<(usize, &str)> = tokens(code);
    for (k, &(_, w)) in words.iter().enumerate() {
        let base: Vec<String> = match w {
            "crate" => Vec::new(),
            "super" => {
                // `super` is the parent of this file's module.
                let mut m = module.to_vec();
                let mut j = k;
                m.pop();
                while words.get(j + 2).is_some_and(|t| t.1 == "super")
                    && words.get(j + 1).is_some_and(|t| t.1 == "::")
                {
                    m.pop();
                    j += 2;
                }
                if j != k {
                    continue;
                }
                m
            }
            _ => continue,
        };
        if k > 0 && words[k - 1].1 == "::" {
            continue;
        }
        follow(&words, k + 1, base, &mut out);
    }
    out
}

/// Follows `::a::b` or `::{a::b, c}` from token `k`, adding each path.
fn follow(words: &[(usize, &str)], k: usize, base: Vec<String>, out: &mut BTreeSet<Vec<String>>) {
    if words.get(k).map(|t| t.1) != Some("::") {
        if !base.is_empty() {
            out.insert(base);
        }
        return;
    }
    match words.get(k + 1).map(|t| t.1) {
        Some("{") => {
            // A group: each comma-separated path inside, to the matching `}`.
            let mut depth = 0;
            let mut j = k + 1;
            let mut start = true;
            while j < words.len() {
                match words[j].1 {
                    "{" => {
                        depth += 1;
                        start = true;
                    }
                    "}" => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    "," => start = true,
                    w if start && depth == 1 && is_ident(w) => {
                        let mut p = base.clone();
                        if w != "self" {
                            p.push(w.to_string());
                        }
                        follow(words, j + 1, p, out);
                        start = false;
                    }
                    _ => {}
                }
                j += 1;
            }
        }
        Some(w) if is_ident(w) => {
            let mut p = base;
            p.push(w.to_string());
            if p.len() >= 3 {
                out.insert(p);
            } else {
                follow(words, k + 2, p, out);
            }
        }
        _ => {
            if !base.is_empty() {
                out.insert(base);
            }
        }
    }
}

fn is_ident(w: &str) -> bool {
    w.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// Identifiers, `::` and the punctuation `{`, `}`, `,` of `code`.
fn tokens(code: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let b = code.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_alphabetic() || c == b'_' {
            let s = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            out.push((s, &code[s..i]));
        } else if b[i..].starts_with(b"::") {
            out.push((i, "::"));
            i += 2;
        } else {
            if matches!(c, b'{' | b'}' | b',') {
                out.push((i, &code[i..i + 1]));
            }
            i += 1;
        }
    }
    out
}

/// The external crates among `names` that `code` uses (`name::` or `use
/// name`).
fn external<'a>(code: &str, names: &[&'a str]) -> Vec<&'a str> {
    let words = tokens(code);
    names
        .iter()
        .copied()
        .filter(|&n| {
            words.iter().enumerate().any(|(k, t)| {
                t.1 == n
                    && (k == 0 || words[k - 1].1 != "::")
                    && (words.get(k + 1).is_some_and(|t| t.1 == "::")
                        || (k > 0 && words[k - 1].1 == "use"))
            })
        })
        .collect()
}

const FRONT_ENDS_ARE: &str = "front";
const NOT_FOR_FRONT_ENDS: &[&str] = &[
    "back", "turtle", "render", "raytrace", "eval", "driver", "cli",
];
const ABOVE_THE_TURTLE: &[&str] = &[
    "render", "raytrace", "eval", "front", "back", "driver", "cli",
];
const NOT_FOR_OUTPUTS: &[&str] = &[
    "front", "back", "eval", "driver", "cli", "lsp", "gallery", "serve",
];
const NOT_FOR_THE_GALLERY: &[&str] = &["front", "back", "cli", "lsp", "serve"];
const THE_FACES: &[&str] = &["cli", "lsp", "gallery", "serve"];
/// The layers under the library's calls, which a face reaches only for
/// [`A_FACE_MAY_NAME`].
const BENEATH_THE_FACES: &[&str] = &["render", "mesh", "raytrace", "turtle", "eval"];
/// Plain data a face puts in a request: a view, a style, a format.
const A_FACE_MAY_NAME: &[&[&str]] = &[
    &["render", "View"],
    &["render", "Style"],
    &["render", "Palette"],
    &["render", "Detail"],
    &["render", "Margin"],
    &["render", "animate", "Container"],
    &["mesh", "MeshFormat"],
    &["mesh", "MeshStats"],
];

/// Whether a face names `path`, a part of a layer under the library's
/// calls that is not plain data: a way of drawing, the turtle, eval.
fn a_face_reaches_past_the_library(path: &[String]) -> bool {
    BENEATH_THE_FACES.contains(&path[0].as_str())
        && !A_FACE_MAY_NAME
            .iter()
            .any(|a| path.len() >= a.len() && a.iter().zip(path).all(|(x, y)| x == y))
}

/// The front ends: the folders under `src/front/`.
fn notations() -> BTreeSet<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src")
        .join(FRONT_ENDS_ARE);
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect()
}

/// Every rule broken, as "file: what it imports".
fn violations(files: &[Source]) -> Vec<String> {
    let notations = notations();
    assert!(notations.len() >= 5, "{notations:?}");
    let mut out = Vec::new();
    for f in files {
        let module = module_of(&f.path);
        let top = module.first().cloned().unwrap_or_default();
        for path in crate_paths(&module, &f.code) {
            let target = path[0].as_str();
            let broken = match top.as_str() {
                "front" if module.len() >= 2 => {
                    NOT_FOR_FRONT_ENDS.contains(&target)
                        || (target == "front"
                            && path
                                .get(1)
                                .is_some_and(|n| notations.contains(n) && *n != module[1]))
                }
                "back" => matches!(target, "front" | "turtle"),
                "ir" => !matches!(target, "ir" | "number"),
                "number" => target != "number",
                "parallel" => target != "parallel",
                "common" | "layout" | "scene" | "decode" | "enviro" => {
                    target != top && !matches!(target, "ir" | "number")
                }
                "turtle" => ABOVE_THE_TURTLE.contains(&target),
                "render" | "mesh" | "raytrace" => NOT_FOR_OUTPUTS.contains(&target),
                "gallery" => NOT_FOR_THE_GALLERY.contains(&target),
                _ => false,
            } || (target == "gallery" && !matches!(top.as_str(), "gallery" | "cli"))
                || (target == "lsp" && !matches!(top.as_str(), "lsp" | "cli"))
                || (THE_FACES.contains(&top.as_str()) && a_face_reaches_past_the_library(&path));
            if broken {
                out.push(format!("{}: imports crate::{}", f.path, path.join("::")));
            }
        }
        let allowed: &[(&str, bool)] = &[
            ("clap", top == "cli"),
            ("ariadne", f.path == "diagnostics/render.rs"),
            ("chumsky", top == "front"),
            ("logos", top == "front"),
            ("tiny_http", top == "serve"),
            ("lsp_types", top == "lsp"),
            ("lsp_server", top == "lsp"),
            // Python is the Python face's alone (`python/src/`).
            ("pyo3", false),
            ("numpy", false),
        ];
        let names: Vec<&str> = allowed.iter().map(|a| a.0).collect();
        for used in external(&f.code, &names) {
            if !allowed.iter().any(|a| a.0 == used && a.1) {
                out.push(format!("{}: uses the crate {used}", f.path));
            }
        }
    }
    out
}

/// The imports between top-level modules (self-imports left out).
fn module_graph(files: &[Source]) -> BTreeMap<String, BTreeSet<String>> {
    let tops: BTreeSet<String> = files
        .iter()
        .filter_map(|f| module_of(&f.path).first().cloned())
        .collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files {
        let module = module_of(&f.path);
        let Some(top) = module.first() else { continue };
        for path in crate_paths(&module, &f.code) {
            if path[0] != *top && tops.contains(&path[0]) {
                graph
                    .entry(top.clone())
                    .or_default()
                    .insert(path[0].clone());
            }
        }
    }
    graph
}

/// A cycle in `graph`, if there is one.
fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(k) = stack.iter().position(|s| s == n) {
            let mut c = stack[k..].to_vec();
            c.push(n.to_string());
            return Some(c);
        }
        if done.contains(n) {
            return None;
        }
        stack.push(n.to_string());
        for m in graph.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, graph, stack, done) {
                return Some(c);
            }
        }
        stack.pop();
        done.insert(n.to_string());
        None
    }
    let mut done = BTreeSet::new();
    for n in graph.keys() {
        if let Some(c) = visit(n, graph, &mut Vec::new(), &mut done) {
            return Some(c);
        }
    }
    None
}

#[test]
fn no_module_imports_what_the_house_rules_forbid() {
    let files = sources();
    assert!(files.len() > 40, "read {} files", files.len());
    let broken = violations(&files);
    assert!(
        broken.is_empty(),
        "forbidden imports:\n{}",
        broken.join("\n")
    );
}

/// A front end never draws: it walks no turtle of its own (no sines and
/// cosines of headings); the geometry of layouts and outline growth is the
/// layout module's (`layout::shapes`, `layout::growth`), drawing the
/// turtle's.
#[test]
fn no_front_end_walks_a_turtle_of_its_own() {
    let files = sources();
    let drawing: Vec<&str> = files
        .iter()
        .filter(|f| f.path.starts_with("front/"))
        .filter(|f| {
            [".sin()", ".cos()", ".sin_cos()"]
                .iter()
                .any(|t| f.code.contains(t))
        })
        .map(|f| f.path.as_str())
        .collect();
    assert!(
        drawing.is_empty(),
        "front ends computing headings: {drawing:?}"
    );
    // The check sees what it looks for: the growth walk does turn headings.
    assert!(files
        .iter()
        .any(|f| f.path == "layout/growth.rs" && f.code.contains(".sin()")));
}

/// Where a face names a notation: each `"NAME"` string and each
/// `front::NAME` path in `raw` (a file's text with its comments and test
/// module, but not its strings, left out), for each notation in
/// `notations`.
fn notations_named(raw: &str, notations: &BTreeSet<String>) -> Vec<String> {
    let code = without_tests(&strip_comments(raw));
    let words = tokens(&code);
    let mut out = Vec::new();
    for n in notations {
        if code.contains(&format!("\"{n}\"")) {
            out.push(format!("\"{n}\""));
        }
        let path = words
            .windows(3)
            .any(|w| w[0].1 == FRONT_ENDS_ARE && w[1].1 == "::" && w[2].1 == n.as_str());
        if path {
            out.push(format!("front::{n}"));
        }
    }
    out
}

/// `src` without its comments (strings kept), for [`notations_named`].
fn strip_comments(src: &str) -> String {
    let mut out = String::with_capacity(src.len());
    let mut rest = src;
    while let Some(k) = rest.find("//") {
        // A `//` inside a string on this line is not a comment.
        let line_start = rest[..k].rfind('\n').map_or(0, |i| i + 1);
        if rest[line_start..k].matches('"').count() % 2 == 1 {
            out.push_str(&rest[..k + 2]);
            rest = &rest[k + 2..];
            continue;
        }
        out.push_str(&rest[..k]);
        rest = &rest[k..];
        rest = &rest[rest.find('\n').unwrap_or(rest.len())..];
    }
    out.push_str(rest);
    out
}

/// The language server matches on no notation's name: what it needs of a
/// notation (keywords, comments, declarations, user functions), the front
/// end answers through `Front`.
#[test]
fn the_language_server_and_the_page_name_no_notation() {
    let notations = notations();
    for face in ["lsp", "serve"] {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(face);
        let mut files = Vec::new();
        collect(&root, &mut files);
        assert!(files.len() >= 5, "{files:?}");
        let named: Vec<String> = files
            .iter()
            .flat_map(|p| {
                let raw = std::fs::read_to_string(p).unwrap();
                let shown = p.strip_prefix(&root).unwrap().display().to_string();
                (notations_named(&raw, &notations).into_iter())
                    .map(move |n| format!("{face}/{shown}: {n}"))
            })
            .collect();
        assert!(
            named.is_empty(),
            "{face} names notations:\n{}",
            named.join("\n")
        );
    }
    // The check sees what it looks for.
    let seen = |code: &str| !notations_named(code, &notations).is_empty();
    assert!(seen("match n { \"stl\" => rules(t), _ => vec![] }"));
    assert!(seen("use crate::front::cpfg::FunctionSite;"));
    assert!(seen("let f = front::fractint::lexer::comment_spans(t);"));
    assert!(!seen("// as \"cpfg\" does\nlet k = c.front.keywords();"));
    assert!(!seen(
        "let k = f.keywords();\n#[cfg(test)]\nmod tests { fn t() { find(\"cpfg\") } }"
    ));
    assert!(!seen("let u = \"http://x\"; let s = \"pfgs\";"));
}

/// What a hover says (what a symbol does to the turtle, which productions
/// rewrite it, a user function's points, a code's explanation) is worded
/// once, in `driver/explain/`: no face words it again, so that the
/// language server and the page of `graftal serve` say the same.
#[test]
fn what_a_hover_says_is_worded_in_the_library_alone() {
    let wording = [
        "fn what_it_does",
        "fn symbol_text",
        "fn angle_text",
        "fn function_text",
        "fn explanation",
    ];
    let files = sources();
    let worded: Vec<(&str, &str)> = (files.iter())
        .flat_map(|f| {
            let found = wording.iter().filter(|w| f.code.contains(*w));
            found.map(|w| (f.path.as_str(), *w))
        })
        .collect();
    let elsewhere: Vec<_> = (worded.iter())
        .filter(|(path, _)| !path.starts_with("driver/explain/"))
        .collect();
    assert!(
        elsewhere.is_empty(),
        "worded outside the library: {elsewhere:?}"
    );
    // The check sees what it looks for: each is worded there, once.
    assert_eq!(worded.len(), wording.len(), "{worded:?}");
}

/// The most lines a source file holds before its test module: a file
/// longer than this mixes responsibilities, and is split into rooms.
const MOST_LINES_BEFORE_TESTS: usize = 1200;

/// The one file allowed to be longer: the IR's specification, whose
/// length is its documentation (each notation's lowering a doctest).
const THE_SPECIFICATION: &str = "ir/mod.rs";

/// The lines of a file before its `#[cfg(test)]` module (all of it when it
/// has none), comments and blank lines included.
fn lines_before_tests(text: &str) -> usize {
    text.lines()
        .take_while(|l| !l.starts_with("#[cfg(test)]"))
        .count()
}

#[test]
fn no_file_but_the_specification_is_over_1200_lines_before_its_tests() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    collect(&root, &mut files);
    let mut long = Vec::new();
    for p in files {
        let path = p
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let n = lines_before_tests(&std::fs::read_to_string(&p).unwrap());
        if n > MOST_LINES_BEFORE_TESTS && path != THE_SPECIFICATION {
            long.push(format!("{path}: {n} lines"));
        }
    }
    assert!(long.is_empty(), "split by responsibility: {long:?}");
    // The count sees what it counts.
    assert_eq!(lines_before_tests("a\nb\n#[cfg(test)]\nmod tests {}\n"), 2);
    assert_eq!(lines_before_tests("a\n\n// c\n"), 3);
}

#[test]
fn the_top_level_modules_form_no_cycle() {
    let graph = module_graph(&sources());
    // The graph is read: the CLI does reach the driver.
    assert!(graph["cli"].contains("driver"), "{graph:?}");
    assert_eq!(cycle(&graph), None, "{graph:?}");
}

/// The checker itself: each rule catches what it is meant to.
#[test]
fn the_checker_sees_each_kind_of_forbidden_import() {
    let file = |path: &str, code: &str| Source {
        path: path.to_string(),
        code: without_tests(&strip(code)),
    };
    let cases = [
        (
            "front/pfg/lower.rs",
            "use crate::front::linf::display;",
            true,
        ),
        (
            "front/pfg/lower.rs",
            "use crate::front::{Front, Read};",
            false,
        ),
        (
            "front/pfg/lower.rs",
            "use crate::{ir::System, eval::Rng};",
            true,
        ),
        ("front/pfg/mod.rs", "fn f() { super::linf::read(x) }", true),
        (
            "front/stl/lower/names.rs",
            "use crate::front::stl::ast::File;",
            false,
        ),
        (
            "front/stl/lower/names.rs",
            "use crate::front::gft::ast::File;",
            true,
        ),
        (
            "front/cpfg/preprocess/macros.rs",
            "use crate::render::Picture;",
            true,
        ),
        (
            "front/comments.rs",
            "use crate::front::pfg::lexer::Token;",
            true,
        ),
        (
            "front/parse.rs",
            "use crate::front::repeats::push_lazily;",
            false,
        ),
        ("front/pfg/lower.rs", "use super::ast::File;", false),
        (
            "front/stl/lower.rs",
            "let x = crate::turtle::interpret(a);",
            true,
        ),
        (
            "back/stl/mod.rs",
            "use crate::front::stl::parser::RESERVED;",
            true,
        ),
        ("back/mod.rs", "use crate::ir::System;", false),
        (
            "back/linf/mod.rs",
            "let p = crate::turtle::DEFAULT_PALETTE;",
            true,
        ),
        (
            "back/linf/mod.rs",
            "let p = crate::ir::colours::DEFAULT_PALETTE;",
            false,
        ),
        ("ir/mod.rs", "use crate::diagnostics::Diagnostic;", true),
        ("ir/d0l.rs", "use super::{SymbolId, System};", false),
        ("ir/mod.rs", "let s = crate::number::readable(x);", false),
        ("ir/mod.rs", "use crate::common::vocabulary;", true),
        ("number.rs", "use crate::ir::Rgb;", true),
        ("common/vocabulary.rs", "use crate::ir::TurtleOp;", false),
        (
            "common/gft_words.rs",
            "use crate::front::gft::parser;",
            true,
        ),
        ("common/vocabulary.rs", "use crate::turtle::Turtle;", true),
        ("common/vocabulary.rs", "use crate::layout::growth;", true),
        (
            "layout/seed.rs",
            "use crate::ir::{Structure, System};",
            false,
        ),
        ("layout/seed.rs", "use super::growth::{self, Comp};", false),
        ("layout/growth.rs", "use crate::turtle::Turtle;", true),
        ("layout/shapes.rs", "use crate::front::stl::ast;", true),
        ("layout/growth.rs", "use crate::common::vocabulary;", true),
        ("ir/mod.rs", "use crate::layout::growth;", true),
        ("front/stl/lower.rs", "use crate::layout::growth;", false),
        ("turtle/instanced.rs", "use crate::render::Picture;", true),
        ("turtle/mod.rs", "use crate::random::Rng;", false),
        ("turtle/run.rs", "use crate::eval::Deriver;", true),
        ("turtle/interpret.rs", "use crate::render::Picture;", true),
        ("turtle/interpret.rs", "use crate::random::Rng;", false),
        ("turtle/state.rs", "use crate::ir::Axis;", false),
        ("turtle/geometry.rs", "use crate::driver::RunOptions;", true),
        ("eval/mod.rs", "use clap::Parser;", true),
        ("cli/mod.rs", "use clap::Parser;", false),
        (
            "diagnostics/mod.rs",
            "fn f(e: &chumsky::error::Rich<'_, T>) {}",
            true,
        ),
        ("diagnostics/render.rs", "use ariadne::Report;", false),
        ("render/mod.rs", "use logos::Logos;", true),
        ("mesh/obj.rs", "use crate::eval::derive;", true),
        (
            "mesh/mod.rs",
            "let s = crate::front::pfg::read_ok(t);",
            true,
        ),
        ("mesh/gltf.rs", "use crate::back::gft::emit;", true),
        ("mesh/mod.rs", "use crate::cli::main;", true),
        ("mesh/mod.rs", "use crate::driver::RunOptions;", true),
        (
            "mesh/instanced.rs",
            "use crate::turtle::{instanced, Segment};",
            false,
        ),
        ("mesh/tube.rs", "use crate::ir::Rgb;", false),
        ("render/animate.rs", "use crate::driver::derive;", true),
        ("render/animate.rs", "use crate::mesh::Scene;", false),
        ("render/animate.rs", "use crate::turtle::Geometry;", false),
        (
            "render/raster/bands.rs",
            "use crate::driver::RunOptions;",
            true,
        ),
        ("render/raster/survey.rs", "use crate::turtle::Sink;", false),
        (
            "render/raster/target.rs",
            "use super::super::shade::Colour;",
            false,
        ),
        ("gallery.rs", "use crate::cli::main;", true),
        ("gallery.rs", "use crate::front::pfg;", true),
        ("gallery.rs", "use crate::lsp::serve;", true),
        (
            "gallery.rs",
            "use crate::driver::picture::{self, Format};",
            false,
        ),
        ("gallery.rs", "use crate::render::View;", false),
        ("driver/mod.rs", "use crate::gallery::write;", true),
        // The hover is the library's: no layer but cli reaches the server.
        (
            "driver/explain/mod.rs",
            "use crate::lsp::features::hover;",
            true,
        ),
        ("driver/explain/prose.rs", "use lsp_types::Hover;", true),
        ("serve/api.rs", "let h = crate::lsp::hover(d, o);", true),
        ("serve/api.rs", "let h = crate::driver::hover(c, o);", false),
        ("cli/mod.rs", "let r = crate::lsp::run_stdio(o);", false),
        ("cli/mod.rs", "use lsp_server::Message;", true),
        (
            "lsp/features.rs",
            "use crate::driver::explain::{DeclarationKind, FunctionSite};",
            false,
        ),
        ("lsp/features.rs", "use lsp_types::Hover;", false),
        ("cli/mod.rs", "use crate::gallery::write;", false),
        // A face draws through `driver::picture`, never by a way of its own.
        ("cli/mod.rs", "let b = crate::render::raster::png(g);", true),
        ("cli/mod.rs", "use crate::render::{coverage, View};", true),
        ("gallery.rs", "use crate::turtle::interpret;", true),
        ("lsp/mod.rs", "use crate::mesh::obj;", true),
        ("cli/mod.rs", "use crate::eval::Deriver;", true),
        ("cli/mod.rs", "use crate::render::{Style, View};", false),
        (
            "cli/mod.rs",
            "let c = crate::render::animate::Container::Gif;",
            false,
        ),
        (
            "cli/mod.rs",
            "let m = crate::mesh::MeshFormat::from_path(p);",
            false,
        ),
        (
            "cli/mod.rs",
            "use crate::driver::picture::{draw, Request};",
            false,
        ),
        // The IFS front end, the library rooms the library notations share,
        // and the attractor drawer.
        (
            "front/ifs/lower.rs",
            "use crate::render::attractor::pixels;",
            true,
        ),
        (
            "front/ifs/parser.rs",
            "use crate::front::fractint::parse;",
            true,
        ),
        (
            "front/ifs/parser.rs",
            "use crate::front::library::{self, Tok};",
            false,
        ),
        (
            "front/library.rs",
            "use crate::front::fractint::ast::Entry;",
            true,
        ),
        (
            "front/fractint/mod.rs",
            "use crate::front::ifs::is_3d;",
            true,
        ),
        (
            "render/attractor.rs",
            "use crate::front::ifs::lower_entry;",
            true,
        ),
        (
            "render/attractor.rs",
            "use crate::driver::picture::Request;",
            true,
        ),
        (
            "render/attractor.rs",
            "use crate::ir::graph::{stretch_2d, Affine};",
            false,
        ),
        (
            "driver/picture/attractor.rs",
            "use crate::render::{self, attractor};",
            false,
        ),
        (
            "cli/mod.rs",
            "let p = crate::render::attractor::pixels(m, o);",
            true,
        ),
        ("serve/api.rs", "use crate::render::raster::png;", true),
        (
            "serve/api.rs",
            "use crate::driver::picture::{self, Request};",
            false,
        ),
        ("eval/mod.rs", "fn f() { tiny_http::Server::http(a) }", true),
        // Comments, strings and the test module are not imports.
        (
            "ir/mod.rs",
            "// see crate::eval::derive\nlet s = \"crate::eval\";",
            false,
        ),
        (
            "turtle/mod.rs",
            "fn f() {}\n#[cfg(test)]\nmod tests { use crate::eval::derive; }",
            false,
        ),
    ];
    for (path, code, forbidden) in cases {
        let found = violations(&[file(path, code)]);
        assert_eq!(!found.is_empty(), forbidden, "{path}: {code}: {found:?}");
    }
    let graph = module_graph(&[
        file("eval/mod.rs", "use crate::turtle::Sink;"),
        file("turtle/mod.rs", "use crate::eval::Rng;"),
    ]);
    assert!(cycle(&graph).is_some());
}

/// The checks of an object-instancing graph are worded in one room that
/// every front end reading a graph shares (`front/graph.rs`: it imports
/// nothing but the IR, the diagnostics and `number`), so that `.gft` and
/// any other notation report them alike; no other module words them.
#[test]
fn the_graph_checks_are_worded_in_one_shared_room() {
    let files = sources();
    let room = files
        .iter()
        .find(|f| f.path == "front/graph.rs")
        .expect("front/graph.rs");
    let module = module_of(&room.path);
    for path in crate_paths(&module, &room.code) {
        let allowed = matches!(path[0].as_str(), "ir" | "diagnostics" | "number")
            || path.get(1).is_some_and(|m| m == "graph");
        assert!(allowed, "front/graph.rs imports crate::{}", path.join("::"));
    }
    let checks = [
        "GRAPH_DIVERGENT",
        "GRAPH_BARE_TERMINAL",
        "GRAPH_SINGULAR",
        "GRAPH_UNREACHABLE",
    ];
    for f in &files {
        if f.path == "front/graph.rs" || f.path.starts_with("diagnostics/") {
            continue;
        }
        for code in checks {
            assert!(!f.code.contains(code), "{} words {code} itself", f.path);
        }
    }
    assert!(checks.iter().all(|c| room.code.contains(c)));
}

/// What the IFS work added stands where the house rules put it: the
/// attractor drawer on the IR and render alone, the library rooms on the
/// diagnostics, the IR and the front ends' shared rooms, the IFS front end
/// on no other notation, and only `driver::picture` choosing the
/// attractor as a way of drawing.
#[test]
fn the_ifs_front_end_the_library_rooms_and_the_attractor_stand_in_their_layers() {
    let files = sources();
    let notations = notations();
    assert!(notations.contains("ifs"), "{notations:?}");
    let imports = |path: &str| {
        let f = files
            .iter()
            .find(|f| f.path == path)
            .unwrap_or_else(|| panic!("no file {path}"));
        crate_paths(&module_of(path), &f.code)
    };
    for path in imports("render/attractor.rs") {
        assert!(
            matches!(path[0].as_str(), "ir" | "render"),
            "render/attractor.rs imports crate::{}",
            path.join("::")
        );
    }
    for path in imports("front/library.rs") {
        let ok = match path[0].as_str() {
            "diagnostics" | "ir" => true,
            "front" => path.get(1).is_none_or(|n| !notations.contains(n)),
            _ => false,
        };
        assert!(ok, "front/library.rs imports crate::{}", path.join("::"));
    }
    for f in files.iter().filter(|f| f.path.starts_with("front/ifs/")) {
        for path in crate_paths(&module_of(&f.path), &f.code) {
            let other_notation = path[0] == "front"
                && path
                    .get(1)
                    .is_some_and(|n| notations.contains(n) && n != "ifs");
            assert!(
                !other_notation && !NOT_FOR_FRONT_ENDS.contains(&path[0].as_str()),
                "{} imports crate::{}",
                f.path,
                path.join("::")
            );
        }
    }
    let drawers: Vec<&str> = files
        .iter()
        .filter(|f| {
            crate_paths(&module_of(&f.path), &f.code)
                .iter()
                .any(|p| p.len() >= 2 && p[0] == "render" && p[1] == "attractor")
        })
        .map(|f| f.path.as_str())
        .collect();
    assert_eq!(drawers, ["driver/picture/attractor.rs"]);
}

/// The Python face's sources (`python/src/`), read as [`sources`] reads
/// the library's.
fn python_sources() -> Vec<Source> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("python")
        .join("src");
    let mut files = Vec::new();
    collect(&root, &mut files);
    files.sort();
    (files.into_iter())
        .map(|p| Source {
            path: format!("python/src/{}", p.strip_prefix(&root).unwrap().display()),
            code: without_tests(&strip(&std::fs::read_to_string(&p).unwrap())),
        })
        .collect()
}

/// The library's paths `code` names (`graftal::driver::…`, `use
/// graftal::{…}`), as module paths of the library (up to three segments).
fn library_paths(code: &str) -> BTreeSet<Vec<String>> {
    let words = tokens(code);
    let mut out = BTreeSet::new();
    for (k, w) in words.iter().enumerate() {
        let at_root = k == 0 || words[k - 1].1 != "::";
        if w.1 == "graftal" && at_root && words.get(k + 1).is_some_and(|t| t.1 == "::") {
            follow(&words, k + 1, Vec::new(), &mut out);
        }
    }
    out
}

/// Every rule of the faces the Python face breaks, as "file: what".
fn python_violations(files: &[(Source, String)]) -> Vec<String> {
    let notations = notations();
    let mut out = Vec::new();
    for (f, raw) in files {
        for path in library_paths(&f.code) {
            let other_face = THE_FACES.contains(&path[0].as_str());
            if other_face || a_face_reaches_past_the_library(&path) {
                out.push(format!("{}: uses graftal::{}", f.path, path.join("::")));
            }
        }
        for named in notations_named(raw, &notations) {
            out.push(format!("{}: names the notation {named}", f.path));
        }
        let speaks: Vec<&str> = ["clap", "ariadne", "tiny_http", "lsp_types", "lsp_server"].into();
        for used in external(&f.code, &speaks) {
            out.push(format!("{}: uses the crate {used}", f.path));
        }
    }
    out
}

#[test]
fn the_python_face_reaches_the_library_as_the_other_faces_do() {
    let files = python_sources();
    assert!(files.len() >= 5, "read {} files of python/src", files.len());
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let with_raw: Vec<(Source, String)> = (files.into_iter())
        .map(|f| {
            let raw = std::fs::read_to_string(root.join(&f.path)).unwrap();
            (f, raw)
        })
        .collect();
    let broken = python_violations(&with_raw);
    assert!(broken.is_empty(), "the Python face:\n{}", broken.join("\n"));
    // The paths are read: it does call the driver, and speaks Python.
    let named: BTreeSet<String> = (with_raw.iter())
        .flat_map(|(f, _)| library_paths(&f.code))
        .map(|p| p[0].clone())
        .collect();
    assert!(named.contains("driver"), "{named:?}");
    assert!(with_raw
        .iter()
        .any(|(f, _)| !external(&f.code, &["pyo3"]).is_empty()));
}

/// The Python face's checker catches what it is meant to.
#[test]
fn the_checker_sees_what_the_python_face_may_not_do() {
    let case = |code: &str| {
        let f = Source {
            path: "python/src/x.rs".into(),
            code: without_tests(&strip(code)),
        };
        !python_violations(&[(f, code.to_string())]).is_empty()
    };
    assert!(case("use graftal::render::raster::png;"));
    assert!(case("let w = graftal::eval::Deriver::new(s);"));
    assert!(case("use graftal::{driver, turtle::Geometry};"));
    assert!(case("use graftal::cli::main;"));
    assert!(case("let f = graftal::front::by_name(\"pfg\");"));
    assert!(case("use graftal::front::stl::ast;"));
    assert!(case("fn f() { tiny_http::Server::http(a) }"));
    assert!(!case("use graftal::driver::{self, Compiled, RunOptions};"));
    assert!(!case(
        "use graftal::driver::picture::{self, Request, Target};"
    ));
    assert!(!case("use graftal::render::{Detail, Margin, View};"));
    assert!(!case("let m = graftal::mesh::MeshFormat::ALL;"));
    assert!(!case("use pyo3::prelude::*;\nuse numpy::PyArray1;"));
    assert!(!case(
        "// graftal::turtle::Geometry, in a comment\nlet x = 1;"
    ));
    // The library itself speaks no Python.
    let lib = Source {
        path: "driver/mod.rs".into(),
        code: "use pyo3::prelude::*;".into(),
    };
    assert!(!violations(&[lib]).is_empty());
}
