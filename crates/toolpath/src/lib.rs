//! A compact, struct-of-arrays record of a program's motions for drawing, picking, statistics
//! and playback.
//!
//! Segment `i` runs from `end(i - 1)` (or the start point for `i == 0`) to `end(i)`. Arcs are kept
//! as tessellated chords that share the arc's source line, so the renderer only sees lines.
//!
//! # Time model
//!
//! Every segment gets the time, in seconds from the program start, at which it ends
//! ([`Timeline`]). Each move follows a trapezoidal velocity profile: it accelerates at the
//! machine's acceleration from its entry speed towards its cruise speed (the programmed feed,
//! or the rapid rate limited per axis) and decelerates to its exit speed. The speeds at the
//! joins between moves are planned over the whole path (a forward pass from the start and a
//! backward pass from the end, the speed at each join being the lower of the two), so a run
//! of short moves speeds up and slows down across blocks the way a control with look-ahead
//! does. Joins are kept simple:
//!
//! - the tool is at rest at the program start, at the end of the last move, and around every
//!   dwell, tool change, spindle or coolant command, program stop and program end;
//! - a rapid starts and ends at rest (the in-position check at the end of a G00 block);
//! - between two cutting moves the tool keeps the lower of their cruise speeds when the
//!   direction changes by at most [`CORNER_DEGREES`] (arcs use their tangent at the join) and
//!   stops at any sharper corner;
//! - the chords of one arc join smoothly, and an arc's speed is capped at `sqrt(a·r)` so that
//!   its centripetal acceleration stays within the machine's acceleration `a`.
//!
//! The backward pass sees at least [`LOOKAHEAD_SEGMENTS`] segments ahead of a join (up to the
//! next stop), like a control's look-ahead buffer, which keeps recording linear in the number
//! of segments.

mod arc;
mod kinematics;
mod planner;
mod record;
mod timeline;

pub use arc::{CHORD_TOLERANCE_MM, tessellate_arc};
pub use kinematics::Kinematics;
pub use planner::{CORNER_DEGREES, LOOKAHEAD_SEGMENTS};
pub use record::{Bounds, CycleMove, Hole, SegmentKind, Toolpath, box_edges};
pub use timeline::{Dwell, Timeline};

/// The next number of a xorshift sequence (reproducible test data without a crate).
#[cfg(test)]
fn xorshift(seed: &mut u64) -> u64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    *seed
}
