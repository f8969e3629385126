//! The short reader of the lines CAM output is made of (`G1 X5.12 Y0.00`): where the speed of
//! the parser is. Its blocks and diagnostics are held to the general reader's by the tests.

use super::MAX_LINE_BYTES;
use super::number::{Decimal, scan_decimal, scan_sign, with_sign};
use crate::{Block, Program, Rules, Span, Word, WordForm};

/// Reads a line of plain words (`N20 G0 Z5.`, `G1 X5.12 Y0`: letter, optional sign, number of at
/// most 15 digits), the lines CAM output makes, onto `blocks` as the general reader would check it.
/// Returns whether it made a block and the line's length (no ending), or `None`, reading nothing.
#[inline]
fn read_plain_line(
    bytes: &[u8],
    base: usize,
    line_no: u32,
    rules: &Rules,
    blocks: &mut Vec<Block>,
    checker: &mut crate::checks::Checker,
) -> Option<(bool, usize)> {
    // A line longer than the longest read whole is left to the general reader, which cuts it:
    // it is read no further than that here, and goes there at its end.
    let bytes = bytes.get(..MAX_LINE_BYTES + 2).unwrap_or(bytes);
    // Whether the line ends at `pos` (where a `\n`, a `\r` or the end is).
    let ends = |pos: usize| matches!(bytes.get(pos), None | Some(b'\n' | b'\r'));
    let mut pos = 0;
    while matches!(bytes.get(pos), Some(b' ' | b'\t')) {
        pos += 1;
    }
    if ends(pos) {
        return (pos <= MAX_LINE_BYTES).then_some((false, pos));
    }
    // The spans' offsets, when the longest line read here lies in the 4 GiB a span addresses
    // (the general reader clamps the offsets past them).
    let reach = bytes.len();
    let base = u32::try_from(base + reach).ok()? - reach as u32;
    let first = pos;
    // As many digits as the general reader takes quietly and one division reads exactly.
    let max_digits = match usize::from(rules.max_digits) {
        0 => 15,
        max => max.min(15),
    };
    let mut number = None;
    // One past the block's last significant byte.
    let mut last = pos;
    if bytes[pos] | 0x20 == b'n' {
        // `N123`: up to nine digits without a point are the number exactly.
        let start = pos + 1;
        pos = start;
        let mut value = 0u32;
        while let Some(&b) = bytes.get(pos)
            && b.is_ascii_digit()
            && pos - start < 9
        {
            value = value * 10 + u32::from(b - b'0');
            pos += 1;
        }
        if pos == start
            || value > rules.max_sequence_number
            || matches!(bytes.get(pos), Some(b'0'..=b'9' | b'.'))
        {
            return None;
        }
        number = Some(value);
        last = pos;
        while matches!(bytes.get(pos), Some(b' ' | b'\t')) {
            pos += 1;
        }
    }
    // The block, its words written straight into it as they are read: it is moved once, into
    // `blocks`, rather than the words into it and then it there.
    let mut block = Block {
        span: Span {
            start: base + first as u32,
            end: base + last as u32,
        },
        line: line_no,
        number: number.and_then(Block::stored_number),
        words: smallvec::SmallVec::new(),
        extras: None,
    };
    let mut scan = crate::checks::PlainScan::default();
    while let Some(&b) = bytes.get(pos) {
        let start = pos;
        let letter = PLAIN_LETTERS[usize::from(b)];
        if letter == 0 {
            if b == b'\n' || b == b'\r' {
                break;
            }
            return None;
        }
        let (negative, at) = scan_sign(bytes, pos + 1);
        let Decimal {
            end,
            value,
            has_point,
            ..
        } = scan_decimal(bytes, at).filter(|d| d.digits <= max_digits)?;
        pos = end;
        let value = with_sign(value, negative);
        scan.word(letter, value);
        block.words.push(Word {
            letter,
            value,
            has_point,
            span: Span {
                start: base + start as u32,
                end: base + pos as u32,
            },
            form: WordForm::Plain,
            expr: None,
        });
        block.span.end = base + pos as u32;
        while matches!(bytes.get(pos), Some(b' ' | b'\t')) {
            pos += 1;
        }
    }
    if pos > MAX_LINE_BYTES {
        return None;
    }
    blocks.push(block);
    checker.check_scanned(blocks.last_mut()?, &scan);
    Some((true, pos))
}

/// What [`read_plain_lines`] read: bytes and lines, whether a line gave a block, and whether
/// the last line read ends the text (it has no line ending).
#[derive(Debug, Default)]
pub(super) struct PlainLines {
    pub(super) bytes: usize,
    pub(super) lines: usize,
    pub(super) block: bool,
    pub(super) last: bool,
}

/// Reads plain lines from the start of `bytes` (from byte `base`, 0-based line `line_no`) with
/// [`read_plain_line`], up to `most` lines or the one ending at or past `until`, indexing line
/// starts as it goes. Not inlined: the line loop, where parsing spends its time, is faster alone.
#[inline(never)]
pub(super) fn read_plain_lines(
    bytes: &[u8],
    base: usize,
    line_no: usize,
    most: usize,
    until: usize,
    program: &mut Program,
    checker: &mut crate::checks::Checker,
) -> PlainLines {
    let rules = program.dialect.rules();
    let mut read = PlainLines::default();
    while read.lines < most {
        let onward = bytes.get(read.bytes..).unwrap_or_default();
        let line = u32::try_from(line_no + read.lines).unwrap_or(u32::MAX);
        let blocks = &mut program.blocks;
        let Some((block, len)) =
            read_plain_line(onward, base + read.bytes, line, rules, blocks, checker)
        else {
            break;
        };
        read.lines += 1;
        read.block |= block;
        let ending = ending_len(onward.get(len..));
        read.bytes += len + ending;
        read.last = ending == 0;
        let start = base + read.bytes;
        if read.last {
            break;
        }
        program
            .lines
            .starts
            .push(u32::try_from(start).unwrap_or(u32::MAX));
        if start >= until || read.bytes == bytes.len() {
            break;
        }
    }
    read
}

/// The length of the line ending at the start of `after` (what follows a line's text): a line
/// ends at a `\n`, a `\r\n` or a `\r`, or else (0) at the end of the text.
#[inline(always)]
pub(super) fn ending_len(after: Option<&[u8]>) -> usize {
    match after {
        Some([b'\r', b'\n', ..]) => 2,
        Some([_, ..]) => 1,
        _ => 0,
    }
}

/// For each byte, the address letter (uppercase) of a word of a plain line that it starts, or 0:
/// any letter but `N` (a sequence number) and `O` (a program number or an O-word).
const PLAIN_LETTERS: [u8; 256] = {
    let mut table = [0; 256];
    let mut b = 0;
    while b < 256 {
        let letter = (b as u8).to_ascii_uppercase();
        if letter.is_ascii_uppercase() && letter != b'N' && letter != b'O' {
            table[b] = letter;
        }
        b += 1;
    }
    table
};

#[cfg(test)]
#[path = "../../../../tests/support/programs.rs"]
mod test_programs;

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use crate::{Dialect, ParseRun, Program, parse};

    /// `text` read by the general line reader alone.
    fn parse_general(text: &str, dialect: Dialect) -> Program {
        let mut run = ParseRun::new(dialect);
        run.plain_lines = false;
        while !run.step(text, usize::MAX) {}
        run.finish()
    }

    /// `text` read a few lines a step.
    fn parse_stepped(text: &str, dialect: Dialect) -> Program {
        let mut run = ParseRun::new(dialect);
        while !run.step(text, 3) {}
        run.finish()
    }

    /// The short reader of plain lines gives what the general reader gives: the same blocks
    /// (values to the bit) and the same diagnostics, whether read a few lines a step or at once.
    fn assert_same_as_general(text: &str, dialect: Dialect) {
        let general = parse_general(text, dialect);
        let stepped = parse_stepped(text, dialect);
        assert!(
            stepped == general && same_values(&stepped, &general),
            "{dialect:?}: {text:?}"
        );
        let fast = parse(text, dialect);
        assert_eq!(
            fast.blocks.len(),
            general.blocks.len(),
            "{dialect:?}: {text:?}"
        );
        for (a, b) in fast.blocks.iter().zip(&general.blocks) {
            assert_eq!(a, b, "{dialect:?}: {text:?}");
        }
        assert_eq!(fast, general, "{dialect:?}: {text:?}");
        assert!(same_values(&fast, &general), "{dialect:?}: {text:?}");
    }

    /// Whether the words of `a` and `b` have the same values to the bit (`==` takes -0 for 0).
    fn same_values(a: &Program, b: &Program) -> bool {
        a.blocks.len() == b.blocks.len()
            && a.blocks.iter().zip(&b.blocks).all(|(x, y)| {
                x.words.len() == y.words.len()
                    && x.words
                        .iter()
                        .zip(&y.words)
                        .all(|(v, w)| v.value.to_bits() == w.value.to_bits())
            })
    }

    #[test]
    fn plain_lines_read_as_the_general_reader_reads_them() {
        let lines = [
            "G1 X5.12 Y0.00 S100",
            " X3.2040 Z-0.1539",
            "G01X1Y2Z-.5F100.",
            "x1.5 y-2 z+3.",
            "\tX1.\t\tY2.  ",
            "N10 G0 Z5.",
            "n20",
            "N30   ",
            "N 40 X1.",
            "N1234567890 X1",
            "N99999 X1",
            "N100000 X1",
            "N10. X1",
            "X1 N10",
            "O100",
            "G1 X1234567890 Y1.",
            "G1 X123456789012345 Y1.",
            "G1 X1234567890123456 Y1.",
            "X0.000000000000001",
            "X0.0000000000000001",
            "X99999999999999999999.5",
            "X-0 Y+0. Z-.0",
            "X.",
            "X-",
            "X--1",
            "X+-1",
            "X 1.",
            "X1.2.3",
            "X1=2",
            "F2=100",
            "X1;Y2",
            "X1 (c)",
            "X1 ; c",
            "/X1",
            "%",
            "X1 Y2 Z3 A4 B5 C6 F7",
            "G1 X1 X2 F-1 T1.5 S-3 H2 D-1",
            "G0 X1 P2 Q3",
            "G1 G0 X1",
            "G2 X1 R1.",
            "G1 M3 X1",
            "G1.0 X1",
            "G-0 X1",
            "G00 G01",
            "IF",
            "DO1",
            "X1\u{e9}",
            "X1\r",
            "X1\r\r",
            "\r",
            "X1\rY2",
            "N10\r",
            "   ",
            "",
        ];
        for dialect in Dialect::ALL {
            for line in lines {
                assert_same_as_general(line, dialect);
            }
            assert_same_as_general(&lines.join("\n"), dialect);
            assert_same_as_general(&lines.join("\r\n"), dialect);
        }
    }

    #[test]
    fn a_runaway_plain_line_is_cut_as_any_other() {
        let text = format!("G1 X1.{}\nG0 X2.\n", " ".repeat(MAX_LINE_BYTES));
        for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
            assert_same_as_general(&text, dialect);
            let program = parse(&text, dialect);
            assert!(
                program
                    .diagnostics
                    .iter()
                    .any(|d| d.code == "E-LINE-LENGTH")
            );
            assert_eq!(program.blocks.len(), 2);
        }
    }

    #[test]
    fn corpus_programs_read_as_the_general_reader_reads_them() {
        let Some(corpus) = programs::corpus() else {
            return;
        };
        for path in programs::programs_under(&corpus) {
            let bytes = std::fs::read(&path).unwrap();
            let text = crate::decode(&bytes).text;
            for dialect in [Dialect::LinuxCnc, Dialect::Fanuc] {
                let fast = parse(&text, dialect);
                let general = parse_general(&text, dialect);
                assert!(
                    fast == general && same_values(&fast, &general),
                    "{}: {dialect:?}",
                    path.display()
                );
            }
        }
    }

    use super::test_programs as programs;

    // proptest is a native-only dev-dependency.
    #[cfg(not(target_arch = "wasm32"))]
    mod props {
        use proptest::prelude::*;

        use super::*;

        /// Pieces of CAM lines, near misses of a plain line among them.
        const PIECES: &[&str] = &[
            "G",
            "X",
            "Y",
            "Z",
            "F",
            "S",
            "T",
            "M",
            "N",
            "O",
            "I",
            "J",
            "K",
            "R",
            "P",
            "D",
            "H",
            "x",
            "g",
            "n",
            "E",
            "A",
            "0",
            "1",
            "5",
            "9",
            "00",
            "123",
            "4567",
            "0.",
            ".",
            ".5",
            "12.3456",
            "-",
            "+",
            " ",
            " ",
            "  ",
            "\t",
            "=",
            "(c)",
            ";",
            "/",
            "%",
            "#1",
            ",",
            ":",
            "[",
            "1234567890",
            "1234567890123456",
            "\u{e9}",
            "IF",
            "DO",
            "\r",
        ];

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(3000))]
            #[test]
            fn lines_read_as_the_general_reader_reads_them(
                lines in prop::collection::vec(
                    prop::collection::vec(prop::sample::select(PIECES), 0..14),
                    1..4,
                ),
                dialect in prop::sample::select(&Dialect::ALL[..]),
            ) {
                let text: Vec<String> = lines.iter().map(|l| l.concat()).collect();
                let text = text.join("\n");
                let fast = parse(&text, dialect);
                let general = parse_general(&text, dialect);
                prop_assert_eq!(&fast, &general, "{:?}", text);
                prop_assert!(same_values(&fast, &general), "{:?}", text);
            }
        }
    }
}
