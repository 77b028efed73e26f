//! Numbers as messages print them.

/// A number as error messages and outputs print it: the shortest text that reads back
/// as the same `f64`, in exponent notation (`1e300`, `2.5e-7`) when its magnitude is
/// at least 1e16 or below 1e-5, so that no value prints as hundreds of digits (Rust's
/// `Display` prints `1e300` with 301). `inf`, `-inf` and `NaN` as Rust writes them.
///
/// ```
/// use geotracks_metrics::Num;
/// assert_eq!(Num(1e300).to_string(), "1e300");
/// assert_eq!(Num(-2.5e-7).to_string(), "-2.5e-7");
/// assert_eq!(Num(0.25).to_string(), "0.25");
/// assert_eq!(Num(123456789.0).to_string(), "123456789");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        let a = x.abs();
        if !x.is_finite() || x == 0.0 || (1e-5..1e16).contains(&a) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Num;

    #[test]
    fn numbers_read_back_and_are_never_hundreds_of_digits() {
        for x in [
            1e300,
            -1e300,
            3.0e-7,
            0.1 + 0.2,
            7e15,
            1e16,
            123.456,
            5e-324,
        ] {
            let text = Num(x).to_string();
            assert!(text.len() < 30, "{text}");
            assert_eq!(text.parse::<f64>().unwrap(), x);
        }
        assert_eq!(Num(f64::INFINITY).to_string(), "inf");
        assert_eq!(Num(f64::NAN).to_string(), "NaN");
    }
}
