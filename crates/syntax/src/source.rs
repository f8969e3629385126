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
