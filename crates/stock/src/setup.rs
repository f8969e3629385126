//! A setup's stock and tools read and checked, and a toolpath cut out of them with what the cut
//! finds as diagnostics at their lines: the one place the command line and the editor share.

use std::collections::BTreeMap;

use glam::DVec3;
use serde::de::DeserializeOwned;
use swarf_interp::Setup;
use swarf_syntax::{Diagnostic, LineIndex, Span};
use swarf_toolpath::{SegmentKind, Toolpath};

use crate::{Finding, Simulation, Stock, StockError, Tool};

/// The stock and tools a setup describes (`[stock]`, `[tools.N]`), checked, with the diameters
/// of its offset registers for the tools it does not describe.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StockSetup {
    /// The setup's `[stock]`; `None`: a box around the feed moves is assumed.
    pub stock: Option<Stock>,
    /// The setup's `[tools.N]` by number.
    pub tools: BTreeMap<u32, Tool>,
    /// Twice the radius of each offset register that has one.
    register_diameters: BTreeMap<u32, f64>,
}

impl StockSetup {
    /// Reads the setup's `[stock]` and `[tools.N]` tables; refuses a key, shape or value out of
    /// place, naming it.
    pub fn from_setup(setup: &Setup) -> Result<Self, StockError> {
        let stock = (setup.stock.as_ref())
            .map(|table| from_table::<Stock>("stock", table).and_then(|s| s.grid().map(|_| s)))
            .transpose()?;
        let mut tools = BTreeMap::new();
        for (&number, table) in &setup.tools {
            let tool: Tool = from_table(&format!("tools.{number}"), table)?;
            tool.validate(number)?;
            tools.insert(number, tool);
        }
        let register_diameters = setup
            .registers
            .iter()
            .map(|(&n, r)| (n, r.radius * 2.0))
            .filter(|&(_, d)| d > 0.0)
            .collect();
        Ok(StockSetup {
            stock,
            tools,
            register_diameters,
        })
    }

    /// The tool `number` cuts with, and why when the setup has no `[tools.N]` for it.
    fn tool(&self, number: u32) -> (Tool, Option<String>) {
        if let Some(tool) = self.tools.get(&number) {
            return (*tool, None);
        }
        let missing = format!("T{number} has no `[tools.{number}]` in the setup");
        let from_register = self.register_diameters.get(&number).map(|&diameter| Tool {
            diameter,
            ..Tool::default()
        });
        let (tool, how) = match from_register.filter(|tool| tool.validate(0).is_ok()) {
            Some(tool) => (tool, format!(", twice register {number}'s radius")),
            None => (Tool::default(), String::new()),
        };
        let note = format!(
            "{missing}: cut as a {} mm flat end mill{how}",
            tool.diameter
        );
        (tool, Some(note))
    }
}

/// `table` read as `T`, a mistake in it named by the table's `key`.
fn from_table<T: DeserializeOwned>(key: &str, table: &toml::Table) -> Result<T, StockError> {
    let value = toml::Value::Table(table.clone());
    value
        .try_into()
        .map_err(|e: toml::de::Error| StockError::Table {
            key: key.to_string(),
            message: e.message().to_string(),
        })
}

/// A toolpath being cut out of a setup's stock a bounded number of segments a step, with what
/// was assumed and what the cut finds as diagnostics.
#[derive(Debug, Clone)]
pub struct StockRun {
    /// The cut: stepped through the toolpath given to [`StockRun::new`], with the stock as cut
    /// so far and what it found.
    pub simulation: Simulation,
    /// What was assumed: the 1-based line each note belongs at, its code and message.
    notes: Vec<(u32, &'static str, String)>,
}

impl StockRun {
    /// The cut of `toolpath` out of `setup`'s stock, or out of a box around the feed moves
    /// below the highest feed's start when the setup has none; `None` when there is no stock:
    /// no `[stock]` and no feed move (or one too far out to assume a stock around).
    pub fn new(toolpath: &Toolpath, setup: &StockSetup) -> Option<Self> {
        let mut notes = Vec::new();
        let mut tools = BTreeMap::new();
        let segment_tools = toolpath.segment_tools();
        for (i, &number) in segment_tools.iter().enumerate() {
            if tools.contains_key(&number) {
                continue;
            }
            let (tool, note) = setup.tool(number);
            tools.insert(number, tool);
            if let Some(note) = note {
                notes.push((line_of(toolpath, i), "N-TOOL-ASSUMED", note));
            }
        }
        let stock = if let Some(stock) = setup.stock {
            stock
        } else {
            let widest = tools.values().map(|t| t.diameter).fold(0.0, f64::max);
            let (stock, line) = assumed_stock(toolpath, widest / 2.0)?;
            let [x0, y0, z0] = stock.min;
            let [x1, y1, z1] = stock.max;
            notes.push((
                line,
                "N-STOCK-ASSUMED",
                format!(
                    "no `[stock]` in the setup: the stock is taken as X{x0:.3}..{x1:.3} \
                     Y{y0:.3}..{y1:.3} Z{z0:.3}..{z1:.3} mm, around the feed moves and below the \
                     highest feed's start (this line)"
                ),
            ));
            stock
        };
        let simulation = Simulation::new(&stock, tools).ok()?;
        Some(StockRun { simulation, notes })
    }

    /// The notes on what was assumed and the findings so far as diagnostics, each at
    /// `line_span` of its 1-based line (the toolpath's line numbers; 0 for none).
    pub fn diagnostics(&self, line_span: impl Fn(u32) -> Span) -> Vec<Diagnostic> {
        let span = |line: u32| match line {
            0 => Span::default(),
            _ => line_span(line),
        };
        let notes = self
            .notes
            .iter()
            .map(|(line, code, message)| Diagnostic::note(span(*line), code, message.clone()));
        let findings = (self.simulation.findings().iter()).map(|finding| match *finding {
            Finding::RapidIntoStock {
                line,
                cell_xy: [x, y],
                depth,
                ..
            } => Diagnostic::warning(
                span(line),
                "W-RAPID-INTO-STOCK",
                format!(
                    "a rapid move into the stock: the tool meets material at X{x:.3} Y{y:.3}, \
                     {depth:.3} mm below its top"
                ),
            ),
            Finding::ShankCut {
                line,
                cell_xy: [x, y],
                depth,
                flute_length,
                ..
            } => Diagnostic::warning(
                span(line),
                "W-SHANK-CUT",
                format!(
                    "the cut is {depth:.3} mm deep at X{x:.3} Y{y:.3}, past the tool's \
                     {flute_length:.3} mm flutes: the shank rubs"
                ),
            ),
        });
        notes.chain(findings).collect()
    }
}

/// The 1-based line of segment `i`.
pub(crate) fn line_of(toolpath: &Toolpath, i: usize) -> u32 {
    toolpath.lines().get(i).copied().unwrap_or(0)
}

/// The box around the feed moves, `margin` wider but topped at the highest feed's start, with
/// that feed's line; `None` without feed moves or when the box is out of the stock's ranges.
fn assumed_stock(toolpath: &Toolpath, margin: f64) -> Option<(Stock, u32)> {
    let mut min = DVec3::INFINITY;
    let mut max = DVec3::NEG_INFINITY;
    let mut top: Option<(f64, usize)> = None;
    for (i, (&end, &kind)) in toolpath.ends().iter().zip(toolpath.kinds()).enumerate() {
        if kind == SegmentKind::Rapid {
            continue;
        }
        let start = toolpath.segment_start(i);
        min = min.min(start).min(end);
        max = max.max(start).max(end);
        if top.is_none_or(|(z, _)| start.z > z) {
            top = Some((start.z, i));
        }
    }
    let (top, segment) = top?;
    let margin = margin.max(1.0);
    let stock = Stock {
        min: (min - DVec3::splat(margin)).to_array(),
        max: [max.x + margin, max.y + margin, top],
        cell_mm: None,
    };
    stock.grid().ok()?;
    Some((stock, line_of(toolpath, segment)))
}

/// The span of 1-based `line` in a text whose lines are `lines`, its line end included.
pub fn line_span(lines: &LineIndex, line: u32) -> Span {
    let line = (line as usize).saturating_sub(1);
    Span {
        start: lines.line_start(line),
        end: lines.line_start(line + 1),
    }
}
