//! Random pfg and LinF systems for the translation tests (tests/it/translate.rs,
//! tests/it/gft_roundtrip.rs).

/// A small deterministic generator for the random systems.
pub struct Gen(pub u64);

impl Gen {
    /// splitmix64.
    pub fn below(&mut self, n: usize) -> usize {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) % n as u64) as usize
    }
    pub fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len())]
    }
    /// A word over `alphabet` with balanced brackets.
    pub fn word(&mut self, alphabet: &[&str], len: usize, sep: &str) -> String {
        let mut out: Vec<String> = Vec::new();
        let mut open = 0;
        for _ in 0..len {
            match self.below(8) {
                0 => {
                    out.push("[".into());
                    open += 1;
                }
                1 if open > 0 => {
                    out.push("]".into());
                    open -= 1;
                }
                _ => out.push(self.pick(alphabet).to_string()),
            }
        }
        out.extend(std::iter::repeat_n("]".to_string(), open));
        out.join(sep)
    }
}

pub fn random_pfg(g: &mut Gen) -> String {
    let factor = [4, 6, 8, 12, 16][g.below(5)];
    let three_d = g.below(4) == 0;
    let mut alphabet = vec!["F", "F", "+", "-", "X", "Y", "A"];
    if g.below(3) == 0 {
        alphabet.push("f");
    }
    if g.below(4) == 0 {
        alphabet.push("|");
    }
    if three_d {
        alphabet.extend(["&", "^", "\\", "/"]);
    }
    let mut s =
        format!(
        "derivation length: {}\nangle factor: {factor}\nscale factor: 100\naxiom: {}\nignore: +-\n",
        g.below(4),
        {
            let n = 1 + g.below(4);
            let w = g.word(&alphabet, n, "");
            if w.is_empty() { "F".to_string() } else { w }
        }
    );
    for head in ["F", "X", "Y"] {
        if g.below(3) > 0 {
            let n = 1 + g.below(6);
            let succ = g.word(&alphabet, n, "");
            let succ = if succ.is_empty() { "*".into() } else { succ };
            s.push_str(&format!("{head} --> {succ}\n"));
        }
    }
    if g.below(5) == 0 {
        // A context: LinF and STL cannot express it.
        s.push_str("X < A --> AF\n");
    }
    s
}

pub fn random_linf(g: &mut Gen) -> String {
    let k = [2, 3, 4, 6][g.below(4)];
    let mut s = String::from("lines f g\nblanks b\n");
    s.push_str(&format!("angles (0, pi/{k})"));
    if g.below(3) == 0 {
        s.push_str(&format!(" t = (pi/{}, 0)", [2, 3][g.below(2)]));
    }
    if g.below(4) == 0 {
        s.push_str(" w = (0, [0 pi])");
    }
    s.push('\n');
    let mut alphabet = vec!["f", "g", "b", "+", "-", "x"];
    if s.contains("t =") {
        alphabet.push("+t");
    }
    if s.contains("w =") {
        alphabet.push("-w");
    }
    if g.below(3) == 0 {
        alphabet.push("0.5@");
    }
    if g.below(4) == 0 {
        alphabet.push("0.5?x");
    }
    let n = 1 + g.below(4);
    let axiom = g.word(&alphabet, n, " ");
    s.push_str(&format!("axiom f {axiom}\nrules\n"));
    for head in ["f", "g", "x"] {
        if g.below(3) > 0 {
            let n = 1 + g.below(6);
            let succ = g.word(&alphabet, n, " ");
            s.push_str(&format!("  {head} = {succ}\n"));
        }
    }
    if !s.contains("  x =") {
        s.push_str("  x = x\n");
    }
    s.push_str(&format!("#: steps {}\n", g.below(4)));
    s
}
