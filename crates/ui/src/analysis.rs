//! What the editor shows of a program's analysis. The analysis itself ([`swarf_analysis`]) runs
//! beside the UI, on a thread or in a web worker; the UI only receives its results.

use std::sync::Arc;

use swarf_analysis::{Plot, Results, StockCut};
use swarf_interp::Setup;
use swarf_syntax::{LinkedFile, Severity};
use swarf_toolpath::Toolpath;

pub use swarf_analysis::{DialectHint, LinkedProblem, Problem, ProgramText, Stats};

use crate::backplot::{Scene, SourceText};

/// A finished analysis as the editor shows it: the problems, the backplot's scene, the summary
/// numbers, where the linked files' lines lie and the dialect the program reads better in.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// Every diagnostic in the program's own text, sorted by position.
    pub problems: Vec<Problem>,
    /// Diagnostics in the other open files its calls reached, by file then position.
    pub elsewhere: Vec<LinkedProblem>,
    /// Geometry for the backplot.
    pub scene: Scene,
    /// Summary numbers.
    pub stats: Stats,
    /// The other open files linked into the program, in the order their lines follow its own.
    pub linked: Vec<LinkedFile>,
    /// Another dialect the program's codes read better in.
    pub hint: Option<DialectHint>,
}

impl Analysis {
    /// The analysis shown of `results`, those of `text`.
    pub fn of(results: Results, text: &ProgramText) -> Self {
        let mut scene = scene(results.plot, results.generation);
        scene.source = Some(Arc::new(SourceText::new(text.clone())));
        Analysis {
            problems: results.problems,
            elsewhere: results.elsewhere,
            scene,
            stats: results.stats,
            linked: results.linked,
            hint: results.hint,
        }
    }

    /// Takes a cut of the stock for the scene shown (another analysis' is dropped): its progress,
    /// or the cut, whose problems replace the stock's when it covers the whole toolpath.
    pub fn take_stock(&mut self, mut cut: StockCut) {
        if cut.generation != self.scene.generation {
            return;
        }
        if !cut.finished() {
            self.scene.stock_progress = Some((cut.done, cut.upto));
            return;
        }
        self.scene.stock_progress = None;
        if cut.whole && cut.error.is_none() {
            self.problems.retain(|p| !STOCK_CODES.contains(&p.code));
            self.problems.append(&mut cut.problems);
            self.problems.sort_by_key(|p| (p.chars.start, p.chars.end));
        }
        self.scene.stock = Some(Arc::new(cut));
    }

    /// Number of problems of `severity`, in the program's own text and in the files it called.
    pub fn count(&self, severity: Severity) -> usize {
        let elsewhere = self.elsewhere.iter().map(|l| &l.problem);
        let all = self.problems.iter().chain(elsewhere);
        all.filter(|p| p.severity == severity).count()
    }

    /// The name of the other open file a 0-based block `line` of the program lies in (`None`:
    /// the program's own text), with the line's 1-based number in that file.
    pub fn linked_line(&self, line: u32) -> Option<(&str, u32)> {
        let file = self.linked.iter().rfind(|l| line >= l.first_line)?;
        Some((file.name.as_str(), line - file.first_line + 1))
    }
}

/// The codes of what cutting the stock assumes and finds.
const STOCK_CODES: [&str; 4] = [
    "N-STOCK-ASSUMED",
    "N-TOOL-ASSUMED",
    "W-RAPID-INTO-STOCK",
    "W-SHANK-CUT",
];

/// The backplot's scene of `path` run on `setup`'s machine (see [`Plot::of`]).
pub fn scene_of(path: &Toolpath, setup: &Setup, generation: u64) -> Scene {
    scene(Plot::of(path, setup), generation)
}

/// The backplot's scene of a plot (its arrays moved, not copied).
fn scene(plot: Plot, generation: u64) -> Scene {
    let drawing = plot.drawing;
    Scene {
        generation,
        lines: Arc::new(plot.lines),
        block_count: Some(plot.block_count),
        feeds: Arc::new(plot.feeds),
        timeline: Arc::new(plot.timeline),
        tools: Arc::new(plot.tools),
        tool_radii: Arc::new(plot.tool_radii),
        points: drawing.points,
        marks: Arc::new(drawing.marks),
        bounds: drawing.bounds,
        zero: drawing.zero,
        origin: drawing.origin,
        lod: plot.lod,
        ..Scene::default()
    }
}
