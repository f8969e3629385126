//! One analysis: parse, link the calls into other open files, run, then locate the problems and
//! prepare what the backplot draws, in pieces of bounded work.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::DVec3;
use swarf_interp::{BlockState, Piece, Setup, States, StatesRun, Status};
use swarf_render::Drawing;
use swarf_syntax::{
    Diagnostic, DiagnosticDef, Dialect, LineIndex, LinkedFile, LinkedSource, ParseRun, Program,
    ReadPoint, Severity,
};
use swarf_toolpath::{Timeline, Toolpath};

use crate::hint::{DialectHint, Sensitive, suggest};
use crate::text::{ProgramText, RopeLines, Text};

/// What to analyse: a program's text, how to read and run it, and the files its calls may reach.
#[derive(Debug, Clone)]
pub struct Job {
    /// Tags the results (a number bumped by every change of the text, dialect or setup).
    pub generation: u64,
    /// The program's text.
    pub text: ProgramText,
    /// The dialect it is read in.
    pub dialect: Dialect,
    /// The machine it runs on.
    pub setup: Setup,
    /// The other open files whose programs its calls may reach; `None` when calls are not
    /// looked for among open files.
    pub others: Option<Vec<OpenFile>>,
    /// The level of detail the results' path is simplified at too (the view's, when it keeps
    /// its zoom); `None`: not simplified (the UI asks with [`crate::Request::Lod`]).
    pub lod: Option<LodLevel>,
}

/// Another open file, whose program a job's calls may reach.
#[derive(Debug, Clone)]
pub struct OpenFile {
    /// Its name, as the CLI looks for a called program's file beside the main one.
    pub name: String,
    /// Changes with every change of its text, so that the worker is sent only changed texts.
    pub revision: u64,
    /// Its text.
    pub text: ProgramText,
}

/// A level of detail of the drawn path: log2 of the tolerance in world units, `None` for every
/// point (see [`swarf_render::simplify_at`]).
pub type LodLevel = Option<i32>;

/// The drawn path's points kept at a level of detail, simplified beside the UI's frames.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Lod {
    /// The level.
    pub level: LodLevel,
    /// The indices of the points kept, ascending (sent beside, see [`crate::wire`]).
    #[serde(skip)]
    pub kept: Arc<Vec<u32>>,
}

impl Lod {
    /// The points of `points` kept at `level`.
    pub fn of(points: &[swarf_render::PathPoint], level: LodLevel) -> Self {
        Lod {
            level,
            kept: Arc::new(swarf_render::simplify_at(points, level)),
        }
    }
}

/// One diagnostic, located for display.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Problem {
    /// 1-based line.
    pub line: u32,
    /// 1-based column in characters.
    pub col: u32,
    /// How bad it is.
    pub severity: Severity,
    /// Stable code such as `E-SYNTAX-CHAR`.
    #[serde(deserialize_with = "registered")]
    pub code: Code,
    /// The message.
    pub message: String,
    /// Character range in the text, for underlining and jumping.
    pub chars: std::ops::Range<usize>,
}

/// A registered diagnostic code: named apart so that serde reads it through [`registered`]
/// instead of borrowing it from the message.
pub type Code = &'static str;

/// A diagnostic code read back as the registered one (`?` for a code not registered).
fn registered<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Code, D::Error> {
    let code = <String as serde::Deserialize>::deserialize(d)?;
    Ok(DiagnosticDef::lookup(&code).map_or("?", |def| def.code))
}

/// A diagnostic in another open file that the program called (a subprogram's error), located
/// in that file.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LinkedProblem {
    /// The name of the file (tab) it is in.
    pub file: String,
    /// The diagnostic, located in that file's text.
    pub problem: Problem,
}

/// Summary numbers of an analysed program.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    /// Blocks parsed.
    pub blocks: usize,
    /// Motion segments recorded.
    pub motions: usize,
    /// Bounds of the path in millimetres (machine frame).
    pub bounds: Option<(DVec3, DVec3)>,
    /// Estimated run time in seconds.
    pub estimated_secs: f64,
}

/// What the backplot shows of a toolpath: its [`Drawing`] (with the setup's travel box), each
/// segment's source line and feed for picking, its times and tool for playback, and the radii
/// of the setup's tools for the tool marker.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plot {
    /// The path and its marks.
    pub drawing: Drawing,
    /// 1-based source line of each segment.
    #[serde(skip)]
    pub lines: Vec<u32>,
    /// Feed of each segment in mm/min (0 for rapids).
    #[serde(skip)]
    pub feeds: Vec<f32>,
    /// When each segment runs.
    pub timeline: Timeline,
    /// The tool in the spindle during each segment.
    #[serde(skip)]
    pub tools: Vec<u32>,
    /// Radius in mm of the tools the setup knows, by number.
    pub tool_radii: BTreeMap<u32, f32>,
    /// The path's points kept at the job's level of detail, if it asked for one.
    pub lod: Option<Lod>,
    /// Number of blocks that move the tool ([`block_starts`]), which playback steps through.
    pub block_count: usize,
}

/// The first segment of each block that moves the tool, given each segment's source line: a
/// block's segments run one after another, so a block starts where the line changes.
pub fn block_starts(lines: &[u32]) -> impl Iterator<Item = usize> + '_ {
    (0..lines.len()).filter(|&i| i == 0 || lines[i] != lines[i - 1])
}

impl Plot {
    /// The plot of `path` run on `setup`'s machine.
    pub fn of(path: &Toolpath, setup: &Setup) -> Self {
        Plot {
            drawing: Drawing::of(path, setup.machine.travel_mm),
            lines: path.lines().to_vec(),
            feeds: path.feeds(),
            timeline: path.timeline(),
            tools: path.segment_tools(),
            tool_radii: setup
                .registers
                .iter()
                .map(|(&n, r)| (n, (r.radius + r.radius_wear) as f32))
                .collect(),
            lod: None,
            block_count: block_starts(path.lines()).count(),
        }
    }
}

/// What the editor shows of a finished analysis: everything but the program, its toolpath and
/// its machine states, which stay with the analysis ([`Kept`]).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Results {
    /// The job's generation.
    pub generation: u64,
    /// Every diagnostic in the program's own text, sorted by position.
    pub problems: Vec<Problem>,
    /// Diagnostics in the other open files its calls reached, by file then position.
    pub elsewhere: Vec<LinkedProblem>,
    /// Summary numbers.
    pub stats: Stats,
    /// What the backplot draws.
    pub plot: Plot,
    /// The other open files linked into the program, in the order their lines follow its own.
    pub linked: Vec<LinkedFile>,
    /// Another dialect the program's codes read better in.
    pub hint: Option<DialectHint>,
}

/// What an analysis keeps to answer questions about its program after its results are sent:
/// the program and the machine state before any block, and what cutting the stock needs.
#[derive(Debug, Clone)]
pub struct Kept {
    /// The job's generation.
    pub generation: u64,
    /// The parsed (and linked) program.
    pub program: Program,
    /// The machine states.
    pub states: States,
    /// The program's text, to locate the stock's diagnostics in.
    pub text: ProgramText,
    /// The machine it ran on, with the stock and tools.
    pub setup: Setup,
    /// The toolpath the stock is cut with.
    pub toolpath: Arc<Toolpath>,
    /// The points the backplot draws, simplified here for the view's zoom ([`Kept::lod`]).
    pub points: Arc<Vec<swarf_render::PathPoint>>,
    /// Where each piece of a program run piece by piece starts, to read it again for a state
    /// (empty: the program is held whole).
    pieces: Vec<PieceAt>,
}

/// Where a piece of a program read and run piece by piece starts (where the parse was, its
/// first line with it) and how many lines it has, so that it can be read again alone.
#[derive(Debug, Clone, Copy)]
struct PieceAt {
    lines: usize,
    at: ReadPoint,
}

impl Kept {
    /// The machine state just before the block on 1-based `line` first runs; `None` when no block
    /// there runs. Re-run from the nearest kept state, so the cost does not grow with the program.
    pub fn state_at(&self, line: u32) -> Option<BlockState> {
        let row = line.checked_sub(1)?;
        let block_on = |blocks: &[swarf_syntax::Block]| {
            let block = blocks.partition_point(|b| b.line < row);
            (blocks.get(block)?.line == row).then_some(block)
        };
        if self.pieces.is_empty() {
            return self
                .states
                .at(&self.program, block_on(&self.program.blocks)?);
        }
        // Run piece by piece: the piece the line is in is read again and re-run alone.
        let i = (self.pieces.partition_point(|p| p.at.line() <= row as usize)).checked_sub(1)?;
        let piece = self.pieces.get(i)?;
        let mut parse = ParseRun::resume(piece.at, self.program.dialect);
        read_lines(&self.text, &mut parse, &mut String::new(), piece.lines);
        let blocks = parse.program();
        self.states.in_piece(i, blocks, block_on(&blocks.blocks)?)
    }
}

/// How far an analysis has got.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Progress {
    /// Reading the text: bytes read, bytes in the text.
    Reading {
        /// Bytes read.
        read: usize,
        /// Bytes in the text.
        bytes: usize,
    },
    /// Running the program: different blocks reached, blocks in the program (a program that
    /// stops early, at an M30 before its end, finishes short of the total).
    Running {
        /// Different blocks run.
        reached: usize,
        /// Blocks in the program.
        blocks: usize,
    },
}

/// Most files linked to one program (a bound on runaway chains of calls).
const MAX_LINKED: usize = 64;

/// Lines the parser reads for one block of budget: reading a line costs about half of running
/// a block.
pub const PARSE_LINES_PER_BLOCK: usize = 2;

/// Most lines of a piece of a program read and run piece by piece (see [`PendingAnalysis`]):
/// the blocks held at once, and the most a state at a line is re-run over.
const PIECE_LINES: usize = 4096;

/// Reads at most `lines` more lines of `text` into `parse`; whether the whole text is read.
fn read_lines(text: &ProgramText, parse: &mut ParseRun, joined: &mut String, lines: usize) -> bool {
    match text {
        ProgramText::Flat(text) => parse.step(text, lines),
        ProgramText::Rope(rope) => parse.step_from(&mut RopeLines::new(rope, joined), lines),
    }
}

/// A program being read and run a piece at a time, so that its blocks are never all held at
/// once: until it jumps, loops or calls, which needs it whole.
#[derive(Debug, Default)]
struct Pieces {
    /// Where each piece run starts (a state at a line reads its piece again).
    starts: Vec<PieceAt>,
    /// Blocks read.
    blocks: usize,
    /// Whether the program has ended (the pieces after are read, not run).
    ended: bool,
    /// The lines with a code whose meaning differs between dialects (for the hint).
    sensitive: Sensitive,
}

/// An analysis under way, read and run a bounded amount per [`step`](PendingAnalysis::step) so the
/// runner can stop between pieces. A straight-through program's blocks are dropped once run; one
/// that jumps, loops or calls is read again whole. Dropping it cancels the run.
#[derive(Debug)]
pub struct PendingAnalysis {
    /// The job (its text, dialect and setup; the other open files until they are linked).
    job: Job,
    /// A line of a rope that straddles its chunks, joined for the parser (reused).
    joined: String,
    /// The parse, until the whole text is read.
    parse: Option<ParseRun>,
    /// The pieces read and run, while the program is read piece by piece.
    pieces: Option<Pieces>,
    program: Program,
    toolpath: Toolpath,
    /// The interpreter's run, once the text is read.
    run: Option<StatesRun>,
    /// The other open files linked for the program's calls.
    linked: Vec<LinkedSource>,
    /// Whether calls were looked for among open files (rather than files beside the program).
    among_open_files: bool,
}

impl PendingAnalysis {
    /// Prepares the analysis of `job` (a rope is parsed in place; nothing is read or executed
    /// yet). A file of `job.others` is copied only when the program calls into it, and a call
    /// found in none says so.
    pub fn start(job: Job) -> Self {
        let parse = ParseRun::new(job.dialect);
        let mut toolpath = Toolpath::for_machine(DVec3::ZERO, &job.setup.machine);
        // About a move a line, of some 24 bytes.
        toolpath.reserve(job.text.len() / 24);
        PendingAnalysis {
            run: Some(StatesRun::new(parse.program(), job.setup.clone())),
            joined: String::new(),
            parse: Some(parse),
            pieces: Some(Pieces::default()),
            program: Program::default(),
            toolpath,
            linked: Vec::new(),
            among_open_files: job.others.is_some(),
            job,
        }
    }

    /// Reads lines, then runs blocks, for at most `budget` blocks' worth of work (a block buys
    /// [`PARSE_LINES_PER_BLOCK`] lines; linking is not counted); returns whether the run is over.
    pub fn step(&mut self, budget: usize) -> bool {
        let mut budget = budget;
        while let Some(parse) = &mut self.parse {
            if budget == 0 {
                return false;
            }
            let mut lines = budget.saturating_mul(PARSE_LINES_PER_BLOCK);
            if self.pieces.is_some() {
                lines = lines.min(PIECE_LINES);
            }
            let at = parse.read_point();
            let (before, _) = parse.progress();
            let done = read_lines(&self.job.text, parse, &mut self.joined, lines);
            let (after, _) = parse.progress();
            let read = (after - before).div_ceil(PARSE_LINES_PER_BLOCK).max(1);
            budget = budget.saturating_sub(read);
            if let (Some(pieces), Some(run)) = (&mut self.pieces, &mut self.run) {
                let piece = parse.program();
                pieces.blocks += piece.blocks.len();
                pieces.sensitive.note(&piece.blocks);
                if !pieces.ended {
                    budget = budget.saturating_sub(piece.blocks.len());
                    let lines = after - before;
                    pieces.starts.push(PieceAt { lines, at });
                    match run.run_piece(piece, &mut self.toolpath) {
                        Piece::Ran => {}
                        Piece::Ended => pieces.ended = true,
                        Piece::NeedsWhole => {
                            self.read_whole();
                            continue;
                        }
                    }
                }
                parse.clear_blocks();
            }
            if done {
                self.program = self.parse.take().map(ParseRun::finish).unwrap_or_default();
                match &mut self.run {
                    Some(run) if self.pieces.is_some() => run.finish_pieces(&mut self.toolpath),
                    _ => self.link_and_start(),
                }
            }
        }
        match &mut self.run {
            Some(run) if budget > 0 => {
                run.step(&self.program, &mut self.toolpath, budget) == Status::Finished
            }
            Some(_) => false,
            None => true,
        }
    }

    /// Starts reading the text again, whole, for a program found to jump, loop or call.
    fn read_whole(&mut self) {
        self.parse = Some(ParseRun::new(self.job.dialect));
        self.pieces = None;
        self.run = None;
        self.toolpath = Toolpath::for_machine(DVec3::ZERO, &self.job.setup.machine);
    }

    /// Links the program's calls from the other open files (when there are any) and starts
    /// the interpreter's run.
    fn link_and_start(&mut self) {
        if let Some(others) = self.job.others.take()
            && !others.is_empty()
        {
            let len = self.job.text.len();
            self.linked = link_open_files(&mut self.program, len, self.job.dialect, &others);
        }
        self.toolpath.reserve(self.program.blocks.len());
        self.run = Some(StatesRun::new(&self.program, self.job.setup.clone()));
    }

    /// How far the analysis has got.
    pub fn progress(&self) -> Progress {
        match (&self.parse, &self.run) {
            (Some(parse), _) => Progress::Reading {
                read: parse.progress().1,
                bytes: self.job.text.len(),
            },
            (None, run) => Progress::Running {
                reached: run.as_ref().map_or(0, StatesRun::blocks_reached),
                blocks: self.program.blocks.len(),
            },
        }
    }

    /// The generation the results will carry.
    pub fn generation(&self) -> u64 {
        self.job.generation
    }

    /// Runs what is left, then locates the problems (the program's own, and those of the files
    /// it called in those files), prepares the plot and looks for a dialect that reads the
    /// program better: the results, and what is kept for questions about the program.
    pub fn finish(mut self) -> (Results, Kept) {
        while !self.step(usize::MAX) {}
        let job = self.job;
        let mut diags = self.program.diagnostics.clone();
        let states = match self.run.take() {
            Some(run) => {
                let (run_diags, states) = run.finish();
                diags.extend(run_diags);
                states
            }
            None => StatesRun::new(&self.program, job.setup.clone()).finish().1,
        };
        diags.sort_by_key(|d| (d.span.start, d.span.end));
        // Diagnostics past the program's own text belong to the files linked after it.
        let program = &self.program;
        let split = diags.partition_point(|d| d.span.start < own_end(program));
        let others = diags.split_off(split);
        if self.among_open_files {
            for d in &mut diags {
                if matches!(d.code, "E-SUBPROGRAM" | "E-OWORD") {
                    d.message = d.message.replace("a file beside it", "an open tab");
                }
            }
        }
        let problems = locate(job.text.as_text(), &program.lines, &diags);
        let mut elsewhere = Vec::new();
        for (i, (at, file)) in program.linked.iter().zip(&self.linked).enumerate() {
            let mut sweep = Sweep::default();
            for d in others
                .iter()
                .filter(|d| program.linked_at_offset(d.span.start) == Some(i))
            {
                let mut d = d.clone();
                d.span.start = d.span.start.saturating_sub(at.first_byte);
                d.span.end = d.span.end.saturating_sub(at.first_byte);
                let problem = locate_one(Text::Flat(&file.text), &file.lines, &mut sweep, &d);
                let file = file.name.clone();
                elsewhere.push(LinkedProblem { file, problem });
            }
        }
        self.toolpath.shrink_to_fit();
        let toolpath = &self.toolpath;
        let pieces = self.pieces.take().unwrap_or_default();
        let stats = Stats {
            blocks: program.blocks.len() + pieces.blocks,
            motions: toolpath.len(),
            bounds: toolpath.bounds().map(|b| (b.min, b.max)),
            estimated_secs: toolpath.estimated_secs(),
        };
        let mut sensitive = pieces.sensitive;
        sensitive.note(&program.blocks);
        let hint = suggest(&job.text, program, &problems, &sensitive);
        let mut plot = Plot::of(toolpath, &job.setup);
        plot.lod = job.lod.map(|level| Lod::of(&plot.drawing.points, level));
        let results = Results {
            generation: job.generation,
            plot,
            problems,
            elsewhere,
            stats,
            linked: program.linked.clone(),
            hint,
        };
        let kept = Kept {
            generation: job.generation,
            program: self.program,
            states,
            text: job.text,
            setup: job.setup,
            toolpath: Arc::new(self.toolpath),
            points: Arc::clone(&results.plot.drawing.points),
            pieces: pieces.starts,
        };
        (results, kept)
    }
}

/// Analyses `job` in one call.
pub fn analyse(job: Job) -> (Results, Kept) {
    PendingAnalysis::start(job).finish()
}

/// `diags` of the program's own text located as [`PendingAnalysis::finish`] locates them
/// (those in linked files are left out), sorted by position.
pub(crate) fn locate_own(kept: &Kept, mut diags: Vec<Diagnostic>) -> Vec<Problem> {
    diags.retain(|d| d.span.start < own_end(&kept.program));
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    locate(kept.text.as_text(), &kept.program.lines, &diags)
}

/// Where the program's own text ends among its spans: the files linked after it lie past it.
fn own_end(program: &Program) -> u32 {
    program.linked.first().map_or(u32::MAX, |l| l.first_byte)
}

/// `diags` of a text, sorted by position, located in it.
fn locate(text: Text<'_>, lines: &LineIndex, diags: &[Diagnostic]) -> Vec<Problem> {
    let mut sweep = Sweep::default();
    (diags.iter())
        .map(|d| locate_one(text, lines, &mut sweep, d))
        .collect()
}

/// Where locating a flat text has counted characters to, so that the sorted diagnostics cost
/// one pass over the text in all.
#[derive(Debug, Default)]
struct Sweep {
    /// Byte offset counted to, and the characters before it.
    at: usize,
    chars: usize,
    /// The last line located and the index of its first character.
    line: Option<(usize, usize)>,
}

impl Sweep {
    /// The index of the character starting at byte `offset` of `text` (or of the next one).
    fn char_at(&mut self, text: &str, offset: usize) -> usize {
        let mut to = offset.min(text.len());
        while !text.is_char_boundary(to) {
            to += 1;
        }
        if to >= self.at {
            self.chars += text.get(self.at..to).map_or(0, |t| t.chars().count());
            self.at = to;
            self.chars
        } else {
            self.chars - text.get(to..self.at).map_or(0, |t| t.chars().count())
        }
    }
}

/// One diagnostic of a text (the program's, or a linked file's) located: its line, column and
/// character range, the diagnostics taken in order of position.
fn locate_one(text: Text<'_>, lines: &LineIndex, sweep: &mut Sweep, d: &Diagnostic) -> Problem {
    let len = match text {
        Text::Flat(text) => text.len(),
        Text::Rope(rope) => rope.len_bytes(),
    };
    let (start_at, end_at) = (d.span.start as usize, d.span.end as usize);
    let line = lines.line_of(d.span.start);
    let line_start = (lines.line_start(line) as usize).min(len);
    let (col, start, end) = match text {
        Text::Flat(text) => {
            let line_chars = match sweep.line {
                Some((l, c)) if l == line => c,
                _ => {
                    let c = sweep.char_at(text, line_start);
                    sweep.line = Some((line, c));
                    c
                }
            };
            let here = sweep.char_at(text, start_at.max(line_start));
            let start = if start_at > len { 0 } else { here };
            let end = if end_at > len {
                start
            } else if end_at >= start_at {
                let mut to = end_at;
                while !text.is_char_boundary(to) {
                    to += 1;
                }
                let from = sweep.at.min(to);
                sweep.chars - text.get(from..sweep.at).map_or(0, |t| t.chars().count())
                    + text.get(from..to).map_or(0, |t| t.chars().count())
            } else {
                start
            };
            (here - line_chars, start, end)
        }
        Text::Rope(rope) => {
            let char_of = |o: usize| {
                let o = o.min(len);
                let c = rope.byte_to_char(o);
                if rope.char_to_byte(c) < o { c + 1 } else { c }
            };
            let here = char_of(start_at.max(line_start));
            let start = if start_at > len { 0 } else { here };
            let end = if end_at > len { start } else { char_of(end_at) };
            (here - char_of(line_start), start, end)
        }
    };
    Problem {
        line: u32::try_from(line + 1).unwrap_or(u32::MAX),
        col: u32::try_from(col + 1).unwrap_or(u32::MAX),
        severity: d.severity,
        code: d.code,
        message: d.message.clone(),
        chars: start..end.max(start),
    }
}

/// Links the programs `program` calls and does not hold from the other open files, by the
/// names the CLI would look for beside it.
fn link_open_files(
    program: &mut Program,
    main_len: usize,
    dialect: Dialect,
    others: &[OpenFile],
) -> Vec<LinkedSource> {
    program.link_calls(main_len, dialect, MAX_LINKED, |missing| {
        let names = missing.file_names();
        let file = names
            .iter()
            .find_map(|n| others.iter().find(|f| f.name == *n))?;
        Some((file.name.clone(), file.text.to_owned_string()))
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use std::sync::Arc;

    use proptest::prelude::*;
    use ropey::Rope;

    use super::*;

    /// Locates `diags` (sorted) one at a time, as the analysis does.
    fn one_by_one(text: &ProgramText, lines: &LineIndex, diags: &[Diagnostic]) -> Vec<Problem> {
        let mut sweep = Sweep::default();
        diags
            .iter()
            .map(|d| locate_one(text.as_text(), lines, &mut sweep, d))
            .collect()
    }

    /// Turns byte spans into lines, columns and character ranges in one pass over the text: what
    /// [`locate_one`] must agree with.
    fn locate(text: &str, lines: &LineIndex, diags: &[Diagnostic]) -> Vec<Problem> {
        let mut offsets: Vec<usize> = diags
            .iter()
            .flat_map(|d| [d.span.start as usize, d.span.end as usize])
            .collect();
        offsets.sort_unstable();
        offsets.dedup();
        let mut char_of = std::collections::HashMap::with_capacity(offsets.len());
        // Each offset becomes the index of the character starting there (or the next one), counted
        // a run of text at a time from the offset before.
        let (mut at, mut chars) = (0usize, 0usize);
        for &o in &offsets {
            if o > text.len() {
                break;
            }
            let mut to = o;
            while !text.is_char_boundary(to) {
                to += 1;
            }
            chars += text.get(at..to).map_or(0, |t| t.chars().count());
            at = to;
            char_of.insert(o, chars);
        }
        let mut cols = lines.cursor(text);
        diags
            .iter()
            .map(|d| {
                let (line, col) = cols.line_col(d.span.start);
                let start = char_of.get(&(d.span.start as usize)).copied().unwrap_or(0);
                let end = char_of
                    .get(&(d.span.end as usize))
                    .copied()
                    .unwrap_or(start);
                Problem {
                    line,
                    col,
                    severity: d.severity,
                    code: d.code,
                    message: d.message.clone(),
                    chars: start..end.max(start),
                }
            })
            .collect()
    }

    proptest! {
        #[test]
        fn diagnostics_located_one_by_one_match_the_single_pass(
            text in "[GX0-9 ;()\\r\\n注释é$]{0,200}",
            spans in proptest::collection::vec((0usize..260, 0usize..40), 0..30),
        ) {
            let bounds: Vec<usize> = text
                .char_indices()
                .map(|(b, _)| b)
                .chain([text.len(), text.len() + 3])
                .collect();
            let mut diags: Vec<Diagnostic> = spans
                .iter()
                .map(|&(a, n)| {
                    let start = bounds[a % bounds.len()];
                    let end = bounds[(a + n) % bounds.len()].max(start);
                    Diagnostic::error(swarf_syntax::Span::new(start, end), "E-SYNTAX-CHAR", "test")
                })
                .collect();
            diags.sort_by_key(|d| (d.span.start, d.span.end));
            let lines = LineIndex::new(&text);
            let expected = locate(&text, &lines, &diags);
            let flat = ProgramText::Flat(Arc::new(text.clone()));
            prop_assert_eq!(&one_by_one(&flat, &lines, &diags), &expected);
            let rope = ProgramText::Rope(Rope::from_str(&text));
            prop_assert_eq!(&one_by_one(&rope, &lines, &diags), &expected);
        }
    }
}
