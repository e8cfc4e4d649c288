//! The Fractint lexers (logos).
//!
//! [`Token`] cuts a file into what its structure needs: line ends, `;`
//! comments (to the end of the line), `{`, `}`, `=` and runs of other
//! characters; every library notation shares it
//! ([`crate::front::library`]).
//!
//! [`Command`] cuts an axiom or rule body (already lowercased, as Fractint
//! lowercases every line) into commands: `/ \ @ c < >` take a number with up
//! to two `q` (square root) or `i` (inverse) prefixes, `@iq2` is one
//! command; every other character is a command or a plain symbol of its own.

use crate::ir::Span;
use logos::Logos;

pub use crate::front::library::{comment_spans, lex, Token};

/// One command of a body.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command<'src> {
    /// `/n \n @n cn <n >n`: the command character, prefixes and number.
    #[regex(r"[/\\@c<>][qi]{0,2}[0-9.]*")]
    WithNumber(&'src str),
    /// Any other character: `+ - | ! [ ] f g d m` or a plain symbol.
    #[regex(r"(?s).", priority = 0)]
    Char(&'src str),
}

/// The commands of `body` (lowercased) with their byte ranges in it.
pub fn commands(body: &str) -> Vec<(&str, Span)> {
    Command::lexer(body)
        .spanned()
        .filter_map(|(c, span)| match c {
            Ok(Command::WithNumber(s) | Command::Char(s)) => Some((s, span)),
            // Every character matches `Char`; kept total for safety.
            Err(()) => None,
        })
        .collect()
}

pub use crate::common::vocabulary::fractint_number as number;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_take_their_numbers() {
        let c: Vec<&str> = commands("f+\\30@iq2c12<2>1x/.5@")
            .iter()
            .map(|c| c.0)
            .collect();
        assert_eq!(
            c,
            ["f", "+", "\\30", "@iq2", "c12", "<2", ">1", "x", "/.5", "@"]
        );
    }

    #[test]
    fn numbers_follow_getnumber() {
        assert_eq!(number("\\30"), 30.0);
        assert_eq!(number("@q4"), 2.0);
        assert_eq!(number("@i4"), 0.25);
        assert!((number("@iq2") - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((number("@qi2") - 0.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(number("@1.5.3"), 1.5);
        assert_eq!(number("@"), 0.0);
        assert_eq!(number("@i0"), 0.0);
        assert_eq!(number("@."), 0.0);
    }
}
