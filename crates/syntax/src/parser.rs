//! The fault-tolerant block parser.
//!
//! Each line is read on its own (the newline is the recovery point); a problem inside a line
//! becomes a diagnostic, the offending characters are skipped, and reading goes on. The lexical
//! rules come from the dialect's [`Rules`](crate::Rules) table.

use nom::branch::alt;
use nom::character::complete::{char, digit0, digit1};
use nom::combinator::opt;
use nom::{IResult, Parser};

use crate::ast::{BinOp, Expr, ExprId, ExprNode, Func, OLabel, OWord, ProgramNumber, Statement};
use crate::source::Window;
use crate::{
    Block, Diagnostic, Dialect, LineIndex, LineSource, Program, Rules, Span, Word, WordForm,
};

/// Nesting depth at which the parser stops descending into an expression, whatever the dialect
/// allows (so hostile input cannot exhaust the stack).
const HARD_DEPTH: u32 = 64;

/// Parses `text` as read by `dialect`. Never fails: problems are in `Program::diagnostics`.
pub fn parse(text: &str, dialect: Dialect) -> Program {
    let mut run = ParseRun::new(text, dialect);
    while !run.step(text, usize::MAX) {}
    run.finish()
}

/// A parse that reads a bounded number of lines per [`step`](ParseRun::step), so an editor can
/// spread the parse of a long program over frames. Stepped to its end it gives the same
/// [`Program`] as [`parse`].
#[derive(Debug)]
pub struct ParseRun {
    program: Program,
    checker: crate::checks::Checker,
    tape: Tape,
    /// Byte offset of the next line.
    offset: usize,
    /// 0-based number of the next line.
    line_no: usize,
    done: bool,
    /// Whether lines of plain words take the short reader (always, but in the tests that
    /// compare it with the general one).
    plain_lines: bool,
    /// Where the program ended at a closing tape mark while its text was still being read
    /// ([`ParseRun::step_growing`]): the text after it is looked at once it is whole
    /// ([`ParseRun::complete`]).
    tape_end: Option<usize>,
    /// The places, among the blocks read since they were last emptied or handed over, of those
    /// that own memory (words past the four stored in a block, or boxed extras): few blocks
    /// do, and the others are let go of at once, without a pass over them
    /// ([`empty_blocks_known`]).
    owning: Vec<u32>,
}

impl ParseRun {
    /// Indexes the lines of `text` (every later step must be given the same text); nothing is
    /// read yet.
    pub fn new(text: &str, dialect: Dialect) -> Self {
        let mut program = Program {
            dialect,
            blocks: Vec::new(),
            exprs: Vec::new(),
            diagnostics: Vec::new(),
            lines: LineIndex::new(text),
            syntec_macro: false,
            linked: Vec::new(),
        };
        // Most lines are one block: reserving for them spares the copies of a growing array.
        program.blocks.reserve_exact(program.lines.line_count());
        ParseRun {
            program,
            checker: crate::checks::Checker::new(dialect),
            // A program that opens with a `%` line (the first line that is not blank) ends at
            // the next `%` line: what follows the closing tape mark is not read (LinuxCNC
            // ignores it; on the Fanuc family it is past the end of the tape).
            tape: Tape::Before,
            offset: 0,
            line_no: 0,
            done: false,
            plain_lines: true,
            tape_end: None,
            owning: Vec::new(),
        }
    }

    /// A run over a text still to be read (a file read a chunk at a time while it is parsed,
    /// see [`ParseRun::step_growing`]): each line's end is found as the line is read, and the
    /// lines are not indexed. It is for a reader that runs a long program piece by piece as it
    /// reads it and has no use for the index (the command line's `stats`, which reads the file
    /// again to report diagnostics at their lines, and only when there are some), where the
    /// index would be four bytes a line of fresh memory for nothing. The program's
    /// [`Program::lines`] holds the first line alone, and [`ParseRun::progress`] counts no
    /// lines but the first in the text.
    pub fn growing_unindexed(dialect: Dialect) -> Self {
        ParseRun::new("", dialect)
    }

    /// Lines read so far and lines in the text.
    pub fn progress(&self) -> (usize, usize) {
        (self.line_no, self.program.lines.line_count())
    }

    /// Reads at most `lines` more lines of `text` (the text given to [`ParseRun::new`]);
    /// whether the whole text is read.
    pub fn step(&mut self, text: &str, lines: usize) -> bool {
        self.read_lines(Some(text), &mut &*text, lines)
    }

    /// [`ParseRun::step`] for a run made with [`ParseRun::growing_unindexed`] over a text that is
    /// still being read: `text` is the part read so far from byte `base` of the whole text on (the
    /// bytes before `base` are read already, and their text need not be kept: a long file is
    /// read through a window). The text grows from call to call, and `base` may move up to
    /// the offset of the next line to read ([`ParseRun::offset`]). Until it is `complete` it
    /// holds whole lines only (each ended by its `\n`), and the run reads none of the line
    /// still to come. The text is UTF-8 (given as bytes, so that a reader can read a file
    /// straight into its window and check each chunk once; a line that is not is read as an
    /// empty one). Whether the whole text is read: never before it is complete, but at a
    /// closing tape mark; call [`ParseRun::complete`] with the rest of the text then.
    pub fn step_growing(&mut self, text: &[u8], base: usize, complete: bool, lines: usize) -> bool {
        self.read_growing(text, base, lines, complete)
    }

    /// Finishes a run read with [`ParseRun::step_growing`] once its text is whole: `text` is
    /// the text from byte `base` on, to its end (`base` at most [`ParseRun::offset`]). Notes
    /// the text after a closing tape mark, as a run over the whole text does.
    pub fn complete(&mut self, text: &[u8], base: usize) {
        if let Some(offset) = self.tape_end.take() {
            ignore_after_tape_end(&mut self.program, &mut Window { text, base }, offset);
        }
    }

    /// Byte offset of the next line to read.
    pub fn offset(&self) -> usize {
        self.offset
    }

    /// Reads at most `lines` more lines from `source` (the same text the run's line index was
    /// made from, see [`ParseRun::with_lines`]); whether the whole text is read.
    ///
    pub fn step_from(&mut self, source: &mut dyn LineSource, lines: usize) -> bool {
        self.read_lines(None, source, lines)
    }

    /// The loop of [`ParseRun::step`] and [`ParseRun::step_from`]: the lines come from `text`
    /// when the whole text is at hand, else from `source` (one dynamic call a line).
    ///
    /// One loop serves every source: made once, it keeps the line reader inlined into it as the
    /// string-only loop did.
    fn read_lines(
        &mut self,
        text: Option<&str>,
        source: &mut dyn LineSource,
        lines: usize,
    ) -> bool {
        let program = &mut self.program;
        let dialect = program.dialect;
        // The lines come from the line index.
        let line_count = program.lines.line_count();
        let stop = self.line_no.saturating_add(lines).min(line_count);
        // The run's state, kept here while the lines are read (stored at the end).
        let mut next = self.line_no;
        let mut offset = self.offset;
        let mut tape = self.tape;
        let mut done = self.done;
        let plain_lines = self.plain_lines;
        let limits = PlainLimits::of(dialect.rules());
        while !done && next < stop {
            let line_no = next;
            let start = program.lines.line_start(line_no) as usize;
            let end = if line_no + 1 < line_count {
                (program.lines.line_start(line_no + 1) as usize).saturating_sub(1)
            } else {
                source.len()
            };
            // The short reader reads bytes: a line of the whole text is taken as bytes, sparing
            // the checks that a `str` is cut between characters (at a newline it always is), and
            // from the line's start on (it finds the same end).
            let (raw, whole, onward) = if let Some(text) = text {
                let onward = text.as_bytes().get(start..).unwrap_or_default();
                (onward.get(..end - start).unwrap_or_default(), None, onward)
            } else {
                let line = source.line(start, end);
                (line.as_bytes(), Some(line), line.as_bytes())
            };
            let raw_len = raw.len();
            let bytes = raw.strip_suffix(b"\r").unwrap_or(raw);
            let line_no = u32::try_from(line_no).unwrap_or(u32::MAX);
            let made = program.blocks.len();
            // A runaway line is cut by the general reader (which reads a plain line as the short
            // one does).
            let plain = if plain_lines && bytes.len() <= MAX_LINE_BYTES {
                read_plain_line(
                    onward,
                    offset,
                    line_no,
                    limits,
                    &mut program.blocks,
                    &mut self.checker,
                )
                .map(|(block, _)| block)
            } else {
                None
            };
            // Whether the line is blank, and whether it is a `%` line, for the tape marks.
            let (blank, percent) = if let Some(block) = plain {
                note_plain_owning(&program.blocks, made, &mut self.owning);
                (!block, false)
            } else {
                let raw = whole
                    .or_else(|| text.and_then(|text| text.get(start..end)))
                    .unwrap_or_default();
                let read = read_general_line(program, &mut self.checker, raw, offset, line_no);
                note_owning(&program.blocks, made, &mut self.owning);
                read
            };
            offset += raw_len + 1;
            next += 1;
            let closed;
            (tape, closed) = tape.after(blank, percent);
            if closed {
                close_tape(program, source, true, offset, &mut self.tape_end);
                done = true;
            }
        }
        self.line_no = next;
        self.offset = offset;
        self.tape = tape;
        self.done = done;
        if self.line_no >= line_count {
            self.done = true;
        }
        self.done
    }

    /// [`ParseRun::read_lines`] for a run over a text still being read
    /// ([`ParseRun::growing_unindexed`]): each line's end is found as it is read (by the short
    /// reader, as it reads a plain line) rather than from a line index. `bytes` start at byte
    /// `base` of the whole text (see [`ParseRun::step_growing`]).
    fn read_growing(&mut self, bytes: &[u8], base: usize, lines: usize, complete: bool) -> bool {
        let program = &mut self.program;
        let limits = PlainLimits::of(program.dialect.rules());
        // A text still being read is read to its last line ending: the line after it is still
        // to come (the text holds whole lines only).
        let readable = if complete {
            usize::MAX
        } else {
            bytes
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(base, |at| base + at + 1)
        };
        let stop = self.line_no.saturating_add(lines);
        let mut next = self.line_no;
        let mut offset = self.offset;
        let mut tape = self.tape;
        let mut done = self.done;
        let plain_lines = self.plain_lines;
        while !done && next < stop && offset < readable {
            let rest = bytes.get(offset.wrapping_sub(base)..).unwrap_or_default();
            let line_no = u32::try_from(next).unwrap_or(u32::MAX);
            let made = program.blocks.len();
            if plain_lines
                && let Some((block, raw_len)) = read_plain_line(
                    rest,
                    offset,
                    line_no,
                    limits,
                    &mut program.blocks,
                    &mut self.checker,
                )
            {
                // One that makes no block is blank; none is a `%` line, so none closes the
                // tape.
                note_plain_owning(&program.blocks, made, &mut self.owning);
                (tape, _) = tape.after(!block, false);
                offset += raw_len + 1;
                next += 1;
                // Not ended by a `\n`: the text's last line.
                done = raw_len >= rest.len();
                continue;
            }
            let raw_len = line_len(rest);
            let at = offset.wrapping_sub(base);
            let raw = bytes.get(at..at + raw_len).unwrap_or_default();
            // Whole at a line's ends, the text is cut between characters.
            let raw = std::str::from_utf8(raw).unwrap_or_default();
            let (blank, percent) =
                read_general_line(program, &mut self.checker, raw, offset, line_no);
            note_owning(&program.blocks, made, &mut self.owning);
            offset += raw_len + 1;
            next += 1;
            if raw_len >= rest.len() {
                // Not ended by a `\n`: the text's last line.
                done = true;
            }
            let closed;
            (tape, closed) = tape.after(blank, percent);
            if closed {
                close_tape(
                    program,
                    &mut Window { text: bytes, base },
                    complete,
                    offset,
                    &mut self.tape_end,
                );
                done = true;
            }
        }
        self.line_no = next;
        self.offset = offset;
        self.tape = tape;
        self.done = done;
        done
    }

    /// Whether the whole text is read.
    pub fn is_done(&self) -> bool {
        self.done
    }

    /// The program as read so far.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Drops the blocks read so far and keeps the rest (expressions, diagnostics, lines), so
    /// that a reader that runs a long program piece by piece as it reads it keeps none of the
    /// pieces it has run; the block array's memory is reused for the next piece.
    pub fn clear_blocks(&mut self) {
        empty_blocks_known(&mut self.program.blocks, &self.owning);
        self.owning.clear();
    }

    /// The places, among the blocks that [`ParseRun::swap_blocks`] hands over next, of those
    /// that own memory: what [`empty_blocks_known`] needs to know of them.
    pub fn take_owning(&mut self) -> Vec<u32> {
        std::mem::take(&mut self.owning)
    }

    /// Hands over the blocks read so far and reads on into `spare` (emptied first), so that a
    /// reader on one thread can pass pieces of a long program to an interpreter on another
    /// and get their arrays back for reuse.
    pub fn swap_blocks(&mut self, mut spare: Vec<Block>) -> Vec<Block> {
        empty_blocks(&mut spare);
        self.owning.clear();
        std::mem::replace(&mut self.program.blocks, spare)
    }

    /// The parsed program (the lines read so far, if the run is not done).
    pub fn finish(self) -> Program {
        let mut program = self.program;
        self.checker.finish(&mut program);
        program
    }
}

impl ParseRun {
    /// Starts a parse over a text whose line index is already made (e.g. from the pieces of a
    /// rope, [`LineIndex::from_chunks`]); the lines are then read with
    /// [`ParseRun::step_from`]. Nothing is read yet.
    pub fn with_lines(lines: LineIndex, dialect: Dialect) -> Self {
        let mut run = ParseRun::new("", dialect);
        run.program.blocks = Vec::with_capacity(lines.line_count());
        run.program.lines = lines;
        run
    }
}

/// Empties `blocks`, keeping the array's memory for the blocks to come (e.g. a piece's array
/// run on one thread, emptied there before it goes back to the reader for reuse).
///
/// Nearly every block owns no memory (its words are stored in it, and it has no statements,
/// comments or program number): such a block is let go of without its destructor, which would
/// find nothing to free, so a million-line program does not pay a million calls for nothing.
pub fn empty_blocks(blocks: &mut Vec<Block>) {
    let mut drain = blocks.drain(..);
    while let Some(block) = drain.as_slice().first() {
        // Looked at in place, so that a block let go of is not moved first.
        if owns_no_memory(block) {
            std::mem::forget(drain.next());
        } else {
            drop(drain.next());
        }
    }
}

/// [`empty_blocks`] for blocks of which it is known which own memory (their places,
/// [`ParseRun::take_owning`]): those let go of what they own, and the array is then emptied at
/// once, without a look at the others. A place left out leaves that block's memory never
/// freed (nothing else goes wrong).
pub fn empty_blocks_known(blocks: &mut Vec<Block>, owning: &[u32]) {
    for &at in owning {
        if let Some(block) = blocks.get_mut(at as usize) {
            drop(std::mem::take(&mut block.words));
            drop(block.extras.take());
        }
    }
    // A drain sets the array's length to the start of its range when it is made: let go of,
    // it leaves the array empty, each block forgotten rather than dropped.
    std::mem::forget(blocks.drain(..));
    // Empty already; were it not, this drops what is left (which frees nothing).
    blocks.clear();
}

/// Notes the places of the blocks from `made` on that own memory in `owning`.
#[inline(always)]
fn note_owning(blocks: &[Block], made: usize, owning: &mut Vec<u32>) {
    for (at, block) in blocks.iter().enumerate().skip(made) {
        if !owns_no_memory(block) {
            owning.push(u32::try_from(at).unwrap_or(u32::MAX));
        }
    }
}

/// [`note_owning`] for a plain line, which makes one block at most (the last, at `made`): the
/// block itself is looked at, without a pass over the blocks made.
#[inline(always)]
fn note_plain_owning(blocks: &[Block], made: usize, owning: &mut Vec<u32>) {
    if blocks.len() > made && blocks.last().is_some_and(|b| !owns_no_memory(b)) {
        owning.push(u32::try_from(made).unwrap_or(u32::MAX));
    }
}

/// Whether dropping `block` frees nothing.
#[inline(always)]
fn owns_no_memory(block: &Block) -> bool {
    // Every field is named, so that a field added to `Block` must be looked at here.
    let Block {
        span: _,
        line: _,
        number: _,
        words,
        extras,
    } = block;
    extras.is_none() && !words.spilled()
}

/// Where the reader is with respect to `%` tape marks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tape {
    /// Only blank lines so far.
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

/// Reads `raw` (a line without its `\n`, at byte `offset`) with the general reader: whether it
/// is blank and whether it is a `%` line, for the tape marks.
fn read_general_line(
    program: &mut Program,
    checker: &mut crate::checks::Checker,
    raw: &str,
    offset: usize,
    line_no: u32,
) -> (bool, bool) {
    let dialect = program.dialect;
    let mut line = raw.strip_suffix('\r').unwrap_or(raw);
    if line.len() > MAX_LINE_BYTES {
        // A runaway line (a binary file, a generator gone wrong): read its start only.
        let mut cut = MAX_LINE_BYTES;
        while !line.is_char_boundary(cut) {
            cut -= 1;
        }
        program.diagnostics.push(Diagnostic::error(
            Span::new(offset + cut, offset + line.len()),
            "E-LINE-LENGTH",
            format!(
                "this line is {} bytes long; only its first {MAX_LINE_BYTES} bytes are read",
                line.len()
            ),
        ));
        line = &line[..cut];
    }
    let mut reader = LineReader {
        dialect,
        rules: dialect.rules(),
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

/// After the line that closes the program, ending at `offset`: the text after it is noted as
/// not read once it is whole (now if `complete`, else its start is kept in `tape_end` for
/// [`ParseRun::complete`]).
fn close_tape(
    program: &mut Program,
    source: &mut dyn LineSource,
    complete: bool,
    offset: usize,
    tape_end: &mut Option<usize>,
) {
    if complete {
        ignore_after_tape_end(program, source, offset);
    } else {
        *tape_end = Some(offset);
    }
}

/// Notes that the text from `offset` on, after the closing `%`, is not read (if it is not blank).
fn ignore_after_tape_end<S: LineSource + ?Sized>(
    program: &mut Program,
    source: &mut S,
    offset: usize,
) {
    let Some((start, end)) = source.trimmed_rest(offset) else {
        return;
    };
    program.diagnostics.push(Diagnostic::note(
        Span::new(start, end),
        "N-AFTER-TAPE-END",
        "the program ends at the closing `%`: the text after it is not read",
    ));
}

/// Digits with an optional decimal point (`12`, `1.5`, `.5`, `3.`), no sign.
fn unsigned(input: &str) -> IResult<&str, &str> {
    // The consumed slice is computed from the remainder: nom 8.0's `recognize` drops the
    // trailing `digit0` of `1.5` (it runs the inner parsers in check mode).
    let (rest, ()) = alt((
        (digit1, opt(char('.')), digit0).map(|_| ()),
        (char('.'), digit1).map(|_| ()),
    ))
    .parse(input)?;
    Ok((rest, &input[..input.len() - rest.len()]))
}

/// A decimal number scanned from the text: `12`, `1.5`, `.5`, `3.` (no sign).
struct Decimal {
    /// Byte offset just after it.
    end: usize,
    /// Its value, as `str::parse::<f64>` gives it.
    value: f64,
    /// Whether it has a decimal point.
    has_point: bool,
    /// How many digits it has.
    digits: usize,
}

/// Scans a decimal number at `pos` in one pass (the hot path of the parser: every word).
///
/// Up to 15 digits the mantissa and the power of ten are exact f64s, so one correctly rounded
/// division gives the correctly rounded value (Clinger's fast path); longer numbers go to the
/// standard library.
fn scan_decimal(bytes: &[u8], pos: usize) -> Option<Decimal> {
    let Digits {
        mantissa,
        end,
        digits,
        frac_digits,
        has_point,
    } = scan_digits(bytes, pos);
    if digits == 0 {
        return None;
    }
    let value = match POW10.get(frac_digits) {
        Some(&scale) if digits <= 15 => decimal_value(mantissa, frac_digits, scale),
        _ => std::str::from_utf8(&bytes[pos..end])
            .ok()
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(f64::NAN),
    };
    Some(Decimal {
        end,
        value,
        has_point,
        digits,
    })
}

/// The value of a mantissa of at most 15 digits, `frac_digits` of them after the point (`scale`
/// is ten to that power): below 10^15 the mantissa converts as a signed integer, exactly as
/// unsigned, and one correctly rounded division gives the value; a whole number (a G or M code,
/// most often) spares the division.
#[inline(always)]
fn decimal_value(mantissa: u64, frac_digits: usize, scale: f64) -> f64 {
    let magnitude = mantissa as i64 as f64;
    if frac_digits == 0 {
        magnitude
    } else {
        magnitude / scale
    }
}

/// The powers of ten that are exact f64s, by number of fraction digits.
const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

/// The digits of an unsigned decimal number (`12`, `12.5`, `.5`, `12.`) at `pos`.
struct Digits {
    /// The digits as one integer, point left out (wrapping: past 19 digits it is unused).
    mantissa: u64,
    /// Where the number ends.
    end: usize,
    /// Digits in all.
    digits: usize,
    /// Digits after the point.
    frac_digits: usize,
    has_point: bool,
}

/// Scans the digits of a number at `pos` (none: `digits` is 0), for [`scan_decimal`] and the
/// short reader of plain lines.
#[inline(always)]
fn scan_digits(bytes: &[u8], pos: usize) -> Digits {
    let n = bytes.len();
    let mut end = pos;
    let mut mantissa: u64 = 0;
    while end < n && bytes[end].is_ascii_digit() {
        mantissa = mantissa
            .wrapping_mul(10)
            .wrapping_add(u64::from(bytes[end] - b'0'));
        end += 1;
    }
    let int_digits = end - pos;
    let has_point = end < n && bytes[end] == b'.';
    let mut frac_digits = 0;
    if has_point {
        end += 1;
        let frac_start = end;
        while end < n && bytes[end].is_ascii_digit() {
            mantissa = mantissa
                .wrapping_mul(10)
                .wrapping_add(u64::from(bytes[end] - b'0'));
            end += 1;
        }
        frac_digits = end - frac_start;
    }
    Digits {
        mantissa,
        end,
        digits: int_digits + frac_digits,
        frac_digits,
        has_point,
    }
}

/// The sign at `pos` before a number: whether it is `-`, and where the number starts.
#[inline(always)]
fn scan_sign(bytes: &[u8], pos: usize) -> (bool, usize) {
    // Without a branch: whether a number is negative is as good as random in a CAM program.
    let b = bytes.get(pos).copied().unwrap_or(0);
    let negative = b == b'-';
    (negative, pos + usize::from(negative | (b == b'+')))
}

/// `value`, a number scanned without its sign (so with no sign bit of its own), negated when
/// `negative` ([`scan_sign`]): without a branch, as the sign is read.
#[inline(always)]
fn with_sign(value: f64, negative: bool) -> f64 {
    f64::from_bits(value.to_bits() | (u64::from(negative) << 63))
}

/// The dialect's limits that [`read_plain_line`] applies, looked up once a step.
#[derive(Debug, Clone, Copy)]
struct PlainLimits {
    /// The number of digits the general reader takes without a diagnostic and that one
    /// division reads exactly (see `scan_decimal`).
    max_digits: usize,
    /// The largest sequence number.
    max_sequence_number: u32,
}

impl PlainLimits {
    fn of(rules: &Rules) -> Self {
        PlainLimits {
            max_digits: match usize::from(rules.max_digits) {
                0 => 15,
                max => max.min(15),
            },
            max_sequence_number: rules.max_sequence_number,
        }
    }
}

/// Reads a line made only of plain words — a letter, an optional sign and a decimal number of
/// at most 15 digits (within the dialect's limit), separated by blanks — and optionally a
/// sequence number first: the line every CAM program is made of (`G1 X5.12 Y0.00 S100`,
/// ` X3.2040 Z-0.1539`, `N20 G0 Z5.`). The block is written in place at the end of `blocks`
/// and checked, exactly as the general reader would make and check it.
///
/// `bytes` is the text from the line's start on: the line ends at its `\n` (a `\r` just before
/// it is not part of it), at a `\r` alone or at the end of `bytes` (see [`line_len`]), and is
/// found as it is read. Returns whether the line gave a block (a blank line gives none) and the
/// length of the line (up to the byte that ends it, a `\r\n` line with its `\r`), or `None`,
/// having read nothing, for any other line (or one over [`MAX_LINE_BYTES`]): the general
/// reader reads it.
#[inline]
fn read_plain_line(
    bytes: &[u8],
    base: usize,
    line_no: u32,
    limits: PlainLimits,
    blocks: &mut Vec<Block>,
    checker: &mut crate::checks::Checker,
) -> Option<(bool, usize)> {
    // A line longer than the longest read whole is left to the general reader, which cuts it:
    // it is read no further than that here, and goes there at its end.
    let bytes = bytes.get(..MAX_LINE_BYTES + 2).unwrap_or(bytes);
    // The line's length with its `\r` if it ends at `pos` (where a `\n`, a `\r\n`, a `\r` alone
    // or the end is): a `\r\n` line keeps its `\r`, a line ended by a `\r` alone does not.
    let end_at = |pos: usize| -> Option<usize> {
        match bytes.get(pos) {
            None | Some(b'\n') => Some(pos),
            Some(b'\r') => Some(pos + usize::from(bytes.get(pos + 1) == Some(&b'\n'))),
            _ => None,
        }
    };
    let mut pos = 0;
    while matches!(bytes.get(pos), Some(b' ' | b'\t')) {
        pos += 1;
    }
    if let Some(raw_len) = end_at(pos) {
        return (pos <= MAX_LINE_BYTES).then_some((false, raw_len));
    }
    // The spans' offsets, when the longest line read here lies in the 4 GiB a span addresses
    // (the general reader clamps the offsets past them).
    let reach = bytes.len();
    let base = u32::try_from(base + reach).ok()? - reach as u32;
    let first = pos;
    let PlainLimits {
        max_digits,
        max_sequence_number,
    } = limits;
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
            || value > max_sequence_number
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
    // Made by the iterator after the array has room for it, the block is written straight into
    // the array (a `push` of a made block copies it there).
    blocks.extend(std::iter::once_with(|| Block {
        line: line_no,
        number: number.and_then(Block::stored_number),
        ..Block::default()
    }));
    let block = blocks.last_mut()?;
    let mut scan = crate::checks::PlainScan::default();
    let raw_len = loop {
        let Some(&b) = bytes.get(pos) else {
            break pos;
        };
        let start = pos;
        let letter = PLAIN_LETTERS[usize::from(b)];
        if letter == 0 {
            if let Some(raw_len) = end_at(pos) {
                break raw_len;
            }
            blocks.pop();
            return None;
        }
        let (negative, at) = scan_sign(bytes, pos + 1);
        // A mantissa of too many digits is not used.
        let Digits {
            mantissa,
            end,
            digits,
            frac_digits,
            has_point,
        } = scan_digits(bytes, at);
        pos = end;
        // At most 15 digits, so at most 15 after the point.
        let scale = POW10.get(frac_digits);
        let (Some(scale), 1..) = (scale, digits) else {
            blocks.pop();
            return None;
        };
        if digits > max_digits || bytes.get(pos) == Some(&b'=') {
            blocks.pop();
            return None;
        }
        let value = with_sign(decimal_value(mantissa, frac_digits, *scale), negative);
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
        last = pos;
        while matches!(bytes.get(pos), Some(b' ' | b'\t')) {
            pos += 1;
        }
    };
    if pos > MAX_LINE_BYTES {
        blocks.pop();
        return None;
    }
    block.span = Span {
        start: base + first as u32,
        end: base + last as u32,
    };
    checker.check_scanned(block, &scan);
    Some((true, raw_len))
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

/// The length of the line `bytes` starts with, up to the byte that ends it (as
/// [`LineIndex`] ends lines): its `\n` (a `\r\n` line keeps its `\r`, which the reader
/// leaves out), a `\r` that no `\n` follows, or the end of `bytes`.
fn line_len(bytes: &[u8]) -> usize {
    let mut at = 0;
    while let Some(off) = bytes
        .get(at..)
        .and_then(|rest| rest.iter().position(|&b| b == b'\n' || b == b'\r'))
    {
        let end = at + off;
        if bytes.get(end) == Some(&b'\n') || bytes.get(end + 1) != Some(&b'\n') {
            return end;
        }
        // `\r\n`: the `\n` ends the line.
        at = end + 1;
    }
    bytes.len()
}

fn is_blank(c: char) -> bool {
    c == ' ' || c == '\t'
}

/// The longest line read in full (1 MiB); the rest of a longer line is reported and skipped.
const MAX_LINE_BYTES: usize = 1 << 20;

/// Whether `c` can only be a stray character where a block item should start: not a blank, a
/// letter, or a character that starts something (comment, block end, slash, variable, comma
/// word, colon, tape mark).
fn is_stray(c: char) -> bool {
    !(is_blank(c)
        || c.is_ascii_alphabetic()
        || matches!(c, '(' | ';' | '/' | '#' | ',' | ':' | '%'))
}

/// The macro keywords of the Fanuc family, and the LinuxCNC O-word keywords.
const KEYWORDS: [&str; 6] = ["IF", "GOTO", "WHILE", "DO", "END", "THEN"];

struct LineReader<'a> {
    dialect: Dialect,
    rules: &'static Rules,
    line: &'a str,
    bytes: &'a [u8],
    base: usize,
    line_no: u32,
    program: &'a mut Program,
    /// The same-block checks, run on each finished block.
    checker: &'a mut crate::checks::Checker,
    /// `[` opened and not yet closed in the expression being read.
    open_brackets: u32,
    /// The statements of the block being read (moved into it when it is finished).
    statements: Vec<Statement>,
    /// The comments of the block being read.
    comments: Vec<Span>,
}

/// A parse failure inside a word or statement: where, and what to say.
struct Fail {
    at: usize,
    end: usize,
    code: &'static str,
    message: String,
}

impl Fail {
    fn new(at: usize, end: usize, code: &'static str, message: impl Into<String>) -> Fail {
        Fail {
            at,
            end,
            code,
            message: message.into(),
        }
    }
}

type PResult<T> = Result<(T, usize), Fail>;

impl LineReader<'_> {
    fn span(&self, start: usize, end: usize) -> Span {
        Span::new(self.base + start, self.base + end)
    }

    fn new_block(&self) -> Block {
        Block {
            line: self.line_no,
            ..Block::default()
        }
    }

    fn error(
        &mut self,
        block: &mut Block,
        start: usize,
        end: usize,
        code: &'static str,
        msg: String,
    ) {
        block.set_error();
        let (start, end) = self.char_range(start, end);
        let span = self.span(start, end);
        self.program
            .diagnostics
            .push(Diagnostic::error(span, code, msg));
    }

    /// `start..end` kept inside the line and widened to whole characters, so that a span that
    /// was computed a byte past a character's start still covers that character.
    fn char_range(&self, start: usize, end: usize) -> (usize, usize) {
        let len = self.line.len();
        let mut start = start.min(len);
        while !self.line.is_char_boundary(start) {
            start -= 1;
        }
        let mut end = end.clamp(start, len);
        while !self.line.is_char_boundary(end) {
            end += 1;
        }
        (start, end)
    }

    fn warn(&mut self, start: usize, end: usize, code: &'static str, msg: String) {
        let span = self.span(start, end);
        self.program
            .diagnostics
            .push(Diagnostic::warning(span, code, msg));
    }

    fn fail(&mut self, block: &mut Block, f: Fail) {
        self.error(block, f.at, f.end, f.code, f.message);
    }

    #[inline]
    fn finish(&mut self, block: Block, first: Option<usize>, last: usize) {
        let statements = std::mem::take(&mut self.statements);
        let comments = std::mem::take(&mut self.comments);
        if let Some(first) = first {
            let mut block = block;
            block.span = self.span(first, last);
            block.set_statements(statements);
            block.set_comments(comments);
            if !block.is_empty()
                || block.number().is_some()
                || block.program().is_some()
                || block.has_error()
                || block.block_delete().is_some()
            {
                self.checker.check(&mut block);
                self.program.blocks.push(block);
            }
        }
    }

    fn skip_blanks(&self, mut pos: usize) -> usize {
        while pos < self.bytes.len() && matches!(self.bytes[pos], b' ' | b'\t') {
            pos += 1;
        }
        pos
    }

    /// The run of ASCII letters starting at `pos`, uppercased.
    fn alpha_run(&self, pos: usize) -> (String, usize) {
        let mut end = pos;
        while end < self.bytes.len() && self.bytes[end].is_ascii_alphabetic() {
            end += 1;
        }
        (self.line[pos..end].to_ascii_uppercase(), end)
    }

    /// Whether everything from `pos` to the end of the block is blanks or comments.
    fn only_trailing(&self, pos: usize) -> bool {
        let rest = self.line[pos..].trim_start_matches(is_blank);
        rest.is_empty()
            || rest.starts_with(';')
            || rest.starts_with('(')
            || (self.rules.slash_comment && rest.starts_with("//"))
    }

    fn read(&mut self) {
        let line = self.line;
        let bytes = self.bytes;
        let mut block = self.new_block();
        // Byte offsets (within the line) of the block's first and last significant characters.
        let mut first: Option<usize> = None;
        let mut last = 0usize;
        let mut pos = 0usize;
        while pos < bytes.len() {
            let c = bytes[pos];
            let start = pos;
            self.open_brackets = 0;
            let at_start = first.is_none();
            match c {
                b' ' | b'\t' => {
                    pos += 1;
                    continue;
                }
                b'%' if at_start => {
                    // Tape start/end mark (the rest of the line belongs to it); Syntec's
                    // `%@MACRO` header marks a macro program.
                    if self.dialect == Dialect::Syntec
                        && line[pos..].to_ascii_uppercase().starts_with("%@MACRO")
                    {
                        self.program.syntec_macro = true;
                    }
                    break;
                }
                b'(' => {
                    if let Some(close) = line[pos..].find(')') {
                        self.comments.push(self.span(pos, pos + close + 1));
                        pos += close + 1;
                    } else {
                        self.comments.push(self.span(pos, bytes.len()));
                        self.error(
                            &mut block,
                            pos,
                            bytes.len(),
                            "E-COMMENT-UNCLOSED",
                            "comment `(` is not closed with `)` on this line".into(),
                        );
                        pos = bytes.len();
                    }
                    continue;
                }
                b';' if self.rules.semicolon_comment => {
                    self.comments.push(self.span(pos, bytes.len()));
                    break;
                }
                b';' => {
                    // End of block: the rest of the line is a new block.
                    let done = std::mem::replace(&mut block, self.new_block());
                    self.finish(done, first.take(), last);
                    pos += 1;
                    continue;
                }
                b'/' if bytes.get(pos + 1) == Some(&b'/') && self.rules.slash_comment => {
                    self.comments.push(self.span(pos, bytes.len()));
                    break;
                }
                b'/' if at_start => {
                    pos += 1;
                    let level = match bytes.get(pos) {
                        Some(d @ b'1'..=b'9') => {
                            pos += 1;
                            d - b'0'
                        }
                        _ => 1,
                    };
                    block.set_block_delete(level);
                }
                b':' if at_start
                    && self.rules.colon_program_number
                    && bytes.get(pos + 1).is_some_and(u8::is_ascii_digit) =>
                {
                    pos = self.read_program_number(&mut block, pos, pos + 1);
                }
                b':' if self.only_trailing(pos + 1)
                    && !(block.words.is_empty() && self.statements.is_empty()) =>
                {
                    // OCR turns `;` into `:` in scanned manuals; read it as the end of the block.
                    self.warn(
                        pos,
                        pos + 1,
                        "W-STRAY-COLON",
                        "`:` at the end of a block is read as the end of the block (`;`)".into(),
                    );
                    pos += 1;
                }
                b'#' => match self.assignment(pos) {
                    Ok((stmt, end)) => {
                        self.statements.push(stmt);
                        pos = end;
                    }
                    Err(f) => {
                        // A broken statement: the rest of the block belongs to it.
                        pos = self.recover(pos, self.block_end(f.end));
                        self.fail(&mut block, f);
                    }
                },
                b',' => {
                    pos = self.read_comma_word(&mut block, pos);
                }
                c if c.is_ascii_alphabetic() => {
                    pos = self.read_letters(&mut block, pos);
                }
                _ => {
                    // One diagnostic for a run of stray characters (`__`, `500`, a remark in
                    // Chinese without a comment marker), not one per character.
                    let end = pos
                        + line[pos..]
                            .find(|c| !is_stray(c))
                            .unwrap_or(line.len() - pos);
                    let end = self.recover(pos, end);
                    let stray = &line[pos..end];
                    let shown = stray.escape_debug();
                    let message = if stray.chars().count() == 1 {
                        format!("unexpected character `{shown}`")
                    } else {
                        format!("unexpected characters `{shown}`")
                    };
                    self.error(&mut block, pos, end, "E-SYNTAX-CHAR", message);
                    pos = end;
                }
            }
            if first.is_none() {
                first = Some(start);
            }
            last = pos.max(last);
        }
        self.finish(block, first, last);
    }

    /// Where to resume after an error at `pos` that ended at `end`: at least one byte on, and
    /// on a character boundary.
    fn recover(&self, pos: usize, end: usize) -> usize {
        let mut at = end.max(pos + 1).min(self.bytes.len());
        while !self.line.is_char_boundary(at) {
            at += 1;
        }
        at
    }

    /// Reads what starts with a letter: a word, a sequence or program number, a macro keyword
    /// statement, or a LinuxCNC O-word line.
    fn read_letters(&mut self, block: &mut Block, pos: usize) -> usize {
        if let Some((word, end)) = self.plain_word(pos) {
            block.words.push(word);
            return end;
        }
        // Keywords are runs of two or more letters; a word is one letter and a value.
        let two_letters = self.bytes.get(pos + 1).is_some_and(u8::is_ascii_alphabetic);
        if two_letters && self.rules.macro_b {
            let (run, run_end) = self.alpha_run(pos);
            if !KEYWORDS.contains(&run.as_str()) {
                return self.read_word_at(block, pos);
            }
            return match self.keyword_statement(&run, pos, run_end) {
                Ok((stmt, end)) => {
                    self.statements.push(stmt);
                    end
                }
                Err(f) => {
                    let end = self.recover(pos, self.block_end(f.end));
                    self.fail(block, f);
                    end
                }
            };
        }
        self.read_word_at(block, pos)
    }

    /// The common case on the hot path: a letter (not N or O) directly followed by a signed
    /// decimal number, as CAM output writes every word (`X12.5`, `Z-0.25`). Anything else —
    /// blanks, expressions, indexed words, errors — is left to the general reader.
    fn plain_word(&self, pos: usize) -> Option<(Word, usize)> {
        let letter = self.bytes[pos].to_ascii_uppercase();
        if letter == b'N' || letter == b'O' {
            return None;
        }
        let (negative, at) = scan_sign(self.bytes, pos + 1);
        let number = scan_decimal(self.bytes, at)?;
        let end = number.end;
        let max = usize::from(self.rules.max_digits);
        if self.bytes.get(end) == Some(&b'=')
            || number.value > 1e15
            || !number.value.is_finite()
            || (max > 0 && number.digits > max)
        {
            return None;
        }
        Some((
            Word {
                letter,
                value: with_sign(number.value, negative),
                has_point: number.has_point,
                span: self.span(pos, end),
                form: WordForm::Plain,
                expr: None,
            },
            end,
        ))
    }

    /// A program or sequence number, an O-word line, or an address word at `pos`.
    fn read_word_at(&mut self, block: &mut Block, pos: usize) -> usize {
        let letter = self.bytes[pos].to_ascii_uppercase();
        if letter == b'O' && block.words.is_empty() && self.statements.is_empty() {
            if self.rules.o_words
                && let Some(end) = self.try_o_word(block, pos)
            {
                return end;
            }
            return self.read_program_number(block, pos, pos + 1);
        }
        if letter == b'N' {
            return self.read_sequence_number(block, pos);
        }
        match self.word(pos) {
            Ok((word, end)) => {
                block.words.push(word);
                end
            }
            Err(f) => {
                let end = self.recover(pos, f.end);
                self.fail(block, f);
                end
            }
        }
    }

    /// `N123` at the start of the block.
    fn read_sequence_number(&mut self, block: &mut Block, pos: usize) -> usize {
        let value_start = self.skip_blanks(pos + 1);
        let Some(number) = scan_decimal(self.bytes, value_start) else {
            self.error(
                block,
                pos,
                pos + 1,
                "E-WORD-VALUE",
                "address `N` needs a number after it".into(),
            );
            return pos + 1;
        };
        let end = number.end;
        let digits = &self.line[value_start..end];
        if !block.words.is_empty() || block.number().is_some() || !self.statements.is_empty() {
            self.error(
                block,
                pos,
                end,
                "E-SEQUENCE-NUMBER",
                "a sequence number `N` must come first in the block".into(),
            );
            return end;
        }
        // Up to nine digits without a point the scanned value is the number exactly.
        let parsed = if !number.has_point && number.digits <= 9 {
            Ok(number.value as u32)
        } else {
            digits.parse::<u32>()
        };
        match parsed {
            Ok(n) => {
                if n > self.rules.max_sequence_number {
                    self.error(
                        block,
                        pos,
                        end,
                        "E-NUMBER-RANGE",
                        format!(
                            "sequence number `N{digits}` is above the largest this control accepts ({})",
                            self.rules.max_sequence_number
                        ),
                    );
                } else {
                    block.set_number(n);
                }
            }
            Err(_) => self.error(
                block,
                pos,
                end,
                "E-SEQUENCE-NUMBER",
                format!("sequence number `N{digits}` must be a whole number"),
            ),
        }
        end
    }

    /// `O1234` (or `:1234`, value starting at `from`) at the start of the block; LinuxCNC also
    /// `O<name>`.
    fn read_program_number(&mut self, block: &mut Block, pos: usize, from: usize) -> usize {
        let value_start = self.skip_blanks(from);
        if self.rules.o_words && self.bytes.get(value_start) == Some(&b'<') {
            return match self.angle_name(value_start) {
                Ok((name, end)) => {
                    block.set_program(ProgramNumber::Name(name));
                    end
                }
                Err(f) => {
                    let end = self.recover(pos, f.end);
                    self.fail(block, f);
                    end
                }
            };
        }
        let rest = &self.line[value_start..];
        let digits_len = rest.bytes().take_while(u8::is_ascii_digit).count();
        let end = value_start + digits_len;
        match rest[..digits_len].parse::<u32>() {
            Ok(n) if digits_len <= 8 => block.set_program(ProgramNumber::Number(n)),
            _ => self.error(
                block,
                pos,
                end.max(pos + 1),
                "E-PROGRAM-NUMBER",
                "a program number `O` needs up to 8 digits after it".into(),
            ),
        }
        end.max(pos + 1)
    }

    /// `<name>` at `pos`: the name lowercased without blanks, as LinuxCNC reads it.
    fn angle_name(&self, pos: usize) -> PResult<Box<str>> {
        let Some(close) = self.line[pos..].find('>') else {
            return Err(Fail::new(
                pos,
                self.line.len(),
                "E-MACRO-SYNTAX",
                "`<` starts a name that is not closed with `>`",
            ));
        };
        let name: String = self.line[pos + 1..pos + close]
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_lowercase();
        if name.is_empty() {
            return Err(Fail::new(
                pos,
                pos + close + 1,
                "E-MACRO-SYNTAX",
                "a name in `<>` must not be empty",
            ));
        }
        Ok((name.into_boxed_str(), pos + close + 1))
    }

    /// A LinuxCNC O-word control line at `pos` (`o100 sub`, `o<x> call [1]`), if it is one.
    fn try_o_word(&mut self, block: &mut Block, pos: usize) -> Option<usize> {
        let label_start = self.skip_blanks(pos + 1);
        let (label, after_label) = match self.bytes.get(label_start) {
            Some(b'<') => {
                let (name, end) = self.angle_name(label_start).ok()?;
                (OLabel::Name(name), end)
            }
            // A computed number: `o[#2 * 10] call`, `o#<sub> call`.
            Some(b'[' | b'#') => match self.word_value(label_start, 0) {
                Ok((expr, end)) => (OLabel::Expr(expr), end),
                Err(f) => {
                    let end = self.recover(pos, self.block_end(f.end));
                    self.fail(block, f);
                    return Some(end);
                }
            },
            _ => {
                let rest = &self.line[label_start..];
                let n = rest.bytes().take_while(u8::is_ascii_digit).count();
                let number = rest[..n].parse::<u32>().ok()?;
                (OLabel::Number(number), label_start + n)
            }
        };
        let kw_start = self.skip_blanks(after_label);
        let (kw, kw_end) = self.alpha_run(kw_start);
        if kw.is_empty() && matches!(label, OLabel::Expr(_)) {
            self.error(
                block,
                pos,
                after_label,
                "E-OWORD",
                "an O-word with a computed number must be followed by a keyword such as `call`"
                    .into(),
            );
            return Some(after_label);
        }
        let kind = match kw.as_str() {
            "SUB" => Some(OWord::Sub),
            "ELSE" => Some(OWord::Else),
            "ENDIF" => Some(OWord::EndIf),
            "ENDWHILE" => Some(OWord::EndWhile),
            "DO" => Some(OWord::Do),
            "ENDREPEAT" => Some(OWord::EndRepeat),
            "BREAK" => Some(OWord::Break),
            "CONTINUE" => Some(OWord::Continue),
            "" => return None,
            _ => None,
        };
        let result: PResult<OWord> = match (kind, kw.as_str()) {
            (Some(k), _) => Ok((k, kw_end)),
            (None, "IF" | "ELSEIF" | "WHILE" | "REPEAT") => {
                self.bracketed(kw_end, 0).map(|(e, end)| {
                    let k = match kw.as_str() {
                        "IF" => OWord::If(e),
                        "ELSEIF" => OWord::ElseIf(e),
                        "WHILE" => OWord::While(e),
                        _ => OWord::Repeat(e),
                    };
                    (k, end)
                })
            }
            (None, "ENDSUB" | "RETURN") => {
                let at = self.skip_blanks(kw_end);
                let value = if self.bytes.get(at) == Some(&b'[') {
                    self.bracketed(at, 0).map(|(e, end)| (Some(e), end))
                } else {
                    Ok((None, kw_end))
                };
                value.map(|(e, end)| {
                    let k = if kw == "ENDSUB" {
                        OWord::EndSub(e)
                    } else {
                        OWord::Return(e)
                    };
                    (k, end)
                })
            }
            (None, "CALL") => {
                let mut args = Vec::new();
                let mut at = self.skip_blanks(kw_end);
                let mut outcome = Ok(());
                while self.bytes.get(at) == Some(&b'[') {
                    match self.bracketed(at, 0) {
                        Ok((e, end)) => {
                            args.push(e);
                            at = self.skip_blanks(end);
                        }
                        Err(f) => {
                            outcome = Err(f);
                            break;
                        }
                    }
                }
                outcome.map(|()| (OWord::Call(args), at))
            }
            _ => Err(Fail::new(
                kw_start,
                kw_end,
                "E-OWORD",
                format!(
                    "`{kw}` is not an O-word keyword (sub, endsub, call, return, if, elseif, else, endif, while, endwhile, do, repeat, endrepeat, break, continue)"
                ),
            )),
        };
        Some(match result {
            Ok((kind, end)) => {
                self.statements.push(Statement::OWord { label, kind });
                end
            }
            Err(f) => {
                let end = self.recover(pos, f.end);
                self.fail(block, f);
                end
            }
        })
    }

    /// `IF`, `GOTO`, `WHILE`, `DO`, `END` statements (Fanuc Macro B).
    fn keyword_statement(&mut self, kw: &str, pos: usize, after: usize) -> PResult<Statement> {
        match kw {
            "GOTO" => {
                let (target, end) = self.word_value(after, 0)?;
                Ok((Statement::Goto { target }, end))
            }
            "IF" => {
                let (cond, end) = self.bracketed(after, 0)?;
                let at = self.skip_blanks(end);
                let (next, next_end) = self.alpha_run(at);
                match next.as_str() {
                    "GOTO" => {
                        let (target, end) = self.word_value(next_end, 0)?;
                        Ok((
                            Statement::If {
                                cond,
                                then: Box::new(Statement::Goto { target }),
                            },
                            end,
                        ))
                    }
                    "THEN" => {
                        let at = self.skip_blanks(next_end);
                        if self.bytes.get(at) != Some(&b'#') {
                            return Err(Fail::new(
                                at,
                                self.block_end(at),
                                "E-MACRO-SYNTAX",
                                "`THEN` must be followed by an assignment `#i=…`",
                            ));
                        }
                        let (stmt, end) = self.assignment(at)?;
                        Ok((
                            Statement::If {
                                cond,
                                then: Box::new(stmt),
                            },
                            end,
                        ))
                    }
                    _ => Err(Fail::new(
                        at,
                        next_end.max(at + 1),
                        "E-MACRO-SYNTAX",
                        "`IF […]` must be followed by `GOTO n` or `THEN #i=…`",
                    )),
                }
            }
            "WHILE" => {
                let (cond, end) = self.bracketed(after, 0)?;
                let at = self.skip_blanks(end);
                let (next, next_end) = self.alpha_run(at);
                if next != "DO" {
                    return Err(Fail::new(
                        at,
                        next_end.max(at + 1),
                        "E-MACRO-SYNTAX",
                        "`WHILE […]` must be followed by `DOm`",
                    ));
                }
                let (label, end) = self.loop_label(at, next_end)?;
                Ok((
                    Statement::While {
                        cond: Some(cond),
                        label,
                    },
                    end,
                ))
            }
            "DO" => {
                let (label, end) = self.loop_label(pos, after)?;
                Ok((Statement::While { cond: None, label }, end))
            }
            "END" => {
                let (label, end) = self.loop_label(pos, after)?;
                Ok((Statement::End { label }, end))
            }
            _ => Err(Fail::new(
                pos,
                after,
                "E-MACRO-SYNTAX",
                format!("`{kw}` must follow `IF […]`"),
            )),
        }
    }

    /// The loop number after `DO`/`END` (1–3 in the Fanuc family).
    fn loop_label(&self, keyword: usize, at: usize) -> PResult<u8> {
        let start = self.skip_blanks(at);
        let rest = &self.line[start..];
        let n = rest.bytes().take_while(u8::is_ascii_digit).count();
        match rest[..n].parse::<u8>() {
            Ok(label @ 1..=3) => Ok((label, start + n)),
            _ => Err(Fail::new(
                keyword,
                (start + n).max(at),
                "E-LOOP-NUMBER",
                "`DO` and `END` take a loop number from 1 to 3",
            )),
        }
    }

    /// `#i = expr` (Syntec also `:=`), starting at the `#`.
    fn assignment(&mut self, pos: usize) -> PResult<Statement> {
        let (target, after) = self.variable(pos, 0)?;
        let at = self.skip_blanks(after);
        let rest = &self.line[at..];
        let value_at = if rest.starts_with(":=") && self.rules.colon_assign {
            at + 2
        } else if rest.starts_with('=') {
            at + 1
        } else {
            return Err(Fail::new(
                pos,
                after,
                "E-MACRO-SYNTAX",
                format!(
                    "variable `{}` must be followed by `=` to assign it",
                    self.line[pos..after].trim()
                ),
            ));
        };
        let (value, end) = self.expression(value_at, 0)?;
        Ok((Statement::Assign { target, value }, end))
    }

    /// A comma word `,C2.` / `,R5.` / `,A30.`.
    fn read_comma_word(&mut self, block: &mut Block, pos: usize) -> usize {
        let at = self.skip_blanks(pos + 1);
        let letter = self.bytes.get(at).map(u8::to_ascii_uppercase);
        let result = match letter {
            Some(l @ (b'C' | b'R' | b'A')) => self.word_from(pos, at, l),
            // Only the comma is wrong: what follows it (`X10, F500`) is read on its own.
            _ => Err(Fail::new(
                pos,
                pos + 1,
                "E-COMMA-WORD",
                "a comma must be followed by `C` (chamfer), `R` (corner rounding) or `A` (angle)",
            )),
        };
        match result {
            Ok((mut word, end)) => {
                word.form = WordForm::Comma;
                if !self.rules.comma_words {
                    self.error(
                        block,
                        pos,
                        end,
                        "E-COMMA-WORD",
                        format!(
                            "{} has no comma words (`,C` chamfer and `,R` corner rounding are LNC and Fanuc syntax)",
                            self.dialect.label()
                        ),
                    );
                }
                block.words.push(word);
                end
            }
            Err(f) => {
                let end = self.recover(pos, f.end);
                self.fail(block, f);
                end
            }
        }
    }

    /// An address word at `pos` (a letter), including `F2=` indexed words.
    fn word(&mut self, pos: usize) -> PResult<Word> {
        let letter = self.bytes[pos].to_ascii_uppercase();
        // `F2=1000`, `S1=150`: letter, one or two digits, `=`, value.
        let digit = |i: usize| self.bytes.get(i).is_some_and(u8::is_ascii_digit);
        let digits = if !digit(pos + 1) {
            0
        } else if self.bytes.get(pos + 2) == Some(&b'=') {
            1
        } else if digit(pos + 2) && self.bytes.get(pos + 3) == Some(&b'=') {
            2
        } else {
            0
        };
        if digits > 0 {
            let index: u8 = self.line[pos + 1..pos + 1 + digits].parse().unwrap_or(0);
            let (mut word, end) = self.word_from(pos, pos + digits + 1, letter)?;
            word.form = WordForm::Indexed(index);
            if !self.rules.indexed_words {
                return Err(Fail::new(
                    pos,
                    end,
                    "E-WORD-INDEXED",
                    format!(
                        "`{}` is Syntec syntax (`F2=` retract feed, `S1=` spindle speed); {} does not read it",
                        &self.line[pos..end],
                        self.dialect.label()
                    ),
                ));
            }
            return Ok((word, end));
        }
        self.word_from(pos, pos, letter)
    }

    /// Reads the value of a word whose text starts at `pos` and whose letter is at `letter_at`.
    fn word_from(&mut self, pos: usize, letter_at: usize, letter: u8) -> PResult<Word> {
        let value_start = self.skip_blanks(letter_at + 1);
        // An indexed word's `=` sits between the letter's digits and the value.
        let value_start = if self.bytes.get(value_start) == Some(&b'=') {
            self.skip_blanks(value_start + 1)
        } else {
            value_start
        };
        let rest = &self.line[value_start..];
        let sign_len = usize::from(rest.starts_with(['+', '-']));
        let after_sign = self.skip_blanks(value_start + sign_len);
        let next = self.bytes.get(after_sign).copied();
        let is_expr = matches!(next, Some(b'#' | b'['))
            || (next.is_some_and(|c| c.is_ascii_alphabetic()) && {
                let (run, _) = self.alpha_run(after_sign);
                Func::NAMES.iter().any(|(n, _)| *n == run)
            });
        if is_expr && (self.rules.macro_b || self.rules.o_words) {
            let (expr, end) = self.word_value(value_start, 0)?;
            return Ok((
                Word {
                    letter,
                    value: 0.0,
                    has_point: true,
                    span: self.span(pos, end),
                    form: WordForm::Plain,
                    expr: Some(expr),
                },
                end,
            ));
        }
        let Some(number) = scan_decimal(self.bytes, after_sign) else {
            let shown = char::from(letter);
            // A run of three or more letters is text, not words: one diagnostic for all of it.
            let (run, run_end) = self.alpha_run(pos);
            if letter_at == pos && run.len() >= 3 {
                return Err(Fail::new(
                    pos,
                    run_end,
                    "E-WORD-VALUE",
                    format!(
                        "`{}` is not a word: address `{shown}` needs a number after it",
                        &self.line[pos..run_end]
                    ),
                ));
            }
            return Err(Fail::new(
                pos,
                letter_at + 1,
                "E-WORD-VALUE",
                format!("address `{shown}` needs a number after it"),
            ));
        };
        let end = number.end;
        let has_point = number.has_point;
        let value = if rest.starts_with('-') {
            -number.value
        } else {
            number.value
        };
        let significant = number.digits;
        let max = usize::from(self.rules.max_digits);
        if !value.is_finite() || value.abs() > 1e15 || (max > 0 && significant > max) {
            return Err(Fail::new(
                pos,
                end,
                "E-NUMBER-RANGE",
                if max > 0 && significant > max {
                    format!(
                        "`{}` has {significant} digits; {} accepts at most {max}",
                        &self.line[pos..end],
                        self.dialect.label()
                    )
                } else {
                    format!("the number `{}` is out of range", &self.line[pos..end])
                },
            ));
        }
        Ok((
            Word {
                letter,
                value,
                has_point,
                span: self.span(pos, end),
                form: WordForm::Plain,
                expr: None,
            },
            end,
        ))
    }

    // ---- expressions ----

    fn push(&mut self, expr: Expr, start: usize, end: usize) -> Result<ExprId, Fail> {
        let id = ExprId::from_index(self.program.exprs.len()).ok_or_else(|| {
            Fail::new(
                start,
                end,
                "E-TOO-LARGE",
                "the program has too many expressions",
            )
        })?;
        let span = self.span(start, end);
        self.program.exprs.push(ExprNode { expr, span });
        Ok(id)
    }

    fn depth_check(&self, pos: usize, depth: u32) -> Result<(), Fail> {
        if depth >= HARD_DEPTH {
            return Err(Fail::new(
                pos,
                self.block_end(pos),
                "E-EXPR-DEPTH",
                format!("expression nested more than {HARD_DEPTH} levels deep"),
            ));
        }
        Ok(())
    }

    /// A word's value: an optionally signed number, variable, bracketed expression or function
    /// call (no binary operators outside brackets, as the controls read words).
    fn word_value(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.unary(pos, depth)
    }

    /// A full expression with binary operators.
    fn expression(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.binary(pos, 0, depth)
    }

    fn precedence(&self, op: BinOp) -> u8 {
        let fanuc = self.rules.fanuc_logic_precedence;
        match op {
            BinOp::Pow => 5,
            BinOp::Mul | BinOp::Div | BinOp::Mod => 4,
            BinOp::And if fanuc => 4,
            BinOp::Add | BinOp::Sub => 3,
            BinOp::Or | BinOp::Xor if fanuc => 3,
            BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le => 2,
            BinOp::And | BinOp::Or | BinOp::Xor => 1,
        }
    }

    /// The binary operator at `pos`, if any, and where it ends.
    fn operator(&self, pos: usize) -> Option<(BinOp, usize)> {
        let at = self.skip_blanks(pos);
        let rest = &self.line[at..];
        let symbol = if rest.starts_with("**") {
            Some((BinOp::Pow, 2))
        } else {
            match rest.bytes().next() {
                Some(b'+') => Some((BinOp::Add, 1)),
                Some(b'-') => Some((BinOp::Sub, 1)),
                Some(b'*') => Some((BinOp::Mul, 1)),
                Some(b'/') if !rest.starts_with("//") || !self.rules.slash_comment => {
                    Some((BinOp::Div, 1))
                }
                _ => None,
            }
        };
        if let Some((op, len)) = symbol {
            return Some((op, at + len));
        }
        let (run, end) = self.alpha_run(at);
        let op = match run.as_str() {
            "MOD" => BinOp::Mod,
            "AND" => BinOp::And,
            "OR" => BinOp::Or,
            "XOR" => BinOp::Xor,
            "EQ" => BinOp::Eq,
            "NE" => BinOp::Ne,
            "GT" => BinOp::Gt,
            "GE" => BinOp::Ge,
            "LT" => BinOp::Lt,
            "LE" => BinOp::Le,
            _ => return None,
        };
        Some((op, end))
    }

    fn binary(&mut self, pos: usize, min: u8, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        let (mut lhs, mut end) = self.unary(start, depth + 1)?;
        while let Some((op, op_end)) = self.operator(end) {
            let prec = self.precedence(op);
            if prec < min {
                break;
            }
            // `**` is right-associative; everything else is left-associative.
            let next_min = if op == BinOp::Pow { prec } else { prec + 1 };
            let (rhs, rhs_end) = self.binary(op_end, next_min, depth + 1)?;
            lhs = self.push(Expr::Binary(op, lhs, rhs), start, rhs_end)?;
            end = rhs_end;
        }
        Ok((lhs, end))
    }

    fn unary(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        match self.bytes.get(start) {
            Some(b'-') => {
                let (inner, end) = self.unary(start + 1, depth + 1)?;
                // Fold `-5` into a literal so plain negative numbers stay one node.
                if let Some(ExprNode {
                    expr: Expr::Num(v), ..
                }) = self.program.expr(inner)
                {
                    let v = -*v;
                    let span = self.span(start, end);
                    if let Some(node) = self.program.exprs.get_mut(inner.index()) {
                        node.expr = Expr::Num(v);
                        node.span = span;
                    }
                    return Ok((inner, end));
                }
                let id = self.push(Expr::Neg(inner), start, end)?;
                Ok((id, end))
            }
            Some(b'+') => self.unary(start + 1, depth + 1),
            _ => self.primary(start, depth + 1),
        }
    }

    fn primary(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(start, depth)?;
        match self.bytes.get(start) {
            Some(b'#') => self.variable(start, depth),
            Some(b'[') => self.bracketed(start, depth),
            Some(c) if c.is_ascii_digit() || *c == b'.' => {
                let Ok((rest, digits)) = unsigned(&self.line[start..]) else {
                    return Err(Fail::new(start, start + 1, "E-EXPR", "expected a number"));
                };
                let end = self.line.len() - rest.len();
                // `1e3` is no number to a control: refused, not read as 1 and a word `E3`.
                let after = self.bytes.get(end + 1..).unwrap_or_default();
                let exponent_digit = match after.first() {
                    Some(b'+' | b'-') => after.get(1).is_some_and(u8::is_ascii_digit),
                    Some(c) => c.is_ascii_digit(),
                    None => false,
                };
                if matches!(self.bytes.get(end), Some(b'e' | b'E')) && exponent_digit {
                    let stop = end
                        + 1
                        + after
                            .iter()
                            .enumerate()
                            .take_while(|&(i, c)| {
                                c.is_ascii_digit() || (i == 0 && b"+-".contains(c))
                            })
                            .count();
                    return Err(Fail::new(
                        start,
                        stop,
                        "E-EXPR",
                        format!(
                            "`{}`: a number with an exponent is not read by the control; write it out in full",
                            &self.line[start..stop]
                        ),
                    ));
                }
                let value = digits.parse::<f64>().unwrap_or(f64::NAN);
                if !value.is_finite() || value > 1e15 {
                    return Err(Fail::new(
                        start,
                        end,
                        "E-NUMBER-RANGE",
                        format!("the number `{digits}` is out of range"),
                    ));
                }
                let id = self.push(Expr::Num(value), start, end)?;
                Ok((id, end))
            }
            Some(c) if c.is_ascii_alphabetic() => self.call(start, depth),
            _ => {
                let end = self.line[start..]
                    .chars()
                    .next()
                    .map_or(start + 1, |c| start + c.len_utf8());
                Err(Fail::new(
                    start,
                    end.min(self.line.len()).max(start),
                    "E-EXPR",
                    if start >= self.line.len() {
                        "expected a value, found the end of the line".to_string()
                    } else {
                        format!("expected a value, found `{}`", &self.line[start..end])
                    },
                ))
            }
        }
    }

    /// `#1`, `#[expr]`, `##1`, `#<name>`.
    fn variable(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(start, depth)?;
        let at = self.skip_blanks(start + 1);
        if self.bytes.get(at) == Some(&b'<') {
            if !self.rules.o_words {
                return Err(Fail::new(
                    start,
                    at + 1,
                    "E-MACRO-SYNTAX",
                    format!(
                        "named parameters `#<name>` are LinuxCNC syntax; {} numbers its variables",
                        self.dialect.label()
                    ),
                ));
            }
            let (name, end) = self.angle_name(at)?;
            let id = self.push(Expr::Named(name), start, end)?;
            return Ok((id, end));
        }
        let (index, end) = match self.bytes.get(at) {
            Some(b'#') => self.variable(at, depth + 1)?,
            Some(b'[') => self.bracketed(at, depth + 1)?,
            Some(c) if c.is_ascii_digit() => self.primary(at, depth + 1)?,
            _ => {
                return Err(Fail::new(
                    start,
                    at.max(start + 1),
                    "E-MACRO-SYNTAX",
                    "`#` must be followed by a variable number, `[expression]` or `#`",
                ));
            }
        };
        let id = self.push(Expr::Var(index), start, end)?;
        Ok((id, end))
    }

    /// `[expr]` starting at (or after blanks before) `pos`.
    fn bracketed(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        if self.bytes.get(start) != Some(&b'[') {
            return Err(Fail::new(
                start,
                (start + 1).min(self.line.len()).max(start),
                "E-EXPR",
                "expected `[`",
            ));
        }
        self.open_bracket(start)?;
        let (inner, end) = self.expression(start + 1, depth + 1)?;
        self.open_brackets = self.open_brackets.saturating_sub(1);
        let close = self.skip_blanks(end);
        if self.bytes.get(close) != Some(&b']') {
            return Err(Fail::new(
                start,
                close.max(start + 1).min(self.line.len()),
                "E-EXPR-BRACKET",
                "`[` is not closed with `]`",
            ));
        }
        Ok((inner, close + 1))
    }

    /// Counts the `[` at `start` as open; more than the dialect allows is an error.
    fn open_bracket(&mut self, start: usize) -> Result<(), Fail> {
        self.open_brackets += 1;
        let nesting = self.open_brackets;
        let max = u32::from(self.rules.max_bracket_depth);
        if nesting > max {
            return Err(Fail::new(
                start,
                self.block_end(start),
                "E-EXPR-DEPTH",
                format!(
                    "brackets nested {nesting} deep; {} allows {max}",
                    self.dialect.label()
                ),
            ));
        }
        Ok(())
    }

    /// A function call `SIN[…]`, `ATAN[a]/[b]`, `ATAN[a,b]`, `POW[a,b]`.
    fn call(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        let (name, name_end) = self.alpha_run(start);
        let Some((_, func)) = Func::NAMES.iter().find(|(n, _)| *n == name) else {
            return Err(Fail::new(
                start,
                name_end,
                "E-EXPR",
                format!(
                    "`{name}` is not a function (SIN, COS, TAN, ASIN, ACOS, ATAN, SQRT, ABS, ROUND, FIX, FUP, LN, EXP, POW, BIN, BCD)"
                ),
            ));
        };
        let func = *func;
        let open = self.skip_blanks(name_end);
        if self.bytes.get(open) != Some(&b'[') {
            return Err(Fail::new(
                start,
                name_end,
                "E-EXPR",
                format!("`{name}` must be followed by `[`"),
            ));
        }
        let two_args = matches!(func, Func::Atan | Func::Pow);
        if func == Func::Exists {
            let (arg, end) = self.bracketed(open, depth + 1)?;
            let id = self.push(Expr::Call(func, arg, None), start, end)?;
            return Ok((id, end));
        }
        // `[a,b]` form.
        self.open_bracket(open)?;
        let (first, after_first) = self.expression(open + 1, depth + 1)?;
        let at = self.skip_blanks(after_first);
        let (second, end) = match self.bytes.get(at) {
            Some(b',') if two_args => {
                let (second, after) = self.expression(at + 1, depth + 1)?;
                let close = self.skip_blanks(after);
                if self.bytes.get(close) != Some(&b']') {
                    return Err(Fail::new(
                        open,
                        close.min(self.line.len()),
                        "E-EXPR-BRACKET",
                        "`[` is not closed with `]`",
                    ));
                }
                self.open_brackets = self.open_brackets.saturating_sub(1);
                (Some(second), close + 1)
            }
            Some(b']') => {
                self.open_brackets = self.open_brackets.saturating_sub(1);
                let end = at + 1;
                // `ATAN[a]/[b]`.
                let slash = self.skip_blanks(end);
                if func == Func::Atan
                    && self.bytes.get(slash) == Some(&b'/')
                    && self.bytes.get(self.skip_blanks(slash + 1)) == Some(&b'[')
                {
                    let (second, end) = self.bracketed(slash + 1, depth + 1)?;
                    (Some(second), end)
                } else {
                    (None, end)
                }
            }
            _ => {
                return Err(Fail::new(
                    open,
                    at.min(self.line.len()),
                    "E-EXPR-BRACKET",
                    "`[` is not closed with `]`",
                ));
            }
        };
        if func == Func::Pow && second.is_none() {
            return Err(Fail::new(
                start,
                end,
                "E-EXPR",
                "`POW` takes two arguments: `POW[base,exponent]`",
            ));
        }
        let id = self.push(Expr::Call(func, first, second), start, end)?;
        Ok((id, end))
    }

    /// End of the current block: the next `;` (Fanuc family) or the end of the line.
    fn block_end(&self, from: usize) -> usize {
        if self.rules.semicolon_comment {
            return self.line.len();
        }
        // `;` is ASCII, so searching the bytes is safe from any offset.
        let from = from.min(self.line.len());
        self.bytes[from..]
            .iter()
            .position(|&b| b == b';')
            .map_or(self.line.len(), |i| from + i)
    }
}

#[cfg(test)]
#[path = "../../../tests/support/programs.rs"]
mod test_programs;

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// `text` read by the general line reader alone.
    fn parse_general(text: &str, dialect: Dialect) -> Program {
        let mut run = ParseRun::new(text, dialect);
        run.plain_lines = false;
        while !run.step(text, usize::MAX) {}
        run.finish()
    }

    /// The short reader of plain lines gives what the general reader gives: the same blocks
    /// (values to the bit) and the same diagnostics.
    fn assert_same_as_general(text: &str, dialect: Dialect) {
        let fast = parse(text, dialect);
        let general = parse_general(text, dialect);
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
        // Read as the command line reads it: a run over a text still being read, which finds
        // each line's end as it reads the line, in pieces of a few lines (its line index holds
        // the first line alone).
        for lines in [1, 3, 1000] {
            let mut run = ParseRun::growing_unindexed(dialect);
            while !run.step_growing(text.as_bytes(), 0, true, lines) {}
            let mut grown = run.finish();
            assert_eq!(grown.lines.line_count(), 1);
            grown.lines = general.lines.clone();
            assert_eq!(grown, general, "{dialect:?} grown by {lines}: {text:?}");
            assert!(same_values(&grown, &general), "{dialect:?}: {text:?}");
        }
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
    fn pieces_read_into_emptied_arrays_make_the_whole_program() {
        let text =
            "O100 (a program)\nG1 X1 Y2 Z3 A4 B5 C6 F7\n#1 = 2\nG0 X#1\n N10 X1.5\n\nX2 (c)\n"
                .repeat(20);
        for dialect in Dialect::ALL {
            let whole = parse(&text, dialect);
            // Blocks that own memory and blocks that own none, both let go of.
            assert!(whole.blocks.iter().any(owns_no_memory), "{dialect:?}");
            assert!(!whole.blocks.iter().all(owns_no_memory), "{dialect:?}");
            let mut run = ParseRun::new(&text, dialect);
            let mut blocks = Vec::new();
            let mut spare = Vec::new();
            for turn in 0.. {
                let done = run.step(&text, 3);
                if turn % 2 == 0 {
                    blocks.extend(run.program().blocks.iter().cloned());
                    run.clear_blocks();
                } else {
                    spare = run.swap_blocks(spare);
                    blocks.extend(spare.iter().cloned());
                }
                assert!(run.program().blocks.is_empty());
                if done {
                    break;
                }
            }
            assert_eq!(blocks, whole.blocks, "{dialect:?}");
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

    #[test]
    fn number_forms() {
        assert_eq!(unsigned("12X"), Ok(("X", "12")));
        assert_eq!(unsigned("1.5"), Ok(("", "1.5")));
        assert_eq!(unsigned(".5"), Ok(("", ".5")));
        assert_eq!(unsigned("3."), Ok(("", "3.")));
        assert!(unsigned("X").is_err());
        assert!(unsigned("-").is_err());
    }

    #[test]
    fn fast_decimal_values_match_the_standard_parser() {
        for text in [
            "0",
            "1",
            "12.5",
            ".5",
            "3.",
            "0.001",
            "123456.789",
            "99999999",
            "0.1",
            "0.3",
            "2.675",
            "1234567890.12345",
            "12345678901234567890",
            "0.000000000000001",
            "1234567890123456.5",
        ] {
            let expected: f64 = text.parse().unwrap();
            let d = scan_decimal(text.as_bytes(), 0).unwrap();
            assert_eq!(d.value, expected, "{text}");
            assert_eq!(d.end, text.len());
            assert_eq!(d.has_point, text.contains('.'));
        }
        let d = scan_decimal(b"12.5.3X", 0).unwrap();
        assert_eq!((d.end, d.value, d.digits), (4, 12.5, 3));
        assert!(scan_decimal(b"X", 0).is_none());
        assert!(scan_decimal(b".", 0).is_none());
    }
}
