//! Where a parse reads its lines from: one string, or the pieces of a larger structure (an
//! editor's rope) read in place, so a long text need not be copied into one string to be parsed.

/// A text read a line at a time by [`ParseRun::step_from`](crate::ParseRun::step_from), in
/// increasing order of offset. Offsets are bytes from the start of the whole text, on `char`
/// boundaries.
pub trait LineSource {
    /// Length of the whole text in bytes.
    fn len(&self) -> usize;

    /// Whether the text is empty.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The text from byte `start` to byte `end` (one line without its `\n`; empty when the range
    /// is outside the text or not on `char` boundaries).
    fn line(&mut self, start: usize, end: usize) -> &str;

    /// The byte range of the text from `offset` on with its leading and trailing whitespace
    /// (as `str::trim` sees it) left out; `None` when that is blank.
    fn trimmed_rest(&mut self, offset: usize) -> Option<(usize, usize)>;
}

impl LineSource for &str {
    #[inline]
    fn len(&self) -> usize {
        str::len(self)
    }

    #[inline]
    fn line(&mut self, start: usize, end: usize) -> &str {
        self.get(start..end).unwrap_or_default()
    }

    fn trimmed_rest(&mut self, offset: usize) -> Option<(usize, usize)> {
        let rest = self.get(offset.min(str::len(self))..).unwrap_or_default();
        let trimmed = rest.trim_start();
        if trimmed.is_empty() {
            return None;
        }
        let start = str::len(self) - trimmed.len();
        Some((start, start + trimmed.trim_end().len()))
    }
}

/// The part of a text from byte `base` on (a file read through a window: the bytes before
/// `base` are gone), addressed by offsets into the whole text. Its bytes are UTF-8.
pub(crate) struct Window<'a> {
    /// The text from `base` on.
    pub(crate) text: &'a [u8],
    /// Where `text` starts in the whole text.
    pub(crate) base: usize,
}

impl LineSource for Window<'_> {
    fn len(&self) -> usize {
        self.base + self.text.len()
    }

    /// Empty for a range before the window or not on a character's bounds.
    fn line(&mut self, start: usize, end: usize) -> &str {
        match (start.checked_sub(self.base), end.checked_sub(self.base)) {
            (Some(start), Some(end)) => self
                .text
                .get(start..end)
                .and_then(|line| std::str::from_utf8(line).ok())
                .unwrap_or_default(),
            _ => "",
        }
    }

    fn trimmed_rest(&mut self, offset: usize) -> Option<(usize, usize)> {
        let rest = self.text.get(offset.saturating_sub(self.base)..)?;
        let rest = std::str::from_utf8(rest).ok()?;
        let (start, end) = (&mut &*rest).trimmed_rest(0)?;
        let at = self.base + self.text.len() - rest.len();
        Some((at + start, at + end))
    }
}
