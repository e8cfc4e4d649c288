//! cpfg's `%`: after each step, each `%` removes itself and the rest of
//! its branch from the word.

use crate::ir::{SymbolId, Word};

/// Removes each `%` and the rest of its branch.
pub(super) fn cut(word: &mut Word, cut: SymbolId) {
    if !word.0.contains(&cut) {
        return;
    }
    let mask = cut_mask(&word.0, cut);
    let mut out = Word::new();
    for (i, _) in mask.iter().enumerate().filter(|(_, &c)| !c) {
        out.push(word.0[i], word.args(i));
    }
    *word = out;
}

/// Per symbol of `word`, whether a `%` (`cut`) removes it: the `%` itself
/// and the rest of its branch, up to the `]` that closes it.
pub fn cut_mask(word: &[SymbolId], cut: SymbolId) -> Vec<bool> {
    let mut mask = vec![false; word.len()];
    let mut i = 0;
    while i < word.len() {
        if word[i] != cut {
            i += 1;
            continue;
        }
        let mut depth = 0usize;
        while i < word.len() {
            match word[i] {
                SymbolId::OPEN => depth += 1,
                SymbolId::CLOSE if depth == 0 => break,
                SymbolId::CLOSE => depth -= 1,
                _ => {}
            }
            mask[i] = true;
            i += 1;
        }
    }
    mask
}
