//! Deriving a system's word: the options of a run, the word with the
//! values its program's globals were left with, its symbols as narrow as
//! they were derived, or written straight to a stream.

use super::interpret::{answer_queries, MAX_MOVES};
use crate::diagnostics::{codes, Diagnostic};
use crate::eval::parametric::Globals;
use crate::eval::tree::{Tree, MAX_TREE_DEPTH};
use crate::eval::{self, DeriveOptions, Deriver, DEFAULT_MAX_SYMBOLS};
use crate::front::Front;
use crate::ir::{System, Word};
use std::io::Write;

/// Derives and writes the word as [`Front::word_text`] would, followed by a
/// newline. A context-free deterministic system whose notation spells words
/// by their symbols' names ([`Front::spells_words_by_name`]) is written
/// straight from its shared derivation tree ([`Tree::walk`]), in chunks,
/// without building the word; any other is derived, then written.
/// `progress` is called as [`derive_with_progress`] calls it. Write errors (a closed
/// pipe) end the writing quietly.
pub fn write_derived(
    front: &dyn Front,
    sys: &System,
    opts: &RunOptions,
    out: &mut dyn std::io::Write,
    mut progress: impl FnMut(u64, usize),
) -> Result<(), Diagnostic> {
    refuse_graph(sys)?;
    let dopts = opts.derive_options(sys);
    let by_name = front.spells_words_by_name();
    let tree = match by_name && dopts.steps <= MAX_TREE_DEPTH {
        true => Tree::new(sys),
        false => None,
    };
    let mut out = std::io::BufWriter::with_capacity(1 << 18, out);
    let names: Vec<&[u8]> = sys.symbols.iter().map(|(_, i)| i.name.as_bytes()).collect();
    if let Some(t) = tree {
        // Checks the limit before anything is written.
        let len = Deriver::new(sys).tree_len(&t, &dopts)?;
        let _ = t.walk(
            dopts.steps,
            |s| names[s.index()],
            |chunk| out.write_all(chunk),
        );
        progress(dopts.steps, len);
    } else if by_name && !sys.rewrites_modules() {
        // Plain symbols, kept as narrow as they were derived (a byte each
        // for most alphabets) and named a chunk at a time: no wider copy
        // of the word, no text of it but the chunks being written.
        let w = Deriver::new(sys).derive_symbols(&dopts, progress)?;
        write_names(&names, &w, opts.threads, &mut out);
    } else {
        let w = derive_with_progress(sys, opts, progress)?;
        if by_name && !w.has_params() {
            let w = eval::Symbols::Wide(w.0);
            write_names(&names, &w, opts.threads, &mut out);
        } else {
            let _ = out.write_all(front.word_text(sys, &w).as_bytes());
        }
    }
    let _ = out.write_all(b"\n");
    let _ = out.flush();
    Ok(())
}

/// E0305 for a system that is an instancing graph: it has no word to
/// derive, print or count.
pub(super) fn refuse_graph(sys: &System) -> Result<(), Diagnostic> {
    let Some(graph) = &sys.graph else {
        return Ok(());
    };
    let maps: usize = graph
        .symbols
        .iter()
        .map(|s| s.rule.as_ref().map_or(0, Vec::len))
        .sum();
    Err(Diagnostic::global(
        codes::GRAPH_NO_WORD,
        format!(
            "this system is an instancing graph ({} symbol{}, {maps} transform{}): it has no word",
            graph.symbols.len(),
            if graph.symbols.len() == 1 { "" } else { "s" },
            if maps == 1 { "" } else { "s" },
        ),
    )
    .with_help("draw it with `graftal render FILE -o OUT.png`; `graftal check FILE` checks it"))
}

/// Symbols named at a time by each thread writing a word: chunks big enough
/// that starting a thread costs little beside them, few enough that the
/// text held (a chunk's a thread) is small beside the word.
const NAMED_AT_ONCE: usize = 1 << 20;

/// Writes the names of `word`'s symbols one after the other, stopping at
/// the first write error (a closed pipe). A long word is named on up to
/// `threads` threads, a chunk each at a time, and the chunks' text written
/// in order: the same bytes on any number of threads. Naming Fig. 3.11a's
/// 9.24 M symbols took 25 ms on one thread, a sixth of its derivation.
fn write_names(names: &[&[u8]], word: &eval::Symbols, threads: usize, out: &mut dyn Write) {
    match word {
        eval::Symbols::Bytes(w) => write_named(names, w, |&s| usize::from(s), threads, out),
        eval::Symbols::Shorts(w) => write_named(names, w, |&s| usize::from(s), threads, out),
        eval::Symbols::Wide(w) => write_named(names, w, |s| s.index(), threads, out),
    }
}

/// [`write_names`] of a word of symbols that `index` numbers.
fn write_named<T: Sync>(
    names: &[&[u8]],
    word: &[T],
    index: impl Fn(&T) -> usize + Sync,
    threads: usize,
    out: &mut dyn Write,
) {
    // One byte a name (most alphabets): a table look-up a symbol.
    let byte: Option<Vec<u8>> =
        (names.iter().all(|n| n.len() == 1)).then(|| names.iter().map(|n| n[0]).collect());
    let name = |(chunk, text): (&[T], &mut Vec<u8>)| {
        text.clear();
        match &byte {
            Some(byte) => text.extend(chunk.iter().map(|s| byte[index(s)])),
            None => chunk
                .iter()
                .for_each(|s| text.extend_from_slice(names[index(s)])),
        }
    };
    let threads = crate::parallel::threads(threads)
        .min(word.len().div_ceil(NAMED_AT_ONCE))
        .max(1);
    let mut texts = vec![Vec::new(); threads];
    for batch in word.chunks(NAMED_AT_ONCE * threads) {
        let chunks = batch.chunks(NAMED_AT_ONCE).zip(texts.iter_mut());
        crate::parallel::on_own_threads(chunks, name);
        let named = batch.len().div_ceil(NAMED_AT_ONCE);
        if texts[..named].iter().any(|t| out.write_all(t).is_err()) {
            return;
        }
    }
}

/// How many symbols of `word` are written: STL's silent stem-level markers
/// (symbols with an empty name) are not counted.
pub(super) fn written_symbols(sys: &System, word: &Word) -> usize {
    let silent: Vec<bool> = sys.symbols.iter().map(|(_, i)| i.name.is_empty()).collect();
    if silent.iter().any(|&s| s) {
        word.0.iter().filter(|s| !silent[s.index()]).count()
    } else {
        word.len()
    }
}

/// Settings given on the command line.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Steps; `None` means the file's own derivation length, else 0.
    pub steps: Option<u64>,
    pub seed: u64,
    pub max_symbols: usize,
    /// The most turtle moves interpreted (see [`MAX_MOVES`]).
    pub max_moves: usize,
    /// Threads that derive; 0 for every core.
    pub threads: usize,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            steps: None,
            seed: 0,
            max_symbols: DEFAULT_MAX_SYMBOLS,
            max_moves: MAX_MOVES,
            threads: 0,
        }
    }
}

impl RunOptions {
    pub fn derive_options(&self, sys: &System) -> DeriveOptions {
        DeriveOptions::new(self.steps.or(sys.settings.steps).unwrap_or(0))
            .seed(self.seed)
            .max_symbols(self.max_symbols)
            .threads(self.threads)
    }
}

/// Derives the word, reporting progress after each step.
pub fn derive_with_progress(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<Word, Diagnostic> {
    derive_values(sys, opts, progress).map(|(w, _)| w)
}

/// Derives the word, reporting progress after each step, with the values
/// its program's globals and arrays were left with (what the homomorphism
/// reads when the word is drawn: [`crate::driver::interpret`]).
pub fn derive_values(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<(Word, Globals), Diagnostic> {
    let dopts = opts.derive_options(sys);
    // The module test alone ([`eval::plan`] would build the Deriver, and
    // its table, a second time): the plain methods are the Deriver's.
    if sys.rewrites_modules() {
        // The environment, if any, is asked at the start of each step (of
        // the word about to be rewritten), or after each step and of the
        // axiom (`after_each_step`): every call but the last, or all.
        let mut program = sys.environment.as_ref().map(crate::enviro::start);
        let after = sys.environment.as_ref().is_some_and(|e| e.after_each_step);
        return eval::parametric::derive(
            sys,
            &dopts,
            progress,
            &mut |w, values, last| match program.as_mut() {
                Some(p) if after || !last => answer_queries(sys, w, values, opts, Some(p.as_mut())),
                _ => answer_queries(sys, w, values, opts, None),
            },
        );
    }
    let word = Deriver::new(sys).derive(&dopts, progress)?;
    Ok((word, Globals::initial(&sys.program)))
}

/// Derives the word.
pub fn derive(sys: &System, opts: &RunOptions) -> Result<Word, Diagnostic> {
    derive_with_progress(sys, opts, |_, _| {})
}
/// Derives the word of a system without modules, its symbols as narrow as
/// the derivation held them (what a picture drawn streamed draws).
pub fn derive_symbols(
    sys: &System,
    opts: &RunOptions,
    progress: impl FnMut(u64, usize),
) -> Result<eval::Symbols, Diagnostic> {
    Deriver::new(sys).derive_symbols(&opts.derive_options(sys), progress)
}

#[cfg(test)]
mod tests {
    use super::{write_names, NAMED_AT_ONCE};
    use crate::eval::Symbols;
    use crate::ir::SymbolId;

    /// A word of two and a half chunks and more, named on 1 to 7 threads,
    /// with one-byte names and longer ones, in each width a word is kept:
    /// the names one after the other, as one thread naming each symbol in
    /// turn writes them.
    #[test]
    fn words_named_in_chunks_on_any_threads_are_their_names_in_order() {
        let len = NAMED_AT_ONCE * 5 / 2 + 17;
        let ids: Vec<u8> = (0..len).map(|i| ((i * 7 + i / 3) % 5) as u8).collect();
        let short: [&[u8]; 5] = [b"F", b"+", b"-", b"[", b"]"];
        let long: [&[u8]; 5] = [b"F", b"plus", b"", b"[", b"Apex"];
        for names in [short, long] {
            let want: Vec<u8> = ids
                .iter()
                .flat_map(|&s| names[s as usize])
                .copied()
                .collect();
            let words = [
                Symbols::Bytes(ids.clone()),
                Symbols::Shorts(ids.iter().map(|&s| u16::from(s)).collect()),
                Symbols::Wide(ids.iter().map(|&s| SymbolId(u32::from(s))).collect()),
            ];
            for word in &words {
                for threads in [1, 2, 3, 7] {
                    let mut out = Vec::new();
                    write_names(&names, word, threads, &mut out);
                    assert!(out == want, "{threads} threads");
                }
            }
        }
    }

    /// A pipe closed after the first chunk: writing stops there.
    #[test]
    fn naming_stops_at_the_first_write_error() {
        struct Closing(usize);
        impl std::io::Write for Closing {
            fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
                if self.0 > 0 {
                    return Err(std::io::ErrorKind::BrokenPipe.into());
                }
                self.0 += buf.len();
                Ok(buf.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let word = Symbols::Bytes(vec![0; NAMED_AT_ONCE * 4]);
        for threads in [1, 2] {
            let mut pipe = Closing(0);
            write_names(&[b"F"], &word, threads, &mut pipe);
            assert_eq!(pipe.0, NAMED_AT_ONCE, "{threads} threads");
        }
    }
}
