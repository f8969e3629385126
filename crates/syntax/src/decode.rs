//! Turning a file's bytes into text: UTF-8, GBK/GB18030 or Big5, detected; UTF-16 and UTF-32
//! by their byte-order mark.

use crate::{Diagnostic, Span};

/// The largest file read as a program, a setup or a called program (256 MiB): a larger one is
/// refused before it is read (the CLI's `--max-file-mb`, the app's open).
pub const MAX_FILE_BYTES: u64 = 256 << 20;

crate::ast::named_enum! {
    /// The character encoding a program file was read with (and should be written back with).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
    pub enum Encoding;
    /// The name shown in the status bar and CLI.
    fn name;
    #[default]
    Utf8    "UTF-8"     "UTF-8 (ASCII files are UTF-8 too).";
    Utf8Bom "UTF-8 BOM" "UTF-8 with a byte-order mark.";
    Gb18030 "GB18030"   "GBK / GB18030 (Simplified Chinese).";
    Big5    "Big5"      "Big5 (Traditional Chinese).";
    Utf16Le "UTF-16LE"  "UTF-16, little-endian, with a byte-order mark (Windows \"Unicode\").";
    Utf16Be "UTF-16BE"  "UTF-16, big-endian, with a byte-order mark.";
    Utf32Le "UTF-32LE"  "UTF-32, little-endian, with a byte-order mark.";
    Utf32Be "UTF-32BE"  "UTF-32, big-endian, with a byte-order mark.";
}

/// The byte-order marks of the UTF-16 and UTF-32 encodings, longest first (UTF-32LE's starts
/// with UTF-16LE's).
const WIDE_BOMS: [(&[u8], Encoding); 4] = [
    (&[0xFF, 0xFE, 0x00, 0x00], Encoding::Utf32Le),
    (&[0x00, 0x00, 0xFE, 0xFF], Encoding::Utf32Be),
    (&[0xFF, 0xFE], Encoding::Utf16Le),
    (&[0xFE, 0xFF], Encoding::Utf16Be),
];

impl Encoding {
    /// Encodes `text` back to bytes in this encoding.
    pub fn encode(self, text: &str) -> Vec<u8> {
        match self {
            Encoding::Utf8 => text.as_bytes().to_vec(),
            Encoding::Utf8Bom => [&[0xEF, 0xBB, 0xBF], text.as_bytes()].concat(),
            Encoding::Gb18030 => encoding_rs::GB18030.encode(text).0.into_owned(),
            Encoding::Big5 => encoding_rs::BIG5.encode(text).0.into_owned(),
            Encoding::Utf16Le | Encoding::Utf16Be => {
                let le = self == Encoding::Utf16Le;
                std::iter::once(0xFEFF)
                    .chain(text.encode_utf16())
                    .flat_map(|u| if le { u.to_le_bytes() } else { u.to_be_bytes() })
                    .collect()
            }
            Encoding::Utf32Le | Encoding::Utf32Be => {
                let le = self == Encoding::Utf32Le;
                std::iter::once(0xFEFF)
                    .chain(text.chars().map(u32::from))
                    .flat_map(|c| if le { c.to_le_bytes() } else { c.to_be_bytes() })
                    .collect()
            }
        }
    }
}

/// Decoded text, the encoding it was found in, and any problems with the bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct Decoded {
    /// The program text.
    pub text: String,
    /// The detected encoding.
    pub encoding: Encoding,
    /// Problems with the bytes (spans are into `text`).
    pub diagnostics: Vec<Diagnostic>,
}

/// Decodes a program file: UTF-8 when valid, otherwise GB18030 or Big5 when the bytes are valid
/// in one of them, otherwise UTF-8 with each invalid byte replaced and reported.
pub fn decode(bytes: &[u8]) -> Decoded {
    for (bom, encoding) in WIDE_BOMS {
        if let Some(rest) = bytes.strip_prefix(bom) {
            return wide(rest, encoding);
        }
    }
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF])
        && let Ok(text) = std::str::from_utf8(rest)
    {
        return plain(text.to_string(), Encoding::Utf8Bom);
    }
    if let Ok(text) = std::str::from_utf8(bytes) {
        return plain(text.to_string(), Encoding::Utf8);
    }
    for (enc, which) in [
        (encoding_rs::GB18030, Encoding::Gb18030),
        (encoding_rs::BIG5, Encoding::Big5),
    ] {
        if let Some(text) = enc.decode_without_bom_handling_and_without_replacement(bytes) {
            return plain(text.into_owned(), which);
        }
    }
    lossy_utf8(bytes)
}

/// [`decode`] for bytes the caller owns: valid UTF-8 without a byte-order mark (the usual
/// file) becomes the text without being copied.
pub fn decode_owned(bytes: Vec<u8>) -> Decoded {
    if bytes.starts_with(&[0xEF, 0xBB, 0xBF])
        || WIDE_BOMS.iter().any(|(bom, _)| bytes.starts_with(bom))
    {
        return decode(&bytes);
    }
    match String::from_utf8(bytes) {
        Ok(text) => plain(text, Encoding::Utf8),
        Err(e) => decode(e.as_bytes()),
    }
}

/// Decodes UTF-16 or UTF-32 text (after its byte-order mark); each unit that is no character is
/// replaced with U+FFFD and reported.
fn wide(bytes: &[u8], encoding: Encoding) -> Decoded {
    let width = match encoding {
        Encoding::Utf16Le | Encoding::Utf16Be => 2,
        _ => 4,
    };
    let le = matches!(encoding, Encoding::Utf16Le | Encoding::Utf32Le);
    let units = bytes.chunks_exact(width).map(|c| {
        let byte = |u: u32, b: &u8| u << 8 | u32::from(*b);
        if le {
            c.iter().rev().fold(0, byte)
        } else {
            c.iter().fold(0, byte)
        }
    });
    let mut chars: Vec<Option<char>> = if width == 2 {
        let units = units.map(|u| u16::try_from(u).unwrap_or(0xFFFD));
        char::decode_utf16(units).map(Result::ok).collect()
    } else {
        units.map(char::from_u32).collect()
    };
    // A last unit cut short is no character either.
    if !bytes.len().is_multiple_of(width) {
        chars.push(None);
    }
    let mut decoded = plain(String::with_capacity(chars.len()), encoding);
    for c in chars {
        match c {
            Some(c) => decoded.text.push(c),
            None => decoded.replaced(format!("invalid {} unit", encoding.name())),
        }
    }
    decoded
}

fn plain(text: String, encoding: Encoding) -> Decoded {
    Decoded {
        text,
        encoding,
        diagnostics: Vec::new(),
    }
}

impl Decoded {
    /// Adds U+FFFD to the text for what `what` describes, and reports it.
    fn replaced(&mut self, what: String) {
        let start = self.text.len();
        self.text.push('\u{FFFD}');
        let message = format!("{what}; replaced with U+FFFD");
        let error = Diagnostic::error(Span::new(start, self.text.len()), "E-ENCODING", message);
        self.diagnostics.push(error);
    }
}

fn lossy_utf8(mut bytes: &[u8]) -> Decoded {
    let mut decoded = plain(String::with_capacity(bytes.len()), Encoding::Utf8);
    loop {
        match std::str::from_utf8(bytes) {
            Ok(valid) => {
                decoded.text.push_str(valid);
                return decoded;
            }
            Err(err) => {
                let (valid, after) = bytes.split_at(err.valid_up_to());
                decoded.text.push_str(&String::from_utf8_lossy(valid));
                let bad_len = err.error_len().unwrap_or(after.len()).max(1);
                let bad = after.get(..bad_len).unwrap_or(after);
                let bad = (bad.iter().map(|b| format!("0x{b:02X}")))
                    .collect::<Vec<_>>()
                    .join(" ");
                let message = format!("invalid byte sequence {bad} (not UTF-8, GB18030 or Big5)");
                decoded.replaced(message);
                bytes = after.get(bad_len..).unwrap_or_default();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn utf16_and_utf32_with_a_byte_order_mark_are_read_and_written_back() {
        let text = "G0 X1. (铣刀 ø6)\r\nM30 𝄞\n";
        for encoding in [
            Encoding::Utf16Le,
            Encoding::Utf16Be,
            Encoding::Utf32Le,
            Encoding::Utf32Be,
        ] {
            let bytes = encoding.encode(text);
            let d = decode(&bytes);
            assert_eq!(d.text, text, "{encoding:?}");
            assert_eq!(d.encoding, encoding);
            assert!(d.diagnostics.is_empty());
            assert_eq!(decode_owned(bytes).text, text);
        }
    }

    #[test]
    fn broken_wide_text_is_replaced_and_reported() {
        // A lone surrogate, then a last unit cut short.
        let d = decode(&[0xFF, 0xFE, b'G', 0, 0x00, 0xD8, b'1', 0, b'X']);
        assert_eq!(d.text, "G\u{FFFD}1\u{FFFD}");
        assert_eq!(d.diagnostics.len(), 2);
        assert!(d.diagnostics.iter().all(|x| x.code == "E-ENCODING"));
    }
}
