//! What the library says of a place in a compiled file, for every face
//! that shows it (the language server's hover, the page of `graftal
//! serve`): the explanation of the diagnostics there, what the symbol
//! there does to the turtle and which productions rewrite it, what a
//! declared name or a user function is; and where the symbol or name there
//! is defined and written. Decided here once, so that the faces say the
//! same: they only turn byte offsets into their own positions.
//!
//! Nothing is derived: all of it is read from the compile (its system, or
//! what was recovered of a file with errors, and its span table).

mod names;
mod places;
mod prose;

use crate::diagnostics::codes;
use crate::driver::Compiled;
use crate::front::declared::word_span;
use crate::ir::Span;
use places::Occurrence;
use std::sync::OnceLock;

pub use crate::front::{Declaration, DeclarationKind, FunctionSite};
pub use names::Names;
pub use prose::what_it_does;

/// What hovering a place shows: Markdown, and the span of the text it
/// speaks of (the narrowest of the symbol, name or diagnostic there), for
/// a face to mark.
#[derive(Clone, Debug, PartialEq)]
pub struct HoverText {
    pub markdown: String,
    pub span: Option<Span>,
}

/// What hovering byte `at` of `c` shows, found afresh: a face that asks
/// about the same compile again keeps a [`Knowledge`] beside it instead.
pub fn hover(c: &Compiled, at: usize) -> Option<HoverText> {
    Knowledge::default().hover(c, at)
}

/// What is known of the places of one compile: where its symbols are
/// written, the names it declares, the user functions beside it. Each is
/// found by the first question that needs it and kept, so a `Knowledge`
/// is made beside one [`Compiled`] and asked only about that one.
/// (`OnceLock`, not `OnceCell`: a face may answer from several threads.)
#[derive(Default)]
pub struct Knowledge {
    occurrences: OnceLock<Vec<Occurrence>>,
    names: OnceLock<Names>,
    /// Read from disk (a cpfg object's files): only when asked for.
    functions: OnceLock<Vec<FunctionSite>>,
}

impl Knowledge {
    /// What hovering byte `at` of `c` shows: the explanation of the
    /// diagnostics there (or of a code written there), what the name, the
    /// user function or the symbol there is; `None` when nothing is.
    pub fn hover(&self, c: &Compiled, at: usize) -> Option<HoverText> {
        let mut said = Said::default();
        explain_codes(c, at, &mut said);
        let names = self.names(c);
        if let Some((i, span)) = names.at(at) {
            said.add(names.decls[i].about.clone(), Some(span.clone()));
        }
        if let Some(f) = self.user_function_at(c, at) {
            said.add(prose::function_text(f), word_span(&c.file.text, at));
        }
        let occurrence = places::at(self.occurrences(c), at);
        if let (Some(sys), Some(o)) = (c.system_or_recovered(), occurrence) {
            said.add(prose::symbol_text(c, sys, o.symbol), Some(o.span.clone()));
        }
        said.into_hover()
    }

    /// Where what is written at byte `at` of `c` is defined: the
    /// predecessors of the productions that rewrite the symbol there and
    /// the declaration of the name there, in the order written.
    pub fn definitions(&self, c: &Compiled, at: usize) -> Vec<Span> {
        self.places(c, at, true)
    }

    /// Every place what is written at byte `at` of `c` (a symbol, a
    /// declared name) is written, in the order written.
    pub fn references(&self, c: &Compiled, at: usize) -> Vec<Span> {
        self.places(c, at, false)
    }

    /// The names `c` declares besides its symbols, and their uses.
    pub fn names(&self, c: &Compiled) -> &Names {
        self.names
            .get_or_init(|| names::find(c.front, &c.file.text))
    }

    /// The user function `c` calls at `at` (a cpfg `func(NAME, x)` or
    /// `func(k, x)`, when `at` is on its `NAME` or `k`), as its front end
    /// finds it.
    pub fn user_function_at(&self, c: &Compiled, at: usize) -> Option<&FunctionSite> {
        let word = c.front.user_function_called_at(&c.file.text, at)?;
        let path = std::path::Path::new(&c.file.name);
        let sites = self.functions.get_or_init(|| c.front.user_functions(path));
        match word.parse::<usize>() {
            Ok(k) => sites.iter().find(|s| s.number == k),
            Err(_) => sites.iter().find(|s| s.name.as_deref() == Some(word)),
        }
    }

    fn occurrences(&self, c: &Compiled) -> &[Occurrence] {
        self.occurrences.get_or_init(|| places::find(c))
    }

    /// [`definitions`](Self::definitions) or, not `definitions`,
    /// [`references`](Self::references).
    fn places(&self, c: &Compiled, at: usize, definitions: bool) -> Vec<Span> {
        let occ = self.occurrences(c);
        let symbol = places::at(occ, at).map(|o| o.symbol);
        let names = self.names(c);
        let named: Vec<&Span> = match names.at(at) {
            Some((i, _)) if definitions => vec![&names.decls[i].span],
            Some((i, _)) => names.places(i).collect(),
            None => Vec::new(),
        };
        let mut spans: Vec<&Span> = (occ.iter())
            .filter(|o| Some(o.symbol) == symbol && (o.defines || !definitions))
            .map(|o| &o.span)
            .collect();
        // A LinF name is both declared (`lines F`) and a symbol: each place once.
        spans.extend(named);
        spans.sort_by_key(|s| (s.start, s.end));
        spans.dedup();
        spans.into_iter().cloned().collect()
    }
}

/// The explanations of the diagnostics whose span holds `at`, then of a
/// code written at `at` (a comment that names one, say) unless said.
fn explain_codes(c: &Compiled, at: usize, said: &mut Said) {
    // A side file's diagnostics point into that file, not this text.
    let here = (c.diagnostics.iter()).filter(|d| d.side.is_none());
    for d in here {
        let Some(span) = d.span.as_ref().filter(|s| s.start <= at && at <= s.end) else {
            continue;
        };
        if let Some(text) = explanation(d.code.0) {
            said.add(text, Some(span.clone()));
        }
    }
    let word = word_span(&c.file.text, at).filter(|w| w.len() == 5);
    if let Some(word) = word {
        let text = explanation(&c.file.text[word.clone()]);
        if let Some(text) = text.filter(|t| !said.parts.contains(t)) {
            said.add(text, Some(word));
        }
    }
}

/// The explanation `graftal explain CODE` prints, as Markdown.
fn explanation(code: &str) -> Option<String> {
    codes::lookup(code).map(codes::explain_text)
}

/// A hover being put together: its parts in the order shown, and the
/// spans of what they speak of.
#[derive(Default)]
struct Said {
    parts: Vec<String>,
    spans: Vec<Span>,
}

impl Said {
    fn add(&mut self, text: String, span: Option<Span>) {
        self.parts.push(text);
        self.spans.extend(span);
    }

    /// The parts as one Markdown text, marking the narrowest span: the
    /// symbol or name under the cursor rather than the production a
    /// diagnostic covers.
    fn into_hover(self) -> Option<HoverText> {
        if self.parts.is_empty() {
            return None;
        }
        Some(HoverText {
            markdown: self.parts.join("\n\n---\n\n"),
            span: self.spans.into_iter().min_by_key(|s| s.len()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceFile;

    /// A pfg plant whose second `F` production can never apply (W0006).
    const PLANT: &str = "derivation length: 2\nangle factor: 4\naxiom: F+G\nF --> F+F\nF --> F-F\n";

    fn compiled(name: &str, text: &str) -> Compiled {
        crate::driver::compile(SourceFile::new(name, text))
    }

    /// The byte offset of the `n`th (from 0) `needle` of `text`.
    fn nth(text: &str, needle: &str, n: usize) -> usize {
        text.match_indices(needle).nth(n).unwrap().0
    }

    #[test]
    fn a_symbol_hovers_with_what_the_turtle_does_and_what_rewrites_it() {
        let c = compiled("plant.l", PLANT);
        let f = nth(PLANT, "F", 0);
        let h = hover(&c, f).expect("a hover over `F`");
        let expected = "`F`: moves one step forward, drawing a line\n\nRewritten by:\n\
                        - line 4: `F --> F+F`\n- line 5: `F --> F-F`\n";
        assert_eq!(h.markdown, expected);
        assert_eq!(h.span, Some(f..f + 1));
        let plus = nth(PLANT, "+", 0);
        let h = hover(&c, plus).expect("a hover over `+`");
        assert_eq!(
            h.markdown,
            "`+`: turns about its up axis U by the angle increment δ\n\n\
             No production rewrites it."
        );
        // Just after `G`, where a cursor that typed it stands (the end of
        // the line: nothing else is there).
        let g = nth(PLANT, "G", 0);
        let h = hover(&c, g + 1).expect("a hover after `G`");
        assert!(h.markdown.starts_with("`G`: "), "{}", h.markdown);
        assert!(h.markdown.ends_with("No production rewrites it."));
        assert_eq!(h.span, Some(g..g + 1));
    }

    #[test]
    fn a_diagnostic_hovers_with_its_explanation_over_its_span() {
        let c = compiled("plant.l", PLANT);
        let shadowed = c.diagnostics.iter().find(|d| d.code.0 == "W0006");
        let span = shadowed.and_then(|d| d.span.clone()).expect("W0006 here");
        // On the arrow of the production it covers: no symbol there.
        let arrow = nth(PLANT, "-->", 1);
        assert!(span.contains(&arrow), "{span:?}");
        let h = hover(&c, arrow).expect("a hover over the arrow");
        assert!(
            h.markdown
                .starts_with("W0006 (warning): production can never apply\n\n"),
            "{}",
            h.markdown
        );
        let info = codes::lookup("W0006").unwrap();
        assert_eq!(h.markdown, codes::explain_text(info));
        assert_eq!(h.span, Some(span.clone()));
        // On its predecessor the symbol is said too, and marked.
        let h = hover(&c, span.start).expect("a hover over `F`");
        let parts: Vec<&str> = h.markdown.split("\n\n---\n\n").collect();
        assert_eq!(parts.len(), 2, "{}", h.markdown);
        assert!(parts[0].starts_with("W0006 (warning)"), "{}", parts[0]);
        assert!(parts[1].starts_with("`F`: moves one step forward"));
        assert_eq!(h.span, Some(span.start..span.start + 1));
    }

    #[test]
    fn a_code_written_in_a_comment_hovers_with_its_explanation() {
        let text = "/* see E0003 */\nderivation length: 2\naxiom: F\nF --> F+F\n";
        let c = compiled("plant.l", text);
        let code = nth(text, "E0003", 0);
        let h = hover(&c, code + 2).expect("a hover over the code");
        assert!(
            h.markdown
                .starts_with("E0003 (error): unexpected token\n\n"),
            "{}",
            h.markdown
        );
        assert_eq!(h.span, Some(code..code + 5));
        // A keyword, the word `see`: nothing to say.
        assert_eq!(hover(&c, nth(text, "derivation", 0) + 2), None);
        assert_eq!(hover(&c, nth(text, "see", 0)), None);
    }

    #[test]
    fn a_declared_name_hovers_with_what_its_front_end_says_of_it() {
        let text = "#define N 5\nLsystem: 1\nderivation length: 1\nAxiom: F(N)\nendlsystem\n";
        let c = compiled("plant.l", text);
        let n = nth(text, "N", 1);
        let h = hover(&c, n).expect("a hover over `N`");
        assert!(h.markdown.contains("`#define N 5`"), "{}", h.markdown);
        assert_eq!(h.span, Some(n..n + 1));
    }

    #[test]
    fn definitions_are_the_predecessors_and_references_every_place() {
        let c = compiled("plant.l", PLANT);
        let known = Knowledge::default();
        let f = nth(PLANT, "F", 0);
        let at = |k: usize| {
            let o = nth(PLANT, "F", k);
            o..o + 1
        };
        // `F` is written seven times: the axiom's, then three a line.
        assert_eq!(known.definitions(&c, f), [at(1), at(4)]);
        let every: Vec<Span> = (0..7).map(at).collect();
        assert_eq!(known.references(&c, f), every);
        // The same answers from any place `F` is written.
        assert_eq!(known.definitions(&c, at(6).start), [at(1), at(4)]);
        assert!(known
            .definitions(&c, nth(PLANT, "derivation", 0))
            .is_empty());
    }

    #[test]
    fn knowledge_may_be_shared_between_threads() {
        // A face serving requests on several threads keeps one per compile.
        fn shared<T: Send + Sync>() {}
        shared::<Knowledge>();
        shared::<HoverText>();
    }
}
