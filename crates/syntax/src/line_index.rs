//! Byte offset to line/column conversion, computed lazily from a table of line starts.

/// The byte offset where each line starts, so diagnostics can be reported as line and column.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LineIndex {
    starts: Vec<u32>,
}

impl LineIndex {
    /// Builds the table for `text` (a line ends at `\n`; `\r\n` counts as one ending).
    pub fn new(text: &str) -> Self {
        // Counted first, the table is written in place.
        let bytes = text.as_bytes();
        let mut starts = vec![0; count_newlines(bytes) + 1];
        let mut line = 0;
        for_each_newline(bytes, |at| {
            line += 1;
            if let Some(start) = starts.get_mut(line) {
                *start = line_after(0, at);
            }
        });
        LineIndex { starts }
    }

    /// Builds the table for a text given as consecutive pieces (the chunks of a rope), as
    /// [`LineIndex::new`] would for their concatenation, without joining them.
    pub fn from_chunks<'a>(chunks: impl IntoIterator<Item = &'a str>) -> Self {
        let mut starts = vec![0];
        let mut base = 0usize;
        for chunk in chunks {
            for_each_newline(chunk.as_bytes(), |at| starts.push(line_after(base, at)));
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

/// The number of `\n` in `bytes`, eight bytes a turn: the newline bytes' marks (see
/// [`newline_mask`]) are added up in byte-wide lanes, summed every 255 turns.
fn count_newlines(bytes: &[u8]) -> usize {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HALF: u64 = 0x00ff_00ff_00ff_00ff;
    let mut total = 0;
    let (words, rest) = bytes.as_chunks::<8>();
    for block in words.chunks(255) {
        let mut lanes = 0u64;
        for word in block {
            lanes += (newline_mask(word) >> 7) & ONES;
        }
        // Byte lanes to 16-bit lanes, then the four summed by a multiplication.
        let pairs = (lanes & HALF) + ((lanes >> 8) & HALF);
        total += (pairs.wrapping_mul(0x0001_0001_0001_0001) >> 48) as usize;
    }
    total + rest.iter().filter(|&&b| b == b'\n').count()
}

/// The top bit of exactly the bytes of `word` that are `\n`: `(b & 0x7f) + 0x7f` carries into
/// the top bit, and never out of the byte, for every byte `b` but zero.
#[inline(always)]
fn newline_mask(word: &[u8; 8]) -> u64 {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    let x = u64::from_le_bytes(*word) ^ 0x0a0a_0a0a_0a0a_0a0a;
    !(((x & LOW7) + LOW7) | x | LOW7)
}

/// Calls `found` with the offset of every `\n` in `bytes`, in order.
///
/// Sixteen bytes a turn, with a mask of their newline bytes whose set bits are walked: lines of
/// G-code are about twenty bytes long, so a search that stops at each newline (`memchr`) spends
/// more on starting again than on scanning.
#[inline(always)]
fn for_each_newline(bytes: &[u8], mut found: impl FnMut(usize)) {
    let mut walk = |at: usize, mut mask: u64| {
        while mask != 0 {
            found(at + mask.trailing_zeros() as usize / 8);
            mask &= mask - 1;
        }
    };
    let (pairs, rest) = bytes.as_chunks::<16>();
    let mut at = 0;
    for pair in pairs {
        let (low, high) = pair.split_at(8);
        walk(at, newline_mask(low.try_into().unwrap_or(&[0; 8])));
        walk(at + 8, newline_mask(high.try_into().unwrap_or(&[0; 8])));
        at += 16;
    }
    for &b in rest {
        if b == b'\n' {
            found(at);
        }
        at += 1;
    }
}

/// The start of the line after a newline at `at` in a text whose first byte is at `base`
/// (past `u32::MAX`, `u32::MAX`).
#[inline(always)]
fn line_after(base: usize, at: usize) -> u32 {
    u32::try_from(base + at + 1).unwrap_or(u32::MAX)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The table by its definition: 0, then one past every `\n`.
    fn simple_starts(text: &str) -> Vec<u32> {
        std::iter::once(0)
            .chain(
                text.bytes()
                    .enumerate()
                    .filter(|&(_, b)| b == b'\n')
                    .map(|(i, _)| u32::try_from(i + 1).unwrap_or(u32::MAX)),
            )
            .collect()
    }

    #[test]
    fn line_starts_follow_the_newlines() {
        for text in [
            "",
            "\n",
            "\n\n",
            "G1 X1",
            "G1 X1\n",
            "G1 X1\r\nG0 Z5.\r\n",
            "1234567\n1234567\n",
            "12345678\n",
            "\n2345678\n2345678\n2345678",
            "\u{e9}\u{e9}\u{e9}\u{e9}\n\u{e9}\n",
        ] {
            assert_eq!(LineIndex::new(text).starts, simple_starts(text), "{text:?}");
        }
    }

    // proptest is a native-only dev-dependency.
    #[cfg(not(target_arch = "wasm32"))]
    mod props {
        use proptest::prelude::*;

        use super::*;

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(2000))]
            #[test]
            fn line_starts_are_one_past_each_newline(
                pieces in prop::collection::vec(
                    prop::sample::select(&["\n", "\r\n", "\r", "G1", " X3.2040", "\u{e9}", "", "\n\n", "12345678"][..]),
                    0..40,
                ),
                cuts in prop::collection::vec(0usize..200, 0..5),
            ) {
                let text = pieces.concat();
                let index = LineIndex::new(&text);
                prop_assert_eq!(&index.starts, &simple_starts(&text), "{:?}", text);
                // The same text in pieces cut anywhere (on character boundaries).
                let mut cuts: Vec<usize> = cuts
                    .into_iter()
                    .map(|c| c.min(text.len()))
                    .filter(|&c| text.is_char_boundary(c))
                    .collect();
                cuts.sort_unstable();
                let mut chunks = Vec::new();
                let mut from = 0;
                for cut in cuts.into_iter().chain([text.len()]) {
                    chunks.push(&text[from..cut]);
                    from = cut;
                }
                prop_assert_eq!(&LineIndex::from_chunks(chunks), &index, "{:?}", text);
            }
        }
    }
}
