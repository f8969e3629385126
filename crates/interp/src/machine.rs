//! The modal machine: runs blocks in bounded steps, follows the program's flow (subprograms,
//! macro calls, Macro B jumps and loops, LinuxCNC O-words) and hands each block's words to
//! [`exec`](crate::exec).

use std::borrow::Cow;
use std::collections::HashMap;

use glam::DVec3;
use swarf_syntax::{
    Block, Diagnostic, Dialect, ExprId, OLabel, OWord, Program, Span, Statement, Word, WordForm,
    codes::Code,
};

use crate::flow::{Index, LabelKey, OKind};
use crate::macros::{self, SystemVariables, Value, Variables};
use crate::state::State;
use crate::{Canon, Setup, Sink, Source};

/// Whether a run has more blocks to execute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The budget ran out; call [`Interpreter::step`] again to go on.
    Running,
    /// The program ended (M02/M30, end of text, or a limit was hit).
    Finished,
}

/// How a piece of a program read piece by piece ran (see [`Interpreter::run_piece`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece {
    /// Every block of the piece ran; give the next piece.
    Ran,
    /// The program ended in this piece (M02/M30 or a limit): the rest need not run.
    Ended,
    /// The program jumps, loops or calls (or holds several programs), which needs all its
    /// blocks at once: run it whole with [`Interpreter::step`] instead, from the start.
    NeedsWhole,
}

/// Passes events on and counts the motions among them (for `[machine] max_motions`).
pub(crate) struct MotionCounter<'s> {
    inner: &'s mut dyn Sink,
    motions: u64,
    /// The run's limit on motions: past it the counter is full (see [`Sink::full`]).
    max_motions: u64,
}

impl Sink for MotionCounter<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        if matches!(
            event,
            Canon::Rapid { .. } | Canon::Feed { .. } | Canon::Arc { .. }
        ) {
            self.motions += 1;
        }
        self.inner.emit(source, event);
    }

    fn full(&self) -> bool {
        self.motions >= self.max_motions || self.inner.full()
    }

    fn origin(&mut self, at: DVec3) {
        self.inner.origin(at);
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.inner.programmed(source, event);
    }

    fn straight(&mut self, source: Source, rapid: bool, x: f64, y: f64, z: f64, feed: f64) {
        self.motions += 1;
        self.inner.straight(source, rapid, x, y, z, feed);
    }

    fn stroke_zone(&mut self, source: Source, zone: Option<&crate::StrokeZone>) {
        self.inner.stroke_zone(source, zone);
    }
}

/// Resource limits that stop runaway programs with a diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most blocks executed in one run.
    pub max_blocks: u64,
    /// Deepest nesting of subprogram and macro calls.
    pub max_call_depth: usize,
}

/// Subprogram and macro nesting the controls allow (Fanuc 0i: 10 subprogram levels; a few
/// more here so that macro calls inside them still fit), beyond which a run stops.
const MAX_CALL_DEPTH: usize = 16;

/// What a block asks the run to do next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Flow {
    /// Go on with the next block.
    Next,
    /// Continue at this block.
    Jump(usize),
    /// Stop the run (M02/M30, an alarm).
    Stop,
}

/// Why a call frame was pushed, which decides how it returns.
#[derive(Debug, Clone, PartialEq)]
enum CallKind {
    /// `M98` (or Syntec `M98 H`): returns at `M99`; locals are shared.
    Subprogram,
    /// `G65`/`G66`: returns at `M99` with a new level of local variables.
    Macro,
    /// LinuxCNC `oN call`: returns at `oN endsub`/`oN return`, with its own #1–#30.
    OWord(LabelKey),
}

/// One level of the call stack.
#[derive(Debug, Clone)]
struct Frame {
    kind: CallKind,
    /// Block to continue at when the call returns.
    return_to: usize,
    /// Where the called code starts (for `M98 … L` repeats).
    start: usize,
    /// Further runs left (`M98 P… L3` runs three times).
    repeats_left: u32,
    /// Whether this is the G66 modal macro, called after a move (its own moves do not call it
    /// again).
    modal: bool,
}

/// Interprets a parsed program in bounded steps.
#[derive(Debug, Clone)]
pub struct Interpreter {
    pub(crate) st: State,
    pub(crate) vars: Variables,
    index: Option<std::sync::Arc<Index>>,
    next_block: usize,
    executed: u64,
    /// Motion events produced so far.
    motions: u64,
    /// The program zero last reported with `Canon::Origin`.
    origin: Option<DVec3>,
    finished: bool,
    calls: Vec<Frame>,
    /// Remaining passes of LinuxCNC `repeat` loops, by the block of their `repeat` line.
    repeats: HashMap<usize, u64>,
    /// Running a program piece by piece (see [`Interpreter::run_piece`]).
    piecewise: bool,
    /// Blocks of the pieces before this one (added to each event's block number).
    block_base: usize,
    /// Whether a block with a program number has been seen (piece by piece).
    program_seen: bool,
    /// Whether a block jumped, or needed the whole program, while running piece by piece.
    jumped: bool,
    /// The first block of the piece not run yet (running piece by piece).
    unvisited: usize,
    /// Whether plain straight moves take the short path (see [`Interpreter::general_path_only`]).
    pub(crate) shortcut: bool,
    /// Whether `origin` is the program zero of the current frame: only blocks that took the
    /// short path leave the frame as it was, so only after them can the check be skipped.
    origin_current: bool,
    /// The frame of the fastest path for plain moves (see `exec::Fast`), and whether it was
    /// made after the last block that could change it (only blocks change the state, so it
    /// holds from one step to the next).
    fast: Option<crate::exec::Fast>,
    fast_current: bool,
}

impl Interpreter {
    /// A machine at power-on for `dialect`, at the origin, with `setup`'s offsets.
    pub fn new(setup: Setup, dialect: Dialect) -> Self {
        Interpreter {
            st: State::new(setup, dialect),
            vars: Variables::new(dialect),
            index: None,
            next_block: 0,
            executed: 0,
            motions: 0,
            origin: None,
            finished: false,
            calls: Vec::new(),
            repeats: HashMap::new(),
            shortcut: true,
            origin_current: false,
            fast: None,
            fast_current: false,
            piecewise: false,
            block_base: 0,
            program_seen: false,
            jumped: false,
            unvisited: 0,
        }
    }

    /// Runs the next piece of a program read piece by piece: `program` holds only the blocks
    /// read since the last piece (the reader dropped the earlier ones; see
    /// `swarf_syntax::ParseRun::clear_blocks`) and the state carries over from the pieces
    /// before. A long program without jumps then never has all its blocks in memory at once.
    /// Call [`Interpreter::finish_pieces`] after the last piece.
    pub fn run_piece(&mut self, program: &Program, sink: &mut dyn Sink) -> Piece {
        if self.jumped || (self.executed > 0 && !self.piecewise) {
            return Piece::NeedsWhole;
        }
        if self.finished {
            return Piece::Ended;
        }
        self.piecewise = true;
        self.index = None;
        self.next_block = 0;
        self.unvisited = 0;
        // A block that needs the whole program (see `needs_whole`) or a jump ends the piece:
        // the program then runs whole, from its start.
        while self.step(program, sink, 4096) == Status::Running
            && !self.jumped
            && self.next_block < program.blocks.len()
        {}
        if self.finished && !self.jumped {
            // The blocks after the end were not run; they still decide, as they would have
            // before the piece ran.
            for block in program.blocks.get(self.unvisited..).unwrap_or_default() {
                if self.needs_whole(block) {
                    self.jumped = true;
                    break;
                }
            }
        }
        self.block_base += program.blocks.len();
        if self.jumped {
            Piece::NeedsWhole
        } else if self.finished {
            Piece::Ended
        } else {
            Piece::Ran
        }
    }

    /// Whether `block`, met running piece by piece, needs what only the whole program's index
    /// knows: a loop or O-word line, a call, or a second program. Each block of a piece is
    /// asked once, in order, except the plain moves of the shortest path, which never do.
    fn needs_whole(&mut self, block: &Block) -> bool {
        let several_programs = block.program().is_some() && self.program_seen;
        self.program_seen |= block.program().is_some();
        let calls = block.words.iter().any(|w| {
            matches!(w.letter, b'G' | b'M')
                && (w.expr.is_some() || matches!(w.value, 65.0 | 66.0 | 66.1 | 98.0 | 99.0 | 198.0))
        });
        let control = block
            .statements()
            .iter()
            .any(|s| !matches!(s, Statement::Assign { .. }));
        several_programs || calls || control
    }

    /// Ends a program run piece by piece (the end of its text), as [`Interpreter::step`] does
    /// at the end of a program run whole.
    pub fn finish_pieces(&mut self, sink: &mut dyn Sink) {
        if !self.finished {
            self.finished = true;
            crate::corners::flush(&mut self.st, sink);
        }
    }

    /// Runs every block through the general path, without the shorter one plain straight moves
    /// otherwise take; the two must give the same events and diagnostics, which this checks.
    pub fn general_path_only(&mut self) {
        self.shortcut = false;
    }

    /// The limits this run stops at.
    pub fn limits(&self) -> Limits {
        Limits {
            max_blocks: self.st.setup.machine.max_blocks,
            max_call_depth: MAX_CALL_DEPTH,
        }
    }

    /// Diagnostics found while executing so far.
    pub fn diagnostics(&self) -> &[Diagnostic] {
        &self.st.diagnostics
    }

    /// Takes the diagnostics found so far, leaving none.
    pub fn take_diagnostics(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.st.diagnostics)
    }

    /// The tool-tip position in the machine frame.
    pub fn position(&self) -> DVec3 {
        self.st.position
    }

    /// How many blocks have been executed.
    pub fn executed_blocks(&self) -> u64 {
        self.executed
    }

    /// Index of the next block to execute (progress through the program).
    pub fn next_block(&self) -> usize {
        self.next_block
    }

    /// A copy of the interpreter without the diagnostics found so far (for [`States`]).
    ///
    /// [`States`]: crate::States
    pub(crate) fn snapshot(&mut self) -> Interpreter {
        let diagnostics = std::mem::take(&mut self.st.diagnostics);
        let copy = self.clone();
        self.st.diagnostics = diagnostics;
        copy
    }

    /// The machine state before the next block, for a "state at cursor" view.
    pub fn block_state(&self) -> crate::BlockState {
        crate::BlockState {
            codes: self.st.active_codes(),
            machine: self.st.position,
            work: self.st.program_pos,
            work_offset_name: self.st.wcs.clone(),
            work_offset: self.st.wcs_offset,
            tool: self.st.tool,
            length_offset: self.st.length_comp,
            feed: self.st.feed_mm_per_min,
            spindle_rpm: self.st.spindle_rpm,
            executed: self.executed,
        }
    }

    /// The active G codes, one per modal group, as text (`G01`, `G17`, `G90`, …), for a
    /// "state at cursor" view.
    pub fn active_codes(&self) -> Vec<String> {
        self.st.active_codes()
    }

    /// Executes at most `budget` blocks of `program`, sending events to `sink`.
    pub fn step(&mut self, program: &Program, sink: &mut dyn Sink, budget: usize) -> Status {
        // A program run piece by piece needs no index: a block that would use it (a jump, a
        // loop, a call) has the program run whole (see `needs_whole`), which makes it.
        if self.index.is_none() && !self.piecewise {
            self.index = Some(std::sync::Arc::new(Index::build(
                program,
                &mut self.st.diagnostics,
            )));
        }
        let mut counted = MotionCounter {
            inner: sink,
            motions: self.motions,
            max_motions: self.st.setup.machine.max_motions,
        };
        let mut left = budget;
        while left > 0 {
            if self.finished {
                break;
            }
            let ran = self.fast_run(program, left, &mut counted);
            if ran > 0 {
                left -= ran;
                continue;
            }
            left -= 1;
            let at = self.next_block;
            let Some(block) = program.blocks.get(at) else {
                if self.piecewise {
                    // The end of a piece, not of the program.
                    break;
                }
                self.end_of_text(program);
                continue;
            };
            // The runaway limits: blocks run, and moves made (the toolpath's memory).
            let machine = &self.st.setup.machine;
            let limit = if self.executed >= machine.max_blocks {
                Some((
                    "E-RUNAWAY",
                    format!(
                        "execution stopped after {} blocks (the limit in [machine] max_blocks): an endless loop?",
                        self.executed
                    ),
                ))
            } else if counted.motions >= machine.max_motions {
                Some((
                    "E-MOTION-LIMIT",
                    format!(
                        "execution stopped after {} moves (the limit in [machine] max_motions): the toolpath would not fit in memory",
                        counted.motions
                    ),
                ))
            } else if counted.inner.full() {
                Some((
                    "E-MOTION-LIMIT",
                    format!(
                        "execution stopped after {} moves: their toolpath holds as many segments as [machine] max_motions allows (an arc is drawn as many), more would not fit in memory",
                        counted.motions
                    ),
                ))
            } else {
                None
            };
            if let Some((code, message)) = limit {
                self.st
                    .diagnostics
                    .push(Diagnostic::error(block.span, code, message));
                self.finished = true;
                break;
            }
            let source = Source {
                block: u32::try_from(self.block_base + at).unwrap_or(u32::MAX),
                line: block.line.saturating_add(1),
            };
            self.executed += 1;
            self.st.blocks_run = self.executed;
            self.st.block_span = block.span;
            let before = counted.motions;
            let plain = if block.has_error() {
                None
            } else {
                self.plain_block(block, source, &mut counted)
            };
            let flow = if let Some(flow) = plain {
                flow
            } else if self.piecewise && self.needs_whole(block) {
                self.jumped = true;
                break;
            } else if block.has_error() {
                Flow::Next
            } else {
                self.origin_current = false;
                self.fast_current = false;
                self.run_block(program, at, block, source, &mut counted)
            };
            self.unvisited = at + 1;
            if counted.motions != before && !self.origin_current {
                // Moves from a program zero not reported yet: report it for the origin marks.
                let origin = self.st.to_machine(DVec3::ZERO);
                self.origin_current = true;
                if self.origin != Some(origin) && origin.is_finite() {
                    self.origin = Some(origin);
                    counted.inner.origin(origin);
                }
            }
            match flow {
                Flow::Next => self.next_block = at + 1,
                Flow::Jump(_) if self.piecewise => {
                    self.jumped = true;
                    break;
                }
                Flow::Jump(to) => self.next_block = to,
                Flow::Stop => self.finished = true,
            }
        }
        self.motions = counted.motions;
        if self.finished {
            crate::corners::flush(&mut self.st, sink);
            Status::Finished
        } else {
            Status::Running
        }
    }

    /// Runs the plain moves from the next block on in the fast frame (see `exec::Fast`), at
    /// most `left` of them and short of the runaway limits, with none of the checks the block
    /// loop makes between other blocks (they change nothing for such moves); how many ran, 0
    /// where the frame does not apply or the next block is not such a move.
    fn fast_run(&mut self, program: &Program, left: usize, sink: &mut MotionCounter<'_>) -> usize {
        // The program zero must have been reported (plain moves leave it as it is); a full
        // sink is left to the block loop, which reports it.
        if !self.shortcut || !self.origin_current || self.st.alarm.is_some() || sink.full() {
            return 0;
        }
        if !self.fast_current {
            self.fast = crate::exec::Fast::of(&self.st);
            self.fast_current = true;
        }
        let Some(fast) = self.fast else {
            return 0;
        };
        // Each block makes one move at most, so this many run within both limits.
        let machine = &self.st.setup.machine;
        let room = machine
            .max_blocks
            .saturating_sub(self.executed)
            .min(machine.max_motions.saturating_sub(sink.motions));
        let room = usize::try_from(room).unwrap_or(usize::MAX).min(left);
        let at = self.next_block;
        let mut ran = 0;
        for block in program
            .blocks
            .get(at..)
            .unwrap_or_default()
            .iter()
            .take(room)
        {
            if block.has_error()
                || block.words.is_empty()
                || block.program().is_some()
                || !block.statements().is_empty()
            {
                break;
            }
            let source = Source {
                block: u32::try_from(self.block_base + at + ran).unwrap_or(u32::MAX),
                line: block.line.saturating_add(1),
            };
            let arc = if crate::exec::fast_move(&mut self.st, fast, block, source, sink) {
                false
            } else if crate::exec::fast_arc(&mut self.st, fast, block, source, sink) {
                true
            } else {
                break;
            };
            self.st.block_span = block.span;
            ran += 1;
            // An arc may add many segments: a full sink ends the run here (the block loop
            // reports it).
            if arc && sink.full() {
                break;
            }
        }
        self.executed += u64::try_from(ran).unwrap_or(u64::MAX);
        self.st.blocks_run = self.executed;
        self.next_block = at + ran;
        self.unvisited = self.next_block;
        ran
    }

    /// The text ran out: inside a call that is an implicit return; otherwise the end.
    fn end_of_text(&mut self, program: &Program) {
        match self.calls.pop() {
            Some(frame) => {
                if let CallKind::Macro | CallKind::OWord(_) = frame.kind {
                    self.vars.pop_frame();
                }
                self.next_block = frame.return_to;
                let _ = program;
            }
            None => self.finished = true,
        }
    }

    /// Runs one block: its words are read (expressions evaluated), its assignments made, its
    /// codes executed, then its control statements decide where to go.
    /// Runs a block of plain straight-move words (no statements, variables or program number)
    /// without the general path's steps for them, when nothing is pending before it (an alarm
    /// raised by the block before); `None`, having done nothing, for any other block.
    fn plain_block(
        &mut self,
        block: &Block,
        source: Source,
        sink: &mut MotionCounter<'_>,
    ) -> Option<Flow> {
        if !self.shortcut
            || block.words.is_empty()
            || block.program().is_some()
            || !block.statements().is_empty()
            || self.st.alarm.is_some()
        {
            return None;
        }
        if !self.fast_current {
            self.fast = crate::exec::Fast::of(&self.st);
            self.fast_current = true;
        }
        if let Some(fast) = self.fast
            && crate::exec::fast_move(&mut self.st, fast, block, source, sink)
        {
            return Some(Flow::Next);
        }
        crate::exec::plain_block(&mut self.st, block, source, sink)
    }

    fn run_block(
        &mut self,
        program: &Program,
        at: usize,
        block: &Block,
        source: Source,
        sink: &mut dyn Sink,
    ) -> Flow {
        // Each `O` program is a program of its own: the main program running into the next
        // one's `O` line has ended (it is only run when called).
        if block.program().is_some()
            && self.calls.is_empty()
            && self
                .index
                .as_ref()
                .is_some_and(|i| i.starts_other_program(at))
        {
            self.st.diagnostics.push(Diagnostic::note(
                block.span,
                "N-PROGRAM-END",
                "the main program ends here, where the next program starts (it runs only when called)",
            ));
            return Flow::Stop;
        }
        let words = match self.resolve_words(program, block) {
            Ok(words) => words,
            Err(e) => {
                self.st.diagnostics.push(e);
                return Flow::Next;
            }
        };
        // Every assignment of the block reads the values from before the block (LinuxCNC's
        // rule; the Fanuc family has one assignment per block).
        let mut prepared = Vec::new();
        for statement in block.statements() {
            if let Statement::Assign { target, value } = statement {
                match macros::prepare_assign(program, *target, *value, &self.vars, &self.st) {
                    Ok(a) => prepared.push(a),
                    Err(e) => {
                        self.st.diagnostics.push(e.to_diagnostic());
                        return Flow::Stop;
                    }
                }
            }
        }
        for assignment in prepared {
            if let Err(e) = assignment.apply(&mut self.vars, &mut self.st) {
                self.st.diagnostics.push(e.to_diagnostic());
                return Flow::Stop;
            }
        }
        if let Some(alarm) = self.st.alarm.take() {
            self.st.diagnostics.push(alarm);
            return Flow::Stop;
        }
        let mut flow = Flow::Next;
        if !words.is_empty() {
            flow = crate::exec::execute(self, program, at, block, &words, source, sink);
        }
        if flow != Flow::Next {
            return flow;
        }
        for statement in block.statements() {
            match self.control(program, at, block, statement) {
                Ok(Flow::Next) => {}
                Ok(other) => return other,
                Err(e) => {
                    self.st.diagnostics.push(e);
                    return Flow::Stop;
                }
            }
        }
        flow
    }

    /// Reads the block's words: expressions are evaluated, and a word whose variable is vacant
    /// is left out, as the Fanuc family does.
    fn resolve_words<'b>(
        &self,
        program: &Program,
        block: &'b Block,
    ) -> Result<Cow<'b, [Word]>, Diagnostic> {
        // Most blocks have literal words only: they are used as they are, without a copy.
        if block.words.iter().all(|w| w.expr.is_none()) {
            return Ok(Cow::Borrowed(&block.words));
        }
        let mut out = Vec::with_capacity(block.words.len());
        for word in &block.words {
            let Some(expr) = word.expr else {
                out.push(*word);
                continue;
            };
            match macros::eval(program, expr, &self.vars, &self.st) {
                Ok(Some(value)) => {
                    let mut w = *word;
                    w.value = value;
                    if w.letter == b'G' || w.letter == b'M' {
                        // A code from a variable is checked like a written one.
                        let code = Code::from_value(w.letter, value);
                        if code
                            .and_then(|c| swarf_syntax::codes::lookup(self.st.dialect, c))
                            .is_none()
                        {
                            return Err(Diagnostic::error(
                                word.span,
                                "E-UNKNOWN-CODE",
                                format!(
                                    "{}{value} (from a variable) is not a code of {}",
                                    w.letter(),
                                    self.st.dialect.label()
                                ),
                            ));
                        }
                        // Codes are read as plain numbers from here on.
                        w.expr = None;
                    }
                    out.push(w);
                }
                Ok(None) => {}
                Err(e) => return Err(Diagnostic::error(e.span, e.code, e.message)),
            }
        }
        Ok(Cow::Owned(out))
    }

    fn eval(&self, program: &Program, id: ExprId) -> Result<Value, Diagnostic> {
        macros::eval(program, id, &self.vars, &self.st)
            .map_err(|e| Diagnostic::error(e.span, e.code, e.message))
    }

    fn condition(&self, program: &Program, id: ExprId) -> Result<bool, Diagnostic> {
        macros::eval_condition(program, id, &self.vars, &self.st)
            .map_err(|e| Diagnostic::error(e.span, e.code, e.message))
    }

    /// The block a `GOTO n` (or `M99 Pn`) in block `at` goes to.
    fn goto(&self, at: usize, n: f64, span: Span) -> Result<usize, Diagnostic> {
        if self.index.is_none() && self.piecewise {
            // No index while running piece by piece: the jump has the program run whole.
            return Ok(at);
        }
        let label = (n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX)).then_some(n as u32);
        label
            .and_then(|n| self.index.as_ref().and_then(|i| i.label(at, n)))
            .ok_or_else(|| {
                Diagnostic::error(
                    span,
                    "E-MACRO-GOTO",
                    format!("there is no block N{n} in this program to jump to"),
                )
            })
    }

    /// What a block that needs the program's index does without one: running piece by piece
    /// (which makes none), a jump, which has the program run whole; else nothing (a program
    /// run whole has its index from its first step).
    fn without_index(&self, at: usize) -> Flow {
        if self.piecewise {
            Flow::Jump(at)
        } else {
            Flow::Next
        }
    }

    /// Macro B and O-word control statements.
    fn control(
        &mut self,
        program: &Program,
        at: usize,
        block: &Block,
        statement: &Statement,
    ) -> Result<Flow, Diagnostic> {
        let Some(index) = self.index.as_ref() else {
            // An assignment needs no index (it runs piece by piece as well).
            return Ok(match statement {
                Statement::Assign { .. } => Flow::Next,
                _ => self.without_index(at),
            });
        };
        match statement {
            Statement::Assign { .. } => Ok(Flow::Next),
            Statement::Goto { target } => {
                let n = self.eval(program, *target)?.unwrap_or(0.0);
                self.goto(at, n, block.span).map(Flow::Jump)
            }
            Statement::If { cond, then } => {
                if !self.condition(program, *cond)? {
                    return Ok(Flow::Next);
                }
                match &**then {
                    Statement::Goto { target } => {
                        let n = self.eval(program, *target)?.unwrap_or(0.0);
                        self.goto(at, n, block.span).map(Flow::Jump)
                    }
                    Statement::Assign { target, value } => {
                        macros::assign(program, *target, *value, &mut self.vars, &mut self.st)
                            .map_err(|e| Diagnostic::error(e.span, e.code, e.message))?;
                        Ok(Flow::Next)
                    }
                    _ => Ok(Flow::Next),
                }
            }
            Statement::While { cond, .. } => {
                let holds = match cond {
                    Some(c) => self.condition(program, *c)?,
                    None => true,
                };
                if holds {
                    return Ok(Flow::Next);
                }
                match index.loop_end(at) {
                    Some(end) => Ok(Flow::Jump(end + 1)),
                    None => Ok(Flow::Stop),
                }
            }
            Statement::End { .. } => match index.loop_head(at) {
                Some(head) => Ok(Flow::Jump(head)),
                None => Ok(Flow::Stop),
            },
            Statement::OWord { label, kind } => self.oword(program, at, block, label, kind),
        }
    }

    /// The key of an O-word label (computed labels are evaluated).
    fn label_key(&self, program: &Program, label: &OLabel) -> Result<LabelKey, Diagnostic> {
        match label {
            OLabel::Number(n) => Ok(LabelKey::Number(*n)),
            OLabel::Name(s) => Ok(LabelKey::Name(s.clone())),
            OLabel::Expr(id) => {
                let v = self.eval(program, *id)?.unwrap_or(0.0);
                if v >= 0.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX) {
                    Ok(LabelKey::Number(v as u32))
                } else {
                    Err(Diagnostic::error(
                        program.expr(*id).map_or(Span::default(), |n| n.span),
                        "E-OWORD",
                        format!("O-word number {v} is not a whole number"),
                    ))
                }
            }
        }
    }

    /// LinuxCNC O-word control lines.
    fn oword(
        &mut self,
        program: &Program,
        at: usize,
        block: &Block,
        label: &OLabel,
        kind: &OWord,
    ) -> Result<Flow, Diagnostic> {
        let key = self.label_key(program, label)?;
        let Some(index) = self.index.as_ref() else {
            return Ok(self.without_index(at));
        };
        let missing = |what: &str| {
            Diagnostic::error(
                block.span,
                "E-OWORD",
                format!("{} has no matching `{what}`", show_label(&key)),
            )
        };
        match kind {
            OWord::Sub => {
                // Reached in sequence: a definition is skipped, not run.
                let end = index
                    .next_oword(&key, at, &[OKind::EndSub])
                    .ok_or_else(|| missing("endsub"))?;
                Ok(Flow::Jump(end.0 + 1))
            }
            OWord::EndSub(value) | OWord::Return(value) => {
                if let Some(v) = value {
                    let result = self.eval(program, *v)?;
                    self.vars.set_named("_value", result);
                }
                match self.calls.last() {
                    Some(frame) if frame.kind == CallKind::OWord(key.clone()) => {
                        let frame = self.calls.pop().map_or(at + 1, |f| f.return_to);
                        self.vars.pop_frame();
                        Ok(Flow::Jump(frame))
                    }
                    _ if matches!(kind, OWord::EndSub(_)) => Ok(Flow::Next),
                    _ => Err(Diagnostic::error(
                        block.span,
                        "E-OWORD",
                        format!("`{} return` outside its subroutine", show_label(&key)),
                    )),
                }
            }
            OWord::Call(args) => {
                let start = index
                    .owords(&key)
                    .iter()
                    .find(|(_, k)| *k == OKind::Sub)
                    .map(|(b, _)| *b)
                    .ok_or_else(|| {
                        let message = match &key {
                            LabelKey::Name(name) if !swarf_syntax::is_plain_file_name(name) => {
                                format!(
                                    "{}: a called subroutine is looked for only beside the program, so its name may not hold a folder, `..` or a root",
                                    show_label(&key)
                                )
                            }
                            _ => format!(
                                "no `{} sub` in this program nor in a file beside it (name.ngc)",
                                show_label(&key)
                            ),
                        };
                        Diagnostic::error(block.span, "E-OWORD", message)
                    })?;
                let mut values = Vec::with_capacity(args.len());
                for (i, arg) in args.iter().enumerate().take(30) {
                    let v = self.eval(program, *arg)?.unwrap_or(0.0);
                    values.push((u8::try_from(i + 1).unwrap_or(30), v));
                }
                self.push_call(block, CallKind::OWord(key), at + 1, start + 1, 1)?;
                self.vars.push_frame(&values);
                Ok(Flow::Jump(start + 1))
            }
            OWord::If(cond) | OWord::ElseIf(cond) => {
                if self.condition(program, *cond)? {
                    return Ok(Flow::Next);
                }
                let next = index
                    .next_oword(&key, at, &[OKind::ElseIf, OKind::Else, OKind::EndIf])
                    .ok_or_else(|| missing("endif"))?;
                Ok(match next.1 {
                    // The elseif line evaluates its own condition.
                    OKind::ElseIf => Flow::Jump(next.0),
                    _ => Flow::Jump(next.0 + 1),
                })
            }
            OWord::Else => {
                // Reached from a branch that ran: skip to the end.
                let end = index
                    .next_oword(&key, at, &[OKind::EndIf])
                    .ok_or_else(|| missing("endif"))?;
                Ok(Flow::Jump(end.0 + 1))
            }
            OWord::EndIf => Ok(Flow::Next),
            OWord::While(cond) => {
                // The tail of a `do … while` loop, or the head of a `while … endwhile` one.
                let do_head = index
                    .previous_oword(&key, at, &[OKind::Do, OKind::EndWhile, OKind::While])
                    .filter(|(_, k)| *k == OKind::Do);
                let holds = self.condition(program, *cond)?;
                if let Some((head, _)) = do_head {
                    return Ok(if holds {
                        Flow::Jump(head + 1)
                    } else {
                        Flow::Next
                    });
                }
                if holds {
                    return Ok(Flow::Next);
                }
                let end = index
                    .next_oword(&key, at, &[OKind::EndWhile])
                    .ok_or_else(|| missing("endwhile"))?;
                Ok(Flow::Jump(end.0 + 1))
            }
            OWord::EndWhile => {
                let head = index
                    .previous_oword(&key, at, &[OKind::While])
                    .ok_or_else(|| missing("while"))?;
                Ok(Flow::Jump(head.0))
            }
            OWord::Do => Ok(Flow::Next),
            OWord::Repeat(count) => {
                let remaining = if let Some(n) = self.repeats.get(&at) {
                    *n
                } else {
                    let n = self.eval(program, *count)?.unwrap_or(0.0).max(0.0).round();
                    n as u64
                };
                if remaining == 0 {
                    self.repeats.remove(&at);
                    let end = index
                        .next_oword(&key, at, &[OKind::EndRepeat])
                        .ok_or_else(|| missing("endrepeat"))?;
                    return Ok(Flow::Jump(end.0 + 1));
                }
                self.repeats.insert(at, remaining - 1);
                Ok(Flow::Next)
            }
            OWord::EndRepeat => {
                let head = index
                    .previous_oword(&key, at, &[OKind::Repeat])
                    .ok_or_else(|| missing("repeat"))?;
                Ok(Flow::Jump(head.0))
            }
            OWord::Break => {
                let end = index
                    .next_oword(&key, at, &[OKind::EndWhile, OKind::EndRepeat, OKind::While])
                    .ok_or_else(|| missing("endwhile"))?;
                if let Some((head, _)) = index.previous_oword(&key, at, &[OKind::Repeat]) {
                    self.repeats.remove(&head);
                }
                Ok(Flow::Jump(end.0 + 1))
            }
            OWord::Continue => {
                let head = index
                    .previous_oword(&key, at, &[OKind::While, OKind::Repeat, OKind::Do])
                    .ok_or_else(|| missing("while"))?;
                Ok(match head.1 {
                    OKind::Do => {
                        let tail = index.next_oword(&key, at, &[OKind::While]);
                        tail.map_or(Flow::Jump(head.0 + 1), |(t, _)| Flow::Jump(t))
                    }
                    _ => Flow::Jump(head.0),
                })
            }
        }
    }

    fn push_call(
        &mut self,
        block: &Block,
        kind: CallKind,
        return_to: usize,
        start: usize,
        repeats: u32,
    ) -> Result<(), Diagnostic> {
        if self.calls.len() >= MAX_CALL_DEPTH {
            return Err(Diagnostic::error(
                block.span,
                "E-NESTING",
                format!(
                    "calls nested more than {MAX_CALL_DEPTH} deep: a subprogram that calls itself?"
                ),
            ));
        }
        self.calls.push(Frame {
            kind,
            return_to,
            start,
            repeats_left: repeats.saturating_sub(1),
            modal: false,
        });
        Ok(())
    }

    /// `M98 P… L…` (or `M98 Pllllpppp`, or Syntec `M98 H…`): runs a subprogram.
    pub(crate) fn call_subprogram(
        &mut self,
        at: usize,
        block: &Block,
        words: &[Word],
    ) -> Result<Flow, Diagnostic> {
        let p = find(words, b'P').map(|w| w.value);
        let h = find(words, b'H').filter(|_| self.st.dialect == Dialect::Syntec);
        let l_word = find(words, b'L').or_else(|| find(words, b'K'));
        if let Some(w) = l_word.filter(|w| w.value > crate::exec::MAX_COUNT) {
            self.st
                .diagnostics
                .push(crate::exec::count_range(w, "repeats"));
        }
        let l = l_word.map(|w| w.value);
        let (number, mut count) = match (p, l) {
            (Some(p), Some(l)) => (p, l),
            // Fanuc: more than four digits in P are the repeat count then the program number.
            (Some(p), None) if p >= 10_000.0 && self.st.dialect != Dialect::LinuxCnc => {
                ((p % 10_000.0).round(), (p / 10_000.0).floor())
            }
            (Some(p), None) => (p, 1.0),
            (None, l) => (f64::NAN, l.unwrap_or(1.0)),
        };
        if count < 1.0 {
            count = 0.0;
        }
        let repeats = count.min(9999.0) as u32;
        if self.index.is_none() && self.piecewise {
            return Ok(self.without_index(at));
        }
        let index = self.index.as_ref().ok_or_else(|| no_index(block))?;
        let start = if let Some(h) = h {
            // Syntec `M98 H n`: the block N n of this program, as a local subprogram.
            let n = h.value;
            index
                .label(at, n as u32)
                .filter(|_| n >= 0.0 && n.fract() == 0.0)
                .ok_or_else(|| {
                    Diagnostic::error(
                        h.span,
                        "E-SUBPROGRAM",
                        format!("there is no block N{n} in this program for M98 H{n}"),
                    )
                })?
        } else {
            if !number.is_finite() {
                return Err(Diagnostic::error(
                    block.span,
                    "E-WORD-MISSING",
                    "M98 needs the program number in P",
                ));
            }
            index
                .program_start(number as u32)
                .map(|s| s + 1)
                .ok_or_else(|| {
                    Diagnostic::error(
                        block.span,
                        "E-SUBPROGRAM",
                        format!(
                            "program O{number:04} is neither in this program nor in a file beside it (O{number:04}, O{number:04}.nc, {number}.nc …)"
                        ),
                    )
                })?
        };
        if repeats == 0 {
            return Ok(Flow::Next);
        }
        self.push_call(block, CallKind::Subprogram, at + 1, start, repeats)?;
        Ok(Flow::Jump(start))
    }

    /// Whether the G66 modal macro is running (a move inside it does not call it again).
    pub(crate) fn in_modal_macro(&self) -> bool {
        self.calls.iter().any(|f| f.modal)
    }

    /// The G66 modal macro after a move: like G65, marked so that its own moves do not call it.
    pub(crate) fn call_modal_macro(
        &mut self,
        at: usize,
        block: &Block,
        number: f64,
        repeats: u32,
        args: &[(u8, f64)],
    ) -> Result<Flow, Diagnostic> {
        let flow = self.call_macro(at, block, number, repeats, args)?;
        if flow != Flow::Next
            && let Some(frame) = self.calls.last_mut()
        {
            frame.modal = true;
        }
        Ok(flow)
    }

    /// `G65 P… L… args`: a macro call with local variables from the arguments.
    pub(crate) fn call_macro(
        &mut self,
        at: usize,
        block: &Block,
        number: f64,
        repeats: u32,
        args: &[(u8, f64)],
    ) -> Result<Flow, Diagnostic> {
        if self.index.is_none() && self.piecewise {
            return Ok(self.without_index(at));
        }
        let index = self.index.as_ref().ok_or_else(|| no_index(block))?;
        let start = index
            .program_start(number as u32)
            .filter(|_| number >= 0.0 && number.fract() == 0.0)
            .map(|s| s + 1)
            .ok_or_else(|| {
                Diagnostic::error(
                    block.span,
                    "E-SUBPROGRAM",
                    format!(
                        "macro program O{number:04} is neither in this program nor in a file beside it (O{number:04}, O{number:04}.nc, {number}.nc …)"
                    ),
                )
            })?;
        if repeats == 0 {
            return Ok(Flow::Next);
        }
        self.push_call(block, CallKind::Macro, at + 1, start, repeats)?;
        self.vars.push_frame(args);
        Ok(Flow::Jump(start))
    }

    /// `M99` (and `M99 Pn`): returns from a subprogram or macro; in the main program it goes back
    /// to the start (or to N n), as the controls do.
    pub(crate) fn return_from(
        &mut self,
        at: usize,
        block: &Block,
        target: Option<&Word>,
    ) -> Result<Flow, Diagnostic> {
        let Some(frame) = self.calls.last_mut() else {
            if self.st.dialect == Dialect::LinuxCnc {
                // LinuxCNC's standalone interpreter ends the program at a main-program M99.
                return Ok(Flow::Stop);
            }
            return match target {
                Some(p) => self.goto(at, p.value, p.span).map(Flow::Jump),
                None => Ok(Flow::Jump(0)),
            };
        };
        if frame.repeats_left > 0 {
            frame.repeats_left -= 1;
            return Ok(Flow::Jump(frame.start));
        }
        let frame = self.calls.pop().ok_or_else(|| no_index(block))?;
        if let CallKind::Macro | CallKind::OWord(_) = frame.kind {
            self.vars.pop_frame();
        }
        match target {
            Some(p) => self
                .goto(frame.return_to.saturating_sub(1), p.value, p.span)
                .map(Flow::Jump),
            None => Ok(Flow::Jump(frame.return_to)),
        }
    }
}

fn no_index(block: &Block) -> Diagnostic {
    Diagnostic::error(block.span, "E-INTERNAL", "the program index is missing")
}

/// The first plain word with address `letter`.
pub(crate) fn find(words: &[Word], letter: u8) -> Option<&Word> {
    words
        .iter()
        .find(|w| w.letter == letter && w.form == WordForm::Plain)
}

fn show_label(key: &LabelKey) -> String {
    match key {
        LabelKey::Number(n) => format!("o{n}"),
        LabelKey::Name(s) => format!("o<{s}>"),
    }
}

/// Runs a whole program with `setup` and returns the execution diagnostics.
pub fn run(program: &Program, setup: Setup, sink: &mut dyn Sink) -> Vec<Diagnostic> {
    let mut interp = Interpreter::new(setup, program.dialect);
    while interp.step(program, sink, 4096) == Status::Running {}
    interp.take_diagnostics()
}

impl SystemVariables for State {
    fn read(&self, n: u32) -> Option<Value> {
        self.system_variable(n)
    }

    fn write(&mut self, n: u32, v: Value) -> Result<bool, String> {
        self.set_system_variable(n, v)
    }
}
