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

    /// The text from byte `start` on, or as much of it as ends at a line end (a source read a
    /// piece at a time: each line in it whole), for a run that indexes the text as it reads it.
    fn rest(&mut self, start: usize) -> &str {
        self.line(start, self.len())
    }

    /// The byte range of the text from `offset` on with its leading and trailing whitespace
    /// (as `str::trim` sees it) left out; `None` when that is blank.
    fn trimmed_rest(&mut self, offset: usize) -> Option<(usize, usize)> {
        let (len, offset) = (self.len(), offset.min(self.len()));
        let rest = self.line(offset, len);
        let trimmed = rest.trim_start();
        let start = offset + rest.len() - trimmed.len();
        (!trimmed.is_empty()).then(|| (start, start + trimmed.trim_end().len()))
    }
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
}
