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
//!
//! Angles in radians print as people write them with [`radians`]: `2*pi`,
//! `pi/3`, `-3*pi/4`, when that text reads back as the same `f64`.
//!
//! A leaf: it imports nothing of the crate, so that the IR, which prints
//! a derived word's parameters by [`readable`], stands on it as every
//! front end and emitter does, without naming a notation.

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

/// The largest whole multiple `k` of `pi` (or of `pi/q`) [`radians`] writes.
pub const PI_MULTIPLE_MAX: u32 = 48;
/// The largest divisor `q` of `pi` [`radians`] writes.
pub const PI_DIVISOR_MAX: u32 = 24;

/// An angle in radians as people write it: `k*pi`, `pi/q` or `k*pi/q`
/// (k up to [`PI_MULTIPLE_MAX`], q up to [`PI_DIVISOR_MAX`]), else `c*pi`
/// with a short decimal `c` (`0.7639*pi`), else [`exact`]; a multiple of pi
/// only when it evaluates, left to right in `f64` as a LinF expression
/// does (`k*pi/q` is `(k × π) / q`), to `x` bit for bit, so that the text
/// reads back as the same angle.
pub fn radians(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return exact(x);
    }
    let sign = if x < 0.0 { "-" } else { "" };
    let v = x.abs();
    let pi = std::f64::consts::PI;
    for q in 1..=PI_DIVISOR_MAX {
        let k = (v * f64::from(q) / pi).round();
        if !(1.0..=f64::from(PI_MULTIPLE_MAX)).contains(&k) {
            continue;
        }
        let times = if k == 1.0 { pi } else { k * pi };
        let value = if q == 1 { times } else { times / f64::from(q) };
        if value == v {
            let times = if k == 1.0 {
                "pi".to_string()
            } else {
                format!("{k}*pi")
            };
            let over = if q == 1 {
                String::new()
            } else {
                format!("/{q}")
            };
            return format!("{sign}{times}{over}");
        }
    }
    // A short decimal coefficient, as in `0.7639*pi`.
    let c = v / pi;
    for digits in 1..=6 {
        let text = format!("{c:.digits$}");
        match text.parse::<f64>() {
            Ok(r) if r != 0.0 && r * pi == v => return format!("{sign}{}*pi", exact(r)),
            _ => {}
        }
    }
    exact(x)
}

/// An interval of radians as LinF writes it: `[0 2*pi]`.
pub fn radians_interval(lo: f64, hi: f64) -> String {
    format!("[{} {}]", radians(lo), radians(hi))
}

/// The number a text begins with, as C's `atof` (and `scanf`'s `%f`) read
/// it: the longest prefix that is a number (`100view.pnl` is 100); `None`
/// when it begins with none.
pub fn leading(t: &str) -> Option<f64> {
    let end = (1..=t.len())
        .rev()
        .find(|&k| t.is_char_boundary(k) && t[..k].parse::<f64>().is_ok())?;
    t[..end].parse().ok()
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

    /// Reads `text` as the LinF reader does: `[-]k*pi/q`, `c*pi` or a
    /// decimal, each operation in `f64` left to right.
    fn read_back(text: &str) -> f64 {
        let (negative, t) = match text.strip_prefix('-') {
            Some(t) => (true, t),
            None => (false, text),
        };
        let (times, over) = t.split_once('/').unwrap_or((t, ""));
        let pi = std::f64::consts::PI;
        let mut v = match times.strip_suffix("pi") {
            Some("") => pi,
            Some(k) => k.strip_suffix('*').unwrap().parse::<f64>().unwrap() * pi,
            None => times.parse().unwrap(),
        };
        if !over.is_empty() {
            v /= over.parse::<f64>().unwrap();
        }
        if negative {
            -v
        } else {
            v
        }
    }

    #[test]
    fn radians_are_written_as_multiples_of_pi() {
        let pi = std::f64::consts::PI;
        assert_eq!(radians(2.0 * pi), "2*pi");
        assert_eq!(radians(pi / 3.0), "pi/3");
        assert_eq!(radians(-pi / 2.0), "-pi/2");
        assert_eq!(radians(3.0 * pi / 4.0), "3*pi/4");
        assert_eq!(radians(pi), "pi");
        assert_eq!(radians(0.7639 * pi), "0.7639*pi");
        assert_eq!(radians(0.3), "0.3");
        assert_eq!(radians(1.0), "1");
        assert_eq!(radians(-0.0), "0");
        assert_eq!(radians_interval(0.0, 2.0 * pi), "[0 2*pi]");
        // Past the divisors written: no `/`.
        assert!(!radians(pi / 25.0).contains('/'), "{}", radians(pi / 25.0));
    }

    #[test]
    fn radians_read_back_to_the_same_bits() {
        let pi = std::f64::consts::PI;
        let mut values = vec![1e-300, 1e300, 0.1, 25.0f64.to_radians()];
        for q in 1..=30u32 {
            for k in -60..=60i32 {
                let times = f64::from(k) * pi;
                values.push(times / f64::from(q));
                values.push(f64::from(k) * (pi / f64::from(q)));
                values.push(f64::from(k) * std::f64::consts::TAU / f64::from(q));
            }
        }
        // Degrees of every turn fraction a pfg file can ask for, and
        // pseudo-random values.
        values.extend((1..=360).map(|d| f64::from(d).to_radians()));
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push((x >> 11) as f64 / (1u64 << 53) as f64 * 40.0 - 20.0);
        }
        for v in values {
            let text = radians(v);
            let back = read_back(&text);
            assert_eq!(back.to_bits(), (v + 0.0).to_bits(), "{v} as {text}");
        }
    }
}
