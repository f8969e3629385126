//! The modal machine: reads each block, checks it, and executes it in a fixed order.

use glam::DVec3;
use swarf_syntax::codes::{self, Code};
use swarf_syntax::{Block, Diagnostic, Dialect, Program, Quantity, Word, WordForm};

use crate::{Axis, Canon, Setup, Sink, Source};

/// Whether a run has more blocks to execute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The budget ran out; call [`Interpreter::step`] again to go on.
    Running,
    /// The program ended (M02/M30, end of text, or a limit was hit).
    Finished,
}

/// Resource limits that stop runaway programs with a diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most blocks executed in one run.
    pub max_blocks: u64,
}

/// The motion mode of modal group 01 that the interpreter can run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum MotionMode {
    Rapid,
    Linear,
    /// G02 (clockwise) or G03 (counter-clockwise) seen from the plane normal's positive end.
    Arc {
        ccw: bool,
    },
}

/// What one G code does, for the codes the interpreter runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum GAction {
    Motion(Option<MotionMode>),
    Plane(Axis),
    Absolute(bool),
    Metric(bool),
    WorkOffset(&'static str),
    Dwell,
    /// Cancels a mode the interpreter cannot enter yet, so it has nothing to do.
    Cancel,
}

/// Modal group numbers, for the two-codes-in-one-group check.
fn group(action: GAction) -> Option<u8> {
    match action {
        GAction::Motion(_) => Some(1),
        GAction::Plane(_) => Some(2),
        GAction::Absolute(_) => Some(3),
        GAction::Metric(_) => Some(6),
        GAction::WorkOffset(_) => Some(14),
        GAction::Dwell | GAction::Cancel => None,
    }
}

/// What the interpreter does for a G code given as ten times its number (`G54.1` is 541);
/// `None` for the codes of the dialect's table that it does not run yet.
fn g_action(dialect: Dialect, code10: i64) -> Option<GAction> {
    let syntec = dialect == Dialect::Syntec;
    Some(match code10 {
        0 => GAction::Motion(Some(MotionMode::Rapid)),
        10 => GAction::Motion(Some(MotionMode::Linear)),
        800 => GAction::Motion(None),
        40 => GAction::Dwell,
        20 => GAction::Motion(Some(MotionMode::Arc { ccw: false })),
        30 => GAction::Motion(Some(MotionMode::Arc { ccw: true })),
        170 => GAction::Plane(Axis::Z),
        180 => GAction::Plane(Axis::Y),
        190 => GAction::Plane(Axis::X),
        900 => GAction::Absolute(true),
        910 => GAction::Absolute(false),
        200 if !syntec => GAction::Metric(false),
        210 if !syntec => GAction::Metric(true),
        700 if syntec => GAction::Metric(false),
        710 if syntec => GAction::Metric(true),
        540 => GAction::WorkOffset("G54"),
        550 => GAction::WorkOffset("G55"),
        560 => GAction::WorkOffset("G56"),
        570 => GAction::WorkOffset("G57"),
        580 => GAction::WorkOffset("G58"),
        590 => GAction::WorkOffset("G59"),
        // Cancel codes of modes that cannot be active yet.
        150 | 400 | 490 | 500 | 501 | 670 | 690 | 940 | 970 | 640 | 611 | 610 => GAction::Cancel,
        _ => return None,
    })
}

/// Interprets a parsed program in bounded steps.
#[derive(Debug, Clone)]
pub struct Interpreter {
    setup: Setup,
    dialect: Dialect,
    next_block: usize,
    executed: u64,
    finished: bool,
    /// Tool-tip position in the machine frame, millimetres.
    position: DVec3,
    motion: Option<MotionMode>,
    plane: Axis,
    absolute: bool,
    metric: bool,
    work_offset: DVec3,
    feed_mm_per_min: f64,
    spindle_rpm: f64,
    tool: u32,
    diagnostics: Vec<Diagnostic>,
    /// Whether the least-increment note has been given in this run.
    noted_least_increment: bool,
}

impl Interpreter {
    /// A machine at power-on for `dialect`, at the origin, with `setup`'s offsets.
    pub fn new(setup: Setup, dialect: Dialect) -> Self {
        let work_offset = setup.work_offset("G54");
        Interpreter {
            setup,
            dialect,
            next_block: 0,
            executed: 0,
            finished: false,
            position: DVec3::ZERO,
            motion: Some(MotionMode::Rapid),
            plane: Axis::Z,
            absolute: true,
            metric: true,
            work_offset,
            feed_mm_per_min: 0.0,
            spindle_rpm: 0.0,
            tool: 0,
            diagnostics: Vec::new(),
            noted_least_increment: false,
        }
    }

    /// The limits this run stops at.
    pub fn limits(&self) -> Limits {
        Limits {
            max_blocks: self.setup.machine.max_blocks,
        }
    }

    /// Diagnostics found while executing so far.
    pub fn diagnostics(&self) -> &[Diagnostic] {
        &self.diagnostics
    }

    /// Takes the diagnostics found so far, leaving none.
    pub fn take_diagnostics(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.diagnostics)
    }

    /// The tool-tip position in the machine frame.
    pub fn position(&self) -> DVec3 {
        self.position
    }

    /// How many blocks have been executed.
    pub fn executed_blocks(&self) -> u64 {
        self.executed
    }

    /// Index of the next block to execute (progress through the program).
    pub fn next_block(&self) -> usize {
        self.next_block
    }

    /// Executes at most `budget` blocks of `program`, sending events to `sink`.
    pub fn step(&mut self, program: &Program, sink: &mut dyn Sink, budget: usize) -> Status {
        for _ in 0..budget {
            if self.finished {
                return Status::Finished;
            }
            let Some(block) = program.blocks.get(self.next_block) else {
                self.finished = true;
                return Status::Finished;
            };
            if self.executed >= self.setup.machine.max_blocks {
                self.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-RUNAWAY",
                    format!(
                        "execution stopped after {} blocks (the limit in [machine] max_blocks)",
                        self.executed
                    ),
                ));
                self.finished = true;
                return Status::Finished;
            }
            let source = Source {
                block: u32::try_from(self.next_block).unwrap_or(u32::MAX),
                line: block.line.saturating_add(1),
            };
            self.next_block += 1;
            self.executed += 1;
            if !block.has_error {
                self.execute(block, source, sink);
            }
        }
        if self.finished || self.next_block >= program.blocks.len() {
            self.finished = true;
            Status::Finished
        } else {
            Status::Running
        }
    }

    fn mm(&self, value: f64) -> f64 {
        if self.metric { value } else { value * 25.4 }
    }

    /// Whether numbers without a decimal point are read in mm (calculator-type input).
    fn calculator(&self) -> bool {
        self.setup
            .machine
            .calculator_input
            .unwrap_or(self.dialect.rules().calculator_input)
    }

    /// A coordinate or distance word in millimetres, read with the dialect's decimal-point rule.
    fn length(&self, word: &Word) -> f64 {
        self.mm(self
            .dialect
            .read(word, Quantity::Length, self.calculator(), !self.metric))
    }

    /// Notes, once per run, that a length without a decimal point is read in least increments.
    fn note_least_increment(&mut self, words: &[Option<&Word>]) {
        if self.noted_least_increment || self.calculator() {
            return;
        }
        let Some(w) = words
            .iter()
            .flatten()
            .find(|w| !w.has_point && w.expr.is_none() && w.value != 0.0)
        else {
            return;
        };
        self.noted_least_increment = true;
        let (unit, units) = if self.metric {
            ("0.001 mm", "mm")
        } else {
            ("0.0001 inch", "inch")
        };
        let read = self.dialect.read(w, Quantity::Length, false, !self.metric);
        self.diagnostics.push(Diagnostic::note(
            w.span,
            "N-LEAST-INCREMENT",
            format!(
                "`{}{}` has no decimal point: {} reads it in least input increments ({unit}) as {read} {units}; write `{}{}.` for {} {units} (or set `calculator_input = true` under [machine])",
                w.letter(),
                w.value,
                self.dialect.label(),
                w.letter(),
                w.value,
                w.value
            ),
        ));
    }

    /// Executes one block: check the words, then modes, feed/speed/tool, motion, then M codes.
    fn execute(&mut self, block: &Block, source: Source, sink: &mut dyn Sink) {
        let mut actions: Vec<(GAction, &Word)> = Vec::new();
        let mut axes: [Option<&Word>; 3] = [None; 3];
        let mut offsets: [Option<&Word>; 3] = [None; 3];
        let mut radius: Option<&Word> = None;
        // F, S and T, in that order.
        let mut settings: [Option<&Word>; 3] = [None; 3];
        let mut runnable = true;
        if block.has_macro() {
            self.diagnostics.push(Diagnostic::warning(
                block.span,
                "W-NOT-INTERPRETED",
                "macro statements and variables are not executed yet; this block is not run",
            ));
            return;
        }
        for word in &block.words {
            match (word.letter, word.form) {
                (_, WordForm::Comma) => self.diagnostics.push(Diagnostic::warning(
                    word.span,
                    "W-NOT-INTERPRETED",
                    format!(
                        "`,{}` (chamfer/corner rounding) is not drawn yet: the corner is drawn sharp",
                        word.letter()
                    ),
                )),
                (_, WordForm::Indexed(n)) => self.diagnostics.push(Diagnostic::warning(
                    word.span,
                    "W-NOT-INTERPRETED",
                    format!("`{}{n}=` is not interpreted yet and is ignored", word.letter()),
                )),
                (b'G', _) => {
                    let code = Code::from_value(b'G', word.value);
                    let action = code.and_then(|c| g_action(self.dialect, i64::from(c.tenths)));
                    match (action, code.and_then(|c| codes::lookup(self.dialect, c))) {
                        (Some(action), _) => {
                            // Two codes of one group: the last one wins (the parser has
                            // already warned, or refused the block where the dialect alarms).
                            if let Some(g) = group(action)
                                && let Some(at) =
                                    actions.iter().position(|(a, _)| group(*a) == Some(g))
                            {
                                actions.remove(at);
                            }
                            actions.push((action, word));
                        }
                        (None, Some(def)) => {
                            self.diagnostics.push(Diagnostic::warning(
                                word.span,
                                "W-NOT-INTERPRETED",
                                format!(
                                    "{} ({}) is not interpreted yet; this block is not run",
                                    def.code, def.name
                                ),
                            ));
                            runnable = false;
                        }
                        (None, None) => {
                            self.diagnostics.push(Diagnostic::error(
                                word.span,
                                "E-UNKNOWN-CODE",
                                format!(
                                    "G{} is not a code of {}",
                                    fmt_code(word.value),
                                    self.dialect.label()
                                ),
                            ));
                            runnable = false;
                        }
                    }
                }
                (b'X' | b'Y' | b'Z', _) => {
                    runnable &= self.store(&mut axes[usize::from(word.letter - b'X')], word);
                }
                (b'I' | b'J' | b'K', _) => {
                    runnable &= self.store(&mut offsets[usize::from(word.letter - b'I')], word);
                }
                (b'R', _) => runnable &= self.store(&mut radius, word),
                (b'F', _) => runnable &= self.store(&mut settings[0], word),
                (b'S', _) => runnable &= self.store(&mut settings[1], word),
                (b'T', _) => runnable &= self.store(&mut settings[2], word),
                (b'M' | b'P', _) => {}
                _ => self.diagnostics.push(Diagnostic::warning(
                    word.span,
                    "W-WORD-IGNORED",
                    format!(
                        "address `{}` is not interpreted yet and is ignored",
                        word.letter()
                    ),
                )),
            }
        }
        if !runnable {
            return;
        }
        let lengths: Vec<Option<&Word>> = axes
            .iter()
            .chain(&offsets)
            .chain([&radius])
            .copied()
            .collect();
        self.note_least_increment(&lengths);
        for (action, w) in settings.iter().enumerate() {
            let Some(w) = w else { continue };
            if w.value < 0.0 {
                self.diagnostics.push(Diagnostic::error(
                    w.span,
                    "E-NEGATIVE",
                    format!("`{}` cannot be negative", w.letter()),
                ));
                return;
            }
            match action {
                0 => self.feed_mm_per_min = w.value,
                1 => self.spindle_rpm = w.value,
                _ => self.tool = w.value.round() as u32,
            }
        }
        // Units first: the feed and the axis words of this block are read in the new units.
        let mut dwell = None;
        let mut motion = self.motion;
        for (action, word) in &actions {
            match *action {
                GAction::Metric(m) => self.metric = m,
                GAction::Absolute(a) => self.absolute = a,
                GAction::WorkOffset(name) => self.work_offset = self.setup.work_offset(name),
                GAction::Motion(m) => motion = m,
                GAction::Dwell => dwell = Some(*word),
                GAction::Plane(p) => self.plane = p,
                GAction::Cancel => {}
            }
        }
        if settings[0].is_some() {
            self.feed_mm_per_min = self.mm(self.feed_mm_per_min);
        }
        if let Some(g4) = dwell {
            self.dwell(block, g4, source, sink);
        }
        self.motion = motion;
        let arc = match motion {
            Some(MotionMode::Arc { ccw }) => Some(ccw),
            _ => None,
        };
        let has_center = offsets.iter().any(Option::is_some) || radius.is_some();
        // With a motion or one-shot code in the block the parser has already said which words
        // are unused; this covers the words a modal motion does not take.
        let checked = actions
            .iter()
            .any(|(a, _)| matches!(a, GAction::Motion(_) | GAction::Dwell));
        if (arc.is_none() || dwell.is_some()) && !checked {
            for w in offsets.iter().flatten().chain(radius.iter()) {
                self.diagnostics.push(Diagnostic::warning(
                    w.span,
                    "W-WORD-IGNORED",
                    format!(
                        "address `{}` is only used by G02/G03 here and is ignored",
                        w.letter()
                    ),
                ));
            }
        }
        if dwell.is_none() {
            if let Some(ccw) = arc.filter(|_| has_center) {
                self.arc_to(block, axes, offsets, radius, ccw, source, sink);
            } else if axes.iter().any(Option::is_some) {
                self.move_to(block, axes, source, sink);
            }
        }
        self.m_codes(block, source, sink);
    }

    /// Puts `word` in its slot; a second word for the same slot is an error (`false`).
    fn store<'w>(&mut self, slot: &mut Option<&'w Word>, word: &'w Word) -> bool {
        if slot.is_some() {
            self.diagnostics.push(Diagnostic::error(
                word.span,
                "E-WORD-TWICE",
                format!("address `{}` appears twice in the block", word.letter()),
            ));
            return false;
        }
        *slot = Some(word);
        true
    }

    fn dwell(&mut self, block: &Block, g4: &Word, source: Source, sink: &mut dyn Sink) {
        let secs = if let Some(p) = block.word(b'P') {
            self.dialect.read(p, Quantity::DwellP, false, false)
        } else if let Some(x) = block.word(b'X').or(block.word(b'U')) {
            self.dialect.read(x, Quantity::DwellX, false, false)
        } else {
            self.diagnostics.push(Diagnostic::error(
                g4.span,
                "E-MISSING-WORD",
                "G04 needs the dwell time in P or X",
            ));
            return;
        };
        if secs < 0.0 {
            self.diagnostics.push(Diagnostic::error(
                g4.span,
                "E-NEGATIVE",
                "a dwell time cannot be negative",
            ));
            return;
        }
        sink.emit(source, &Canon::Dwell { secs });
    }

    fn move_to(
        &mut self,
        block: &Block,
        axes: [Option<&Word>; 3],
        source: Source,
        sink: &mut dyn Sink,
    ) {
        let Some(mode) = self.motion else {
            let span = axes.iter().flatten().next().map_or(block.span, |w| w.span);
            self.diagnostics.push(Diagnostic::error(
                span,
                "E-NO-MOTION-MODE",
                "axis words with no motion mode active (after G80): add G00 or G01",
            ));
            return;
        };
        let to = self.target(axes);
        let event = match mode {
            MotionMode::Rapid => Canon::Rapid { to },
            // Syntec runs an arc block with neither R nor I/J/K as G01 (the parser has
            // said so with W-ARC-AS-LINE).
            MotionMode::Arc { .. } if self.dialect == Dialect::Syntec => Canon::Feed {
                to,
                feed_mm_per_min: self.feed_mm_per_min,
            },
            MotionMode::Arc { .. } => {
                self.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-ARC-CENTER",
                    "G02/G03 needs the centre (I, J, K) or the radius (R)",
                ));
                return;
            }
            MotionMode::Linear => {
                if self.feed_mm_per_min <= 0.0 {
                    self.diagnostics.push(Diagnostic::error(
                        block.span,
                        "E-NO-FEED",
                        "G01 needs a feed rate: program F before or in this block",
                    ));
                }
                Canon::Feed {
                    to,
                    feed_mm_per_min: self.feed_mm_per_min,
                }
            }
        };
        self.position = to;
        sink.emit(source, &event);
    }

    /// The machine-frame end point of a move programmed with `axes`.
    fn target(&self, axes: [Option<&Word>; 3]) -> DVec3 {
        let work = self.position - self.work_offset;
        let mut target = work;
        for (i, word) in axes.iter().enumerate() {
            if let Some(w) = word {
                let v = self.length(w);
                target[i] = if self.absolute { v } else { work[i] + v };
            }
        }
        target + self.work_offset
    }

    /// G02/G03: centre from I/J/K (incremental from the start) or from R (negative R for
    /// more than half a circle); the axis words off the plane make it helical.
    #[allow(clippy::too_many_arguments)]
    fn arc_to(
        &mut self,
        block: &Block,
        axes: [Option<&Word>; 3],
        offsets: [Option<&Word>; 3],
        radius: Option<&Word>,
        ccw: bool,
        source: Source,
        sink: &mut dyn Sink,
    ) {
        let (u, v) = plane_axes(self.plane);
        let from = self.position;
        let to = self.target(axes);
        let mut center = from;
        if let Some(r) = radius.filter(|_| offsets.iter().all(Option::is_none)) {
            let r_mm = self.length(r);
            let (du, dv) = (to[u] - from[u], to[v] - from[v]);
            let chord = du.hypot(dv);
            if chord < 1e-9 {
                self.diagnostics.push(Diagnostic::error(
                    r.span,
                    "E-ARC-CENTER",
                    "an arc programmed with R cannot end where it starts: use I/J/K for a full circle",
                ));
                return;
            }
            let half = chord / 2.0;
            if r_mm.abs() + self.setup.machine.arc_tolerance_mm < half {
                self.diagnostics.push(Diagnostic::error(
                    r.span,
                    "E-ARC-RADIUS",
                    format!(
                        "R{} is smaller than half the distance to the end point ({half:.4} mm)",
                        r.value
                    ),
                ));
                return;
            }
            let h = (r_mm * r_mm - half * half).max(0.0).sqrt();
            // Left of the chord for a short counter-clockwise arc, right for a short clockwise one.
            let side = if ccw == (r_mm > 0.0) { 1.0 } else { -1.0 };
            center[u] = from[u] + du / 2.0 - side * h * dv / chord;
            center[v] = from[v] + dv / 2.0 + side * h * du / chord;
        } else {
            for (i, w) in offsets.iter().enumerate() {
                if let Some(w) = w {
                    if i == u || i == v {
                        center[i] = from[i] + self.length(w);
                    } else {
                        self.diagnostics.push(Diagnostic::warning(
                            w.span,
                            "W-WORD-IGNORED",
                            format!(
                                "`{}` is not a centre offset in the selected plane and is ignored",
                                w.letter()
                            ),
                        ));
                    }
                }
            }
            if let Some(r) = radius {
                self.diagnostics.push(Diagnostic::warning(
                    r.span,
                    "W-WORD-IGNORED",
                    "R is ignored when the centre is given with I/J/K",
                ));
            }
            let r0 = (from[u] - center[u]).hypot(from[v] - center[v]);
            let r1 = (to[u] - center[u]).hypot(to[v] - center[v]);
            if r0 < 1e-9 {
                self.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-ARC-CENTER",
                    "the arc's centre is at its start point",
                ));
                return;
            }
            if (r0 - r1).abs() > self.setup.machine.arc_tolerance_mm {
                let alarm = if self.dialect == Dialect::Syntec {
                    " (alarm COR-006)"
                } else {
                    ""
                };
                self.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-ARC-RADIUS",
                    format!(
                        "the end point is {:.4} mm off the arc: start radius {r0:.4} mm, end radius {r1:.4} mm{alarm}",
                        (r0 - r1).abs()
                    ),
                ));
                return;
            }
        }
        if self.feed_mm_per_min <= 0.0 {
            self.diagnostics.push(Diagnostic::error(
                block.span,
                "E-NO-FEED",
                "G02/G03 needs a feed rate: program F before or in this block",
            ));
        }
        self.position = to;
        sink.emit(
            source,
            &Canon::Arc {
                to,
                center,
                axis: self.plane,
                ccw,
                turns: 0,
                feed_mm_per_min: self.feed_mm_per_min,
            },
        );
    }

    fn m_codes(&mut self, block: &Block, source: Source, sink: &mut dyn Sink) {
        for word in block.words.iter().filter(|w| w.letter == b'M') {
            let event = match code10(word.value) {
                Some(0) => Canon::Pause { optional: false },
                Some(10) => Canon::Pause { optional: true },
                Some(20 | 300) => {
                    self.finished = true;
                    Canon::End
                }
                Some(30) => Canon::Spindle {
                    clockwise: Some(true),
                    rpm: self.spindle_rpm,
                },
                Some(40) => Canon::Spindle {
                    clockwise: Some(false),
                    rpm: self.spindle_rpm,
                },
                Some(50) => Canon::Spindle {
                    clockwise: None,
                    rpm: 0.0,
                },
                Some(60) => Canon::ToolChange { tool: self.tool },
                Some(80) => Canon::Coolant { on: true },
                Some(90) => Canon::Coolant { on: false },
                _ => {
                    // Codes outside the dialect's list were reported by the parser.
                    if let Some(def) = Code::from_value(b'M', word.value)
                        .and_then(|c| codes::lookup(self.dialect, c))
                    {
                        self.diagnostics.push(Diagnostic::warning(
                            word.span,
                            "W-NOT-INTERPRETED",
                            format!("{} ({}) is not interpreted yet", def.code, def.name),
                        ));
                    }
                    continue;
                }
            };
            sink.emit(source, &event);
        }
    }
}

/// Ten times a code number when it has at most one decimal (`54.1` → 541).
fn code10(value: f64) -> Option<i64> {
    let scaled = value * 10.0;
    let rounded = scaled.round();
    ((scaled - rounded).abs() < 1e-6 && rounded.abs() < 1e9 && rounded >= 0.0)
        .then_some(rounded as i64)
}

/// A code number as written in messages: `0` → `00`, `54.1` stays.
fn fmt_code(value: f64) -> String {
    if value.fract() == 0.0 && (0.0..10.0).contains(&value) {
        format!("0{value}")
    } else {
        format!("{value}")
    }
}

/// Runs a whole program with `setup` and returns the execution diagnostics.
pub fn run(program: &Program, setup: Setup, sink: &mut dyn Sink) -> Vec<Diagnostic> {
    let mut interp = Interpreter::new(setup, program.dialect);
    while interp.step(program, sink, 4096) == Status::Running {}
    interp.take_diagnostics()
}

/// Indices of the two in-plane axes (u, v) of a plane, ordered so that u × v points along the
/// plane normal: X,Y for G17; Z,X for G18; Y,Z for G19.
fn plane_axes(normal: Axis) -> (usize, usize) {
    match normal {
        Axis::Z => (0, 1),
        Axis::Y => (2, 0),
        Axis::X => (1, 2),
    }
}
