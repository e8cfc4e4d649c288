//! Stale words: what the docs say about the registries, read from the docs
//! and held against the registries, so that adding a notation, an emitter or
//! a diagnostic code without the words that go with it fails here.
//!
//! * The docs (the README, `docs/`, the standard library's `INDEX.md`
//!   files, `grammar/` and the doc comments of `src/`) name notations in
//!   lists: two or more names (`pfg`, `LinF`, `.gft`, …) joined by `|`,
//!   `,`, `or`, `and`. A list after `--notation` is every notation graftal
//!   reads ([`FRONTS`]); after `--to`, every one it writes ([`BACKS`]);
//!   after `.l`, every front end claiming `.l`; any other list of five or
//!   more is one of the two registries (shorter ones say what holds for
//!   some notations; a list ending in `none` is the turtle sets of `.gft`,
//!   which are not a registry of notations). "N emitters" and "N front
//!   ends" count the registries.
//! * The README's editor settings list every extension a front end claims.
//! * Every code in the registry of diagnostic codes is emitted somewhere in
//!   `src/`: its constant, or its text as a literal, occurs outside the
//!   registry's tables and outside test modules. Nothing outside the tables
//!   makes a `Code` of its own, so a code has no other way to be given.

use graftal::back::BACKS;
use graftal::diagnostics::codes;
use graftal::front::FRONTS;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` (recursively) whose name ends with `suffix`.
fn files_under(dir: &Path, suffix: &str, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files_under(&p, suffix, out);
        } else if p.to_string_lossy().ends_with(suffix) {
            out.push(p);
        }
    }
}

/// A document: its path (relative to the repository) and its prose, one
/// entry per line of the file so that line numbers hold.
struct Doc {
    path: String,
    lines: Vec<String>,
}

/// The prose of a Rust file: its doc comments; every other line is a
/// break (`;`), so that no list runs from one comment into the next.
fn doc_comments(src: &str) -> Vec<String> {
    src.lines()
        .map(|l| {
            let t = l.trim_start();
            match t.strip_prefix("//!").or_else(|| t.strip_prefix("///")) {
                Some(doc) => doc.to_string(),
                None => ";".to_string(),
            }
        })
        .collect()
}

/// The README, `docs/*.md`, the stdlib's `INDEX.md` files, `grammar/*`
/// and the doc comments under `src/`.
fn docs() -> Vec<Doc> {
    let root = root();
    let mut prose = vec![root.join("README.md")];
    files_under(&root.join("docs"), ".md", &mut prose);
    files_under(&root.join("stdlib"), "INDEX.md", &mut prose);
    files_under(&root.join("grammar"), "", &mut prose);
    let mut rust = Vec::new();
    files_under(&root.join("src"), ".rs", &mut rust);
    let read = |p: &Path| std::fs::read_to_string(p).unwrap();
    let relative = |p: &Path| {
        p.strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .into_owned()
    };
    let mut all: Vec<Doc> = prose
        .iter()
        .map(|p| Doc {
            path: relative(p),
            lines: read(p).lines().map(str::to_string).collect(),
        })
        .collect();
    all.extend(rust.iter().map(|p| Doc {
        path: relative(p),
        lines: doc_comments(&read(p)),
    }));
    all.sort_by(|a, b| a.path.cmp(&b.path));
    all
}

/// A token of prose: a word (letters, digits, `.`, `-`, `_`; a leading or
/// trailing `.` dropped), a separator of a list (`|` or `,`), or a break
/// (any other mark but quotes, backquotes and parentheses, which lists
/// stand inside).
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Word(String),
    Separator,
    Break,
}

/// Whether a line is one of the README's editor settings, a list of
/// extensions (`"l", "linf"`) that [`readme_extensions`] checks.
fn is_editor_setting(line: &str) -> bool {
    line.starts_with("file-types = [") || line.contains("\"*.")
}

/// The tokens of a document, each with its line (from 1): a list or a
/// count may run from one line to the next.
fn tokens(doc: &Doc) -> Vec<(usize, Token)> {
    let mut out = Vec::new();
    let is_word = |c: char| c.is_alphanumeric() || matches!(c, '.' | '-' | '_');
    for (k, line) in doc.lines.iter().enumerate() {
        if is_editor_setting(line) {
            out.push((k + 1, Token::Break));
            continue;
        }
        let mut word = String::new();
        for c in line.chars().chain([' ']) {
            if is_word(c) {
                word.push(c);
                continue;
            }
            let w = word.trim_matches('.');
            if !w.is_empty() {
                out.push((k + 1, Token::Word(w.to_string())));
            }
            word.clear();
            match c {
                '|' | ',' => out.push((k + 1, Token::Separator)),
                c if c.is_whitespace() || matches!(c, '`' | '"' | '(' | ')' | '[' | ']') => {}
                _ => out.push((k + 1, Token::Break)),
            }
        }
    }
    out
}

/// The notation a word names: a front end's name or title, any case
/// (`pfg`, `LinF`, `gft`); graftal's own title is the program's name, which
/// prose uses for the program, so `.gft` is named by its name alone.
fn notation(word: &str) -> Option<&'static str> {
    FRONTS
        .iter()
        .find(|f| {
            word.eq_ignore_ascii_case(f.name())
                || (f.title() != "graftal" && word.eq_ignore_ascii_case(f.title()))
        })
        .map(|f| f.name())
}

/// A list of notations: the line it starts on, its names, whether `none`
/// ends it, and the two words before it (nearest first).
struct List {
    line: usize,
    names: Vec<&'static str>,
    ends_in_none: bool,
    before: [String; 2],
}

fn is_joiner(t: &Token) -> bool {
    match t {
        Token::Separator => true,
        Token::Word(w) => w == "or" || w == "and",
        Token::Break => false,
    }
}

/// The lists of two or more notation names in `tokens`.
fn lists(tokens: &[(usize, Token)]) -> Vec<List> {
    let line = |k: usize| tokens[k].0;
    let tokens: Vec<&Token> = tokens.iter().map(|(_, t)| t).collect();
    let word = |t: &Token| match t {
        Token::Word(w) => Some(w.clone()),
        _ => None,
    };
    let name = |t: &Token| word(t).and_then(|w| notation(&w));
    let mut out = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let Some(first) = name(tokens[i]) else {
            i += 1;
            continue;
        };
        let mut names = vec![first];
        let mut ends_in_none = false;
        let mut k = i + 1;
        loop {
            let mut m = k;
            while m < tokens.len() && is_joiner(tokens[m]) {
                m += 1;
            }
            match tokens.get(m).copied() {
                Some(t) if m > k && name(t).is_some() => {
                    names.extend(name(t));
                    k = m + 1;
                }
                Some(t) if m > k && word(t).as_deref() == Some("none") => {
                    ends_in_none = true;
                    break;
                }
                _ => break,
            }
        }
        if names.len() > 1 {
            let mut before = tokens[..i].iter().rev().filter_map(|t| word(t));
            let before = [(); 2].map(|_| before.next().unwrap_or_default());
            out.push(List {
                line: line(i),
                names,
                ends_in_none,
                before,
            });
        }
        i = k;
    }
    out
}

/// The names of every front end, of every emitter, and of the front ends
/// claiming `.l`.
struct Registries {
    fronts: BTreeSet<&'static str>,
    backs: BTreeSet<&'static str>,
    dot_l: BTreeSet<&'static str>,
}

fn registries() -> Registries {
    Registries {
        fronts: FRONTS.iter().map(|f| f.name()).collect(),
        backs: BACKS.iter().map(|b| b.name()).collect(),
        dot_l: FRONTS
            .iter()
            .filter(|f| f.extensions().contains(&"l"))
            .map(|f| f.name())
            .collect(),
    }
}

/// What is wrong with a list, if anything.
fn wrong_list(list: &List, r: &Registries) -> Option<String> {
    let names: BTreeSet<&str> = list.names.iter().copied().collect();
    let [one, two] = [list.before[0].as_str(), list.before[1].as_str()];
    let (expected, what) = if one == "--notation" {
        (&r.fronts, "the notations graftal reads (FRONTS)")
    } else if one == "--to" {
        (&r.backs, "the notations graftal writes (BACKS)")
    } else if one == "l" || (one == "is" && two == "l") {
        (&r.dot_l, "the front ends claiming `.l`")
    } else if list.ends_in_none || names.len() < 5 || names == r.fronts || names == r.backs {
        return None;
    } else {
        return Some(format!(
            "{:?} is neither FRONTS {:?} nor BACKS {:?}",
            list.names, r.fronts, r.backs
        ));
    };
    (names != *expected)
        .then(|| format!("{:?} after `{one}` is not {what}: {expected:?}", list.names))
}

/// The number a word spells, for counts of a few.
fn number(word: &str) -> Option<usize> {
    const WORDS: [&str; 13] = [
        "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    let w = word.to_ascii_lowercase();
    WORDS
        .iter()
        .position(|n| *n == w)
        .or_else(|| w.parse().ok())
}

/// What is wrong with the counts ("three emitters"), with their lines.
fn wrong_counts(tokens: &[(usize, Token)]) -> Vec<(usize, String)> {
    let words: Vec<&str> = tokens
        .iter()
        .map(|(_, t)| match t {
            Token::Word(w) => w.as_str(),
            _ => ";",
        })
        .collect();
    let mut out = Vec::new();
    for (k, w) in words.iter().enumerate() {
        let Some(n) = number(w) else { continue };
        let (counted, actual) = match (words.get(k + 1), words.get(k + 2)) {
            (Some(&"emitters"), _) => ("emitters", BACKS.len()),
            (Some(&"front"), Some(&"ends")) => ("front ends", FRONTS.len()),
            _ => continue,
        };
        if n != actual {
            let what = format!("\"{w} {counted}\": there are {actual}");
            out.push((tokens[k].0, what));
        }
    }
    out
}

/// Every stale list or count in `doc`, as `path:line: what`.
fn stale_in(doc: &Doc, r: &Registries) -> Vec<String> {
    let t = tokens(doc);
    let lists = lists(&t);
    let wrong = lists
        .iter()
        .filter_map(|l| Some((l.line, wrong_list(l, r)?)));
    let mut found: Vec<(usize, String)> = wrong.chain(wrong_counts(&t)).collect();
    found.sort();
    found
        .into_iter()
        .map(|(line, what)| format!("{}:{line}: {what}", doc.path))
        .collect()
}

#[test]
fn the_docs_lists_of_notations_are_the_registries() {
    let r = registries();
    let stale: Vec<String> = docs().iter().flat_map(|d| stale_in(d, &r)).collect();
    assert!(
        stale.is_empty(),
        "stale lists of notations:\n{}",
        stale.join("\n")
    );
}

#[test]
fn the_checker_sees_each_kind_of_stale_list() {
    let r = registries();
    let doc = |text: &str| Doc {
        path: "sample".into(),
        lines: vec![text.to_string()],
    };
    for stale in [
        "`--notation pfg|linf|stl|cpfg|fractint` overrides both",
        "`graftal translate FILE --to pfg|linf|stl` writes it",
        "for `.l` (pfg, cpfg, Fractint, Smith) from the content",
        "`.l` is pfg and cpfg",
        "every front end (pfg, LinF, STL, cpfg, Fractint) lowers its AST",
        "The three emitters walk a system alike",
        "all nine front ends",
    ] {
        assert_eq!(
            stale_in(&doc(stale), &r).len(),
            1,
            "not seen as stale: {stale}"
        );
    }
    let fronts: Vec<&str> = FRONTS.iter().map(|f| f.name()).collect();
    let backs: Vec<&str> = BACKS.iter().map(|b| b.name()).collect();
    for fresh in [
        format!("`--notation {}`", fronts.join("|")),
        format!("--to {} [-o OUT]", backs.join("|")),
        format!("every front end ({})", fronts.join(", ")),
        format!("The {} emitters", BACKS.len()),
        "render --to png|svg, pfg or LinF from STL, `turtle pfg|linf|stl|cpfg|fractint|none`"
            .into(),
        "first in file order (pfg, LinF, Fractint, STL, a cpfg system without `seed:`)".into(),
        "file-types = [\"l\", \"linf\", \"stl\", \"gft\"]".into(),
    ] {
        assert_eq!(stale_in(&doc(&fresh), &r), Vec::<String>::new(), "{fresh}");
    }
}

/// The extensions between the brackets of the README's Helix
/// `file-types = [...]` line, and those of its VS Code `"*.EXT": "graftal"`
/// associations.
fn readme_extensions() -> [BTreeSet<String>; 2] {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let helix = readme
        .lines()
        .find_map(|l| l.strip_prefix("file-types = ["))
        .expect("the README's Helix settings name the file types");
    let helix = helix.trim_end_matches(']').split(',');
    let helix = helix
        .map(|e| e.trim().trim_matches('"').to_string())
        .collect();
    let vscode = readme
        .split("\"*.")
        .skip(1)
        .filter_map(|rest| {
            rest.split_once("\": \"graftal\"")
                .map(|(ext, _)| ext.to_string())
        })
        .collect();
    [helix, vscode]
}

#[test]
fn the_readme_editor_settings_claim_every_extension() {
    let claimed: BTreeSet<String> = FRONTS
        .iter()
        .flat_map(|f| f.extensions().iter().map(|e| e.to_string()))
        .collect();
    let [helix, vscode] = readme_extensions();
    assert_eq!(helix, claimed, "Helix's file-types");
    assert_eq!(vscode, claimed, "VS Code's files.associations");
}

/// A source file under `src/` without comments and without its test module
/// (by the house convention the last item of a file); for the registry's
/// own files, without the `codes! { … }` tables.
fn emitting_code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.split("#[cfg(test)]").next().unwrap_or_default();
    let mut out = String::new();
    let mut in_table = false;
    for line in text.lines() {
        if line.starts_with("codes! {") {
            in_table = true;
        } else if in_table {
            in_table = line != "}";
        } else {
            let code = line.split("//").next().unwrap_or_default();
            out.push_str(code);
            out.push('\n');
        }
    }
    out
}

/// The constants the registry declares (`NAME = "E0004", …`) with their
/// codes, read from the tables under `src/diagnostics/codes/`.
fn declared_codes() -> Vec<(String, String)> {
    let mut tables = Vec::new();
    files_under(&root().join("src/diagnostics/codes"), ".rs", &mut tables);
    let mut out = Vec::new();
    for table in tables {
        for line in std::fs::read_to_string(table).unwrap().lines() {
            let Some((name, rest)) = line.trim().split_once(" = \"") else {
                continue;
            };
            let code = rest.split('"').next().unwrap_or_default();
            if name
                .chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
            {
                out.push((name.to_string(), code.to_string()));
            }
        }
    }
    out
}

/// Whether `code` names the identifier `name` (not as part of a longer one).
fn names_identifier(code: &str, name: &str) -> bool {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    code.match_indices(name).any(|(at, _)| {
        let before = code[..at].chars().next_back();
        let after = code[at + name.len()..].chars().next();
        !before.is_some_and(is_ident) && !after.is_some_and(is_ident)
    })
}

#[test]
fn every_registered_code_is_emitted_somewhere() {
    let declared = declared_codes();
    let registered: BTreeSet<&str> = codes::all().map(|c| c.code.0).collect();
    let read: BTreeSet<&str> = declared.iter().map(|(_, c)| c.as_str()).collect();
    assert_eq!(read, registered, "the tables as read here are the registry");
    let mut sources = Vec::new();
    files_under(&root().join("src"), ".rs", &mut sources);
    let code: Vec<(String, String)> = sources
        .iter()
        .map(|p| (p.to_string_lossy().replace('\\', "/"), emitting_code(p)))
        .collect();
    for (path, text) in &code {
        if !path.contains("src/diagnostics/codes/") {
            let made = text
                .match_indices("Code(")
                .any(|(at, _)| !text[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_'));
            assert!(!made, "{path} makes a Code of its own");
        }
    }
    let silent: Vec<String> = declared
        .iter()
        .filter(|(name, literal)| {
            !code.iter().any(|(_, text)| {
                names_identifier(text, name) || text.contains(&format!("\"{literal}\""))
            })
        })
        .map(|(name, literal)| format!("{literal} ({name})"))
        .collect();
    assert!(
        silent.is_empty(),
        "codes that nothing in src/ emits (retire them: codes::RETIRED): {}",
        silent.join(", ")
    );
}
