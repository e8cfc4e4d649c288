//! Keeps each `grammar/*.ebnf` true to its front end.
//!
//! A grammar file is read as ISO EBNF (comments, terminals, special
//! sequences, rules) and checked for internal consistency; its keywords are
//! compared with the front end's; the codes of its constraint section with
//! the diagnostics registry; and every example and counterexample it holds
//! is compiled with `graftal::driver::compile` as a file of its notation.
//! See the top of `grammar/pfg.ebnf` for the format of the examples.

use graftal::diagnostics::codes;
use graftal::driver::{compile_entry, Compiled};
use graftal::front::linf::lexer::BlockKind;
use graftal::front::pfg::parser::HEADERS;
use graftal::source::SourceFile;
use std::collections::{BTreeMap, BTreeSet};

const MIN_EXAMPLES: usize = 15;
const MIN_COUNTEREXAMPLES: usize = 12;

/// A grammar file and the extension of the files it describes.
struct Grammar {
    file: &'static str,
    ext: &'static str,
    /// Rules every such grammar must define.
    starts: &'static [&'static str],
    /// The code range of the notation's own diagnostics (`"04"` for
    /// E04xx/W04xx), every one of which the grammar must name.
    range: Option<&'static str>,
}

const GRAMMARS: [Grammar; 7] = [
    Grammar {
        file: "pfg.ebnf",
        ext: "l",
        starts: &["file", "source text", "header", "production"],
        range: None,
    },
    Grammar {
        file: "linf.ebnf",
        ext: "linf",
        starts: &["file", "block", "string", "expression", "interval"],
        range: Some("04"),
    },
    Grammar {
        file: "stl.ebnf",
        ext: "stl",
        starts: &["file", "source text", "string", "entries", "shape"],
        range: Some("05"),
    },
    Grammar {
        file: "fractint.ebnf",
        ext: "l",
        starts: &["file", "entry", "entry line", "string", "command"],
        range: Some("07"),
    },
    Grammar {
        file: "smith.ebnf",
        ext: "smith",
        starts: &["file", "entry", "rule string", "image", "axiom"],
        range: Some("097"),
    },
    Grammar {
        file: "ifs.ebnf",
        ext: "ifs",
        starts: &["file", "entry", "map line", "map 2d", "map 3d", "number"],
        range: Some("11"),
    },
    Grammar {
        file: "graftal.ebnf",
        ext: "gft",
        starts: &["file", "item", "word", "production", "expression"],
        range: Some("090"),
    },
];

fn grammar_text(file: &str) -> String {
    let path = format!("{}/grammar/{file}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {path}: {e}"))
}

// ---------------------------------------------------------------------------
// ISO EBNF, as much of it as the grammar uses.

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    /// A meta-identifier, inner whitespace collapsed to one space.
    Ident(String),
    /// A terminal string, without its quotes.
    Term(String),
    /// A special sequence `? … ?`, without the question marks.
    Special(String),
    /// One of `= , | ; - [ ] { } ( )`.
    Op(char),
}

/// 1-based line of byte offset `at`.
fn line_of(src: &str, at: usize) -> usize {
    src[..at].matches('\n').count() + 1
}

/// Tokenises ISO EBNF, skipping (nested) comments.
fn lex_ebnf(src: &str) -> Result<Vec<Tok>, String> {
    let chars: Vec<(usize, char)> = src.char_indices().collect();
    let at = |i: usize| chars.get(i).map(|&(_, c)| c);
    let pos = |i: usize| chars.get(i).map_or(src.len(), |&(p, _)| p);
    let mut toks = Vec::new();
    let mut i = 0;
    while let Some(c) = at(i) {
        if c.is_whitespace() {
            i += 1;
        } else if c == '(' && at(i + 1) == Some('*') {
            let start = i;
            let mut depth = 0usize;
            loop {
                match (at(i), at(i + 1)) {
                    (Some('('), Some('*')) => {
                        depth += 1;
                        i += 2;
                    }
                    (Some('*'), Some(')')) => {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            break;
                        }
                    }
                    (Some(_), _) => i += 1,
                    (None, _) => {
                        return Err(format!(
                            "line {}: comment never closed",
                            line_of(src, pos(start))
                        ))
                    }
                }
            }
        } else if c == '*' && at(i + 1) == Some(')') {
            return Err(format!(
                "line {}: `*)` outside a comment",
                line_of(src, pos(i))
            ));
        } else if c == '"' || c == '\'' || c == '?' {
            let start = i;
            i += 1;
            let mut text = String::new();
            loop {
                match at(i) {
                    Some(d) if d == c => break,
                    Some('\n') | None if c != '?' => {
                        return Err(format!(
                            "line {}: unterminated terminal string",
                            line_of(src, pos(start))
                        ))
                    }
                    None => {
                        return Err(format!(
                            "line {}: unterminated special sequence",
                            line_of(src, pos(start))
                        ))
                    }
                    Some(d) => text.push(d),
                }
                i += 1;
            }
            i += 1;
            if c == '?' {
                toks.push(Tok::Special(text));
            } else if text.is_empty() {
                return Err(format!(
                    "line {}: empty terminal string",
                    line_of(src, pos(start))
                ));
            } else {
                toks.push(Tok::Term(text));
            }
        } else if c.is_ascii_alphabetic() {
            let mut words = Vec::new();
            let mut word = String::new();
            while let Some(d) = at(i) {
                if d.is_ascii_alphanumeric() {
                    word.push(d);
                } else if d.is_whitespace() {
                    if !word.is_empty() {
                        words.push(std::mem::take(&mut word));
                    }
                } else {
                    break;
                }
                i += 1;
            }
            if !word.is_empty() {
                words.push(word);
            }
            toks.push(Tok::Ident(words.join(" ")));
        } else if "=,|;-[]{}()".contains(c) {
            toks.push(Tok::Op(c));
            i += 1;
        } else {
            return Err(format!(
                "line {}: unexpected character {c:?} outside a comment",
                line_of(src, pos(i))
            ));
        }
    }
    Ok(toks)
}

/// The rules of the grammar: name -> definition tokens, in file order.
fn rules(src: &str) -> Vec<(String, Vec<Tok>)> {
    let toks = lex_ebnf(src).unwrap_or_else(|e| panic!("grammar: {e}"));
    let mut out = Vec::new();
    let mut rest = toks.as_slice();
    while !rest.is_empty() {
        let Some(end) = rest.iter().position(|t| *t == Tok::Op(';')) else {
            panic!(
                "grammar: rule without `;` near {:?}",
                &rest[..3.min(rest.len())]
            );
        };
        let rule = &rest[..end];
        rest = &rest[end + 1..];
        let [Tok::Ident(name), Tok::Op('='), body @ ..] = rule else {
            panic!("grammar: not a rule `name = …;`: {rule:?}");
        };
        let mut depth: Vec<char> = Vec::new();
        for t in body {
            match t {
                Tok::Op(c @ ('[' | '{' | '(')) => depth.push(*c),
                Tok::Op(c @ (']' | '}' | ')')) => {
                    let open = match c {
                        ']' => '[',
                        '}' => '{',
                        _ => '(',
                    };
                    assert_eq!(depth.pop(), Some(open), "unbalanced `{c}` in rule `{name}`");
                }
                Tok::Op('=') => panic!("`=` inside rule `{name}` (missing `;`?)"),
                _ => {}
            }
        }
        assert!(depth.is_empty(), "unclosed bracket in rule `{name}`");
        out.push((name.clone(), body.to_vec()));
    }
    out
}

#[test]
fn grammars_are_well_formed_iso_ebnf() {
    for g in &GRAMMARS {
        well_formed(g);
    }
}

fn well_formed(g: &Grammar) {
    let src = grammar_text(g.file);
    let rules = rules(&src);
    assert!(rules.len() > 20, "only {} rules found", rules.len());
    let mut defined = BTreeSet::new();
    for (name, _) in &rules {
        assert!(
            defined.insert(name.as_str()),
            "rule `{name}` is defined twice"
        );
    }
    let mut undefined = BTreeSet::new();
    for (name, body) in &rules {
        for t in body {
            if let Tok::Ident(id) = t {
                if !defined.contains(id.as_str()) {
                    undefined.insert(format!("`{id}` (used in `{name}`)"));
                }
            }
        }
    }
    assert!(
        undefined.is_empty(),
        "undefined meta-identifiers: {undefined:?}"
    );
    for start in g.starts {
        assert!(defined.contains(start), "{}: no rule `{start}`", g.file);
    }
}

/// The alternatives of rule `name` in grammar `file`, each a list of
/// terminals joined by `,`, the terminals of an alternative joined by a
/// space.
fn keyword_rule(file: &str, name: &str) -> Vec<String> {
    let src = grammar_text(file);
    let rules = rules(&src);
    let body = rules
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, b)| b.clone())
        .unwrap_or_else(|| panic!("{file} has no rule `{name}`"));
    let mut keywords = Vec::new();
    for alt in body.split(|t| *t == Tok::Op('|')) {
        let mut words = Vec::new();
        for (i, t) in alt.iter().enumerate() {
            match (i % 2, t) {
                (0, Tok::Term(w)) => words.push(w.clone()),
                (1, Tok::Op(',')) => {}
                _ => {
                    panic!("`header keyword` alternatives must be terminals joined by `,`: {alt:?}")
                }
            }
        }
        assert!(!words.is_empty(), "empty alternative in `{name}`");
        keywords.push(words.join(" "));
    }
    keywords
}

#[test]
fn linf_block_keywords_match_the_lexer() {
    let keywords = keyword_rule("linf.ebnf", "block keyword");
    let lexer: Vec<&str> = BlockKind::ALL.iter().map(|k| k.keyword()).collect();
    assert_eq!(keywords, lexer);
}

#[test]
fn stl_keywords_shapes_and_reserved_names_match_the_implementation() {
    assert_eq!(
        keyword_rule("stl.ebnf", "keyword"),
        graftal::front::stl::parser::KEYWORDS.to_vec()
    );
    let shapes = keyword_rule("stl.ebnf", "shape name");
    assert_eq!(shapes, ["Rectangle", "RoundRect", "Ellipse", "Polygon"]);
    let reserved = keyword_rule("stl.ebnf", "reserved name");
    for r in graftal::front::stl::parser::RESERVED {
        assert!(
            reserved.contains(&r.to_string()),
            "`{r}` is reserved but not in the grammar"
        );
    }
    // Each shape is accepted by the front end.
    for k in shapes {
        let c = run(
            &format!("SEED\nF\nENDSEED\nLAYOUT\n(clWhite) {k} (0,0), (1,0), (0,1)\nENDLAYOUT\n"),
            "stl",
            None,
        );
        assert!(!codes_of(&c).contains(&"E0505"), "{k}");
    }
}

#[test]
fn smith_keys_match_the_lowering() {
    assert_eq!(
        keyword_rule("smith.ebnf", "key"),
        graftal::front::smith::lower::KEYS
    );
}

#[test]
fn header_keywords_match_the_parser() {
    let keywords = keyword_rule("pfg.ebnf", "header keyword");
    assert_eq!(keywords, HEADERS.to_vec());
    // The keys are words: letters only, so that the lexer reads them as
    // `word` tokens; written in lower case, compared without regard to case.
    for k in &keywords {
        assert!(
            k.chars().all(|c| c.is_ascii_lowercase() || c == ' '),
            "`{k}`"
        );
    }
}

// ---------------------------------------------------------------------------
// Examples and counterexamples.

#[derive(Debug)]
struct Example {
    /// `None` for an example, the expected code for a counterexample.
    code: Option<String>,
    text: String,
    /// The entry chosen (`counterexample CODE entry NAME:`).
    entry: Option<String>,
    /// 1-based line in the grammar file.
    line: usize,
}

/// Decodes the escapes of an example's text (see the top of the grammar).
fn unescape(raw: &str, line: usize) -> String {
    let mut out = String::new();
    let mut it = raw.chars();
    while let Some(c) = it.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match it.next() {
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some('t') => out.push('\t'),
            Some('\\') => out.push('\\'),
            Some('u') => {
                assert_eq!(it.next(), Some('{'), "line {line}: `\\u` without `{{`");
                let hex: String = it.by_ref().take_while(|&c| c != '}').collect();
                let ch = u32::from_str_radix(&hex, 16)
                    .ok()
                    .and_then(char::from_u32)
                    .unwrap_or_else(|| panic!("line {line}: bad escape `\\u{{{hex}}}`"));
                out.push(ch);
            }
            other => panic!("line {line}: unknown escape `\\{}`", other.unwrap_or(' ')),
        }
    }
    out
}

fn is_code(s: &str) -> bool {
    s.len() == 5
        && (s.starts_with('E') || s.starts_with('W'))
        && s[1..].chars().all(|c| c.is_ascii_digit())
}

fn examples(src: &str) -> Vec<Example> {
    let mut out = Vec::new();
    for (i, line) in src.lines().enumerate() {
        let n = i + 1;
        // Indented lines are documentation of the format, not examples.
        if !(line.starts_with("(* example") || line.starts_with("(* counterexample")) {
            continue;
        }
        let body = line
            .strip_suffix(" *)")
            .unwrap_or_else(|| panic!("line {n}: an example must end with ` *)`"));
        let mut entry = None;
        let (code, raw) = if let Some(raw) = body.strip_prefix("(* example: ") {
            (None, raw)
        } else if let Some(rest) = body.strip_prefix("(* counterexample ") {
            let (code, raw) = rest
                .split_once(": ")
                .unwrap_or_else(|| panic!("line {n}: expected `(* counterexample CODE: …`"));
            let code = match code.split_once(" entry ") {
                Some((code, name)) => {
                    entry = Some(name.to_string());
                    code
                }
                None => code,
            };
            assert!(is_code(code), "line {n}: `{code}` is not a code");
            (Some(code.to_string()), raw)
        } else {
            panic!("line {n}: malformed example line");
        };
        assert!(
            !raw.contains("*)") && !raw.contains("(*"),
            "line {n}: an example's text may not contain `*)` or `(*`"
        );
        out.push(Example {
            code,
            text: unescape(raw, n),
            entry,
            line: n,
        });
    }
    out
}

fn run(text: &str, ext: &str, entry: Option<&str>) -> Compiled {
    compile_entry(SourceFile::new(format!("ex.{ext}"), text), entry)
}

fn codes_of(c: &Compiled) -> Vec<&'static str> {
    c.diagnostics.iter().map(|d| d.code.0).collect()
}

/// The codes named between the constraint markers.
fn constraint_codes(src: &str) -> BTreeSet<String> {
    let marker = |m: &str| {
        let found: Vec<usize> = src
            .lines()
            .enumerate()
            .filter(|(_, l)| l.trim_end() == m)
            .map(|(i, _)| i)
            .collect();
        assert_eq!(found.len(), 1, "the grammar must have one line `{m}`");
        found[0]
    };
    let begin = marker("(* BEGIN CONSTRAINTS *)");
    let end = marker("(* END CONSTRAINTS *)");
    assert!(begin < end, "END CONSTRAINTS before BEGIN CONSTRAINTS");
    let section: String = src
        .lines()
        .skip(begin + 1)
        .take(end - begin - 1)
        .collect::<Vec<_>>()
        .join("\n");
    let section: Vec<char> = section.chars().collect();
    let mut found = BTreeSet::new();
    for i in 0..section.len().saturating_sub(4) {
        let word: String = section[i..i + 5].iter().collect();
        let before = i.checked_sub(1).map(|j| section[j]);
        let after = section.get(i + 5);
        let boundary = |c: Option<&char>| !c.is_some_and(|c| c.is_ascii_alphanumeric());
        if is_code(&word) && boundary(before.as_ref()) && boundary(after) {
            found.insert(word);
        }
    }
    found
}

#[test]
fn enough_examples_to_mean_something() {
    for g in &GRAMMARS {
        enough_examples(g);
    }
}

fn enough_examples(g: &Grammar) {
    let all = examples(&grammar_text(g.file));
    let valid = all.iter().filter(|e| e.code.is_none()).count();
    let invalid = all.len() - valid;
    assert!(valid >= MIN_EXAMPLES, "only {valid} examples");
    assert!(
        invalid >= MIN_COUNTEREXAMPLES,
        "only {invalid} counterexamples"
    );
}

#[test]
fn examples_compile_without_any_diagnostic() {
    for g in &GRAMMARS {
        examples_compile(g);
    }
}

fn examples_compile(g: &Grammar) {
    let mut failures = Vec::new();
    let mut count = 0;
    for ex in examples(&grammar_text(g.file))
        .iter()
        .filter(|e| e.code.is_none())
    {
        count += 1;
        let c = run(&ex.text, g.ext, ex.entry.as_deref());
        if c.diagnostics.has_errors() || c.system.is_none() || !c.diagnostics.is_empty() {
            failures.push(format!(
                "line {}: {:?}\n    gave {:?}",
                ex.line,
                ex.text,
                c.diagnostics
                    .iter()
                    .map(|d| format!("{} {}", d.code, d.message))
                    .collect::<Vec<_>>()
            ));
        }
    }
    assert!(count >= MIN_EXAMPLES);
    assert!(
        failures.is_empty(),
        "{}: examples that do not compile cleanly:\n{}",
        g.file,
        failures.join("\n")
    );
}

#[test]
fn counterexamples_give_exactly_their_code() {
    for g in &GRAMMARS {
        counterexamples(g);
    }
}

fn counterexamples(g: &Grammar) {
    let mut failures = Vec::new();
    let mut count = 0;
    for ex in examples(&grammar_text(g.file)) {
        let Some(code) = &ex.code else { continue };
        count += 1;
        let c = run(&ex.text, g.ext, ex.entry.as_deref());
        let got = codes_of(&c);
        let is_warning = code.starts_with('W');
        let compiled = c.system.is_some() && !c.diagnostics.has_errors();
        let ok = !got.is_empty() && got.iter().all(|g| g == code) && compiled == is_warning;
        if !ok {
            failures.push(format!(
                "line {}: {:?}\n    expected only {code} ({}), got {got:?}, compiled: {compiled}",
                ex.line,
                ex.text,
                if is_warning {
                    "and compiling"
                } else {
                    "and failing"
                },
            ));
        }
    }
    assert!(count >= MIN_COUNTEREXAMPLES);
    assert!(
        failures.is_empty(),
        "{}: counterexamples that disagree with the implementation:\n{}",
        g.file,
        failures.join("\n")
    );
}

#[test]
fn constraint_codes_are_registered_and_each_has_a_counterexample() {
    for g in &GRAMMARS {
        constraint_codes_checked(g);
    }
}

fn constraint_codes_checked(g: &Grammar) {
    let src = grammar_text(g.file);
    let named = constraint_codes(&src);
    assert!(named.len() >= MIN_COUNTEREXAMPLES, "only {named:?}");
    let registered: BTreeSet<&str> = codes::all().map(|c| c.code.0).collect();
    let unknown: Vec<_> = named
        .iter()
        .filter(|c| !registered.contains(c.as_str()))
        .collect();
    assert!(
        unknown.is_empty(),
        "codes in the grammar but not in codes::ALL: {unknown:?}"
    );
    if let Some(range) = g.range {
        let unnamed: Vec<&&str> = registered
            .iter()
            .filter(|c| c[1..].starts_with(range) && !named.contains(**c))
            .collect();
        assert!(
            unnamed.is_empty(),
            "{}: codes of the notation the grammar does not name: {unnamed:?}",
            g.file
        );
    }

    let mut per_code: BTreeMap<&str, usize> = BTreeMap::new();
    let all = examples(&src);
    for ex in &all {
        if let Some(code) = &ex.code {
            *per_code.entry(code.as_str()).or_default() += 1;
            assert!(
                named.contains(code),
                "line {}: counterexample for {code}, which the constraint section does not name",
                ex.line
            );
        }
    }
    let missing: Vec<_> = named
        .iter()
        .filter(|c| !per_code.contains_key(c.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "constraint codes without a counterexample: {missing:?}"
    );
}

#[test]
fn gft_keywords_match_the_parser() {
    let parser: Vec<String> = graftal::front::gft::parser::KEYWORDS
        .iter()
        .map(|(k, _)| k.to_string())
        .collect();
    assert_eq!(keyword_rule("graftal.ebnf", "keyword"), parser);
}

#[test]
fn fractint_keywords_match_the_parser() {
    assert_eq!(
        keyword_rule("fractint.ebnf", "keyword"),
        graftal::front::fractint::parser::KEYWORDS
    );
}

#[test]
fn fractint_reserved_characters_match_the_reader() {
    // The grammar's reserved list, in the W0701 line of its constraints.
    let src = grammar_text("fractint.ebnf");
    let line = src
        .lines()
        .find(|l| l.contains("W0701"))
        .expect("a W0701 constraint");
    let listed: String = line
        .split('`')
        .nth(1)
        .expect("the reserved characters in backquotes")
        .split(' ')
        .collect();
    assert_eq!(listed, graftal::front::fractint::RESERVED);
}

#[test]
fn the_fig_3_11a_data_file_is_an_example_whole() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/stdlib/pfg/hogeweg-hesper-a.l");
    let file = std::fs::read_to_string(path).expect("stdlib/pfg/hogeweg-hesper-a.l");
    assert!(
        examples(&grammar_text("pfg.ebnf"))
            .iter()
            .any(|e| e.code.is_none() && e.text == file),
        "no example is exactly {path}"
    );
}

#[test]
fn the_fig_10_listing_is_an_example_whole() {
    let listing = "lines f\nangles (0, [0 2*pi])\naxiom f\nrules f = f+f\n";
    assert!(examples(&grammar_text("linf.ebnf"))
        .iter()
        .any(|e| e.code.is_none() && e.text == listing));
}

#[test]
fn escapes_decode() {
    assert_eq!(
        unescape(r"a\nb\r\n\t\\\u{7}\u{feff}", 1),
        "a\nb\r\n\t\\\u{7}\u{feff}"
    );
}
