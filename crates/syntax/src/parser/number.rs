//! Decimal numbers as the parser reads them, in one pass over the bytes.

/// A decimal number scanned from the text: `12`, `1.5`, `.5`, `3.` (no sign).
pub(super) struct Decimal {
    /// Byte offset just after it.
    pub(super) end: usize,
    /// Its value, as `str::parse::<f64>` gives it.
    pub(super) value: f64,
    /// Whether it has a decimal point.
    pub(super) has_point: bool,
    /// How many digits it has.
    pub(super) digits: usize,
}

/// Scans a decimal number at `pos` in one pass (the parser's hot path: every word). Up to 15
/// digits the mantissa and power of ten are exact f64s, so one division rounds correctly
/// (Clinger's fast path) and a whole number needs none; longer numbers go to the standard library.
#[inline(always)]
pub(super) fn scan_decimal(bytes: &[u8], pos: usize) -> Option<Decimal> {
    // The digits as one integer, the point left out (wrapping: past 15 digits it is unused).
    let mut mantissa: u64 = 0;
    let mut digits_from = |mut end: usize| {
        while let Some(&b) = bytes.get(end)
            && b.is_ascii_digit()
        {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
            end += 1;
        }
        end
    };
    let int_end = digits_from(pos);
    let has_point = bytes.get(int_end) == Some(&b'.');
    let end = digits_from(int_end + usize::from(has_point));
    let frac_digits = end - int_end - usize::from(has_point);
    let digits = int_end - pos + frac_digits;
    if digits == 0 {
        return None;
    }
    let value = match POW10.get(frac_digits) {
        // Below 10^15 the mantissa converts as a signed integer, exactly as unsigned.
        Some(_) if digits <= 15 && frac_digits == 0 => mantissa as i64 as f64,
        Some(&scale) if digits <= 15 => mantissa as i64 as f64 / scale,
        _ => std::str::from_utf8(&bytes[pos..end])
            .ok()
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(f64::NAN),
    };
    Some(Decimal {
        end,
        value,
        has_point,
        digits,
    })
}

/// The powers of ten that are exact f64s, by number of fraction digits.
const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

/// The sign at `pos` before a number: whether it is `-`, and where the number starts.
#[inline(always)]
pub(super) fn scan_sign(bytes: &[u8], pos: usize) -> (bool, usize) {
    // Without a branch: whether a number is negative is as good as random in a CAM program.
    let b = bytes.get(pos).copied().unwrap_or(0);
    let negative = b == b'-';
    (negative, pos + usize::from(negative | (b == b'+')))
}

/// `value`, a number scanned without its sign (so with no sign bit of its own), negated when
/// `negative` ([`scan_sign`]): without a branch, as the sign is read.
#[inline(always)]
pub(super) fn with_sign(value: f64, negative: bool) -> f64 {
    f64::from_bits(value.to_bits() | (u64::from(negative) << 63))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    #[test]
    fn fast_decimal_values_match_the_standard_parser() {
        for text in [
            "0",
            "1",
            "12.5",
            ".5",
            "3.",
            "0.001",
            "123456.789",
            "99999999",
            "0.1",
            "0.3",
            "2.675",
            "1234567890.12345",
            "12345678901234567890",
            "0.000000000000001",
            "1234567890123456.5",
        ] {
            let expected: f64 = text.parse().unwrap();
            let d = scan_decimal(text.as_bytes(), 0).unwrap();
            assert_eq!(d.value, expected, "{text}");
            assert_eq!(d.end, text.len());
            assert_eq!(d.has_point, text.contains('.'));
        }
        let d = scan_decimal(b"12.5.3X", 0).unwrap();
        assert_eq!((d.end, d.value, d.digits), (4, 12.5, 3));
        assert!(scan_decimal(b"X", 0).is_none());
        assert!(scan_decimal(b".", 0).is_none());
    }
}
