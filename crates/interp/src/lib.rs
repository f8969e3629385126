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
pub mod macros;
mod position;
mod setup;
mod state;
mod states;

pub use canon::{Arc, Axis, Canon, CanonRecorder, PlaneArc, Source, plane_length, plane_sweep};
pub use machine::{Interpreter, Piece, Status, run};
pub use setup::{CornerMode, Machine, Register, Setup, SetupError, ShiftDirection, Units};
pub use states::{BlockState, States, StatesRun, run_with_states};

/// Receives the canonical events of a running program, in execution order.
pub trait Sink {
    /// One event caused by the block at `source`.
    fn emit(&mut self, source: Source, event: &Canon);

    /// A straight move to (`x`, `y`, `z`): a rapid ([`Canon::Rapid`]) when `rapid`, else a
    /// feed ([`Canon::Feed`]) at `feed_mm_per_min`. The same as emitting the event, which is
    /// what it does unless a sink takes moves this way: the numbers then come in registers, not
    /// in an event written just before the call and read back at its start (a read that
    /// spans two of those writes waits for them to reach the cache, on every move).
    fn straight(
        &mut self,
        source: Source,
        rapid: bool,
        x: f64,
        y: f64,
        z: f64,
        feed_mm_per_min: f64,
    ) {
        let to = glam::DVec3::new(x, y, z);
        self.emit(source, &Canon::line(rapid, to, feed_mm_per_min));
    }

    /// Whether the sink holds all it may (a recorder whose memory has a limit): the run then
    /// stops before the next block with a diagnostic, and a block that makes many moves (a
    /// canned cycle's holes and pecks) makes no more. `false` for a sink without a limit.
    fn full(&self) -> bool {
        false
    }

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

    /// A G22 stroke limit switched on (`Some`, as the block at `source` set it) or off by G23
    /// (`None`), so a backplot can draw the zone. Not part of the canonical stream.
    fn stroke_zone(&mut self, source: Source, zone: Option<&StrokeZone>) {
        let _ = (source, zone);
    }
}

/// A programmable stroke limit (G22) in machine coordinates (mm): the box the tool must stay
/// inside (LNC's soft limits) or out of (Syntec's protected zone). An axis without a limit
/// spans from negative to positive infinity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeZone {
    /// Lower limit per axis (negative infinity where the axis has none).
    pub min: glam::DVec3,
    /// Upper limit per axis (infinity where the axis has none).
    pub max: glam::DVec3,
    /// Whether the tool must stay out of the box rather than inside it.
    pub inside_forbidden: bool,
}
