//! How numbers are printed for people, in one place for every front end
//! and emitter.
//!
//! Two rules, one per use:
//!
//! * [`exact`]: for text that is read back (emitted files). The shortest
//!   decimal that reads back as the same `f64`, in positional form
//!   (`0.1`, `25.714285714285715`, `1`), since not every target notation
//!   reads exponents. Nothing is lost.
//! * [`readable`]: for text that is only read by people (derived words).
//!   At most [`READABLE_DIGITS`] significant digits, so the artefacts of
//!   binary arithmetic disappear (`0.7000000000000001` prints `0.7`); a
//!   magnitude below [`NOISE_FLOOR`] prints `0`, since that is what
//!   cancellation leaves of a zero (`1 - 10 × 0.1` is `1.4e-16`); and a
//!   magnitude of 1e15 or more or below 1e-4 prints in exponent form
//!   (`2.5e-7`) instead of a row of zeros. The loss is at most half a unit
//!   in the 12th significant digit, or the value itself below the floor.

/// Significant digits [`readable`] keeps.
pub const READABLE_DIGITS: usize = 12;
/// Magnitudes below this print as `0` in [`readable`].
pub const NOISE_FLOOR: f64 = 1e-12;

/// `x` as the shortest positional decimal that reads back as the same
/// `f64` (`-0` as `0`).
pub fn exact(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    format!("{x}")
}

/// `x` as people write it: see the module documentation.
pub fn readable(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x.abs() < NOISE_FLOOR {
        return "0".to_string();
    }
    // `{:.11e}` rounds to 12 significant digits; reading it back and
    // printing the shortest form drops the trailing zeros.
    let rounded: f64 = format!("{x:.prec$e}", prec = READABLE_DIGITS - 1)
        .parse()
        .unwrap_or(x);
    let magnitude = rounded.abs();
    if (1e-4..1e15).contains(&magnitude) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

/// The degrees of one n-th of a turn, as the shortest positional decimal
/// that reads back as the same angle in radians (360/7 prints
/// `51.42857142857143`, 360/8 prints `45`).
pub fn turn_fraction_degrees(n: u64) -> String {
    degrees((std::f64::consts::TAU / n.max(1) as f64).max(f64::MIN_POSITIVE))
}

/// An angle in radians as the degrees people write: the shortest decimal
/// whose conversion to radians gives the angle back exactly.
pub fn degrees(radians: f64) -> String {
    let deg = radians.to_degrees();
    (0..=17)
        .map(|digits| format!("{deg:.digits$}").parse::<f64>().unwrap_or(deg))
        .find(|d| d.to_radians() == radians)
        .map_or_else(|| exact(deg), exact)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_round_trips_in_positional_form() {
        for x in [0.1, 25.714285714285715, 1.0, -2.5, 4e-15, 1e20, 1.0 / 3.0] {
            let s = exact(x);
            assert!(!s.contains('e'), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
        assert_eq!(exact(1.0), "1");
        assert_eq!(exact(-0.0), "0");
    }

    #[test]
    fn readable_drops_binary_artefacts() {
        assert_eq!(readable(0.1 + 0.2), "0.3");
        assert_eq!(readable(1.0 - 0.3), "0.7");
        assert_eq!(readable(360.0 / 14.0), "25.7142857143");
        assert_eq!(readable(2.0), "2");
        assert_eq!(readable(-1.5), "-1.5");
    }

    #[test]
    fn readable_prints_cancellation_residue_as_zero() {
        let mut x = 1.0;
        for _ in 0..10 {
            x -= 0.1;
        }
        assert_ne!(x, 0.0);
        assert_eq!(readable(x), "0");
        assert_eq!(readable(3.9968028886505635e-15), "0");
        assert_eq!(readable(-0.0), "0");
    }

    #[test]
    fn readable_uses_exponents_for_extreme_magnitudes() {
        assert_eq!(readable(2.5e-7), "2.5e-7");
        assert_eq!(readable(1e20), "1e20");
        assert_eq!(readable(0.00012), "0.00012");
        assert_eq!(readable(123456.0), "123456");
        assert_eq!(readable(f64::INFINITY), "inf");
    }

    #[test]
    fn degrees_are_shortest_that_read_back() {
        assert_eq!(turn_fraction_degrees(8), "45");
        assert_eq!(turn_fraction_degrees(4), "90");
        let s = turn_fraction_degrees(14);
        let back = s.parse::<f64>().unwrap().to_radians();
        assert_eq!(back, std::f64::consts::TAU / 14.0);
        assert_eq!(degrees(30f64.to_radians()), "30");
    }
}
