//! Expressions: numbers, variables, brackets, function calls and binary operators, in the
//! expression arena of the program.

use super::block::{Fail, LineReader, PResult};
use super::number::scan_decimal;
use crate::ast::{BinOp, Expr, ExprId, ExprNode, Func};
use crate::excerpt;

/// Nesting depth at which the parser stops descending into an expression, whatever the dialect
/// allows (so hostile input cannot exhaust the stack).
const HARD_DEPTH: u32 = 64;

impl LineReader<'_> {
    /// Adds the node for `start..end` to the arena.
    fn push(&mut self, expr: Expr, start: usize, end: usize) -> PResult<ExprId> {
        let Some(id) = ExprId::from_index(self.program.exprs.len()) else {
            let message = "the program has too many expressions";
            return Err(Fail::new(start, end, "E-TOO-LARGE", message));
        };
        let span = self.span(start, end);
        self.program.exprs.push(ExprNode { expr, span });
        Ok((id, end))
    }

    fn depth_check(&self, pos: usize, depth: u32) -> Result<(), Fail> {
        if depth < HARD_DEPTH {
            return Ok(());
        }
        let message = format!("expression nested more than {HARD_DEPTH} levels deep");
        Err(Fail::new(pos, self.block_end(pos), "E-EXPR-DEPTH", message))
    }

    /// A full expression with binary operators.
    pub(super) fn expression(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
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
        let comment = rest.starts_with("//") && self.rules.slash_comment;
        let symbols = [BinOp::Pow, BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div];
        if let Some(op) = symbols.into_iter().find(|op| rest.starts_with(op.symbol())) {
            return (!comment).then_some((op, at + op.symbol().len()));
        }
        let (run, end) = self.alpha_run(at);
        let op = BinOp::ALL.iter().find(|op| op.symbol() == run)?;
        Some((*op, end))
    }

    fn binary(&mut self, pos: usize, min: u8, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        let (mut lhs, mut end) = self.word_value(start, depth + 1)?;
        while let Some((op, op_end)) = self.operator(end) {
            let prec = self.precedence(op);
            if prec < min {
                break;
            }
            // `**` is right-associative; everything else is left-associative.
            let next_min = if op == BinOp::Pow { prec } else { prec + 1 };
            let (rhs, rhs_end) = self.binary(op_end, next_min, depth + 1)?;
            (lhs, end) = self.push(Expr::Binary(op, lhs, rhs), start, rhs_end)?;
        }
        Ok((lhs, end))
    }

    /// A word's value: an optionally signed number, variable, bracketed expression or function
    /// call (no binary operators outside brackets, as the controls read words).
    pub(super) fn word_value(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        match self.bytes.get(start) {
            Some(b'-') => {
                let (inner, end) = self.word_value(start + 1, depth + 1)?;
                let span = self.span(start, end);
                // Fold `-5` into a literal so plain negative numbers stay one node.
                if let Some(node) = self.program.exprs.get_mut(inner.index())
                    && let Expr::Num(v) = &mut node.expr
                {
                    *v = -*v;
                    node.span = span;
                    return Ok((inner, end));
                }
                self.push(Expr::Neg(inner), start, end)
            }
            Some(b'+') => self.word_value(start + 1, depth + 1),
            _ => self.primary(start, depth + 1),
        }
    }

    fn primary(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(start, depth)?;
        match self.bytes.get(start) {
            Some(b'#') => self.variable(start, depth),
            Some(b'[') => self.bracketed(start, depth),
            Some(c) if c.is_ascii_digit() || *c == b'.' => {
                let Some(number) = scan_decimal(self.bytes, start) else {
                    return Err(Fail::new(start, start + 1, "E-EXPR", "expected a number"));
                };
                let (end, value) = (number.end, number.value);
                // `1e3` is no number to a control: refused, not read as 1 and a word `E3`.
                if matches!(self.bytes.get(end), Some(b'e' | b'E')) {
                    let sign = usize::from(matches!(self.bytes.get(end + 1), Some(b'+' | b'-')));
                    let after = self.bytes.get(end + 1 + sign..).unwrap_or_default();
                    let exponent = after.iter().take_while(|c| c.is_ascii_digit()).count();
                    let stop = end + 1 + sign + exponent;
                    if exponent > 0 {
                        let number = excerpt(&self.line[start..stop]);
                        let message = format!(
                            "`{number}`: a number with an exponent is not read by the control; write it out in full"
                        );
                        return Err(Fail::new(start, stop, "E-EXPR", message));
                    }
                }
                if !value.is_finite() || value > 1e15 {
                    let digits = excerpt(&self.line[start..end]);
                    let message = format!("the number `{digits}` is out of range");
                    return Err(Fail::new(start, end, "E-NUMBER-RANGE", message));
                }
                self.push(Expr::Num(value), start, end)
            }
            Some(c) if c.is_ascii_alphabetic() => self.call(start, depth),
            _ => {
                let found = self.line.get(start..).and_then(|rest| rest.chars().next());
                let end = start + found.map_or(0, char::len_utf8);
                let what = found.map_or("the end of the line".to_string(), |c| format!("`{c}`"));
                let message = format!("expected a value, found {what}");
                Err(Fail::new(start, end, "E-EXPR", message))
            }
        }
    }

    /// `#1`, `#[expr]`, `##1`, `#<name>`.
    pub(super) fn variable(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(start, depth)?;
        let at = self.skip_blanks(start + 1);
        if self.bytes.get(at) == Some(&b'<') {
            if !self.rules.o_words {
                let label = self.program.dialect.label();
                let message = format!(
                    "named parameters `#<name>` are LinuxCNC syntax; {label} numbers its variables"
                );
                return Err(Fail::new(start, at + 1, "E-MACRO-SYNTAX", message));
            }
            let (name, end) = self.angle_name(at)?;
            return self.push(Expr::Named(name), start, end);
        }
        let (index, end) = match self.bytes.get(at) {
            Some(b'#') => self.variable(at, depth + 1)?,
            Some(b'[') => self.bracketed(at, depth + 1)?,
            Some(c) if c.is_ascii_digit() => self.primary(at, depth + 1)?,
            _ => {
                let message = "`#` must be followed by a variable number, `[expression]` or `#`";
                let end = at.max(start + 1);
                return Err(Fail::new(start, end, "E-MACRO-SYNTAX", message));
            }
        };
        self.push(Expr::Var(index), start, end)
    }

    /// `[expr]` starting at (or after blanks before) `pos`.
    pub(super) fn bracketed(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.depth_check(pos, depth)?;
        let start = self.skip_blanks(pos);
        if self.bytes.get(start) != Some(&b'[') {
            let end = (start + 1).min(self.line.len()).max(start);
            return Err(Fail::new(start, end, "E-EXPR", "expected `[`"));
        }
        self.open_bracket(start)?;
        let (inner, end) = self.expression(start + 1, depth + 1)?;
        self.open_brackets = self.open_brackets.saturating_sub(1);
        let close = self.skip_blanks(end);
        if self.bytes.get(close) != Some(&b']') {
            return Err(unclosed(start, close.max(start + 1).min(self.line.len())));
        }
        Ok((inner, close + 1))
    }

    /// Counts the `[` at `start` as open; more than the dialect allows is an error.
    fn open_bracket(&mut self, start: usize) -> Result<(), Fail> {
        self.open_brackets += 1;
        let nesting = self.open_brackets;
        let max = u32::from(self.rules.max_bracket_depth);
        if nesting <= max {
            return Ok(());
        }
        let label = self.program.dialect.label();
        let message = format!("brackets nested {nesting} deep; {label} allows {max}");
        let end = self.block_end(start);
        Err(Fail::new(start, end, "E-EXPR-DEPTH", message))
    }

    /// A function call `SIN[…]`, `ATAN[a]/[b]`, `ATAN[a,b]`, `POW[a,b]`.
    fn call(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
        let (name, name_end) = self.alpha_run(start);
        let Some((_, func)) = Func::names().find(|(n, _)| *n == name) else {
            let name = excerpt(&name);
            let message = format!(
                "`{name}` is not a function (SIN, COS, TAN, ASIN, ACOS, ATAN, SQRT, ABS, ROUND, FIX, FUP, LN, EXP, POW, BIN, BCD)"
            );
            return Err(Fail::new(start, name_end, "E-EXPR", message));
        };
        let open = self.skip_blanks(name_end);
        if self.bytes.get(open) != Some(&b'[') {
            let message = format!("`{}` must be followed by `[`", excerpt(&name));
            return Err(Fail::new(start, name_end, "E-EXPR", message));
        }
        let two_args = matches!(func, Func::Atan | Func::Pow);
        if func == Func::Exists {
            let (arg, end) = self.bracketed(open, depth + 1)?;
            return self.push(Expr::Call(func, arg, None), start, end);
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
                    return Err(unclosed(open, close.min(self.line.len())));
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
            _ => return Err(unclosed(open, at.min(self.line.len()))),
        };
        if func == Func::Pow && second.is_none() {
            let message = "`POW` takes two arguments: `POW[base,exponent]`";
            return Err(Fail::new(start, end, "E-EXPR", message));
        }
        self.push(Expr::Call(func, first, second), start, end)
    }
}

/// The failure of a `[` at `open` that is not closed before `end`.
fn unclosed(open: usize, end: usize) -> Fail {
    Fail::new(open, end, "E-EXPR-BRACKET", "`[` is not closed with `]`")
}
