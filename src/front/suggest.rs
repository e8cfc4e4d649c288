//! "Did you mean …?" within a budget of work per file.
//!
//! A suggestion compares an unknown name with every name the file declares,
//! each comparison an edit distance that costs the product of the two
//! lengths. A file with thousands of names and thousands of unknown ones
//! made that quadratic: 20,000 STL rules each using an unknown rule took 77
//! s, the same in LinF two minutes. A front end asks a [`Suggester`] before
//! it gathers the candidates; once a file has spent [`SUGGESTION_BUDGET`],
//! its unknown names get no suggestion (the diagnostic is the same
//! otherwise).

use crate::diagnostics::nearest;

/// Pairs of characters a file may compare for suggestions: a few hundred
/// unknown names against a few hundred declared ones, some tens of
/// milliseconds.
pub const SUGGESTION_BUDGET: usize = 20_000_000;

/// What comparing with one candidate costs besides its pairs of
/// characters (in pairs: [`nearest`] lowercases each candidate).
const PER_CANDIDATE: usize = 16;

/// What one file has left to spend on suggestions.
#[derive(Debug)]
pub struct Suggester {
    left: usize,
}

impl Default for Suggester {
    fn default() -> Self {
        Suggester {
            left: SUGGESTION_BUDGET,
        }
    }
}

impl Suggester {
    /// Whether comparing a name of `len` bytes with `count` candidates of
    /// at most `longest` bytes fits in what is left, spending it if so.
    /// Asked before the candidates are gathered, which costs as much.
    pub fn afford(&mut self, len: usize, count: usize, longest: usize) -> bool {
        let pairs = len
            .saturating_add(1)
            .saturating_mul(longest.saturating_add(1));
        let cost = count.saturating_mul(pairs.saturating_add(PER_CANDIDATE));
        if cost > self.left {
            return false;
        }
        self.left -= cost;
        true
    }

    /// The candidates nearest to `name` ([`nearest`]), or none once the
    /// budget is spent.
    pub fn nearest<'a>(&mut self, name: &str, candidates: &[&'a str]) -> Vec<&'a str> {
        let longest = candidates.iter().map(|c| c.len()).max().unwrap_or(0);
        if !self.afford(name.len(), candidates.len(), longest) {
            return Vec::new();
        }
        nearest(name, candidates)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_stop_when_the_budget_is_spent() {
        let mut s = Suggester::default();
        assert_eq!(s.nearest("axim", &["axiom", "angle"]), ["axiom"]);
        // A comparison past what is left suggests nothing; smaller ones
        // still fit, until the budget is spent.
        let long = "x".repeat(10_000);
        let many: Vec<&str> = std::iter::repeat_n(long.as_str(), 1_000).collect();
        assert!(s.nearest(&long, &many).is_empty());
        assert_eq!(s.nearest("axim", &["axiom"]), ["axiom"]);
        // 1,000 candidates of 99 bytes for a name of 99: 10,016,000, once
        // within the 20 million less what was spent above.
        let spent = (0..).take_while(|_| s.afford(99, 1_000, 99)).count();
        assert_eq!(spent, 1);
        assert!(!s.afford(99, 1_000, 99));
        assert!(s.afford(0, 0, 0));
    }
}
