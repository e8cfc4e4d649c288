//! Rendering diagnostics: ariadne for people, JSON for tools. The only code
//! in graftal that knows ariadne.

use super::{Diagnostic, Severity};
use crate::source::SourceFile;
use ariadne::{Color, Config, IndexType, Label, Report, ReportKind, Source};
use serde_json::{json, Value};

/// Renders one diagnostic for a person; `colour` only on a terminal.
pub fn render_human(d: &Diagnostic, file: &SourceFile, colour: bool) -> String {
    render_all(std::slice::from_ref(d), file, colour)
}

/// At most this many diagnostics are rendered for people; the rest are
/// counted in a last line (JSON output has them all).
pub const MAX_SHOWN: usize = 200;

/// Renders diagnostics of one file for a person, the file's line index
/// built once for all of them.
pub fn render_all(ds: &[Diagnostic], file: &SourceFile, colour: bool) -> String {
    let source = Source::from(file.text.as_str());
    let mut out = String::new();
    for d in ds.iter().take(MAX_SHOWN) {
        out.push_str(&render_one(d, file, &source, colour));
    }
    if ds.len() > MAX_SHOWN {
        let errors = ds[MAX_SHOWN..].iter().filter(|d| d.is_error()).count();
        out.push_str(&format!(
            "... and {} more diagnostics ({errors} errors) not shown; `--format json` lists them all\n",
            ds.len() - MAX_SHOWN
        ));
    }
    out
}

fn render_one(d: &Diagnostic, file: &SourceFile, source: &Source<&str>, colour: bool) -> String {
    let kind = match d.severity {
        Severity::Error => ReportKind::Error,
        Severity::Warning => ReportKind::Warning,
    };
    let (accent, muted) = match d.severity {
        Severity::Error => (Color::Red, Color::Blue),
        Severity::Warning => (Color::Yellow, Color::Blue),
    };
    let name = file.name.as_str();
    let len = file.text.len();
    let clamp = |s: &std::ops::Range<usize>| s.start.min(len)..s.end.min(len).max(s.start.min(len));
    let Some(span) = d.span.as_ref().map(clamp) else {
        // No place in the file: a plain header line, notes and help.
        let mut out = format!("{}[{}]: {}\n", severity_word(d.severity), d.code, d.message);
        for n in &d.notes {
            out.push_str(&format!("  = note: {n}\n"));
        }
        if let Some(h) = &d.help {
            out.push_str(&format!("  = help: {h}\n"));
        }
        return out;
    };
    let mut report = Report::build(kind, (name, span.clone()))
        .with_config(
            Config::new()
                .with_index_type(IndexType::Byte)
                .with_color(colour),
        )
        .with_code(d.code)
        .with_message(&d.message);
    let mut primary = Label::new((name, span)).with_color(accent);
    if let Some(msg) = &d.label {
        primary = primary.with_message(msg);
    }
    report = report.with_label(primary);
    for l in &d.labels {
        report = report.with_label(
            Label::new((name, clamp(&l.span)))
                .with_message(&l.message)
                .with_color(muted),
        );
    }
    for n in &d.notes {
        report = report.with_note(n);
    }
    if let Some(h) = &d.help {
        report = report.with_help(h);
    }
    let mut buf = Vec::new();
    report
        .finish()
        .write((name, source.clone()), &mut buf)
        .expect("writing to a Vec cannot fail");
    String::from_utf8_lossy(&buf).into_owned()
}

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "Error",
        Severity::Warning => "Warning",
    }
}

/// One diagnostic as the JSON object of the CLI contract.
pub fn to_json(d: &Diagnostic, file: &SourceFile) -> Value {
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
    json!({
        "code": d.code.0,
        "severity": d.severity,
        "message": d.message,
        "file": file.name,
        "line": line,
        "column": column,
        "start": start,
        "end": end,
        "labels": labels,
        "notes": d.notes,
        "help": d.help,
    })
}

/// All diagnostics of one file as JSON lines (one object per line).
pub fn render_json(ds: &[Diagnostic], file: &SourceFile) -> String {
    let mut out = String::new();
    for d in ds {
        out.push_str(&to_json(d, file).to_string());
        out.push('\n');
    }
    out
}
