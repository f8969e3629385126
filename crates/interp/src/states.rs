//! The machine state at any block, for the editor's "state at cursor" view: a run records when
//! each block first executes and keeps a copy of the interpreter every few thousand blocks, so
//! the state before any block is a short re-run from the nearest copy, not a copy per block.

use glam::DVec3;
use swarf_syntax::{Diagnostic, Program};

use crate::machine::{Interpreter, Status};
use crate::{Canon, Setup, Sink, Source};

/// Blocks between two kept copies of the interpreter.
const CHECKPOINT_EVERY: u64 = 4096;

/// What the machine is doing just before a block runs.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BlockState {
    /// The active G codes, one per modal group (`G01`, `G17`, `G90`, `G21`, `G54` …).
    pub codes: Vec<String>,
    /// Tool-tip position in the machine frame, mm.
    pub machine: DVec3,
    /// The same point in the program's coordinates (work offset, G52/G92 and rotation undone), mm.
    pub work: DVec3,
    /// The active work coordinate system (`G54`, `G54.1P7`, `G59.3`).
    pub work_offset_name: String,
    /// Its offset, mm.
    pub work_offset: DVec3,
    /// The tool number last selected.
    pub tool: u32,
    /// The active length offset: register and signed value (mm).
    pub length_offset: Option<(u32, f64)>,
    /// Feed rate (mm/min in G94).
    pub feed: f64,
    /// Spindle speed.
    pub spindle_rpm: f64,
    /// Blocks executed before this one (loops and calls count every pass).
    pub executed: u64,
}

/// Where each block first runs, and copies of the interpreter to re-run from.
#[derive(Debug, Clone, Default)]
pub struct States {
    /// Per block: how many blocks had run when it first ran (`u32::MAX`: never ran).
    first_run: Vec<u32>,
    /// (blocks executed, interpreter before the next block), in run order.
    checkpoints: Vec<(u64, Interpreter)>,
}

impl States {
    /// The state just before block `block` first runs, or `None` when it never runs.
    pub fn at(&self, program: &Program, block: usize) -> Option<BlockState> {
        let target = u64::from(*self.first_run.get(block)?);
        if target == u64::from(u32::MAX) {
            return None;
        }
        let (_, from) = self.checkpoints.iter().rev().find(|(n, _)| *n <= target)?;
        let mut interp = from.clone();
        while interp.executed_blocks() < target
            && interp.step(program, &mut Discard, 1) != Status::Finished
        {}
        Some(interp.block_state())
    }

    /// The state just before block `block` of piece `piece` (its blocks read again as they
    /// were run, see [`StatesRun::run_piece`]) first runs, or `None` when it never runs.
    pub fn in_piece(&self, piece: usize, blocks: &Program, block: usize) -> Option<BlockState> {
        let (_, from) = self.checkpoints.get(piece)?;
        let mut interp = from.clone();
        interp.start_piece();
        while interp.next_block < block {
            let before = interp.next_block;
            interp.step(blocks, &mut Discard, 1);
            if interp.status == Status::Finished || interp.next_block == before {
                return None;
            }
        }
        (interp.next_block == block).then(|| interp.block_state())
    }

    /// How many copies of the interpreter are kept.
    pub fn checkpoints(&self) -> usize {
        self.checkpoints.len()
    }
}

/// A sink that drops everything (re-runs for a state only need the machine).
struct Discard;

impl Sink for Discard {
    fn emit(&mut self, _source: Source, _event: &Canon) {}
}

/// A run like [`run`](crate::run) that also records [`States`], in bounded steps, so an editor can
/// spread a long program over several frames.
#[derive(Debug, Clone)]
pub struct StatesRun {
    interp: Interpreter,
    states: States,
    /// Distinct blocks reached so far (for progress).
    reached: usize,
}

impl StatesRun {
    /// A run of `program` from power-on with `setup`; nothing executed yet.
    pub fn new(program: &Program, setup: Setup) -> Self {
        StatesRun {
            interp: Interpreter::new(setup, program.dialect),
            states: States {
                first_run: vec![u32::MAX; program.blocks.len()],
                checkpoints: Vec::new(),
            },
            reached: 0,
        }
    }

    /// Executes at most `budget` blocks of `program` (the one given to [`StatesRun::new`]),
    /// sending events to `sink`.
    pub fn step(&mut self, program: &Program, sink: &mut dyn Sink, budget: usize) -> Status {
        for _ in 0..budget {
            if self.interp.status == Status::Finished {
                break;
            }
            let executed = self.interp.executed_blocks();
            if executed.is_multiple_of(CHECKPOINT_EVERY) {
                let copy = self.interp.snapshot();
                self.states.checkpoints.push((executed, copy));
            }
            if let Some(first) = self.states.first_run.get_mut(self.interp.next_block)
                && *first == u32::MAX
            {
                *first = u32::try_from(executed).unwrap_or(u32::MAX);
                self.reached += 1;
            }
            self.interp.step(program, sink, 1);
        }
        self.interp.status
    }

    /// Runs the next piece of a program read piece by piece like [`Interpreter::run_piece`],
    /// keeping a copy of the interpreter before it: the state at a block of a piece is then a
    /// re-run of that piece alone ([`States::in_piece`]).
    pub fn run_piece(&mut self, piece: &Program, sink: &mut dyn Sink) -> crate::Piece {
        let copy = (self.interp.executed_blocks(), self.interp.snapshot());
        self.states.checkpoints.push(copy);
        self.reached += piece.blocks.len();
        self.interp.run_piece(piece, sink)
    }

    /// Ends a program run piece by piece (see [`Interpreter::finish_pieces`]).
    pub fn finish_pieces(&mut self, sink: &mut dyn Sink) {
        self.interp.finish_pieces(sink);
    }

    /// How many different blocks have run so far (at most the program's block count; loops
    /// count each block once), for a progress bar.
    pub fn blocks_reached(&self) -> usize {
        self.reached
    }

    /// How many blocks have been executed (every pass of a loop counts).
    pub fn executed_blocks(&self) -> u64 {
        self.interp.executed_blocks()
    }

    /// The diagnostics found while executing and the recorded states; call once the run is
    /// finished (earlier, they cover the blocks run so far).
    pub fn finish(mut self) -> (Vec<Diagnostic>, States) {
        (self.interp.take_diagnostics(), self.states)
    }
}
