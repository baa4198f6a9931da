//! Numbers in messages: significant digits, never hundreds of fixed digits.
//!
//! Rust's `{}` prints an `f64` in full positional notation (`1e-16` as
//! `0.0000000000000001`, `1e50` with fifty digits). Error messages print their numbers
//! through [`Sig`] instead: six significant digits, positional for magnitudes in
//! [1e-3, 1e6), scientific otherwise, trailing zeros dropped.

use std::fmt;

/// An `f64` displayed with six significant digits (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sig(pub f64);

impl fmt::Display for Sig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if !x.is_finite() || x == 0.0 {
            return write!(f, "{x}");
        }
        let a = x.abs();
        if (1e-3..1e6).contains(&a) {
            // Digits after the point so that six significant digits show.
            let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
            let s = format!("{x:.decimals$}");
            let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.') } else { &s };
            f.write_str(s)
        } else {
            let s = format!("{x:.5e}");
            let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
            let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
            write!(f, "{mantissa}e{exponent}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Sig;

    #[test]
    fn six_significant_digits_and_no_long_runs() {
        let cases = [
            (1e-16, "1e-16"),
            (1e50, "1e50"),
            (-7.7e2, "-770"),
            (0.08, "0.08"),
            (2.0e4, "20000"),
            (1.234_567_89, "1.23457"),
            (123_456.789, "123457"),
            (1e6, "1e6"),
            (-1.1e23, "-1.1e23"),
            (0.000_999_9, "9.999e-4"),
            (0.0, "0"),
        ];
        for (x, want) in cases {
            assert_eq!(Sig(x).to_string(), want, "{x:e}");
        }
        assert_eq!(Sig(f64::NAN).to_string(), "NaN");
        for k in -300..300 {
            let s = Sig(1.234_567 * 10f64.powi(k)).to_string();
            assert!(s.len() <= 12, "{s}");
        }
    }
}
