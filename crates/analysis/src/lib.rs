//! The editor's analysis of a program: parse, link the calls, run, locate the problems, prepare
//! the backplot, suggest a dialect and cut the stock. It runs in pieces beside the UI (a thread or
//! web worker) as a [`Service`] that keeps the results and answers questions about them.

mod hint;
mod run;
mod service;
mod stock;
mod text;
pub mod wire;

pub use hint::DialectHint;
pub use run::{
    Job, Kept, LinkedProblem, Lod, LodLevel, OpenFile, PARSE_LINES_PER_BLOCK, PendingAnalysis,
    Plot, Problem, Progress, Results, Stats, analyse, block_starts,
};
#[cfg(not(target_arch = "wasm32"))]
pub use service::Thread;
pub use service::{Analyst, Inline, PIECE, Reply, Request, Service};
pub use stock::{StockCut, StockField};
pub use text::{ProgramText, RopeLines};
