//! The editor's analysis of a program: parse (a rope in place), link the calls into the other
//! open files, run, then locate the problems, prepare what the backplot draws and look for a
//! dialect that reads the program better, and on request cuts the stock with the toolpath. It
//! runs in pieces beside the UI, on a thread or in a web worker, as a [`Service`] the UI sends
//! requests to and takes replies from; the program, its machine states and its toolpath stay on
//! that side, which answers questions about them.

mod hint;
mod run;
mod service;
mod stock;
mod text;
pub mod wire;

pub use hint::DialectHint;
pub use run::{
    Job, Kept, LinkedProblem, Lod, LodLevel, OpenFile, PARSE_LINES_PER_BLOCK, PendingAnalysis,
    Plot, Problem, Progress, Results, Stats, analyse,
};
#[cfg(not(target_arch = "wasm32"))]
pub use service::Thread;
pub use service::{Analyst, Inline, PIECE, Reply, Request, Service};
pub use stock::{StockCut, StockField};
pub use text::{ProgramText, RopeLines};
