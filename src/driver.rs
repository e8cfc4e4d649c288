//! The pipeline as library calls: load a file (a path or `std:NAME`),
//! compile it to the IR with its diagnostics, derive, interpret, render,
//! measure. The CLI is a thin layer over these; tests call them directly.

use crate::back;
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
pub use crate::eval::parametric::Globals;
use crate::eval::tree::{Tree, MAX_TREE_DEPTH};
use crate::eval::{self, DeriveOptions, Deriver, DEFAULT_MAX_SYMBOLS};
use crate::front::{self, Front, Library};
use crate::ir::{SpanTable, System, TurtleOp, Word};
use crate::render::{self, RenderOptions, View};
use crate::source::{NotText, SourceFile};
use crate::stdlib;
use crate::turtle::instanced::Instanced;
use crate::turtle::{self, Geometry};
use serde::Serialize;
use std::io::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

pub use crate::source::MAX_SOURCE_BYTES;

/// Why a file could not be read (a usage or I/O problem: exit status 2).
#[derive(Debug)]
pub struct LoadError(pub String);

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// Reads `spec`: a path, or `std:NAME` for a stdlib entry.
pub fn load(spec: &str) -> Result<SourceFile, LoadError> {
    if let Some(name) = spec.strip_prefix("std:") {
        return match stdlib::get(name) {
            Some(e) => Ok(SourceFile::new(e.file, e.text)),
            None => Err(LoadError(stdlib::unknown(name))),
        };
    }
    SourceFile::read(Path::new(spec)).map_err(|e| LoadError(format!("cannot read `{spec}`: {e}")))
}

/// A file compiled to the IR. `system` is `None` when the file has errors,
/// or when it is a library of several entries and none was chosen
/// (`library.needs_entry`).
pub struct Compiled {
    pub file: SourceFile,
    pub system: Option<System>,
    pub spans: SpanTable,
    pub diagnostics: Diagnostics,
    /// The notation the file was read as.
    pub front: &'static dyn Front,
    /// A library's entries, and which was read.
    pub library: Option<Library>,
}

impl Compiled {
    /// Several entries and none chosen: `system` is `None` without errors.
    pub fn needs_entry(&self) -> bool {
        self.library.as_ref().is_some_and(|l| l.needs_entry)
    }

    /// The derived word as text in the notation the file was read in.
    pub fn word_text(&self, sys: &System, word: &Word) -> String {
        self.front.word_text(sys, word)
    }
}

/// Splits `FILE:NAME` (a library entry) when `FILE` exists and the whole
/// does not; anything else is a path as it is.
pub fn split_entry(spec: &str) -> (String, Option<String>) {
    if !spec.starts_with("std:") && !Path::new(spec).exists() {
        if let Some((path, name)) = spec.rsplit_once(':') {
            if !name.is_empty() && !name.contains(['/', '\\']) && Path::new(path).is_file() {
                return (path.to_string(), Some(name.to_string()));
            }
        }
    }
    (spec.to_string(), None)
}

/// The error for a library whose entry was not chosen (see
/// [`Compiled::needs_entry`]), listing the entries.
pub fn choose_entry(c: &Compiled) -> Diagnostic {
    let empty = Library::default();
    let lib = c.library.as_ref().unwrap_or(&empty);
    front::choose_entry(&c.file.name, c.front.title(), lib)
}

/// Translates the system `sys` of `c` as `req` asks: the emitter learns
/// from the source's front end what it knows of the source (comments, the
/// angle increment it states).
pub fn translate(c: &Compiled, sys: &System, req: &back::Request) -> back::Translation {
    let origin = back::Origin {
        title: c.front.title(),
        comments: c.front.comments(&c.file.text),
        angle_divisions: c.front.angle_divisions(sys),
    };
    let mut t = back::translate(sys, &c.spans, &c.file.text, &origin, req);
    if req.lossy && !t.diagnostics.is_empty() {
        compare_pictures(sys, req, &mut t);
    }
    t
}

/// The most symbols [`compare_pictures`] derives for either picture: a
/// fraction of a second, so that `--lossy` stays quick.
pub const COMPARE_MAX_SYMBOLS: usize = 500_000;

/// What [`compare_pictures`] measures of a picture.
struct Drawn {
    steps: u64,
    segments: usize,
    /// Width, height and depth of the bounds (zeros when nothing is drawn).
    extents: [f64; 3],
}

/// Derives and draws `sys` within [`COMPARE_MAX_SYMBOLS`]: `None` when
/// that is not enough.
fn drawn(sys: &System, steps: Option<u64>) -> Option<Drawn> {
    let opts = RunOptions {
        steps,
        max_symbols: COMPARE_MAX_SYMBOLS,
        max_moves: COMPARE_MAX_SYMBOLS,
        ..RunOptions::default()
    };
    let (_, g) = geometry(sys, &opts).ok()?;
    let b = g.bbox().unwrap_or([0.0; 6]);
    Some(Drawn {
        steps: opts.derive_options(sys).steps,
        segments: g.segments.len(),
        extents: [b[3] - b[0], b[4] - b[1], b[5] - b[2]],
    })
}

/// Draws the source `sys` and its approximated translation `t` (bounded
/// by [`COMPARE_MAX_SYMBOLS`]) and, when they differ much, adds one
/// warning with both sets of figures; when either is too large to draw
/// quickly, a note on the first warning says they were not compared.
fn compare_pictures(sys: &System, req: &back::Request, t: &mut back::Translation) {
    let Some(text) = &t.text else { return };
    // The source first: reading a translation to STL expands its rules,
    // as large as the source's word.
    let source = drawn(sys, req.steps);
    let name = format!("translation.{}", req.target.extension());
    let out = match source {
        Some(_) => match compile(SourceFile::new(name, text.as_str())).system {
            Some(out) => Some(out),
            // Not read back (a bug the tests look for): nothing to compare.
            None => return,
        },
        None => None,
    };
    // The translation states its own derivation length (or, in STL, has
    // the steps written out).
    let translated = out.as_ref().and_then(|out| drawn(out, None));
    let (Some(source), Some(translated)) = (&source, translated) else {
        let large = if source.is_none() {
            "the source"
        } else {
            "the translation"
        };
        if let Some(first) = t.diagnostics.0.first_mut() {
            first.notes.push(format!(
                "the translation's picture was not compared with the source's: {large} \
                 derives more than {COMPARE_MAX_SYMBOLS} symbols, too many to draw quickly"
            ));
        }
        return;
    };
    if let Some(d) = picture_difference(source, &translated) {
        t.diagnostics.push(d);
    }
}

/// The warning that `translated` no longer draws `source`'s picture: the
/// segment counts differ by more than half, or the bounds' proportions by
/// more than a quarter of the picture's size (a uniform scale is no
/// difference: every picture is fitted to its frame). A source that draws
/// no segment (polygons only, or nothing) is not compared.
fn picture_difference(source: &Drawn, translated: &Drawn) -> Option<Diagnostic> {
    let (a, b) = (source.segments, translated.segments);
    if a == 0 {
        return None;
    }
    let counts_differ = a.max(b) as f64 > 1.5 * a.min(b) as f64;
    let size = |d: &Drawn| d.extents.iter().copied().fold(0.0, f64::max);
    let (sa, sb) = (size(source), size(translated));
    let proportion = |d: &Drawn, s: f64, i: usize| if s > 0.0 { d.extents[i] / s } else { 0.0 };
    let proportions_differ =
        (0..3).any(|i| (proportion(source, sa, i) - proportion(translated, sb, i)).abs() > 0.25);
    if !counts_differ && !proportions_differ {
        return None;
    }
    // Width x height (x depth, for a 3D picture), the largest side 1.
    let dims = if source.extents[2] == 0.0 && translated.extents[2] == 0.0 {
        2
    } else {
        3
    };
    let bounds = |d: &Drawn, s: f64| {
        let shown: Vec<String> = (0..dims)
            .map(|i| format!("{:.2}", proportion(d, s, i)))
            .collect();
        shown.join(" x ")
    };
    let (ba, bb) = (bounds(source, sa), bounds(translated, sb));
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let message = if counts_differ {
        format!(
            "the translation draws {b} segment{} where the source draws {a}",
            plural(b)
        )
    } else {
        format!("the translation's picture is {bb} (its largest side 1) where the source's is {ba}")
    };
    Some(
        Diagnostic::global(codes::TR_PICTURE_DIFFERS, message)
            .with_note(format!(
                "drawn with {} steps (the source) and {} (the translation): {a} and {b} \
                 segments; bounds {ba} and {bb}, as proportions of their largest side",
                source.steps, translated.steps
            ))
            .with_help(
                "the approximations above changed the picture: translate without `--lossy` \
                 to see what the target cannot express",
            ),
    )
}

/// Parses, lowers and validates `file`, collecting every diagnostic.
pub fn compile(file: SourceFile) -> Compiled {
    compile_entry(file, None)
}

/// [`compile`], choosing the entry `entry` of a library (names compared
/// without regard to case). Without a choice, a library of one entry gives
/// that entry; of several, every entry is checked and
/// [`Compiled::needs_entry`] holds.
pub fn compile_entry(file: SourceFile, entry: Option<&str>) -> Compiled {
    compile_as(file, entry, None)
}

/// [`compile_entry`] in the notation `notation` (`--notation`), else in
/// the one [`front::detect`] chooses; a file that reads badly in the
/// chosen one ([`front::reads_badly`]) and cleanly in another says so on
/// its first error.
pub fn compile_as(
    file: SourceFile,
    entry: Option<&str>,
    notation: Option<&'static dyn Front>,
) -> Compiled {
    let mut diags = Diagnostics::default();
    if let Some(refused) = refuse_unread(&file) {
        // Not read, so not told apart either: the first front end stands
        // for it.
        diags.push(refused);
        return Compiled {
            file,
            system: None,
            spans: SpanTable::default(),
            diagnostics: diags,
            front: front::FRONTS[0],
            library: None,
        };
    }
    let ext = file.extension().unwrap_or("l").to_ascii_lowercase();
    let front = notation.unwrap_or_else(|| front::detect(&ext, &file.text));
    if file.text.trim().is_empty() {
        // Every notation would say something different about nothing.
        diags.push(empty_file(&file));
        return Compiled {
            file,
            system: None,
            spans: SpanTable::default(),
            diagnostics: diags,
            front,
            library: None,
        };
    }
    let read = front.read(&file, entry, &mut diags);
    if entry.is_some() && read.library.is_none() {
        diags.push(
            Diagnostic::global(
                codes::FR_UNKNOWN_ENTRY,
                format!(
                    "an entry was chosen, but this file is {} and has no entries",
                    front.title()
                ),
            )
            .with_help(format!(
                "only libraries have entries to choose ({})",
                front::FRONTS
                    .iter()
                    .filter_map(|f| f
                        .library_form()
                        .map(|form| format!("{}: {form}", f.title())))
                    .collect::<Vec<_>>()
                    .join("; ")
            )),
        );
    }
    diags.sort();
    if notation.is_none() && front::reads_badly(&file, &diags) {
        if let Some(other) = front::reads_cleanly_as(&file, front) {
            let note = front::other_notation_note(front, &ext, other);
            if let Some(first) = diags.0.iter_mut().find(|d| d.is_error()) {
                first.notes.push(note);
            }
        }
    }
    let (system, spans) = match read.lowered {
        Some(l) => (Some(l.system), l.spans),
        None => (None, SpanTable::default()),
    };
    let system = if diags.has_errors() { None } else { system };
    Compiled {
        file,
        system,
        spans,
        diagnostics: diags,
        front,
        library: read.library,
    }
}

/// The notations graftal reads, with their extensions: `pfg .l, …`.
pub fn notations() -> String {
    let each: Vec<String> = front::FRONTS
        .iter()
        .map(|f| format!("{} .{}", f.title(), f.extensions().join(" .")))
        .collect();
    each.join(", ")
}

/// The one diagnostic for a file of nothing but white space, the same
/// in every notation.
fn empty_file(file: &SourceFile) -> Diagnostic {
    Diagnostic::global(
        codes::EMPTY_FILE,
        format!("`{}` is empty: there is no L-system in it", file.name),
    )
    .with_help("write an axiom and productions; `graftal list` names examples to start from")
}

/// The one diagnostic for a file no front end reads: larger than
/// [`MAX_SOURCE_BYTES`], or not text (a picture, a program, random bytes),
/// which would otherwise give one diagnostic per byte.
fn refuse_unread(file: &SourceFile) -> Option<Diagnostic> {
    if let Some(over) = file.oversize() {
        let message = match over.size {
            Some(n) => {
                format!("the file has {n} bytes, more than the {MAX_SOURCE_BYTES} graftal reads")
            }
            // A pipe or a device: read no further than the limit.
            None => format!("the file has more than the {MAX_SOURCE_BYTES} bytes graftal reads"),
        };
        return Some(
            Diagnostic::global(codes::FILE_TOO_LARGE, message).with_help(
                "an L-system file holds rules, not derived words: write the axiom and productions",
            ),
        );
    }
    let why = match file.not_text()? {
        NotText::Nul(at) => {
            let (line, col) = file.line_col(at);
            format!("it holds a NUL byte (line {line}, column {col})")
        }
        NotText::Unprintable(percent) => {
            format!("{percent}% of its first characters are neither printable nor white space")
        }
    };
    Some(
        Diagnostic::global(
            codes::NOT_TEXT,
            format!("`{}` is not a text file", file.name),
        )
        .with_note(why)
        .with_help(format!(
            "graftal reads L-system files, which are plain text: {}",
            notations()
        )),
    )
}

/// Derives and writes the word as [`Front::word_text`] would, followed by a
/// newline. A context-free deterministic system whose notation spells words
/// by their symbols' names ([`Front::spells_words_by_name`]) is written
/// straight from its shared derivation tree ([`Tree::walk`]), in chunks,
/// without building the word; any other is derived, then written.
/// `progress` is called as [`derive_with_progress`] calls it. Write errors (a closed
/// pipe) end the writing quietly.
pub fn write_derived(
    front: &dyn Front,
    sys: &System,
    opts: &RunOptions,
    out: &mut dyn std::io::Write,
    mut progress: impl FnMut(u64, usize),
) -> Result<(), Diagnostic> {
    let dopts = opts.derive_options(sys);
    let by_name = front.spells_words_by_name();
    let tree = match by_name && dopts.steps <= MAX_TREE_DEPTH {
        true => Tree::new(sys),
        false => None,
    };
    let mut out = std::io::BufWriter::with_capacity(1 << 18, out);
    let names: Vec<&[u8]> = sys.symbols.iter().map(|(_, i)| i.name.as_bytes()).collect();
    if let Some(t) = tree {
        // Checks the limit before anything is written.
        let len = Deriver::new(sys).tree_len(&t, &dopts)?;
        let _ = t.walk(
            dopts.steps,
            |s| names[s.index()],
            |chunk| out.write_all(chunk),
        );
        progress(dopts.steps, len);
    } else if by_name && !sys.rewrites_modules() {
        // Plain symbols, kept as narrow as they were derived (a byte each
        // for most alphabets) and written in chunks: no wider copy of the
        // word, no text of it.
        let w = Deriver::new(sys).derive_symbols(&dopts, progress)?;
        write_names(&names, w.iter(), &mut out);
    } else {
        let w = derive_with_progress(sys, opts, progress)?;
        if by_name && !w.has_params() {
            write_names(&names, w.0.iter().copied(), &mut out);
        } else {
            let _ = out.write_all(front.word_text(sys, &w).as_bytes());
        }
    }
    let _ = out.write_all(b"\n");
    let _ = out.flush();
    Ok(())
}

/// Writes the symbols' names one after the other, stopping at the first
/// write error (a closed pipe).
fn write_names(
    names: &[&[u8]],
    word: impl Iterator<Item = crate::ir::SymbolId>,
    out: &mut dyn std::io::Write,
) {
    if names.iter().all(|n| n.len() == 1) {
        // One byte per symbol: a table look-up per symbol, a chunk at a time.
        let byte: Vec<u8> = names.iter().map(|n| n[0]).collect();
        let mut chunk = Vec::with_capacity(1 << 16);
        for s in word {
            chunk.push(byte[s.index()]);
            if chunk.len() == chunk.capacity() {
                if out.write_all(&chunk).is_err() {
                    return;
                }
                chunk.clear();
            }
        }
        let _ = out.write_all(&chunk);
    } else {
        // Name by name into the buffer: no text built in between.
        for s in word {
            if out.write_all(names[s.index()]).is_err() {
                return;
            }
        }
    }
}

/// How many symbols of `word` are written: STL's silent stem-level markers
/// (symbols with an empty name) are not counted.
fn written_symbols(sys: &System, word: &Word) -> usize {
    let silent: Vec<bool> = sys.symbols.iter().map(|(_, i)| i.name.is_empty()).collect();
    if silent.iter().any(|&s| s) {
        word.0.iter().filter(|s| !silent[s.index()]).count()
    } else {
        word.len()
    }
}

/// The most symbols `check` derives a system to (and 20 times as many
/// rewritten, [`DeriveOptions::max_symbols`]): a derivation beyond this
/// takes seconds, and `check` stays quick. A derivation counted on its
/// shared tree costs nothing to count, and is checked at `derive`'s own
/// limit.
pub const CHECK_MAX_SYMBOLS: usize = 1_000_000;

/// The most symbols `check` derives each entry of a library to, when no
/// entry is chosen and each is derived ([`derivation_diagnostics`]).
pub const CHECK_ENTRY_MAX_SYMBOLS: usize = 100_000;

/// The most entries of a library `check` lists, and derives one by one:
/// a library may hold 100,000, and one line each would flood the
/// terminal. The largest library known (Fractint's own `fractint.l`) has
/// 69, listed whole.
pub const LISTED_ENTRIES: usize = 100;

/// The most bytes of source `check` reads again to derive a library's
/// entries one by one: entries times the file's length (each entry is
/// compiled from the whole file). Beyond it entries are not derived.
const CHECK_LIBRARY_BYTES: usize = 16 << 20;

/// What `derive` would report besides the file's own diagnostics, found by
/// the derivation it runs (the file's steps, seed 0): a derivation past the
/// symbol or work limit (E0301, E0302). `check` reports these as warnings,
/// with a note that `derive` stops there; a derivation that is only too
/// long for `check`'s own limit ([`CHECK_MAX_SYMBOLS`]) says so. Of a
/// library without a chosen entry each listed entry is derived (to
/// [`CHECK_ENTRY_MAX_SYMBOLS`]), and its diagnostics name it.
pub fn derivation_diagnostics(c: &Compiled) -> Vec<Diagnostic> {
    if let Some(sys) = &c.system {
        return derivation_limits(c.front, sys, CHECK_MAX_SYMBOLS)
            .into_iter()
            .collect();
    }
    let Some(lib) = c.library.as_ref().filter(|l| l.needs_entry) else {
        return Vec::new();
    };
    let listed = lib.entries.len().min(LISTED_ENTRIES);
    if listed.saturating_mul(c.file.text.len()) > CHECK_LIBRARY_BYTES {
        return Vec::new();
    }
    let mut out = Vec::new();
    for e in &lib.entries[..listed] {
        let one = compile_as(c.file.clone(), Some(&e.name), Some(c.front));
        let Some(sys) = &one.system else { continue };
        if let Some(mut d) = derivation_limits(one.front, sys, CHECK_ENTRY_MAX_SYMBOLS) {
            d.message = format!("entry `{}`: {}", e.name, d.message);
            out.push(d);
        }
    }
    out
}

/// The derivation `derive` runs of `sys`, checked against its limits: on
/// the shared tree when `derive` counts there (exact, at `derive`'s
/// limit), else derived up to `max` symbols. The limit's diagnostic, as a
/// warning, when one is reached.
fn derivation_limits(front: &dyn Front, sys: &System, max: usize) -> Option<Diagnostic> {
    let full = RunOptions::default();
    let dopts = full.derive_options(sys);
    let tree = (front.spells_words_by_name() && dopts.steps <= MAX_TREE_DEPTH)
        .then(|| Tree::new(sys))
        .flatten();
    let (result, capped) = match tree {
        Some(t) => (Deriver::new(sys).tree_len(&t, &dopts).map(|_| ()), false),
        None => {
            let opts = RunOptions {
                max_symbols: max.min(full.max_symbols),
                ..full
            };
            (derive_values(sys, &opts, |_, _| {}).map(|_| ()), true)
        }
    };
    let mut d = result.err()?;
    d.severity = crate::diagnostics::Severity::Warning;
    Some(if capped {
        d.with_note(format!(
            "`check` derives up to {max} symbols and stops here; `graftal derive` allows {} \
             (`--max-symbols`), and stops with this error if the derivation goes past it",
            full.max_symbols
        ))
    } else {
        d.with_note("`graftal derive` stops here with this error")
    })
}

/// Settings given on the command line.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Steps; `None` means the file's own derivation length, else 0.
    pub steps: Option<u64>,
    pub seed: u64,
    pub max_symbols: usize,
    /// The most turtle moves interpreted (see [`MAX_MOVES`]).
    pub max_moves: usize,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            steps: None,
            seed: 0,
            max_symbols: DEFAULT_MAX_SYMBOLS,
            max_moves: MAX_MOVES,
        }
    }
}

impl RunOptions {
    pub fn derive_options(&self, sys: &System) -> DeriveOptions {
        DeriveOptions::new(self.steps.or(sys.settings.steps).unwrap_or(0))
            .seed(self.seed)
            .max_symbols(self.max_symbols)
    }
}

/// Derives the word, reporting progress after each step.
pub fn derive_with_progress(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<Word, Diagnostic> {
    derive_values(sys, opts, progress).map(|(w, _)| w)
}

/// Derives the word, reporting progress after each step, with the values
/// its program's globals and arrays were left with (what the homomorphism
/// reads when the word is drawn: [`interpret`]).
pub fn derive_values(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<(Word, Globals), Diagnostic> {
    let dopts = opts.derive_options(sys);
    // The module test alone ([`eval::plan`] would build the Deriver, and
    // its table, a second time): the plain methods are the Deriver's.
    if sys.rewrites_modules() {
        return eval::parametric::derive(sys, &dopts, progress, &mut |w, values| {
            answer_queries(sys, w, values, opts)
        });
    }
    let word = Deriver::new(sys).derive(&dopts, progress)?;
    Ok((word, Globals::initial(&sys.program)))
}

/// Derives the word.
pub fn derive(sys: &System, opts: &RunOptions) -> Result<Word, Diagnostic> {
    derive_with_progress(sys, opts, |_, _| {})
}

/// The most turtle moves a word may have to be interpreted: each becomes a
/// segment or a point kept in memory (about 64 bytes, and as much again to
/// draw it), so 30 million stay within a few GB.
pub const MAX_MOVES: usize = 30_000_000;

/// Interprets `word`, refusing words whose geometry would not fit in memory
/// ([`MAX_MOVES`]). With `paths`, the turtle's paths are recorded too. A
/// system whose rewriting needs modules draws its word through its
/// homomorphism, which reads the program's globals and arrays as `values`
/// holds them ([`derive_values`]).
pub fn interpret(
    sys: &System,
    word: &Word,
    values: &Globals,
    opts: &RunOptions,
    paths: bool,
) -> Result<Geometry, Diagnostic> {
    let drawn = drawn_word(sys, word, values, opts)?;
    Ok(turtle::Run {
        paths,
        ..turtle::Run::word(sys, &drawn, opts.seed)
    }
    .geometry())
}

/// The word the turtle draws for `word`: itself, or what the system's
/// homomorphism makes of it (reading the program's globals and arrays as
/// `values` holds them); refused when its geometry would not fit in
/// memory ([`MAX_MOVES`]).
fn drawn_word<'w>(
    sys: &System,
    word: &'w Word,
    values: &Globals,
    opts: &RunOptions,
) -> Result<std::borrow::Cow<'w, Word>, Diagnostic> {
    if sys.rewrites_modules() {
        let dopts = opts.derive_options(sys);
        let (drawn, _) = eval::parametric::homomorphism(sys, word, values, &dopts)?;
        let moves = turtle::drawn_cost(sys, &drawn);
        if moves > opts.max_moves as u64 {
            return Err(too_much_geometry(moves, opts.max_moves).with_note(
                "each triangle of a surface and face of a generalized cylinder counts as a move",
            ));
        }
        return Ok(std::borrow::Cow::Owned(drawn));
    }
    let moves = turtle::drawn_cost(sys, word);
    if moves > opts.max_moves as u64 {
        return Err(too_much_geometry(moves, opts.max_moves)
            .with_note(format!("the derived word has {} symbols", word.len())));
    }
    Ok(std::borrow::Cow::Borrowed(word))
}

/// Whether an STL layout would draw an outline under the system's picture.
fn has_outline(sys: &System) -> bool {
    sys.structure
        .as_ref()
        .is_some_and(|st| !st.constraint.outline.is_empty())
}

/// Whether [`render_lit`] may draw `sys` to `format` with `ropts`: a PNG
/// of a lit look, without splines or an STL layout (`layout`: one would be
/// added).
pub fn streams_lit(sys: &System, format: Format, ropts: &RenderOptions, layout: bool) -> bool {
    format == Format::Png
        && sys.look.lighting.is_some()
        && !ropts.spline
        && !(layout && has_outline(sys))
}

/// Draws a lit system's word to a PNG straight from the turtle
/// ([`render::raster::png_surveyed`]): the turtle runs once for the framing and
/// once per band of rows, and nothing drawn is stored, so a plant of
/// millions of polygons draws in the memory of its picture. The picture is
/// the one [`render_bytes`] draws from the stored geometry. `Ok(None)` when
/// nearly nothing is drawn, which the stored way explains. Call it where
/// [`streams_lit`] holds.
pub fn render_lit(
    sys: &System,
    word: &Word,
    values: &Globals,
    opts: &RunOptions,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Option<Result<Vec<u8>, LoadError>>, Diagnostic> {
    let drawn = drawn_word(sys, word, values, opts)?;
    apply_look(sys, &mut ropts);
    ropts.thin_dense = true;
    let Some(lighting) = sys.look.lighting.as_ref() else {
        return Ok(None);
    };
    let replay = |sink: &mut dyn turtle::Sink| {
        turtle::run(turtle::Run::word(sys, &drawn, opts.seed), sink).max_depth
    };
    let drawing = render::raster::Drawing::replayed(&replay, sys.settings.world_widths);
    let survey = render::raster::survey(&drawing, lighting, &ropts);
    if survey.pixels_across(&ropts) < NEARLY_NOTHING {
        return Ok(None);
    }
    let png =
        render::raster::png_surveyed(&drawing, &survey, lighting, palette(sys), &ropts, progress);
    Ok(Some(png.ok_or_else(|| {
        LoadError(format!(
            "cannot make a {}x{} PNG",
            ropts.width, ropts.height
        ))
    })))
}

/// Fills the query modules (`?P`, `?H`, …) of `word` with what the turtle
/// finds there, drawing the word through the homomorphism.
fn answer_queries(sys: &System, word: &mut Word, values: &Globals, opts: &RunOptions) {
    let dopts = opts.derive_options(sys);
    let Ok((drawn, origins)) = eval::parametric::homomorphism(sys, word, values, &dopts) else {
        return;
    };
    let run = turtle::Run {
        queries: true,
        ..turtle::Run::word(sys, &drawn, opts.seed)
    };
    for (i, v) in turtle::run(run, &mut Geometry::default()).answers {
        // Only a query module the homomorphism kept writes back.
        let Some(&o) = origins.get(i) else { continue };
        let o = o as usize;
        if word.0.get(o) != drawn.0.get(i) {
            continue;
        }
        word.set_args(o, &v);
    }
}

/// Derives and interprets: the geometry of the system.
pub fn geometry(sys: &System, opts: &RunOptions) -> Result<(Word, Geometry), Diagnostic> {
    let (word, values) = derive_values(sys, opts, |_, _| {})?;
    let g = interpret(sys, &word, &values, opts, false)?;
    Ok((word, g))
}

/// Adds an STL system's layout shapes to `g` as filled polygons drawn
/// first, so the tree is drawn over them (PNG and SVG draw polygons before
/// segments). Systems without a layout are left as they are.
pub fn add_layout(sys: &System, g: &mut Geometry) {
    let Some(st) = &sys.structure else { return };
    let shapes: Vec<turtle::Polygon> = st
        .constraint
        .outline
        .iter()
        .map(|s| turtle::Polygon {
            points: crate::ir::layout::outline(s)
                .into_iter()
                .map(|p| [p[0], p[1], 0.0])
                .collect(),
            colour: crate::ir::layout::colour(s),
            index: 0,
            surface: false,
        })
        .filter(|p| p.points.len() >= 3)
        .collect();
    g.polygons.splice(0..0, shapes);
}

/// The warning for a picture with nothing in it, naming the likely cause
/// ([`why_nothing_drawn`]). When the file's own `diagnostics` say the
/// model waits on an environment that never answers (W0821), the warning
/// says that this is why.
pub fn nothing_drawn(
    sys: &System,
    word: &Word,
    file: &str,
    opts: &RunOptions,
    diagnostics: &Diagnostics,
) -> Diagnostic {
    let mut d = Diagnostic::global(
        codes::NOTHING_DRAWN,
        "nothing is drawn: the picture is empty",
    )
    .with_note(format!(
        "the derived word has {} symbols and none of them draws",
        word.len()
    ));
    match diagnostics
        .iter()
        .find(|d| d.code == codes::CPFG_NO_ENVIRONMENT)
    {
        Some(env) => {
            d = d.with_note(
                "the model draws only what its environment answers to `?E`, \
                 and graftal runs no environment program (W0821)",
            );
            d.notes.extend(env.notes.iter().cloned());
        }
        None => {
            let steps = opts.derive_options(sys).steps;
            if let Some(why) = why_nothing_drawn(sys, word, file, steps) {
                d = d.with_note(why);
            }
        }
    }
    d
}

/// The likely cause of an empty picture, checked in this order: a stdlib
/// schema (its source prints words, not a picture); a word whose turtle
/// only moves without drawing (`f`: a kolam, drawn with `--spline`); a
/// word with no symbol that moves the turtle at all (a string example);
/// no derivation steps, so only the axiom was drawn.
pub fn why_nothing_drawn(sys: &System, word: &Word, file: &str, steps: u64) -> Option<String> {
    if let Some(e) = stdlib::by_file(file).filter(|e| e.kind() == stdlib::Kind::Schema) {
        return Some(format!(
            "`std:{}` is a schema, not a drawing ({}): `graftal derive std:{}` prints its words",
            e.name,
            e.schema_reason().unwrap_or_default(),
            e.name
        ));
    }
    let (mut moves, mut draws) = (false, false);
    for &s in word.symbols() {
        if let Some(TurtleOp::Forward { draw }) = sys.op(s) {
            moves = true;
            draws |= draw;
        }
    }
    if moves && !draws {
        return Some(
            "the turtle only moves without drawing (`f`): a kolam is drawn as a \
             B-spline through its positions; try `--spline`"
                .into(),
        );
    }
    if !moves && steps > 0 {
        return Some(
            "no symbol of the derived word moves the turtle: a string example is \
             read with `graftal derive`, or its symbols need `F` to draw"
                .into(),
        );
    }
    (steps == 0)
        .then(|| "the derivation has 0 steps, so only the axiom is drawn: try `-n 4`".into())
}

/// Pixels under which a picture's width (or length) counts as nothing:
/// a line drawn one or two pixels wide shows no shape.
pub const NEARLY_NOTHING: f64 = 2.0;

/// The warning for a picture that draws nearly nothing at the view and
/// size of `ropts` (W0009): what it draws is under [`NEARLY_NOTHING`]
/// pixels across ([`render::drawn_spread`]), a line or a point. A note
/// says why: geometry in a plane seen edge-on (with the `--view` that
/// looks straight at it), geometry on one line, or a picture too long for
/// its width at this size.
pub fn nearly_nothing_drawn(
    sys: &System,
    g: &Geometry,
    ropts: &RenderOptions,
) -> Option<Diagnostic> {
    let mut opts = *ropts;
    apply_look(sys, &mut opts);
    let drawn = render::drawn_spread(g, &opts);
    if drawn.width >= NEARLY_NOTHING {
        return None;
    }
    let (w, h) = (opts.width, opts.height);
    if drawn.length < NEARLY_NOTHING {
        return Some(
            Diagnostic::global(codes::NEARLY_NOTHING_DRAWN, "nearly nothing is drawn: the picture is a point")
                .with_note(format!(
                    "what is drawn covers under {NEARLY_NOTHING} pixels of the {w}x{h} picture: its segments have no length, or all lie at one point"
                )),
        );
    }
    let d = Diagnostic::global(
        codes::NEARLY_NOTHING_DRAWN,
        format!(
            "nearly nothing is drawn: the picture is a line {:.0} pixels long and {:.1} wide",
            drawn.length, drawn.width
        ),
    );
    let points = world_points(g, opts.spline);
    let axes = principal_spreads(&points).map(|(_, axis)| axis);
    let range = |axis: turtle::Vec3| {
        let along = points
            .iter()
            .map(|p| p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2]);
        let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        (hi - lo).max(0.0)
    };
    let (long, wide) = (range(axes[0]), range(axes[1]));
    let longer = format!(
        "the picture is {:.0} times longer than it is wide",
        drawn.length / drawn.width.max(1e-3)
    );
    if wide <= 1e-9 * long {
        return Some(d.with_note(
            "every segment lies on one line, so the picture is a line from every view",
        ));
    }
    // Even seen straight on, the widest view, the width would be lost.
    if wide / long * drawn.length < NEARLY_NOTHING {
        return Some(d.with_note(format!(
            "{longer}, from every view: draw it larger with `--size`"
        )));
    }
    let (az, el) = view_along(axes[2]);
    let face_on = RenderOptions {
        view: View::degrees(az, el),
        camera: None,
        ..opts
    };
    if render::drawn_spread(g, &face_on).width >= NEARLY_NOTHING {
        return Some(
            d.with_note("the geometry lies in a plane, and this view sees it edge-on")
                .with_help(format!(
                    "try `--view {az:.0},{el:.0}`, which looks straight at that plane"
                )),
        );
    }
    Some(d.with_note(format!("{longer}: draw it larger with `--size`")))
}

/// The points a picture of `g` is made of: segment ends and polygon
/// corners, or with `spline` the turtle's positions the curves pass by.
fn world_points(g: &Geometry, spline: bool) -> Vec<turtle::Vec3> {
    if spline {
        return g
            .paths
            .iter()
            .flat_map(|p| p.points.iter().copied())
            .collect();
    }
    g.segments
        .iter()
        .flat_map(|s| [s.a, s.b])
        .chain(g.polygons.iter().flat_map(|p| p.points.iter().copied()))
        .chain(g.discs.iter().map(|d| d.centre))
        .collect()
}

/// The variances of `points` along their principal axes, largest first,
/// each with its axis (a unit vector): the eigenvalues and eigenvectors of
/// their covariance, by Jacobi rotations.
fn principal_spreads(points: &[turtle::Vec3]) -> [(f64, turtle::Vec3); 3] {
    let n = points.len().max(1) as f64;
    let mean = [0, 1, 2].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
    let mut c = [[0.0f64; 3]; 3];
    for p in points {
        let d = [0, 1, 2].map(|k| p[k] - mean[k]);
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j] / n;
            }
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let (p, q) = [(0, 1), (0, 2), (1, 2)]
            .into_iter()
            .max_by(|a, b| c[a.0][a.1].abs().total_cmp(&c[b.0][b.1].abs()))
            .unwrap_or((0, 1));
        if c[p][q].abs() <= 1e-300 {
            break;
        }
        let theta = 0.5 * (2.0 * c[p][q]).atan2(c[q][q] - c[p][p]);
        let (s, co) = theta.sin_cos();
        // c = Jᵀ c J and v = v J for the rotation J in the (p, q) plane:
        // turning the rows of c gives c J, whose transpose is Jᵀ c (c is
        // symmetric), and turning that again gives Jᵀ c J.
        let turn = |row: &mut [f64; 3]| {
            let (a, b) = (row[p], row[q]);
            row[p] = co * a - s * b;
            row[q] = s * a + co * b;
        };
        c.iter_mut().for_each(turn);
        c = [0, 1, 2].map(|i| [c[0][i], c[1][i], c[2][i]]);
        c.iter_mut().for_each(turn);
        v.iter_mut().for_each(turn);
    }
    let mut out = [0, 1, 2].map(|k| (c[k][k].max(0.0), [v[0][k], v[1][k], v[2][k]]));
    out.sort_by(|a, b| b.0.total_cmp(&a.0));
    out
}

/// The view (azimuth, elevation in degrees) that looks along `normal`:
/// the direction [`render`]'s parallel view looks from is
/// (-sin az cos el, sin el, cos az cos el).
fn view_along(normal: turtle::Vec3) -> (f64, f64) {
    let n = if normal[2] < 0.0 {
        normal.map(|x| -x)
    } else {
        normal
    };
    let el = n[1].clamp(-1.0, 1.0).asin().to_degrees();
    let az = (-n[0]).atan2(n[2]).to_degrees();
    // No `-0` in the suggestion.
    (az.round() + 0.0, el.round() + 0.0)
}

/// Output formats of [`render`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Png,
    Svg,
}

impl Format {
    /// The formats' names, as `render --to` takes them and as extensions.
    pub const NAMES: &'static [&'static str] = &["png", "svg"];

    /// The format named `name` (`png`, `svg`; any case).
    pub fn from_name(name: &str) -> Option<Format> {
        match name.to_ascii_lowercase().as_str() {
            "png" => Some(Format::Png),
            "svg" => Some(Format::Svg),
            _ => None,
        }
    }

    /// The format for an output path, by its extension.
    pub fn from_path(path: &str) -> Option<Format> {
        Format::from_name(Path::new(path).extension()?.to_str()?)
    }

    pub fn name(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Svg => "svg",
        }
    }
}

/// Where a command writes its result: `-o -`, like no `-o`, is standard
/// output; anything else is a file's path (a file named `-` is `-o ./-`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Output {
    Stdout,
    File(String),
}

impl Output {
    /// The output `-o` names; `None` (no `-o`) is standard output.
    pub fn from_arg(arg: Option<&str>) -> Output {
        match arg {
            None | Some("-") => Output::Stdout,
            Some(path) => Output::File(path.to_string()),
        }
    }

    /// The file's path, `None` for standard output.
    pub fn path(&self) -> Option<&str> {
        match self {
            Output::Stdout => None,
            Output::File(p) => Some(p),
        }
    }
}

/// A command line that cannot be carried out (exit status 2): what is
/// wrong, and how to say it instead.
#[derive(Debug, PartialEq, Eq)]
pub struct UsageError {
    pub message: String,
    pub help: String,
}

/// The picture format `render` writes to `output`: `to` (`--to`) when
/// given, else the file's extension. Standard output has no extension, so
/// there `to` is needed; a `to` that contradicts the extension is refused
/// rather than writing SVG text into `plant.png`. A binary PNG is refused
/// when standard output is a terminal (`stdout_terminal`): it would fill
/// the screen with noise and can leave the terminal in a strange state.
pub fn picture_format(
    output: &Output,
    to: Option<Format>,
    stdout_terminal: bool,
) -> Result<Format, UsageError> {
    let format = match (output, to) {
        (Output::Stdout, None) => {
            return Err(UsageError {
                message: "`-o -` writes the picture to standard output, but in which format?"
                    .into(),
                help: "add `--to png` or `--to svg`".into(),
            })
        }
        (Output::Stdout, Some(f)) => f,
        (Output::File(path), to) => match (Format::from_path(path), to) {
            (None, None) => {
                return Err(UsageError {
                    message: format!("cannot tell the picture format of `{path}`"),
                    help: "end the file name in .png or .svg, or add `--to png` or `--to svg`"
                        .into(),
                })
            }
            (Some(by_name), Some(f)) if by_name != f => {
                return Err(UsageError {
                    message: format!(
                        "`--to {}` but `{path}` names a {} file",
                        f.name(),
                        by_name.name()
                    ),
                    help: format!("drop `--to`, or name the file `….{}`", f.name()),
                })
            }
            (_, Some(f)) | (Some(f), None) => f,
        },
    };
    if format == Format::Png && *output == Output::Stdout && stdout_terminal {
        return Err(UsageError {
            message: "refusing to write a binary PNG to the terminal".into(),
            help: "redirect standard output (`… -o - --to png > plant.png`), or use `--to svg`"
                .into(),
        });
    }
    Ok(format)
}

/// Renders a geometry to bytes of `format`.
pub fn render_bytes(
    sys: &System,
    g: &Geometry,
    format: Format,
    opts: RenderOptions,
) -> Result<Vec<u8>, LoadError> {
    render_bytes_with(sys, g, format, opts, &mut |_, _| {})
}

/// [`render_bytes`], calling `progress(drawn, total)` as segments are
/// drawn.
pub fn render_bytes_with(
    sys: &System,
    g: &Geometry,
    format: Format,
    mut opts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<u8>, LoadError> {
    apply_look(sys, &mut opts);
    opts.thin_dense = format == Format::Png;
    let lighting = sys.look.lighting.as_ref();
    match (format, lighting) {
        (Format::Png, Some(lighting)) => {
            render::raster::png(g, lighting, palette(sys), &opts, progress).ok_or_else(|| {
                LoadError(format!("cannot make a {}x{} PNG", opts.width, opts.height))
            })
        }
        (Format::Svg, _) if lighting.is_some() || opts.camera.is_some() => {
            Ok(render::svg::write_scene(g, lighting, palette(sys), &opts).into_bytes())
        }
        _ => encode(&render::layout(g, &opts), format, &opts, progress),
    }
}

/// What the system's settings and look say of the picture: the share it
/// fills, its background, and its camera unless a view was asked for.
fn apply_look(sys: &System, opts: &mut RenderOptions) {
    opts.scale = sys.settings.scale;
    opts.background = sys.look.background.unwrap_or(render::WHITE);
    opts.background_alpha = 255;
    if let Some(bg) = opts.style.background {
        opts.background = bg.rgb;
        opts.background_alpha = bg.alpha;
    }
    opts.base_width = sys.settings.width;
    opts.camera = if opts.view_given {
        None
    } else {
        sys.look.camera
    };
}

/// The colour map: the system's colours, else the turtle's default.
fn palette(sys: &System) -> &[crate::ir::Rgb] {
    if sys.colours.is_empty() {
        &crate::turtle::DEFAULT_PALETTE
    } else {
        &sys.colours
    }
}

/// Refuses, before deriving, to draw a system whose word would move the
/// turtle more than [`RunOptions::max_moves`] times when it must be drawn
/// segment by segment: counted on the shared derivation tree of a
/// context-free deterministic system, and bounded from below for the
/// others ([`eval::fewest_at`]: the fewest moves any choices can make).
pub fn check_moves_up_front(sys: &System, opts: &RunOptions) -> Result<(), Diagnostic> {
    let steps = opts.derive_options(sys).steps;
    let is_move = |s: crate::ir::SymbolId| {
        u128::from(matches!(
            sys.op(s),
            Some(TurtleOp::Forward { .. } | TurtleOp::ForwardReal { .. })
        ))
    };
    let max = opts.max_moves as u128;
    if let Some(t) = (steps <= MAX_TREE_DEPTH).then(|| Tree::new(sys)).flatten() {
        let moves: Vec<u128> = (0..sys.symbols.len() as u32)
            .map(|i| is_move(crate::ir::SymbolId(i)))
            .collect();
        return match t.weighed(steps, &moves, max) {
            Ok(_) => Ok(()),
            Err(step) => Err(too_much_geometry(max, opts.max_moves).with_note(format!(
                "known before deriving: the word of step {step} of {steps} already moves it more"
            ))),
        };
    }
    // A homomorphism decides what draws: the word's own moves tell nothing.
    if !sys.homomorphism.productions.is_empty() {
        return Ok(());
    }
    match eval::fewest_at(sys, steps, is_move, u128::from(u64::MAX)) {
        Some(fewest) if fewest > max => Err(too_much_geometry(
            format!("at least {fewest}"),
            opts.max_moves,
        )
        .with_note("known before deriving: whatever the contexts, conditions and random choices")),
        _ => Ok(()),
    }
}

fn too_much_geometry(moves: impl std::fmt::Display, max: usize) -> Diagnostic {
    Diagnostic::global(
        codes::TOO_MUCH_GEOMETRY,
        format!("the word moves the turtle {moves} times, more than can be drawn ({max})"),
    )
    .with_help("draw fewer steps with `-n`; `derive` and `stats` have no such limit")
}

/// Draws a context-free deterministic system from its shared derivation
/// tree ([`render::shared::picture`]): nothing is derived or stored but the
/// picture's polylines, and a subtree within one pixel is drawn as one
/// line. `None` when the system or the view is not one this covers (a 2D
/// system in one colour and width, seen face on, without splines); the
/// caller then derives and interprets.
pub fn render_shared(
    sys: &System,
    opts: &RunOptions,
    format: Format,
    ropts: RenderOptions,
) -> Option<Result<Vec<u8>, LoadError>> {
    render_shared_with(sys, opts, format, ropts, &mut |_, _| {})
}

/// [`render_shared`], calling `progress(drawn, total)` as segments are
/// drawn.
pub fn render_shared_with(
    sys: &System,
    opts: &RunOptions,
    format: Format,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Option<Result<Vec<u8>, LoadError>> {
    let steps = opts.derive_options(sys).steps;
    // A lit look or a camera draws through the full geometry.
    let look = &sys.look;
    // So do a rotation (the fit needs every point, not the box) and a
    // palette (it colours each segment).
    if ropts.spline
        || ropts.style.rotate != 0.0
        || ropts.style.palette.is_some()
        || ropts.view != render::View::default()
        || steps > MAX_TREE_DEPTH
        || look.lighting.is_some()
        || look.camera.is_some()
    {
        return None;
    }
    let mut inst = Instanced::new(sys).filter(|i| i.can_draw() && i.fits(steps))?;
    let whole = inst.word(steps);
    if !whole.draws() || whole.lo[2] != whole.hi[2] {
        return None;
    }
    apply_look(sys, &mut ropts);
    let pic = render::shared::picture(sys, &mut inst, steps, &ropts);
    // A picture that is nearly a line is drawn the long way, which says so
    // ([`nearly_nothing_drawn`]).
    if render::picture_spread(&pic).width < NEARLY_NOTHING {
        return None;
    }
    Some(encode(&pic, format, &ropts, progress))
}

/// A mesh file's contents ([`render_mesh`]).
pub struct MeshOutput {
    pub bytes: Vec<u8>,
    /// The OBJ's material library, to be written as the `mtllib` line
    /// names it.
    pub mtl: Option<String>,
    pub stats: crate::mesh::MeshStats,
}

/// The mesh of the system in `format`: for glTF from its shared subtrees
/// when [`Instanced`] can (one mesh per repeated subtree), else from the
/// derived word's geometry (with an STL file's layout unless
/// `no_layout`). `mtl_file` is the material library the OBJ names.
pub fn render_mesh(
    sys: &System,
    opts: &RunOptions,
    format: crate::mesh::MeshFormat,
    mtl_file: &str,
    no_layout: bool,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<MeshOutput, Diagnostic> {
    use crate::mesh::{MeshFormat, Scene};
    let steps = opts.derive_options(sys).steps;
    let shared = (format == MeshFormat::Glb && steps <= MAX_TREE_DEPTH)
        .then(|| Instanced::new(sys).filter(|i| i.fits(steps)))
        .flatten()
        .and_then(|mut inst| crate::mesh::instanced::scene(sys, &mut inst, steps));
    let scene = match shared {
        Some(s) => s,
        None => {
            check_moves_up_front(sys, opts)?;
            let (word, values) = derive_values(sys, opts, |_, _| {})?;
            let mut g = interpret(sys, &word, &values, opts, false)?;
            if !no_layout {
                add_layout(sys, &mut g);
            }
            let lighting = sys.look.lighting.as_ref();
            Scene::single(crate::mesh::of_geometry(&g, lighting, progress))
        }
    };
    let stats = scene.stats();
    let (bytes, mtl) = match format {
        MeshFormat::Glb => (crate::mesh::glb(&scene), None),
        MeshFormat::Obj => {
            let mesh = scene.flattened();
            let mtl = crate::mesh::mtl(&mesh);
            (crate::mesh::obj(&mesh, mtl_file).into_bytes(), Some(mtl))
        }
        MeshFormat::Ply => (crate::mesh::ply(&scene.flattened()).into_bytes(), None),
    };
    Ok(MeshOutput { bytes, mtl, stats })
}

/// Whether [`render_streamed`] may draw `sys` to `format` with `ropts`:
/// a PNG of plain symbols (no modules, which draw through a
/// homomorphism), unlit, without a camera, splines, an STL layout or a
/// palette that needs the totals (by depth, along the path).
pub fn streams(sys: &System, format: Format, ropts: &RenderOptions) -> bool {
    format == Format::Png
        && !sys.rewrites_modules()
        && !ropts.spline
        && !has_outline(sys)
        && sys.look.lighting.is_none()
        && sys.look.camera.is_none()
        && matches!(ropts.style.palette, None | Some(render::Palette::Mono))
}

/// Derives the word of a system without modules, its symbols as narrow as
/// the derivation held them (what [`render_streamed`] draws).
pub fn derive_symbols(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<eval::Symbols, Diagnostic> {
    Deriver::new(sys).derive_symbols(&opts.derive_options(sys), progress)
}

/// What [`render_streamed`] made: the PNG, or back the word when its
/// drawing needs the stored way (or draws nearly nothing, which the stored
/// way explains), with the values [`interpret`] reads.
pub enum Streamed {
    Picture(Result<Vec<u8>, LoadError>),
    Word(Word, Globals),
}

/// Draws `word` to a PNG streamed ([`render::coverage`]): the turtle runs
/// over the word twice, once for the bounds and once drawing each segment
/// into the picture as it is made; no segment is stored. Call it where
/// [`streams`] holds.
pub fn render_streamed(
    sys: &System,
    opts: &RunOptions,
    word: eval::Symbols,
    mut ropts: RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Streamed {
    apply_look(sys, &mut ropts);
    let unstreamed =
        |w: eval::Symbols| Streamed::Word(w.into_word(), Globals::initial(&sys.program));
    let mut survey = render::coverage::Survey::new(&ropts);
    turtle::run(
        turtle::Run::symbols(sys, word.iter(), opts.seed),
        &mut survey,
    );
    if !survey.streams() {
        return unstreamed(word);
    }
    let world_widths = sys.settings.world_widths;
    let Some(mut painter) = render::coverage::Painter::new(&survey, &ropts, world_widths, progress)
    else {
        return Streamed::Picture(Err(LoadError(format!(
            "cannot make a {}x{} PNG",
            ropts.width, ropts.height
        ))));
    };
    turtle::run(
        turtle::Run::symbols(sys, word.iter(), opts.seed),
        &mut painter,
    );
    if painter.overflow || painter.spread_width() < NEARLY_NOTHING {
        return unstreamed(word);
    }
    Streamed::Picture(painter.picture.png().ok_or_else(|| {
        LoadError(format!(
            "cannot make a {}x{} PNG",
            ropts.width, ropts.height
        ))
    }))
}

/// A picture as bytes of `format`.
fn encode(
    pic: &render::Picture,
    format: Format,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Vec<u8>, LoadError> {
    match format {
        Format::Svg => Ok(render::svg::write_with(pic, opts.detail).into_bytes()),
        Format::Png => render::png::encode_with(pic, progress)
            .ok_or_else(|| LoadError(format!("cannot make a {}x{} PNG", opts.width, opts.height))),
    }
}

/// An animation of a system's growth ([`render::animate`]): the still
/// pictures of steps 0..=N (N from `opts`) as frames, all fitted as the
/// last one is. Every frame is derived anew; the frames together move the
/// turtle at most `opts.max_moves` times. `layout` adds an STL layout
/// under each frame. Errors: a derivation's or the geometry limit's
/// diagnostic, else (inner) a frame that cannot be made or encoded.
pub fn animate(
    sys: &System,
    opts: &RunOptions,
    mut ropts: RenderOptions,
    mut anim: render::animate::Animation,
    layout: bool,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Result<Vec<u8>, LoadError>, Diagnostic> {
    let last = opts.derive_options(sys).steps;
    anim.frames = last.saturating_add(1);
    if let Some(why) = anim.refusal() {
        return Ok(Err(LoadError(why)));
    }
    check_moves_up_front(sys, opts)?;
    let grown = (last == 0)
        .then(|| grown_geometry(sys, opts, layout))
        .flatten();
    if let Some(grown) = &grown {
        anim.frames = grown.frames;
        if let Some(why) = anim.refusal() {
            return Ok(Err(LoadError(why)));
        }
    }
    let mut budget = opts.max_moves;
    let mut frame_geometry = |step: u64| -> Result<Geometry, Diagnostic> {
        let at = RunOptions {
            steps: Some(step),
            max_moves: budget,
            ..opts.clone()
        };
        let (word, values) = derive_values(sys, &at, |_, _| {})?;
        let mut g = interpret(sys, &word, &values, &at, ropts.spline).map_err(|d| {
            d.with_note(format!(
                "an animation moves the turtle at most {} times in all its frames",
                opts.max_moves
            ))
        })?;
        budget -= g.segments.len().min(budget);
        if layout {
            add_layout(sys, &mut g);
        }
        Ok(g)
    };
    let mut final_g = Some(frame_geometry(last)?);
    ropts.framing = final_g.as_ref().map(|g| frame_framing(sys, g, ropts));
    // A derivation's diagnostic, kept while the encoder stops.
    let mut failed: Option<Diagnostic> = None;
    let mut frame = |k: u64| -> Result<render::animate::Frame, String> {
        // Growth replayed: the stems grown before frame k's share of them.
        if let Some(grown) = grown.as_ref().filter(|g| k + 1 < g.frames) {
            let before = (u64::from(grown.stems) * (k + 1) / grown.frames) as u32;
            let part = render::animate::grown_part(&grown.geometry, &grown.appeared, before);
            let png = render_bytes(sys, &part, Format::Png, ropts);
            return render::animate::Frame::from_png(&png.map_err(|e| e.0)?);
        }
        let step = if grown.is_some() { last } else { k };
        let at = RunOptions {
            steps: Some(step),
            ..opts.clone()
        };
        // Each frame drawn the way its still is: shared subtrees, streamed
        // or stored.
        let shared = match render_shared(sys, &at, Format::Png, ropts) {
            Some(png) => Some(png),
            None => streamed_frame(sys, &at, ropts).map_err(|d| {
                failed = Some(d);
                "stopped".to_string()
            })?,
        };
        let png = match shared {
            Some(png) => png,
            None => {
                let kept = if step == last { final_g.take() } else { None };
                let g = match kept {
                    Some(g) => g,
                    None => frame_geometry(step).map_err(|d| {
                        failed = Some(d);
                        "stopped".to_string()
                    })?,
                };
                render_bytes(sys, &g, Format::Png, ropts)
            }
        };
        render::animate::Frame::from_png(&png.map_err(|e| e.0)?)
    };
    let mut bytes = Vec::new();
    let done = render::animate::encode(&anim, &mut bytes, &mut frame, progress);
    match failed {
        Some(d) => Err(d),
        None => Ok(done.map(|()| bytes).map_err(LoadError)),
    }
}

/// A frame drawn streamed, as its still is ([`render_streamed`]); `None`
/// where the still is drawn from stored geometry.
fn streamed_frame(
    sys: &System,
    at: &RunOptions,
    ropts: RenderOptions,
) -> Result<Option<Result<Vec<u8>, LoadError>>, Diagnostic> {
    if !streams(sys, Format::Png, &ropts) {
        return Ok(None);
    }
    let w = derive_symbols(sys, at, |_, _| {})?;
    Ok(match render_streamed(sys, at, w, ropts, &mut |_, _| {}) {
        Streamed::Picture(png) => Some(png),
        Streamed::Word(..) => None,
    })
}

/// The framing of `g`'s still picture, from the renderer that draws it:
/// streamed ([`render_streamed`]), lit (which fits cylinders and spheres)
/// or flat ([`render_bytes`]).
fn frame_framing(sys: &System, g: &Geometry, mut ropts: RenderOptions) -> render::Framing {
    let streamed = streams(sys, Format::Png, &ropts) && g.polygons.is_empty() && g.discs.is_empty();
    apply_look(sys, &mut ropts);
    if streamed {
        let mut survey = render::coverage::Survey::new(&ropts);
        for s in &g.segments {
            turtle::Sink::segment(&mut survey, s.clone());
        }
        if survey.streams() {
            return survey.framing(&ropts, sys.settings.world_widths);
        }
    }
    match &sys.look.lighting {
        Some(lighting) => render::raster::framing(g, lighting, &ropts),
        None => render::framing(g, &ropts),
    }
}

/// A grown structure's picture with what drew each part, and when each
/// symbol of its word appeared in growth ([`crate::ir::seed::growth_order`]).
struct Grown {
    geometry: Geometry,
    appeared: Vec<u32>,
    stems: u32,
    frames: u64,
}

/// The frames of an outline's growth: one per stem, at most
/// [`render::animate::GROWTH_FRAMES`]. `None` unless the system's word is
/// its structure's grown seed and nothing rewrites it.
fn grown_geometry(sys: &System, opts: &RunOptions, layout: bool) -> Option<Grown> {
    let st = sys.structure.as_ref()?;
    let order = crate::ir::seed::growth_order(&mut sys.clone(), st).ok()??;
    if order.word != sys.axiom || sys.rewrites_modules() || order.stems == 0 {
        return None;
    }
    let mut geometry = turtle::Run {
        origins: true,
        ..turtle::Run::word(sys, &sys.axiom, opts.seed)
    }
    .geometry();
    if layout {
        let before = geometry.polygons.len();
        add_layout(sys, &mut geometry);
        // The layout's shapes come first and show in every frame.
        let added = geometry.polygons.len() - before;
        geometry
            .origins
            .polygons
            .splice(0..0, std::iter::repeat_n(usize::MAX, added));
    }
    Some(Grown {
        geometry,
        appeared: order.appeared,
        stems: order.stems,
        frames: u64::from(order.stems).min(render::animate::GROWTH_FRAMES),
    })
}

/// What `graftal stats` reports.
#[derive(Clone, Debug, Serialize)]
pub struct Stats {
    pub steps: u64,
    pub symbols: u128,
    pub segments: u128,
    pub polygons: u128,
    /// `[minx, miny, minz, maxx, maxy, maxz]`, turtle units (zeros when
    /// nothing is drawn).
    pub bbox: [f64; 6],
    pub max_depth: usize,
    /// How the figures were found: `"shared subtrees"` (context-free
    /// systems, without deriving the word), `"streamed"` (the word's
    /// symbols interpreted one by one as they are derived, nothing kept) or
    /// `"derived"` (the word derived, then interpreted without keeping what
    /// is drawn).
    pub method: &'static str,
    /// How the word is derived ([`eval::Method::name`]): `"shared tree"`,
    /// `"table"`, `"general"` or `"modules"`, chosen from the system's
    /// properties.
    pub derivation: &'static str,
    /// Seconds per stage.
    pub time: StageTimes,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct StageTimes {
    /// Reading and checking the file (filled in by the caller that did it).
    pub parse: f64,
    pub derive: f64,
    pub interpret: f64,
}

/// A turtle sink that only counts and measures.
#[derive(Default)]
struct Counter {
    segments: u128,
    polygons: u128,
    bbox: Option<[f64; 6]>,
}

impl Counter {
    /// The figures counted, with what else `stats` reports: how the
    /// figures were found and how the word is derived.
    fn stats(
        self,
        steps: u64,
        symbols: u128,
        max_depth: usize,
        (method, derivation): (&'static str, &'static str),
        time: StageTimes,
    ) -> Stats {
        Stats {
            steps,
            symbols,
            segments: self.segments,
            polygons: self.polygons,
            bbox: self.bbox.unwrap_or([0.0; 6]),
            max_depth,
            method,
            derivation,
            time,
        }
    }

    fn point(&mut self, p: turtle::Vec3) {
        turtle::grow_box(&mut self.bbox, p);
    }
}

impl turtle::Sink for Counter {
    fn segment(&mut self, s: turtle::Segment) {
        self.segments += 1;
        self.point(s.a);
        self.point(s.b);
    }
    fn polygon(&mut self, p: turtle::Polygon) {
        self.polygons += 1;
        p.points.iter().for_each(|&q| self.point(q));
    }
    fn disc(&mut self, d: turtle::Disc) {
        self.point(d.centre);
    }
}

/// Derives and interprets without drawing, and measures; nothing drawn is
/// kept. A context-free deterministic system is measured on its shared
/// derivation tree ([`Instanced`]) without deriving its word, so its size
/// is not limited by `--max-symbols`; when its turtle commands cannot be
/// instanced, its word is streamed symbol by symbol through the turtle
/// (memory grows with the depth, not the word). Any other system is
/// derived (within the symbol limit), then interpreted.
pub fn stats(sys: &System, opts: &RunOptions) -> Result<Stats, Diagnostic> {
    let t0 = Instant::now();
    let dopts = opts.derive_options(sys);
    let steps = dopts.steps;
    let derivation = eval::plan(sys, steps).name();
    let secs = |d: Duration| d.as_secs_f64();
    let silent: Vec<u128> = sys
        .symbols
        .iter()
        .map(|(_, i)| u128::from(!i.name.is_empty()))
        .collect();
    let tree = (steps <= MAX_TREE_DEPTH).then(|| Tree::new(sys)).flatten();
    if let Some(t) = &tree {
        let symbols = t
            .weighed(steps, &silent, u128::MAX)
            .expect("no limit to pass");
        let measured = |c: Counter, max_depth: usize, method: &'static str| {
            let time = StageTimes {
                parse: 0.0,
                derive: 0.0,
                interpret: secs(t0.elapsed()),
            };
            c.stats(steps, symbols, max_depth, (method, derivation), time)
        };
        if let Some(mut inst) = Instanced::new(sys).filter(|i| i.fits(steps)) {
            let x = inst.word(steps);
            let c = Counter {
                segments: x.segments,
                polygons: 0,
                bbox: x
                    .draws()
                    .then(|| [x.lo[0], x.lo[1], x.lo[2], x.hi[0], x.hi[1], x.hi[2]]),
            };
            return Ok(measured(c, x.depth as usize, "shared subtrees"));
        }
        // Streaming costs time in proportion to the word: the limit says
        // so before it starts.
        Deriver::new(sys).tree_len(t, &dopts)?;
        let mut c = Counter::default();
        let run = turtle::Run::symbols(sys, t.symbols(steps), opts.seed);
        let max_depth = turtle::run(run, &mut c).max_depth;
        return Ok(measured(c, max_depth, "streamed"));
    }
    let (w, values) = derive_values(sys, opts, |_, _| {})?;
    let t1 = Instant::now();
    let (symbols, c, max_depth) = if sys.rewrites_modules() {
        // Drawn through the homomorphism, which may need the whole word.
        let g = interpret(sys, &w, &values, opts, false)?;
        let c = Counter {
            segments: g.segments.len() as u128,
            polygons: g.polygons.len() as u128,
            bbox: g.bbox(),
        };
        (w.len() as u128, c, g.max_depth)
    } else {
        let mut c = Counter::default();
        let run = turtle::Run::symbols(sys, w.0.iter().copied(), opts.seed);
        let depth = turtle::run(run, &mut c).max_depth;
        (written_symbols(sys, &w) as u128, c, depth)
    };
    let t2 = Instant::now();
    let time = StageTimes {
        parse: 0.0,
        derive: secs(t1 - t0),
        interpret: secs(t2 - t1),
    };
    Ok(c.stats(steps, symbols, max_depth, ("derived", derivation), time))
}
