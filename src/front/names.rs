//! The longest declared name at each place of a run of letters, for the
//! notations that write names side by side (LinF's `fgf` is `f g f`, STL's
//! `FR1` is `F R1`).
//!
//! Trying every length up to the longest name at every place costs the
//! square of that length per place: one declared name of 2,000 letters
//! and a string of 20,000 made a 22 KB file take 7 s. [`LongestNames`]
//! finds, for every place of a run at once, the longest name starting
//! there in time linear in the run: an Aho-Corasick automaton of the names
//! reversed, run over the run from its end. After reading `run[i..]`
//! backwards, the automaton's state is the longest suffix of what it read
//! that begins a reversed name; the longest reversed name ending there,
//! which is the longest name starting at `i`, is that state or its nearest
//! suffix that is a whole name, kept per state.

/// No state.
const NONE: u32 = u32::MAX;

/// An automaton over the declared names (see the module). A state's
/// transitions are a list through `sibling`, from `first`: names are made
/// of a few dozen letters, and a file of names has millions of states.
#[derive(Debug)]
pub struct LongestNames {
    /// Each state's first transition (a state), or [`NONE`].
    first: Vec<u32>,
    /// The next transition of the same state, or [`NONE`].
    sibling: Vec<u32>,
    /// The byte a state is reached by.
    byte: Vec<u8>,
    /// Each state's longest proper suffix that is a state.
    fail: Vec<u32>,
    /// The length of the longest name that is a suffix of each state's
    /// string (0 if none).
    longest: Vec<u32>,
}

impl LongestNames {
    pub fn new<'a>(names: impl IntoIterator<Item = &'a str>) -> Self {
        let mut a = LongestNames {
            first: vec![NONE],
            sibling: vec![NONE],
            byte: vec![0],
            fail: Vec::new(),
            longest: vec![0],
        };
        for name in names {
            let mut state = 0;
            for &b in name.as_bytes().iter().rev() {
                state = match a.step(state, b) {
                    Some(s) => s,
                    None => a.add(state, b),
                };
            }
            // Its length, for now: the suffixes are added below.
            a.longest[state as usize] = name.len() as u32;
        }
        a.link();
        a
    }

    fn add(&mut self, state: u32, b: u8) -> u32 {
        let s = self.first.len() as u32;
        self.first.push(NONE);
        self.sibling.push(self.first[state as usize]);
        self.byte.push(b);
        self.longest.push(0);
        self.first[state as usize] = s;
        s
    }

    fn step(&self, state: u32, b: u8) -> Option<u32> {
        let mut s = self.first[state as usize];
        while s != NONE {
            if self.byte[s as usize] == b {
                return Some(s);
            }
            s = self.sibling[s as usize];
        }
        None
    }

    /// The state for the longest proper suffix of `state`'s string
    /// followed by `b`, from the suffix links of shorter states.
    fn suffix_after(&self, mut state: u32, b: u8) -> u32 {
        loop {
            if let Some(s) = self.step(state, b) {
                return s;
            }
            if state == 0 {
                return 0;
            }
            state = self.fail[state as usize];
        }
    }

    /// Sets the suffix links, and each state's longest name among its
    /// suffixes, breadth first (a state's suffixes are shorter).
    fn link(&mut self) {
        self.fail = vec![0; self.first.len()];
        let mut queue = std::collections::VecDeque::from([0u32]);
        while let Some(u) = queue.pop_front() {
            let mut v = self.first[u as usize];
            while v != NONE {
                let b = self.byte[v as usize];
                let link = match u {
                    0 => 0,
                    _ => self.suffix_after(self.fail[u as usize], b),
                };
                let (vi, li) = (v as usize, link as usize);
                self.fail[vi] = link;
                if self.longest[vi] == 0 {
                    self.longest[vi] = self.longest[li];
                }
                queue.push_back(v);
                v = self.sibling[vi];
            }
        }
    }

    /// For each byte offset of `run`, the length in bytes of the longest
    /// name starting there (0 if none).
    pub fn longest_at(&self, run: &str) -> Vec<usize> {
        let mut out = vec![0; run.len()];
        let mut state = 0;
        for (i, &b) in run.as_bytes().iter().enumerate().rev() {
            state = self.suffix_after(state, b);
            out[i] = self.longest[state as usize] as usize;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The longest name at each place, tried length by length.
    fn by_trying(names: &[&str], run: &str) -> Vec<usize> {
        (0..run.len())
            .map(|i| {
                (1..=run.len() - i)
                    .rev()
                    .find(|&n| names.contains(&&run[i..i + n]))
                    .unwrap_or(0)
            })
            .collect()
    }

    #[test]
    fn finds_the_longest_name_at_each_place() {
        let cases: [(&[&str], &str); 5] = [
            (&["f", "g", "fg"], "fgfgf"),
            (&["f", "ff", "fff", "fgf"], "ffgffffgf"),
            (&["ab", "b", "bab", "abab"], "ababab"),
            (&["R1", "R12", "R2", "F"], "FR12R1R2FR"),
            (&[], "abc"),
        ];
        for (names, run) in cases {
            let n = LongestNames::new(names.iter().copied());
            assert_eq!(n.longest_at(run), by_trying(names, run), "{names:?} {run}");
        }
        // Pseudo-random names over two letters.
        let mut seed = 7u32;
        let mut letter = || {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            if (seed >> 16) & 1 == 0 {
                'a'
            } else {
                'b'
            }
        };
        let names: Vec<String> = (1..40)
            .map(|i| (0..1 + i % 7).map(|_| letter()).collect())
            .collect();
        let run: String = (0..300).map(|_| letter()).collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let n = LongestNames::new(names.iter().copied());
        assert_eq!(n.longest_at(&run), by_trying(&names, &run));
    }

    #[test]
    fn a_long_name_costs_nothing_where_it_does_not_match() {
        let long = format!("{}g", "f".repeat(100_000));
        let n = LongestNames::new(["f", long.as_str()]);
        let run = "f".repeat(1_000_000);
        let t = std::time::Instant::now();
        let at = n.longest_at(&run);
        assert!(at.iter().all(|&l| l == 1));
        assert!(t.elapsed() < std::time::Duration::from_secs(2));
    }
}
