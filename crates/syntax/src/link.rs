//! Programs from other files appended to a program, so its calls (`M98 P`, `M198 P`, `G65 P`,
//! `o<name> call`) reach them as a control reaches its memory. Their spans and lines follow the
//! caller's; [`Program::linked`] tells whose they are.

use crate::ast::{Expr, ExprId, OLabel, OWord, Statement};
use crate::{Dialect, LineIndex, MAX_PARSED_BYTES, ParseRun, Program, ProgramNumber, Span};

/// The text of a file [`Program::link_calls`] linked, kept to show its diagnostics.
#[derive(Debug, Clone)]
pub struct LinkedSource {
    /// The file's name (as `find` gave it).
    pub name: String,
    /// Its text.
    pub text: String,
    /// Its line index (for locating its diagnostics).
    pub lines: LineIndex,
}

/// A file linked into a program: where its text lies among the program's byte offsets and lines.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct LinkedFile {
    /// The file's name (as the caller gave it, e.g. its path).
    pub name: String,
    /// The offset its first byte has in the linked program's spans.
    pub first_byte: u32,
    /// The 0-based line its first line has in the linked program's blocks.
    pub first_line: u32,
    /// Its length in bytes.
    pub len: u32,
    /// Its number of lines.
    pub lines: u32,
}

/// A call target a program uses and does not define.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Missing {
    /// `M98 P1234` (`M198`, `G65`, `G66`) with no `O1234` in the program.
    Number(u32),
    /// LinuxCNC `o<name> call` with no `o<name> sub`.
    Name(String),
}

/// What [`Program::link_calls`]'s `find` found for a call: `None` and `Some((name, text))`
/// convert to it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Lookup {
    /// No file holds the called program.
    None,
    /// The file (its name, e.g. its path) and its text.
    Found(String, String),
    /// A file that would hold it cannot be linked (a folder, unreadable, too large): why,
    /// naming the file, for the call's diagnostic.
    Refused(String),
}

impl From<Option<(String, String)>> for Lookup {
    fn from(found: Option<(String, String)>) -> Self {
        found.map_or(Lookup::None, |(name, text)| Lookup::Found(name, text))
    }
}

/// File name extensions a called program's file may have, in the order they are tried.
pub const CALLED_FILE_EXTENSIONS: [&str; 8] =
    ["", ".nc", ".NC", ".ngc", ".tap", ".txt", ".gcode", ".cnc"];

/// Whether `name` (a LinuxCNC `o<name> call`) can name a called program's file: a plain file
/// name with no folder, no `..` and no root or drive, so that a call never reaches a file
/// outside the program's own folder.
pub fn is_plain_file_name(name: &str) -> bool {
    !name.is_empty() && name != "." && name != ".." && !name.contains(['/', '\\', ':', '\0'])
}

impl Missing {
    /// The file names that may hold this called program, in the order tried: `O1234`, `O1234.nc`,
    /// `1234.nc` … for a number, `name.ngc` or `name.nc` for a [plain](is_plain_file_name) name.
    pub fn file_names(&self) -> Vec<String> {
        let mut stems: Vec<String> = match self {
            Missing::Name(name) if !is_plain_file_name(name) => return Vec::new(),
            Missing::Number(n) => ["O", "o", ""]
                .iter()
                .flat_map(|p| [format!("{p}{n:04}"), format!("{p}{n}")])
                .collect(),
            Missing::Name(name) => vec![name.clone()],
        };
        // `{n:04}` and `{n}` agree from 1000 on; the rest differ, and so do their names.
        stems.dedup();
        let name = |s: &String| CALLED_FILE_EXTENSIONS.map(|e| format!("{s}{e}"));
        stems.iter().flat_map(name).collect()
    }
}

impl Program {
    /// Links the programs this program calls and lacks, each file once as `dialect`, at most `max`
    /// and within what `main_len` leaves of [`MAX_PARSED_BYTES`]; `find` gives a call's file or why
    /// not. A call left unlinked is in [`Program::unlinked`] with the reason.
    pub fn link_calls<L: Into<Lookup>>(
        &mut self,
        main_len: usize,
        dialect: Dialect,
        max: usize,
        mut find: impl FnMut(&Missing) -> L,
    ) -> Vec<LinkedSource> {
        let mut linked: Vec<LinkedSource> = Vec::new();
        // What the linked files may still hold (counted once a file is found).
        let mut left: Option<usize> = None;
        let limit = MAX_PARSED_BYTES >> 20;
        loop {
            let mut progress = false;
            for missing in self.missing_calls() {
                if self.unlinked.iter().any(|(m, _)| *m == missing) {
                    continue;
                }
                if linked.len() >= max {
                    let reason =
                        format!("not looked for: the program links {max} files, the most it may");
                    self.unlinked.push((missing, reason));
                    continue;
                }
                let (name, text) = match find(&missing).into() {
                    Lookup::None => continue,
                    Lookup::Found(name, text) => (name, text),
                    Lookup::Refused(reason) => {
                        self.unlinked.push((missing, reason));
                        continue;
                    }
                };
                if linked.iter().any(|l| l.name == name) {
                    continue;
                }
                let room =
                    *left.get_or_insert_with(|| MAX_PARSED_BYTES.saturating_sub(self.held_bytes()));
                let Some(room) = room.checked_sub(text.len()) else {
                    let reason = format!(
                        "{name} is not linked: with it the program would hold more than {limit} MiB"
                    );
                    self.unlinked.push((missing, reason));
                    continue;
                };
                let mut run = ParseRun::new(dialect);
                run.set_max_bytes(room);
                while !run.step(&text, usize::MAX) {}
                left = Some(room.saturating_sub(run.held_bytes()));
                let mut sub = run.finish();
                if let Missing::Number(n) = missing {
                    number_by_file_name(&mut sub, n, &name);
                }
                let lines = sub.lines.clone();
                self.link(sub, &name, main_len, text.len());
                linked.push(LinkedSource { name, text, lines });
                progress = true;
            }
            if !progress {
                return linked;
            }
        }
    }

    /// Appends `other` (parsed from the file `name`, `len` bytes long) after this program, with
    /// its spans moved past `self_len` bytes of this program's own text and everything linked
    /// before, its lines past all lines before, and its expressions after this program's.
    pub fn link(&mut self, other: Program, name: &str, self_len: usize, len: usize) {
        let clamp = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        let (end, first_line) = match self.linked.last() {
            Some(l) => (
                l.first_byte.saturating_add(l.len),
                l.first_line.saturating_add(l.lines),
            ),
            None => (clamp(self_len), clamp(self.lines.line_count())),
        };
        let first_byte = end.saturating_add(1);
        let shift = |s: Span| Span {
            start: s.start.saturating_add(first_byte),
            end: s.end.saturating_add(first_byte),
        };
        let base = self.exprs.len();
        let id = |e: ExprId| ExprId::from_index(e.index() + base).unwrap_or(e);
        for mut node in other.exprs {
            node.span = shift(node.span);
            node.expr = match node.expr {
                Expr::Var(a) => Expr::Var(id(a)),
                Expr::Neg(a) => Expr::Neg(id(a)),
                Expr::Binary(op, a, b) => Expr::Binary(op, id(a), id(b)),
                Expr::Call(f, a, b) => Expr::Call(f, id(a), b.map(id)),
                other @ (Expr::Num(_) | Expr::Named(_)) => other,
            };
            self.exprs.push(node);
        }
        for mut block in other.blocks {
            block.span = shift(block.span);
            block.line = block.line.saturating_add(first_line);
            for w in &mut block.words {
                w.span = shift(w.span);
                w.expr = w.expr.map(id);
            }
            if let Some(extras) = block.extras.as_deref_mut() {
                for c in &mut extras.comments {
                    *c = shift(*c);
                }
                for s in &mut extras.statements {
                    rebase_statement(s, &id);
                }
            }
            self.blocks.push(block);
        }
        for mut d in other.diagnostics {
            d.span = shift(d.span);
            self.diagnostics.push(d);
        }
        self.linked.push(LinkedFile {
            name: name.to_string(),
            first_byte,
            first_line,
            len: clamp(len),
            lines: clamp(other.lines.line_count()),
        });
    }

    /// The index in [`Program::linked`] of the file byte `offset` of this program lies in
    /// (`None`: the program's own text).
    pub fn linked_at_offset(&self, offset: u32) -> Option<usize> {
        self.linked.iter().rposition(|l| offset >= l.first_byte)
    }

    /// The index in [`Program::linked`] of the file the 0-based `line` of this program's
    /// blocks lies in (`None`: the program's own text).
    pub fn linked_at_line(&self, line: u32) -> Option<usize> {
        self.linked.iter().rposition(|l| line >= l.first_line)
    }

    /// The subprogram numbers and O-word names this program calls with literal targets but
    /// does not define (in the order first called).
    pub fn missing_calls(&self) -> Vec<Missing> {
        let (mut defined, mut called) = (Vec::new(), Vec::new());
        for block in &self.blocks {
            match block.program() {
                Some(ProgramNumber::Number(n)) => defined.push(Missing::Number(*n)),
                Some(ProgramNumber::Name(n)) => defined.push(Missing::Name(n.to_string())),
                None => {}
            }
            let call = [(b'M', 98.0), (b'M', 198.0), (b'G', 65.0), (b'G', 66.0)];
            let calls = (block.words.iter())
                .any(|w| w.expr.is_none() && call.contains(&(w.letter, w.value)));
            if calls
                && let Some(p) = block.word(b'P').filter(|p| p.expr.is_none())
                && p.value >= 0.0
                && p.value.fract() == 0.0
            {
                // Fanuc: more than four digits in P are the repeat count then the number.
                let repeats = p.value >= 10_000.0 && block.word(b'L').is_none();
                let number = if repeats { p.value % 10_000.0 } else { p.value };
                called.push(Missing::Number(number as u32));
            }
            for s in block.statements() {
                match s {
                    Statement::OWord {
                        label: OLabel::Name(n),
                        kind: OWord::Sub,
                    } => defined.push(Missing::Name(n.to_string())),
                    Statement::OWord {
                        label: OLabel::Name(n),
                        kind: OWord::Call(_),
                    } => called.push(Missing::Name(n.to_string())),
                    _ => {}
                }
            }
        }
        let mut missing: Vec<Missing> = Vec::new();
        for m in called {
            if !defined.contains(&m) && !missing.contains(&m) {
                missing.push(m);
            }
        }
        missing
    }
}

/// Makes `sub` (file `name`, found for `O n`) program `O n`, as a control loading it under that
/// number runs it: an empty `O n` block goes first if it has no `O` line; another number becomes
/// `O n`, with a warning.
fn number_by_file_name(sub: &mut Program, n: u32, name: &str) {
    let defines = |b: &crate::Block| b.program() == Some(&ProgramNumber::Number(n));
    if sub.blocks.iter().any(defines) {
        return;
    }
    if let Some(first) = sub.blocks.first_mut()
        && let Some(other) = first.program()
    {
        let other = match other {
            ProgramNumber::Number(m) => format!("O{m:04}"),
            ProgramNumber::Name(s) => format!("O<{}>", crate::excerpt(s)),
        };
        let message = format!(
            "{name} is found by its name for O{n:04} but opens with {other}: it runs as O{n:04}"
        );
        let warning = crate::Diagnostic::warning(first.span, "W-PROGRAM-NUMBER", message);
        sub.diagnostics.push(warning);
        first.extras_mut().program = Some(ProgramNumber::Number(n));
        return;
    }
    let mut header = crate::Block::default();
    header.extras_mut().program = Some(ProgramNumber::Number(n));
    sub.blocks.insert(0, header);
}

fn rebase_statement(s: &mut Statement, id: &impl Fn(ExprId) -> ExprId) {
    match s {
        Statement::Assign { target, value } => {
            *target = id(*target);
            *value = id(*value);
        }
        Statement::Goto { target } => *target = id(*target),
        Statement::If { cond, then } => {
            *cond = id(*cond);
            rebase_statement(then, id);
        }
        Statement::While { cond, .. } => *cond = cond.map(id),
        Statement::End { .. } => {}
        Statement::OWord { label, kind } => {
            if let OLabel::Expr(e) = label {
                *e = id(*e);
            }
            match kind {
                OWord::EndSub(e) | OWord::Return(e) => *e = e.map(id),
                OWord::Call(args) => args.iter_mut().for_each(|a| *a = id(*a)),
                OWord::If(e) | OWord::ElseIf(e) | OWord::While(e) | OWord::Repeat(e) => {
                    *e = id(*e);
                }
                _ => {}
            }
        }
    }
}
