//! The program text as a rope: an edit copies no text, and a copy of the buffer (an undo step)
//! shares the chunks it did not change. Lines end at `\n`, `\r\n` or a lone `\r`, as the parser
//! reads them. [`Buffer::as_str`] makes a flat copy at most once per change, never per frame.

use std::borrow::Cow;
use std::cell::OnceCell;
use std::ops::Range;
use std::sync::Arc;

use ropey::Rope;

/// 0-based `line` of `rope` without its line ending (`\n`, `\r\n` or `\r`), if it has one.
pub(crate) fn line_of(rope: &Rope, line: usize) -> Option<ropey::RopeSlice<'_>> {
    let slice = rope.get_line(line)?;
    let n = slice.len_chars();
    let n = n - usize::from(n > 0 && slice.char(n - 1) == '\n');
    Some(slice.slice(..n - usize::from(n > 0 && slice.char(n - 1) == '\r')))
}

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

impl From<String> for Buffer {
    /// The rope of `text`; the string is not kept beside it (a long program is held once).
    fn from(text: String) -> Self {
        Buffer::from(Rope::from_str(&text))
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

    /// The whole text as one string, copied on the first call after an edit and kept.
    pub fn as_str(&self) -> &str {
        self.flat.get_or_init(|| Arc::new(String::from(&self.rope)))
    }

    /// The text for an analysis: the flat copy when it exists (small programs, edited as one
    /// string), otherwise the rope, which the parser reads in place (no copy per edit).
    pub fn program_text(&self) -> swarf_analysis::ProgramText {
        match self.flat.get() {
            Some(flat) => swarf_analysis::ProgramText::Flat(Arc::clone(flat)),
            None => swarf_analysis::ProgramText::Rope(self.rope.clone()),
        }
    }

    /// The whole text as a new string (from the flat copy if any; none is kept for it).
    pub fn to_text(&self) -> String {
        match self.flat.get() {
            Some(flat) => flat.as_ref().clone(),
            None => String::from(&self.rope),
        }
    }

    /// Whether the flat copy of the current text exists (edits are not to make one).
    pub fn is_flat(&self) -> bool {
        self.flat.get().is_some()
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
        let ends = lines > 1 && matches!(self.rope.char(self.len_chars() - 1), '\n' | '\r');
        u32::try_from(lines - usize::from(ends)).unwrap_or(u32::MAX)
    }

    /// The 0-based line of character `char` (clamped to the text).
    pub fn char_to_line(&self, char: usize) -> usize {
        self.rope.char_to_line(char.min(self.len_chars()))
    }

    /// The character where 0-based `line` starts (clamped to the text).
    pub fn line_to_char(&self, line: usize) -> usize {
        self.rope.line_to_char(line.min(self.len_lines()))
    }

    /// Characters of 0-based `line` without its line ending (`\n`, `\r\n`, `\r`).
    pub fn line_len_chars(&self, line: usize) -> usize {
        line_of(&self.rope, line).map_or(0, |l| l.len_chars())
    }

    /// The text of 0-based `line` without its line ending (empty past the end).
    pub fn line_text(&self, line: usize) -> Cow<'_, str> {
        line_of(&self.rope, line).map_or(Cow::Borrowed(""), Cow::from)
    }

    /// The characters `chars` (clamped to the text) as a string.
    pub fn slice(&self, chars: Range<usize>) -> String {
        let end = chars.end.min(self.len_chars());
        let start = chars.start.min(end);
        String::from(self.rope.slice(start..end))
    }

    /// Replaces the characters `chars` (clamped to the text) with `text`; the character after
    /// the inserted text.
    pub fn replace(&mut self, chars: Range<usize>, text: &str) -> usize {
        let end = chars.end.min(self.len_chars());
        let start = chars.start.min(end);
        if start < end || !text.is_empty() {
            self.flat.take();
            self.rope.remove(start..end);
            self.rope.insert(start, text);
        }
        start + text.chars().count()
    }
}
