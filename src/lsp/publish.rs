//! graftal's diagnostics as the protocol's: what `graftal check` reports
//! of a file, each in the file its spans point into (the document, or a
//! cpfg side file read beside it).

use super::position::range;
use super::uri;
use crate::diagnostics::{Diagnostic, Severity};
use crate::source::SourceFile;
use lsp_types::{
    DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Position, Uri,
};
use std::collections::BTreeMap;

/// The most diagnostics published for one file: an editor shows no more
/// usefully, and ten thousand take the client longer to read than a
/// keystroke may (`check` shows 20 and counts the rest).
pub const MAX_PUBLISHED: usize = 1000;

/// The protocol diagnostics of `ds`, reported on `file` (at `file_uri`),
/// grouped by the URI of the file each points into: the document's own
/// first (present even when empty, so that fixed problems are cleared).
pub fn by_file(
    ds: &[Diagnostic],
    file: &SourceFile,
    file_uri: &Uri,
) -> Vec<(Uri, Vec<lsp_types::Diagnostic>)> {
    let mut own = Vec::new();
    let mut sides: BTreeMap<String, (Uri, SourceFile, Vec<lsp_types::Diagnostic>)> =
        BTreeMap::new();
    let mut unshown = 0;
    for d in ds {
        if d.side.is_none() && own.len() == MAX_PUBLISHED {
            // Not converted: the conversion of ten thousand took longer
            // than a keystroke may.
            unshown += 1;
            continue;
        }
        let side = d.side.as_ref().and_then(|s| {
            let uri = uri::from_path(&s.name)?;
            Some((s, uri))
        });
        match side {
            Some((s, side_uri)) => {
                let entry = sides.entry(s.name.clone()).or_insert_with(|| {
                    let f = SourceFile::new(s.name.clone(), s.text.clone());
                    (side_uri, f, Vec::new())
                });
                let converted = convert(d, &entry.1, &entry.0);
                entry.2.push(converted);
            }
            // A side file without a path to name is reported on the document.
            None if d.side.is_some() => own.push(convert_placeless(d)),
            None => own.push(convert(d, file, file_uri)),
        }
    }
    if unshown > 0 {
        let more = unshown;
        own.push(lsp_types::Diagnostic {
            severity: Some(DiagnosticSeverity::INFORMATION),
            source: Some("graftal".to_string()),
            message: format!(
                "… and {more} more diagnostics not shown; `graftal check --format json` lists them all"
            ),
            ..Default::default()
        });
    }
    let mut out = vec![(file_uri.clone(), own)];
    out.extend(sides.into_values().map(|(u, _, v)| (u, v)));
    out
}

/// One diagnostic, its spans in `file` (at `file_uri`).
pub fn convert(d: &Diagnostic, file: &SourceFile, file_uri: &Uri) -> lsp_types::Diagnostic {
    let mut out = convert_placeless(d);
    if let Some(span) = &d.span {
        out.range = range(file, span);
    }
    let related: Vec<_> = d
        .labels
        .iter()
        .map(|l| DiagnosticRelatedInformation {
            location: Location::new(file_uri.clone(), range(file, &l.span)),
            message: l.message.clone(),
        })
        .collect();
    out.related_information = (!related.is_empty()).then_some(related);
    out
}

/// One diagnostic at the start of its file, without related places.
fn convert_placeless(d: &Diagnostic) -> lsp_types::Diagnostic {
    let start = Position::new(0, 0);
    lsp_types::Diagnostic {
        range: lsp_types::Range::new(start, start),
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
        }),
        code: Some(NumberOrString::String(d.code.0.to_string())),
        source: Some("graftal".to_string()),
        message: message(d),
        ..Default::default()
    }
}

/// The message, then what `check` shows around it (the label, notes, help)
/// and the code's title as `graftal explain` gives it.
fn message(d: &Diagnostic) -> String {
    let mut text = d.message.clone();
    if let Some(label) = &d.label {
        text.push_str(&format!(" ({label})"));
    }
    for note in d.all_notes() {
        text.push_str(&format!("\nnote: {note}"));
    }
    if let Some(help) = &d.help {
        text.push_str(&format!("\nhelp: {help}"));
    }
    let info = d.code.info();
    text.push_str(&format!(
        "\n{}: {} (`graftal explain {}`)",
        info.code, info.title, info.code
    ));
    text
}
