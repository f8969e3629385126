//! The interpreter: runs a parsed program the way the selected control would and emits the
//! canonical motion stream through a [`Sink`], each event tagged with its source block.

mod canon;
mod comp;
mod corners;
mod cycles;
mod exec;
mod flow;
mod machine;
pub mod macros;
mod position;
mod setup;
mod state;
mod states;

pub use canon::{Axis, Canon, CanonRecorder, Source};
pub use machine::{Interpreter, Limits, Status, run};
pub use setup::{CornerMode, Machine, Register, Setup, SetupError, ShiftDirection, Units};
pub use states::{BlockState, States, StatesRun, run_with_states};

/// Receives the canonical events of a running program, in execution order.
pub trait Sink {
    /// One event caused by the block at `source`.
    fn emit(&mut self, source: Source, event: &Canon);

    /// The program zero (work offset with its G52/G92 shifts, machine frame) that the moves
    /// just emitted were programmed from; told once per change, for the backplot's origin
    /// marks. Not part of the canonical stream: sinks that do not draw may ignore it.
    fn origin(&mut self, _at: glam::DVec3) {}

    /// The programmed motion of a block run under cutter radius compensation, before its
    /// compensated events are emitted: the contour the part program describes, so a backplot
    /// can draw it next to the tool centre's path. Ignored unless a sink wants it.
    fn programmed(&mut self, source: Source, event: &Canon) {
        let _ = (source, event);
    }
}
