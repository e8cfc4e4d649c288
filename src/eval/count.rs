//! Exact counts of what a derived word holds (symbols, segments, moves),
//! however large.
//!
//! A context-free system's counts are known without deriving the word
//! ([`super::tree::Tree::count`]): sums of products of the successors'
//! counts, one level per step. They grow exponentially — the Koch island's
//! segments are `4 · 8ⁿ`, past `u128` at 42 steps — and the tree goes to
//! 4096 steps, so a fixed width would saturate and print a wrong number.
//! Only addition and multiplication by a small factor are needed, and
//! printing in decimal: a few dozen lines, not a dependency.

use serde::{Serialize, Serializer};
use std::cmp::Ordering;
use std::fmt;

/// A natural number of any size: 64-bit limbs, least significant first,
/// with no zero limb at the top (zero has none).
#[derive(Debug, Default, PartialEq, Eq, Hash)]
pub struct Count(Vec<u64>);

// By hand, for `clone_from` to reuse the room it has: sums level by level
// overwrite the numbers of two levels before.
impl Clone for Count {
    fn clone(&self) -> Count {
        Count(self.0.clone())
    }
    fn clone_from(&mut self, source: &Count) {
        self.0.clone_from(&source.0);
    }
}

impl Count {
    pub fn zero() -> Count {
        Count(Vec::new())
    }

    /// Sets it to zero, keeping its room for the next sum.
    pub fn set_zero(&mut self) {
        self.0.clear();
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    /// How many 64-bit limbs it takes: the cost of adding it.
    pub fn limbs(&self) -> usize {
        self.0.len()
    }

    /// `self += x · k`.
    pub fn add_times(&mut self, x: &Count, k: u64) {
        if k == 0 || x.is_zero() {
            return;
        }
        if self.0.len() < x.0.len() {
            self.0.resize(x.0.len(), 0);
        }
        let mut carry: u128 = 0;
        for (i, limb) in self.0.iter_mut().enumerate() {
            let product = x.0.get(i).map_or(0, |&v| u128::from(v) * u128::from(k));
            // At most (2⁶⁴−1) + (2⁶⁴−1)² + (2⁶⁴−1) < 2¹²⁸: no overflow.
            let sum = u128::from(*limb) + product + carry;
            *limb = sum as u64;
            carry = sum >> 64;
            if carry == 0 && i >= x.0.len() {
                break;
            }
        }
        while carry > 0 {
            self.0.push(carry as u64);
            carry >>= 64;
        }
    }

    /// The value, when it fits in a `u128`.
    pub fn to_u128(&self) -> Option<u128> {
        match self.0[..] {
            [] => Some(0),
            [a] => Some(u128::from(a)),
            [a, b] => Some(u128::from(a) | u128::from(b) << 64),
            _ => None,
        }
    }

    /// The number of decimal digits it is written with.
    pub fn digits(&self) -> usize {
        self.to_string().len()
    }

    /// As people read it in a message: exact up to 15 digits, else the
    /// first two and the power of ten (`about 6.7e541`, cut, not rounded).
    pub fn short(&self) -> String {
        let digits = self.to_string();
        if digits.len() <= 15 {
            return digits;
        }
        format!(
            "about {}.{}e{}",
            &digits[..1],
            &digits[1..2],
            digits.len() - 1
        )
    }

    /// Divides by `d` in place, returning the remainder.
    fn div_rem(&mut self, d: u64) -> u64 {
        let mut rem: u128 = 0;
        for limb in self.0.iter_mut().rev() {
            let cur = rem << 64 | u128::from(*limb);
            *limb = (cur / u128::from(d)) as u64;
            rem = cur % u128::from(d);
        }
        while self.0.last() == Some(&0) {
            self.0.pop();
        }
        rem as u64
    }
}

impl From<u128> for Count {
    fn from(v: u128) -> Count {
        let mut c = Count(vec![v as u64, (v >> 64) as u64]);
        while c.0.last() == Some(&0) {
            c.0.pop();
        }
        c
    }
}

impl From<u64> for Count {
    fn from(v: u64) -> Count {
        Count::from(u128::from(v))
    }
}

impl PartialEq<u128> for Count {
    fn eq(&self, other: &u128) -> bool {
        self.to_u128() == Some(*other)
    }
}

impl Ord for Count {
    fn cmp(&self, other: &Count) -> Ordering {
        // No zero limb at the top: more limbs is larger.
        self.0
            .len()
            .cmp(&other.0.len())
            .then_with(|| self.0.iter().rev().cmp(other.0.iter().rev()))
    }
}

impl PartialOrd for Count {
    fn partial_cmp(&self, other: &Count) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Count {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(v) = self.to_u128() {
            return write!(f, "{v}");
        }
        // Groups of 19 digits, least significant first (10¹⁹ < 2⁶⁴).
        const GROUP: u64 = 10_000_000_000_000_000_000;
        let mut rest = self.clone();
        let mut groups = Vec::with_capacity(self.0.len() * 64 / 63 + 1);
        while !rest.is_zero() {
            groups.push(rest.div_rem(GROUP));
        }
        let mut groups = groups.iter().rev();
        if let Some(top) = groups.next() {
            write!(f, "{top}")?;
        }
        groups.try_for_each(|g| write!(f, "{g:019}"))
    }
}

/// A JSON number, whatever its size: JSON sets no limit on a number's
/// digits, and a reader that keeps integers exact (Python's `json`) reads
/// the count exactly. Up to `u128` it goes through the serializer's own
/// integers; beyond, as the digits themselves ([`serde_json`]'s raw value).
impl Serialize for Count {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.to_u128() {
            Some(v) if v <= u128::from(u64::MAX) => s.serialize_u64(v as u64),
            Some(v) => s.serialize_u128(v),
            None => {
                let raw = serde_json::value::RawValue::from_string(self.to_string())
                    .map_err(serde::ser::Error::custom)?;
                raw.serialize(s)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2^k, built by doubling.
    fn power_of_two(k: u32) -> Count {
        let mut c = Count::from(1u64);
        for _ in 0..k {
            let x = c.clone();
            c.add_times(&x, 1);
        }
        c
    }

    #[test]
    fn sums_and_products_carry_across_limbs() {
        let mut c = Count::from(u128::MAX);
        c.add_times(&Count::from(1u64), 1);
        assert_eq!(c, power_of_two(128));
        assert_eq!(c.to_u128(), None);
        assert_eq!(c.to_string(), "340282366920938463463374607431768211456");
        let mut d = Count::from(u64::MAX);
        d.add_times(&Count::from(u64::MAX), u64::MAX);
        // (2⁶⁴−1) + (2⁶⁴−1)² = 2⁶⁴ (2⁶⁴−1).
        assert_eq!(d.to_u128(), Some((u128::from(u64::MAX)) << 64));
        let mut z = Count::zero();
        z.add_times(&Count::zero(), 7);
        assert!(z.is_zero());
        assert_eq!(z.to_string(), "0");
    }

    #[test]
    fn decimal_digits_pad_each_group() {
        // 10^40 = 10^21 · 10^19: a middle group of zeros.
        let mut c = Count::from(10u128.pow(21));
        let x = c.clone();
        c = Count::zero();
        c.add_times(&x, 10u64.pow(19));
        let want = format!("1{}", "0".repeat(40));
        assert_eq!(c.to_string(), want);
        assert_eq!(c.digits(), 41);
        assert_eq!(c.short(), "about 1.0e40");
        assert_eq!(
            Count::from(999_999_999_999_999u64).short(),
            "999999999999999"
        );
        assert_eq!(
            power_of_two(200).to_string(),
            "1606938044258990275541962092341162602522202993782792835301376"
        );
    }

    #[test]
    fn order_is_numeric() {
        let big = power_of_two(130);
        assert_eq!(big.cmp(&Count::from(u128::MAX)), Ordering::Greater);
        assert!(Count::from(3u64) < Count::from(5u64));
        assert!(power_of_two(130) < power_of_two(131));
        let mut a = power_of_two(130);
        a.add_times(&Count::from(1u64), 1);
        assert!(a > power_of_two(130));
    }

    #[test]
    fn json_writes_every_count_as_a_number() {
        let json = |c: &Count| serde_json::to_string(c).unwrap();
        assert_eq!(json(&Count::from(42u64)), "42");
        assert_eq!(json(&Count::from(u128::MAX)), u128::MAX.to_string());
        assert_eq!(json(&power_of_two(200)), power_of_two(200).to_string());
    }
}
