//! The modal machine: runs blocks in bounded steps, follows the program's flow (calls, Macro B
//! jumps and loops, LinuxCNC O-words) and hands each block's words to [`exec`](crate::exec).

use std::borrow::Cow;
use std::collections::HashMap;

use glam::DVec3;
use swarf_syntax::{
    Block, Diagnostic, Dialect, ExprId, Missing, OLabel, OWord, Program, Span, Statement, Word,
    WordForm, codes::Code,
};

use crate::exec::{MAX_COUNT, Request, count_range};
use crate::flow::{Index, LabelKey};
use crate::macros::{self, Value, Variables};
use crate::state::{MacroCall, State};
use crate::{Canon, Setup, Sink, Source};

/// Whether a run has more blocks to execute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Status {
    /// The budget ran out; call [`Interpreter::step`] again to go on.
    #[default]
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

/// The farthest from the machine origin a position may be, in mm per axis: a move, arc centre or
/// hole past it (or not finite) is an error of its block (`E-COORDINATE-RANGE`) that ends the run.
pub const MAX_COORDINATE_MM: f64 = 1.0e9;

/// The longest dwell (s, about 32 years) and lowest feed other than zero (mm/min) a run accepts:
/// only a variable gone astray gives more or less, and the time estimate would not be finite.
const MAX_DWELL_SECS: f64 = 1.0e9;
const MIN_FEED_MM_PER_MIN: f64 = 1.0e-100;

/// The work of an arc's extra turn: the points it is checked at (see `max_work`).
const TURN_WORK: u64 = 64;

/// The work of a diagnostic met again (its message is made again; see `max_work`).
const REPEAT_WORK: u64 = 8;

/// Passes events on, counting motions (`max_motions`) and arc turns (`max_work`), and holds back
/// every event from the first whose numbers are out of range on (see [`MAX_COORDINATE_MM`]). The
/// program zero goes to `inner` directly (`Interpreter::report_origin`).
pub(crate) struct MotionCounter<'s> {
    inner: &'s mut dyn Sink,
    motions: u64,
    /// The run's limit on motions: past it the counter is full (see [`Sink::full`]).
    max_motions: u64,
    /// The work of the extra full turns of the arcs passed on.
    turns: u64,
    /// The first event out of range: its block and what is wrong.
    out_of_range: Option<(Source, String)>,
}

/// Whether a coordinate is within [`MAX_COORDINATE_MM`] (a NaN is not).
fn within(c: f64) -> bool {
    c.abs() <= MAX_COORDINATE_MM
}

/// Whether a feed rate is usable: zero, or at least [`MIN_FEED_MM_PER_MIN`] and finite.
fn usable_feed(feed: f64) -> bool {
    feed == 0.0 || (MIN_FEED_MM_PER_MIN..=f64::MAX).contains(&feed)
}

/// What is out of range in a point (see [`MAX_COORDINATE_MM`]), if anything.
fn point_out_of_range(what: &str, p: DVec3) -> Option<String> {
    (!(within(p.x) && within(p.y) && within(p.z))).then(|| {
        format!(
            "{what} X{} Y{} Z{} mm (machine frame) is beyond the ±{MAX_COORDINATE_MM:e} mm any machine reaches: a variable or scale out of range? The run stops here",
            p.x, p.y, p.z
        )
    })
}

/// What is out of range in a feed rate, if anything.
fn feed_out_of_range(feed: f64) -> Option<String> {
    (!usable_feed(feed)).then(|| {
        format!(
            "the feed {feed} mm/min is not a usable number (a move would take forever): a variable out of range? The run stops here"
        )
    })
}

/// What is out of range in an event's numbers, if anything.
fn out_of_range(event: &Canon) -> Option<String> {
    match event {
        Canon::Rapid { to } => point_out_of_range("the end point", *to),
        Canon::Feed {
            to,
            feed_mm_per_min,
        } => point_out_of_range("the end point", *to)
            .or_else(|| feed_out_of_range(*feed_mm_per_min)),
        Canon::Arc(a) => point_out_of_range("the end point", a.to)
            .or_else(|| point_out_of_range("the arc centre", a.center))
            .or_else(|| feed_out_of_range(a.feed_mm_per_min)),
        Canon::Hole { top, bottom, .. } => point_out_of_range("the hole's top", *top)
            .or_else(|| point_out_of_range("the hole's bottom", *bottom)),
        Canon::Dwell { secs } => (!(0.0..=MAX_DWELL_SECS).contains(secs)).then(|| {
            format!(
                "a dwell of {secs} s is beyond the {MAX_DWELL_SECS:e} s a run accepts: a variable out of range? The run stops here"
            )
        }),
        _ => None,
    }
}

impl Sink for MotionCounter<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        if self.out_of_range.is_some() {
            return;
        }
        if let Some(problem) = out_of_range(event) {
            self.out_of_range = Some((source, problem));
            return;
        }
        match event {
            Canon::Rapid { .. } | Canon::Feed { .. } => self.motions += 1,
            Canon::Arc(a) => {
                self.motions += 1;
                self.turns += u64::from(a.turns) * TURN_WORK;
            }
            _ => {}
        }
        self.inner.emit(source, event);
    }

    fn full(&self) -> bool {
        self.motions >= self.max_motions || self.out_of_range.is_some() || self.inner.full()
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        if self.out_of_range.is_none() {
            self.inner.programmed(source, event);
        }
    }

    fn straight(&mut self, source: Source, rapid: bool, x: f64, y: f64, z: f64, feed: f64) {
        if self.out_of_range.is_some() {
            return;
        }
        // The common move in range tested without a branch an axis; the message only when not.
        if !(within(x) & within(y) & within(z) & (rapid || usable_feed(feed))) {
            let problem = point_out_of_range("the end point", DVec3::new(x, y, z))
                .or_else(|| (!rapid).then(|| feed_out_of_range(feed)).flatten());
            self.out_of_range = problem.map(|p| (source, p));
            return;
        }
        self.motions += 1;
        self.inner.straight(source, rapid, x, y, z, feed);
    }

    fn stroke_zone(&mut self, source: Source, zone: Option<&crate::StrokeZone>) {
        self.inner.stroke_zone(source, zone);
    }
}

/// Call nesting the controls allow (Fanuc 0i: 10, and macro calls), past which a run stops.
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

/// Where the run goes next, or the diagnostic that stops it.
type FlowResult = Result<Flow, Diagnostic>;

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
    /// Whether this is the G66 modal macro, called after a move (its own moves do not call it).
    modal: bool,
}

/// Interprets a parsed program in bounded steps.
#[derive(Debug, Clone, Default)]
pub struct Interpreter {
    pub(crate) st: State,
    pub(crate) vars: Variables,
    index: Option<std::sync::Arc<Index>>,
    /// The next block to run (progress through the program).
    pub(crate) next_block: usize,
    executed: u64,
    /// Work done inside the blocks: expression terms and O-word lines searched.
    work: u64,
    /// The last jump back (from block, to block): the loop a runaway run is in.
    back_jump: Option<(usize, usize)>,
    /// Motion events produced so far.
    motions: u64,
    /// The program zero last reported with `Canon::Origin`.
    origin: Option<DVec3>,
    pub(crate) status: Status,
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
    /// Whether every block takes the general path (see [`Interpreter::general_path_only`]).
    general_only: bool,
    /// Whether `origin` is the current program zero (only short-path blocks keep it).
    origin_current: bool,
    /// The short path's data (see `exec::Shortcut`), and whether it is current.
    short: Option<crate::exec::Shortcut>,
    short_current: bool,
}

impl Interpreter {
    /// A machine at power-on for `dialect`, at the origin, with `setup`'s offsets.
    pub fn new(setup: Setup, dialect: Dialect) -> Self {
        Interpreter {
            st: State::new(setup, dialect),
            vars: Variables::new(dialect),
            ..Interpreter::default()
        }
    }

    /// Runs the next piece of a program read piece by piece (see `ParseRun::clear_blocks`), the
    /// state carrying over; call [`Interpreter::finish_pieces`] last.
    pub fn run_piece(&mut self, program: &Program, sink: &mut dyn Sink) -> Piece {
        if self.jumped || (self.executed > 0 && !self.piecewise) {
            return Piece::NeedsWhole;
        }
        if self.status == Status::Finished {
            return Piece::Ended;
        }
        self.start_piece();
        // A block that needs the whole program or a jump ends the piece (the program runs whole).
        while self.step(program, sink, 4096) == Status::Running
            && !self.jumped
            && self.next_block < program.blocks.len()
        {}
        if self.status == Status::Finished && !self.jumped {
            // The blocks after the end were not run; they still decide, as before the piece ran.
            let rest = program.blocks.get(self.unvisited..).unwrap_or_default();
            self.jumped = rest.iter().any(|block| self.needs_whole(block));
        }
        self.block_base += program.blocks.len();
        if self.jumped {
            Piece::NeedsWhole
        } else if self.status == Status::Finished {
            Piece::Ended
        } else {
            Piece::Ran
        }
    }

    /// Makes the next block the first of a new piece.
    pub(crate) fn start_piece(&mut self) {
        self.piecewise = true;
        self.index = None;
        self.next_block = 0;
        self.unvisited = 0;
    }

    /// Whether `block`, met piece by piece, needs the whole index (a loop, call, program).
    fn needs_whole(&mut self, block: &Block) -> bool {
        let several_programs = block.program().is_some() && self.program_seen;
        self.program_seen |= block.program().is_some();
        // A code the table marks `whole`, in the dialect or else in Fanuc's (M198 calls in all).
        let dialect = self.st.dialect;
        let calls = block.words.iter().any(|w| {
            matches!(w.letter, b'G' | b'M')
                && (w.expr.is_some()
                    || Code::from_value(w.letter, w.value).is_some_and(|code| {
                        swarf_syntax::codes::lookup(dialect, code)
                            .or_else(|| swarf_syntax::codes::lookup(Dialect::Fanuc, code))
                            .is_some_and(|def| def.whole)
                    }))
        });
        let control = (block.statements().iter()).any(|s| !matches!(s, Statement::Assign { .. }));
        several_programs || calls || control
    }

    /// Ends a program run piece by piece, as [`Interpreter::step`] ends one run whole.
    pub fn finish_pieces(&mut self, sink: &mut dyn Sink) {
        if self.status == Status::Running {
            self.status = Status::Finished;
            crate::corners::flush(&mut self.st, sink);
        }
    }

    /// Runs every block through the general path, to check the short path gives the same.
    pub fn general_path_only(&mut self) {
        self.general_only = true;
    }

    /// Takes the diagnostics so far: each code and place once with its count (at most `MAX_KEPT`).
    pub fn take_diagnostics(&mut self) -> Vec<Diagnostic> {
        self.st.diagnostics.take()
    }

    /// How many blocks have been executed.
    pub fn executed_blocks(&self) -> u64 {
        self.executed
    }

    /// A copy of the interpreter without the diagnostics found so far (for [`crate::States`]).
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

    /// Executes at most `budget` blocks of `program`, sending events to `sink`.
    pub fn step(&mut self, program: &Program, sink: &mut dyn Sink, budget: usize) -> Status {
        // Piece by piece there is no index: a block that needs it has the program run whole.
        if self.index.is_none() && !self.piecewise {
            let index = Index::build(program, &mut self.st.diagnostics);
            self.index = Some(std::sync::Arc::new(index));
        }
        let mut counted = MotionCounter {
            inner: sink,
            motions: self.motions,
            max_motions: self.st.setup.machine.max_motions,
            turns: 0,
            out_of_range: None,
        };
        let mut left = budget;
        while left > 0 {
            if self.stopped(program, &mut counted) {
                break;
            }
            let ran = self.short_run(program, left, &mut counted);
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
                // The text ran out: inside a call that is an implicit return; otherwise the end.
                match self.pop_call() {
                    Some(frame) => self.next_block = frame.return_to,
                    None => self.status = Status::Finished,
                }
                continue;
            };
            // The runaway limits: blocks run, the work inside them, and moves made (memory).
            let machine = &self.st.setup.machine;
            if self.executed >= machine.max_blocks
                || self.work(&counted) >= machine.max_work
                || counted.motions >= machine.max_motions
                || counted.inner.full()
            {
                self.limit_reached(program, block, &counted);
                break;
            }
            let source = Source {
                block: u32::try_from(self.block_base + at).unwrap_or(u32::MAX),
                line: block.line.saturating_add(1),
            };
            self.executed += 1;
            self.st.diagnostics.block = self.executed;
            self.work += match &self.index {
                Some(index) => index.terms(at),
                None => crate::flow::terms(program, block),
            };
            self.st.blocks_run = self.executed;
            self.st.block_span = block.span;
            let before = counted.motions;
            let flow = if self.piecewise
                && !ends_main_program(block, self.st.dialect)
                && self.needs_whole(block)
            {
                self.jumped = true;
                break;
            } else if block.has_error() {
                Flow::Next
            } else {
                self.origin_current = false;
                self.short_current = false;
                self.run_block(program, at, block, source, &mut counted)
            };
            self.unvisited = at + 1;
            if counted.motions != before && !self.origin_current {
                self.report_origin(counted.inner);
            }
            match flow {
                Flow::Next => self.next_block = at + 1,
                Flow::Jump(_) if self.piecewise => {
                    self.jumped = true;
                    break;
                }
                Flow::Jump(to) => {
                    if to <= at {
                        self.back_jump = Some((at, to));
                    }
                    self.next_block = to;
                }
                Flow::Stop => self.status = Status::Finished,
            }
        }
        self.stopped(program, &mut counted);
        if self.status == Status::Finished {
            crate::corners::flush(&mut self.st, &mut counted);
        }
        self.motions = counted.motions;
        self.work += counted.turns;
        self.status
    }

    /// Whether the run has ended or must end now (a stopping diagnostic, numbers out of range).
    fn stopped(&mut self, program: &Program, counted: &mut MotionCounter<'_>) -> bool {
        if let Some((source, problem)) = counted.out_of_range.take() {
            let at = (source.block as usize).saturating_sub(self.block_base);
            let span = (program.blocks.get(at)).map_or(self.st.block_span, |b| b.span);
            self.st.error(span, "E-COORDINATE-RANGE", problem);
            // Nothing more is passed on.
            counted.out_of_range = Some((source, String::new()));
            self.status = Status::Finished;
        }
        if self.st.diagnostics.stops() {
            self.status = Status::Finished;
        }
        self.status == Status::Finished
    }

    /// Ends the run at one of its limits, naming it and the loop the run is in.
    fn limit_reached(&mut self, program: &Program, block: &Block, counted: &MotionCounter<'_>) {
        let machine = &self.st.setup.machine;
        let (in_loop, loop_span) = self.in_loop(program).unzip();
        let work = self.work(counted);
        let (blocks, moves) = (self.executed, counted.motions);
        let (runaway, after, why) = if blocks >= machine.max_blocks {
            let after = format!("{blocks} blocks (the limit in [machine] max_blocks)");
            (true, after, "an endless loop?")
        } else if work >= machine.max_work {
            let after = format!(
                "{blocks} blocks and {work} steps of work in them: expression terms, O-word lines searched, arc turns, diagnostics met again (the limit in [machine] max_work)"
            );
            (true, after, "an endless loop?")
        } else if moves >= machine.max_motions {
            let after = format!("{moves} moves (the limit in [machine] max_motions)");
            (false, after, "the toolpath would not fit in memory")
        } else {
            let why = "their toolpath holds as much as [machine] max_motions allows (an arc is drawn as many segments; holes, dwells and changes of feed or tool count too), more would not fit in memory";
            (false, format!("{moves} moves"), why)
        };
        let (code, span) = if runaway {
            ("E-RUNAWAY", loop_span)
        } else {
            ("E-MOTION-LIMIT", None)
        };
        let in_loop = in_loop.unwrap_or_default();
        let message = format!("execution stopped after {after}{in_loop}: {why}");
        self.st.error(span.unwrap_or(block.span), code, message);
        self.status = Status::Finished;
    }

    /// The work done so far (see `[machine] max_work`).
    fn work(&self, counted: &MotionCounter<'_>) -> u64 {
        self.work + counted.turns + REPEAT_WORK * self.st.diagnostics.repeats
    }

    /// The loop the run is in, for a runaway's message, and the span of its jump back.
    fn in_loop(&self, program: &Program) -> Option<(String, Span)> {
        let (from, to) = self.back_jump?;
        let (from, to) = (program.blocks.get(from)?, program.blocks.get(to)?);
        let (head, back) = (to.line + 1, from.line + 1);
        let words = format!(", in the loop from line {head} to the jump back at line {back}");
        Some((words, from.span))
    }

    /// Runs the plain motion blocks from the next one through the short path; how many ran.
    fn short_run(&mut self, program: &Program, left: usize, sink: &mut MotionCounter<'_>) -> usize {
        // An alarm raised by the block before is reported by the block loop, as is a full sink.
        if self.general_only || self.st.alarm.is_some() || sink.full() {
            return 0;
        }
        if !self.short_current {
            self.short = crate::exec::Shortcut::of(&self.st);
            self.short_current = true;
        }
        let Some(short) = self.short else {
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
        for block in (program.blocks.get(at..).unwrap_or_default().iter()).take(room) {
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
            // What the block loop sets before a block, which compensation and diagnostics read.
            self.st.block_span = block.span;
            self.st.blocks_run += 1;
            self.st.diagnostics.block = self.st.blocks_run;
            let before = sink.motions;
            let Some(one_segment) =
                crate::exec::plain_block(&mut self.st, short, block, source, sink)
            else {
                break;
            };
            ran += 1;
            if !self.origin_current && sink.motions != before {
                self.report_origin(sink.inner);
            }
            // An arc may add many segments: a full sink ends the run here, as do alarms.
            if (!one_segment && sink.full())
                || self.st.alarm.is_some()
                || self.st.diagnostics.stops()
                || sink.out_of_range.is_some()
            {
                break;
            }
        }
        self.executed += u64::try_from(ran).unwrap_or(u64::MAX);
        self.st.blocks_run = self.executed;
        self.next_block = at + ran;
        self.unvisited = self.next_block;
        ran
    }

    /// Reports the program zero of the moves for the origin marks when it is not current.
    fn report_origin(&mut self, sink: &mut dyn Sink) {
        let origin = self.st.to_machine(DVec3::ZERO);
        self.origin_current = true;
        if self.origin != Some(origin) && origin.is_finite() {
            self.origin = Some(origin);
            sink.origin(origin);
        }
    }

    /// Leaves the innermost call, and its level of local variables where it has one.
    fn pop_call(&mut self) -> Option<Frame> {
        let frame = self.calls.pop()?;
        if let CallKind::Macro | CallKind::OWord(_) = frame.kind {
            self.vars.pop_frame();
        }
        Some(frame)
    }

    /// Runs one block: reads its words, makes its assignments, runs its codes and statements.
    fn run_block(
        &mut self,
        program: &Program,
        at: usize,
        block: &Block,
        source: Source,
        sink: &mut dyn Sink,
    ) -> Flow {
        // Running into another `O` program's line ends the main program (it runs only when called).
        let first = self.index.as_ref().and_then(|i| i.first_program);
        if block.program().is_some() && self.calls.is_empty() && first.is_some_and(|f| f != at) {
            let message = "the main program ends here, where the next program starts (it runs only when called)";
            self.st.note(block.span, "N-PROGRAM-END", message);
            return Flow::Stop;
        }
        let words = match self.resolve_words(program, block) {
            Ok(words) => words,
            Err(e) => {
                self.st.diagnostics.push(e);
                return Flow::Next;
            }
        };
        // Each assignment reads the values from before the block (LinuxCNC's rule).
        let assigned = (block.statements().iter())
            .filter_map(|s| match s {
                Statement::Assign { target, value } => Some((*target, *value)),
                _ => None,
            })
            .map(|(t, v)| macros::prepare_assign(program, t, v, &self.vars, &self.st))
            .collect::<Result<Vec<_>, _>>()
            .and_then(|all| {
                all.iter()
                    .try_for_each(|a| a.apply(&mut self.vars, &mut self.st))
            });
        if let Some(e) = assigned.err().or_else(|| self.st.alarm.take()) {
            return self.stop_with(e);
        }
        let mut flow = Flow::Next;
        if !words.is_empty() {
            for request in crate::exec::execute(&mut self.st, block, &words, source, sink) {
                flow = self.carry_out(at, block, &words, request, flow);
            }
        }
        if flow != Flow::Next {
            return flow;
        }
        for statement in block.statements() {
            match self.control(program, at, block, statement) {
                Ok(Flow::Next) => {}
                Ok(other) => return other,
                Err(e) => return self.stop_with(e),
            }
        }
        flow
    }

    /// Carries out a block's request after the ones before (`flow`): where the run goes next.
    fn carry_out(
        &mut self,
        at: usize,
        block: &Block,
        words: &[Word],
        request: Request,
        flow: Flow,
    ) -> Flow {
        let next = match request {
            Request::Stop => return Flow::Stop,
            Request::Subprogram => self.call_subprogram(at, block, words),
            Request::Return => self.return_from(at, block, find(words, b'P')),
            Request::Macro(call) => self.call_macro(at, block, &call),
            Request::ModalMacro => match self.st.modal_macro.clone() {
                Some(call) if flow == Flow::Next && !self.calls.iter().any(|f| f.modal) => {
                    // Like G65, marked so that the macro's own moves do not call it again.
                    let called = self.call_macro(at, block, &call);
                    if called.as_ref().is_ok_and(|f| *f != Flow::Next)
                        && let Some(frame) = self.calls.last_mut()
                    {
                        frame.modal = true;
                    }
                    called
                }
                _ => return flow,
            },
        };
        next.unwrap_or_else(|e| self.stop_with(e))
    }

    /// Reports the diagnostic that stops the run.
    fn stop_with(&mut self, e: Diagnostic) -> Flow {
        self.st.diagnostics.push(e);
        Flow::Stop
    }

    /// Reads the block's words: expressions evaluated, a word of a vacant variable left out.
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
            let Some(value) = self.eval(program, expr)? else {
                continue;
            };
            let mut w = *word;
            w.value = value;
            if w.letter == b'G' || w.letter == b'M' {
                // A code from a variable is checked like a written one.
                let code = Code::from_value(w.letter, value);
                if (code.and_then(|c| swarf_syntax::codes::lookup(self.st.dialect, c))).is_none() {
                    let (l, control) = (w.letter(), self.st.dialect.label());
                    let message =
                        format!("{l}{value} (from a variable) is not a code of {control}");
                    return Err(Diagnostic::error(word.span, "E-UNKNOWN-CODE", message));
                }
                // Codes are read as plain numbers from here on.
                w.expr = None;
            }
            out.push(w);
        }
        Ok(Cow::Owned(out))
    }

    fn eval(&self, program: &Program, id: ExprId) -> Result<Value, Diagnostic> {
        macros::eval(program, id, &self.vars, &self.st)
    }

    /// A condition (`IF`, `WHILE`, `if`, `while`): nonzero is true, vacant false.
    fn condition(&self, program: &Program, id: ExprId) -> Result<bool, Diagnostic> {
        Ok(self.eval(program, id)?.is_some_and(|v| v != 0.0))
    }

    /// The block a `GOTO n` (or `M99 Pn`) in block `at` goes to.
    fn goto(&self, at: usize, n: f64, span: Span) -> Result<usize, Diagnostic> {
        // No index while running piece by piece: the jump has the program run whole.
        let Some(index) = &self.index else {
            return Ok(at);
        };
        let label = (n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX)).then_some(n as u32);
        label.and_then(|n| index.label(at, n)).ok_or_else(|| {
            let message = format!("there is no block N{n} in this program to jump to");
            Diagnostic::error(span, "E-MACRO-GOTO", message)
        })
    }

    /// Macro B and O-word control statements.
    fn control(
        &mut self,
        program: &Program,
        at: usize,
        block: &Block,
        statement: &Statement,
    ) -> FlowResult {
        // No index piece by piece: an assignment runs, anything else has the program run whole.
        let Some(index) = self.index.as_ref() else {
            return Ok(match statement {
                Statement::Assign { .. } => Flow::Next,
                _ => Flow::Jump(at),
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
                    Statement::Goto { .. } => self.control(program, at, block, then),
                    Statement::Assign { target, value } => {
                        macros::prepare_assign(program, *target, *value, &self.vars, &self.st)?
                            .apply(&mut self.vars, &mut self.st)?;
                        Ok(Flow::Next)
                    }
                    _ => Ok(Flow::Next),
                }
            }
            Statement::While { cond, .. } => {
                let holds = cond.map_or(Ok(true), |c| self.condition(program, c))?;
                if holds {
                    return Ok(Flow::Next);
                }
                let end = index.loop_end.get(&at);
                Ok(end.map_or(Flow::Stop, |end| Flow::Jump(end + 1)))
            }
            Statement::End { .. } => {
                Ok((index.loop_head.get(&at)).map_or(Flow::Stop, |h| Flow::Jump(*h)))
            }
            Statement::OWord { label, kind } => self.oword(program, at, block, label, kind),
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
    ) -> FlowResult {
        // The label's key (a computed label by its value).
        let key = match label {
            OLabel::Number(n) => LabelKey::Number(*n),
            OLabel::Name(s) => LabelKey::Name(s.clone()),
            OLabel::Expr(id) => {
                let v = self.eval(program, *id)?.unwrap_or(0.0);
                if !(v >= 0.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX)) {
                    let span = program.expr(*id).map_or(Span::default(), |n| n.span);
                    let message = format!("O-word number {v} is not a whole number");
                    return Err(Diagnostic::error(span, "E-OWORD", message));
                }
                LabelKey::Number(v as u32)
            }
        };
        let shown = match &key {
            LabelKey::Number(n) => format!("o{n}"),
            LabelKey::Name(s) => format!("o<{}>", swarf_syntax::excerpt(s)),
        };
        // A copy of the index's handle, so the O-word lines searched count as work.
        let Some(index) = self.index.clone() else {
            return Ok(Flow::Jump(at));
        };
        let missing = |what: &str| {
            let message = format!("{shown} has no matching `{what}`");
            Diagnostic::error(block.span, "E-OWORD", message)
        };
        // The nearest line of the label after or before this one that is one of `kinds`.
        type Kinds = fn(&OWord) -> bool;
        let after = |work: &mut u64, kinds: Kinds| index.near_oword(&key, at, true, kinds, work);
        let before = |work: &mut u64, kinds: Kinds| index.near_oword(&key, at, false, kinds, work);
        // A jump past the next such line, or back to the last one; `what` names it when missing.
        let past = |work: &mut u64, kinds: Kinds, what: &str| {
            (after(work, kinds).map(|l| Flow::Jump(l.0 + 1))).ok_or_else(|| missing(what))
        };
        let back = |work: &mut u64, kinds: Kinds, what: &str| {
            (before(work, kinds).map(|l| Flow::Jump(l.0))).ok_or_else(|| missing(what))
        };
        match kind {
            OWord::Sub => {
                // Reached in sequence: a definition is skipped, not run.
                past(&mut self.work, |k| matches!(k, OWord::EndSub(_)), "endsub")
            }
            OWord::EndSub(value) | OWord::Return(value) => {
                if let Some(v) = value {
                    self.vars.set_named("_value", self.eval(program, *v)?);
                }
                match self.calls.last() {
                    Some(frame) if frame.kind == CallKind::OWord(key.clone()) => {
                        Ok(Flow::Jump(self.pop_call().map_or(at + 1, |f| f.return_to)))
                    }
                    _ if matches!(kind, OWord::EndSub(_)) => Ok(Flow::Next),
                    _ => {
                        let message = format!("`{shown} return` outside its subroutine");
                        Err(Diagnostic::error(block.span, "E-OWORD", message))
                    }
                }
            }
            OWord::Call(args) => {
                let sub = index.owords(&key).iter().find(|(_, k)| *k == OWord::Sub);
                let Some(&(start, _)) = sub else {
                    let message = match &key {
                        LabelKey::Name(name) if !swarf_syntax::is_plain_file_name(name) => format!(
                            "{shown}: a called subroutine is looked for only beside the program, so its name may not hold a folder, `..` or a root"
                        ),
                        LabelKey::Name(name)
                            if let Some(why) = index.unlinked(&Missing::Name(name.to_string())) =>
                        {
                            format!("no `{shown} sub` in this program: {why}")
                        }
                        _ => format!(
                            "no `{shown} sub` in this program nor in a file beside it (name.ngc)"
                        ),
                    };
                    return Err(Diagnostic::error(block.span, "E-OWORD", message));
                };
                let values = (args.iter().zip(1..=30))
                    .map(|(arg, i)| Ok((i, self.eval(program, *arg)?.unwrap_or(0.0))))
                    .collect::<Result<Vec<_>, Diagnostic>>()?;
                self.push_call(block, CallKind::OWord(key), at + 1, start + 1, 1)?;
                self.vars.push_frame(&values);
                Ok(Flow::Jump(start + 1))
            }
            OWord::If(cond) | OWord::ElseIf(cond) => {
                if self.condition(program, *cond)? {
                    return Ok(Flow::Next);
                }
                let next = after(&mut self.work, |k| {
                    matches!(k, OWord::ElseIf(_) | OWord::Else | OWord::EndIf)
                });
                Ok(match next.ok_or_else(|| missing("endif"))? {
                    // The elseif line evaluates its own condition.
                    (line, OWord::ElseIf(_)) => Flow::Jump(line),
                    (line, _) => Flow::Jump(line + 1),
                })
            }
            OWord::Else => {
                // Reached from a branch that ran: skip to the end.
                past(&mut self.work, |k| *k == OWord::EndIf, "endif")
            }
            OWord::EndIf => Ok(Flow::Next),
            OWord::While(cond) => {
                // The tail of a `do … while` loop, or the head of a `while … endwhile` one.
                let do_head = before(&mut self.work, |k| {
                    matches!(k, OWord::Do | OWord::EndWhile | OWord::While(_))
                })
                .filter(|(_, k)| **k == OWord::Do);
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
                past(&mut self.work, |k| *k == OWord::EndWhile, "endwhile")
            }
            OWord::EndWhile => back(&mut self.work, |k| matches!(k, OWord::While(_)), "while"),
            OWord::Do => Ok(Flow::Next),
            OWord::Repeat(count) => {
                let remaining = match self.repeats.get(&at) {
                    Some(n) => *n,
                    None => self.eval(program, *count)?.unwrap_or(0.0).max(0.0).round() as u64,
                };
                if remaining == 0 {
                    self.repeats.remove(&at);
                    return past(&mut self.work, |k| *k == OWord::EndRepeat, "endrepeat");
                }
                self.repeats.insert(at, remaining - 1);
                Ok(Flow::Next)
            }
            OWord::EndRepeat => back(&mut self.work, |k| matches!(k, OWord::Repeat(_)), "repeat"),
            OWord::Break => {
                let ends =
                    |k: &OWord| matches!(k, OWord::EndWhile | OWord::EndRepeat | OWord::While(_));
                let end = past(&mut self.work, ends, "endwhile")?;
                if let Some((head, _)) = before(&mut self.work, |k| matches!(k, OWord::Repeat(_))) {
                    self.repeats.remove(&head);
                }
                Ok(end)
            }
            OWord::Continue => {
                let head = before(&mut self.work, |k| {
                    matches!(k, OWord::While(_) | OWord::Repeat(_) | OWord::Do)
                });
                Ok(match head.ok_or_else(|| missing("while"))? {
                    (head, OWord::Do) => {
                        let tail = after(&mut self.work, |k| matches!(k, OWord::While(_)));
                        tail.map_or(Flow::Jump(head + 1), |(t, _)| Flow::Jump(t))
                    }
                    (head, _) => Flow::Jump(head),
                })
            }
        }
    }

    /// Calls the code at `start` `repeats` times (none: the run goes on), returning to `return_to`.
    fn push_call(
        &mut self,
        block: &Block,
        kind: CallKind,
        return_to: usize,
        start: usize,
        repeats: u32,
    ) -> FlowResult {
        if repeats == 0 {
            return Ok(Flow::Next);
        }
        if self.calls.len() >= MAX_CALL_DEPTH {
            let message = format!(
                "calls nested more than {MAX_CALL_DEPTH} deep: a subprogram that calls itself?"
            );
            return Err(Diagnostic::error(block.span, "E-NESTING", message));
        }
        self.calls.push(Frame {
            kind,
            return_to,
            start,
            repeats_left: repeats - 1,
            modal: false,
        });
        Ok(Flow::Jump(start))
    }

    /// `M98 P… L…` (or `M98 Pllllpppp`, or Syntec `M98 H…`): runs a subprogram.
    fn call_subprogram(&mut self, at: usize, block: &Block, words: &[Word]) -> FlowResult {
        let p = find(words, b'P').map(|w| w.value);
        let h = find(words, b'H').filter(|_| self.st.dialect == Dialect::Syntec);
        let l_word = find(words, b'L').or_else(|| find(words, b'K'));
        if let Some(w) = l_word.filter(|w| w.value > MAX_COUNT) {
            self.st.diagnostics.push(count_range(w, "repeats"));
        }
        let (number, count) = match (p, l_word.map(|w| w.value)) {
            (Some(p), Some(l)) => (p, l),
            // Fanuc: more than four digits in P are the repeat count then the program number.
            (Some(p), None) if p >= 10_000.0 && self.st.dialect != Dialect::LinuxCnc => {
                ((p % 10_000.0).round(), (p / 10_000.0).floor())
            }
            (Some(p), None) => (p, 1.0),
            (None, l) => (f64::NAN, l.unwrap_or(1.0)),
        };
        let repeats = count.clamp(0.0, 9999.0) as u32;
        let Some(index) = self.index.as_ref() else {
            return Ok(Flow::Jump(at));
        };
        let start = if let Some(h) = h {
            // Syntec `M98 H n`: the block N n of this program, as a local subprogram.
            let n = h.value;
            let label = (index.label(at, n as u32)).filter(|_| n >= 0.0 && n.fract() == 0.0);
            label.ok_or_else(|| {
                let message = format!("there is no block N{n} in this program for M98 H{n}");
                Diagnostic::error(h.span, "E-SUBPROGRAM", message)
            })?
        } else {
            if !number.is_finite() {
                let message = "M98 needs the program number in P";
                return Err(Diagnostic::error(block.span, "E-WORD-MISSING", message));
            }
            index
                .program_start(number as u32)
                .map(|s| s + 1)
                .ok_or_else(|| not_found(index, block, "program", number))?
        };
        self.push_call(block, CallKind::Subprogram, at + 1, start, repeats)
    }

    /// `G65 P… L… args`: a macro call with local variables from the arguments.
    fn call_macro(&mut self, at: usize, block: &Block, call: &MacroCall) -> FlowResult {
        let number = call.number;
        let Some(index) = self.index.as_ref() else {
            return Ok(Flow::Jump(at));
        };
        let start = index
            .program_start(number as u32)
            .filter(|_| number >= 0.0 && number.fract() == 0.0)
            .map(|s| s + 1)
            .ok_or_else(|| not_found(index, block, "macro program", number))?;
        let flow = self.push_call(block, CallKind::Macro, at + 1, start, call.repeats)?;
        if flow != Flow::Next {
            self.vars.push_frame(&call.args);
        }
        Ok(flow)
    }

    /// `M99` (`M99 Pn`): returns from a call; in the main program back to its start (or N n).
    fn return_from(&mut self, at: usize, block: &Block, target: Option<&Word>) -> FlowResult {
        let Some(frame) = self.calls.last_mut() else {
            // The control runs the program again, endlessly: one pass is drawn.
            let from = match target {
                Some(p) => {
                    self.goto(at, p.value, p.span)?;
                    format!("from N{}", p.value)
                }
                None => "from its start".to_string(),
            };
            let message = format!(
                "M99 in the main program: the control runs it again {from}, over and over until it is stopped; one pass is run here. (A subprogram opened on its own returns here.)"
            );
            self.st.note(block.span, "N-M99-MAIN-REPEATS", message);
            return Ok(Flow::Stop);
        };
        if frame.repeats_left > 0 {
            frame.repeats_left -= 1;
            return Ok(Flow::Jump(frame.start));
        }
        let return_to = frame.return_to;
        self.pop_call();
        match target {
            Some(p) => (self.goto(return_to.saturating_sub(1), p.value, p.span)).map(Flow::Jump),
            None => Ok(Flow::Jump(return_to)),
        }
    }
}

/// Whether `block` is a plain `M99` (no P, other call, statement or program number): met piece by
/// piece with no call open, it ends the main program, which needs no more than the pieces run.
fn ends_main_program(block: &Block, dialect: Dialect) -> bool {
    let mut m99 = false;
    let mut codes = (block.words.iter()).filter(|w| matches!(w.letter, b'G' | b'M'));
    let no_other_call = codes.all(|w| {
        let code = Code::from_value(w.letter, w.value);
        m99 |= w.letter == b'M' && w.value == 99.0;
        let def = code.and_then(|c| swarf_syntax::codes::lookup(dialect, c));
        w.expr.is_none() && (w.value == 99.0 || !def.is_some_and(|def| def.whole))
    });
    m99 && no_other_call
        && block.program().is_none()
        && block.statements().is_empty()
        && block.word(b'P').is_none()
}

/// The first plain word with address `letter`.
pub(crate) fn find(words: &[Word], letter: u8) -> Option<&Word> {
    (words.iter()).find(|w| w.letter == letter && w.form == WordForm::Plain)
}

/// The error of a call to `O number` not in the program: why its file was not linked.
fn not_found(index: &Index, block: &Block, what: &str, number: f64) -> Diagnostic {
    let why = (number >= 0.0 && number.fract() == 0.0)
        .then(|| index.unlinked(&Missing::Number(number as u32)))
        .flatten();
    let message = match why {
        Some(why) => format!("{what} O{number:04} is not in this program: {why}"),
        None => format!(
            "{what} O{number:04} is neither in this program nor in a file beside it (O{number:04}, O{number:04}.nc, {number}.nc …)"
        ),
    };
    Diagnostic::error(block.span, "E-SUBPROGRAM", message)
}

/// Runs a whole program with `setup` and returns the execution diagnostics.
pub fn run(program: &Program, setup: Setup, sink: &mut dyn Sink) -> Vec<Diagnostic> {
    let mut interp = Interpreter::new(setup, program.dialect);
    while interp.step(program, sink, 4096) == Status::Running {}
    interp.take_diagnostics()
}
