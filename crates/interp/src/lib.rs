//! The interpreter: runs a parsed program the way the selected control would and emits the
//! canonical motion stream through a [`Sink`], each event tagged with its source block.

mod canon;
mod comp;
mod corners;
mod cycles;
mod diagnostics;
mod exec;
mod flow;
mod machine;
mod macros;
mod position;
mod setup;
mod state;
mod states;

pub use canon::{Arc, Axis, Canon, CanonRecorder, PlaneArc, Source, plane_length, plane_sweep};
pub use machine::{Interpreter, Piece, Status, run};
pub use setup::{CornerMode, Machine, Register, Setup, SetupError, ShiftDirection, Units};
pub use states::{BlockState, States, StatesRun};

/// Receives the canonical events of a running program, in execution order.
pub trait Sink {
    /// One event caused by the block at `source`.
    fn emit(&mut self, source: Source, event: &Canon);

    /// A straight move to (`x`, `y`, `z`), rapid when `rapid`: emitting the event, with the numbers
    /// in registers for sinks that take moves this way.
    fn straight(&mut self, source: Source, rapid: bool, x: f64, y: f64, z: f64, feed: f64) {
        self.emit(source, &Canon::line(rapid, glam::DVec3::new(x, y, z), feed));
    }

    /// Whether the sink holds all it may: the run then stops before the next block with a
    /// diagnostic, and a canned cycle makes no more holes. `false` for a sink without a limit.
    fn full(&self) -> bool {
        false
    }

    /// The program zero (machine frame) the moves just emitted were programmed from, told once per
    /// change for the backplot's origin marks; not part of the canonical stream.
    fn origin(&mut self, _at: glam::DVec3) {}

    /// The programmed motion of a block under cutter radius compensation, before its compensated
    /// events, so a backplot can draw the contour beside the tool centre's path.
    fn programmed(&mut self, _source: Source, _event: &Canon) {}

    /// A G22 stroke limit switched on (`Some`, as the block at `source` set it) or off by G23
    /// (`None`), so a backplot can draw the zone. Not part of the canonical stream.
    fn stroke_zone(&mut self, _source: Source, _zone: Option<&StrokeZone>) {}
}

/// A programmable stroke limit (G22) in machine coordinates (mm): the box the tool must stay inside
/// (LNC) or out of (Syntec); an axis without a limit spans all numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeZone {
    /// Lower limit per axis (negative infinity where the axis has none).
    pub min: glam::DVec3,
    /// Upper limit per axis (infinity where the axis has none).
    pub max: glam::DVec3,
    /// Whether the tool must stay out of the box rather than inside it.
    pub inside_forbidden: bool,
}
