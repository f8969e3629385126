//! [`ParseRun`]: a parse of a `&str` or a [`LineSource`] in steps of a bounded number of lines,
//! each line read by the short reader of plain lines or by the general one.

use super::block::LineReader;
use super::plain::{PlainLines, ending_len, read_plain_lines};
use super::{MAX_LINE_BYTES, MAX_PARSED_BYTES, is_blank};
use crate::{Block, Diagnostic, Dialect, ExprNode, LineIndex, LineSource, Program, Span};

/// A parse that reads a bounded number of lines per [`step`](ParseRun::step), so an editor can
/// spread the parse of a long program over frames. Stepped to its end it gives the same
/// [`Program`] as [`parse`](super::parse).
#[derive(Debug)]
pub struct ParseRun {
    program: Program,
    checker: crate::checks::Checker,
    at: ReadPoint,
    done: bool,
    /// Whether lines of plain words take the short reader (always, but in the tests that
    /// compare it with the general one).
    pub(super) plain_lines: bool,
    /// What the parsed program holds, and the most it may hold.
    held: Held,
}

/// The bytes the parsed program holds, counted as its lines are read, so that the reading stops
/// at [`Held::max`] with `E-PROGRAM-SIZE`.
#[derive(Debug, Default)]
struct Held {
    /// The most the program may hold ([`MAX_PARSED_BYTES`] unless set).
    max: usize,
    /// Blocks, expressions, diagnostics and the checker's diagnostics counted so far.
    blocks: usize,
    /// Bytes of the line table (counted as it grows).
    table: usize,
    exprs: usize,
    diagnostics: usize,
    checked: usize,
    /// Bytes of the blocks and expressions counted (dropped with them by
    /// [`ParseRun::clear_blocks`]), and of everything else.
    piece_bytes: usize,
    other_bytes: usize,
    /// The byte offset from which the next count is made: a count every
    /// [`Held::COUNT_EVERY`] bytes of text costs little, and passes the bound by no more than
    /// that much text makes (a few hundred bytes a byte at most).
    count_at: usize,
}

impl Held {
    const COUNT_EVERY: usize = 16 << 10;

    /// Nothing counted but the line table's first line.
    fn new(max: usize) -> Self {
        Held {
            max,
            table: size_of::<u32>(),
            ..Held::default()
        }
    }

    /// The most blocks the program can come to hold: as many as fit beside its line table,
    /// and the lines of the text read past the bound before the count that finds it.
    fn most_blocks(&self) -> usize {
        self.max.saturating_sub(self.table) / size_of::<Block>() + Self::COUNT_EVERY / 2 + 1
    }

    /// Counts what was read since the last count; the total.
    fn count(&mut self, program: &Program, checker: &crate::checks::Checker) -> usize {
        self.table = program.lines.line_count().min(max_lines(self.max) + 1) * size_of::<u32>();
        let new_blocks = program.blocks.get(self.blocks..).unwrap_or_default();
        self.piece_bytes += new_blocks.iter().map(Block::held_bytes).sum::<usize>();
        self.blocks = program.blocks.len();
        let new_exprs = program.exprs.get(self.exprs..).unwrap_or_default();
        self.piece_bytes += new_exprs.iter().map(ExprNode::held_bytes).sum::<usize>();
        self.exprs = program.exprs.len();
        for (counted, diagnostics) in [
            (&mut self.diagnostics, program.diagnostics.as_slice()),
            (&mut self.checked, checker.diagnostics()),
        ] {
            let new = diagnostics.get(*counted..).unwrap_or_default();
            self.other_bytes += new.iter().map(Diagnostic::held_bytes).sum::<usize>();
            *counted = diagnostics.len();
        }
        self.piece_bytes + self.other_bytes + self.table
    }

    /// Counts what was read up to `offset` where a count is due there (or `now`), and reports
    /// a program of `len` bytes that holds more than the most from there on: whether it does.
    fn count_due(
        &mut self,
        program: &mut Program,
        checker: &crate::checks::Checker,
        offset: usize,
        len: usize,
        now: bool,
    ) -> bool {
        if offset < self.count_at && !now {
            return false;
        }
        self.count_at = offset.saturating_add(Held::COUNT_EVERY);
        let over = self.count(program, checker) > self.max;
        if over {
            too_large(program, len, offset, self.max);
        }
        over
    }
}

impl ParseRun {
    /// Starts a parse that indexes the text's lines as it reads them; nothing is read yet.
    pub fn new(dialect: Dialect) -> Self {
        ParseRun {
            program: Program {
                dialect,
                lines: LineIndex::new(""),
                ..Program::default()
            },
            checker: crate::checks::Checker::new(dialect),
            at: ReadPoint::default(),
            done: false,
            plain_lines: true,
            held: Held::new(MAX_PARSED_BYTES),
        }
    }

    /// Where the parse has read to: the next line, its byte offset and the tape marks met, so
    /// that [`ParseRun::resume`] reads the same lines again later without the ones before.
    pub fn read_point(&self) -> ReadPoint {
        self.at
    }

    /// Starts a parse at `at` (a [`ParseRun::read_point`] of a parse of the same text): the
    /// blocks read are those the first parse read there, with their lines and spans, but the
    /// program's line table counts from `at`, not from the text's first line.
    pub fn resume(at: ReadPoint, dialect: Dialect) -> Self {
        ParseRun {
            at,
            ..ParseRun::new(dialect)
        }
    }

    /// Lowers the most the parsed program may hold (bytes, see [`MAX_PARSED_BYTES`]) before
    /// anything is read: a reader with less memory, or a test.
    pub fn set_max_bytes(&mut self, max: usize) {
        self.held = Held::new(max.min(self.held.max));
    }

    /// The bytes the parsed program holds (see [`MAX_PARSED_BYTES`]), as last counted.
    pub fn held_bytes(&self) -> usize {
        self.held.piece_bytes + self.held.other_bytes + self.held.table
    }

    /// Lines and bytes read so far.
    pub fn progress(&self) -> (usize, usize) {
        (self.at.line_no, self.at.offset)
    }

    /// Reads at most `lines` more lines of `text` (the same text at every step); whether the
    /// whole text is read.
    pub fn step(&mut self, text: &str, lines: usize) -> bool {
        self.step_from(&mut &*text, lines)
    }

    /// Reads at most `lines` more lines from `source` (the same text at every step); whether
    /// the whole text is read.
    pub fn step_from(&mut self, source: &mut dyn LineSource, lines: usize) -> bool {
        let program = &mut self.program;
        // The run's state, kept here while the lines are read (stored at the end).
        let (mut offset, mut next, mut tape) = (self.at.offset, self.at.line_no, self.at.tape);
        let mut done = self.done;
        // A text of more lines than a parse indexes is read up to that many.
        let most = max_lines(self.held.max);
        let stop = next.saturating_add(lines).min(most);
        // Room for a block a line read in this step (a line is rarely under sixteen bytes),
        // reserved once: a run read in pieces reuses it.
        if program.blocks.capacity() == 0 {
            let unread = source.len().saturating_sub(offset) / 16 + 1;
            let room = unread.min(stop - next).min(self.held.most_blocks());
            program.blocks.reserve_exact(room);
        }
        let text_len = source.len();
        while !done && next < stop {
            // The text from the next line on, as far as the source holds it (whole lines): its
            // lines are read in turn, each line's end found as it is read.
            let text = source.rest(offset);
            let text_at = offset;
            let mut closed;
            loop {
                let from = offset - text_at;
                let onward = text.as_bytes().get(from..).unwrap_or_default();
                // A run of plain lines is read at once.
                let run = if self.plain_lines {
                    let (lines, until) = (stop - next, self.held.count_at);
                    let checker = &mut self.checker;
                    read_plain_lines(onward, offset, next, lines, until, program, checker)
                } else {
                    PlainLines::default()
                };
                let last;
                if run.lines > 0 {
                    (offset, next, last) = (offset + run.bytes, next + run.lines, run.last);
                    (tape, closed) = tape.after(!run.block, false);
                } else {
                    let line_no = u32::try_from(next).unwrap_or(u32::MAX);
                    // Whether the line is blank and whether it is a `%` line (for the tape
                    // marks), and its length without its ending.
                    let len = onward.iter().position(|&b| b == b'\n' || b == b'\r');
                    let len = len.unwrap_or(onward.len());
                    let raw = text.get(from..from + len).unwrap_or_default();
                    let (blank, percent) =
                        read_general_line(program, &mut self.checker, raw, offset, line_no);
                    let ending = ending_len(onward.get(len..));
                    last = ending == 0;
                    offset += len + ending;
                    next += 1;
                    if !last {
                        let start = u32::try_from(offset).unwrap_or(u32::MAX);
                        program.lines.starts.push(start);
                    }
                    (tape, closed) = tape.after(blank, percent);
                }
                if closed {
                    break;
                }
                done = last;
                let now = done || next == most;
                let held = &mut self.held;
                done |= held.count_due(program, &self.checker, offset, text_len, now);
                if done || next >= stop || offset - text_at >= text.len() {
                    break;
                }
            }
            if closed {
                ignore_after_tape_end(program, source, offset);
                let held = &mut self.held;
                held.count_due(program, &self.checker, offset, text_len, true);
                done = true;
            }
        }
        if !done && next == most && program.lines.line_count() > most {
            too_large(program, text_len, offset, self.held.max);
            done = true;
        }
        // A run stopped before the end of the text indexes the rest.
        if done && program.lines.line_count() == next + 1 {
            let rest = source.line(offset, source.len());
            program.lines.index_from(rest, offset, most + 1);
        }
        (self.at.offset, self.at.line_no, self.at.tape, self.done) = (offset, next, tape, done);
        done
    }

    /// The program as read so far.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Drops the blocks and expressions read so far (keeping diagnostics, lines and the memory) so
    /// a reader run piece by piece keeps none it has run. A block refers only to its own line's
    /// expressions, so the next piece's count from 0.
    pub fn clear_blocks(&mut self) {
        self.program.blocks.clear();
        self.program.exprs.clear();
        (self.held.blocks, self.held.exprs, self.held.piece_bytes) = (0, 0, 0);
    }

    /// The parsed program (the lines read so far, if the run is not done).
    pub fn finish(self) -> Program {
        let mut program = self.program;
        self.checker.finish(&mut program);
        program
    }
}

/// Where a [`ParseRun`] has read to (see [`ParseRun::read_point`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReadPoint {
    /// Byte offset of the next line.
    offset: usize,
    /// 0-based number of the next line.
    line_no: usize,
    tape: Tape,
}

impl ReadPoint {
    /// The 0-based number of the line read next from here.
    pub fn line(&self) -> usize {
        self.line_no
    }
}

/// Where the reader is with respect to `%` tape marks. A program that opens with a `%` line
/// (the first line that is not blank) ends at the next `%` line: what follows the closing tape
/// mark is not read (LinuxCNC ignores it; on the Fanuc family it is past the end of the tape).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Tape {
    /// Only blank lines so far.
    #[default]
    Before,
    /// The program opened with a `%` line: the next one closes it.
    Open,
    /// The program did not open with `%`: a `%` line is only a mark.
    Plain,
}

impl Tape {
    /// Where the reader is after a line (whether blank, whether a `%` line), and whether that
    /// line closed the program.
    fn after(self, blank: bool, percent: bool) -> (Tape, bool) {
        match (self, percent) {
            (_, false) if blank => (self, false),
            (Tape::Before, true) => (Tape::Open, false),
            (Tape::Before | Tape::Plain, false) => (Tape::Plain, false),
            (Tape::Open, true) => (self, true),
            (other, _) => (other, false),
        }
    }
}

/// Reads `line` (without its ending, at byte `offset`) with the general reader: whether it
/// is blank and whether it is a `%` line, for the tape marks. Not inlined: the line loop it
/// is called from reads the plain lines, and is faster without it.
#[inline(never)]
fn read_general_line(
    program: &mut Program,
    checker: &mut crate::checks::Checker,
    mut line: &str,
    offset: usize,
    line_no: u32,
) -> (bool, bool) {
    if line.len() > MAX_LINE_BYTES {
        // A runaway line (a binary file, a generator gone wrong): read its start only.
        let (cut, len) = (line.floor_char_boundary(MAX_LINE_BYTES), line.len());
        let message = format!(
            "this line is {len} bytes long; only its first {MAX_LINE_BYTES} bytes are read"
        );
        let span = Span::new(offset + cut, offset + len);
        let error = Diagnostic::error(span, "E-LINE-LENGTH", message);
        program.diagnostics.push(error);
        line = &line[..cut];
    }
    let mut reader = LineReader {
        rules: program.dialect.rules(),
        line,
        bytes: line.as_bytes(),
        base: offset,
        line_no,
        program,
        checker,
        open_brackets: 0,
        statements: Vec::new(),
        comments: Vec::new(),
    };
    reader.read();
    let significant = line.trim_start_matches(is_blank);
    (significant.is_empty(), significant.starts_with('%'))
}

/// The most lines a parse that may hold `max` bytes indexes: their table may take half of them.
fn max_lines(max: usize) -> usize {
    (max / 2 / size_of::<u32>()).max(2)
}

/// Reports that the text from `offset` (of `len` bytes) on is not read: the program read so far
/// holds more than `max` bytes.
fn too_large(program: &mut Program, len: usize, offset: usize, max: usize) {
    let message = format!(
        "the program is too large to hold whole: what is read up to here passes {} MiB \
         (its lines, blocks, expressions and diagnostics), so the rest is not read",
        max.div_ceil(1 << 20)
    );
    let error = Diagnostic::error(Span::new(offset.min(len), len), "E-PROGRAM-SIZE", message);
    program.diagnostics.push(error);
}

/// Notes that the text from `offset` on, after the closing `%`, is not read (if it is not blank).
fn ignore_after_tape_end(program: &mut Program, source: &mut dyn LineSource, offset: usize) {
    if let Some((start, end)) = source.trimmed_rest(offset) {
        let message = "the program ends at the closing `%`: the text after it is not read";
        let note = Diagnostic::note(Span::new(start, end), "N-AFTER-TAPE-END", message);
        program.diagnostics.push(note);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse;

    /// `block` written out with each expression id replaced by its expression from `exprs`
    /// (written out in turn): the same for a block read in a piece and read whole.
    fn resolved(block: &str, exprs: &[crate::ExprNode]) -> String {
        let mut out = String::new();
        let mut rest = block;
        while let Some(at) = rest.find("ExprId(") {
            out.push_str(&rest[..at]);
            rest = &rest[at + "ExprId(".len()..];
            let end = rest.find(')').unwrap();
            let index = rest[..end].parse::<usize>().unwrap() - 1;
            out.push_str(&resolved(&format!("{:?}", exprs[index]), exprs));
            rest = &rest[end + 1..];
        }
        out + rest
    }

    /// A run read a few lines a step gives the whole parse's program, its line table the text's:
    /// read to the end or stopped at a closing tape mark; stopped at the most lines a parse
    /// indexes, it indexes as many as that.
    #[test]
    fn a_run_in_steps_indexes_the_lines_as_it_reads_them() {
        let read = |mut run: ParseRun, text: &str, max: usize| {
            run.set_max_bytes(max);
            while !run.step(text, 7) {}
            run.finish()
        };
        for text in [
            format!("%\nG0 X1\r\n%\r\r\nX$\n{}", "G1 X2\r\n".repeat(100)),
            format!("G1 X1\rX2\r\n\r\r\n{}\nM30\r", "(c) X3.5 Y-1\n".repeat(50)),
        ] {
            let stepped = read(ParseRun::new(Dialect::Fanuc), &text, MAX_PARSED_BYTES);
            assert!(stepped == parse(&text, Dialect::Fanuc), "{text:?}");
            assert!(stepped.lines == LineIndex::new(&text), "{text:?}");
            assert!(stepped.lines.line_count() > 50, "{text:?}");
        }
        let text = "\n".repeat(1 << 18);
        let program = read(ParseRun::new(Dialect::Fanuc), &text, 1 << 19);
        let most = max_lines(1 << 19);
        assert!(program.lines == LineIndex::at_most(&text, most + 1));
        let stop = program.diagnostics.last().map(|d| (d.code, d.span.start));
        assert_eq!(stop, Some(("E-PROGRAM-SIZE", most as u32)));
    }

    #[test]
    fn pieces_read_after_the_blocks_are_cleared_make_the_whole_program() {
        let text = "O100 (a program)\nG1 X1 Y2 Z3 A4 B5 C6 F7\n#1 = [2 + #1]\nG0 X#1\n \
                    N10 X1.5\n\nX2 (c)\nIF [#1 GT 3] THEN #2 = -#1\n"
            .repeat(20);
        for dialect in Dialect::ALL {
            let whole = parse(&text, dialect);
            let whole: Vec<String> = whole
                .blocks
                .iter()
                .map(|b| resolved(&format!("{b:?}"), &whole.exprs))
                .collect();
            let mut run = ParseRun::new(dialect);
            let mut blocks = Vec::new();
            loop {
                let done = run.step(&text, 3);
                let program = run.program();
                blocks.extend(
                    program
                        .blocks
                        .iter()
                        .map(|b| resolved(&format!("{b:?}"), &program.exprs)),
                );
                run.clear_blocks();
                assert!(run.program().blocks.is_empty() && run.program().exprs.is_empty());
                if done {
                    break;
                }
            }
            assert_eq!(blocks, whole, "{dialect:?}");
            assert!(whole.iter().any(|b| b.contains("Binary(Add")));
        }
    }
}
