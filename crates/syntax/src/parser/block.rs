//! The general line reader: blocks, words, sequence and program numbers, comments; the
//! statements and expressions in a line are read by `statement.rs` and `expr.rs`.

use super::is_blank;
use super::number::{scan_decimal, scan_sign, with_sign};
use crate::ast::{ExprId, Func, ProgramNumber, Statement};
use crate::{Block, Diagnostic, Dialect, Program, Rules, Span, Word, WordForm, excerpt};

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

/// Reads one line with the general reader into the program's blocks, expressions and
/// diagnostics.
pub(super) struct LineReader<'a> {
    pub(super) rules: &'static Rules,
    pub(super) line: &'a str,
    pub(super) bytes: &'a [u8],
    pub(super) base: usize,
    pub(super) line_no: u32,
    pub(super) program: &'a mut Program,
    /// The same-block checks, run on each finished block.
    pub(super) checker: &'a mut crate::checks::Checker,
    /// `[` opened and not yet closed in the expression being read.
    pub(super) open_brackets: u32,
    /// The statements of the block being read (moved into it when it is finished).
    pub(super) statements: Vec<Statement>,
    /// The comments of the block being read.
    pub(super) comments: Vec<Span>,
}

/// A parse failure inside a word or statement: where, and what to say.
pub(super) struct Fail {
    pub(super) at: usize,
    pub(super) end: usize,
    pub(super) code: &'static str,
    pub(super) message: String,
}

impl Fail {
    pub(super) fn new(at: usize, end: usize, code: &'static str, msg: impl Into<String>) -> Fail {
        let message = msg.into();
        Fail {
            at,
            end,
            code,
            message,
        }
    }
}

pub(super) type PResult<T> = Result<(T, usize), Fail>;

impl LineReader<'_> {
    pub(super) fn span(&self, start: usize, end: usize) -> Span {
        Span::new(self.base + start, self.base + end)
    }

    fn new_block(&self) -> Block {
        Block {
            line: self.line_no,
            ..Block::default()
        }
    }

    pub(super) fn error(
        &mut self,
        block: &mut Block,
        at: usize,
        end: usize,
        code: &'static str,
        msg: impl Into<String>,
    ) {
        block.extras_mut().has_error = true;
        let (start, end) = self.char_range(at, end);
        let error = Diagnostic::error(self.span(start, end), code, msg);
        self.program.diagnostics.push(error);
    }

    /// `start..end` kept inside the line and widened to whole characters, so that a span that
    /// was computed a byte past a character's start still covers that character.
    fn char_range(&self, start: usize, end: usize) -> (usize, usize) {
        let start = self.line.floor_char_boundary(start);
        (start, self.line.ceil_char_boundary(end.max(start)))
    }

    /// Reports `f` and returns where to resume: past the failure, or past the rest of the block
    /// when `whole` (a broken statement owns the rest of the block).
    pub(super) fn failed(&mut self, block: &mut Block, pos: usize, f: Fail, whole: bool) -> usize {
        let end = if whole { self.block_end(f.end) } else { f.end };
        let end = self.recover(pos, end);
        self.error(block, f.at, f.end, f.code, f.message);
        end
    }

    /// Keeps what `read` read with `keep`, or reports its failure; returns where to resume.
    pub(super) fn settle<T>(
        &mut self,
        block: &mut Block,
        pos: usize,
        read: PResult<T>,
        whole: bool,
        keep: impl FnOnce(&mut Self, &mut Block, T),
    ) -> usize {
        match read {
            Ok((t, end)) => {
                keep(self, block, t);
                end
            }
            Err(f) => self.failed(block, pos, f, whole),
        }
    }

    #[inline]
    fn finish(&mut self, mut block: Block, first: Option<usize>, last: usize) {
        let statements = std::mem::take(&mut self.statements);
        let comments = std::mem::take(&mut self.comments);
        let Some(first) = first else { return };
        block.span = self.span(first, last);
        // No statements and no comments make no room for them.
        if block.extras.is_some() || !(statements.is_empty() && comments.is_empty()) {
            let extras = block.extras_mut();
            extras.statements = statements.into_boxed_slice();
            extras.comments = comments.into_boxed_slice();
        }
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

    pub(super) fn skip_blanks(&self, mut pos: usize) -> usize {
        while pos < self.bytes.len() && matches!(self.bytes[pos], b' ' | b'\t') {
            pos += 1;
        }
        pos
    }

    /// The run of ASCII letters starting at `pos`, uppercased.
    pub(super) fn alpha_run(&self, pos: usize) -> (String, usize) {
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

    pub(super) fn read(&mut self) {
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
                    if self.program.dialect == Dialect::Syntec
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
                        let message = "comment `(` is not closed with `)` on this line";
                        self.error(&mut block, pos, bytes.len(), "E-COMMENT-UNCLOSED", message);
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
                    block.extras_mut().block_delete = Some(level);
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
                    let message = "`:` at the end of a block is read as the end of the block (`;`)";
                    let warning =
                        Diagnostic::warning(self.span(pos, pos + 1), "W-STRAY-COLON", message);
                    self.program.diagnostics.push(warning);
                    pos += 1;
                }
                b'#' => {
                    let read = self.assignment(pos);
                    pos = self.settle(&mut block, pos, read, true, |s, _, st| {
                        s.statements.push(st);
                    });
                }
                b',' => pos = self.read_comma_word(&mut block, pos),
                c if c.is_ascii_alphabetic() => pos = self.read_letters(&mut block, pos),
                _ => {
                    // One diagnostic for a run of stray characters (`__`, `500`, a remark in
                    // Chinese without a comment marker), not one per character.
                    let end = (line[pos..].find(|c| !is_stray(c))).map_or(line.len(), |i| pos + i);
                    let end = self.recover(pos, end);
                    let stray = &line[pos..end];
                    let shown = excerpt(stray);
                    let shown = shown.escape_debug();
                    let s = if stray.chars().count() == 1 { "" } else { "s" };
                    let message = format!("unexpected character{s} `{shown}`");
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
    pub(super) fn recover(&self, pos: usize, end: usize) -> usize {
        self.line.ceil_char_boundary(end.max(pos + 1))
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
            let read = self.keyword_statement(&run, pos, run_end);
            return self.settle(block, pos, read, true, |s, _, st| s.statements.push(st));
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
        let value = with_sign(number.value, negative);
        Some(self.plain(letter, value, number.has_point, pos, end, None))
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
        let read = self.word(pos);
        self.settle(block, pos, read, false, |_, b, w| b.words.push(w))
    }

    /// `N123` at the start of the block.
    fn read_sequence_number(&mut self, block: &mut Block, pos: usize) -> usize {
        let value_start = self.skip_blanks(pos + 1);
        let Some(number) = scan_decimal(self.bytes, value_start) else {
            let message = "address `N` needs a number after it";
            self.error(block, pos, pos + 1, "E-WORD-VALUE", message);
            return pos + 1;
        };
        let end = number.end;
        let digits = &self.line[value_start..end];
        if !block.words.is_empty() || block.number().is_some() || !self.statements.is_empty() {
            let message = "a sequence number `N` must come first in the block";
            self.error(block, pos, end, "E-SEQUENCE-NUMBER", message);
            return end;
        }
        // Up to nine digits without a point the scanned value is the number exactly.
        let parsed = if !number.has_point && number.digits <= 9 {
            Ok(number.value as u32)
        } else {
            digits.parse::<u32>()
        };
        let (shown, max) = (excerpt(digits), self.rules.max_sequence_number);
        match parsed {
            Ok(n) if n <= max => block.number = Block::stored_number(n),
            Ok(_) => {
                let message = format!(
                    "sequence number `N{shown}` is above the largest this control accepts ({max})"
                );
                self.error(block, pos, end, "E-NUMBER-RANGE", message);
            }
            Err(_) => {
                let message = format!("sequence number `N{shown}` must be a whole number");
                self.error(block, pos, end, "E-SEQUENCE-NUMBER", message);
            }
        }
        end
    }

    /// `O1234` (or `:1234`, value starting at `from`) at the start of the block; LinuxCNC also
    /// `O<name>`.
    fn read_program_number(&mut self, block: &mut Block, pos: usize, from: usize) -> usize {
        let value_start = self.skip_blanks(from);
        if self.rules.o_words && self.bytes.get(value_start) == Some(&b'<') {
            let read = self.angle_name(value_start);
            return self.settle(block, pos, read, false, |_, b, name| {
                b.extras_mut().program = Some(ProgramNumber::Name(name));
            });
        }
        let rest = &self.line[value_start..];
        let digits_len = rest.bytes().take_while(u8::is_ascii_digit).count();
        let end = (value_start + digits_len).max(pos + 1);
        match rest[..digits_len].parse::<u32>() {
            Ok(n) if digits_len <= 8 => block.extras_mut().program = Some(ProgramNumber::Number(n)),
            _ => {
                let message = "a program number `O` needs up to 8 digits after it";
                self.error(block, pos, end, "E-PROGRAM-NUMBER", message);
            }
        }
        end
    }

    /// `<name>` at `pos`: the name lowercased without blanks, as LinuxCNC reads it.
    pub(super) fn angle_name(&self, pos: usize) -> PResult<Box<str>> {
        let Some(close) = self.line[pos..].find('>') else {
            let message = "`<` starts a name that is not closed with `>`";
            return Err(Fail::new(pos, self.line.len(), "E-MACRO-SYNTAX", message));
        };
        let name = self.line[pos + 1..pos + close].replace(char::is_whitespace, "");
        let name = name.to_ascii_lowercase();
        if name.is_empty() {
            let message = "a name in `<>` must not be empty";
            return Err(Fail::new(pos, pos + close + 1, "E-MACRO-SYNTAX", message));
        }
        Ok((name.into_boxed_str(), pos + close + 1))
    }

    /// A comma word `,C2.` / `,R5.` / `,A30.`.
    fn read_comma_word(&mut self, block: &mut Block, pos: usize) -> usize {
        let at = self.skip_blanks(pos + 1);
        let letter = self.bytes.get(at).map(u8::to_ascii_uppercase);
        let read = if let Some(l @ (b'C' | b'R' | b'A')) = letter {
            self.word_from(pos, at, l)
        } else {
            // Only the comma is wrong: what follows it (`X10, F500`) is read on its own.
            let message =
                "a comma must be followed by `C` (chamfer), `R` (corner rounding) or `A` (angle)";
            Err(Fail::new(pos, pos + 1, "E-COMMA-WORD", message))
        };
        if let (Ok((_, end)), false) = (&read, self.rules.comma_words) {
            let dialect = self.program.dialect.label();
            let message = format!(
                "{dialect} has no comma words (`,C` chamfer and `,R` corner rounding are LNC and Fanuc syntax)"
            );
            self.error(block, pos, *end, "E-COMMA-WORD", message);
        }
        self.settle(block, pos, read, false, |_, b, mut word| {
            word.form = WordForm::Comma;
            b.words.push(word);
        })
    }

    /// An address word at `pos` (a letter), including `F2=` indexed words.
    fn word(&mut self, pos: usize) -> PResult<Word> {
        let letter = self.bytes[pos].to_ascii_uppercase();
        // `F2=1000`, `S1=150`: letter, one or two digits, `=`, value.
        let digit = |i: usize| self.bytes.get(i).is_some_and(u8::is_ascii_digit);
        let indexed = |n: usize| {
            (1..=n).all(|i| digit(pos + i)) && self.bytes.get(pos + n + 1) == Some(&b'=')
        };
        if let Some(digits) = (1..=2).find(|&n| indexed(n)) {
            let index: u8 = self.line[pos + 1..pos + 1 + digits].parse().unwrap_or(0);
            let (mut word, end) = self.word_from(pos, pos + digits + 1, letter)?;
            word.form = WordForm::Indexed(index);
            if !self.rules.indexed_words {
                let (text, dialect) = (excerpt(&self.line[pos..end]), self.program.dialect.label());
                let message = format!(
                    "`{text}` is Syntec syntax (`F2=` retract feed, `S1=` spindle speed); {dialect} does not read it"
                );
                return Err(Fail::new(pos, end, "E-WORD-INDEXED", message));
            }
            return Ok((word, end));
        }
        self.word_from(pos, pos, letter)
    }

    /// Reads the value of a word whose text starts at `pos` and whose letter is at `letter_at`.
    fn word_from(&mut self, pos: usize, letter_at: usize, letter: u8) -> PResult<Word> {
        let value_start = self.skip_blanks(letter_at + 1);
        // An indexed word's `=` sits between the letter's digits and the value.
        let equals = usize::from(self.bytes.get(value_start) == Some(&b'='));
        let value_start = self.skip_blanks(value_start + equals);
        let rest = &self.line[value_start..];
        let sign_len = usize::from(rest.starts_with(['+', '-']));
        let after_sign = self.skip_blanks(value_start + sign_len);
        let next = self.bytes.get(after_sign).copied();
        let is_expr = matches!(next, Some(b'#' | b'['))
            || (next.is_some_and(|c| c.is_ascii_alphabetic()) && {
                let (run, _) = self.alpha_run(after_sign);
                Func::names().any(|(n, _)| n == run)
            });
        if is_expr && (self.rules.macro_b || self.rules.o_words) {
            let (expr, end) = self.word_value(value_start, 0)?;
            return Ok(self.plain(letter, 0.0, true, pos, end, Some(expr)));
        }
        let Some(number) = scan_decimal(self.bytes, after_sign) else {
            let shown = char::from(letter);
            // A run of three or more letters is text, not words: one diagnostic for all of it.
            let (run, run_end) = self.alpha_run(pos);
            if letter_at == pos && run.len() >= 3 {
                let text = excerpt(&self.line[pos..run_end]);
                let message =
                    format!("`{text}` is not a word: address `{shown}` needs a number after it");
                return Err(Fail::new(pos, run_end, "E-WORD-VALUE", message));
            }
            let message = format!("address `{shown}` needs a number after it");
            return Err(Fail::new(pos, letter_at + 1, "E-WORD-VALUE", message));
        };
        let (end, significant) = (number.end, number.digits);
        let value = with_sign(number.value, rest.starts_with('-'));
        let max = usize::from(self.rules.max_digits);
        if max > 0 && significant > max {
            let (text, dialect) = (excerpt(&self.line[pos..end]), self.program.dialect.label());
            let message =
                format!("`{text}` has {significant} digits; {dialect} accepts at most {max}");
            return Err(Fail::new(pos, end, "E-NUMBER-RANGE", message));
        }
        if !value.is_finite() || value.abs() > 1e15 {
            let text = excerpt(&self.line[pos..end]);
            let message = format!("the number `{text}` is out of range");
            return Err(Fail::new(pos, end, "E-NUMBER-RANGE", message));
        }
        Ok(self.plain(letter, value, number.has_point, pos, end, None))
    }

    /// A plain-form word spanning `pos..end`, with `end`.
    #[inline]
    fn plain(
        &self,
        letter: u8,
        value: f64,
        has_point: bool,
        pos: usize,
        end: usize,
        expr: Option<ExprId>,
    ) -> (Word, usize) {
        let (span, form) = (self.span(pos, end), WordForm::Plain);
        let word = Word {
            letter,
            value,
            has_point,
            span,
            form,
            expr,
        };
        (word, end)
    }

    /// End of the current block: the next `;` (Fanuc family) or the end of the line.
    pub(super) fn block_end(&self, from: usize) -> usize {
        if self.rules.semicolon_comment {
            return self.line.len();
        }
        // `;` is ASCII, so searching the bytes is safe from any offset.
        let from = from.min(self.line.len());
        (self.bytes[from..].iter().position(|&b| b == b';')).map_or(self.line.len(), |i| from + i)
    }
}
