//! A program's text as the analysis reads it: one shared string, or the editor's rope read in
//! place.

use std::borrow::Cow;
use std::sync::Arc;

use ropey::Rope;
use swarf_syntax::LineIndex;

/// A program's text as the analysis reads it: one shared string, or the editor's rope, which
/// is parsed and located in place so that an edit of a long program costs no copy of it.
#[derive(Debug, Clone)]
pub enum ProgramText {
    /// The whole text as one string.
    Flat(Arc<String>),
    /// The text as a rope (a clone shares its chunks).
    Rope(Rope),
}

/// A text borrowed from a [`ProgramText`] or a linked file.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Text<'a> {
    Flat(&'a str),
    Rope(&'a Rope),
}

impl From<String> for ProgramText {
    fn from(text: String) -> Self {
        ProgramText::Flat(Arc::new(text))
    }
}

impl ProgramText {
    /// Length in bytes.
    pub fn len(&self) -> usize {
        match self {
            ProgramText::Flat(text) => text.len(),
            ProgramText::Rope(rope) => rope.len_bytes(),
        }
    }

    /// The text borrowed.
    pub(crate) fn as_text(&self) -> Text<'_> {
        match self {
            ProgramText::Flat(text) => Text::Flat(text),
            ProgramText::Rope(rope) => Text::Rope(rope),
        }
    }

    /// Whether the text is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The text as one new string (for a linked file, which the program then holds).
    pub fn to_owned_string(&self) -> String {
        match self {
            ProgramText::Flat(text) => text.as_ref().clone(),
            ProgramText::Rope(rope) => String::from(rope),
        }
    }

    /// The text's pieces in order (the whole string, or the rope's chunks).
    pub fn chunks(&self) -> impl Iterator<Item = &str> {
        let (flat, rope) = match self {
            ProgramText::Flat(text) => (Some(text.as_str()), None),
            ProgramText::Rope(rope) => (None, Some(rope.chunks())),
        };
        flat.into_iter().chain(rope.into_iter().flatten())
    }

    /// The text of 0-based `line` as `lines` (the text's index) divides it, without its line
    /// ending; empty past the end.
    pub fn line(&self, lines: &LineIndex, line: usize) -> Cow<'_, str> {
        let len = self.len();
        let start = (lines.line_start(line) as usize).min(len);
        let end = if line + 1 < lines.line_count() {
            (lines.line_start(line + 1) as usize).clamp(start, len)
        } else {
            len
        };
        let text: Cow<'_, str> = match self {
            ProgramText::Flat(text) => Cow::Borrowed(text.get(start..end).unwrap_or_default()),
            ProgramText::Rope(rope) => rope
                .get_byte_slice(start..end)
                .map_or(Cow::Borrowed(""), Cow::from),
        };
        match text {
            Cow::Borrowed(t) => Cow::Borrowed(t.trim_end_matches(['\n', '\r'])),
            Cow::Owned(t) => Cow::Owned(t.trim_end_matches(['\n', '\r']).to_string()),
        }
    }
}

/// The lines of a rope for the parser ([`swarf_syntax::LineSource`]), read in place: a line
/// inside one chunk of the rope is borrowed from it, and only a line that straddles chunks is
/// copied, into a reused buffer. Lines are read forward from wherever the first one asked is.
pub struct RopeLines<'a> {
    rope: &'a Rope,
    /// The chunks after `chunk`.
    chunks: Option<ropey::iter::Chunks<'a>>,
    /// The chunk the last line was read from, and its byte offset in the text.
    chunk: &'a str,
    chunk_start: usize,
    /// A line that straddles chunks, joined.
    joined: &'a mut String,
}

impl<'a> RopeLines<'a> {
    /// Reads the lines of `rope`; `joined` is the buffer for lines that straddle chunks (kept
    /// by the caller so that it is reused from one run of lines to the next).
    pub fn new(rope: &'a Rope, joined: &'a mut String) -> Self {
        RopeLines {
            rope,
            chunks: None,
            chunk: "",
            chunk_start: 0,
            joined,
        }
    }

    /// Moves to the chunk holding byte `at` (the one that starts there when `at` is a boundary).
    fn seek(&mut self, at: usize) {
        if let Some((mut chunks, start, _, _)) = self.rope.get_chunks_at_byte(at) {
            self.chunk = chunks.next().unwrap_or("");
            self.chunk_start = start;
            self.chunks = Some(chunks);
        }
    }

    /// Moves to the chunk holding byte `at`, forward from the one at hand where it can; whether
    /// there is one.
    fn reach(&mut self, at: usize) -> bool {
        if self.chunks.is_none() || at < self.chunk_start {
            self.seek(at);
        }
        while at >= self.chunk_start + self.chunk.len() {
            if !self.advance() {
                return false;
            }
        }
        true
    }

    /// Moves to the next chunk; whether there is one.
    fn advance(&mut self) -> bool {
        match self.chunks.as_mut().and_then(Iterator::next) {
            Some(next) => {
                self.chunk_start += self.chunk.len();
                self.chunk = next;
                true
            }
            None => false,
        }
    }
}

impl swarf_syntax::LineSource for RopeLines<'_> {
    fn len(&self) -> usize {
        self.rope.len_bytes()
    }

    fn line(&mut self, start: usize, end: usize) -> &str {
        if start >= end || end > self.rope.len_bytes() || !self.reach(start) {
            return "";
        }
        let from = start - self.chunk_start;
        if end <= self.chunk_start + self.chunk.len() {
            return self.chunk.get(from..end - self.chunk_start).unwrap_or("");
        }
        self.joined.clear();
        self.joined.push_str(self.chunk.get(from..).unwrap_or(""));
        while self.chunk_start + self.chunk.len() < end && self.advance() {
            let take = (end - self.chunk_start).min(self.chunk.len());
            self.joined.push_str(self.chunk.get(..take).unwrap_or(""));
        }
        self.joined.as_str()
    }

    fn rest(&mut self, start: usize) -> &str {
        // The chunk's whole lines from `start` on, or else the line that straddles chunks.
        if start >= self.rope.len_bytes() || !self.reach(start) {
            return "";
        }
        let tail = self.chunk.get(start - self.chunk_start..).unwrap_or("");
        if let Some(end) = tail.rfind('\n') {
            return tail.get(..=end).unwrap_or("");
        }
        self.joined.clear();
        self.joined.push_str(tail);
        while self.advance() {
            let end = self.chunk.find('\n').map_or(self.chunk.len(), |i| i + 1);
            self.joined.push_str(self.chunk.get(..end).unwrap_or(""));
            if end < self.chunk.len() || self.chunk.ends_with('\n') {
                break;
            }
        }
        self.joined.as_str()
    }

    fn trimmed_rest(&mut self, offset: usize) -> Option<(usize, usize)> {
        let len = self.rope.len_bytes();
        let first = self.rope.try_byte_to_char(offset.min(len)).ok()?;
        let mut start = self.rope.char_to_byte(first);
        let mut chars = self.rope.chars_at(first);
        loop {
            let c = chars.next()?;
            if !c.is_whitespace() {
                break;
            }
            start += c.len_utf8();
        }
        let mut end = len;
        let mut back = self.rope.chars_at(self.rope.len_chars());
        while let Some(c) = back.prev() {
            if !c.is_whitespace() {
                break;
            }
            end -= c.len_utf8();
        }
        Some((start, end.max(start)))
    }
}
