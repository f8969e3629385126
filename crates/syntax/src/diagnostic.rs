//! Diagnostics shared by every stage of the pipeline.

mod registry;

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

pub use registry::{DIAGNOSTICS, DiagnosticDef};

/// A byte range `start..end` into the program text.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// First byte of the range.
    pub start: u32,
    /// One past the last byte of the range.
    pub end: u32,
}

impl Span {
    /// Makes a span from byte offsets (offsets past `u32::MAX` are clamped).
    pub fn new(start: usize, end: usize) -> Self {
        let clamp = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        Span {
            start: clamp(start),
            end: clamp(end.max(start)),
        }
    }

    /// The span as a `usize` range, for slicing the text.
    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// The most characters of a program's text that a diagnostic quotes.
pub const EXCERPT_CHARS: usize = 40;

/// `text` as a diagnostic quotes it: at most [`EXCERPT_CHARS`] characters, then `…`, so that a
/// message stays short however long the line it quotes.
pub fn excerpt(text: &str) -> Cow<'_, str> {
    match text.char_indices().nth(EXCERPT_CHARS) {
        Some((at, _)) => Cow::Owned(format!("{}…", text.get(..at).unwrap_or_default())),
        None => Cow::Borrowed(text),
    }
}

crate::ast::named_enum! {
    /// How bad a diagnostic is: errors stop the affected block from running.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
    pub enum Severity;
    /// The lowercase name used in CLI output and the JS API.
    fn as_str;
    Note    "note"    "Information for the programmer; nothing is wrong.";
    Warning "warning" "The program runs, but probably not as intended.";
    Error   "error"   "The control would alarm or the block cannot be run.";
}

/// One problem found in a program, located by a byte span.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Where the problem is.
    pub span: Span,
    /// How bad it is.
    pub severity: Severity,
    /// A stable code such as `E-SYNTAX-CHAR`.
    pub code: &'static str,
    /// A sentence for the programmer.
    pub message: String,
}

impl Diagnostic {
    /// An error diagnostic.
    pub fn error(span: Span, code: &'static str, message: impl Into<String>) -> Self {
        Self::new(span, Severity::Error, code, message.into())
    }

    /// A warning diagnostic.
    pub fn warning(span: Span, code: &'static str, message: impl Into<String>) -> Self {
        Self::new(span, Severity::Warning, code, message.into())
    }

    /// A note diagnostic.
    pub fn note(span: Span, code: &'static str, message: impl Into<String>) -> Self {
        Self::new(span, Severity::Note, code, message.into())
    }

    /// The bytes the diagnostic holds, its own and its message's.
    pub(crate) fn held_bytes(&self) -> usize {
        size_of::<Diagnostic>() + self.message.capacity()
    }

    /// The one constructor; debug builds check `code` is registered with `severity`.
    fn new(span: Span, severity: Severity, code: &'static str, message: String) -> Self {
        debug_assert_eq!(
            DiagnosticDef::lookup(code).map(|d| d.severity),
            Some(severity),
            "diagnostic code {code} is not registered as {severity} in diagnostic/registry.rs"
        );
        Diagnostic {
            span,
            severity,
            code,
            message,
        }
    }
}
