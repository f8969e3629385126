//! Statements: LinuxCNC O-word lines, the Fanuc family's macro keywords (`IF`, `GOTO`,
//! `WHILE`, `DO`, `END`) and assignments.

use super::block::{Fail, LineReader, PResult};
use crate::ast::{ExprId, OLabel, OWord, Statement};
use crate::{Block, excerpt};

impl LineReader<'_> {
    /// A LinuxCNC O-word control line at `pos` (`o100 sub`, `o<x> call [1]`), if it is one.
    pub(super) fn try_o_word(&mut self, block: &mut Block, pos: usize) -> Option<usize> {
        let label_start = self.skip_blanks(pos + 1);
        let (label, after_label) = match self.bytes.get(label_start) {
            Some(b'<') => {
                let (name, end) = self.angle_name(label_start).ok()?;
                (OLabel::Name(name), end)
            }
            // A computed number: `o[#2 * 10] call`, `o#<sub> call`.
            Some(b'[' | b'#') => match self.word_value(label_start, 0) {
                Ok((expr, end)) => (OLabel::Expr(expr), end),
                Err(f) => return Some(self.failed(block, pos, f, true)),
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
            let message =
                "an O-word with a computed number must be followed by a keyword such as `call`";
            self.error(block, pos, after_label, "E-OWORD", message);
            return Some(after_label);
        }
        let result: PResult<OWord> = match kw.as_str() {
            "" => return None,
            "SUB" => Ok((OWord::Sub, kw_end)),
            "ELSE" => Ok((OWord::Else, kw_end)),
            "ENDIF" => Ok((OWord::EndIf, kw_end)),
            "ENDWHILE" => Ok((OWord::EndWhile, kw_end)),
            "DO" => Ok((OWord::Do, kw_end)),
            "ENDREPEAT" => Ok((OWord::EndRepeat, kw_end)),
            "BREAK" => Ok((OWord::Break, kw_end)),
            "CONTINUE" => Ok((OWord::Continue, kw_end)),
            "IF" => made(self.bracketed(kw_end, 0), OWord::If),
            "ELSEIF" => made(self.bracketed(kw_end, 0), OWord::ElseIf),
            "WHILE" => made(self.bracketed(kw_end, 0), OWord::While),
            "REPEAT" => made(self.bracketed(kw_end, 0), OWord::Repeat),
            "ENDSUB" => made(self.optional_bracketed(kw_end), OWord::EndSub),
            "RETURN" => made(self.optional_bracketed(kw_end), OWord::Return),
            "CALL" => self.call_args(kw_end),
            _ => {
                let message = format!(
                    "`{}` is not an O-word keyword (sub, endsub, call, return, if, elseif, else, endif, while, endwhile, do, repeat, endrepeat, break, continue)",
                    excerpt(&kw)
                );
                Err(Fail::new(kw_start, kw_end, "E-OWORD", message))
            }
        };
        let keep =
            |s: &mut Self, _: &mut Block, kind| s.statements.push(Statement::OWord { label, kind });
        Some(self.settle(block, pos, result, false, keep))
    }

    /// `[expr]` after the blanks at `pos`, if one is there.
    fn optional_bracketed(&mut self, pos: usize) -> PResult<Option<ExprId>> {
        let at = self.skip_blanks(pos);
        if self.bytes.get(at) != Some(&b'[') {
            return Ok((None, pos));
        }
        self.bracketed(at, 0).map(|(e, end)| (Some(e), end))
    }

    /// The bracketed arguments of an O-word `call`, from `pos`.
    fn call_args(&mut self, pos: usize) -> PResult<OWord> {
        let (mut args, mut at) = (Vec::new(), self.skip_blanks(pos));
        while self.bytes.get(at) == Some(&b'[') {
            let (e, end) = self.bracketed(at, 0)?;
            args.push(e);
            at = self.skip_blanks(end);
        }
        Ok((OWord::Call(args), at))
    }

    /// `IF`, `GOTO`, `WHILE`, `DO`, `END` statements (Fanuc Macro B).
    pub(super) fn keyword_statement(
        &mut self,
        kw: &str,
        pos: usize,
        after: usize,
    ) -> PResult<Statement> {
        match kw {
            "GOTO" => {
                let (target, end) = self.word_value(after, 0)?;
                Ok((Statement::Goto { target }, end))
            }
            "IF" => {
                let (cond, end) = self.bracketed(after, 0)?;
                let at = self.skip_blanks(end);
                let (next, next_end) = self.alpha_run(at);
                let then_at = self.skip_blanks(next_end);
                let (then, end) = match next.as_str() {
                    "GOTO" => self.keyword_statement("GOTO", at, next_end)?,
                    "THEN" if self.bytes.get(then_at) == Some(&b'#') => self.assignment(then_at)?,
                    "THEN" => {
                        let stop = self.block_end(then_at);
                        let message = "`THEN` must be followed by an assignment `#i=…`";
                        return Err(Fail::new(then_at, stop, "E-MACRO-SYNTAX", message));
                    }
                    _ => {
                        let stop = next_end.max(at + 1);
                        let message = "`IF […]` must be followed by `GOTO n` or `THEN #i=…`";
                        return Err(Fail::new(at, stop, "E-MACRO-SYNTAX", message));
                    }
                };
                let then = Box::new(then);
                Ok((Statement::If { cond, then }, end))
            }
            "WHILE" => {
                let (cond, end) = self.bracketed(after, 0)?;
                let at = self.skip_blanks(end);
                let (next, next_end) = self.alpha_run(at);
                if next != "DO" {
                    let stop = next_end.max(at + 1);
                    let message = "`WHILE […]` must be followed by `DOm`";
                    return Err(Fail::new(at, stop, "E-MACRO-SYNTAX", message));
                }
                let (label, end) = self.loop_label(at, next_end)?;
                let cond = Some(cond);
                Ok((Statement::While { cond, label }, end))
            }
            "DO" => {
                let (label, end) = self.loop_label(pos, after)?;
                Ok((Statement::While { cond: None, label }, end))
            }
            "END" => {
                let (label, end) = self.loop_label(pos, after)?;
                Ok((Statement::End { label }, end))
            }
            _ => {
                let message = format!("`{kw}` must follow `IF […]`");
                Err(Fail::new(pos, after, "E-MACRO-SYNTAX", message))
            }
        }
    }

    /// The loop number after `DO`/`END` (1–3 in the Fanuc family).
    fn loop_label(&self, keyword: usize, at: usize) -> PResult<u8> {
        let start = self.skip_blanks(at);
        let rest = &self.line[start..];
        let n = rest.bytes().take_while(u8::is_ascii_digit).count();
        if let Ok(label @ 1..=3) = rest[..n].parse::<u8>() {
            return Ok((label, start + n));
        }
        let message = "`DO` and `END` take a loop number from 1 to 3";
        let end = (start + n).max(at);
        Err(Fail::new(keyword, end, "E-LOOP-NUMBER", message))
    }

    /// `#i = expr` (Syntec also `:=`), starting at the `#`.
    pub(super) fn assignment(&mut self, pos: usize) -> PResult<Statement> {
        let (target, after) = self.variable(pos, 0)?;
        let at = self.skip_blanks(after);
        let rest = &self.line[at..];
        let value_at = if rest.starts_with(":=") && self.rules.colon_assign {
            at + 2
        } else if rest.starts_with('=') {
            at + 1
        } else {
            let variable = excerpt(self.line[pos..after].trim());
            let message = format!("variable `{variable}` must be followed by `=` to assign it");
            return Err(Fail::new(pos, after, "E-MACRO-SYNTAX", message));
        };
        let (value, end) = self.expression(value_at, 0)?;
        Ok((Statement::Assign { target, value }, end))
    }
}

/// `result` with its value made into another by `make`.
fn made<T, U>(result: PResult<T>, make: impl FnOnce(T) -> U) -> PResult<U> {
    result.map(|(v, end)| (make(v), end))
}
