//! The program's structure, indexed once before it runs (`O` programs, `N` labels, Macro B loops
//! and LinuxCNC O-word lines), so calls, jumps and loops find their targets without a rescan.

use std::collections::HashMap;

use swarf_syntax::{
    Block, Diagnostic, Expr, ExprId, Missing, OLabel, OWord, Program, ProgramNumber, Statement,
    excerpt,
};

use crate::diagnostics::Diagnostics;

/// A LinuxCNC O-word label as a map key (`o100`, `o<name>`; computed ones by value).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) enum LabelKey {
    Number(u32),
    Name(Box<str>),
}

/// The index of one parsed program.
#[derive(Debug, Clone, Default)]
pub(crate) struct Index {
    /// Block index where each `O` program starts (its `O` block), in text order.
    starts: Vec<usize>,
    /// `O` number → index into `starts`.
    numbers: HashMap<u32, usize>,
    /// `O<name>` → index into `starts`.
    names: HashMap<Box<str>, usize>,
    /// (program, N, block) of every numbered block, sorted: a jump goes to the first.
    labels: Vec<(u32, u32, u32)>,
    /// `WHILE … DOm` / `DOm` block → its `ENDm` block, and back.
    pub(crate) loop_end: HashMap<usize, usize>,
    pub(crate) loop_head: HashMap<usize, usize>,
    /// O-word label → its lines in text order.
    owords: HashMap<LabelKey, Vec<(usize, OWord)>>,
    /// The first block with a program number: the main program's header.
    pub(crate) first_program: Option<usize>,
    /// The expression terms of each block (see [`terms`]), up to the last block that has any.
    terms: Vec<u32>,
    /// Why the files of the calls found but not linked were not ([`Program::unlinked`]).
    unlinked: Vec<(Missing, String)>,
}

impl Index {
    /// Indexes `program`; structural problems (an `ENDm` with no `DOm`) become diagnostics.
    pub(crate) fn build(program: &Program, diagnostics: &mut Diagnostics) -> Index {
        let mut index = Index::default();
        // Program 0 is what comes before the first `O` (the main program when there is none).
        index.starts.push(0);
        let mut open_loops: Vec<(u8, usize)> = Vec::new();
        for (i, block) in program.blocks.iter().enumerate() {
            let terms = terms(program, block);
            if terms > 0 {
                index.terms.resize(i, 0);
                index.terms.push(u32::try_from(terms).unwrap_or(u32::MAX));
            }
            if let Some(number) = block.program() {
                index.first_program.get_or_insert(i);
                if index.starts.last() != Some(&i) {
                    index.starts.push(i);
                }
                let slot = index.starts.len() - 1;
                let first = match number {
                    ProgramNumber::Number(n) => *index.numbers.entry(*n).or_insert(slot),
                    ProgramNumber::Name(name) => *index.names.entry(name.clone()).or_insert(slot),
                };
                // A second program of the same number: calls go to the first, so it never runs.
                if first != slot
                    && let Some(earlier) =
                        index.starts.get(first).and_then(|&b| program.blocks.get(b))
                {
                    let name = match number {
                        ProgramNumber::Number(n) => format!("O{n:04}"),
                        ProgramNumber::Name(name) => format!("O<{}>", excerpt(name)),
                    };
                    let message = format!(
                        "{name} is defined twice in this program: at line {} and here; a call runs the first",
                        earlier.line + 1
                    );
                    diagnostics.push(Diagnostic::error(block.span, "E-PROGRAM-TWICE", message));
                }
            }
            let slot = index.starts.len() - 1;
            if let Some(n) = block.number()
                && let (Ok(slot), Ok(i)) = (u32::try_from(slot), u32::try_from(i))
            {
                index.labels.push((slot, n, i));
            }
            for statement in block.statements() {
                match statement {
                    Statement::While { label, .. } => open_loops.push((*label, i)),
                    Statement::End { label } => {
                        match open_loops.iter().rposition(|(l, _)| l == label) {
                            Some(at) => {
                                let (_, head) = open_loops[at];
                                open_loops.truncate(at);
                                index.loop_end.insert(head, i);
                                index.loop_head.insert(i, head);
                            }
                            None => diagnostics.push(Diagnostic::error(
                                block.span,
                                "E-MACRO-LOOP",
                                format!("END{label} has no WHILE … DO{label} before it"),
                            )),
                        }
                    }
                    Statement::OWord { label, kind } => {
                        let key = match label {
                            OLabel::Number(n) => LabelKey::Number(*n),
                            OLabel::Name(s) => LabelKey::Name(s.clone()),
                            OLabel::Expr(_) => continue,
                        };
                        index.owords.entry(key).or_default().push((i, kind.clone()));
                    }
                    _ => {}
                }
            }
        }
        // Usually in order already (numbers rising through the text), which the sort notices.
        index.labels.sort_unstable();
        index.unlinked.clone_from(&program.unlinked);
        for (label, head) in open_loops {
            if let Some(block) = program.blocks.get(head) {
                let message = format!("DO{label} has no END{label} after it");
                diagnostics.push(Diagnostic::error(block.span, "E-MACRO-LOOP", message));
            }
        }
        index
    }

    /// Why the file holding the called program `missing` was not linked, if it was found.
    pub(crate) fn unlinked(&self, missing: &Missing) -> Option<&str> {
        (self.unlinked.iter().find(|(m, _)| m == missing)).map(|(_, why)| why.as_str())
    }

    /// The first block of program `O number`.
    pub(crate) fn program_start(&self, number: u32) -> Option<usize> {
        (self.numbers.get(&number).and_then(|p| self.starts.get(*p))).copied()
    }

    /// The block numbered `N n` in the program that block `at` belongs to.
    pub(crate) fn label(&self, at: usize, n: u32) -> Option<usize> {
        // The program (index into `starts`) that block `at` belongs to.
        let program = self.starts.partition_point(|&s| s <= at).saturating_sub(1);
        let program = u32::try_from(program).ok()?;
        let labels = &self.labels;
        let (p, m, block) =
            *labels.get(labels.partition_point(|&(p, m, _)| (p, m) < (program, n)))?;
        ((p, m) == (program, n)).then_some(block as usize)
    }

    /// The lines of O-word `label`, in text order.
    pub(crate) fn owords(&self, label: &LabelKey) -> &[(usize, OWord)] {
        self.owords.get(label).map_or(&[], Vec::as_slice)
    }

    /// The expression terms of block `at` (see [`terms`]).
    pub(crate) fn terms(&self, at: usize) -> u64 {
        self.terms.get(at).map_or(0, |&t| u64::from(t))
    }

    /// The nearest line of `label` after or before `at` that is one of `kinds`, counting lines in
    /// `searched`.
    pub(crate) fn near_oword(
        &self,
        label: &LabelKey,
        at: usize,
        forward: bool,
        kinds: fn(&OWord) -> bool,
        searched: &mut u64,
    ) -> Option<(usize, &OWord)> {
        let lines = self.owords(label);
        let wanted = |line: &&(usize, OWord)| {
            *searched += 1;
            kinds(&line.1)
        };
        let found = if forward {
            let after = lines.get(lines.partition_point(|(b, _)| *b <= at)..)?;
            after.iter().find(wanted)
        } else {
            let before = lines.get(..lines.partition_point(|(b, _)| *b < at))?;
            before.iter().rev().find(wanted)
        };
        found.map(|(b, k)| (*b, k))
    }
}

/// How many expression terms `block` evaluates at most (counted by `max_work`).
pub(crate) fn terms(program: &Program, block: &Block) -> u64 {
    if !block.has_macro() {
        return 0;
    }
    let mut roots: Vec<ExprId> = block.words.iter().filter_map(|w| w.expr).collect();
    let mut statements: Vec<&Statement> = block.statements().iter().collect();
    while let Some(statement) = statements.pop() {
        match statement {
            Statement::Assign { target, value } => roots.extend([*target, *value]),
            Statement::Goto { target } => roots.push(*target),
            Statement::If { cond, then } => {
                roots.push(*cond);
                statements.push(then);
            }
            Statement::While { cond, .. } => roots.extend(*cond),
            Statement::End { .. } => {}
            Statement::OWord { label, kind } => {
                if let OLabel::Expr(id) = label {
                    roots.push(*id);
                }
                match kind {
                    OWord::EndSub(value) | OWord::Return(value) => roots.extend(*value),
                    OWord::Call(args) => roots.extend(args),
                    OWord::If(e) | OWord::ElseIf(e) | OWord::While(e) | OWord::Repeat(e) => {
                        roots.push(*e);
                    }
                    _ => {}
                }
            }
        }
    }
    // Every node once; a tree has no more nodes than the arena.
    let mut count = 0;
    while let Some(id) = roots.pop() {
        count += 1;
        if count > program.exprs.len() as u64 {
            break;
        }
        match program.expr(id).map(|n| &n.expr) {
            Some(Expr::Var(a) | Expr::Neg(a) | Expr::Call(_, a, None)) => roots.push(*a),
            Some(Expr::Binary(_, a, b) | Expr::Call(_, a, Some(b))) => roots.extend([*a, *b]),
            _ => {}
        }
    }
    count
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use swarf_syntax::{Dialect, parse};

    #[test]
    fn an_oword_search_starts_at_its_line_and_counts_the_lines_it_looks_at() {
        let text = "o1 if [1]\no1 endif\n".repeat(1000);
        let program = parse(&text, Dialect::LinuxCnc);
        let index = Index::build(&program, &mut Diagnostics::default());
        let key = LabelKey::Number(1);
        let mut searched = 0;
        let if_line = |k: &OWord| matches!(k, OWord::If(_));
        let found = index.near_oword(&key, 1998, true, |k| *k == OWord::EndIf, &mut searched);
        assert_eq!((found, searched), (Some((1999, &OWord::EndIf)), 1));
        let found = index.near_oword(&key, 1999, false, if_line, &mut searched);
        assert_eq!((found.map(|f| f.0), searched), (Some(1998), 2));
        assert_eq!(
            index.near_oword(&key, 1999, true, if_line, &mut searched),
            None
        );
        assert_eq!(searched, 2);
    }

    #[test]
    fn a_block_s_terms_are_its_expression_nodes() {
        let program = parse("#1=[1+2*#3]\nG01 X[#1] Y2.\nG00 X1.\n", Dialect::Fanuc);
        let terms: Vec<u64> = program.blocks.iter().map(|b| terms(&program, b)).collect();
        // #1 (two nodes) = 1 + 2 * #3 (six); X[#1] (two); none.
        assert_eq!(terms, [8, 2, 0]);
        let index = Index::build(&program, &mut Diagnostics::default());
        assert_eq!(
            (0..4).map(|b| index.terms(b)).collect::<Vec<_>>(),
            [8, 2, 0, 0]
        );
    }
}
