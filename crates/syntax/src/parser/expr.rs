//! Expressions: numbers, variables, brackets, function calls and binary operators, in the
//! expression arena of the program.

use super::block::{Fail, LineReader, PResult};
use super::number::unsigned;
use crate::ast::{BinOp, Expr, ExprId, ExprNode, Func};
use crate::excerpt;

/// Nesting depth at which the parser stops descending into an expression, whatever the dialect
/// allows (so hostile input cannot exhaust the stack).
const HARD_DEPTH: u32 = 64;

impl LineReader<'_> {
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
    pub(super) fn word_value(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
        self.unary(pos, depth)
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
                            excerpt(&self.line[start..stop])
                        ),
                    ));
                }
                let value = digits.parse::<f64>().unwrap_or(f64::NAN);
                if !value.is_finite() || value > 1e15 {
                    return Err(Fail::new(
                        start,
                        end,
                        "E-NUMBER-RANGE",
                        format!("the number `{}` is out of range", excerpt(digits)),
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
    pub(super) fn variable(&mut self, start: usize, depth: u32) -> PResult<ExprId> {
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
    pub(super) fn bracketed(&mut self, pos: usize, depth: u32) -> PResult<ExprId> {
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
                    "`{}` is not a function (SIN, COS, TAN, ASIN, ACOS, ATAN, SQRT, ABS, ROUND, FIX, FUP, LN, EXP, POW, BIN, BCD)",
                    excerpt(&name)
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
                format!("`{}` must be followed by `[`", excerpt(&name)),
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
}
