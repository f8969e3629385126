//! Turning a file's bytes into text: UTF-8, GBK/GB18030 or Big5, detected.

use crate::{Diagnostic, Span};

/// The character encoding a program file was read with (and should be written back with).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Encoding {
    /// UTF-8 (ASCII files are UTF-8 too).
    #[default]
    Utf8,
    /// UTF-8 with a byte-order mark.
    Utf8Bom,
    /// GBK / GB18030 (Simplified Chinese).
    Gb18030,
    /// Big5 (Traditional Chinese).
    Big5,
}

impl Encoding {
    /// The name shown in the status bar and CLI.
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Utf8 => "UTF-8",
            Encoding::Utf8Bom => "UTF-8 BOM",
            Encoding::Gb18030 => "GB18030",
            Encoding::Big5 => "Big5",
        }
    }

    /// Encodes `text` back to bytes in this encoding.
    pub fn encode(self, text: &str) -> Vec<u8> {
        match self {
            Encoding::Utf8 => text.as_bytes().to_vec(),
            Encoding::Utf8Bom => {
                let mut out = vec![0xEF, 0xBB, 0xBF];
                out.extend_from_slice(text.as_bytes());
                out
            }
            Encoding::Gb18030 => encoding_rs::GB18030.encode(text).0.into_owned(),
            Encoding::Big5 => encoding_rs::BIG5.encode(text).0.into_owned(),
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
    if bytes.starts_with(&[0xEF, 0xBB, 0xBF]) {
        return decode(&bytes);
    }
    match String::from_utf8(bytes) {
        Ok(text) => plain(text, Encoding::Utf8),
        Err(e) => decode(e.as_bytes()),
    }
}

fn plain(text: String, encoding: Encoding) -> Decoded {
    Decoded {
        text,
        encoding,
        diagnostics: Vec::new(),
    }
}

fn lossy_utf8(mut bytes: &[u8]) -> Decoded {
    let mut text = String::with_capacity(bytes.len());
    let mut diagnostics = Vec::new();
    loop {
        match std::str::from_utf8(bytes) {
            Ok(valid) => {
                text.push_str(valid);
                break;
            }
            Err(err) => {
                let (valid, after) = bytes.split_at(err.valid_up_to());
                text.push_str(&String::from_utf8_lossy(valid));
                let bad_len = err.error_len().unwrap_or(after.len()).max(1);
                let start = text.len();
                text.push('\u{FFFD}');
                diagnostics.push(Diagnostic::error(
                    Span::new(start, text.len()),
                    "E-ENCODING",
                    format!(
                        "invalid byte sequence {} (not UTF-8, GB18030 or Big5); replaced with U+FFFD",
                        after
                            .iter()
                            .take(bad_len)
                            .map(|b| format!("0x{b:02X}"))
                            .collect::<Vec<_>>()
                            .join(" ")
                    ),
                ));
                bytes = after.get(bad_len..).unwrap_or_default();
            }
        }
    }
    Decoded {
        text,
        encoding: Encoding::Utf8,
        diagnostics,
    }
}
