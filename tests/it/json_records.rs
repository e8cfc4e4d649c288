//! The `--format json` contract: every line a command writes, on stdout
//! and on stderr, is one JSON object whose `type` names a record the
//! README's table lists, on the stream the table gives it, with the fields
//! the table gives it (those after its `;` only sometimes). Each record
//! type is seen at least once.

use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};

use crate::common::{graftal, temp};

/// A record type as the README documents it.
struct Documented {
    stream: String,
    fields: BTreeSet<String>,
    sometimes: BTreeSet<String>,
}

/// The backquoted words of `text`.
fn quoted(text: &str) -> BTreeSet<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(String::from)
        .collect()
}

/// The README's table of records, by type.
fn documented() -> BTreeMap<String, Documented> {
    let readme = include_str!("../../README.md");
    let header = "| `type` | stream | written by | fields |";
    let at = readme
        .find(header)
        .expect("the README's table of JSON records");
    let rows = readme[at..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'));
    rows.map(|row| {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (always, sometimes) = cells[4].split_once(';').unwrap_or((cells[4], ""));
        let kind = cells[1].trim_matches('`').to_string();
        let doc = Documented {
            stream: cells[2].to_string(),
            fields: quoted(always),
            sometimes: quoted(sometimes),
        };
        (kind, doc)
    })
    .collect()
}

/// Checks each line of `text`, written to `stream` by `graftal ARGS`, as a
/// documented record; the types seen.
fn check_records(
    args: &[&str],
    stream: &str,
    text: &str,
    table: &BTreeMap<String, Documented>,
) -> Vec<String> {
    let mut seen = Vec::new();
    for line in text.lines() {
        let record: Value = serde_json::from_str(line)
            .unwrap_or_else(|e| panic!("{args:?} {stream}: not JSON ({e}): {line}"));
        let kind = record["type"]
            .as_str()
            .unwrap_or_else(|| panic!("{args:?} {stream}: no `type`: {line}"));
        let doc = (table.get(kind))
            .unwrap_or_else(|| panic!("{args:?}: `{kind}` is not in the README's table"));
        assert_eq!(doc.stream, stream, "{args:?}: where `{kind}` is written");
        let fields: BTreeSet<String> = (record.as_object().unwrap().keys())
            .filter(|k| *k != "type")
            .cloned()
            .collect();
        let missing: Vec<_> = doc.fields.difference(&fields).collect();
        assert!(
            missing.is_empty(),
            "{args:?}: `{kind}` lacks {missing:?}: {line}"
        );
        let allowed: BTreeSet<String> = doc.fields.union(&doc.sometimes).cloned().collect();
        let extra: Vec<_> = fields.difference(&allowed).collect();
        assert!(
            extra.is_empty(),
            "{args:?}: `{kind}` has undocumented {extra:?}"
        );
        seen.push(kind.to_string());
    }
    seen
}

/// A command line, its exit status, and the types of the records it
/// writes on stdout and on stderr, in order (each once or more).
type Run<'a> = (&'a [&'a str], i32, &'a [&'a str], &'a [&'a str]);

#[test]
fn every_json_line_of_every_command_is_a_documented_record() {
    let table = documented();
    assert!(table.len() >= 7, "{:?}", table.keys());
    let bad = temp("bad.l");
    std::fs::write(&bad, "angle factor: 0\naxiom: F[\nF -> F+F\n").unwrap();
    let bad = bad.to_str().unwrap();
    let mesh = temp("koch.obj");
    let mesh = mesh.to_str().unwrap();
    let unwritable = "/no/such/folder/koch.svg";
    let runs: [Run; 9] = [
        (
            &["check", bad, "/no/such/file.l"],
            2,
            &["files"],
            &["diagnostic", "error"],
        ),
        (&["check", "std:algae"], 0, &["files"], &[]),
        (&["derive", bad], 1, &[], &["diagnostic"]),
        (&["stats", "std:koch-island", "-n", "1"], 0, &["stats"], &[]),
        (
            &["render", "std:koch-island", "-n", "1", "-o", mesh],
            0,
            &["mesh"],
            &[],
        ),
        (
            &["render", "std:koch-island", "-o", unwritable],
            2,
            &[],
            &["error"],
        ),
        (
            &["translate", "std:koch-island", "--to", "linf"],
            0,
            &["translation"],
            &[],
        ),
        (&["translate", bad, "--to", "linf"], 1, &[], &["diagnostic"]),
        (&["list"], 0, &["stdlib"], &[]),
    ];
    let mut all = BTreeSet::new();
    for (args, status, out, err) in runs {
        let mut argv = args.to_vec();
        argv.extend(["--format", "json"]);
        let o = graftal(&argv);
        assert_eq!(o.status, status, "{argv:?}: {}", o.stderr);
        for (stream, text, expected) in [("stdout", &o.stdout, out), ("stderr", &o.stderr, err)] {
            let mut seen = check_records(&argv, stream, text, &table);
            all.extend(seen.iter().cloned());
            seen.dedup();
            assert_eq!(seen, expected, "{argv:?}: the records on {stream}");
        }
    }
    let documented: BTreeSet<String> = table.keys().cloned().collect();
    assert_eq!(all, documented, "every documented record is written");
}
