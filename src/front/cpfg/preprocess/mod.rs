//! The C preprocessor pass cpfg runs over an L-system file.
//!
//! cpfg hands the `.l` file to the C preprocessor before reading it, so cpfg
//! files use `#define` (object-like and function-like, with `\` continuation
//! lines), `#undef`, `#include "file"`, `#if`/`#ifdef`/`#ifndef`/`#elif`/
//! `#else`/`#endif` and C comments. This module is that pass:
//!
//! - comments (`/* */`, `//`) become spaces (their line breaks stay), so
//!   columns and lines stay put; nothing inside a comment or a `"…"` string
//!   is expanded;
//! - macros expand as in C: arguments are expanded first, the result is
//!   rescanned, and a macro is not expanded again inside its own expansion
//!   (hide sets, after Prosser's algorithm). The stringizing `#` and pasting
//!   `##` operators are *not* implemented: in cpfg `#` is a module (line
//!   width), and no cpfg file uses either;
//! - directives become empty lines, so a line of the output is the same line
//!   of the input wherever possible (a macro call spanning lines, a `\`
//!   continuation outside a directive, or an included file shift the lines
//!   after it until the next line break of the original, where the missing
//!   breaks are put back);
//! - [`SourceMap`] sends any output range back to the original text: copied
//!   bytes to themselves, bytes made by an expansion to the whole macro call
//!   (name and arguments), bytes of an included file to the `#include` line;
//!   [`SourceMap::locate`] sends them into the included file itself.
//!
//! It never panics and always ends: output is capped at 8 MiB and expansion
//! at 20 million steps ([`codes::CPFG_EXPANSION_LIMIT`]); macro calls in
//! arguments and `#if` conditions nest at most [`MAX_NESTING`] deep (E0013,
//! graftal's one depth limit), since both are followed by recursion.

mod comments;
mod conditions;
mod directives;
mod include;
mod macros;
mod output;
mod tokens;

use crate::diagnostics::{codes, Diagnostic, Diagnostics, SideFile};
use comments::strip_comments;
use macros::Macro;
use output::Out;
use std::collections::HashMap;
use std::ops::Range;
use std::rc::Rc;
use std::sync::Arc;
use tokens::{is_directive, strip_ws, tokenize, Kind, Tok};

/// Output larger than this is cut off.
pub const MAX_OUTPUT: usize = 8 << 20;
const MAX_STEPS: u64 = 20_000_000;
const MAX_PENDING_TOKENS: usize = 2_000_000;
const MAX_INCLUDE_DEPTH: usize = 16;

/// The preprocessed text, its map back to the original, and what went wrong.
#[derive(Clone, Debug)]
pub struct Preprocessed {
    pub text: String,
    pub map: SourceMap,
    pub diagnostics: Diagnostics,
    /// Expansion stopped at macro calls nested past the depth limit
    /// (reported): the rest of the text is left as written, nesting and all.
    pub stopped_too_deep: bool,
}

/// Maps byte ranges of the preprocessed text to byte ranges of the original
/// main file, or of the file `#include`d there.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    segs: Vec<Seg>,
    src_len: usize,
    /// The included files' text in the output, each with its own map.
    included: Vec<Included>,
}

/// An included file's place in the output (bytes `out`), how its own
/// output maps into it, and the note that says where it was included.
#[derive(Clone, Debug)]
struct Included {
    file: Arc<SideFile>,
    out: Range<usize>,
    map: SourceMap,
    note: String,
}

/// Where output bytes come from when they come from an included file: that
/// file (the innermost one), and the notes that say where each file on the
/// way was included, innermost first.
pub type IncludedFrom = (Arc<SideFile>, Vec<String>);

#[derive(Clone, Debug, PartialEq)]
struct Seg {
    out: Range<usize>,
    src: Range<usize>,
    /// Bytes copied from the original (byte i of `out` is byte i of `src`);
    /// otherwise the whole of `out` comes from `src` (a macro call, an
    /// `#include` line).
    identity: bool,
}

impl SourceMap {
    /// The byte range of the original main file that produced the output
    /// bytes `out`: copied bytes map to themselves, expanded bytes to the
    /// whole macro call, included bytes to the `#include` directive. An
    /// empty range maps to the place it stands at.
    pub fn to_source(&self, out: Range<usize>) -> Range<usize> {
        let (a, b) = (out.start, out.end.max(out.start));
        if self.segs.is_empty() {
            return a.min(self.src_len)..a.min(self.src_len);
        }
        // First segment whose end is beyond `a` (or that contains the point a).
        let first = self.segs.partition_point(|s| s.out.end <= a);
        if a == b {
            let s = self
                .segs
                .get(first)
                .unwrap_or(&self.segs[self.segs.len() - 1]);
            return if s.identity {
                let p = (s.src.start + a.saturating_sub(s.out.start)).min(s.src.end);
                let p = if a >= s.out.end { s.src.end } else { p };
                p..p
            } else {
                s.src.clone()
            };
        }
        let mut lo = usize::MAX;
        let mut hi = 0;
        for s in &self.segs[first.min(self.segs.len())..] {
            if s.out.start >= b {
                break;
            }
            let (x, y) = if s.identity {
                let x = s.src.start + a.max(s.out.start) - s.out.start;
                let y = s.src.start + b.min(s.out.end) - s.out.start;
                (x, y)
            } else {
                (s.src.start, s.src.end)
            };
            lo = lo.min(x);
            hi = hi.max(y);
        }
        if lo == usize::MAX {
            let end = self.segs.last().map_or(0, |s| s.src.end.max(s.src.start));
            return end..end;
        }
        lo..hi
    }

    /// [`Self::to_source`], but output bytes that come from an included
    /// file map into that file (a mistake is shown where it is written,
    /// as rustc shows one inside a macro of another file).
    pub fn locate(&self, out: Range<usize>) -> (Range<usize>, Option<IncludedFrom>) {
        let inside = |i: &&Included| {
            i.out.start <= out.start && out.end <= i.out.end && out.start < i.out.end
        };
        let Some(inc) = self.included.iter().find(inside) else {
            return (self.to_source(out), None);
        };
        let shifted = out.start - inc.out.start..out.end - inc.out.start;
        let (span, deeper) = inc.map.locate(shifted);
        let (file, mut notes) = deeper.unwrap_or_else(|| (inc.file.clone(), Vec::new()));
        notes.push(inc.note.clone());
        (span, Some((file, notes)))
    }
}

/// Runs the preprocessor over `text` (the main file). `include` is called
/// with the name written in an `#include` and returns that file's text, or
/// `None` when there is no such file.
pub fn preprocess(text: &str, include: &mut dyn FnMut(&str) -> Option<String>) -> Preprocessed {
    preprocess_with_defines(text, &[], include)
}

/// [`preprocess`] with macros defined beforehand, as `cpp -D NAME=body`
/// does. cpfg defines one per user function (`-D FUNCNAME=id`, manual
/// §8.1.6), so a file can write `func(FUNCNAME, x)`.
pub fn preprocess_with_defines(
    text: &str,
    defines: &[(String, String)],
    include: &mut dyn FnMut(&str) -> Option<String>,
) -> Preprocessed {
    let mut pp = Pp {
        macros: HashMap::new(),
        names: Vec::new(),
        include,
        steps: 0,
        aborted: false,
        too_deep: false,
        stack: Vec::new(),
        texts: vec![Rc::from(text)],
        diags: Diagnostics::default(),
    };
    for (name, body) in defines {
        let toks = tokenize(body, 0, false);
        let body = strip_ws(toks);
        let id = pp.intern(name);
        pp.macros.insert(
            name.clone(),
            Macro {
                id,
                params: None,
                variadic: false,
                body,
                def: None,
            },
        );
    }
    let mut out = Out::default();
    pp.run(text, &mut out, true);
    out.flush_pending(text.len());
    let diagnostics = pp.diags;
    Preprocessed {
        text: out.text,
        map: SourceMap {
            segs: out.segs,
            src_len: text.len(),
            included: out.included,
        },
        diagnostics,
        stopped_too_deep: pp.too_deep,
    }
}

// ---------------------------------------------------------------------------
// Tokens

struct Cond {
    /// This group's text is kept.
    active: bool,
    /// A group of this `#if` chain was kept already.
    taken: bool,
    /// The enclosing text is kept.
    parent: bool,
    seen_else: bool,
    span: Range<usize>,
}

/// A directive line taken apart.
struct Directive<'a> {
    name: &'a str,
    /// The tokens after the name.
    rest: Vec<Tok>,
    /// `rest` without its surrounding blanks (the point after the name when
    /// there is nothing).
    rest_span: Range<usize>,
    name_span: Range<usize>,
    /// From the `#` to the end of the line's text.
    line_span: Range<usize>,
}

struct Pp<'a> {
    macros: HashMap<String, Macro>,
    names: Vec<String>,
    include: &'a mut dyn FnMut(&str) -> Option<String>,
    steps: u64,
    aborted: bool,
    /// Expansion stopped at calls nested past the depth limit.
    too_deep: bool,
    /// Names of the files being included (for recursion).
    stack: Vec<String>,
    /// The text of the main file, then of each file in `stack`: where the
    /// notes find the line of an `#include`.
    texts: Vec<Rc<str>>,
    diags: Diagnostics,
}

impl Pp<'_> {
    fn intern(&mut self, name: &str) -> u32 {
        if let Some(i) = self.names.iter().position(|n| n == name) {
            return i as u32;
        }
        self.names.push(name.to_string());
        (self.names.len() - 1) as u32
    }

    fn abort(&mut self, span: Range<usize>, what: &str) {
        if !self.aborted {
            self.aborted = true;
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_EXPANSION_LIMIT,
                    span,
                    format!("macro expansion stopped: {what}"),
                )
                .with_label("expanding this")
                .with_help("look for macros that expand into several copies of each other"),
            );
        }
    }

    /// Preprocesses one file's text into `out`. Diagnostics have spans in
    /// this text.
    fn run(&mut self, text: &str, out: &mut Out, main: bool) {
        let (clean, nl_in_comment) = strip_comments(text, &mut self.diags);
        let b = clean.as_bytes();
        let mut conds: Vec<Cond> = Vec::new();
        let mut pos = 0;
        let mut region: Option<usize> = None; // start of pending text lines
        while pos < b.len() {
            // The logical line: up to a line break that is neither escaped
            // nor inside a comment.
            let mut end = pos;
            loop {
                match clean[end..].find('\n') {
                    None => {
                        end = b.len();
                        break;
                    }
                    Some(k) => {
                        let nl = end + k;
                        let escaped = (nl >= 1 && b[nl - 1] == b'\\')
                            || (nl >= 2 && b[nl - 1] == b'\r' && b[nl - 2] == b'\\');
                        if escaped || nl_in_comment[nl] {
                            end = nl + 1;
                            continue;
                        }
                        end = nl + 1;
                        break;
                    }
                }
            }
            let line = &clean[pos..end];
            let trimmed = line.trim_start_matches([' ', '\t', '\x0b', '\x0c', '\r']);
            let active = conds.last().is_none_or(|c| c.active);
            if is_directive(trimmed) {
                if let Some(r) = region.take() {
                    self.text_region(&clean, r..pos, out);
                }
                let hash = pos + (line.len() - trimmed.len());
                self.directive(&clean, hash, end, &mut conds, out, active, main);
                // The directive's lines become empty lines.
                for (k, &c) in b[pos..end].iter().enumerate() {
                    if c == b'\n' {
                        out.copy("\n", pos + k..pos + k + 1);
                    }
                }
                out.src_hi = out.src_hi.max(end);
            } else if active {
                region.get_or_insert(pos);
            } else {
                for (k, &c) in b[pos..end].iter().enumerate() {
                    if c == b'\n' {
                        out.copy("\n", pos + k..pos + k + 1);
                    }
                }
                out.src_hi = out.src_hi.max(end);
            }
            pos = end;
            if out.full {
                break;
            }
        }
        if let Some(r) = region.take() {
            self.text_region(&clean, r..b.len(), out);
        }
        if out.full {
            self.abort(0..0, "the output passed 8 MiB");
        }
        for c in conds {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_UNTERMINATED_IF,
                    c.span,
                    "conditional block never closed",
                )
                .with_label("opened here")
                .with_help("add `#endif` where the conditional text ends"),
            );
        }
    }

    /// Expands and writes the text lines `range` of `clean`.
    fn text_region(&mut self, clean: &str, range: Range<usize>, out: &mut Out) {
        if out.full {
            return;
        }
        let toks = tokenize(&clean[range.clone()], range.start, false);
        let expanded = self.expand(toks.into(), 0);
        for t in expanded {
            if out.full {
                break;
            }
            if t.own {
                if t.kind == Kind::Splice {
                    out.pending += 1;
                    out.src_hi = out.src_hi.max(t.origin.end);
                } else {
                    out.copy(&t.text, t.origin.clone());
                }
            } else {
                out.generated(&t.text, t.origin.clone(), clean);
            }
        }
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pp(text: &str) -> Preprocessed {
        preprocess(text, &mut |_| None)
    }
    fn codes_of(p: &Preprocessed) -> Vec<&'static str> {
        p.diagnostics.iter().map(|d| d.code.0).collect()
    }

    #[test]
    fn object_macros_expand_and_lines_stay() {
        let src =
            "#define RATE 1.02 /* growth */\n#define N 3\naxiom: A(RATE)\nA(x) --> A(x*RATE)B(N)\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text, "\n\naxiom: A(1.02)\nA(x) --> A(x*1.02)B(3)\n");
        assert_eq!(p.text.lines().count(), src.lines().count());
    }

    #[test]
    fn function_like_macros_nest_and_rescan() {
        let src =
            "#define MAX(a,b) (((a)>(b))?(a):(b))\n#define W(x) MAX(x,1)\nA --> F(W(MAX(2,3)))\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        let y = "(((2)>(3))?(2):(3))";
        assert_eq!(p.text.trim(), format!("A --> F(((({y})>(1))?({y}):(1)))"));
    }

    #[test]
    fn a_name_without_parenthesis_is_not_a_call() {
        let p = pp("#define f(x) g\nA --> f + f(1)\n");
        assert_eq!(p.text, "\nA --> f + g\n");
    }

    #[test]
    fn no_self_recursion() {
        let p = pp("#define A A+B\n#define B A*2\nx: A\n");
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "\n\nx: A+A*2\n");
        let p = pp("#define f(x) f(x+1)\nf(f(0))\n");
        assert_eq!(p.text, "\nf(f(0+1)+1)\n");
    }

    #[test]
    fn continuation_lines_join_the_definition_and_keep_line_count() {
        let src = "#define LEAF(a) [+F(a)\\\n   -F(a)]\nA --> LEAF(2)\nB\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text, "\n\nA --> [+F(2)   -F(2)]\nB\n");
    }

    #[test]
    fn double_backslash_is_dropped_with_a_warning() {
        let p = pp("#define f(x) \\\\\n\t(x*2)\nA --> F(f(3))\n");
        assert_eq!(codes_of(&p), ["W0802"]);
        assert_eq!(p.text, "\n\nA --> F((3*2))\n");
    }

    #[test]
    fn no_expansion_in_comments_or_strings() {
        let p = pp("#define N 5\n/* N */ printf(\"N=%d\", N); // N\n");
        assert_eq!(p.text, "\n        printf(\"N=%d\", 5);     \n");
    }

    #[test]
    fn multi_line_comment_inside_a_define() {
        let src = "#define LM (8/8)  /* amount\n   maintained */\nA --> F(LM)\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "\n\nA --> F((8/8))\n");
    }

    #[test]
    fn conditionals() {
        let src = "#define LEAVES 2\n#if LEAVES==1\none\n#elif LEAVES>1 && defined(LEAVES)\ntwo\n#else\nthree\n#endif\n#ifdef NOPE\nx\n#endif\n#ifndef NOPE\ny\n#endif\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text.split_whitespace().collect::<Vec<_>>(), ["two", "y"]);
        assert_eq!(p.text.lines().count(), src.lines().count());
        // Nested, with arithmetic and the ternary.
        let p = pp("#if (7 % 4) * 2 - 6 == 0 ? !0 : 0\n#if 1 < 0 || (2 <= 2 && 3 >= 4)\nno\n#else\nyes\n#endif\n#endif\n");
        assert_eq!(p.text.trim(), "yes");
    }

    #[test]
    fn map_sends_expansions_back_to_the_call() {
        let src = "#define W(x) #(x*2)\naxiom: F W(3) G\n";
        let p = pp(src);
        let at = p.text.find("#(3*2)").unwrap();
        let call = src.find("W(3)").unwrap();
        assert_eq!(p.map.to_source(at + 2..at + 3), call..call + 4);
        // Copied text maps to itself.
        let g = p.text.find('G').unwrap();
        let gs = src.rfind('G').unwrap();
        assert_eq!(p.map.to_source(g..g + 1), gs..gs + 1);
        let a = p.text.find("axiom").unwrap();
        assert_eq!(&src[p.map.to_source(a..a + 5)], "axiom");
    }

    #[test]
    fn calls_spanning_lines_put_the_line_breaks_back() {
        let src = "#define P(a,b) a+b\nA --> P(1,\n 2) B\nC\n";
        let p = pp(src);
        assert_eq!(p.text, "\nA --> 1+2 B\n\nC\n");
        let c = p.text.find('C').unwrap();
        assert_eq!(
            p.map.to_source(c..c + 1),
            src.find('C').map(|i| i..i + 1).unwrap()
        );
    }

    #[test]
    fn includes() {
        let mut files = |n: &str| match n {
            "leaf.l" => Some("#define LW 2\nleaf --> F(LW)\n".to_string()),
            "self.l" => Some("#include \"self.l\"\n".to_string()),
            _ => None,
        };
        let src = "#include \"leaf.l\"\nA --> LW\n#include \"nope.l\"\n#include \"self.l\"\n";
        let p = preprocess(src, &mut files);
        assert!(p.text.contains("leaf --> F(2)"));
        assert!(p.text.contains("A --> 2"));
        assert_eq!(codes_of(&p), ["E0806", "E0807"]);
        let missing = &p.diagnostics.0[0];
        assert_eq!(&src[missing.span.clone().unwrap()], "\"nope.l\"");
        // Included text maps to the directive.
        let at = p.text.find("leaf -->").unwrap();
        assert_eq!(&src[p.map.to_source(at..at + 4)], "#include \"leaf.l\"");
        // Recursion is reported at the directive, naming the file.
        assert!(p.diagnostics.0[1]
            .notes
            .iter()
            .any(|n| n.contains("self.l")));
    }

    #[test]
    fn errors_with_spans() {
        let src = "/* open\nA";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0801"]);
        assert_eq!(p.diagnostics.0[0].span, Some(0..2));

        let p = pp("#if 1\nA\n");
        assert_eq!(codes_of(&p), ["E0802"]);
        let p = pp("A\n#endif\n#else\n");
        assert_eq!(codes_of(&p), ["E0803", "E0803"]);
        let p = pp("#if 0\n#else\n#else\n#endif\n");
        assert_eq!(codes_of(&p), ["E0803"]);

        let src = "#define M(a,b) a\nA --> M(1)\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0804"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "M(1)");
        assert_eq!(p.diagnostics.0[0].labels[0].span, 0..16);

        let src = "x\n#w(d) --> #(d*2)\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0805"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "#w");
        // `#` before something that is not a name is text, as vlab reads it.
        let p = pp("A -->\n\t#(0.06) F\n");
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "A -->\n\t#(0.06) F\n");
        let p = pp("#defin X 1\n");
        assert_eq!(
            p.diagnostics.0[0].help.as_deref(),
            Some("did you mean `#define`?")
        );

        let src = "#define M(a) a\nA --> M(1\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0808"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "M");

        let p = pp("#if 1/0\n#endif\n#if 2 +\n#endif\n#define\n#include nope\n");
        assert_eq!(codes_of(&p), ["E0809", "E0809", "E0809", "E0809"]);
    }

    #[test]
    fn predefined_function_names() {
        let p = preprocess_with_defines(
            "x = func(LEAF_WIDTH, 0.5);\n",
            &[("LEAF_WIDTH".into(), "2".into())],
            &mut |_| None,
        );
        assert_eq!(p.text, "x = func(2, 0.5);\n");
    }

    #[test]
    fn exponential_macros_are_cut_off() {
        let mut src = String::new();
        for i in 0..40 {
            src.push_str(&format!("#define M{i} M{} M{}\n", i + 1, i + 1));
        }
        src.push_str("M0\n");
        let p = pp(&src);
        assert!(codes_of(&p).contains(&"E0810"));
        assert!(p.text.len() <= MAX_OUTPUT);
    }

    #[test]
    fn redefinition_warns_only_when_different() {
        let p = pp("#define A 1\n#define A 1\n#define A 2\nA\n");
        assert_eq!(codes_of(&p), ["W0801"]);
        assert_eq!(p.text.trim(), "2");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn never_panics_and_maps_into_the_source(
            parts in proptest::collection::vec(
                prop_oneof![
                    Just("#define ".to_string()), Just("#if ".to_string()), Just("#endif\n".to_string()),
                    Just("#else\n".to_string()), Just("#include \"a\"\n".to_string()), Just("(".to_string()),
                    Just(")".to_string()), Just(",".to_string()), Just("\\\n".to_string()), Just("/*".to_string()),
                    Just("*/".to_string()), Just("//".to_string()), Just("\"".to_string()), Just("\n".to_string()),
                    Just("A".to_string()), Just("B(x)".to_string()), Just(" A B ".to_string()), Just("é".to_string()),
                    Just("defined".to_string()), Just("1".to_string()), Just("==".to_string()), Just("#".to_string()),
                    "[ -~]{0,6}",
                ],
                0..40,
            )
        ) {
            let src: String = parts.concat();
            let p = preprocess(&src, &mut |n| (n == "a").then(|| "A\n#include \"a\"\n".to_string()));
            prop_assert!(p.text.len() <= MAX_OUTPUT);
            for s in [0..p.text.len(), 0..0, p.text.len() / 2..p.text.len()] {
                let r = p.map.to_source(s);
                prop_assert!(r.start <= r.end && r.end <= src.len(), "{r:?}");
            }
            for d in p.diagnostics.iter() {
                let s = d.span.clone().unwrap_or(0..0);
                prop_assert!(s.start <= s.end && s.end <= shown_in(d, &src).len());
            }
        }
    }

    /// The text a diagnostic's span points into: the included file it is
    /// reported on, else the main file.
    fn shown_in<'a>(d: &'a crate::diagnostics::Diagnostic, main: &'a str) -> &'a str {
        d.side.as_ref().map_or(main, |f| f.text.as_str())
    }

    /// A file that includes itself is reported on that file, at the name
    /// in its own `#include` (the case the property above first found).
    #[test]
    fn a_file_including_itself_is_reported_where_it_does() {
        let inner = "A\n#include \"a\"\n";
        let src = "#include \"a\"\n";
        let p = preprocess(src, &mut |n| (n == "a").then(|| inner.to_string()));
        let on_a: Vec<_> = (p.diagnostics.iter())
            .filter(|d| d.side.as_ref().is_some_and(|f| f.name == "a"))
            .collect();
        assert!(!on_a.is_empty(), "{:?}", p.diagnostics);
        for d in on_a {
            let s = d.span.clone().expect("a place");
            assert_eq!(&shown_in(d, src)[s], "\"a\"");
        }
    }
}
