//! Running the pipeline for the editor: parse, interpret, record, and prepare the scene.

use std::sync::Arc;

use glam::DVec3;
use ropey::Rope;
use swarf_interp::Setup;
use swarf_render::{Kind, PathPoint};
use swarf_syntax::{Diagnostic, Dialect, LineIndex, LinkedSource, ParseRun, Program, Severity};
use swarf_toolpath::{CycleMove, SegmentKind, Toolpath, box_edges};

use crate::backplot::{Scene, SourceText};
use crate::buffer::RopeLines;

/// A program's text as the analysis reads it: one shared string, or the editor's rope, which
/// is parsed and located in place so that an edit of a long program costs no copy of it.
#[derive(Debug, Clone)]
pub enum ProgramText {
    /// The whole text as one string.
    Flat(Arc<String>),
    /// The text as a rope (a clone shares its chunks).
    Rope(Rope),
}

impl ProgramText {
    /// Length in bytes.
    pub fn len(&self) -> usize {
        match self {
            ProgramText::Flat(text) => text.len(),
            ProgramText::Rope(rope) => rope.len_bytes(),
        }
    }

    /// Whether the text is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The text as one new string (for a linked file, which the program then holds).
    fn to_owned_string(&self) -> String {
        match self {
            ProgramText::Flat(text) => text.as_ref().clone(),
            ProgramText::Rope(rope) => rope.to_string(),
        }
    }
}

/// One diagnostic, located for display.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// 1-based line.
    pub line: u32,
    /// 1-based column in characters.
    pub col: u32,
    /// How bad it is.
    pub severity: Severity,
    /// Stable code such as `E-SYNTAX-CHAR`.
    pub code: &'static str,
    /// The message.
    pub message: String,
    /// Character range in the text, for underlining and jumping.
    pub chars: std::ops::Range<usize>,
}

/// A diagnostic in another open file that the program called (a subprogram's error), located
/// in that file.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkedProblem {
    /// The name of the file (tab) it is in.
    pub file: String,
    /// The diagnostic, located in that file's text.
    pub problem: Problem,
}

/// Another open file whose programs a program's calls may reach: it is linked when its name is
/// one the CLI looks for beside a program (`O1234.nc`, `1234.nc`, `name.ngc` …, see
/// [`swarf_syntax::Missing::file_names`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OpenFile<'a> {
    /// The file's name, as shown on its tab.
    pub name: &'a str,
    /// Its text.
    pub text: &'a str,
}

/// Most files linked to one program (a bound on runaway chains of calls).
const MAX_LINKED: usize = 64;

/// Summary numbers of an analysed program.
#[derive(Debug, Clone, Copy, PartialEq)]
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

/// The result of running the pipeline over one text.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// The parsed program.
    pub program: Program,
    /// The recorded toolpath.
    pub toolpath: Toolpath,
    /// Every diagnostic in the program's own text, sorted by position.
    pub problems: Vec<Problem>,
    /// Diagnostics in the other open files its calls reached, by file then position.
    pub elsewhere: Vec<LinkedProblem>,
    /// Geometry for the backplot.
    pub scene: Scene,
    /// The machine state at any block (for the state-at-cursor view).
    pub states: swarf_interp::States,
}

impl Analysis {
    /// Parses and interprets `text` in one call; `generation` tags the scene so the GPU copy is
    /// refreshed. The editor spreads long programs over frames with [`PendingAnalysis`].
    pub fn run(text: &str, dialect: Dialect, setup: &Setup, generation: u64) -> Self {
        let mut pending = PendingAnalysis::start(text, dialect, setup, generation);
        while !pending.step(usize::MAX) {}
        pending.finish()
    }

    /// Summary numbers for the status bar and the JS API.
    pub fn stats(&self) -> Stats {
        Stats {
            blocks: self.program.blocks.len(),
            motions: self.toolpath.len(),
            bounds: self.toolpath.bounds().map(|b| (b.min, b.max)),
            estimated_secs: self.toolpath.estimated_secs(),
        }
    }

    /// Number of problems of `severity`, in the program's own text and in the files it called.
    pub fn count(&self, severity: Severity) -> usize {
        self.problems
            .iter()
            .chain(self.elsewhere.iter().map(|l| &l.problem))
            .filter(|p| p.severity == severity)
            .count()
    }

    /// The name of the other open file a 0-based block `line` of the program lies in (`None`:
    /// the program's own text), with the line's 1-based number in that file.
    pub fn linked_line(&self, line: u32) -> Option<(&str, u32)> {
        let i = self.program.linked_at_line(line)?;
        let file = self.program.linked.get(i)?;
        Some((file.name.as_str(), line - file.first_line + 1))
    }
}

/// Lines the parser reads for one block of budget: reading a line costs about half of running
/// a block.
pub const PARSE_LINES_PER_BLOCK: usize = 2;

/// An analysis under way: the text is parsed and then run by the interpreter, a bounded amount
/// of each per [`step`](PendingAnalysis::step), so a long program never holds up a frame for
/// long. Dropping it cancels the run.
#[derive(Debug)]
pub struct PendingAnalysis {
    text: ProgramText,
    /// A line of a rope that straddles its chunks, joined for the parser (reused).
    joined: String,
    /// The parse, until the whole text is read.
    parse: Option<ParseRun>,
    program: Program,
    toolpath: Toolpath,
    /// The interpreter's run, once the text is parsed.
    run: Option<swarf_interp::StatesRun>,
    setup: Setup,
    generation: u64,
    finished: bool,
    /// The other open files linked for the program's calls.
    linked: Vec<LinkedSource>,
    /// The other open files (name, text) to link the program's calls from once it is read;
    /// `None` when calls are not looked for among open files.
    others: Option<Vec<(String, ProgramText)>>,
    /// Whether calls were looked for among open files (rather than files beside the program).
    among_open_files: bool,
    /// The dialect the text is read in (for the linked files).
    dialect: Dialect,
    /// Lines read plus blocks executed so far (what the budget is spent on).
    work: u64,
    /// Blocks executed, and different blocks reached, by the run so far.
    executed: u64,
    reached: usize,
    /// Once the run has ended: what is left to do.
    wrap: Option<WrapUp>,
}

impl PendingAnalysis {
    /// Prepares the analysis of `text` (nothing read or executed yet).
    pub fn start(text: &str, dialect: Dialect, setup: &Setup, generation: u64) -> Self {
        Self::start_with(
            ProgramText::Flat(Arc::new(text.to_string())),
            dialect,
            setup,
            generation,
            None,
        )
    }

    /// [`PendingAnalysis::start`] for a text already held in an `Arc` (not copied).
    pub fn start_shared(
        text: Arc<String>,
        dialect: Dialect,
        setup: &Setup,
        generation: u64,
    ) -> Self {
        Self::start_with(ProgramText::Flat(text), dialect, setup, generation, None)
    }

    /// Like [`start`](PendingAnalysis::start), for a program open beside `others`: the
    /// programs it calls and does not hold are linked from those files (named as the CLI
    /// looks for them beside a program), and a call found in none says so.
    pub fn start_among(
        text: &str,
        dialect: Dialect,
        setup: &Setup,
        generation: u64,
        others: &[OpenFile<'_>],
    ) -> Self {
        let text = ProgramText::Flat(Arc::new(text.to_string()));
        let others = others
            .iter()
            .map(|f| {
                let text = ProgramText::Flat(Arc::new(f.text.to_string()));
                (f.name.to_string(), text)
            })
            .collect();
        Self::start_with(text, dialect, setup, generation, Some(others))
    }

    /// [`PendingAnalysis::start_among`] for texts already held in `Arc`s (not copied): the
    /// program's and the other open files' as (name, text).
    pub fn start_shared_among(
        text: Arc<String>,
        dialect: Dialect,
        setup: &Setup,
        generation: u64,
        others: Vec<(String, Arc<String>)>,
    ) -> Self {
        let others = others
            .into_iter()
            .map(|(name, text)| (name, ProgramText::Flat(text)))
            .collect();
        Self::start_with(
            ProgramText::Flat(text),
            dialect,
            setup,
            generation,
            Some(others),
        )
    }

    /// [`PendingAnalysis::start_shared_among`] for texts that may be ropes: a rope is parsed
    /// in place, and another file's is copied only when the program calls into it.
    pub fn start_text_among(
        text: ProgramText,
        dialect: Dialect,
        setup: &Setup,
        generation: u64,
        others: Vec<(String, ProgramText)>,
    ) -> Self {
        Self::start_with(text, dialect, setup, generation, Some(others))
    }

    fn start_with(
        text: ProgramText,
        dialect: Dialect,
        setup: &Setup,
        generation: u64,
        others: Option<Vec<(String, ProgramText)>>,
    ) -> Self {
        let among_open_files = others.is_some();
        let parse = match &text {
            ProgramText::Flat(text) => ParseRun::new(text, dialect),
            ProgramText::Rope(rope) => {
                ParseRun::with_lines(LineIndex::from_chunks(rope.chunks()), dialect)
            }
        };
        PendingAnalysis {
            text,
            joined: String::new(),
            parse: Some(parse),
            program: Program::default(),
            toolpath: Toolpath::for_machine(DVec3::ZERO, &setup.machine),
            run: None,
            setup: setup.clone(),
            generation,
            finished: false,
            linked: Vec::new(),
            others,
            among_open_files,
            dialect,
            work: 0,
            executed: 0,
            reached: 0,
            wrap: None,
        }
    }

    /// Reads lines, then executes blocks, then locates the problems and prepares the scene, for
    /// at most `budget` blocks' worth of work (a block buys [`PARSE_LINES_PER_BLOCK`] lines;
    /// see [`LOCATE_COST`] and [`SCENE_SEGMENTS_PER_BLOCK`]); whether the analysis is finished.
    ///
    /// Locating and the scene of a long program each take a step of their own, so that
    /// finishing does not hold up one frame for as long as all of it.
    pub fn step(&mut self, budget: usize) -> bool {
        let full = budget;
        let mut budget = budget;
        if let Some(parse) = &mut self.parse {
            let (before, _) = parse.progress();
            let lines = budget.saturating_mul(PARSE_LINES_PER_BLOCK);
            let done = match &self.text {
                ProgramText::Flat(text) => parse.step(text, lines),
                ProgramText::Rope(rope) => {
                    parse.step_from(&mut RopeLines::new(rope, &mut self.joined), lines)
                }
            };
            let (after, _) = parse.progress();
            let read = after - before;
            self.work += read as u64;
            budget = budget.saturating_sub(read.div_ceil(PARSE_LINES_PER_BLOCK));
            if !done {
                return false;
            }
            if let Some(parse) = self.parse.take() {
                self.program = parse.finish();
            }
        }
        if self.run.is_none() && self.wrap.is_none() {
            // Looking for the calls into other files goes over every block: for a long
            // program it waits for a step of its own.
            let cost = self.link_cost();
            if cost > budget && budget < full {
                return false;
            }
            self.link_and_start();
            self.work += (cost.min(budget) * PARSE_LINES_PER_BLOCK) as u64;
            budget = budget.saturating_sub(cost);
        }
        if self.wrap.is_none()
            && budget > 0
            && let Some(run) = &mut self.run
        {
            let before = run.executed_blocks();
            let ran = run.step(&self.program, &mut self.toolpath, budget)
                == swarf_interp::Status::Finished;
            let executed = run.executed_blocks() - before;
            self.work += executed;
            self.executed = run.executed_blocks();
            self.reached = run.blocks_reached();
            budget = budget.saturating_sub(usize::try_from(executed).unwrap_or(usize::MAX));
            if ran {
                self.start_wrap_up();
            }
        }
        if self.wrap.is_some() {
            self.wrap_up(full, budget);
        }
        self.finished
    }

    /// Budget (in blocks) that linking the program's calls from the other open files costs.
    fn link_cost(&self) -> usize {
        match &self.others {
            Some(others) if !others.is_empty() => self.program.blocks.len() / LINK_BLOCKS_PER_BLOCK,
            _ => 0,
        }
    }

    /// Links the program's calls from the other open files (when there are any) and starts
    /// the interpreter's run.
    fn link_and_start(&mut self) {
        if let Some(others) = self.others.take()
            && !others.is_empty()
        {
            self.linked =
                link_open_files(&mut self.program, self.text.len(), self.dialect, &others);
        }
        self.toolpath.reserve(self.program.blocks.len());
        self.run = Some(swarf_interp::StatesRun::new(
            &self.program,
            self.setup.clone(),
        ));
    }

    /// Ends the run (or, when the text was not read to its end, runs nothing): the machine
    /// states and the diagnostics, sorted and split between the program and its linked files.
    fn start_wrap_up(&mut self) {
        let mut diags = self.program.diagnostics.clone();
        let states = match self.run.take() {
            Some(run) => {
                let (run_diags, states) = run.finish();
                diags.extend(run_diags);
                states
            }
            None => {
                swarf_interp::StatesRun::new(&self.program, self.setup.clone())
                    .finish()
                    .1
            }
        };
        diags.sort_by_key(|d| (d.span.start, d.span.end));
        // Diagnostics past the program's own text belong to the files linked after it.
        let own_end = self
            .program
            .linked
            .first()
            .map_or(u32::MAX, |l| l.first_byte);
        let split = diags.partition_point(|d| d.span.start < own_end);
        let others = diags.split_off(split);
        if self.among_open_files {
            for d in &mut diags {
                if matches!(d.code, "E-SUBPROGRAM" | "E-OWORD") {
                    d.message = d.message.replace("a file beside it", "an open tab");
                }
            }
        }
        self.wrap = Some(WrapUp {
            states,
            problems: Vec::with_capacity(diags.len()),
            own: diags,
            others,
            sweep: Sweep::default(),
            scene: None,
        });
    }

    /// Locates problems and then prepares the scene for `budget` of the step's `full` budget;
    /// a part that does not fit waits for the next step unless nothing was done in this one.
    fn wrap_up(&mut self, full: usize, mut budget: usize) {
        let Some(wrap) = &mut self.wrap else {
            return;
        };
        if wrap.problems.len() < wrap.own.len() {
            let mut n = budget / LOCATE_COST;
            if budget == full {
                n = n.max(1);
            }
            let from = wrap.problems.len();
            let to = from.saturating_add(n).min(wrap.own.len());
            for d in &wrap.own[from..to] {
                let problem = locate_one(&self.text, &self.program.lines, &mut wrap.sweep, d);
                wrap.problems.push(problem);
            }
            let cost = (to - from).saturating_mul(LOCATE_COST);
            self.work += (cost * PARSE_LINES_PER_BLOCK) as u64;
            budget = budget.saturating_sub(cost);
            if wrap.problems.len() < wrap.own.len() {
                return;
            }
        }
        if wrap.scene.is_none() {
            let cost = self.toolpath.len() / SCENE_SEGMENTS_PER_BLOCK;
            if cost > budget && budget < full {
                return;
            }
            let mut scene = scene_of(&self.toolpath, self.generation);
            if let Some(travel) = self.setup.machine.travel_mm {
                let mut marks = scene.marks.as_ref().clone();
                marks.extend(box_marks(travel, scene.origin));
                scene.marks = Arc::new(marks);
            }
            scene.source = Some(Arc::new(match &self.text {
                ProgramText::Flat(text) => SourceText::shared(Arc::clone(text)),
                ProgramText::Rope(rope) => SourceText::from_rope(rope.clone()),
            }));
            scene.tool_radii = Arc::new(
                self.setup
                    .registers
                    .iter()
                    .map(|(&n, r)| (n, (r.radius + r.radius_wear) as f32))
                    .collect(),
            );
            wrap.scene = Some(scene);
            self.work += (cost.min(budget) * PARSE_LINES_PER_BLOCK) as u64;
        }
        self.finished = true;
    }

    /// Whether the run is finished, so [`finish`](PendingAnalysis::finish) gives the result.
    pub fn is_finished(&self) -> bool {
        self.finished
    }

    /// While the text is being read: (lines read, lines in the text).
    pub fn parse_progress(&self) -> Option<(usize, usize)> {
        self.parse.as_ref().map(ParseRun::progress)
    }

    /// Progress of the run as (different blocks run, blocks in the program); (0, 0) while the
    /// text is still being read. A program that stops early (M30 before its end) finishes short
    /// of the total.
    pub fn progress(&self) -> (usize, usize) {
        if self.run.is_none() && self.wrap.is_none() {
            return (0, 0);
        }
        (self.reached, self.program.blocks.len())
    }

    /// Blocks executed so far (every pass of a loop counts).
    pub fn executed_blocks(&self) -> u64 {
        self.executed
    }

    /// The work done so far against the frame budget: lines read (a block's worth per
    /// [`PARSE_LINES_PER_BLOCK`]) plus blocks executed.
    pub fn work_done(&self) -> u64 {
        let lines = self.work - self.executed_blocks();
        lines.div_ceil(PARSE_LINES_PER_BLOCK as u64) + self.executed_blocks()
    }

    /// The generation the result will carry.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The finished analysis: problems located, scene prepared. Called before the run is
    /// finished, it covers the lines read and the blocks run so far.
    pub fn finish(mut self) -> Analysis {
        if !self.finished {
            match self.parse.take() {
                Some(parse) => self.program = parse.finish(),
                // Read to its end, not yet linked: linked now (and run no further).
                None if self.run.is_none() && self.wrap.is_none() => self.link_and_start(),
                None => {}
            }
            if self.wrap.is_none() {
                self.start_wrap_up();
            }
            self.wrap_up(usize::MAX, usize::MAX);
        }
        let PendingAnalysis {
            program,
            toolpath,
            wrap,
            setup,
            generation,
            linked,
            ..
        } = self;
        let (states, problems, others, scene) = match wrap {
            Some(w) => (w.states, w.problems, w.others, w.scene),
            None => (
                swarf_interp::StatesRun::new(&program, setup).finish().1,
                Vec::new(),
                Vec::new(),
                None,
            ),
        };
        let mut elsewhere = Vec::new();
        for (i, (at, file)) in program.linked.iter().zip(&linked).enumerate() {
            let here: Vec<Diagnostic> = others
                .iter()
                .filter(|d| program.linked_at_offset(d.span.start) == Some(i))
                .map(|d| {
                    let mut d = d.clone();
                    d.span.start = d.span.start.saturating_sub(at.first_byte);
                    d.span.end = d.span.end.saturating_sub(at.first_byte);
                    d
                })
                .collect();
            elsewhere.extend(
                locate(&file.text, &file.lines, &here)
                    .into_iter()
                    .map(|problem| LinkedProblem {
                        file: file.name.clone(),
                        problem,
                    }),
            );
        }
        Analysis {
            program,
            scene: scene.unwrap_or_else(|| scene_of(&toolpath, generation)),
            toolpath,
            problems,
            elsewhere,
            states,
        }
    }
}

/// Budget (in blocks) that locating one diagnostic costs: about twice running a block.
pub const LOCATE_COST: usize = 2;

/// Blocks looked over for calls into other files per block of budget.
pub const LINK_BLOCKS_PER_BLOCK: usize = 16;

/// Toolpath segments the scene is prepared for per block of budget.
pub const SCENE_SEGMENTS_PER_BLOCK: usize = 8;

/// What is left to do once the run has ended.
#[derive(Debug)]
struct WrapUp {
    states: swarf_interp::States,
    /// The diagnostics in the program's own text, sorted by position.
    own: Vec<Diagnostic>,
    /// The diagnostics in the files linked after it.
    others: Vec<Diagnostic>,
    /// `own` located so far, in order.
    problems: Vec<Problem>,
    sweep: Sweep,
    scene: Option<Scene>,
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

/// One diagnostic of the program's own text located (as [`locate`] does for many), the
/// diagnostics taken in order of position.
fn locate_one(text: &ProgramText, lines: &LineIndex, sweep: &mut Sweep, d: &Diagnostic) -> Problem {
    let len = text.len();
    let (start_at, end_at) = (d.span.start as usize, d.span.end as usize);
    let line = lines.line_of(d.span.start);
    let line_start = (lines.line_start(line) as usize).min(len);
    let (col, start, end) = match text {
        ProgramText::Flat(text) => {
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
        ProgramText::Rope(rope) => {
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
    others: &[(String, ProgramText)],
) -> Vec<LinkedSource> {
    program.link_calls(main_len, dialect, MAX_LINKED, |missing| {
        let names = missing.file_names();
        let (name, text) = names
            .iter()
            .find_map(|n| others.iter().find(|(name, _)| name == n))?;
        Some((name.clone(), text.to_owned_string()))
    })
}

/// Turns byte spans into lines, columns and character ranges in one pass over the text.
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

/// The toolpath as one polyline stream relative to its bounds' centre ([`scene_origin`]):
/// the start point (pen up), then one point per segment end carrying the segment's kind,
/// plus each segment's source line and feed for picking, and its times and tool for playback.
pub fn scene_of(path: &Toolpath, generation: u64) -> Scene {
    let Some(bounds) = path.bounds() else {
        return Scene {
            generation,
            ..Scene::default()
        };
    };
    let origin = scene_origin(path);
    let rel = |p: DVec3| (p - origin).as_vec3();
    let mut points = Vec::with_capacity(path.len() + 1);
    points.push(PathPoint::pen_up(rel(path.start())));
    points.extend(path.ends().iter().zip(path.kinds()).map(|(end, kind)| {
        let kind = match kind {
            SegmentKind::Rapid => Kind::Rapid,
            SegmentKind::Feed => Kind::Feed,
            SegmentKind::Arc => Kind::Arc,
        };
        PathPoint::new(rel(*end), kind)
    }));
    mark_cycle_moves(path, &mut points);
    mark_compensated(path, &mut points);
    color_by_tool(path, &mut points);
    let diagonal = (bounds.max - bounds.min).length();
    let mut marks = hole_marks(path, rel, diagonal);
    marks.extend(peck_marks(path, rel, diagonal));
    marks.extend(programmed_marks(path, rel));
    marks.extend(origin_marks(path, rel, diagonal));
    for (min, max) in path.zone_boxes() {
        marks.extend(edge_marks(&box_edges(min, max), origin, Kind::Zone));
    }
    Scene {
        generation,
        points: Arc::new(points),
        lines: Arc::new(path.lines().to_vec()),
        feeds: Arc::new(path.feeds()),
        timeline: Arc::new(path.timeline()),
        tools: Arc::new(path.segment_tools()),
        bounds: Some((rel(bounds.min), rel(bounds.max))),
        zero: rel(DVec3::ZERO),
        origin,
        marks: Arc::new(marks),
        ..Scene::default()
    }
}

/// The twelve edges of the machine's travel box (machine coordinates, mm) relative to the
/// scene's `origin`.
pub fn box_marks([min, max]: [[f64; 3]; 2], origin: DVec3) -> Vec<PathPoint> {
    edge_marks(
        &box_edges(DVec3::from_array(min), DVec3::from_array(max)),
        origin,
        Kind::Boundary,
    )
}

/// Line segments (machine coordinates) as `kind` marks relative to `origin`.
pub fn edge_marks(edges: &[(DVec3, DVec3)], origin: DVec3, kind: Kind) -> Vec<PathPoint> {
    let rel = |p: DVec3| (p - origin).as_vec3();
    edges
        .iter()
        .flat_map(|&(a, b)| [PathPoint::pen_up(rel(a)), PathPoint::new(rel(b), kind)])
        .collect()
}

/// An X/Y/Z axis cross at every program zero the moves were programmed from (G54…, with
/// G52/G92 shifts), 1/20 of the scene's diagonal long (2 to 50 mm).
fn origin_marks(
    path: &Toolpath,
    rel: impl Fn(DVec3) -> glam::Vec3,
    diagonal: f64,
) -> Vec<PathPoint> {
    let length = (diagonal / 20.0).clamp(2.0, 50.0);
    let mut marks = Vec::with_capacity(path.origins().len() * 6);
    for &at in path.origins() {
        for (axis, kind) in [
            (DVec3::X, Kind::AxisX),
            (DVec3::Y, Kind::AxisY),
            (DVec3::Z, Kind::AxisZ),
        ] {
            marks.push(PathPoint::pen_up(rel(at)));
            marks.push(PathPoint::new(rel(at + axis * length), kind));
        }
    }
    marks
}

/// A ring at the top of every hole, across the hole's axis, sized to the scene (1/150 of its
/// diagonal, 0.5 to 5 mm), so holes stand out where plunges are seen end-on (a top view).
fn hole_marks(path: &Toolpath, rel: impl Fn(DVec3) -> glam::Vec3, diagonal: f64) -> Vec<PathPoint> {
    const SIDES: usize = 12;
    let radius = (diagonal / 150.0).clamp(0.5, 5.0);
    let mut marks = Vec::with_capacity(path.holes().len() * (SIDES + 1));
    for hole in path.holes() {
        let axis = (hole.bottom - hole.top).normalize_or(DVec3::NEG_Z);
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        for k in 0..=SIDES {
            let a = std::f64::consts::TAU * k as f64 / SIDES as f64;
            let p = rel(hole.top + (u * a.cos() + v * a.sin()) * radius);
            marks.push(if k == 0 {
                PathPoint::pen_up(p)
            } else {
                PathPoint::new(p, Kind::Cycle)
            });
        }
    }
    marks
}

/// A small cross across the hole's axis at the bottom of every peck of a hole drilled in more
/// than one plunge (G83, G73): each peck's retract runs back over the plunges, so without
/// them the pecks merge into one line and cannot be counted.
fn peck_marks(path: &Toolpath, rel: impl Fn(DVec3) -> glam::Vec3, diagonal: f64) -> Vec<PathPoint> {
    let half = (diagonal / 150.0).clamp(0.5, 5.0) * 0.6;
    let mut plunges: Vec<(usize, usize)> = Vec::new();
    for (segment, role) in path.cycle_moves() {
        if role == CycleMove::Plunge
            && let Some(hole) = path.hole_of_segment(segment)
        {
            plunges.push((hole, segment));
        }
    }
    let mut marks = Vec::new();
    for group in plunges.chunk_by(|a, b| a.0 == b.0) {
        if group.len() < 2 {
            continue;
        }
        let Some(hole) = path.holes().get(group[0].0) else {
            continue;
        };
        let axis = (hole.bottom - hole.top).normalize_or(DVec3::NEG_Z);
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        for &(_, segment) in group {
            let Some(&bottom) = path.ends().get(segment) else {
                continue;
            };
            for across in [u, v] {
                marks.push(PathPoint::pen_up(rel(bottom - across * half)));
                marks.push(PathPoint::new(rel(bottom + across * half), Kind::Plunge));
            }
        }
    }
    marks
}

/// The segments of blocks cut under cutter radius compensation are the tool centre's path:
/// they are drawn as compensated (the programmed contour goes beside them as a mark).
fn mark_compensated(path: &Toolpath, points: &mut [PathPoint]) {
    if path.programmed().is_empty() {
        return;
    }
    let lines: std::collections::HashSet<u32> = path.programmed().iter().map(|(l, _)| *l).collect();
    for (point, (line, kind)) in points
        .iter_mut()
        .skip(1)
        .zip(path.lines().iter().zip(path.kinds()))
    {
        if lines.contains(line) && *kind != SegmentKind::Rapid {
            *point = PathPoint::new(point.position(), Kind::Compensated);
        }
    }
}

/// The programmed contour of the compensated blocks (the part as drawn, beside the tool centre's
/// path), as marks: each move from the end of the one before, arcs as chords.
fn programmed_marks(path: &Toolpath, rel: impl Fn(DVec3) -> glam::Vec3) -> Vec<PathPoint> {
    let mut marks = Vec::new();
    let mut last: Option<(u32, DVec3)> = None;
    for (line, event) in path.programmed() {
        let Some(end) = event.end_point() else {
            continue;
        };
        // A move right after the one before continues it; otherwise the contour starts here.
        let from = last.filter(|(l, _)| *l <= *line).map(|(_, p)| p);
        match from {
            None => marks.push(PathPoint::pen_up(rel(end))),
            Some(from) => {
                if let swarf_interp::Canon::Arc {
                    center,
                    axis,
                    ccw,
                    turns,
                    ..
                } = event
                {
                    for p in swarf_toolpath::tessellate_arc(from, end, *center, *axis, *ccw, *turns)
                    {
                        marks.push(PathPoint::new(rel(p), Kind::Programmed));
                    }
                } else {
                    marks.push(PathPoint::new(rel(end), Kind::Programmed));
                }
            }
        }
        last = Some((*line, end));
    }
    marks
}

/// Gives every point the number of its segment's tool in order of first use, so the backplot can
/// colour the path by tool (`ColorMode::ByIndex`). `points[0]` is the start point.
fn color_by_tool(path: &Toolpath, points: &mut [PathPoint]) {
    let tools = path.tools();
    for (point, tool) in points.iter_mut().skip(1).zip(path.segment_tools()) {
        let index = tools.iter().position(|t| *t == tool).unwrap_or(0);
        *point = point.with_color_index(u16::try_from(index).unwrap_or(u16::MAX));
    }
}

/// Gives the segments of canned cycles their kinds (plunge, retract, other cycle move), so the
/// backplot colours holes apart from the contour. `points[0]` is the start point.
fn mark_cycle_moves(path: &Toolpath, points: &mut [PathPoint]) {
    for (segment, role) in path.cycle_moves() {
        if let Some(p) = points.get_mut(segment + 1) {
            let kind = match role {
                CycleMove::Plunge => Kind::Plunge,
                CycleMove::Retract => Kind::Retract,
                CycleMove::Other => Kind::Cycle,
            };
            *p = PathPoint::new(p.position(), kind);
        }
    }
}

/// The machine point the scene's f32 vertices are relative to: the centre of the bounds.
pub fn scene_origin(path: &Toolpath) -> DVec3 {
    path.bounds().map_or(DVec3::ZERO, |b| b.center())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Locates `diags` (sorted) one at a time, as the analysis does over steps.
    fn one_by_one(text: &ProgramText, lines: &LineIndex, diags: &[Diagnostic]) -> Vec<Problem> {
        let mut sweep = Sweep::default();
        diags
            .iter()
            .map(|d| locate_one(text, lines, &mut sweep, d))
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
                    Diagnostic::error(swarf_syntax::Span::new(start, end), "E-TEST", "test")
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
