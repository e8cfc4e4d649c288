//! graftal's random numbers, two kinds of them. A running stream is ChaCha8
//! (rand_chacha), seeded from a `u64`: parametric systems draw from it in
//! word order. A keyed draw ([`keyed`]) depends on its key alone: a
//! stochastic production's choice is keyed by seed, step and place in the
//! word, and an interval angle by seed and place, so a word rewritten or
//! drawn in pieces on any number of threads draws the same numbers. Both
//! are specified bit for bit, so a seed gives the same numbers on every
//! platform; floats are made from the top 53 bits of a `u64`, which is
//! exact and portable too.
//!
//! Every generator is made here, for a named [`Stream`]: one seed gives
//! independent streams for the derivation, the turtle and the homomorphism,
//! so drawing a picture never changes the word and vice versa.
//!
//! cpfg files draw instead from cpfg's own generator, the 48-bit linear
//! congruential generator of `erand48`/`drand48` ([`Lcg48`]), seeded as cpfg
//! seeds it, so that a seeded cpfg model grows the plant cpfg grows.

use rand_chacha::ChaCha8Rng;
use rand_core::{Rng as _, SeedableRng};

/// What a random stream is for. Each is a ChaCha stream of its own for the
/// same seed; the numbers are the streams' ids and never change (changing
/// one would change every stochastic picture).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stream {
    /// Rewriting: stochastic choices and guards (`p?s`), keyed; `ran()` in
    /// productions and blocks (and what `srand()` restarts), a stream.
    Derivation = 0,
    /// The turtle: interval angles drawn while drawing.
    Turtle = 1,
    /// cpfg's homomorphism: expressions evaluated for drawing only.
    Homomorphism = 2,
}

/// A seeded, portable random stream: graftal's own, or cpfg's.
#[derive(Clone, Debug)]
pub enum Rng {
    Portable(Box<ChaCha8Rng>),
    Cpfg(Lcg48),
}

impl Rng {
    /// The generator of `stream` for `seed`.
    pub fn new(seed: u64, stream: Stream) -> Self {
        let mut r = ChaCha8Rng::seed_from_u64(seed);
        r.set_stream(stream as u64);
        Rng::Portable(Box::new(r))
    }

    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        match self {
            Rng::Portable(r) => (r.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64),
            Rng::Cpfg(r) => r.next_f64(),
        }
    }
}

/// cpfg's generator: `X ← (a·X + c) mod 2^48` with the constants of
/// `drand48` (a = 0x5DEECE66D, c = 0xB), a draw being `X / 2^48` after the
/// step (exact in an `f64`, as glibc's `erand48` builds it).
/// A number in [0, 1) that depends only on `seed`, `stream`, `index` and
/// `draw` (a counter-based stream: SplitMix64's finaliser over the four),
/// so that what is drawn at a place in a word does not depend on what was
/// drawn before it: the turtle draws interval angles this way, keyed by
/// the module's index in the word and its draws there, and a word drawn
/// in pieces on any number of threads draws the same angles.
pub fn keyed(seed: u64, stream: Stream, index: u64, draw: u64) -> f64 {
    const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;
    fn mix(mut z: u64) -> u64 {
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    let key = mix(seed.wrapping_add(GOLDEN.wrapping_mul(stream as u64 + 1)));
    let at = mix(key ^ index.wrapping_mul(GOLDEN));
    let z = mix(at.wrapping_add(GOLDEN.wrapping_mul(draw + 1)));
    (z >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lcg48 {
    state: u64,
}

impl Lcg48 {
    const A: u64 = 0x5_DEEC_E66D;
    const C: u64 = 0xB;
    const MASK: u64 = (1 << 48) - 1;

    /// The state `seed48(s)` sets: `s[2]·2^32 + s[1]·2^16 + s[0]`.
    pub fn seed48(s: [u16; 3]) -> Lcg48 {
        Lcg48 {
            state: u64::from(s[2]) << 32 | u64::from(s[1]) << 16 | u64::from(s[0]),
        }
    }

    /// The state `srand48(seed)` sets: the seed's 32 bits above `0x330E`.
    pub fn srand48(seed: u32) -> Lcg48 {
        Lcg48 {
            state: u64::from(seed) << 16 | 0x330E,
        }
    }

    /// cpfg's stream for choosing among productions (`generate.c`'s
    /// `SelectProd`, libc's `drand48`): `seed48({seed, 0, 155})` for a
    /// `seed:` other than 0 (its low 16 bits), else libc's initial state (0
    /// in glibc).
    pub fn cpfg_choice(seed: u64) -> Lcg48 {
        match seed {
            0 => Lcg48 { state: 0 },
            s => Lcg48::seed48([s as u16, 0, 155]),
        }
    }

    /// The state after the next step.
    pub fn next_state(&mut self) -> u64 {
        self.state = Self::A.wrapping_mul(self.state).wrapping_add(Self::C) & Self::MASK;
        self.state
    }

    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        self.next_state() as f64 / (1u64 << 48) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_numbers_and_known_values() {
        let mut a = Rng::new(42, Stream::Derivation);
        let mut b = Rng::new(42, Stream::Derivation);
        let xs: Vec<f64> = (0..4).map(|_| a.next_f64()).collect();
        let ys: Vec<f64> = (0..4).map(|_| b.next_f64()).collect();
        assert_eq!(xs, ys);
        let f = Rng::new(1, Stream::Derivation).next_f64();
        let (Rng::Portable(x), Rng::Portable(y)) = (&mut a, &mut b) else {
            panic!("graftal's own stream")
        };
        assert_eq!(x.next_u64(), y.next_u64());
        assert!((0.0..1.0).contains(&f));
        // Streams differ.
        let turtle = Rng::new(42, Stream::Turtle).next_f64();
        assert_ne!(turtle, Rng::new(42, Stream::Derivation).next_f64());
        // The derivation's stream is ChaCha's default stream: `ran()`
        // draws what it drew before streams were named.
        let plain = ChaCha8Rng::seed_from_u64(42).next_u64();
        let ours = (plain >> 11) as f64 / (1u64 << 53) as f64;
        assert_eq!(Rng::new(42, Stream::Derivation).next_f64(), ours);
    }

    /// The generator against its published definition (POSIX `drand48`:
    /// a = 0x5DEECE66D, c = 0xB, m = 2^48, `srand48` putting the seed above
    /// 0x330E), stepped here with 128-bit arithmetic, and against values
    /// glibc's `drand48` gives.
    #[test]
    fn keyed_draws_depend_on_their_key_alone_and_spread_evenly() {
        let a = keyed(7, Stream::Turtle, 1000, 0);
        assert_eq!(a, keyed(7, Stream::Turtle, 1000, 0));
        for other in [
            keyed(8, Stream::Turtle, 1000, 0),
            keyed(7, Stream::Derivation, 1000, 0),
            keyed(7, Stream::Turtle, 1001, 0),
            keyed(7, Stream::Turtle, 1000, 1),
        ] {
            assert_ne!(a, other);
        }
        // Neighbouring keys give numbers spread over [0, 1): a tenth in
        // each tenth, within 1% of 100 000 draws.
        let mut tenths = [0u32; 10];
        for i in 0..100_000 {
            let u = keyed(0, Stream::Turtle, i, i % 2);
            assert!((0.0..1.0).contains(&u));
            tenths[(u * 10.0) as usize] += 1;
        }
        assert!(
            tenths.iter().all(|&n| (9_000..11_000).contains(&n)),
            "{tenths:?}"
        );
    }

    #[test]
    fn cpfg_s_generator_is_drand48() {
        let mut x: u128 = (7u128 << 16) | 0x330E;
        let mut g = Lcg48::srand48(7);
        for _ in 0..1000 {
            x = (0x5DEECE66D * x + 0xB) % (1u128 << 48);
            assert_eq!(g.next_state() as u128, x);
        }
        // glibc 2.x, printed with %.17g (the shortest digits that give the
        // same double here): srand48(0); drand48() twice;
        // srand48(1); drand48(); seed48({1, 0, 155}) (cpfg's `seed: 1`);
        // drand48().
        let mut zero = Lcg48::srand48(0);
        assert_eq!(zero.next_f64(), 0.17082803610628972);
        assert_eq!(zero.next_f64(), 0.749_901_980_484_963_8);
        assert_eq!(Lcg48::srand48(1).next_f64(), 0.041630344771878214);
        assert_eq!(Lcg48::cpfg_choice(1).next_f64(), 0.515_699_322_545_032_1);
        assert_eq!(Lcg48::cpfg_choice(1), Lcg48::seed48([1, 0, 155]));
        assert_eq!(Lcg48::seed48([1, 0, 155]).state, 155 << 32 | 1);
        // glibc starts from 0 when nothing seeded it: the first draw is c.
        assert_eq!(Lcg48::cpfg_choice(0).next_state(), 0xB);
    }
}
