//! The program text as a rope: an edit costs a walk down a balanced tree of small chunks, not a
//! copy of the text, and a copy of the buffer (an undo step) shares every chunk it did not
//! change. Lines end at `\n`, `\r\n` or a lone `\r`, as the parser reads them.
//!
//! Code that wants the text as one `str` (the parser, find, save) gets it through
//! [`Buffer::as_str`] (or `Deref`): the flat copy is made on the first such call after an edit
//! and kept until the next edit, so it is made at most once per change, never per frame.

use std::borrow::Cow;
use std::cell::OnceCell;
use std::ops::Range;
use std::sync::Arc;

use ropey::Rope;

/// A rope holding the program text, with a flat copy made on demand.
#[derive(Clone, Default)]
pub struct Buffer {
    rope: Rope,
    /// The whole text as one string, made on demand and dropped by every edit.
    flat: OnceCell<Arc<String>>,
}

impl std::fmt::Debug for Buffer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Buffer")
            .field("bytes", &self.rope.len_bytes())
            .field("lines", &self.rope.len_lines())
            .finish()
    }
}

impl PartialEq for Buffer {
    fn eq(&self, other: &Self) -> bool {
        self.rope == other.rope
    }
}

impl From<String> for Buffer {
    fn from(text: String) -> Self {
        let rope = Rope::from_str(&text);
        let flat = OnceCell::new();
        let _ = flat.set(Arc::new(text));
        Buffer { rope, flat }
    }
}

impl From<&str> for Buffer {
    fn from(text: &str) -> Self {
        Buffer::from(text.to_string())
    }
}

impl From<Rope> for Buffer {
    fn from(rope: Rope) -> Self {
        Buffer {
            rope,
            flat: OnceCell::new(),
        }
    }
}

impl std::ops::Deref for Buffer {
    type Target = str;

    fn deref(&self) -> &str {
        self.as_str()
    }
}

impl Buffer {
    /// The rope (cheap to clone: clones share their chunks).
    pub fn rope(&self) -> &Rope {
        &self.rope
    }

    /// The whole text as one string: made on the first call after an edit (a copy of the
    /// text), then kept until the next edit.
    pub fn as_str(&self) -> &str {
        self.shared().as_str()
    }

    /// The whole text as a shared string (see [`Buffer::as_str`]).
    pub fn shared(&self) -> &Arc<String> {
        self.flat.get_or_init(|| Arc::new(self.rope.to_string()))
    }

    /// The text for an analysis: the flat copy when it exists (small programs, edited as one
    /// string), otherwise the rope, which the parser reads in place (no copy per edit).
    pub fn program_text(&self) -> crate::analysis::ProgramText {
        match self.flat.get() {
            Some(flat) => crate::analysis::ProgramText::Flat(Arc::clone(flat)),
            None => crate::analysis::ProgramText::Rope(self.rope.clone()),
        }
    }

    /// The whole text as a new string, copied from the flat copy when it exists and from the
    /// rope otherwise (one copy; the flat copy is not made and kept for it).
    pub fn to_text(&self) -> String {
        match self.flat.get() {
            Some(flat) => flat.as_ref().clone(),
            None => self.rope.to_string(),
        }
    }

    /// Whether the flat copy of the current text exists (for measuring that edits do not make
    /// one).
    pub fn is_flat(&self) -> bool {
        self.flat.get().is_some()
    }

    /// Length in bytes.
    pub fn len_bytes(&self) -> usize {
        self.rope.len_bytes()
    }

    /// Length in characters.
    pub fn len_chars(&self) -> usize {
        self.rope.len_chars()
    }

    /// Number of lines (an empty text, or one ending in a line ending, has an empty last line).
    /// A line ends at `\n`, `\r\n` or a lone `\r`, as the parser reads it.
    pub fn len_lines(&self) -> usize {
        self.rope.len_lines()
    }

    /// Number of lines as [`crate::commands::line_count`] counts them (a final newline ends
    /// the last line rather than starting one), without a pass over the text.
    pub fn line_count(&self) -> u32 {
        let lines = self.len_lines();
        let n = if lines > 1 && matches!(self.rope.char(self.len_chars() - 1), '\n' | '\r') {
            lines - 1
        } else {
            lines
        };
        u32::try_from(n).unwrap_or(u32::MAX)
    }

    /// The 0-based line of character `char` (clamped to the text).
    pub fn char_to_line(&self, char: usize) -> usize {
        self.rope.char_to_line(char.min(self.len_chars()))
    }

    /// The character where 0-based `line` starts (clamped to the text).
    pub fn line_to_char(&self, line: usize) -> usize {
        self.rope.line_to_char(line.min(self.len_lines()))
    }

    /// The byte offset of character `char` (clamped to the text).
    pub fn char_to_byte(&self, char: usize) -> usize {
        self.rope.char_to_byte(char.min(self.len_chars()))
    }

    /// The character at byte offset `byte` (clamped to the text).
    pub fn byte_to_char(&self, byte: usize) -> usize {
        self.rope.byte_to_char(byte.min(self.len_bytes()))
    }

    /// Characters of 0-based `line` without its line ending (`\n`, `\r\n`, `\r`).
    pub fn line_len_chars(&self, line: usize) -> usize {
        if line >= self.len_lines() {
            return 0;
        }
        let slice = self.rope.line(line);
        let mut n = slice.len_chars();
        if n > 0 && slice.char(n - 1) == '\n' {
            n -= 1;
            if n > 0 && slice.char(n - 1) == '\r' {
                n -= 1;
            }
        } else if n > 0 && slice.char(n - 1) == '\r' {
            n -= 1;
        }
        n
    }

    /// The text of 0-based `line` without its line ending (empty past the end).
    pub fn line_text(&self, line: usize) -> Cow<'_, str> {
        if line >= self.len_lines() {
            return Cow::Borrowed("");
        }
        let start = self.rope.line_to_char(line);
        let text: Cow<'_, str> = self
            .rope
            .slice(start..start + self.line_len_chars(line))
            .into();
        text
    }

    /// The characters `chars` (clamped to the text) as a string.
    pub fn slice(&self, chars: Range<usize>) -> String {
        let end = chars.end.min(self.len_chars());
        let start = chars.start.min(end);
        self.rope.slice(start..end).to_string()
    }

    /// Inserts `text` at character `at` (clamped to the text).
    pub fn insert(&mut self, at: usize, text: &str) {
        if text.is_empty() {
            return;
        }
        self.flat.take();
        self.rope.insert(at.min(self.len_chars()), text);
    }

    /// Removes the characters `chars` (clamped to the text).
    pub fn remove(&mut self, chars: Range<usize>) {
        let end = chars.end.min(self.len_chars());
        let start = chars.start.min(end);
        if start == end {
            return;
        }
        self.flat.take();
        self.rope.remove(start..end);
    }

    /// Replaces the characters `chars` with `text`; the character after the inserted text.
    pub fn replace(&mut self, chars: Range<usize>, text: &str) -> usize {
        let end = chars.end.min(self.len_chars());
        let start = chars.start.min(end);
        self.remove(start..end);
        self.insert(start, text);
        start + text.chars().count()
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
        if start >= end || end > self.rope.len_bytes() {
            return "";
        }
        if self.chunks.is_none() || start < self.chunk_start {
            self.seek(start);
        }
        while start >= self.chunk_start + self.chunk.len() {
            if !self.advance() {
                return "";
            }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_keep_the_rope_and_the_flat_copy_in_step() {
        let mut b = Buffer::from("G0 X1\nG1 Y2 F100\r\nM30");
        assert!(b.is_flat(), "made from a string, the string is kept");
        assert_eq!(b.len_lines(), 3);
        assert_eq!(b.line_text(1), "G1 Y2 F100");
        assert_eq!(b.line_len_chars(1), 10);
        assert_eq!(b.line_text(2), "M30");
        assert_eq!(b.line_text(9), "");
        b.insert(6, "N10 ");
        assert!(!b.is_flat(), "an edit drops the flat copy");
        assert_eq!(b.line_text(1), "N10 G1 Y2 F100");
        assert_eq!(&*b, "G0 X1\nN10 G1 Y2 F100\r\nM30");
        assert!(b.is_flat());
        b.remove(0..6);
        assert_eq!(b.as_str(), "N10 G1 Y2 F100\r\nM30");
        let after = b.replace(4..6, "G01");
        assert_eq!(after, 7);
        assert_eq!(b.as_str(), "N10 G01 Y2 F100\r\nM30");
        b.insert(1000, "\n");
        assert_eq!(b.len_lines(), 3);
        assert_eq!(b.line_text(2), "");
        b.remove(5..1000);
        assert_eq!(b.as_str(), "N10 G");
    }

    #[test]
    fn positions_convert_between_characters_bytes_and_lines() {
        let b = Buffer::from("(µm)\nG1 X1\n\nM30\n");
        assert_eq!(b.len_chars(), 16);
        assert_eq!(b.len_bytes(), 17);
        assert_eq!(b.char_to_byte(2), 3);
        assert_eq!(b.byte_to_char(3), 2);
        assert_eq!(b.char_to_line(4), 0);
        assert_eq!(b.char_to_line(5), 1);
        assert_eq!(b.line_to_char(3), 12);
        assert_eq!(
            b.len_lines(),
            5,
            "a last empty line after the final newline"
        );
        assert_eq!(b.char_to_line(10_000), 4);
        assert_eq!(b.slice(5..10), "G1 X1");
        assert_eq!(b.slice(15..99), "\n");
    }

    #[test]
    fn lines_are_counted_as_the_commands_count_them() {
        for text in [
            "",
            "\n",
            "G0",
            "G0\n",
            "G0\nG1",
            "G0\nG1\n\n",
            "\r\n",
            "G0\rG1",
            "G0\r",
            "G0\r\r\nG1\r\n",
        ] {
            assert_eq!(
                Buffer::from(text).line_count(),
                crate::commands::line_count(text),
                "{text:?}"
            );
        }
    }

    #[test]
    fn line_feeds_and_carriage_returns_end_lines_as_the_parser_reads_them() {
        let b = Buffer::from("G0\rX1\u{2028}Y2\u{85}\nM30\r\r\nM2");
        assert_eq!(b.len_lines(), 5);
        assert_eq!(b.line_text(0), "G0");
        assert_eq!(b.line_text(1), "X1\u{2028}Y2\u{85}");
        assert_eq!(b.line_text(2), "M30");
        assert_eq!(b.line_text(3), "");
        assert_eq!(b.line_text(4), "M2");
        assert_eq!(b.line_count(), 5);
    }

    #[test]
    fn a_copy_shares_the_text_and_does_not_see_later_edits() {
        let text: String = (0..10_000).map(|i| format!("G1 X{i}\n")).collect();
        let mut b = Buffer::from(text.clone());
        let before = b.clone();
        b.insert(0, "G90\n");
        assert_eq!(before.as_str(), text);
        assert_eq!(b.len_lines(), before.len_lines() + 1);
        assert_ne!(b, before);
        let mut undone = b.clone();
        undone.remove(0..4);
        assert_eq!(undone, before);
    }
}
