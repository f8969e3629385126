//! Running a toolpath through the stock a bounded number of segments at a time, with what it
//! finds on the way.

use std::collections::BTreeMap;
use std::mem::discriminant;

use glam::DVec3;
use swarf_toolpath::{SegmentKind, Toolpath};

use crate::field::{Check, Hit};
use crate::{HeightField, Stock, StockError, Tool};

/// The check a segment of `kind` gets with `tool`: rapids for material, feeds (when the tool's
/// flute length is known) for shank cuts.
fn check_of(kind: SegmentKind, tool: &Tool) -> Option<Check> {
    match kind {
        SegmentKind::Rapid => Some(Check::Rapid),
        SegmentKind::Feed | SegmentKind::Arc => {
            tool.flute_length.map(|flutes| Check::Shank(flutes as f32))
        }
    }
}

/// A problem found while cutting, in the order the segments run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Finding {
    /// A rapid whose tool meets material (it is still cut away).
    RapidIntoStock {
        /// The rapid's segment in the toolpath.
        segment: usize,
        /// Its 1-based source line.
        line: u32,
        /// Machine XY of the first cell the tool meets along the move.
        cell_xy: [f64; 2],
        /// How far the tool's end goes below the material's top there, mm.
        depth: f64,
    },
    /// A cutting move over material that stands higher above the tool's tip than its flutes
    /// reach, so the shank rubs.
    ShankCut {
        /// The move's segment in the toolpath.
        segment: usize,
        /// Its 1-based source line.
        line: u32,
        /// Machine XY of the cell where material stands highest above the tip.
        cell_xy: [f64; 2],
        /// How far the tip goes below the material's top there, mm.
        depth: f64,
        /// The tool's flute length, mm.
        flute_length: f64,
    },
}

impl Finding {
    /// The 1-based source line of its segment.
    pub fn line(&self) -> u32 {
        match *self {
            Finding::RapidIntoStock { line, .. } | Finding::ShankCut { line, .. } => line,
        }
    }
}

/// A toolpath being cut out of the stock a few milliseconds at a time: rapids are checked for
/// material, feeds (with a flute length) for shank cuts, and every move removes what it sweeps.
#[derive(Debug, Clone)]
pub struct Simulation {
    field: HeightField,
    tools: BTreeMap<u32, Tool>,
    /// The tool of each segment, taken from the toolpath at the first step.
    segment_tools: Vec<u32>,
    next: usize,
    /// Where the last cut ended and its tool's number.
    last: Option<(DVec3, u32)>,
    findings: Vec<Finding>,
}

impl Simulation {
    /// A simulation of uncut `stock` with `tools` by number; a number missing from the map
    /// cuts as [`Tool::default`]. Refuses a stock or tool outside its ranges.
    pub fn new(stock: &Stock, tools: BTreeMap<u32, Tool>) -> Result<Self, StockError> {
        for (number, tool) in &tools {
            tool.validate(*number)?;
        }
        Ok(Simulation {
            field: HeightField::new(stock)?,
            tools,
            segment_tools: Vec::new(),
            next: 0,
            last: None,
            findings: Vec::new(),
        })
    }

    /// Cuts at most `max_segments` more segments of `toolpath` (the same one at every step);
    /// true once every segment is cut.
    pub fn step(&mut self, toolpath: &Toolpath, max_segments: usize) -> bool {
        if self.segment_tools.len() != toolpath.len() {
            self.segment_tools = toolpath.segment_tools();
        }
        let end = self.next.saturating_add(max_segments).min(toolpath.len());
        // The next segment's cut, planned with this one's so that each may leave the other
        // the cells about their joint that it cuts anyway.
        let mut planned = None;
        for i in self.next..end {
            let number = self.segment_tools.get(i).copied().unwrap_or(0);
            let tool = self.tools.get(&number).copied().unwrap_or_default();
            let (Some(&to), Some(&kind)) = (toolpath.ends().get(i), toolpath.kinds().get(i)) else {
                break;
            };
            let from = toolpath.segment_start(i);
            let check = check_of(kind, &tool);
            let continues = self.last == Some((from, number));
            self.last = Some((to, number));
            let cut = planned
                .take()
                .or_else(|| (self.field).plan(from, to, &tool, continues, check.is_some()));
            let Some(mut cut) = cut else {
                continue;
            };
            // Within the step only, so that what it leaves is cut before the step ends.
            let next = (i + 1 < end && self.segment_tools.get(i + 1) == Some(&number))
                .then(|| toolpath.ends().get(i + 1).zip(toolpath.kinds().get(i + 1)))
                .flatten();
            if let Some((&next_to, &next_kind)) = next {
                let checked = check_of(next_kind, &tool).is_some();
                planned = self.field.plan(to, next_to, &tool, true, checked);
                if let Some(next) = &mut planned {
                    cut.join(next);
                }
            }
            let hit = self.field.apply(&cut, check);
            if let (Some(hit), Some(check)) = (hit, check) {
                self.report(i, crate::setup::line_of(toolpath, i), &tool, check, hit);
            }
        }
        self.next = self.next.max(end);
        self.next >= toolpath.len()
    }

    /// Records a hit as a finding, unless the last finding is the same problem on the same
    /// line (the chords of one arc, the holes of one cycle block).
    fn report(&mut self, segment: usize, line: u32, tool: &Tool, check: Check, hit: Hit) {
        let (nx, _) = self.field.size();
        let cell_xy = self.field.cell_center(hit.index % nx, hit.index / nx);
        let depth = f64::from(hit.depth);
        let finding = match check {
            Check::Rapid => Finding::RapidIntoStock {
                segment,
                line,
                cell_xy,
                depth,
            },
            Check::Shank(_) => Finding::ShankCut {
                segment,
                line,
                cell_xy,
                depth,
                flute_length: tool.flute_length.unwrap_or(0.0),
            },
        };
        let same =
            |last: &Finding| discriminant(last) == discriminant(&finding) && last.line() == line;
        if !self.findings.last().is_some_and(same) {
            self.findings.push(finding);
        }
    }

    /// The stock as cut so far.
    pub fn field(&self) -> &HeightField {
        &self.field
    }

    /// What was found so far, in segment order.
    pub fn findings(&self) -> &[Finding] {
        &self.findings
    }
}
