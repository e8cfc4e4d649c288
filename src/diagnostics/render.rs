//! Rendering diagnostics: ariadne for people, JSON for tools. The only code
//! in graftal that knows ariadne.
//!
//! What people see is bounded whatever the input: at most [`MAX_SHOWN`]
//! diagnostics, each string at most [`MAX_TEXT`] characters, and a long
//! source line cut to windows around its labels. Control characters and
//! the replacement characters that stand for invalid UTF-8 are shown
//! escaped (`\u{7}`), in snippets and in every string.

use super::{codes, Diagnostic, NotKept, Severity, SideFile};
use crate::source::SourceFile;
use ariadne::{Color, Config, IndexType, Label, Report, ReportKind, Source};
use serde_json::{json, Value};
use std::borrow::Cow;
use std::ops::Range;
use std::sync::Arc;

/// At most this many diagnostics are rendered for people (clang's
/// `-ferror-limit` is 20 too); the rest are counted, by code, in a last
/// line (JSON output has them all).
pub const MAX_SHOWN: usize = 20;

/// The most characters of a message, label, note or help shown.
const MAX_TEXT: usize = 200;

/// The most secondary labels drawn for one diagnostic.
const MAX_LABELS: usize = 8;

/// Source lines wider than this (in characters as shown) are cut to
/// windows around the labels.
const LONG_LINE: usize = 120;

/// Characters shown on each side of a label on a cut line.
const CONTEXT: usize = 40;

/// The most characters of one label shown on a cut line: its start (or,
/// on the line where a label of several lines ends, its end).
const LABEL_SHOWN: usize = 60;

/// Source lines ariadne may be given or walk through for one file's
/// diagnostics (measured: 1 M lines cost about 20 ms to index); past it a
/// diagnostic is shown with its place but without its snippet.
const LINE_BUDGET: usize = 4_000_000;

/// Where a long line or a long string was cut.
const ELLIPSIS: &str = "…";

/// Renders one diagnostic for a person; `colour` only on a terminal.
pub fn render_human(d: &Diagnostic, file: &SourceFile, colour: bool) -> String {
    render_all(std::slice::from_ref(d), file, colour)
}

/// Renders diagnostics of one file for a person: the first
/// [`MAX_SHOWN`], then a line that counts the others.
pub fn render_all(ds: &[Diagnostic], file: &SourceFile, colour: bool) -> String {
    let mut renderer = Renderer::new(file, colour);
    let mut sides = SideFiles::default();
    let mut out = String::new();
    for d in ds.iter().take(MAX_SHOWN) {
        match &d.side {
            Some(_) => {
                let side = sides.file_of(d, file);
                out.push_str(&Renderer::new(side, colour).render(d));
            }
            None => out.push_str(&renderer.render(d)),
        }
    }
    out.push_str(&not_shown(ds));
    out
}

/// The last line when not every diagnostic is shown: how many, of which
/// codes (most frequent first), and how many were not even kept.
fn not_shown(ds: &[Diagnostic]) -> String {
    let hidden = ds.get(MAX_SHOWN..).unwrap_or(&[]);
    let not_kept = ds
        .iter()
        .filter_map(|d| d.not_kept)
        .fold(NotKept::default(), |mut sum, n| {
            sum.errors += n.errors;
            sum.warnings += n.warnings;
            sum
        });
    if hidden.is_empty() && not_kept.total() == 0 {
        return String::new();
    }
    // Codes in the order first met, then by count: a stable order.
    let mut by_code: Vec<(codes::Code, usize)> = Vec::new();
    for d in hidden {
        match by_code.iter_mut().find(|(c, _)| *c == d.code) {
            Some((_, n)) => *n += 1,
            None => by_code.push((d.code, 1)),
        }
    }
    by_code.sort_by_key(|(_, n)| std::cmp::Reverse(*n));
    const NAMED: usize = 4;
    let mut parts: Vec<String> = by_code
        .iter()
        .take(NAMED)
        .map(|(code, n)| match codes::lookup(code.0) {
            Some(info) => format!("{n} {code} ({})", info.title),
            None => format!("{n} {code}"),
        })
        .collect();
    if by_code.len() > NAMED {
        let rest: usize = by_code[NAMED..].iter().map(|(_, n)| n).sum();
        parts.push(format!("{rest} of {} other codes", by_code.len() - NAMED));
    }
    if not_kept.total() > 0 {
        parts.push(format!(
            "{} more found and not kept ({} errors)",
            not_kept.total(),
            not_kept.errors
        ));
    }
    let listed = if not_kept.total() > 0 {
        format!("the {} kept", ds.len())
    } else {
        "them all".to_string()
    };
    format!(
        "... and {} more diagnostics not shown: {}; `--format json` lists {listed}\n",
        hidden.len() + not_kept.total(),
        parts.join(", ")
    )
}

/// Whether `c` is shown escaped: control characters but tab, the
/// replacement character (invalid UTF-8), and the characters that break
/// lines or reorder text without being seen.
fn needs_escape(c: char) -> bool {
    (c.is_control() && c != '\t')
        || matches!(
            c,
            '\u{fffd}'
                | '\u{2028}'
                | '\u{2029}'
                | '\u{200e}'
                | '\u{200f}'
                | '\u{202a}'..='\u{202e}'
                | '\u{2066}'..='\u{2069}'
        )
}

/// How many characters `c` takes as shown.
fn shown_width(c: char) -> usize {
    if needs_escape(c) {
        c.escape_unicode().len()
    } else {
        1
    }
}

fn push_shown(out: &mut String, s: &str) {
    for c in s.chars() {
        if needs_escape(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
}

/// `s` with control characters, invalid UTF-8 and invisible line breaks
/// escaped as `\u{7}`.
pub fn escaped(s: &str) -> Cow<'_, str> {
    if !s.chars().any(needs_escape) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 16);
    push_shown(&mut out, s);
    Cow::Owned(out)
}

/// [`escaped`], and cut to at most about `max` characters: its start and
/// its end, with `…` between.
pub fn shortened(s: &str, max: usize) -> Cow<'_, str> {
    let mut width = 0;
    let fits = s.chars().all(|c| {
        width += shown_width(c);
        width <= max
    });
    if fits {
        return escaped(s);
    }
    let tail_width = max / 3;
    let head = byte_after_width(s, 0, max.saturating_sub(tail_width + 1));
    let tail = byte_before_width(s, s.len(), tail_width).max(head);
    let mut out = String::new();
    push_shown(&mut out, &s[..head]);
    out.push_str(ELLIPSIS);
    push_shown(&mut out, &s[tail..]);
    Cow::Owned(out)
}

/// The byte offset after the characters of `s` from `from` that take at
/// most `width` as shown.
fn byte_after_width(s: &str, from: usize, width: usize) -> usize {
    let mut used = 0;
    for (i, c) in s[from..].char_indices() {
        used += shown_width(c);
        if used > width {
            return from + i;
        }
    }
    s.len()
}

/// The byte offset before the characters of `s` up to `to` that take at
/// most `width` as shown.
fn byte_before_width(s: &str, to: usize, width: usize) -> usize {
    let mut used = 0;
    for (i, c) in s[..to].char_indices().rev() {
        used += shown_width(c);
        if used > width {
            return i + c.len_utf8();
        }
    }
    0
}

/// A string of a diagnostic as shown to people.
fn text(s: &str) -> String {
    shortened(s, MAX_TEXT).into_owned()
}

/// A label's span as ariadne places it: clamped to the file, its lines
/// (an empty span at the very end of a file that ends with a line break
/// is on the last line, as ariadne has it).
#[derive(Clone, Debug)]
struct Placed {
    span: Range<usize>,
    start_line: usize,
    end_line: usize,
}

impl Placed {
    fn new(file: &SourceFile, span: &Range<usize>) -> Self {
        let text = &file.text;
        let floor = |mut i: usize| {
            i = i.min(text.len());
            while !text.is_char_boundary(i) {
                i -= 1;
            }
            i
        };
        let start = floor(span.start);
        let end = floor(span.end).max(start);
        let mut start_line = file.line_index(start);
        if start == text.len() && start_line > 0 && file.line_range(start_line).is_empty() {
            start_line -= 1;
        }
        let end_line = if end > start {
            file.line_index(end - 1)
        } else {
            start_line
        };
        Placed {
            span: start..end,
            start_line,
            end_line,
        }
    }
}

/// Renders diagnostics of one file, giving ariadne the file itself
/// (indexed once) when its shown lines can be printed as they are, else an
/// [`Excerpt`]; within a budget of lines for the whole file.
struct Renderer<'a> {
    file: &'a SourceFile,
    name: String,
    colour: bool,
    whole: Option<Source<&'a str>>,
    /// The file has characters ariadne takes for line breaks and the
    /// lexers do not (vertical tab, form feed, …): ariadne's line numbers
    /// would be wrong, so it is always given excerpts, where they are
    /// escaped.
    odd_breaks: bool,
    budget: usize,
}

impl<'a> Renderer<'a> {
    fn new(file: &'a SourceFile, colour: bool) -> Self {
        let odd_breaks = file
            .text
            .contains(['\u{b}', '\u{c}', '\u{85}', '\u{2028}', '\u{2029}']);
        Renderer {
            file,
            name: text(&file.name),
            colour,
            whole: None,
            odd_breaks,
            budget: LINE_BUDGET,
        }
    }

    fn render(&mut self, d: &Diagnostic) -> String {
        let Some(primary) = &d.span else {
            return plain(d, &self.name, None);
        };
        let primary = Placed::new(self.file, primary);
        let secondary: Vec<Placed> = d
            .labels
            .iter()
            .take(MAX_LABELS)
            .map(|l| Placed::new(self.file, &l.span))
            .collect();
        let placed: Vec<&Placed> = std::iter::once(&primary).chain(&secondary).collect();
        let first = placed.iter().map(|p| p.start_line).min().unwrap_or(0);
        let last = placed.iter().map(|p| p.end_line).max().unwrap_or(0);
        // The whole file is indexed once for all its diagnostics unless it
        // has so many lines that excerpts up to the lines shown cost less.
        let too_many_lines = self.whole.is_none() && self.file.line_count() > self.budget / 2;
        let excerpt =
            self.odd_breaks || too_many_lines || placed.iter().any(|p| self.needs_excerpt(p));
        // ariadne walks every line from the first label to the last, and
        // indexes every line of the text it is given.
        let indexed = match (excerpt, &self.whole) {
            (true, _) => last + 1,
            (false, None) => self.file.line_count(),
            (false, Some(_)) => 0,
        };
        let cost = (last - first + 1) + indexed;
        if cost > self.budget {
            let (line, col) = self.file.line_col(primary.span.start);
            return plain(d, &self.name, Some((line, col)));
        }
        self.budget -= cost;
        if excerpt {
            let ex = Excerpt::new(self.file, &placed);
            let source = Source::from(ex.text.as_str());
            let map = |p: &Placed| ex.map_span(self.file, p);
            let spans = secondary.iter().map(map);
            let out = write_report(d, &self.name, self.colour, &source, map(&primary), spans);
            self.fix_header_column(out, &source, map(&primary).start, &primary)
        } else {
            let source = self
                .whole
                .get_or_insert_with(|| Source::from(self.file.text.as_str()));
            let spans = secondary.iter().map(|p| p.span.clone());
            let primary = primary.span.clone();
            write_report(d, &self.name, self.colour, source, primary, spans)
        }
    }

    /// Whether a label's lines cannot be printed as they are: too wide,
    /// or holding characters shown escaped.
    fn needs_excerpt(&self, p: &Placed) -> bool {
        [p.start_line, p.end_line].iter().any(|&line| {
            let content = &self.file.text[self.file.line_range(line)];
            let mut width = 0;
            content.chars().any(|c| {
                width += 1;
                needs_escape(c) || width > LONG_LINE
            })
        })
    }

    /// ariadne heads a report with `file:line:column` of the primary span
    /// in the text it was given; in an excerpt the column is that of the
    /// window, so it is put back to the file's (the line is the file's).
    fn fix_header_column(
        &self,
        out: String,
        source: &Source<&str>,
        start_in_excerpt: usize,
        primary: &Placed,
    ) -> String {
        let Some((line, idx, byte_col)) = source.get_byte_line(start_in_excerpt) else {
            return out;
        };
        let line_text = source.get_line_text(line).unwrap_or("");
        let shown_col = line_text[..byte_col.min(line_text.len())].chars().count() + 1;
        let line_start = self.file.line_range(idx).start;
        let real_col = self.file.chars_between(line_start, primary.span.start) + 1;
        if shown_col == real_col {
            return out;
        }
        let shown = format!(" {}:{}:{shown_col} ", self.name, idx + 1);
        let real = format!(" {}:{}:{real_col} ", self.name, idx + 1);
        out.split_inclusive('\n')
            .map(|l| match is_source_header(l) {
                true => Cow::Owned(l.replacen(&shown, &real, 1)),
                false => Cow::Borrowed(l),
            })
            .collect()
    }
}

/// Whether `line` of ariadne's output heads a source section
/// (`╭─[ file:line:col ]` or `├─[ … ]`), colour codes aside.
fn is_source_header(line: &str) -> bool {
    let mut rest = line.trim_start_matches(' ');
    while let Some(after) = rest.strip_prefix("\u{1b}[") {
        rest = after.split_once('m').map_or("", |(_, r)| r);
    }
    rest.starts_with(['╭', '├'])
}

/// Writes `d` with ariadne, its spans given in `source`'s bytes.
fn write_report(
    d: &Diagnostic,
    name: &str,
    colour: bool,
    source: &Source<&str>,
    primary: Range<usize>,
    secondary: impl Iterator<Item = Range<usize>>,
) -> String {
    let kind = match d.severity {
        Severity::Error => ReportKind::Error,
        Severity::Warning => ReportKind::Warning,
    };
    let (accent, muted) = match d.severity {
        Severity::Error => (Color::Red, Color::Blue),
        Severity::Warning => (Color::Yellow, Color::Blue),
    };
    let mut report = Report::build(kind, (name, primary.clone()))
        .with_config(
            Config::new()
                .with_index_type(IndexType::Byte)
                .with_color(colour),
        )
        .with_code(d.code)
        .with_message(text(&d.message));
    let order = |span: &Range<usize>| line_order(source, span);
    let mut label = Label::new((name, primary.clone()))
        .with_color(accent)
        .with_order(order(&primary));
    if let Some(msg) = &d.label {
        label = label.with_message(text(msg));
    }
    report = report.with_label(label);
    for (l, span) in d.labels.iter().zip(secondary) {
        report = report.with_label(
            Label::new((name, span.clone()))
                .with_message(text(&l.message))
                .with_color(muted)
                .with_order(order(&span)),
        );
    }
    for n in notes(d) {
        report = report.with_note(n);
    }
    if let Some(h) = &d.help {
        report = report.with_help(text(h));
    }
    let mut buf = Vec::new();
    report
        .finish()
        .write((name, source), &mut buf)
        .expect("writing to a Vec cannot fail");
    String::from_utf8_lossy(&buf).into_owned()
}

/// The line a label ends on, its order for ariadne. ariadne draws labels
/// in the order given and starts a new section, headed with the primary
/// label's place, at a label that ends on an earlier line than the one
/// before: a secondary label above the primary one would be shown under
/// the primary one's place. In the lines' order every line is in one
/// section (labels on one line keep the order given: the sort is stable).
fn line_order(source: &Source<&str>, span: &Range<usize>) -> i32 {
    let last = span.end.max(span.start + 1) - 1;
    let line = source.get_byte_line(last).map_or(0, |(_, idx, _)| idx);
    i32::try_from(line).unwrap_or(i32::MAX)
}

/// The notes shown: the diagnostic's own, one for secondary labels not
/// drawn, one for diagnostics counted and not kept.
fn notes(d: &Diagnostic) -> Vec<String> {
    let mut out: Vec<String> = d.all_notes().map(|n| text(&n)).collect();
    if d.labels.len() > MAX_LABELS {
        out.push(format!(
            "and {} more places; `--format json` lists them",
            d.labels.len() - MAX_LABELS
        ));
    }
    out
}

/// A diagnostic without a snippet: the header ariadne writes for the
/// others (`[CODE] Kind: message`), the file it is about with its place if
/// it has one (`--> file:line:col`), notes and help.
fn plain(d: &Diagnostic, name: &str, place: Option<(usize, usize)>) -> String {
    let mut out = format!(
        "[{}] {}: {}\n",
        d.code,
        severity_word(d.severity),
        text(&d.message)
    );
    match place {
        Some((line, col)) => {
            out.push_str(&format!("  --> {name}:{line}:{col}"));
            if let Some(label) = &d.label {
                out.push_str(&format!(": {}", text(label)));
            }
        }
        None => out.push_str(&format!("  --> {name}")),
    }
    out.push('\n');
    for n in notes(d) {
        out.push_str(&format!("  = note: {n}\n"));
    }
    if let Some(h) = &d.help {
        out.push_str(&format!("  = help: {}\n", text(h)));
    }
    out
}

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "Error",
        Severity::Warning => "Warning",
    }
}

/// The text ariadne is given for one diagnostic when the file will not
/// do: each line a label starts or ends on, escaped, and cut to windows
/// around the labels when it is long; every other line up to the last of
/// them empty, so that ariadne numbers lines as the file does.
struct Excerpt {
    text: String,
    lines: Vec<ExcerptLine>,
}

/// One line of the file as it is in an [`Excerpt`].
struct ExcerptLine {
    line: usize,
    /// The line's bytes in the file, without its line break.
    content: Range<usize>,
    /// The windows shown, in the file's bytes, each with where it starts
    /// in the excerpt; `…` stands for the bytes between them.
    windows: Vec<(Range<usize>, usize)>,
    /// Where the line's content ends in the excerpt.
    end: usize,
    /// 1 when a line break follows in the excerpt.
    break_len: usize,
}

impl Excerpt {
    fn new(file: &SourceFile, placed: &[&Placed]) -> Self {
        let mut shown: Vec<usize> = placed
            .iter()
            .flat_map(|p| [p.start_line, p.end_line])
            .collect();
        shown.sort_unstable();
        shown.dedup();
        let mut text = String::new();
        let mut lines = Vec::with_capacity(shown.len());
        let mut next = 0;
        for &line in &shown {
            text.extend(std::iter::repeat_n('\n', line - next));
            next = line + 1;
            let content = file.line_range(line);
            let mut windows = Vec::new();
            for (i, w) in line_windows(file, line, placed).into_iter().enumerate() {
                if i > 0 || w.start > content.start {
                    text.push_str(ELLIPSIS);
                }
                windows.push((w.clone(), text.len()));
                push_shown(&mut text, &file.text[w]);
            }
            if windows.last().is_some_and(|(w, _)| w.end < content.end) {
                text.push_str(ELLIPSIS);
            }
            let end = text.len();
            let break_len = usize::from(line + 1 < file.line_count());
            if break_len == 1 {
                text.push('\n');
            }
            lines.push(ExcerptLine {
                line,
                content,
                windows,
                end,
                break_len,
            });
        }
        Excerpt { text, lines }
    }

    /// Where a label's span is in the excerpt.
    fn map_span(&self, file: &SourceFile, p: &Placed) -> Range<usize> {
        let start = self.map(file, p.start_line, p.span.start);
        let end = if p.span.end > p.span.start {
            self.map(file, p.end_line, p.span.end)
        } else {
            start
        };
        start..end.max(start)
    }

    /// Where byte `at` of the file, on line `line` (or just past it), is
    /// in the excerpt: in a window, exactly; cut away, just after the `…`
    /// that stands for it.
    fn map(&self, file: &SourceFile, line: usize, at: usize) -> usize {
        let Ok(i) = self.lines.binary_search_by_key(&line, |l| l.line) else {
            return 0;
        };
        let l = &self.lines[i];
        if at >= l.content.end {
            return l.end + (at - l.content.end).min(l.break_len);
        }
        for (w, start) in &l.windows {
            if at < w.start {
                return *start;
            }
            if at <= w.end {
                let mut shown = String::new();
                push_shown(&mut shown, &file.text[w.start..at]);
                return start + shown.len();
            }
        }
        l.end
    }
}

/// The windows of `line` shown in an excerpt: the whole line when it is
/// not wide; else the part of each label on it that matters (its start,
/// or the end of a label that ends there), with [`CONTEXT`] characters
/// around, overlapping windows merged.
fn line_windows(file: &SourceFile, line: usize, placed: &[&Placed]) -> Vec<Range<usize>> {
    let content = file.line_range(line);
    let s = &file.text;
    let mut width = 0;
    let wide = s[content.clone()].chars().any(|c| {
        width += shown_width(c);
        width > LONG_LINE
    });
    if !wide {
        return vec![content];
    }
    let mut windows: Vec<Range<usize>> = placed
        .iter()
        .filter(|p| p.start_line == line || p.end_line == line)
        .map(|p| {
            // A span may end past the line's content (its line break, or
            // the end of the file).
            let from = p.span.start.clamp(content.start, content.end);
            let to = p.span.end.clamp(from, content.end);
            let (from, to) = if p.start_line == line {
                (from, to.min(byte_after_width(s, from, LABEL_SHOWN)))
            } else {
                (from.max(byte_before_width(s, to, LABEL_SHOWN)), to)
            };
            let from = byte_before_width(s, from, CONTEXT).max(content.start);
            let to = byte_after_width(s, to, CONTEXT).min(content.end);
            from..to
        })
        .collect();
    windows.sort_by_key(|w| w.start);
    let mut merged: Vec<Range<usize>> = Vec::with_capacity(windows.len());
    for w in windows {
        match merged.last_mut() {
            // Windows a few characters apart are one: `…` would hide
            // nothing.
            Some(m) if w.start <= byte_after_width(s, m.end, 3).min(content.end) => {
                m.end = m.end.max(w.end);
            }
            _ => merged.push(w),
        }
    }
    merged
}

/// One diagnostic as the JSON object of the CLI contract.
pub fn to_json(d: &Diagnostic, file: &SourceFile) -> Value {
    let mut sides = SideFiles::default();
    json_in(d, sides.file_of(d, file))
}

/// The side files of diagnostics, indexed once each however many
/// diagnostics they have (a view file can have one per line).
#[derive(Default)]
struct SideFiles {
    last: Option<(Arc<SideFile>, SourceFile)>,
}

impl SideFiles {
    /// The file `d`'s spans point into: its side file, or `file`.
    fn file_of<'a>(&'a mut self, d: &Diagnostic, file: &'a SourceFile) -> &'a SourceFile {
        let Some(side) = &d.side else {
            return file;
        };
        if !self
            .last
            .as_ref()
            .is_some_and(|(s, _)| Arc::ptr_eq(s, side))
        {
            let indexed = SourceFile::new(side.name.clone(), side.text.clone());
            self.last = Some((side.clone(), indexed));
        }
        self.last.as_ref().map_or(file, |(_, f)| f)
    }
}

/// [`to_json`] with `file` the file `d`'s spans point into.
fn json_in(d: &Diagnostic, file: &SourceFile) -> Value {
    let place = |s: &std::ops::Range<usize>| {
        let (line, column) = file.line_col(s.start);
        (line, column)
    };
    let (line, column, start, end) = match &d.span {
        Some(s) => {
            let (l, c) = place(s);
            (json!(l), json!(c), json!(s.start), json!(s.end))
        }
        None => (Value::Null, Value::Null, Value::Null, Value::Null),
    };
    let mut labels: Vec<Value> = Vec::new();
    if let (Some(s), Some(m)) = (&d.span, &d.label) {
        let (l, c) = place(s);
        labels.push(json!({"message": m, "line": l, "column": c, "start": s.start, "end": s.end, "primary": true}));
    }
    for lab in &d.labels {
        let (l, c) = place(&lab.span);
        labels.push(json!({"message": lab.message, "line": l, "column": c, "start": lab.span.start, "end": lab.span.end, "primary": false}));
    }
    let notes: Vec<Cow<str>> = d.all_notes().collect();
    json!({
        // Every record of `--format json` says what it is (the CLI's
        // results and errors are records on the same streams).
        "type": "diagnostic",
        "code": d.code.0,
        "severity": d.severity,
        "message": d.message,
        "file": file.name,
        "line": line,
        "column": column,
        "start": start,
        "end": end,
        "labels": labels,
        "notes": notes,
        "help": d.help,
    })
}

/// All diagnostics of one file as JSON lines (one object per line).
pub fn render_json(ds: &[Diagnostic], file: &SourceFile) -> String {
    let mut out = String::new();
    let mut sides = SideFiles::default();
    for d in ds {
        push_json_line(&mut out, &json_in(d, sides.file_of(d, file)).to_string());
    }
    out
}

/// Appends one JSON line with DEL and the C1 controls escaped too: JSON
/// lets them stand raw (serde_json escapes only U+0000–U+001F), but a
/// terminal acts on them (U+009B starts an escape sequence).
fn push_json_line(out: &mut String, json: &str) {
    for c in json.chars() {
        if c == '\u{7f}' || ('\u{80}'..='\u{9f}').contains(&c) {
            out.push_str(&format!("\\u{:04x}", c as u32));
        } else {
            out.push(c);
        }
    }
    out.push('\n');
}

#[cfg(test)]
mod tests {
    #[test]
    fn json_lines_escape_del_and_c1_controls() {
        let file = SourceFile::new("x.l", "A\u{7f}B\u{9b}C");
        let d = Diagnostic::at(codes::SYNTAX, 1..2, "unexpected `\u{7f}` before `\u{9b}`");
        let out = render_json(std::slice::from_ref(&d), &file);
        assert!(
            !out.chars()
                .any(|c| c == '\u{7f}' || ('\u{80}'..='\u{9f}').contains(&c)),
            "{out:?}"
        );
        let v: serde_json::Value = serde_json::from_str(out.trim_end()).unwrap();
        assert_eq!(v["message"], "unexpected `\u{7f}` before `\u{9b}`");
    }

    use super::*;
    use crate::diagnostics::{codes, Diagnostics};

    fn at(span: Range<usize>, message: &str) -> Diagnostic {
        Diagnostic::at(codes::SYNTAX, span, message).with_label("here")
    }

    /// The snippet line of line `n` (1-based) in a rendering.
    fn shown_line(out: &str, n: usize) -> &str {
        let margin = format!(" {n} │ ");
        let line = out
            .lines()
            .find(|l| l.trim_start().starts_with(&margin[1..]));
        line.unwrap_or_else(|| panic!("no line {n} in\n{out}"))
    }

    /// The column (in characters) where `pat` first is in `line`.
    fn char_col(line: &str, pat: impl Fn(char) -> bool) -> Option<usize> {
        line.chars().position(pat)
    }

    /// Asserts the underline of the rendering's one label starts under
    /// `shown` on snippet line `n`.
    fn assert_underlined(out: &str, n: usize, shown: &str) {
        let line = shown_line(out, n);
        let at = line.find(shown).unwrap();
        let col = line[..at].chars().count();
        let under = out.lines().find(|l| l.contains('┬')).unwrap();
        assert_eq!(char_col(under, |c| c == '─'), Some(col), "{out}");
    }

    #[test]
    fn strings_are_escaped_and_shortened_keeping_both_ends() {
        assert!(matches!(escaped("plain\ttext"), Cow::Borrowed(_)));
        assert_eq!(escaped("a\u{7}b\u{fffd}\n"), "a\\u{7}b\\u{fffd}\\u{a}");
        assert_eq!(escaped("bidi\u{202e}x"), "bidi\\u{202e}x");
        let long = format!("start{}end", "x".repeat(1000));
        let cut = shortened(&long, 60);
        assert!(
            cut.starts_with("startxx") && cut.ends_with("xxend"),
            "{cut}"
        );
        assert!(cut.contains(ELLIPSIS));
        assert!(cut.chars().count() <= 60, "{}", cut.chars().count());
        // Escapes count as wide as they are shown, and are never split.
        let controls = "\u{1}".repeat(100);
        let cut = shortened(&controls, 30);
        assert!(cut.chars().count() <= 30, "{cut}");
        assert!(
            cut.starts_with("\\u{1}\\u{1}") && cut.ends_with("\\u{1}"),
            "{cut}"
        );
        assert_eq!(shortened("short", 60), "short");
    }

    #[test]
    fn a_long_line_shows_a_window_with_the_real_line_and_column() {
        let text = format!("a\nb\n{}BAD{}\nc\n", "x".repeat(5000), "y".repeat(5000));
        let f = SourceFile::new("w.l", text.clone());
        let bad = text.find("BAD").unwrap();
        let out = render_human(&at(bad..bad + 3, "bad"), &f, false);
        assert!(out.contains("─[ w.l:3:5001 ]"), "{out}");
        let line = shown_line(&out, 3);
        assert!(line.contains(&format!(
            "…{}BAD{}…",
            "x".repeat(CONTEXT),
            "y".repeat(CONTEXT)
        )));
        assert!(out.len() < 1000, "{} bytes:\n{out}", out.len());
        assert_underlined(&out, 3, "BAD");
        // The same column in JSON.
        assert_eq!(to_json(&at(bad..bad + 3, "bad"), &f)["column"], 5001);
    }

    #[test]
    fn a_label_over_lines_shows_both_ends_cut_and_escaped() {
        let long = "x".repeat(3000);
        let text = format!("{long}START{long}\nmiddle\n{long}\u{1b}END{long}\n");
        let f = SourceFile::new("m.l", text.clone());
        let (from, to) = (text.find("START").unwrap(), text.find("END").unwrap() + 3);
        let out = render_human(&at(from..to, "over lines"), &f, false);
        assert!(out.contains("─[ m.l:1:3001 ]"), "{out}");
        let context = "x".repeat(CONTEXT);
        assert!(
            shown_line(&out, 1).contains(&format!("▶ …{context}START")),
            "{out}"
        );
        assert!(shown_line(&out, 3).contains("x\\u{1b}ENDxxxx"), "{out}");
        assert!(!out.contains("middle"), "{out}");
        // Box drawing characters take 3 bytes each.
        assert!(out.len() < 2500, "{} bytes:\n{out}", out.len());
    }

    #[test]
    fn control_characters_are_escaped_and_labels_still_point_at_them() {
        let text = "axiom: F\u{7}F\u{1b}[31m\nX";
        let f = SourceFile::new("c.l", text);
        let d = Diagnostic::at(codes::INVALID_CHARACTER, 8..9, "bad \u{7}").with_label("bell");
        let out = render_human(&d, &f, false);
        assert!(!out.chars().any(|c| c.is_control() && c != '\n'), "{out}");
        assert!(out.contains("bad \\u{7}"), "{out}");
        assert!(out.contains("─[ c.l:1:9 ]"), "{out}");
        assert_underlined(&out, 1, "\\u{7}");
    }

    #[test]
    fn lines_are_numbered_as_the_lexers_number_them() {
        // ariadne alone takes a form feed or U+2028 for a line break.
        let text = "a\u{c}b\nc\u{2028}d\nERR\n";
        let f = SourceFile::new("n.l", text);
        let err = text.find("ERR").unwrap();
        let out = render_human(&at(err..err + 3, "third line"), &f, false);
        assert!(out.contains("─[ n.l:3:1 ]"), "{out}");
        assert!(shown_line(&out, 3).contains("ERR"), "{out}");
    }

    #[test]
    fn short_clean_lines_render_as_ariadne_renders_the_file() {
        let text = "axiom: F\nF -> F\n";
        let f = SourceFile::new("s.l", text);
        let d = at(11..13, "arrow").with_secondary(0..5, "axiom");
        let ours = render_human(&d, &f, false);
        let theirs = write_report(
            &d,
            "s.l",
            false,
            &Source::from(text),
            11..13,
            std::iter::once(0..5),
        );
        assert_eq!(ours, theirs);
    }

    #[test]
    fn a_label_on_an_earlier_line_is_shown_on_its_own_line() {
        let text = "axiom: F\nangle: 3\nangle: 4\n";
        let f = SourceFile::new("d.l", text);
        let d = at(18..23, "twice").with_secondary(9..14, "first given here");
        let out = render_human(&d, &f, false);
        // One section, headed with the primary place, showing line 2 then
        // line 3; no second header that puts line 2 under line 3's place.
        assert_eq!(out.matches("d.l:").count(), 1, "{out}");
        assert!(out.contains("─[ d.l:3:1 ]"), "{out}");
        let two = out.find(shown_line(&out, 2)).unwrap();
        let three = out.find(shown_line(&out, 3)).unwrap();
        assert!(two < three, "{out}");
    }

    #[test]
    fn a_diagnostic_without_a_place_names_its_file() {
        let f = SourceFile::new("whole.l", "x\n");
        let d = Diagnostic::global(codes::SYNTAX, "about the whole file");
        let out = render_human(&d, &f, false);
        assert_eq!(out, "[E0003] Error: about the whole file\n  --> whole.l\n");
    }

    #[test]
    fn a_side_file_diagnostic_is_shown_and_listed_as_that_files() {
        let f = SourceFile::new("dir/plant.l", "axiom: F\n");
        let side = std::sync::Arc::new(crate::diagnostics::SideFile {
            name: "dir/plant.v".into(),
            text: "angle: 8\nbad: 3\n".into(),
        });
        let d = Diagnostic::at(codes::SYNTAX, 9..12, "unknown").in_side_file(side);
        let out = render_human(&d.clone().with_label("here"), &f, false);
        assert!(out.contains("─[ dir/plant.v:2:1 ]"), "{out}");
        assert!(shown_line(&out, 2).contains("bad: 3"), "{out}");
        let v = to_json(&d, &f);
        assert_eq!(
            (v["file"].as_str(), v["line"].as_u64()),
            (Some("dir/plant.v"), Some(2))
        );
    }

    #[test]
    fn the_last_line_counts_what_is_not_shown_by_code() {
        let f = SourceFile::new("many.l", "x\n");
        let mut ds: Vec<Diagnostic> = (0..30).map(|_| at(0..1, "syntax")).collect();
        ds.extend((0..5).map(|_| Diagnostic::at(codes::INVALID_CHARACTER, 0..1, "char")));
        let out = render_all(&ds, &f, false);
        assert_eq!(out.matches("[E0003]").count(), MAX_SHOWN);
        let last = out.lines().last().unwrap();
        assert_eq!(
            last,
            "... and 15 more diagnostics not shown: 10 E0003 (unexpected token), \
             5 E0001 (invalid character); `--format json` lists them all"
        );
        // Diagnostics counted and not kept are counted here too.
        let mut list = Diagnostics::default();
        for _ in 0..crate::diagnostics::MAX_KEPT + 7 {
            list.push(at(0..1, "syntax"));
        }
        let last = list.render(&f, false).lines().last().unwrap().to_string();
        assert!(
            last.contains("7 more found and not kept (7 errors)"),
            "{last}"
        );
        assert!(last.ends_with("lists the 100000 kept"), "{last}");
    }

    #[test]
    fn past_the_line_budget_a_diagnostic_keeps_its_place_without_a_snippet() {
        let text = format!("START\n{}END\n", "\n".repeat(LINE_BUDGET));
        let f = SourceFile::new("b.l", text.clone());
        let d = at(0..text.len() - 1, "the whole file");
        let t = std::time::Instant::now();
        let out = render_human(&d, &f, false);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
        assert_eq!(
            out, "[E0003] Error: the whole file\n  --> b.l:1:1: here\n",
            "{out}"
        );
    }
}
