//! Byte offset to line/column conversion, computed lazily from a table of line starts.

/// The byte offset where each line starts, so diagnostics can be reported as line and column.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LineIndex {
    pub(crate) starts: Vec<u32>,
}

impl LineIndex {
    /// Builds the table for `text`. A line ends at `\n`, at `\r\n` (one ending) or at a `\r`
    /// alone (old Mac files, and the `\r\r\n` some Windows tools write, which is two endings).
    pub fn new(text: &str) -> Self {
        LineIndex::at_most(text, usize::MAX)
    }

    /// Builds the table for the first `max` lines of `text` (at least one), so that a text of
    /// more lines than a reader takes costs no more table than it reads.
    pub fn at_most(text: &str, max: usize) -> Self {
        let mut index = LineIndex { starts: vec![0] };
        index.index_from(text, 0, max);
        index
    }

    /// Adds the lines that follow the first line of `rest`, the text from byte `from` (the start
    /// of the table's last line) on, up to `max` lines in all.
    pub(crate) fn index_from(&mut self, rest: &str, from: usize, max: usize) {
        let bytes = rest.as_bytes();
        let starts = &mut self.starts;
        // A line is rarely under sixteen bytes, so the table seldom grows.
        starts.reserve((bytes.len() / 16 + 1).min(max.saturating_sub(starts.len())));
        let push = |at| {
            if starts.len() < max {
                starts.push(line_after(from, at));
            }
        };
        for_each_line_end(bytes, push);
    }

    /// Number of lines (an empty text has one empty line).
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// The 0-based line that contains byte `offset`.
    pub fn line_of(&self, offset: u32) -> usize {
        (self.starts.binary_search(&offset)).unwrap_or_else(|i| i.saturating_sub(1))
    }

    /// Byte offset where 0-based `line` starts (the text's end for lines past it).
    pub fn line_start(&self, line: usize) -> u32 {
        (self.starts.get(line).or(self.starts.last())).map_or(0, |&s| s)
    }

    /// 1-based line and 1-based column (in characters) of byte `offset` in `text`.
    pub fn line_col(&self, text: &str, offset: u32) -> (u32, u32) {
        self.cursor(text).line_col(offset)
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

/// One in every byte.
const ONES: u64 = 0x0101_0101_0101_0101;

/// The top bit of exactly the bytes of `word` that are `byte` (not zero): `(b & 0x7f) + 0x7f`
/// carries into the top bit, and never out of the byte, for every byte `b` but zero.
#[inline(always)]
fn byte_mask(word: u64, byte: u64) -> u64 {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    let x = word ^ (byte * ONES);
    !(((x & LOW7) + LOW7) | x | LOW7)
}

/// The top bit of exactly the bytes of `word` that end a line: each `\n`, and each `\r` not
/// followed by a `\n` (`next` is the byte after the word, 0 at the text's end).
#[inline(always)]
fn line_end_mask(word: &[u8; 8], next: u8) -> u64 {
    let word = u64::from_le_bytes(*word);
    let lf = byte_mask(word, u64::from(b'\n'));
    let cr = byte_mask(word, u64::from(b'\r'));
    // A `\n` after each byte: the next byte's mark moved down one lane, the last from `next`.
    let lf_after = (lf >> 8) | (u64::from(next == b'\n') << 63);
    lf | (cr & !lf_after)
}

/// Calls `found` with the offset of every byte of `bytes` that ends a line (see
/// [`line_end_mask`]; a `\r` at the end of `bytes` is one). Most texts have no `\r` (a search
/// for one is quick): then only line feeds end lines.
#[inline(always)]
fn for_each_line_end(bytes: &[u8], found: impl FnMut(usize)) {
    if bytes.contains(&b'\r') {
        for_each_marked(bytes, line_end_mask, found);
    } else {
        let line_feeds = |word: &[u8; 8], _| byte_mask(u64::from_le_bytes(*word), u64::from(b'\n'));
        for_each_marked(bytes, line_feeds, found);
    }
}

/// Calls `found` with the offset of every byte `marks` marks (top bit of each marked byte of a
/// word, given the byte after it, 0 at the end), in order, sixteen bytes a turn: G-code lines are
/// about twenty bytes, so stopping at each newline (`memchr`) costs more in restarts than scanning.
#[inline(always)]
fn for_each_marked(
    bytes: &[u8],
    mut marks: impl FnMut(&[u8; 8], u8) -> u64,
    mut found: impl FnMut(usize),
) {
    let mut walk = |at: usize, mut mask: u64| {
        while mask != 0 {
            found(at + mask.trailing_zeros() as usize / 8);
            mask &= mask - 1;
        }
    };
    let (pairs, rest) = bytes.as_chunks::<16>();
    let mut last = [0; 16];
    last[..rest.len()].copy_from_slice(rest);
    let mut at = 0;
    for pair in pairs.iter().chain([&last]) {
        let (low, high) = pair.split_at(8);
        let low = low.try_into().unwrap_or(&[0; 8]);
        let high = high.try_into().unwrap_or(&[0; 8]);
        walk(at, marks(low, high[0]));
        let next = bytes.get(at + 16).copied().unwrap_or(0);
        walk(at + 8, marks(high, next));
        at += 16;
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
        let col = col0 + (self.text.get(from..end)).map_or(end - from, |s| s.chars().count());
        self.last = Some((line, end, col));
        let one_based = |n: usize| u32::try_from(n + 1).unwrap_or(u32::MAX);
        (one_based(line), one_based(col))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table by its definition: 0, then one past every `\n` and every `\r` that no `\n`
    /// follows.
    fn simple_starts(text: &str) -> Vec<u32> {
        let bytes = text.as_bytes();
        std::iter::once(0)
            .chain(
                bytes
                    .iter()
                    .enumerate()
                    .filter(|&(i, &b)| {
                        b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n'))
                    })
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
            "G21 G90\r\r\nG0 X1 Y2\r\r\nM2\r\r\n",
            "G1\rX1\rY2\r",
            "1234567\r\n1234567\r\r123456\r\n\r",
            "123456789012345\r\n123456789012345\r",
        ] {
            assert_eq!(LineIndex::new(text).starts, simple_starts(text), "{text:?}");
        }
    }

    #[test]
    fn a_carriage_return_alone_ends_a_line_and_before_a_line_feed_does_not() {
        let index = LineIndex::new("G21\r\r\nG0 X1\rM2\r\n");
        assert_eq!(index.starts, [0, 4, 6, 12, 16]);
    }

    // proptest is a native-only dev-dependency.
    #[cfg(not(target_arch = "wasm32"))]
    mod props {
        use proptest::prelude::*;

        use super::*;

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(2000))]
            #[test]
            fn line_starts_are_one_past_each_line_end(
                pieces in prop::collection::vec(
                    prop::sample::select(&["\n", "\r\n", "\r", "\r\r\n", "G1", " X3.2040", "\u{e9}", "", "\n\n", "12345678"][..]),
                    0..40,
                ),
            ) {
                let text = pieces.concat();
                let index = LineIndex::new(&text);
                prop_assert_eq!(&index.starts, &simple_starts(&text), "{:?}", text);
            }
        }
    }
}
