//! The fault-tolerant block parser.
//!
//! Each line is read on its own (the newline is the recovery point); a problem inside a line
//! becomes a diagnostic, the offending characters are skipped, and reading goes on.

use nom::branch::alt;
use nom::bytes::complete::take_while;
use nom::character::complete::{char, digit0, digit1, one_of};
use nom::combinator::opt;
use nom::{IResult, Parser};

use crate::{Block, Diagnostic, Dialect, LineIndex, Program, Span, Word};

/// Parses `text` as read by `dialect`. Never fails: problems are in `Program::diagnostics`.
pub fn parse(text: &str, dialect: Dialect) -> Program {
    let mut program = Program {
        dialect,
        blocks: Vec::with_capacity(text.len() / 20 + 1),
        diagnostics: Vec::new(),
        lines: LineIndex::new(text),
    };
    let mut offset = 0usize;
    for (line_no, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let mut reader = LineReader {
            dialect,
            line,
            base: offset,
            line_no: u32::try_from(line_no).unwrap_or(u32::MAX),
            program: &mut program,
        };
        reader.read();
        offset += raw.len() + 1;
    }
    program
}

/// Optional sign, then digits with an optional decimal point (`12`, `-1.5`, `.5`, `3.`).
fn number(input: &str) -> IResult<&str, &str> {
    // The consumed slice is computed from the remainder: nom 8.0's `recognize` drops the
    // trailing `digit0` of `1.5` (it runs the inner parsers in check mode).
    let (rest, _) = (
        opt(one_of("+-")),
        take_while(is_blank),
        alt((
            (digit1, opt(char('.')), digit0).map(|_| ()),
            (char('.'), digit1).map(|_| ()),
        )),
    )
        .parse(input)?;
    Ok((rest, &input[..input.len() - rest.len()]))
}

fn is_blank(c: char) -> bool {
    c == ' ' || c == '\t'
}

struct LineReader<'a> {
    dialect: Dialect,
    line: &'a str,
    base: usize,
    line_no: u32,
    program: &'a mut Program,
}

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
        block.has_error = true;
        let span = self.span(start, end);
        self.program
            .diagnostics
            .push(Diagnostic::error(span, code, msg));
    }

    fn finish(&mut self, block: Block, first: Option<usize>, last: usize) {
        if let Some(first) = first {
            let mut block = block;
            block.span = self.span(first, last);
            if !block.words.is_empty()
                || block.number.is_some()
                || block.has_error
                || block.block_delete.is_some()
            {
                self.program.blocks.push(block);
            }
        }
    }

    fn read(&mut self) {
        let line = self.line;
        let bytes = line.as_bytes();
        let mut block = self.new_block();
        // Byte offsets (within the line) of the block's first and last significant characters.
        let mut first: Option<usize> = None;
        let mut last = 0usize;
        let mut pos = 0usize;
        while pos < bytes.len() {
            let c = bytes[pos];
            let start = pos;
            match c {
                b' ' | b'\t' => {
                    pos += 1;
                    continue;
                }
                b'%' if first.is_none() && block.words.is_empty() => {
                    // Tape start/end mark: the rest of the line belongs to it.
                    break;
                }
                b'(' => {
                    match line[pos..].find(')') {
                        Some(close) => {
                            block.comments.push(self.span(pos, pos + close + 1));
                            pos += close + 1;
                        }
                        None => {
                            block.comments.push(self.span(pos, bytes.len()));
                            self.error(
                                &mut block,
                                pos,
                                bytes.len(),
                                "E-COMMENT-UNCLOSED",
                                "comment `(` is not closed with `)` on this line".into(),
                            );
                            pos = bytes.len();
                        }
                    }
                    continue;
                }
                b';' if self.dialect.semicolon_is_comment() => {
                    block.comments.push(self.span(pos, bytes.len()));
                    break;
                }
                b';' => {
                    // End of block: the rest of the line is a new block.
                    let done = std::mem::replace(&mut block, self.new_block());
                    self.finish(done, first.take(), last);
                    pos += 1;
                    continue;
                }
                b'/' if bytes.get(pos + 1) == Some(&b'/') && self.dialect == Dialect::Syntec => {
                    block.comments.push(self.span(pos, bytes.len()));
                    break;
                }
                b'/' if first.is_none() => {
                    pos += 1;
                    let level = match bytes.get(pos) {
                        Some(d @ b'1'..=b'9') => {
                            pos += 1;
                            d - b'0'
                        }
                        _ => 1,
                    };
                    block.block_delete = Some(level);
                }
                b'#' | b'[' => {
                    let end = self.block_end(pos);
                    self.error(
                        &mut block,
                        pos,
                        end,
                        "E-MACRO-UNSUPPORTED",
                        "macro statements and variables are not interpreted yet; this block is skipped"
                            .into(),
                    );
                    pos = end;
                }
                b',' => {
                    let end = self.word_end(pos + 1);
                    self.error(
                        &mut block,
                        pos,
                        end,
                        "E-COMMA-UNSUPPORTED",
                        format!(
                            "comma word `{}` (chamfer/corner rounding) is not interpreted yet",
                            &line[pos..end]
                        ),
                    );
                    pos = end;
                }
                c if c.is_ascii_alphabetic() => {
                    pos = self.read_word(&mut block, pos);
                }
                _ => {
                    let ch = line[pos..].chars().next().unwrap_or('\u{FFFD}');
                    let end = pos + ch.len_utf8();
                    self.error(
                        &mut block,
                        pos,
                        end,
                        "E-SYNTAX-CHAR",
                        format!("unexpected character `{}`", ch.escape_debug()),
                    );
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

    /// End of the current block: the next `;` (Fanuc family) or the end of the line.
    fn block_end(&self, from: usize) -> usize {
        if self.dialect.semicolon_is_comment() {
            return self.line.len();
        }
        self.line[from..]
            .find(';')
            .map_or(self.line.len(), |i| from + i)
    }

    /// End of a word's value characters starting at `from` (digits, sign, point, blanks).
    fn word_end(&self, from: usize) -> usize {
        let bytes = self.line.as_bytes();
        let mut end = from;
        while end < bytes.len()
            && (bytes[end].is_ascii_alphanumeric() || b"+-. \t".contains(&bytes[end]))
        {
            if end > from && bytes[end].is_ascii_alphabetic() {
                break;
            }
            end += 1;
        }
        end
    }

    /// Reads one address word at `pos` (a letter); returns the position after it.
    fn read_word(&mut self, block: &mut Block, pos: usize) -> usize {
        let line = self.line;
        let letter = line.as_bytes()[pos].to_ascii_uppercase();
        let after_letter = pos + 1;
        let rest = &line[after_letter..];
        let trimmed = rest.trim_start_matches(is_blank);
        let value_start = after_letter + (rest.len() - trimmed.len());
        let Ok((remaining, digits)) = number(trimmed) else {
            let shown = char::from(letter);
            self.error(
                block,
                pos,
                after_letter,
                "E-WORD-VALUE",
                format!("address `{shown}` needs a number after it"),
            );
            return after_letter;
        };
        let end = value_start + (trimmed.len() - remaining.len());
        let cleaned: String = digits.chars().filter(|c| !is_blank(*c)).collect();
        let value = cleaned.parse::<f64>().unwrap_or(f64::NAN);
        if !value.is_finite() || value.abs() > 1e15 {
            self.error(
                block,
                pos,
                end,
                "E-NUMBER-RANGE",
                format!("the number `{cleaned}` is out of range"),
            );
            return end;
        }
        let span = self.span(pos, end);
        match letter {
            b'N' if block.words.is_empty() && block.number.is_none() => {
                if value < 0.0 || value.fract() != 0.0 || value > f64::from(u32::MAX) {
                    self.error(
                        block,
                        pos,
                        end,
                        "E-SEQUENCE-NUMBER",
                        format!("sequence number `N{cleaned}` must be a whole number"),
                    );
                } else {
                    // The check above keeps the value in u32's range.
                    block.number = Some(value as u32);
                }
            }
            b'N' => {
                self.error(
                    block,
                    pos,
                    end,
                    "E-SEQUENCE-NUMBER",
                    "a sequence number `N` must come first in the block".into(),
                );
            }
            _ => block.words.push(Word {
                letter,
                value,
                has_point: cleaned.contains('.'),
                span,
            }),
        }
        end
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_forms() {
        assert_eq!(number("12X"), Ok(("X", "12")));
        assert_eq!(number("-1.5"), Ok(("", "-1.5")));
        assert_eq!(number(".5"), Ok(("", ".5")));
        assert_eq!(number("3."), Ok(("", "3.")));
        assert_eq!(number("+ 7"), Ok(("", "+ 7")));
        assert!(number("X").is_err());
        assert!(number("-").is_err());
    }
}
