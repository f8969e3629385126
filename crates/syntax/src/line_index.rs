//! Byte offset to line/column conversion, computed lazily from a table of line starts.

/// The byte offset where each line starts, so diagnostics can be reported as line and column.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LineIndex {
    starts: Vec<u32>,
}

impl LineIndex {
    /// Builds the table for `text` (a line ends at `\n`; `\r\n` counts as one ending).
    pub fn new(text: &str) -> Self {
        let mut starts = Vec::with_capacity(text.len() / 24 + 1);
        starts.push(0);
        starts.extend(
            memchr::memchr_iter(b'\n', text.as_bytes())
                .map(|i| u32::try_from(i + 1).unwrap_or(u32::MAX)),
        );
        LineIndex { starts }
    }

    /// Builds the table for a text given as consecutive pieces (the chunks of a rope), as
    /// [`LineIndex::new`] would for their concatenation, without joining them.
    pub fn from_chunks<'a>(chunks: impl IntoIterator<Item = &'a str>) -> Self {
        let mut starts = vec![0];
        let mut base = 0usize;
        for chunk in chunks {
            starts.extend(
                memchr::memchr_iter(b'\n', chunk.as_bytes())
                    .map(|i| u32::try_from(base + i + 1).unwrap_or(u32::MAX)),
            );
            base += chunk.len();
        }
        LineIndex { starts }
    }

    /// Number of lines (an empty text has one empty line).
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// The 0-based line that contains byte `offset`.
    pub fn line_of(&self, offset: u32) -> usize {
        match self.starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        }
    }

    /// Byte offset where 0-based `line` starts (the text's end for lines past it).
    pub fn line_start(&self, line: usize) -> u32 {
        self.starts
            .get(line)
            .copied()
            .unwrap_or_else(|| self.starts.last().copied().unwrap_or(0))
    }

    /// 1-based line and 1-based column (in characters) of byte `offset` in `text`.
    pub fn line_col(&self, text: &str, offset: u32) -> (u32, u32) {
        let line = self.line_of(offset);
        let start = self.line_start(line) as usize;
        let end = (offset as usize).min(text.len()).max(start);
        let col = text
            .get(start..end)
            .map_or(end - start, |s| s.chars().count());
        (
            u32::try_from(line + 1).unwrap_or(u32::MAX),
            u32::try_from(col + 1).unwrap_or(u32::MAX),
        )
    }

    /// A cursor that turns many offsets into line and column: in increasing order each costs
    /// only the characters since the last one, so a million diagnostics on one long line stay
    /// linear.
    pub fn cursor<'a>(&'a self, text: &'a str) -> LineCols<'a> {
        LineCols {
            index: self,
            text,
            last: None,
        }
    }
}

/// Line and column lookups that remember the last answer (see [`LineIndex::cursor`]).
#[derive(Debug, Clone)]
pub struct LineCols<'a> {
    index: &'a LineIndex,
    text: &'a str,
    /// The last (0-based line, byte offset, 0-based column in characters).
    last: Option<(usize, usize, usize)>,
}

impl LineCols<'_> {
    /// 1-based line and 1-based column (in characters) of byte `offset`, as
    /// [`LineIndex::line_col`].
    pub fn line_col(&mut self, offset: u32) -> (u32, u32) {
        let line = self.index.line_of(offset);
        let start = self.index.line_start(line) as usize;
        let end = (offset as usize).min(self.text.len()).max(start);
        let (from, col0) = match self.last {
            Some((l, o, c)) if l == line && o <= end => (o, c),
            _ => (start, 0),
        };
        let col = col0
            + self
                .text
                .get(from..end)
                .map_or(end - from, |s| s.chars().count());
        self.last = Some((line, end, col));
        (
            u32::try_from(line + 1).unwrap_or(u32::MAX),
            u32::try_from(col + 1).unwrap_or(u32::MAX),
        )
    }
}
