//! The registry of diagnostic codes: each with its severity, a title and the
//! long explanation `graftal explain CODE` prints.
//!
//! Codes are stable: a code is never reused for another problem. `E` codes
//! are errors, `W` codes warnings. Ranges: `E00xx` lexing and parsing,
//! `E01xx` headers and settings, `E02xx` productions and axioms, `E03xx`
//! evaluation, `E04xx` LinF (`codes/linf.rs`), `E05xx` STL (`codes/stl.rs`), `E06xx`
//! translation (`codes/translate.rs`), `E07xx` Fractint (`codes/fractint.rs`),
//! `E080x`–`E082x` the cpfg preprocessor and side files (`codes/cpfg.rs`),
//! `E083x` the cpfg L-system language (`codes/cpfg_lsystem.rs`), `E090x`
//! graftal's own notation `.gft` (`codes/gft.rs`) and `E092x` its `graph`
//! blocks, `E097x` Smith (`codes/smith.rs`), `E10xx` the checks of
//! object-instancing graphs that every front end reading one reports
//! (`codes/graph.rs`), `E11xx` Fractint's IFS libraries (`codes/ifs.rs`);
//! `W00xx` general and pfg warnings, `W04xx` LinF, `W05xx` STL, `W06xx`
//! translation, `W07xx` Fractint, `W080x`–`W082x` cpfg, `W090x` `.gft`,
//! `W097x` Smith, `W10xx` object-instancing graphs, `W11xx` IFS.
//!
//! A code nothing emits any more is retired: its entry goes and its number
//! joins [`RETIRED`], never to be given again. `tests/it/stale_words.rs` holds
//! that every code registered here is emitted somewhere in `src/`.

use super::Severity;
use std::fmt;

/// A diagnostic code, e.g. `E0004`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Code(pub &'static str);

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl Code {
    pub fn severity(self) -> Severity {
        if self.0.starts_with('W') {
            Severity::Warning
        } else {
            Severity::Error
        }
    }

    /// The registry entry for this code.
    pub fn info(self) -> &'static CodeInfo {
        lookup(self.0).expect("every code used is registered")
    }
}

/// One entry of the registry.
pub struct CodeInfo {
    pub code: Code,
    pub title: &'static str,
    pub explanation: &'static str,
}

/// What `graftal explain CODE` prints: the code, its severity and title,
/// then its explanation.
pub fn explain_text(info: &CodeInfo) -> String {
    let severity = match info.code.severity() {
        Severity::Error => "error",
        Severity::Warning => "warning",
    };
    format!(
        "{} ({severity}): {}\n\n{}",
        info.code, info.title, info.explanation
    )
}

/// Declares codes: a constant for each and a registry slice `$registry`.
macro_rules! codes {
    ($registry:ident; $($name:ident = $code:literal, $title:literal, $expl:literal;)*) => {
        $(pub const $name: Code = Code($code);)*
        /// The codes declared in this file, in order.
        pub static $registry: &[crate::diagnostics::codes::CodeInfo] = &[
            $(crate::diagnostics::codes::CodeInfo { code: $name, title: $title, explanation: $expl },)*
        ];
    };
}

mod cpfg;
mod cpfg_lsystem;
mod fractint;
mod gft;
mod graph;
mod ifs;
mod linf;
mod smith;
mod stl;
mod translate;
pub use cpfg::*;
pub use cpfg_lsystem::*;
pub use fractint::*;
pub use gft::*;
pub use graph::*;
pub use ifs::*;
pub use linf::*;
pub use smith::*;
pub use stl::*;
pub use translate::*;

/// Codes no longer given, whose numbers stay unused: `E0010` ("notation
/// not supported") was given to cpfg files before graftal read cpfg.
pub const RETIRED: &[&str] = &["E0010"];

/// Every registered code: the general and pfg codes, then each front end's.
pub fn all() -> impl Iterator<Item = &'static CodeInfo> {
    GENERAL
        .iter()
        .chain(linf::LINF)
        .chain(stl::STL)
        .chain(translate::TRANSLATE)
        .chain(fractint::FRACTINT)
        .chain(cpfg::CPFG)
        .chain(cpfg_lsystem::CPFG_LSYSTEM)
        .chain(smith::SMITH)
        .chain(gft::GFT)
        .chain(graph::GRAPH)
        .chain(ifs::IFS)
}

codes! { GENERAL;
    FILE_TOO_LARGE = "E0011", "file too large",
"graftal reads source files of up to 8 MiB. L-system files are a few
kilobytes: a larger one is most likely a derived word or another kind of
file given by mistake.";

    NOT_TEXT = "E0012", "not a text file",
"The file is not text: it holds NUL bytes, or mostly bytes that are neither
printable characters nor white space (an image, a program, compressed
data). graftal reads L-system notations, which are plain text, and says so
once instead of reporting every byte.

Example:
    graftal check plant.png     <- give the `.l`, `.linf` or `.stl` file";

    EMPTY_FILE = "E0014", "empty file",
"The file holds nothing but white space (or nothing at all), so there is
no L-system to read. The same error is given in every notation.

Example:
    graftal check new.l      <- saved before anything was written in it";

    OTHER_NOTATION = "E0015", "file in another notation",
"The file was read in the notation its extension (or its content) points
to, and most of it did not read: errors over half its lines. Read in
another notation, it reads without an error. It is almost certainly a file
of that notation saved under another extension (a LinF file saved as
`.l`), so graftal says so once, instead of listing every error the wrong
reading finds; the note gives the first of them, in case the file is
meant to be in the first notation after all.

Example:
    graftal check snowflake.l     <- a LinF file

Write:
    graftal check snowflake.linf  (renamed), or --notation linf";

    GRAPH_UNBOUNDED = "E0016", "instancing graph without a picture",
"An instancing graph (a `.gft` `graph` block, an `.ifs` entry) is drawn
from its limit: what its rules give when applied forever. The limit exists
only when every cycle of rules shrinks what it places (its composed
transform is contractive), and there is something to draw only when a
symbol the axiom reaches carries a geometry (or no symbol does: then the
limit itself is drawn). Without either there is no picture; `graftal
check` names the cycle that does not shrink (E1001) or the symbol without
a geometry (E1002).

Example:
    A -> [scale 1.1](A)       <- grows forever

Write:
    A -> [scale 0.5](A) [translate (1, 0, 0) scale 0.5](A)";

    NESTED_TOO_DEEPLY = "E0013", "nested too deeply",
"graftal follows nesting (parentheses in expressions, brackets and braces,
branches of a structure, the levels of a derivation an emitter walks) to a
depth of at most 256 in every notation. The limit keeps every input within
the stack: a deeper file is almost always generated or damaged, and the
first place past the limit is reported.

Example:
    A(((((((((((...1...)))))))))))   <- 2000 parentheses deep

Flatten the expression, or split the structure into named parts.";

    INVALID_CHARACTER = "E0001", "invalid character",
"The file contains a control character (or another character that cannot be
an L-system symbol). Symbols are printable characters; tabs, spaces and line
breaks separate items.

Example:
    axiom: F\u{7}F      <- a BEL character hidden between the F's

Remove the character; most editors can show invisible characters.";

    UNTERMINATED_COMMENT = "E0002", "unterminated comment",
"A comment opened with /* is never closed with */, so the rest of the file
is swallowed by it.

Example:
    /* Koch island
    axiom: F+F+F+F

Close the comment:
    /* Koch island */";

    SYNTAX = "E0003", "unexpected token",
"The parser met something that does not fit where it stands. The message
says what was found and what could come instead. A pfg line is either a
header (`axiom: F+F`) or a production (`lc < pred > rc --> succ`).

Example:
    F --> F+F : : 0.5

The parser skips to the end of the line and keeps reading, so every error in
the file is reported in one run.";

    MISSING_ARROW = "E0004", "missing `-->`",
"A line that is not a header must be a production, and a production needs
the arrow `-->` between its predecessor (with contexts) and its successor.

Example:
    F   F+F-F      <- no arrow

Write:
    F --> F+F-F";

    MALFORMED_ARROW = "E0005", "malformed arrow",
"pfg writes the production arrow as `-->` (two hyphens and a greater-than
sign). `->`, `=>` and `→` are not accepted, because `-` and `>` are
themselves symbols in pfg.

Example:
    F -> F+F

Write:
    F --> F+F";

    MISPLACED_CONTEXT = "E0006", "misplaced `<` or `>`",
"A production has at most one `<` (ending the left context) and one `>`
(starting the right context), in that order, both before the arrow and with
something on each side (`*` stands for an empty context).

Example:
    a > b < c --> d      <- `>` before `<`
    < a --> b            <- nothing before `<`

Write:
    b < a > c --> d
    * < a --> b";

    UNEXPECTED_EOF = "E0007", "unexpected end of file",
"The file ends in the middle of an item: a production whose successor is
missing on the last line, or a comment or rule cut off by the end.

Example (last line of the file):
    F -->

Write the successor, or `*` for the empty successor:
    F --> *";

    MISSING_SUCCESSOR = "E0008", "missing successor",
"Nothing follows the arrow. An empty successor is written `*` (the
listing's convention), so that a missing one is not taken for an empty one.

Example:
    X -->

Write:
    X --> *";

    MISSING_PREDECESSOR = "E0009", "missing predecessor",
"A production needs a strict predecessor: the symbols it replaces. `*`
stands for an empty context or successor, never for an empty predecessor.

Example:
    --> F
    a < * --> b

Write:
    F --> FF";

    UNKNOWN_HEADER = "E0101", "unknown header",
"pfg files start with the headers of the Appendix A listing:
    derivation length: N
    angle factor: N
    scale factor: N
    axiom: STRING
    ignore: SYMBOLS
Any other `name:` line is not understood. Misspellings get a suggestion.
cpfg files get the same for their item keywords (`derivation length:`,
`axiom:`, `maximum depth:`, …).

Example:
    derivation lenght: 5

Write:
    derivation length: 5";

    BAD_HEADER_VALUE = "E0102", "malformed header value",
"The value of a header is not of the expected kind: `derivation length`,
`angle factor` and `scale factor` take whole numbers; `axiom` takes a
non-empty string of symbols.

Example:
    derivation length: five

Write:
    derivation length: 5";

    BAD_ANGLE_FACTOR = "E0103", "angle factor not a positive integer",
"The angle factor n gives the angle increment δ = 360°/n, so it must be a
whole number greater than zero. For δ = 22.5° write 16, for 60° write 6,
for 25.7° (≈ 360/14) write 14.

Example:
    angle factor: 0

Write:
    angle factor: 4      (δ = 90°)";

    NEGATIVE_STEPS = "E0104", "negative derivation length",
"The derivation length counts rewriting steps, so it cannot be negative.

Example:
    derivation length: -3

Write:
    derivation length: 3";

    MISSING_AXIOM = "E0105", "missing axiom",
"Every L-system needs an axiom, the word derivation starts from.

Example: a file with productions but no `axiom:` line.

Add one, after the angle and scale factors as in the listing:
    axiom: F+F+F+F";

    BRACKET_IN_PREDECESSOR = "E0201", "bracket in a predecessor or context",
"In pfg, brackets may appear only in successors and in the axiom (the
listing: \"Brackets can appear only in the production successor\"). Context
matching already skips whole branches, so a context never needs them.

Example:
    A < [B] --> C

Write:
    A < B --> C";

    UNBALANCED_SUCCESSOR = "E0202", "unbalanced brackets in a successor",
"Every `[` in a successor needs a matching `]` after it, and no `]` may close
a branch the successor did not open; otherwise the derived word would pop
the turtle's stack when it is empty.

Example:
    F --> F[+F

Write:
    F --> F[+F]";

    UNBALANCED_AXIOM = "E0203", "unbalanced brackets in the axiom",
"Every `[` in the axiom needs a matching `]` after it, and every `]` a `[`
before it.

Example:
    axiom: F[+F]]

Write:
    axiom: F[+F]";

    BAD_PROBABILITY = "E0204", "probability not positive",
"The weight after `:` in a stochastic production must be a number greater
than zero. The weights of productions with the same predecessor and contexts
are normalised, so 1 : 1 : 2 means 25%, 25%, 50%.

Example:
    F --> F[+F]F : 0

Write:
    F --> F[+F]F : 0.33";

    MISSING_WEIGHT = "E0205", "stochastic production without a weight",
"Productions with the same predecessor and contexts form one stochastic
choice when they carry weights (`: 0.33`). If some of them have a weight
and others do not, the choice is ambiguous.

Example:
    F --> F[+F]F : 0.5
    F --> F[-F]F

Give every alternative a weight:
    F --> F[-F]F : 0.5";

    TOO_MANY_SYMBOLS = "E0301", "derivation exceeds the symbol limit",
"The derived word would be longer than `--max-symbols` allows. L-systems
grow exponentially, and a few more steps can take more memory than the
machine has, so graftal stops with this error instead.

Use fewer steps (`-n`), or raise the limit with `--max-symbols N` if the
machine has the memory (each symbol takes 4 bytes, twice over).";

    TOO_MUCH_WORK = "E0302", "derivation takes too long",
"The derivation would rewrite more symbols, over all its steps, than the
work limit allows (20 times `--max-symbols`). This happens with a very
large derivation length on a word that keeps changing without growing,
e.g. `a --> b`, `b --> a` for a billion steps.

Use fewer steps (`-n`). A word that stops changing ends the derivation
early by itself.";

    GRAPH_NO_WORD = "E0305", "an instancing graph has no word",
"The system is an object-instancing graph (an IFS code, or Bekaert and
Willems' IFS code with restrictions): a figure made of transformed copies
of itself. It is never rewritten into a word of symbols, so there is
nothing for `derive` to print or for `stats` to count: draw it with
`graftal render FILE -o OUT.png`, and `graftal check FILE` checks its
maps.";

    DERIVE_WOULD_EXCEED_SYMBOLS = "W0301", "`derive` would stop at the symbol limit",
"`graftal check` derives the file as `graftal derive` would, and the word
would grow past the symbol limit (E0301 there). The file itself is valid,
so `check` says it as a warning: `derive` (and drawing segment by segment)
will stop with E0301 at this step, unless given fewer steps (`-n`) or a
higher `--max-symbols`. A context-free picture drawn from its shared
subtrees (`render`, `stats`) is not limited this way.";

    DERIVE_WOULD_TAKE_TOO_LONG = "W0302", "`derive` would take too long",
"`graftal check` derives the file as `graftal derive` would, and the
derivation would rewrite more symbols over all its steps than the work
limit allows (E0302 there). The file itself is valid, so `check` says it as
a warning: `derive` will stop with E0302 unless given fewer steps (`-n`).";

    TOO_MUCH_GEOMETRY = "E0303", "picture too large to draw",
"The derived word moves the turtle more times than graftal draws segment
by segment (30 million): every move becomes a segment or a point held in
memory, and drawing needs as much again. `derive` is not limited this way,
nor is a context-free system drawn in one colour and width, face on, up to
4096 steps: that is drawn from its shared subtrees, however many segments
its word has. The message says how many moves the word makes (at least,
where contexts and random choices decide), and a note how that is known.

Draw fewer steps with `-n`. Beyond a few million segments a picture shows
little more than at a step less.";

    COUNTS_TOO_LONG = "E0304", "counts too long to work out",
"`stats` counts a context-free system's symbols and segments exactly from
its shared derivation tree, without deriving the word: one level of sums a
step, of numbers that grow by about as many digits each step. A system
with many symbols, each rewritten into many others, at thousands of steps,
makes numbers of thousands of digits, and adding them up over every level
would take more than about half a second; graftal stops with this error
instead of giving a count that is not exact.

Count fewer steps with `-n`.";

    HEADER_ORDER = "W0001", "header out of the listing's order",
"The Appendix A program reads its headers in a fixed order: derivation
length, angle factor, scale factor, axiom, ignore. graftal accepts them in
any order, but the original program (and files meant for it) would not.

Example:
    axiom: F
    derivation length: 3

Write:
    derivation length: 3
    axiom: F";

    DUPLICATE_HEADER = "W0002", "header given twice",
"The same header appears more than once; the later value is used.

Example:
    angle factor: 4
    angle factor: 6";

    NOTHING_DRAWN = "W0003", "nothing is drawn",
"The derived word contains no symbol that draws (in pfg, `F` or a polygon),
so the picture is empty. This is not an error: a system can be meant only
for `derive`. Check the derivation length and the symbols the turtle
understands (F f + - | [ ] & ^ \\ / { } ! ').

A note names the likely cause, the first that applies: a stdlib entry
marked as a schema (a string example: `graftal list` shows which); a turtle
that only moves without drawing (`f`, as in a kolam: try `--spline`); a
derived word with no symbol that moves the turtle; no derivation steps.";

    BOX_TOO_LARGE = "W0010", "bounding box beyond floating point",
"`stats` gives the bounding box in turtle units as floating-point numbers,
and the box is larger than the largest of them (about 1.8e308): a figure
that grows by a factor each step gets there in a few hundred steps (the
Koch island, 4 times wider a step, from 512 on). The box is left out
(`null` in JSON) and the warning says about how wide it is; the counts are
exact whatever their size, and the picture of such a system is drawn all
the same, in a unit of its own, when it is drawn from shared subtrees.

Example:
    graftal stats std:koch-island -n 1000

Count fewer steps with `-n` for a box in numbers.";

    NEARLY_NOTHING_DRAWN = "W0009", "nearly nothing is drawn",
"What is drawn is under two pixels wide at the picture's view and size:
a line or a point, whatever the system's shape. A note names the likely
cause: the geometry lies in a plane seen edge-on (a 3D model drawn from
the side of its plane: the help names the `--view AZ,EL` that looks
straight at it), every segment lies on one line (a 2D system whose
turns cancel, or an angle that never turns off the line), or a picture
so long for its width that its width is lost at this `--size`.

Example:
    axiom: F&F&F        (pitched only: a figure in a vertical plane)
    rendered with --view 90,0, which looks along that plane";

    SCALE_RANGE = "W0004", "scale factor out of range",
"The scale factor is the share of the picture the figure fills, from 0 to
100. Values outside are clamped.

Example:
    scale factor: 150";

    MISSING_HEADER = "W0005", "header missing, default used",
"A header the listing expects is missing, so its default is used:
derivation length 0, angle factor 4 (δ = 90°), scale factor 100.

Example: a file without `angle factor:` draws with δ = 90°.";

    BRACKET_IGNORED = "W0007", "bracket in the ignore list",
"`[` and `]` cannot be ignored: context matching always skips whole
branches and enters the parent branch (the listing's `lcondiff` and
`rcondiff`). graftal drops brackets from `ignore:` and says so.

Example:
    ignore: +-[]

Write:
    ignore: +-";

    TEXT_AFTER_STAR = "W0008", "text after `*` is ignored",
"In a production, `*` stands for the empty string, and the Appendix A
listing reads *any* string that starts with `*` as empty: `*AB` is empty,
not the symbols `*AB`. graftal does the same and warns, because the text
after the `*` was probably meant to count.

Example:
    F --> *F

Write:
    F --> *      (empty)   or   F --> F";

    SHADOWED_PRODUCTION = "W0006", "production can never apply",
"An earlier production with the same predecessor and contexts always
matches first (the first production in file order wins), so this one is
never used.

Example:
    F --> FF
    F --> F+F      <- never applies";
}

/// Finds a code by name (case-insensitive).
pub fn lookup(code: &str) -> Option<&'static CodeInfo> {
    all().find(|c| c.code.0.eq_ignore_ascii_case(code))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_well_formed_and_explained() {
        let mut seen = std::collections::HashSet::new();
        for info in all() {
            assert!(seen.insert(info.code.0), "duplicate {}", info.code);
            assert!(!RETIRED.contains(&info.code.0), "{} is retired", info.code);
            let c = info.code.0;
            assert!(c.len() == 5 && (c.starts_with('E') || c.starts_with('W')));
            assert!(c[1..].chars().all(|d| d.is_ascii_digit()));
            assert!(!info.title.is_empty());
            assert!(info.explanation.len() > 60, "{c} explanation too short");
        }
    }

    #[test]
    fn severity_follows_the_prefix() {
        assert_eq!(MISSING_ARROW.severity(), Severity::Error);
        assert_eq!(HEADER_ORDER.severity(), Severity::Warning);
        assert_eq!(lookup("e0004").unwrap().code, MISSING_ARROW);
        assert!(lookup("E9999").is_none());
    }
}
