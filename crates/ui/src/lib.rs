//! egui widgets for Swarf: the G-code editor, the problems list and the 3D backplot, and the
//! workbench that wires them to the parse → interpret → toolpath pipeline.

pub mod analysis;
pub mod backplot;
pub mod editor;
mod workbench;

pub use analysis::{Analysis, Problem, Stats};
pub use workbench::{EXAMPLE_PROGRAM, Workbench, format_duration};
