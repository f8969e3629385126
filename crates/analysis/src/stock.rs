//! The stock cut by a finished analysis' toolpath, in bounded pieces up to the segment the view
//! asks for. A later segment continues the cut; an earlier one, or a new analysis, restarts it.

use std::sync::Arc;

use glam::DVec3;
use swarf_stock::{Finding, StockRun, StockSetup};
use swarf_toolpath::Toolpath;

use crate::run::{Kept, Problem, locate_own};
use crate::service::{Held, with_kept};

/// Cells of tool travel per piece (a segment counts one more): a few milliseconds, so that
/// a newer request replaces the cut at once.
const PIECE_CELLS: f64 = 4096.0;

/// The cut stock's heights, as the view draws them.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StockField {
    /// The height of each cell (machine Z, mm), row by row from the lowest Y: cell `(i, j)` at
    /// index `j · nx + i`, over the cell's centre.
    #[serde(skip)]
    pub heights: Vec<f32>,
    /// Cells along X and along Y (`nx`, `ny`).
    pub size: (usize, usize),
    /// Side of one square cell, mm.
    pub cell_mm: f64,
    /// The grid's lowest corner in X and Y and the stock's bottom in Z, machine mm.
    pub min: DVec3,
    /// The uncut stock's top, machine Z.
    pub top: f64,
}

impl StockField {
    /// The height of the cell under machine (`x`, `y`), if it lies on the grid.
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        let i = (x - self.min.x) / self.cell_mm;
        let j = (y - self.min.y) / self.cell_mm;
        let (nx, ny) = self.size;
        if !(0.0..nx as f64).contains(&i) || !(0.0..ny as f64).contains(&j) {
            return None;
        }
        (self.heights.get(j as usize * nx + i as usize)).map(|&h| f64::from(h))
    }
}

/// The stock as cut for the analysis of `generation`: the answer to
/// [`crate::Request::Stock`], or its progress while `done` is short of `upto`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StockCut {
    /// The analysis whose toolpath is cut.
    pub generation: u64,
    /// Segments asked to be cut (at most the toolpath's).
    pub upto: usize,
    /// Segments cut so far.
    pub done: usize,
    /// Whether `upto` is the whole toolpath.
    pub whole: bool,
    /// The heights once `done` reaches `upto`; `None` while cutting or without stock.
    pub field: Option<StockField>,
    /// Each rapid into the stock found so far: its segment and the machine XY where it meets
    /// material.
    pub rapids: Vec<(usize, [f64; 2])>,
    /// Once the whole toolpath is cut: what was assumed and found, located in the program's
    /// own text.
    pub problems: Vec<Problem>,
    /// Why there is no stock to cut (a setup table that does not read, no feed move).
    pub error: Option<String>,
}

impl StockCut {
    /// Whether the cut asked for is finished (or there is none to make).
    pub fn finished(&self) -> bool {
        self.done >= self.upto
    }
}

/// A cut under way, or finished and kept to be continued.
#[derive(Debug)]
pub(crate) struct StockJob {
    generation: u64,
    toolpath: Arc<Toolpath>,
    run: StockRun,
    done: usize,
    upto: usize,
    /// Whether the asker is still owed the answer.
    pub(crate) due: bool,
}

impl StockJob {
    /// A cut of the held analysis `generation` up to segment `upto`, or why there is none.
    pub(crate) fn start(held: &Held, generation: u64, upto: usize) -> Result<Self, String> {
        let kept = |k: &Kept| (StockSetup::from_setup(&k.setup), Arc::clone(&k.toolpath));
        let (setup, toolpath) =
            with_kept(held, generation, kept).ok_or("the analysis is no longer held")?;
        let setup = setup.map_err(|e| format!("the setup: {e}"))?;
        let run = StockRun::new(&toolpath, &setup)
            .ok_or("no [stock] in the setup and no feed move to assume one around")?;
        Ok(StockJob {
            generation,
            upto: upto.min(toolpath.len()),
            toolpath,
            run,
            done: 0,
            due: true,
        })
    }

    /// Takes a new goal when it continues this cut (same analysis, not behind it); false when
    /// the cut must start again.
    pub(crate) fn extend(&mut self, generation: u64, upto: usize) -> bool {
        let upto = upto.min(self.toolpath.len());
        if generation != self.generation || upto < self.done {
            return false;
        }
        self.upto = upto;
        self.due = true;
        true
    }

    /// Cuts one piece: the progress, or the finished cut (then nothing is due).
    pub(crate) fn step(&mut self, held: &Held) -> StockCut {
        let cell = self.run.simulation.field().cell_mm();
        let mut end = self.done;
        let mut cost = 0.0;
        while end < self.upto && cost < PIECE_CELLS {
            let from = self.toolpath.segment_start(end).truncate();
            let to = self.toolpath.ends().get(end).map_or(from, |p| p.truncate());
            cost += 1.0 + from.distance(to) / cell;
            end += 1;
        }
        self.run.simulation.step(&self.toolpath, end - self.done);
        self.done = end;
        let finished = self.done >= self.upto;
        self.due = !finished;
        let whole = self.upto >= self.toolpath.len();
        let field = finished.then(|| {
            let f = self.run.simulation.field();
            StockField {
                heights: f.heights().to_vec(),
                size: f.size(),
                cell_mm: f.cell_mm(),
                min: DVec3::from_array(f.stock().min),
                top: f.stock().max[2],
            }
        });
        let rapid = |f: &Finding| match *f {
            Finding::RapidIntoStock {
                segment, cell_xy, ..
            } => Some((segment, cell_xy)),
            Finding::ShankCut { .. } => None,
        };
        let rapids = (self.run.simulation.findings().iter())
            .filter_map(rapid)
            .collect();
        let located = |kept: &Kept| {
            let span = |line| swarf_stock::line_span(&kept.program.lines, line);
            locate_own(kept, self.run.diagnostics(span))
        };
        let problems = (finished && whole)
            .then(|| with_kept(held, self.generation, located))
            .flatten()
            .unwrap_or_default();
        StockCut {
            generation: self.generation,
            upto: self.upto,
            done: self.done,
            whole,
            field,
            rapids,
            problems,
            error: None,
        }
    }
}
