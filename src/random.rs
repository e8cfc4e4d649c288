//! The one random generator graftal uses: ChaCha8 (rand_chacha), seeded from
//! a `u64`. ChaCha's output is specified bit for bit, so a seed gives the same
//! numbers on every platform; floats are made from the top 53 bits of a
//! `u64`, which is exact and portable too.
//!
//! Every generator is made here, for a named [`Stream`]: one seed gives
//! independent streams for the derivation, the turtle and the homomorphism,
//! so drawing a picture never changes the word and vice versa.

use rand_chacha::ChaCha8Rng;
use rand_core::{Rng as _, SeedableRng};

/// What a random stream is for. Each is a ChaCha stream of its own for the
/// same seed; the numbers are the streams' ids and never change (changing
/// one would change every stochastic picture).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stream {
    /// Rewriting: stochastic choices, guards (`p?s`), cpfg's `ran()` in
    /// productions and blocks (and what `srand()` restarts).
    Derivation = 0,
    /// The turtle: interval angles drawn while drawing.
    Turtle = 1,
    /// cpfg's homomorphism: expressions evaluated for drawing only.
    Homomorphism = 2,
}

/// A seeded, portable random stream.
#[derive(Clone, Debug)]
pub struct Rng(ChaCha8Rng);

impl Rng {
    /// The generator of `stream` for `seed`.
    pub fn new(seed: u64, stream: Stream) -> Self {
        let mut r = ChaCha8Rng::seed_from_u64(seed);
        r.set_stream(stream as u64);
        Rng(r)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_numbers_and_known_values() {
        let mut a = Rng::new(42, Stream::Derivation);
        let mut b = Rng::new(42, Stream::Derivation);
        let xs: Vec<u64> = (0..4).map(|_| a.next_u64()).collect();
        let ys: Vec<u64> = (0..4).map(|_| b.next_u64()).collect();
        assert_eq!(xs, ys);
        let f = Rng::new(1, Stream::Derivation).next_f64();
        assert!((0.0..1.0).contains(&f));
        // Streams differ.
        let turtle = Rng::new(42, Stream::Turtle).next_u64();
        assert_ne!(turtle, Rng::new(42, Stream::Derivation).next_u64());
        // The derivation's stream is ChaCha's default stream: stochastic
        // words stay what they were before streams were named.
        let plain = ChaCha8Rng::seed_from_u64(42).next_u64();
        assert_eq!(Rng::new(42, Stream::Derivation).next_u64(), plain);
    }
}
