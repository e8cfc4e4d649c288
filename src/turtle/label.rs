//! cpfg's labels (`@L("format", p1, …)`): the text C's `printf` makes of
//! a format and numbers, as cpfg's `sprintf` makes it for `iGlLabel`.

use std::fmt::Write;

/// Widths and precisions beyond this are cut to it: a label is a few
/// characters, and `%1000000d` must not make a megabyte.
const MAX_FIELD: usize = 64;

/// The text `printf(format, values…)` writes, for the conversions a label
/// uses: `d i u o x X c e E f F g G s %`, with the flags `- + space 0 #`,
/// a width and a precision (`*` takes them from the values, as C does).
/// Length modifiers (`l`, `h`, `L`) are read and mean nothing: every value
/// is a number. A conversion with no value left prints 0; `%s` prints its
/// number as `%g` does.
pub fn printf(format: &str, values: &[f64]) -> String {
    let mut out = String::new();
    let mut next = values.iter().copied();
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        let mut spec = Spec::default();
        while let Some(&f) = chars.peek() {
            match f {
                '-' => spec.left = true,
                '+' => spec.plus = true,
                ' ' => spec.space = true,
                '0' => spec.zero = true,
                '#' => spec.alternate = true,
                _ => break,
            }
            chars.next();
        }
        spec.width = field(&mut chars, &mut next);
        if chars.peek() == Some(&'.') {
            chars.next();
            spec.precision = Some(field(&mut chars, &mut next).unwrap_or(0));
        }
        while matches!(chars.peek(), Some('l' | 'h' | 'L' | 'q' | 'j' | 'z' | 't')) {
            chars.next();
        }
        match chars.next() {
            Some('%') => out.push('%'),
            Some(conv) => {
                let v = next.next().unwrap_or(0.0);
                out.push_str(&spec.pad(convert(conv, v, &spec)));
            }
            None => out.push('%'),
        }
    }
    out
}

/// A width or precision: digits, or `*` for the next value.
fn field(
    chars: &mut std::iter::Peekable<std::str::Chars<'_>>,
    values: &mut impl Iterator<Item = f64>,
) -> Option<usize> {
    if chars.peek() == Some(&'*') {
        chars.next();
        let v = values.next().unwrap_or(0.0);
        return Some((v.max(0.0) as usize).min(MAX_FIELD));
    }
    let mut n: Option<usize> = None;
    while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
        n = Some((n.unwrap_or(0) * 10 + d as usize).min(MAX_FIELD));
        chars.next();
    }
    n
}

#[derive(Default)]
struct Spec {
    left: bool,
    plus: bool,
    space: bool,
    zero: bool,
    alternate: bool,
    width: Option<usize>,
    precision: Option<usize>,
}

/// A converted value: its sign and its digits, apart so that zeros pad
/// between them.
struct Converted {
    sign: &'static str,
    digits: String,
    /// Whether `0` pads it (numbers; not `c`, not infinities).
    numeric: bool,
}

impl Spec {
    fn sign(&self, negative: bool) -> &'static str {
        match (negative, self.plus, self.space) {
            (true, _, _) => "-",
            (false, true, _) => "+",
            (false, false, true) => " ",
            _ => "",
        }
    }

    fn pad(&self, c: Converted) -> String {
        let len = c.sign.len() + c.digits.chars().count();
        let width = self.width.unwrap_or(0);
        if len >= width {
            return format!("{}{}", c.sign, c.digits);
        }
        let fill = width - len;
        if self.left {
            format!("{}{}{}", c.sign, c.digits, " ".repeat(fill))
        } else if self.zero && c.numeric {
            format!("{}{}{}", c.sign, "0".repeat(fill), c.digits)
        } else {
            format!("{}{}{}", " ".repeat(fill), c.sign, c.digits)
        }
    }
}

fn convert(conv: char, v: f64, spec: &Spec) -> Converted {
    let precision = spec.precision.map(|p| p.min(MAX_FIELD));
    let number = |digits: String, negative: bool| Converted {
        sign: spec.sign(negative),
        digits,
        numeric: true,
    };
    if !v.is_finite() && conv != 'c' {
        let word = if v.is_nan() { "nan" } else { "inf" };
        let word = if conv.is_ascii_uppercase() {
            word.to_uppercase()
        } else {
            word.to_string()
        };
        return Converted {
            sign: spec.sign(v < 0.0),
            digits: word,
            numeric: false,
        };
    }
    match conv {
        'd' | 'i' | 'u' => {
            // C converts the float argument to an int: toward zero.
            let n = v.trunc();
            let mut digits = format!("{:.0}", n.abs());
            if let Some(p) = precision {
                digits = format!("{digits:0>p$}");
            }
            number(digits, n < 0.0)
        }
        'o' | 'x' | 'X' => {
            let n = v.trunc().abs().min(u64::MAX as f64) as u64;
            let digits = match conv {
                'o' => format!("{n:o}"),
                'x' => format!("{n:x}"),
                _ => format!("{n:X}"),
            };
            number(digits, v.trunc() < 0.0)
        }
        'c' => Converted {
            sign: "",
            digits: char::from_u32(v as u32).map_or(String::new(), |c| c.to_string()),
            numeric: false,
        },
        'f' | 'F' => number(
            format!("{:.*}", precision.unwrap_or(6), v.abs()),
            v.is_sign_negative() && v != 0.0,
        ),
        'e' | 'E' => {
            let s = exponential(v.abs(), precision.unwrap_or(6));
            let s = if conv == 'E' { s.to_uppercase() } else { s };
            number(s, v < 0.0)
        }
        'g' | 'G' | 's' => {
            let s = general(v.abs(), precision.unwrap_or(6), spec.alternate);
            let s = if conv == 'G' { s.to_uppercase() } else { s };
            number(s, v < 0.0)
        }
        other => Converted {
            sign: "",
            digits: format!("%{other}"),
            numeric: false,
        },
    }
}

/// `%e` of a non-negative finite number: `d.ddde±XX`.
fn exponential(v: f64, precision: usize) -> String {
    let s = format!("{v:.precision$e}");
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let mut out = String::from(mantissa);
    let _ = write!(out, "e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs());
    out
}

/// `%g` of a non-negative finite number: `%e` or `%f` by the exponent,
/// trailing zeros removed unless `#`.
fn general(v: f64, precision: usize, alternate: bool) -> String {
    let p = precision.max(1);
    let exp = if v == 0.0 {
        0
    } else {
        // The exponent after rounding to p significant digits.
        let e = format!("{:.*e}", p - 1, v);
        e.split_once('e')
            .and_then(|(_, x)| x.parse::<i32>().ok())
            .unwrap_or(0)
    };
    let s = if exp < -4 || exp >= p as i32 {
        exponential(v, p - 1)
    } else {
        format!("{:.*}", (p as i32 - 1 - exp).max(0) as usize, v)
    };
    if alternate {
        return s;
    }
    match s.split_once('e') {
        Some((m, e)) => format!("{}e{e}", trim_zeros(m)),
        None => trim_zeros(&s).to_string(),
    }
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::printf;

    /// Values C's printf gives (glibc).
    #[test]
    fn printf_writes_what_c_writes() {
        let cases: &[(&str, &[f64], &str)] = &[
            (" %.f", &[43.5], " 44"),
            (" %.f", &[42.5], " 42"),
            ("%d", &[-7.9], "-7"),
            ("%5.2f|%-6.1f|", &[1.23456, 2.0], " 1.23|2.0   |"),
            ("%05d %+d % d", &[42.0, 3.0, 3.0], "00042 +3  3"),
            (
                "%g %g %g %g",
                &[0.0001, 123456.0, 1234567.0, 0.5],
                "0.0001 123456 1.23457e+06 0.5",
            ),
            ("%e", &[12345.678], "1.234568e+04"),
            ("%.3G", &[0.000012345], "1.23E-05"),
            ("%x %X %o %c", &[255.0, 255.0, 8.0, 65.0], "ff FF 10 A"),
            ("100%% %s", &[2.5], "100% 2.5"),
            ("%*d", &[4.0, 7.0], "   7"),
            ("no value: %f", &[], "no value: 0.000000"),
            ("%ld %lf", &[3.0, 1.5], "3 1.500000"),
        ];
        for (format, values, expected) in cases {
            assert_eq!(printf(format, values), *expected, "{format}");
        }
    }

    /// Huge fields are cut, and nothing malformed panics.
    #[test]
    fn any_format_is_safe() {
        assert!(printf("%1000000d", &[1.0]).len() <= 64);
        assert!(printf("%.1000000f", &[1.0]).len() <= 70);
        for f in ["%", "%-", "%.", "%*", "%q", "%l", "%.*", "%ç"] {
            let _ = printf(f, &[f64::NAN, f64::INFINITY, -0.0]);
        }
        assert_eq!(printf("%f %d", &[f64::INFINITY, f64::NAN]), "inf nan");
    }
}
