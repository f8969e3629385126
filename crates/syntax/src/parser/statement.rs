//! Statements: LinuxCNC O-word lines, the Fanuc family's macro keywords (`IF`, `GOTO`,
//! `WHILE`, `DO`, `END`) and assignments.

use super::block::{Fail, LineReader, PResult};
use crate::ast::{OLabel, OWord, Statement};
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
                    "`{}` is not an O-word keyword (sub, endsub, call, return, if, elseif, else, endif, while, endwhile, do, repeat, endrepeat, break, continue)",
                    excerpt(&kw)
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
    pub(super) fn assignment(&mut self, pos: usize) -> PResult<Statement> {
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
                    excerpt(self.line[pos..after].trim())
                ),
            ));
        };
        let (value, end) = self.expression(value_at, 0)?;
        Ok((Statement::Assign { target, value }, end))
    }
}
