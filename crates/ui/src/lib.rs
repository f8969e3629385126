//! egui widgets for Swarf: the G-code editor, the problems list and the 3D backplot, and the
//! workbench that wires them to the parse → interpret → toolpath pipeline.

pub mod analysis;
pub mod backplot;
pub mod buffer;
pub mod commands;
mod completion;
pub mod editor;
pub mod examples;
pub mod history;
pub mod i18n;
pub mod rows;
mod settings;
mod workbench;

pub use analysis::{Analysis, LinkedProblem, Problem, Stats};
pub use workbench::{
    Document, EXAMPLE_PROGRAM, HostRequest, TabRecord, Workbench, format_duration, reply_frame,
};
