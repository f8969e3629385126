//! The program's structure, indexed once before it runs: `O` programs, `N` labels per program,
//! Macro B loops (`WHILE … DOm` ↔ `ENDm`) and LinuxCNC O-word lines, so that calls, jumps and
//! loops find their targets without rescanning the text.

use std::collections::HashMap;

use swarf_syntax::{Diagnostic, OLabel, OWord, Program, ProgramNumber, Statement};

/// A LinuxCNC O-word label as a map key (`o100` or `o<name>`; computed labels are looked up by
/// their value at run time).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) enum LabelKey {
    Number(u32),
    Name(Box<str>),
}

/// What kind of O-word line a block is (for searching forward and back).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OKind {
    Sub,
    EndSub,
    If,
    ElseIf,
    Else,
    EndIf,
    While,
    EndWhile,
    Do,
    Repeat,
    EndRepeat,
    Other,
}

impl OKind {
    fn of(kind: &OWord) -> OKind {
        match kind {
            OWord::Sub => OKind::Sub,
            OWord::EndSub(_) => OKind::EndSub,
            OWord::If(_) => OKind::If,
            OWord::ElseIf(_) => OKind::ElseIf,
            OWord::Else => OKind::Else,
            OWord::EndIf => OKind::EndIf,
            OWord::While(_) => OKind::While,
            OWord::EndWhile => OKind::EndWhile,
            OWord::Do => OKind::Do,
            OWord::Repeat(_) => OKind::Repeat,
            OWord::EndRepeat => OKind::EndRepeat,
            _ => OKind::Other,
        }
    }
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
    /// (program, N, block index) of every numbered block, sorted: a jump to `N` goes to the
    /// first block with that number in the program. (A sorted array rather than a map: CAM
    /// output numbers every line, and the array costs a third of the memory and no hashing.)
    labels: Vec<(u32, u32, u32)>,
    /// `WHILE … DOm` / `DOm` block → its `ENDm` block, and back.
    loop_end: HashMap<usize, usize>,
    loop_head: HashMap<usize, usize>,
    /// O-word label → its lines in text order.
    owords: HashMap<LabelKey, Vec<(usize, OKind)>>,
    /// The first block with a program number: the main program's header.
    first_program: Option<usize>,
}

impl Index {
    /// Indexes `program`; structural problems (an `ENDm` with no `DOm`) become diagnostics.
    pub(crate) fn build(program: &Program, diagnostics: &mut Vec<Diagnostic>) -> Index {
        let mut index = Index::default();
        // Program 0 is what comes before the first `O` (the main program when there is none).
        index.starts.push(0);
        let mut open_loops: Vec<(u8, usize)> = Vec::new();
        for (i, block) in program.blocks.iter().enumerate() {
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
                // A second program of the same number: calls go to the first, so the second
                // would never run.
                if first != slot
                    && let Some(earlier) =
                        index.starts.get(first).and_then(|&b| program.blocks.get(b))
                {
                    let name = match number {
                        ProgramNumber::Number(n) => format!("O{n:04}"),
                        ProgramNumber::Name(name) => format!("O<{name}>"),
                    };
                    diagnostics.push(Diagnostic::error(
                        block.span,
                        "E-PROGRAM-TWICE",
                        format!(
                            "{name} is defined twice in this program: at line {} and here; a call runs the first",
                            earlier.line + 1
                        ),
                    ));
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
                        index
                            .owords
                            .entry(key)
                            .or_default()
                            .push((i, OKind::of(kind)));
                    }
                    _ => {}
                }
            }
        }
        // Usually in order already (numbers rising through the text), which the sort notices.
        index.labels.sort_unstable();
        for (label, head) in open_loops {
            if let Some(block) = program.blocks.get(head) {
                diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-MACRO-LOOP",
                    format!("DO{label} has no END{label} after it"),
                ));
            }
        }
        index
    }

    /// The program (index into the program table) that block `at` belongs to.
    pub(crate) fn program_of(&self, at: usize) -> usize {
        match self.starts.binary_search(&at) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        }
    }

    /// Whether block `at` starts a program other than the main one (the first `O` line of the
    /// text heads the main program; later ones start programs that run only when called).
    pub(crate) fn starts_other_program(&self, at: usize) -> bool {
        self.first_program.is_some_and(|first| first != at)
    }

    /// The first block of program `O number`.
    pub(crate) fn program_start(&self, number: u32) -> Option<usize> {
        self.numbers
            .get(&number)
            .and_then(|p| self.starts.get(*p))
            .copied()
    }

    /// The block numbered `N n` in the program that block `at` belongs to.
    pub(crate) fn label(&self, at: usize, n: u32) -> Option<usize> {
        let program = u32::try_from(self.program_of(at)).ok()?;
        let first = self
            .labels
            .partition_point(|&(p, m, _)| (p, m) < (program, n));
        self.labels
            .get(first)
            .filter(|&&(p, m, _)| p == program && m == n)
            .map(|&(_, _, block)| block as usize)
    }

    /// The `ENDm` block of the loop whose head is `head`.
    pub(crate) fn loop_end(&self, head: usize) -> Option<usize> {
        self.loop_end.get(&head).copied()
    }

    /// The loop head of the `ENDm` block `end`.
    pub(crate) fn loop_head(&self, end: usize) -> Option<usize> {
        self.loop_head.get(&end).copied()
    }

    /// The lines of O-word `label`, in text order.
    pub(crate) fn owords(&self, label: &LabelKey) -> &[(usize, OKind)] {
        self.owords.get(label).map_or(&[], Vec::as_slice)
    }

    /// The next line of `label` after block `at` whose kind is in `kinds`.
    pub(crate) fn next_oword(
        &self,
        label: &LabelKey,
        at: usize,
        kinds: &[OKind],
    ) -> Option<(usize, OKind)> {
        self.owords(label)
            .iter()
            .find(|(b, k)| *b > at && kinds.contains(k))
            .copied()
    }

    /// The last line of `label` before block `at` whose kind is in `kinds`.
    pub(crate) fn previous_oword(
        &self,
        label: &LabelKey,
        at: usize,
        kinds: &[OKind],
    ) -> Option<(usize, OKind)> {
        self.owords(label)
            .iter()
            .rev()
            .find(|(b, k)| *b < at && kinds.contains(k))
            .copied()
    }
}
