//! Executing one block's words, in the controls' order: feed/speed/tool, then the modal codes
//! (units first, so the block's numbers are read in the new unit), coordinate-system codes,
//! one-shot codes, motion, then M codes.

use glam::{DVec2, DVec3};
use smallvec::SmallVec;
use swarf_syntax::codes::{self, Code, Group};
use swarf_syntax::{Block, Diagnostic, Dialect, Program, Quantity, Word, WordForm};

use crate::machine::{Flow, Interpreter, MotionCounter, find};
use crate::macros::argument_variable;
use crate::state::{FeedMode, ModalMacro, MotionMode, Polar, Rotation, Scaling, State, plane_axes};
use crate::{Axis, Canon, PlaneArc, Sink, Source, StrokeZone, plane_length};

/// What one G code does.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Action {
    Motion(Option<MotionMode>),
    Plane(Axis),
    Absolute(bool),
    Metric(bool),
    WorkOffset,
    Dwell,
    ExactStop,
    PathMode(u32),
    FeedMode(FeedMode),
    SpindleMode(bool),
    ReturnLevel(bool),
    Polar(bool),
    Rotation(bool),
    Scaling(bool),
    Mirror(bool),
    Local,
    Machine,
    SetPosition,
    ResetShift,
    Reference(u8),
    FromReference,
    /// LNC G168: rotation by a measured angle from the setup.
    MeasuredRotation,
    /// LinuxCNC G28.1/G30.1: the current position becomes reference point n.
    StoreReference(usize),
    DataInput,
    LengthComp(Option<bool>),
    /// LinuxCNC G43.1/G43.2: a length offset given in the block's axis words.
    DynamicLength,
    CutterComp(u32),
    MacroCall,
    ModalMacro(bool),
    /// G31 skip: drawn as the full programmed move.
    Probe,
    /// Syntec G37 (`false`, Z in program coordinates) and G37.1 (`true`, Z in machine
    /// coordinates): tool-length measurement, drawn as the return to the reference point and
    /// the full measuring move.
    Measure(bool),
    /// Syntec G92.1: the program zero preset at X Y Z from the work origin, the plane turned by R.
    PresetZero,
    /// Syntec G134, G135, G136, G137.1: the stored canned cycle at each point of a hole pattern.
    Pattern(u32),
    StrokeLimit(bool),
    /// LinuxCNC G90.1 (`true`) / G91.1: whether arc centres I/J/K are absolute.
    ArcCentres(bool),
    /// A mode with nothing to draw (cancels, lathe diameter mode).
    Nothing,
}

/// The action of a code in `dialect`, or `None` for the codes the interpreter does not run yet.
fn action(dialect: Dialect, group: Group, tenths: u32) -> Option<Action> {
    let syntec = dialect == Dialect::Syntec;
    let linuxcnc = dialect == Dialect::LinuxCnc;
    Some(match (group, tenths) {
        (Group::Motion, 0) => Action::Motion(Some(MotionMode::Rapid)),
        (Group::Motion, 10) => Action::Motion(Some(MotionMode::Linear)),
        (Group::Motion, 20) => Action::Motion(Some(MotionMode::Arc { ccw: false })),
        (Group::Motion, 30) => Action::Motion(Some(MotionMode::Arc { ccw: true })),
        (Group::Motion, 330) => Action::Motion(Some(MotionMode::Thread)),
        (Group::Motion | Group::Cycle, 800) => Action::Motion(None),
        (Group::Motion | Group::Cycle, t) if crate::cycles::runs(dialect, t) => {
            Action::Motion(Some(MotionMode::Cycle(t)))
        }
        (_, 40) => Action::Dwell,
        (_, 90) if !linuxcnc => Action::ExactStop,
        (Group::Plane, 170) => Action::Plane(Axis::Z),
        (Group::Plane, 180) => Action::Plane(Axis::Y),
        (Group::Plane, 190) => Action::Plane(Axis::X),
        (Group::Distance, 900) => Action::Absolute(true),
        (Group::Distance, 910) => Action::Absolute(false),
        (Group::Units, 200) if !syntec => Action::Metric(false),
        (Group::Units, 210) if !syntec => Action::Metric(true),
        (Group::Units, 700) if syntec => Action::Metric(false),
        (Group::Units, 710) if syntec => Action::Metric(true),
        (Group::WorkOffset, _) => Action::WorkOffset,
        (Group::PathMode, t) => Action::PathMode(t),
        (Group::FeedMode, 930) => Action::FeedMode(FeedMode::InverseTime),
        (Group::FeedMode, 940) => Action::FeedMode(FeedMode::PerMinute),
        (Group::FeedMode, 950) => Action::FeedMode(FeedMode::PerRevolution),
        // GSK's examples use G98/G99 for feed per minute / per revolution.
        (Group::FeedMode, 980) => Action::FeedMode(FeedMode::PerMinute),
        (Group::FeedMode, 990) => Action::FeedMode(FeedMode::PerRevolution),
        (Group::SpindleMode, 960) => Action::SpindleMode(true),
        (Group::SpindleMode, 970) => Action::SpindleMode(false),
        (Group::ReturnLevel, 980) => Action::ReturnLevel(true),
        (Group::ReturnLevel, 990) => Action::ReturnLevel(false),
        (Group::Polar, 150) => Action::Polar(false),
        (Group::Polar, 160) => Action::Polar(true),
        (Group::Rotation, 680) => Action::Rotation(true),
        (Group::Rotation, 690) => Action::Rotation(false),
        (Group::Rotation, 1680) => Action::MeasuredRotation,
        (Group::Scaling, 500) => Action::Scaling(false),
        (Group::Scaling, 510) => Action::Scaling(true),
        (Group::Mirror, 501) => Action::Mirror(false),
        (Group::Mirror, 511) => Action::Mirror(true),
        (Group::StrokeLimit, 220) => Action::StrokeLimit(true),
        (Group::StrokeLimit, 230) => Action::StrokeLimit(false),
        (Group::LengthComp, 430) => Action::LengthComp(Some(true)),
        (Group::LengthComp, 440) => Action::LengthComp(Some(false)),
        (Group::LengthComp, 490) => Action::LengthComp(None),
        (Group::LengthComp, 431 | 432) if linuxcnc => Action::DynamicLength,
        (Group::CutterComp, t) => Action::CutterComp(t),
        // G45–G48 change the block's move (`position::offset_line`, `offset_arc`).
        (Group::NonModal, 450 | 460 | 470 | 480)
            if matches!(dialect, Dialect::Fanuc | Dialect::Syntec) =>
        {
            Action::Nothing
        }
        (Group::MacroModal, 660) => Action::ModalMacro(true),
        (Group::MacroModal, 670) => Action::ModalMacro(false),
        (Group::ArcDistance, 901) => Action::ArcCentres(true),
        (Group::ArcDistance, 911) => Action::ArcCentres(false),
        (Group::LatheMode, _) => Action::Nothing,
        (Group::NonModal, 520) => Action::Local,
        (Group::NonModal, 530) => Action::Machine,
        (Group::NonModal, 920) => Action::SetPosition,
        (Group::NonModal, 921 | 922) if linuxcnc => Action::ResetShift,
        (Group::NonModal, 280) => Action::Reference(1),
        (Group::NonModal, 300) => Action::Reference(2),
        (Group::NonModal, 290) => Action::FromReference,
        (Group::NonModal, 281) if linuxcnc => Action::StoreReference(1),
        (Group::NonModal, 301) if linuxcnc => Action::StoreReference(2),
        (Group::NonModal, 100) => Action::DataInput,
        (Group::NonModal, 650) => Action::MacroCall,
        (Group::NonModal, 310) if !linuxcnc => Action::Probe,
        (Group::NonModal, 370) if syntec => Action::Measure(false),
        (Group::NonModal, 371) if syntec => Action::Measure(true),
        (Group::NonModal, 921) if syntec => Action::PresetZero,
        (Group::NonModal, t @ (1340 | 1350 | 1360 | 1371)) if syntec => Action::Pattern(t),
        _ => return None,
    })
}

/// The axis words of a block, in millimetres where given.
type Axes<'w> = [Option<&'w Word>; 3];

/// The largest repeat or turn count a word may give (the manuals' 9999).
pub(crate) const MAX_COUNT: f64 = 9999.0;

/// The diagnostic for a count word out of 1–9999 (the count is clamped into the range).
pub(crate) fn count_range(w: &Word, what: &str) -> Diagnostic {
    Diagnostic::error(
        w.span,
        "E-NUMBER-RANGE",
        format!(
            "`{}{}` is out of range: the number of {what} is 1 to 9999 (it is clamped)",
            w.letter(),
            w.value
        ),
    )
}

/// A macro call's repeat count L (1 when absent), clamped to 0–9999 with a diagnostic.
fn repeat_count(st: &mut State, l: Option<&Word>) -> u32 {
    let Some(l) = l else {
        return 1;
    };
    if !(0.0..=MAX_COUNT).contains(&l.value) {
        st.diagnostics.push(count_range(l, "repeats"));
    }
    l.value.clamp(0.0, MAX_COUNT) as u32
}

/// Executes `words` (the block's words with expressions evaluated); with a G22 stroke limit
/// active, every move of the block is checked against it.
pub(crate) fn execute(
    it: &mut Interpreter,
    program: &Program,
    at: usize,
    block: &Block,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Flow {
    let stroke = it.st.stroke_zone.filter(|_| it.st.stroke_check);
    let travel = it.st.setup.machine.travel_mm.map(|[min, max]| StrokeZone {
        min: DVec3::from_array(min),
        max: DVec3::from_array(max),
        inside_forbidden: false,
    });
    if stroke.is_none() && travel.is_none() {
        return execute_block(it, program, at, block, words, source, sink);
    }
    let mut guard = StrokeGuard {
        inner: sink,
        zones: [stroke, travel],
        from: it.st.position + tool_tip_shift(&it.st),
        gauge: tool_tip_shift(&it.st),
        broken: [false; 2],
    };
    let flow = execute_block(it, program, at, block, words, source, &mut guard);
    if guard.broken[0] {
        let what = if stroke.is_some_and(|z| z.inside_forbidden) {
            "enters the G22 protected zone"
        } else {
            "leaves the G22 stroke limits"
        };
        it.st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-STROKE-LIMIT",
            format!(
                "this move {what} (machine coordinates); the control stops with an overtravel alarm"
            ),
        ));
    }
    if guard.broken[1] {
        it.st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-OVERTRAVEL",
            "this move leaves the machine's travel (the setup's `travel_mm`); the machine stops with an overtravel alarm",
        ));
    }
    flow
}

/// Checks the moves of one block against the G22 stroke limit and the machine's travel before
/// passing them on.
struct StrokeGuard<'s> {
    inner: &'s mut dyn Sink,
    /// The G22 zone and the machine's travel, where they apply.
    zones: [Option<StrokeZone>; 2],
    /// The machine position (gauge line) before the next move.
    from: DVec3,
    /// The gauge line's offset from the tool tip.
    gauge: DVec3,
    /// Which of `zones` a move broke.
    broken: [bool; 2],
}

impl Sink for StrokeGuard<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        let points = match event {
            Canon::Rapid { to } | Canon::Feed { to, .. } => vec![*to + self.gauge],
            Canon::Arc {
                to,
                center,
                axis,
                ccw,
                turns,
                ..
            } => arc_points(self.from - self.gauge, *to, *center, *axis, *ccw, *turns)
                .into_iter()
                .map(|p| p + self.gauge)
                .collect(),
            _ => Vec::new(),
        };
        for p in points {
            for (zone, broken) in self.zones.iter().zip(&mut self.broken) {
                if let Some(zone) = zone {
                    *broken |= zone.violated_by(self.from, p);
                }
            }
            self.from = p;
        }
        self.inner.emit(source, event);
    }

    fn full(&self) -> bool {
        self.inner.full()
    }

    fn origin(&mut self, at: DVec3) {
        self.inner.origin(at);
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.inner.programmed(source, event);
    }

    fn stroke_zone(&mut self, source: Source, zone: Option<&StrokeZone>) {
        self.inner.stroke_zone(source, zone);
    }
}

/// Points along an arc event from `from` (excluding it, ending at `to`), 64 per turn.
fn arc_points(
    from: DVec3,
    to: DVec3,
    center: DVec3,
    axis: Axis,
    ccw: bool,
    turns: u32,
) -> Vec<DVec3> {
    let arc = PlaneArc::new(from, to, center, axis, ccw, turns);
    let n = ((arc.sweep.abs() / std::f64::consts::TAU * 64.0).ceil() as usize).clamp(1, 100_000);
    arc.points(from, to, n)
}

/// Executes one block's words.
fn execute_block(
    it: &mut Interpreter,
    program: &Program,
    at: usize,
    block: &Block,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Flow {
    let _ = program;
    if it.shortcut
        && let Some(flow) = plain_move(&mut it.st, block, words, source, sink)
    {
        return flow;
    }
    let dialect = it.st.dialect;
    let mut actions: SmallVec<[(Action, &Word); 4]> = SmallVec::new();
    let mut runnable = true;
    for word in words
        .iter()
        .filter(|w| w.letter == b'G' && w.form == WordForm::Plain)
    {
        let Some(def) = Code::from_value(b'G', word.value).and_then(|c| codes::lookup(dialect, c))
        else {
            continue;
        };
        match action(dialect, def.group, def.code.tenths) {
            Some(a) => {
                // Two codes of one group: the last one wins (the parser has warned, or refused
                // the block where the dialect alarms).
                if def.group.exclusive()
                    && let Some(i) = actions.iter().position(|(b, w)| {
                        Code::from_value(b'G', w.value)
                            .and_then(|c| codes::lookup(dialect, c))
                            .is_some_and(|d| d.group == def.group)
                            && *b != Action::Dwell
                    })
                {
                    actions.remove(i);
                }
                actions.push((a, word));
            }
            None if def.documented != codes::Documented::Full => {
                // LNC's two-stage cycles, G36–G39, G77/G78 …: the manual lists the code but
                // not its format, so nothing can be drawn from it.
                it.st.diagnostics.push(Diagnostic::warning(
                    word.span,
                    "W-NOT-DOCUMENTED",
                    format!(
                        "{} ({}) is only listed in the {} manual, which does not document its format or motion; this block is not run",
                        def.code,
                        def.name,
                        dialect.label()
                    ),
                ));
                runnable = false;
            }
            None => {
                it.st.diagnostics.push(Diagnostic::warning(
                    word.span,
                    "W-NOT-INTERPRETED",
                    format!(
                        "{} ({}) is not interpreted yet; this block is not run",
                        def.code, def.name
                    ),
                ));
                runnable = false;
            }
        }
    }
    for word in words {
        match word.form {
            WordForm::Comma if matches!(word.letter, b'C' | b'R') => {}
            WordForm::Comma => it.st.diagnostics.push(Diagnostic::warning(
                word.span,
                "W-NOT-INTERPRETED",
                format!(
                    "`,{}` (chamfer/corner rounding) is not drawn yet: the corner is drawn sharp",
                    word.letter()
                ),
            )),
            // Syntec's `F2=`: the retract feed of G81 (read by the cycle).
            WordForm::Indexed(2) if word.letter == b'F' && dialect == Dialect::Syntec => {}
            WordForm::Indexed(n) => it.st.diagnostics.push(Diagnostic::warning(
                word.span,
                "W-NOT-INTERPRETED",
                format!(
                    "`{}{n}=` is not interpreted yet and is ignored",
                    word.letter()
                ),
            )),
            WordForm::Plain => {}
        }
    }
    if !runnable {
        return Flow::Next;
    }
    let has = |a: fn(&Action) -> bool| actions.iter().any(|(x, _)| a(x));
    // G65: a macro call takes the block's words as arguments.
    if let Some((_, g65)) = actions.iter().find(|(a, _)| matches!(a, Action::MacroCall)) {
        return macro_call(it, at, block, words, g65);
    }
    if let Some((_, g66)) = actions
        .iter()
        .find(|(a, _)| matches!(a, Action::ModalMacro(true)))
    {
        let args = arguments(&it.st, words);
        // L: how many times the macro runs after each move.
        let repeats = repeat_count(&mut it.st, find(words, b'L'));
        match find(words, b'P') {
            Some(p) => {
                it.st.modal_macro = Some(ModalMacro {
                    number: p.value,
                    repeats,
                    args,
                });
            }
            None => it.st.diagnostics.push(Diagnostic::error(
                g66.span,
                "E-WORD-MISSING",
                "G66 needs the macro program number in P",
            )),
        }
        return Flow::Next;
    }
    let st = &mut it.st;
    let length_before = st.length_comp.map_or(0.0, |(_, o)| o);
    if !settings(st, words) {
        return Flow::Stop;
    }
    let presets_spindle = has(|a| matches!(a, Action::SetPosition));
    // Units first: the block's numbers are read in the new unit.
    for (a, _) in &actions {
        match *a {
            Action::Metric(m) => st.metric = m,
            Action::Absolute(abs) => st.absolute = abs,
            Action::ArcCentres(abs) => st.arc_centres_absolute = abs,
            Action::Plane(p) => st.plane = p,
            Action::FeedMode(m) => st.feed_mode = m,
            Action::SpindleMode(css) => st.css = css,
            Action::PathMode(t) => st.path_mode = t,
            Action::ReturnLevel(initial) => st.return_initial = initial,
            Action::ModalMacro(false) => st.modal_macro = None,
            _ => {}
        }
    }
    spindle_speed(st, words, presets_spindle);
    feed_word(st, find(words, b'F'));
    for (a, w) in &actions {
        match *a {
            Action::WorkOffset => work_offset(st, w, words),
            Action::LengthComp(sign) if !length_comp(st, w, words, sign) => return Flow::Stop,
            Action::StrokeLimit(on) => {
                stroke_limit(st, w, words, on);
                let zone = st.stroke_zone.filter(|_| st.stroke_check);
                sink.stroke_zone(source, zone.as_ref());
            }
            Action::CutterComp(t) if !cutter_comp(st, w, words, t) => {
                return Flow::Stop;
            }
            Action::Motion(m) => {
                let was_cycle = matches!(st.motion, Some(MotionMode::Cycle(_)));
                st.motion = match m {
                    Some(MotionMode::Cycle(_)) => {
                        if !was_cycle {
                            crate::cycles::enter(st);
                        }
                        m
                    }
                    None if was_cycle => crate::cycles::cancel(st),
                    // Fanuc family: G80 is group 09 and leaves the group-01 mode as it is.
                    None if st.dialect != Dialect::LinuxCnc => st.motion,
                    _ => {
                        if was_cycle {
                            crate::cycles::cancel(st);
                        }
                        m
                    }
                };
            }
            _ => {}
        }
    }
    new_length_register(st, words, has(|a| matches!(a, Action::LengthComp(_))));
    let comp_code = actions
        .iter()
        .find(|(a, _)| matches!(a, Action::CutterComp(_)));
    if comp_code.is_none()
        && !new_radius_register(st, words, has(|a| *a == Action::SpindleMode(true)))
    {
        return Flow::Stop;
    }
    if let Some((_, w)) = comp_code
        && dialect != Dialect::LinuxCnc
        && matches!(st.motion, Some(MotionMode::Arc { .. }))
        && axis_words(words).iter().any(Option::is_some)
    {
        st.diagnostics.push(Diagnostic::error(
            w.span,
            "E-COMP-ARC",
            format!(
                "{} starts or cancels cutter compensation only in a G00/G01 block, not with G02/G03: the control alarms and stops",
                Code::from_value(b'G', w.value).map_or_else(|| "G40–G42".to_string(), |c| c.to_string())
            ),
        ));
        return Flow::Stop;
    }
    let axes = axis_words(words);
    // In a block that runs a canned cycle (the block's motion code is already the mode), K is
    // the repeat count, not a length.
    let lengths = if matches!(st.motion, Some(MotionMode::Cycle(_))) {
        CYCLE_LENGTH_LETTERS
    } else {
        LENGTH_LETTERS
    };
    note_least_increment(st, lengths, words);
    // Modes that take the block's axis words as their data.
    let mut consumed = false;
    for (a, w) in &actions {
        let done = match *a {
            Action::Polar(on) => {
                polar(st, on);
                false
            }
            Action::MeasuredRotation => {
                measured_rotation(st, w, words);
                true
            }
            Action::Rotation(on) => {
                rotation(st, w, words, on);
                on
            }
            Action::Scaling(on) => {
                scaling(st, w, words, on);
                on
            }
            Action::Mirror(on) => {
                mirror(st, words, on);
                true
            }
            Action::Local => {
                local(st, &axes);
                true
            }
            Action::SetPosition => {
                set_position(st, &axes);
                true
            }
            Action::PresetZero => {
                preset_zero(st, words);
                true
            }
            Action::Pattern(t) => {
                let (u, v) = plane_axes(st.plane);
                let mut plane_words: Axes<'_> = [None; 3];
                plane_words[u] = axes[u];
                plane_words[v] = axes[v];
                let origin = target(st, &plane_words);
                let feed =
                    |st: &mut State, block: &Block, length: f64| move_feed(st, block, length, None);
                crate::cycles::pattern(st, block, w, words, t, origin, &feed, source, sink);
                true
            }
            // The words are the limits, not a move.
            Action::StrokeLimit(_) => true,
            Action::Measure(second) => {
                measure(st, block, w, words, second, source, sink);
                true
            }
            Action::ResetShift => {
                st.shift = DVec3::ZERO;
                st.resync();
                true
            }
            Action::DataInput => {
                if !data_input(st, w, words) {
                    return Flow::Stop;
                }
                true
            }
            Action::Dwell => {
                dwell(st, w, words, source, sink);
                true
            }
            Action::Reference(n) => {
                reference(st, words, &axes, n, source, sink);
                true
            }
            Action::FromReference => {
                from_reference(st, &axes, source, sink);
                true
            }
            Action::StoreReference(n) => {
                let points = &mut st.setup.machine.reference_points;
                if points.len() < n {
                    points.resize(n, [0.0; 3]);
                }
                points[n - 1] = st.position.to_array();
                true
            }
            Action::Machine => machine_move(st, block, w, &axes, source, sink),
            Action::DynamicLength => {
                // The tool tip still follows the program; the offset is only recorded.
                let z = axes[2].map_or(0.0, |z| st.length(z));
                st.length_comp = Some((0, z));
                st.length_plus = true;
                true
            }
            Action::ExactStop | Action::Nothing => false,
            _ => false,
        };
        consumed |= done;
    }
    // LinuxCNC: a new length offset does not move the machine, but the point it controls is
    // now the tip, that much further from the gauge line, so the current coordinate changes at
    // once (a G91 move in the block starts from it). The Fanuc family adds the offset to the
    // block's move instead (`G91 G43 Z-32. H1` ends 32 below the old coordinate).
    let length_after = st.length_comp.map_or(0.0, |(_, o)| o);
    if length_after != length_before && st.dialect == Dialect::LinuxCnc {
        let (u, v) = plane_axes(st.plane);
        st.position[3 - u - v] -= length_after - length_before;
        st.resync();
    }
    let probe = has(|a| matches!(a, Action::Probe));
    let mut moved = false;
    // Rotary axis words alone still make a move (the rotary position itself is not drawn).
    let rotary = words
        .iter()
        .any(|w| w.form == WordForm::Plain && matches!(w.letter, b'A' | b'B' | b'C'));
    let cycle = matches!(st.motion, Some(MotionMode::Cycle(_)));
    if !consumed
        && (axes.iter().any(Option::is_some) || rotary || cycle || arc_full_circle(st, words))
    {
        if probe {
            st.diagnostics.push(Diagnostic::note(
                block.span,
                "N-PROBE",
                "a skip or measuring move is drawn as its full programmed move (where the signal stops it is not known)",
            ));
        }
        moved = motion(st, block, words, &axes, probe, source, sink);
    }
    // Without G codes the parser cannot tell which words the modal motion uses.
    if actions.is_empty()
        && !matches!(
            it.st.motion,
            Some(MotionMode::Arc { .. } | MotionMode::Cycle(_))
        )
    {
        for w in words
            .iter()
            .filter(|w| w.form == WordForm::Plain && matches!(w.letter, b'I' | b'J' | b'K' | b'R'))
        {
            it.st.diagnostics.push(Diagnostic::warning(
                w.span,
                "W-WORD-IGNORED",
                format!(
                    "address `{}` is only used by G02/G03 here and is ignored",
                    w.letter()
                ),
            ));
        }
    }
    let flow = m_codes(it, at, block, words, source, sink);
    // G66: the modal macro is called after each move.
    if moved
        && flow == Flow::Next
        && !it.in_modal_macro()
        && let Some(call) = it.st.modal_macro.clone()
    {
        return match it.call_modal_macro(at, block, call.number, call.repeats, &call.args) {
            Ok(flow) => flow,
            Err(e) => {
                it.st.diagnostics.push(e);
                Flow::Stop
            }
        };
    }
    flow
}

/// The words of a plain straight move: nothing but `G00`/`G01`, X/Y/Z, F and S words with
/// literal values, in a straight-move mode.
struct PlainWords<'w> {
    /// The motion mode after the block.
    mode: MotionMode,
    axes: Axes<'w>,
    /// The first F and S words.
    feed: Option<&'w Word>,
    spindle: Option<&'w Word>,
    /// Whether an axis word may be read in least increments (no decimal point).
    least_increment: bool,
}

impl<'w> PlainWords<'w> {
    /// The block's words sorted out, or `None` when it is not a plain straight move from the
    /// current mode.
    #[inline(always)]
    fn of(st: &State, words: &'w [Word]) -> Option<Self> {
        let mut axes: Axes<'w> = [None; 3];
        let mut code = None;
        let mut feed = None;
        let mut spindle = None;
        let mut least_increment = false;
        for w in words {
            if w.form != WordForm::Plain || w.expr.is_some() {
                return None;
            }
            match w.letter {
                b'X' | b'Y' | b'Z' => {
                    axes[usize::from(w.letter - b'X')] = Some(w);
                    least_increment |= !w.has_point && w.value != 0.0;
                }
                b'F' => feed = feed.or(Some(w)),
                b'S' => spindle = spindle.or(Some(w)),
                b'G' if code.is_none() && w.value == 0.0 => code = Some(MotionMode::Rapid),
                b'G' if code.is_none() && w.value == 1.0 => code = Some(MotionMode::Linear),
                _ => return None,
            }
        }
        let mode = code.or(st.motion)?;
        if !matches!(mode, MotionMode::Rapid | MotionMode::Linear)
            || matches!(st.motion, Some(MotionMode::Cycle(_)))
        {
            return None;
        }
        Some(PlainWords {
            mode,
            axes,
            feed,
            spindle,
            least_increment,
        })
    }
}

/// Runs a block of nothing but `G00`/`G01`, X/Y/Z, F and S words with literal values, when it
/// is a straight move from a straight-move mode, without the general path's passes over the
/// words for every kind of code (most lines of a CAM program are such blocks). Does exactly what
/// [`execute_block`] does for them; returns `None`, having done nothing, for any other block.
fn plain_move(
    st: &mut State,
    block: &Block,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Option<Flow> {
    // A word left out for a vacant variable leaves the block's own words different.
    if st.modal_macro.is_some() || words.len() != block.words.len() {
        return None;
    }
    let plain = PlainWords::of(st, words)?;
    spindle_speed(st, words, false);
    feed_word(st, plain.feed);
    st.motion = Some(plain.mode);
    if plain.least_increment {
        note_least_increment(st, LENGTH_LETTERS, words);
    }
    let (mode, axes) = (plain.mode, plain.axes);
    if axes.iter().any(Option::is_some) {
        let p = target(st, &axes);
        let to = st.to_machine(p);
        if mode == MotionMode::Rapid {
            st.position = to;
            st.program_pos = p;
            crate::corners::emit(st, sink, source, &Canon::Rapid { to });
        } else {
            feed_to(st, block, p, to, source, sink);
        }
    }
    Some(Flow::Next)
}

/// Runs a block through [`plain_move`] straight from the interpreter's loop (see
/// `Interpreter::plain_block`) where [`execute`] would add nothing to it: no G22 stroke limit
/// and no machine travel to check the moves against.
pub(crate) fn plain_block(
    st: &mut State,
    block: &Block,
    source: Source,
    sink: &mut dyn Sink,
) -> Option<Flow> {
    if (st.stroke_check && st.stroke_zone.is_some()) || st.setup.machine.travel_mm.is_some() {
        return None;
    }
    plain_move(st, block, &block.words, source, sink)
}

/// The state that lets plain straight moves take the fastest path ([`fast_move`]): the
/// coordinate chain is the offsets alone (no polar coordinates, rotation, scaling or mirror),
/// the feed is per minute at constant spindle speed, nothing is held for a corner or for cutter
/// compensation, and no stroke limit or travel is checked. Plain moves do not change any of
/// this, so it holds until another kind of block runs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fast {
    /// The program frame → machine frame offset ([`State::base`]).
    base: DVec3,
    /// Whether G02 and G03 are the dialect's arcs (for [`fast_arc`]).
    arcs: bool,
}

impl Fast {
    /// The fast path's frame for `st`, or `None` when moves need the general steps.
    pub(crate) fn of(st: &State) -> Option<Fast> {
        let simple = st.modal_macro.is_none()
            && !(st.stroke_check && st.stroke_zone.is_some())
            && st.setup.machine.travel_mm.is_none()
            && st.polar.is_none()
            && st.rotation.is_none()
            && st.scaling.is_none()
            && st.mirror == DVec3::ONE
            && st.wcs_rotation == 0.0
            && st.preset_rotation == 0.0
            && st.feed_mode == FeedMode::PerMinute
            && !st.css
            && st.pending.is_none()
            && st.comp.is_idle()
            && st.cutter_comp == 400;
        simple.then(|| Fast {
            base: st.base(),
            arcs: [2.0, 3.0].iter().all(|&g| {
                Code::from_value(b'G', g)
                    .and_then(|c| codes::lookup(st.dialect, c))
                    .and_then(|d| action(st.dialect, d.group, d.code.tenths))
                    == Some(Action::Motion(Some(MotionMode::Arc { ccw: g == 3.0 })))
            }),
        })
    }
}

/// Runs a plain arc in a [`Fast`] frame: a block of nothing but `G02`/`G03`, X/Y/Z, I/J/K or R,
/// F and S words with literal values, in an arc mode. It takes the steps [`execute_block`]
/// takes for such a block (the others find nothing to do in it) and then the same [`motion`];
/// whether it ran the block (`false`, having done nothing, for any other block).
pub(crate) fn fast_arc(
    st: &mut State,
    fast: Fast,
    block: &Block,
    source: Source,
    sink: &mut MotionCounter<'_>,
) -> bool {
    if !fast.arcs {
        return false;
    }
    let words = &block.words[..];
    let mut axes: Axes<'_> = [None; 3];
    let mut code = None;
    let mut feed = None;
    let mut spindle = None;
    let mut centre = false;
    for w in words {
        if w.form != WordForm::Plain || w.expr.is_some() {
            return false;
        }
        match w.letter {
            b'X' | b'Y' | b'Z' => axes[usize::from(w.letter - b'X')] = Some(w),
            b'I' | b'J' | b'K' => centre = true,
            b'R' => {}
            b'F' => feed = feed.or(Some(w)),
            b'S' => spindle = spindle.or(Some(w)),
            b'G' if code.is_none() && w.value == 2.0 => code = Some(MotionMode::Arc { ccw: false }),
            b'G' if code.is_none() && w.value == 3.0 => code = Some(MotionMode::Arc { ccw: true }),
            _ => return false,
        }
    }
    let Some(mode @ MotionMode::Arc { .. }) = code.or(st.motion) else {
        return false;
    };
    if matches!(st.motion, Some(MotionMode::Cycle(_))) {
        return false;
    }
    // `spindle_speed` at constant spindle speed.
    if let Some(s) = spindle.filter(|s| s.value >= 0.0) {
        st.spindle_rpm = s.value;
    }
    feed_word(st, feed);
    st.motion = Some(mode);
    note_least_increment(st, LENGTH_LETTERS, words);
    // No end point and no centre (`G02 R5.`): only the mode is set, as `execute_block` does.
    if axes.iter().any(Option::is_some) || centre {
        motion(st, block, words, &axes, false, source, sink);
    }
    true
}

/// [`plain_move`] in a [`Fast`] frame: the same events, diagnostics and state, without the
/// steps the frame makes void (the transform chain reduces to adding the offsets, and the move
/// goes straight to the sink past the corner and compensation stages, which would pass it on).
/// Whether it ran the block: `false`, having done nothing, for a block that is not a plain
/// straight move (after one, the program goes on to the next block).
pub(crate) fn fast_move(
    st: &mut State,
    fast: Fast,
    block: &Block,
    source: Source,
    sink: &mut MotionCounter<'_>,
) -> bool {
    let Some(PlainWords {
        mode,
        axes,
        feed,
        spindle,
        least_increment,
    }) = PlainWords::of(st, &block.words)
    else {
        return false;
    };
    // `spindle_speed` at constant spindle speed.
    if let Some(s) = spindle.filter(|s| s.value >= 0.0) {
        st.spindle_rpm = s.value;
    }
    feed_word(st, feed);
    st.motion = Some(mode);
    if least_increment {
        note_least_increment(st, LENGTH_LETTERS, &block.words);
    }
    if axes.iter().any(Option::is_some) {
        // `target` without polar coordinates, then `State::to_machine` in the frame.
        let mut p = st.program_pos;
        for (i, w) in axes.iter().enumerate() {
            if let Some(w) = w {
                let v = st.length(w);
                p[i] = if st.absolute { v } else { p[i] + v };
            }
        }
        let to = p + fast.base;
        let rapid = mode == MotionMode::Rapid;
        // `move_feed` per minute, where the move's length does not count: only a feed that is
        // not positive needs its steps (and its diagnostic).
        let feed = match st.feed_mm_per_min {
            _ if rapid => 0.0,
            feed if feed > 0.0 => feed,
            _ => move_feed(st, block, 0.0, None),
        };
        st.position = to;
        st.program_pos = p;
        // What the compensation stage does with a move when it is off.
        st.comp.prog = to;
        st.comp.tool = None;
        // On the counter itself, not through a `dyn Sink`: no dispatch to it.
        sink.straight(source, rapid, to.x, to.y, to.z, feed);
    }
    true
}

/// The block's F word (the first one), read in the feed mode.
fn feed_word(st: &mut State, f: Option<&Word>) {
    st.block_has_feed = f.is_some();
    if let Some(f) = f {
        st.feed_word = f.value;
        st.feed_mm_per_min = match st.feed_mode {
            FeedMode::PerMinute => st.mm(f.value),
            // Per revolution and inverse time are kept as given; each move's feed in mm/min
            // comes from them (`move_feed`).
            FeedMode::PerRevolution | FeedMode::InverseTime => f.value,
        };
    }
}

/// S and T, D and H words; with M06 in the block, the selected tool is the one in the spindle
/// from here on (LinuxCNC changes the tool before it applies G43 or G41/G42). Returns `false`
/// when the run stops: LinuxCNC selects only the tools of its table.
fn settings(st: &mut State, words: &[Word]) -> bool {
    for w in words.iter().filter(|w| w.form == WordForm::Plain) {
        match w.letter {
            b'T' if w.value >= 0.0 => {
                let tool = w.value.round() as u32;
                if st.dialect == Dialect::LinuxCnc && !known_register(st, tool, w.span, "tool") {
                    return false;
                }
                st.tool = tool;
            }
            b'D' if w.value >= 0.0 => st.d_word = w.value.round() as u32,
            b'H' if w.value >= 0.0 && st.dialect != Dialect::Syntec => {
                st.h_word = w.value.round() as u32;
            }
            b'M' if w.value == 6.0 => st.spindle_tool = st.tool,
            _ => {}
        }
    }
    true
}

/// Whether offset register (or LinuxCNC tool) `n`, named by the word at `span`, is one the
/// setup holds; `what` is what is read from it (`length`, `radius`, or `tool` for a LinuxCNC T
/// word). Number 0 is no register. One the setup does not hold reads as zeros: with a note when
/// the setup listed no registers at all (nothing is known of the machine's), with a warning in
/// the Fanuc family when it listed others, and in LinuxCNC, whose tool table must hold every
/// tool a program names, with an error: the run stops there (`false`), as LinuxCNC's does.
fn known_register(st: &mut State, n: u32, span: swarf_syntax::Span, what: &str) -> bool {
    if n == 0 || st.setup.registers.contains_key(&n) {
        return true;
    }
    if !st.registers_listed {
        if what != "tool" {
            st.diagnostics.push(Diagnostic::note(
                span,
                "N-OFFSET-UNSET",
                format!("offset register {n} is not in the setup: its {what} is taken as 0"),
            ));
        }
        return true;
    }
    if st.dialect == Dialect::LinuxCnc {
        st.diagnostics.push(Diagnostic::error(
            span,
            "E-TOOL-UNKNOWN",
            format!(
                "tool {n} is not in the setup's tool table (its registers): LinuxCNC stops here (requested tool not found in the tool table)"
            ),
        ));
        return false;
    }
    st.diagnostics.push(Diagnostic::warning(
        span,
        "W-OFFSET-UNSET",
        format!("offset register {n} is not among the setup's registers: its {what} is taken as 0"),
    ));
    true
}

/// The S word: the spindle speed (rpm under G97, surface speed under G96), or with G92 the
/// most rpm G96 may reach (the Fanuc family's `G92 S`).
fn spindle_speed(st: &mut State, words: &[Word], g92: bool) {
    let s = find(words, b'S').filter(|s| s.value >= 0.0);
    if let Some(s) = s {
        if g92 && st.dialect != Dialect::LinuxCnc {
            st.spindle_clamp = Some(s.value);
            return;
        }
        if st.css {
            st.surface_speed = s.value;
        } else {
            st.spindle_rpm = s.value;
            return;
        }
    } else if !st.css {
        // G97 without S keeps the last speed (the one G96 reached).
        return;
    }
    if st.dialect == Dialect::LinuxCnc {
        // LinuxCNC's G96 follows the X position of a lathe; the speed is read as written.
        st.spindle_rpm = st.surface_speed;
        return;
    }
    // A milling cutter cuts at its diameter: the radius in the D register (or the tool's own
    // register when no D has been given).
    let register = if st.d_word > 0 { st.d_word } else { st.tool };
    let radius = st
        .setup
        .registers
        .get(&register)
        .map_or(0.0, |r| r.radius + r.radius_wear);
    if radius <= 0.0 {
        if let Some(s) = s {
            st.diagnostics.push(Diagnostic::note(
                s.span,
                "N-CSS-DIAMETER",
                format!(
                    "G96: the tool's diameter is not known (no radius in offset register {register}), so the spindle speed for S{} is not known",
                    s.value
                ),
            ));
        }
        st.spindle_rpm = st.spindle_clamp.unwrap_or(0.0);
        return;
    }
    let diameter = 2.0 * radius;
    // V = pi D N / 1000 (m/min, mm) or pi D N / 12 (ft/min, inch).
    let rpm = if st.metric {
        1000.0 * st.surface_speed / (std::f64::consts::PI * diameter)
    } else {
        12.0 * st.surface_speed / (std::f64::consts::PI * diameter / 25.4)
    };
    st.spindle_rpm = st.spindle_clamp.map_or(rpm, |c| rpm.min(c));
}

/// G40/G41/G42 (LinuxCNC also G41.1/G42.1): the side, and the radius from the D register
/// (geometry plus wear; LinuxCNC: the tool table's radius of tool D, or of the tool in the
/// spindle, and for G41.1/G42.1 half the diameter D). Returns `false` when the control alarms.
fn cutter_comp(st: &mut State, w: &Word, words: &[Word], tenths: u32) -> bool {
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    if tenths == 400 {
        st.cutter_comp = 400;
        return true;
    }
    if linuxcnc {
        if st.cutter_comp != 400 {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-COMP-ON",
                "cutter radius compensation cannot be turned on when it is already on",
            ));
            return false;
        }
        if st.plane == Axis::X {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-COMP-PLANE",
                "LinuxCNC has cutter radius compensation in the XY and XZ planes only",
            ));
            return false;
        }
    }
    let d = find(words, b'D');
    if tenths == 411 || tenths == 421 {
        // LinuxCNC: G41.1/G42.1 D<diameter> [L<orientation>], L only in G18.
        let orientation = match find(words, b'L') {
            Some(l) if st.plane != Axis::Y => {
                st.diagnostics.push(Diagnostic::error(
                    l.span,
                    "E-COMP-PLANE",
                    format!(
                        "G{}.1 with an L word (a lathe tool orientation) needs the XZ plane (G18)",
                        tenths / 10
                    ),
                ));
                return false;
            }
            Some(l) if !(0.0..=9.0).contains(&l.value.round()) => {
                st.diagnostics.push(Diagnostic::error(
                    l.span,
                    "E-COMP-ORIENTATION",
                    "a lathe tool orientation is 0 to 9",
                ));
                return false;
            }
            Some(l) => l.value.round() as u8,
            None => 0,
        };
        st.cutter_comp = if tenths == 421 { 420 } else { 410 };
        st.comp_radius = d.map_or(0.0, |d| st.mm(d.value)) / 2.0;
        st.comp.orientation = orientation;
        return true;
    }
    let n = match d {
        Some(d) => d.value.round().max(0.0) as u32,
        None if linuxcnc => st.spindle_tool,
        None => st.d_word,
    };
    if !known_register(st, n, d.map_or(w.span, |d| d.span), "radius") {
        return false;
    }
    let orientation = st.setup.registers.get(&n).map_or(0, |r| r.orientation);
    if linuxcnc && st.plane != Axis::Y && !matches!(orientation, 0 | 9) {
        st.diagnostics.push(Diagnostic::error(
            d.map_or(w.span, |d| d.span),
            "E-COMP-PLANE",
            format!(
                "G{} with a lathe tool (orientation {orientation}) needs the XZ plane (G18)",
                tenths / 10
            ),
        ));
        return false;
    }
    st.cutter_comp = if tenths == 420 { 420 } else { 410 };
    st.comp.orientation = orientation;
    st.comp_radius = st
        .setup
        .registers
        .get(&n)
        .map_or(0.0, |r| r.radius + r.radius_wear);
    true
}

/// A D word in a block without G41/G42: while cutter compensation is on, the Fanuc family
/// takes the new register's radius (from the end of this block's move); LinuxCNC has no use for
/// it outside G41/G42 and G96 and stops with an error. Returns `false` when the run stops.
fn new_radius_register(st: &mut State, words: &[Word], css: bool) -> bool {
    let Some(d) = find(words, b'D') else {
        return true;
    };
    if st.dialect == Dialect::LinuxCnc {
        if css {
            return true;
        }
        st.diagnostics.push(Diagnostic::error(
            d.span,
            "E-WORD-UNUSED",
            "a D word without G41, G41.1, G42, G42.1 or G96 to use it (LinuxCNC changes the radius only with G40 and a new G41/G42)",
        ));
        return false;
    }
    if st.cutter_comp == 400 {
        return true;
    }
    let n = d.value.round().max(0.0) as u32;
    known_register(st, n, d.span, "radius");
    let r = st.setup.registers.get(&n).copied().unwrap_or_default();
    st.comp_radius = r.radius + r.radius_wear;
    st.comp.orientation = r.orientation;
    true
}

/// An H word in a block without G43/G44/G49 while length compensation is on selects the new
/// register at once (H00 cancels, as KT documents); Syntec's H names the tool to measure and
/// LinuxCNC applies H only with G43.
fn new_length_register(st: &mut State, words: &[Word], has_code: bool) {
    if has_code
        || st.length_comp.is_none()
        || matches!(st.dialect, Dialect::Syntec | Dialect::LinuxCnc)
    {
        return;
    }
    let Some(h) = find(words, b'H') else {
        return;
    };
    let n = h.value.round().max(0.0) as u32;
    if n == 0 {
        st.length_comp = None;
        return;
    }
    known_register(st, n, h.span, "length");
    let length = st
        .setup
        .registers
        .get(&n)
        .map_or(0.0, |r| r.length + r.length_wear);
    st.length_comp = Some((n, if st.length_plus { length } else { -length }));
}

fn axis_words(words: &[Word]) -> Axes<'_> {
    let mut axes: Axes<'_> = [None; 3];
    for w in words.iter().filter(|w| w.form == WordForm::Plain) {
        if let b'X' | b'Y' | b'Z' = w.letter {
            axes[usize::from(w.letter - b'X')] = Some(w);
        }
    }
    axes
}

/// The letters whose plain words are lengths (read in least input increments without a point).
const LENGTH_LETTERS: &[u8] = b"XYZIJKRQ";

/// [`LENGTH_LETTERS`] in a block that runs a canned cycle, where K is the repeat count.
const CYCLE_LENGTH_LETTERS: &[u8] = b"XYZIJRQ";

/// Notes, once per run, that a length (a word of `lengths`) without a decimal point is read in
/// least increments.
fn note_least_increment(st: &mut State, lengths: &[u8], words: &[Word]) {
    if st.noted_least_increment || st.calculator() {
        return;
    }
    let Some(w) = words.iter().find(|w| {
        lengths.contains(&w.letter)
            && w.form == WordForm::Plain
            && !w.has_point
            && w.expr.is_none()
            && w.value != 0.0
    }) else {
        return;
    };
    st.noted_least_increment = true;
    let (unit, units) = if st.metric {
        ("0.001 mm", "mm")
    } else {
        ("0.0001 inch", "inch")
    };
    let read = st.dialect.read(w, Quantity::Length, false, !st.metric);
    st.diagnostics.push(Diagnostic::note(
        w.span,
        "N-LEAST-INCREMENT",
        format!(
            "`{}{}` has no decimal point: {} reads it in least input increments ({unit}) as {read} {units}; write `{}{}.` for {} {units} (or set `calculator_input = true` under [machine])",
            w.letter(),
            w.value,
            st.dialect.label(),
            w.letter(),
            w.value,
            w.value
        ),
    ));
}

/// The program-frame end point of a move programmed with `axes` (G90/G91, polar).
fn target(st: &State, axes: &Axes<'_>) -> DVec3 {
    let mut p = st.program_pos;
    if let Some(pole) = st.polar {
        let (u, v) = plane_axes(st.plane);
        let rel = DVec2::new(p[u] - pole.pole.x, p[v] - pole.pole.y);
        let (mut r, mut a) = (rel.length(), rel.y.atan2(rel.x).to_degrees());
        if let Some(w) = axes[u] {
            let given = st.length(w);
            r = if st.absolute { given.abs() } else { r + given };
        }
        if let Some(w) = axes[v] {
            let given = st.angle(w);
            a = if st.absolute { given } else { a + given };
        }
        let (sin, cos) = a.to_radians().sin_cos();
        p[u] = pole.pole.x + r * cos;
        p[v] = pole.pole.y + r * sin;
        let normal = 3 - u - v;
        if let Some(w) = axes[normal] {
            let given = st.length(w);
            p[normal] = if st.absolute {
                given
            } else {
                p[normal] + given
            };
        }
        return p;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let v = st.length(w);
            p[i] = if st.absolute { v } else { p[i] + v };
        }
    }
    p
}

/// Whether an arc block has no end point but I/J/K (a full circle).
fn arc_full_circle(st: &State, words: &[Word]) -> bool {
    matches!(st.motion, Some(MotionMode::Arc { .. }))
        && words
            .iter()
            .any(|w| w.form == WordForm::Plain && matches!(w.letter, b'I' | b'J' | b'K'))
}

/// The block's move in the current motion mode; returns whether the tool moved.
#[allow(clippy::too_many_arguments)]
fn motion(
    st: &mut State,
    block: &Block,
    words: &[Word],
    axes: &Axes<'_>,
    probe: bool,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let Some(mode) = st.motion else {
        let span = axes.iter().flatten().next().map_or(block.span, |w| w.span);
        st.diagnostics.push(Diagnostic::error(
            span,
            "E-NO-MOTION-MODE",
            "axis words with no motion mode active (after G80): add G00 or G01",
        ));
        return false;
    };
    let mut p = target(st, axes);
    if matches!(mode, MotionMode::Rapid | MotionMode::Linear) {
        // G45–G48: the travel of each moving axis changes by the offset.
        p = crate::position::offset_line(st, block, words, axes, p);
    }
    let to = st.to_machine(p);
    let event = match mode {
        MotionMode::Rapid if !probe => Canon::Rapid { to },
        MotionMode::Arc { ccw } => {
            let offsets: Axes<'_> = {
                let mut o: Axes<'_> = [None; 3];
                for w in words.iter().filter(|w| w.form == WordForm::Plain) {
                    if let b'I' | b'J' | b'K' = w.letter {
                        o[usize::from(w.letter - b'I')] = Some(w);
                    }
                }
                o
            };
            let radius = find(words, b'R');
            if offsets.iter().all(Option::is_none) && radius.is_none() {
                if st.dialect == Dialect::Syntec {
                    // Documented: no R and no I/J/K runs as G01 (the parser has said so).
                    return feed_to(st, block, p, to, source, sink);
                }
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-ARC-CENTER",
                    "G02/G03 needs the centre (I, J, K) or the radius (R)",
                ));
                return false;
            }
            // Syntec's L: the number of turns of a spiral (or of a multi-turn arc); LinuxCNC's
            // P: the number of turns of a multi-turn arc or helix.
            let turns = match st.dialect {
                Dialect::Syntec => find(words, b'L'),
                Dialect::LinuxCnc => find(words, b'P'),
                _ => None,
            };
            return arc(st, block, p, (offsets, radius, turns), ccw, source, sink);
        }
        MotionMode::Thread => return thread(st, block, words, p, to, source, sink),
        MotionMode::Cycle(t) => {
            // The hole position: the block's in-plane words only (the normal word is the bottom).
            let (u, v) = plane_axes(st.plane);
            let mut plane_words: Axes<'_> = [None; 3];
            plane_words[u] = axes[u];
            plane_words[v] = axes[v];
            let hole = move |st: &State| target(st, &plane_words);
            let feed =
                |st: &mut State, block: &Block, length: f64| move_feed(st, block, length, None);
            return crate::cycles::run(st, block, words, t, &hole, &feed, source, sink);
        }
        MotionMode::Linear if st.dialect.rules().comma_words => {
            if let Some(corner) = corner_word(st, block) {
                // Held back one block: the next move decides where the corner goes.
                let from = st.position;
                let feed = move_feed(st, block, from.distance(to), None);
                // A corner held from the block before is cut against this move first.
                crate::corners::resolve(
                    st,
                    sink,
                    &Canon::Feed {
                        to,
                        feed_mm_per_min: feed,
                    },
                );
                st.position = to;
                st.program_pos = p;
                st.pending = Some(crate::corners::Pending {
                    from,
                    to,
                    feed_mm_per_min: feed,
                    source,
                    corner: corner.0,
                    span: corner.1,
                });
                return true;
            }
            return feed_to(st, block, p, to, source, sink);
        }
        MotionMode::Rapid | MotionMode::Linear => return feed_to(st, block, p, to, source, sink),
    };
    st.position = to;
    st.program_pos = p;
    crate::corners::emit(st, sink, source, &event);
    true
}

/// G33: a feed along the programmed line at the lead (F; LinuxCNC's K) per spindle revolution.
fn thread(
    st: &mut State,
    block: &Block,
    words: &[Word],
    p: DVec3,
    to: DVec3,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let lead = if st.dialect == Dialect::LinuxCnc {
        find(words, b'K').map_or(0.0, |k| st.length(k))
    } else {
        st.mm(st.feed_word)
    };
    let feed_mm_per_min = lead * st.spindle_rpm;
    if feed_mm_per_min <= 0.0 {
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-NO-FEED",
            "G33 feeds the lead once per spindle revolution: it needs the lead and a spindle speed (S)",
        ));
    }
    st.position = to;
    st.program_pos = p;
    crate::corners::emit(
        st,
        sink,
        source,
        &Canon::Feed {
            to,
            feed_mm_per_min: feed_mm_per_min.max(0.0),
        },
    );
    true
}

/// The block's `,C` or `,R` word as a corner in millimetres.
fn corner_word(st: &State, block: &Block) -> Option<(crate::corners::Corner, swarf_syntax::Span)> {
    let c = block.comma_word(b'C');
    let r = block.comma_word(b'R');
    match (c, r) {
        (Some(c), _) => Some((crate::corners::Corner::Chamfer(st.length(c).abs()), c.span)),
        (None, Some(r)) => Some((crate::corners::Corner::Round(st.length(r).abs()), r.span)),
        _ => None,
    }
}

fn feed_to(
    st: &mut State,
    block: &Block,
    p: DVec3,
    to: DVec3,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let length = st.position.distance(to);
    let feed_mm_per_min = move_feed(st, block, length, None);
    st.position = to;
    st.program_pos = p;
    crate::corners::emit(
        st,
        sink,
        source,
        &Canon::Feed {
            to,
            feed_mm_per_min,
        },
    );
    true
}

/// The feed of one cutting move in mm/min, from the feed mode: F per minute as programmed; F
/// per revolution times the spindle speed; under G93 F times the move's length (LinuxCNC and
/// Fanuc: the move takes 1/F minutes), or as Syntec's manual defines it, F times the length of
/// a line and F times the radius of an arc (`radius`). Reports a move that cannot feed.
fn move_feed(st: &mut State, block: &Block, length: f64, radius: Option<f64>) -> f64 {
    let (feed, problem) = match st.feed_mode {
        FeedMode::PerMinute => (
            st.feed_mm_per_min,
            "a cutting move needs a feed rate: program F before or in this block",
        ),
        FeedMode::PerRevolution => {
            let per_rev = st.mm(st.feed_mm_per_min);
            if per_rev > 0.0 && st.spindle_rpm <= 0.0 {
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-NO-FEED",
                    "a feed per revolution (G95) needs a spindle speed: program S before or in this block",
                ));
                return 0.0;
            }
            (
                per_rev * st.spindle_rpm,
                "a cutting move needs a feed per revolution: program F before or in this block",
            )
        }
        FeedMode::InverseTime => {
            if !st.block_has_feed {
                let alarm = if st.dialect == Dialect::Syntec {
                    " (alarm Cor85)"
                } else {
                    ""
                };
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-NO-FEED",
                    format!(
                        "in inverse-time mode (G93) every cutting block needs its own F{alarm}"
                    ),
                ));
                return 0.0;
            }
            let f = st.feed_mm_per_min;
            let feed = match radius {
                Some(r) if st.dialect == Dialect::Syntec => f * r,
                _ => f * length,
            };
            (feed, "F must be positive in inverse-time mode (G93)")
        }
    };
    // A move of no length under G93 takes no time whatever its F.
    let inverse_nothing = st.feed_mode == FeedMode::InverseTime && st.feed_mm_per_min > 0.0;
    if feed <= 0.0 && !inverse_nothing {
        st.diagnostics
            .push(Diagnostic::error(block.span, "E-NO-FEED", problem));
        return 0.0;
    }
    feed.max(0.0)
}

/// The words that shape an arc: centre offsets I/J/K, radius R and Syntec's turns L.
type ArcWords<'w> = (Axes<'w>, Option<&'w Word>, Option<&'w Word>);

/// G02/G03 in the program frame (centre from I/J/K or from R), then through the transform.
/// With Syntec's L the arc is a spiral (or conical spiral) of L turns, a partial turn counting
/// as one, and its end need not lie on the start's circle; LNC changes the radius progressively
/// when the end is off the circle.
fn arc(
    st: &mut State,
    block: &Block,
    p: DVec3,
    (offsets, radius, turns_word): ArcWords<'_>,
    ccw: bool,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let (u, v) = plane_axes(st.plane);
    let turns = turns_word.map_or(0, |l| {
        let n = l.value.round();
        if !(1.0..=MAX_COUNT).contains(&n) {
            st.diagnostics.push(count_range(l, "turns"));
        }
        n.clamp(1.0, MAX_COUNT) as u32 - 1
    });
    let from = st.program_pos;
    let mut center = from;
    if let Some(r) = radius.filter(|_| offsets.iter().all(Option::is_none)) {
        let r_mm = st.length(r);
        let (du, dv) = (p[u] - from[u], p[v] - from[v]);
        let chord = plane_length(du, dv);
        if chord < 1e-9 {
            st.diagnostics.push(Diagnostic::error(
                r.span,
                "E-ARC-CENTER",
                "an arc programmed with R cannot end where it starts: use I/J/K for a full circle",
            ));
            return false;
        }
        let half = chord / 2.0;
        if r_mm.abs() + st.setup.machine.arc_tolerance_mm < half {
            st.diagnostics.push(Diagnostic::error(
                r.span,
                "E-ARC-RADIUS",
                format!(
                    "R{} is smaller than half the distance to the end point ({half:.4} mm)",
                    r.value
                ),
            ));
            return false;
        }
        let h = (r_mm * r_mm - half * half).max(0.0).sqrt();
        // Left of the chord for a short counter-clockwise arc, right for a short clockwise one.
        let side = if ccw == (r_mm > 0.0) { 1.0 } else { -1.0 };
        center[u] = from[u] + du / 2.0 - side * h * dv / chord;
        center[v] = from[v] + dv / 2.0 + side * h * du / chord;
    } else {
        // LinuxCNC G90.1: the centre words are the centre's program coordinates.
        let absolute = st.arc_centres_absolute;
        let plane = match st.plane {
            Axis::Z => "XY plane (G17)",
            Axis::Y => "XZ plane (G18)",
            Axis::X => "YZ plane (G19)",
        };
        for (i, w) in offsets.iter().enumerate() {
            if let Some(w) = w {
                if i == u || i == v {
                    let at = st.length(w);
                    center[i] = if absolute { at } else { from[i] + at };
                } else if st.dialect == Dialect::LinuxCnc {
                    st.diagnostics.push(Diagnostic::error(
                        w.span,
                        "E-ARC-WORD",
                        format!(
                            "`{}` is not a centre word of an arc in the {plane}: LinuxCNC refuses the block, which is not run",
                            w.letter()
                        ),
                    ));
                    return false;
                } else {
                    st.diagnostics.push(Diagnostic::warning(
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
        if absolute && let Some(i) = [u, v].into_iter().find(|&i| offsets[i].is_none()) {
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-CENTER",
                format!(
                    "under G90.1 (absolute arc centres) an arc in the {plane} needs both centre words: `{}` is missing",
                    char::from(b"IJK"[i])
                ),
            ));
            return false;
        }
        let r0 = plane_length(from[u] - center[u], from[v] - center[v]);
        let r1 = plane_length(p[u] - center[u], p[v] - center[v]);
        if r0 < 1e-9 {
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-CENTER",
                "the arc's centre is at its start point",
            ));
            return false;
        }
        if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm && turns_word.is_some() {
            // A spiral: the radius goes from the start's to the end's.
        } else if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm && st.dialect == Dialect::Lnc
        {
            st.diagnostics.push(Diagnostic::warning(
                block.span,
                "W-ARC-SPIRAL",
                format!(
                    "the end point is {:.4} mm off the arc: LNC changes the radius progressively from {r0:.4} mm to {r1:.4} mm",
                    (r0 - r1).abs()
                ),
            ));
        } else if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm {
            let alarm = if st.dialect == Dialect::Syntec {
                " (alarm COR-006)"
            } else {
                ""
            };
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-RADIUS",
                format!(
                    "the end point is {:.4} mm off the arc: start radius {r0:.4} mm, end radius {r1:.4} mm{alarm}",
                    (r0 - r1).abs()
                ),
            ));
            return false;
        }
    }
    // G45–G48 on an arc: the centre stays, the end moves along its radius by the offset.
    let by_radius = radius.is_some() && offsets.iter().all(Option::is_none);
    let p = match crate::position::offset_arc(st, block, &block.words, by_radius, center, p, ccw) {
        Some(Some(q)) => q,
        Some(None) => p,
        None => return false,
    };
    let to = st.to_machine(p);
    let mut machine_center = st.to_machine(center);
    let normal = 3 - u - v;
    // The centre lies in the start's plane.
    machine_center[normal] = st.position[normal];
    let program_ccw = ccw;
    let ccw = ccw != st.reverses_arcs();
    if let Some(c) = unequal_scaling_center(st, from, p, center, program_ccw, turns_word.is_some())
    {
        machine_center = c;
        machine_center[normal] = st.position[normal];
    }
    let from_machine = st.position;
    // The arc's length and radius count only for a feed in inverse time: most arcs spare the
    // angles and radii they take.
    let feed_mm_per_min = if st.feed_mode == FeedMode::InverseTime {
        let arc = PlaneArc::new(from_machine, to, machine_center, st.plane, ccw, turns);
        let length = (arc.sweep.abs() * (arc.radius + arc.end_radius) / 2.0)
            .hypot(to[normal] - from_machine[normal]);
        move_feed(st, block, length, Some(arc.radius))
    } else {
        move_feed(st, block, 0.0, None)
    };
    st.position = to;
    st.program_pos = p;
    crate::corners::emit(
        st,
        sink,
        source,
        &Canon::Arc {
            to,
            center: machine_center,
            axis: st.plane,
            ccw,
            turns,
            feed_mm_per_min,
        },
    );
    true
}

/// Syntec scales an arc's radius by the largest of the plane's two factors when G51 scales them
/// unequally (`G51 I2. J1.` cuts arcs like `G51 P2.`): the machine centre for the scaled end
/// points, on the same side as the programmed arc's. `None` when the scaling is equal.
fn unequal_scaling_center(
    st: &State,
    from: DVec3,
    to: DVec3,
    center: DVec3,
    ccw: bool,
    spiral: bool,
) -> Option<DVec3> {
    let s = st.scaling?;
    let (u, v) = plane_axes(st.plane);
    let (fu, fv) = (s.factors[u].abs(), s.factors[v].abs());
    if spiral || (fu - fv).abs() < 1e-12 {
        return None;
    }
    let factor = fu.max(fv);
    let (a, b) = (st.scaled(from), st.scaled(to));
    let offset = DVec2::new(center[u] - from[u], center[v] - from[v]);
    let r = offset.length() * factor;
    let (du, dv) = (b[u] - a[u], b[v] - a[v]);
    let chord = plane_length(du, dv);
    let mut c = a;
    if chord < 1e-9 {
        // A full circle: the centre offset, scaled by the largest factor (with the signs of
        // the factors, so a mirrored one still points the right way).
        c[u] = a[u] + offset.x * factor * s.factors[u].signum();
        c[v] = a[v] + offset.y * factor * s.factors[v].signum();
    } else {
        // The programmed arc's sweep decides between the short and the long way round.
        let sweep = PlaneArc::new(from, to, center, st.plane, ccw, 0)
            .sweep
            .abs();
        let long = sweep > std::f64::consts::PI;
        let ccw_scaled = ccw != st.reverses_arcs();
        let half = chord / 2.0;
        let h = (r * r - half * half).max(0.0).sqrt();
        let side = if ccw_scaled == long { -1.0 } else { 1.0 };
        c[u] = a[u] + du / 2.0 - side * h * dv / chord;
        c[v] = a[v] + dv / 2.0 + side * h * du / chord;
    }
    Some(st.place(c))
}

fn dwell(st: &mut State, g4: &Word, words: &[Word], source: Source, sink: &mut dyn Sink) {
    let secs = if let Some(p) = find(words, b'P') {
        st.dialect.read(p, Quantity::DwellP, false, false)
    } else if let Some(x) = find(words, b'X').or(find(words, b'U')) {
        st.dialect.read(x, Quantity::DwellX, false, false)
    } else {
        st.diagnostics.push(Diagnostic::error(
            g4.span,
            "E-WORD-MISSING",
            "G04 needs the dwell time in P or X",
        ));
        return;
    };
    if secs < 0.0 {
        st.diagnostics.push(Diagnostic::error(
            g4.span,
            "E-NUMBER-RANGE",
            "a dwell time cannot be negative",
        ));
        return;
    }
    crate::corners::emit(st, sink, source, &Canon::Dwell { secs });
}

/// G54–G59, G54.1 Pn, G59.n.
fn work_offset(st: &mut State, w: &Word, words: &[Word]) {
    let name = match Code::from_value(b'G', w.value).map(|c| c.tenths) {
        Some(541) => {
            let p = find(words, b'P').map_or(1.0, |p| p.value);
            format!("G54.1P{}", p.round())
        }
        Some(t) if t % 10 == 0 => format!("G{}", t / 10),
        Some(t) => format!("G{}.{}", t / 10, t % 10),
        None => return,
    };
    st.wcs_offset = st.setup.work_offset(&name);
    st.wcs_rotation = st.wcs_rotations.get(&name).copied().unwrap_or(0.0);
    st.wcs = name;
    st.resync();
}

/// G43/G44 H / G49: the tool tip still follows the programmed Z; the offset is recorded.
/// G43/G44 H (`sign`: whether it adds) and G49 (`None`). Without H the Fanuc family takes the
/// last H word, LinuxCNC the tool in the spindle. Returns `false` when the run stops (LinuxCNC:
/// a tool its table does not hold).
fn length_comp(st: &mut State, w: &Word, words: &[Word], sign: Option<bool>) -> bool {
    let Some(plus) = sign else {
        st.length_comp = None;
        return true;
    };
    let h_word = find(words, b'H');
    let h = match h_word {
        Some(h) => h.value.round() as u32,
        None if st.dialect == Dialect::LinuxCnc => st.spindle_tool,
        None => st.h_word,
    };
    if h == 0 {
        // H00 cancels (KT); LinuxCNC's tool 0 has no offsets.
        st.length_comp = None;
        return true;
    }
    if !known_register(st, h, w.span, "length") {
        return false;
    }
    let length = st
        .setup
        .registers
        .get(&h)
        .map_or(0.0, |r| r.length + r.length_wear);
    st.length_comp = Some((h, if plus { length } else { -length }));
    st.length_plus = plus;
    true
}

fn polar(st: &mut State, on: bool) {
    if !on {
        st.polar = None;
        return;
    }
    let (u, v) = plane_axes(st.plane);
    // G90 G16: the pole is the work origin (with G52); G91 G16: the current position.
    let pole = if st.absolute {
        DVec2::ZERO
    } else {
        DVec2::new(st.program_pos[u], st.program_pos[v])
    };
    st.polar = Some(Polar { pole });
}

/// LNC G168 X Y Q: rotation about the centre (or the current point) by measurement result Q
/// (1–4, default 1) from `[machine] measured_angles`.
fn measured_rotation(st: &mut State, w: &Word, words: &[Word]) {
    let q = find(words, b'Q').map_or(1.0, |q| q.value.round());
    let Some(degrees) = (1.0..=4.0)
        .contains(&q)
        .then(|| {
            st.setup
                .machine
                .measured_angles
                .get(q as usize - 1)
                .copied()
        })
        .flatten()
    else {
        st.diagnostics.push(Diagnostic::error(
            w.span,
            "E-MEASUREMENT",
            format!(
                "G168 Q{q} needs measurement result {q} in the setup (`[machine] measured_angles`)"
            ),
        ));
        return;
    };
    let (u, v) = plane_axes(st.plane);
    let letters = [b'X', b'Y', b'Z'];
    let center_of = |i: usize| find(words, letters[i]).map_or(st.program_pos[i], |c| st.length(c));
    st.rotation = Some(Rotation {
        plane: st.plane,
        center: DVec2::new(center_of(u), center_of(v)),
        degrees,
    });
}

/// G68 X Y R (centre from the words, or the current position; angle absolute or, under G91,
/// added to the active rotation).
fn rotation(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.rotation = None;
        return;
    }
    let (u, v) = plane_axes(st.plane);
    let letters = [b'X', b'Y', b'Z'];
    // The centre is absolute in either mode; without it, the current position.
    let center_of = |i: usize| find(words, letters[i]).map_or(st.program_pos[i], |c| st.length(c));
    let center = DVec2::new(center_of(u), center_of(v));
    let Some(r) = find(words, b'R') else {
        if st.dialect == Dialect::Lnc {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-WORD-MISSING",
                "LNC alarms on G68 without the angle R: the rotation is not turned on",
            ));
            return;
        }
        st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-WORD-MISSING",
            "G68 without R rotates by 0° (the angle in the control's parameter is not known)",
        ));
        st.rotation = Some(Rotation {
            plane: st.plane,
            center,
            degrees: 0.0,
        });
        return;
    };
    let angle = st.angle(r);
    let degrees = match (st.absolute, st.rotation) {
        (false, Some(prev)) => prev.degrees + angle,
        _ => angle,
    };
    // The tool stays where it is: the new frame applies to the next move's end point.
    st.rotation = Some(Rotation {
        plane: st.plane,
        center,
        degrees,
    });
}

/// G51 X Y Z P (or I J K per axis) / G50.
fn scaling(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.scaling = None;
        return;
    }
    let letters = [b'X', b'Y', b'Z'];
    let mut center = st.program_pos;
    for (i, l) in letters.iter().enumerate() {
        if let Some(c) = find(words, *l) {
            center[i] = st.length(c);
        }
    }
    // Scale factors: P for all axes, or I/J/K per axis (read as written, e.g. P2.0 or P0.5).
    let p = find(words, b'P').map(|p| p.value);
    let mut factors = DVec3::splat(p.unwrap_or(1.0));
    for (i, l) in [b'I', b'J', b'K'].iter().enumerate() {
        if let Some(f) = find(words, *l) {
            factors[i] = f.value;
        }
    }
    if p.is_none() && [b'I', b'J', b'K'].iter().all(|l| find(words, *l).is_none()) {
        st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-WORD-MISSING",
            "G51 without P or I/J/K scales by 1",
        ));
    }
    st.scaling = Some(Scaling { center, factors });
}

/// G51.1 X Y Z: mirror about the given axis positions / G50.1 X Y Z: cancel (all axes when none
/// is given).
fn mirror(st: &mut State, words: &[Word], on: bool) {
    let letters = [b'X', b'Y', b'Z'];
    let given: Vec<usize> = (0..3)
        .filter(|i| find(words, letters[*i]).is_some())
        .collect();
    for (i, letter) in letters.iter().enumerate() {
        if let Some(w) = find(words, *letter) {
            if on {
                st.mirror_center[i] = st.length(w);
                st.mirror[i] = -1.0;
            } else {
                st.mirror[i] = 1.0;
            }
        } else if !on && given.is_empty() {
            st.mirror[i] = 1.0;
        }
    }
}

/// G52 X Y Z: the local coordinate system (relative to the work system; `G52 X0 Y0 Z0` cancels).
fn local(st: &mut State, axes: &Axes<'_>) {
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            st.local[i] = st.length(w);
        }
    }
    st.resync();
}

/// G92 X Y Z: the current position becomes the given coordinates.
fn set_position(st: &mut State, axes: &Axes<'_>) {
    if st.preset_rotation != 0.0 {
        // Under Syntec's G92.1 rotation the offsets are in the machine's axes: the shift that
        // puts the given program point (unrotated, unscaled) at the current position.
        let mut wanted = st.program_pos;
        for (i, w) in axes.iter().enumerate() {
            if let Some(w) = w {
                wanted[i] = st.length(w);
            }
        }
        let q = crate::state::rotate_xy(st.scaled(wanted), st.preset_rotation);
        st.shift = st.position - st.wcs_offset - st.local - q;
        st.resync();
        return;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let wanted = st.length(w);
            st.shift[i] += st.program_pos[i] - wanted;
        }
    }
    st.resync();
}

/// G10 L2/L20 (work offsets) and L10–L13 / LinuxCNC L1, L10, L11 (offset registers). Returns
/// `false` when the run stops (LinuxCNC: a tool its table does not hold).
fn data_input(st: &mut State, w: &Word, words: &[Word]) -> bool {
    let l = find(words, b'L').map(|l| l.value.round() as i64);
    let p = find(words, b'P').map_or(0, |p| p.value.round() as i64);
    let absolute = st.absolute;
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    match l {
        Some(2 | 20) => {
            let name = if l == Some(20) && !linuxcnc {
                format!("G54.1P{p}")
            } else {
                match (st.dialect, p) {
                    (_, 0) => st.wcs.clone(),
                    (Dialect::LinuxCnc, 7..=9) => format!("G59.{}", p - 6),
                    (_, 1..=6) => format!("G{}", 53 + p),
                    _ => {
                        st.diagnostics.push(Diagnostic::error(
                            w.span,
                            "E-NUMBER-RANGE",
                            format!("G10 L2 P{p} is not a work coordinate system"),
                        ));
                        return true;
                    }
                }
            };
            let mut offset = st.setup.work_offset(&name);
            let mut rotation = st.wcs_rotations.get(&name).copied().unwrap_or(0.0);
            if linuxcnc && let Some(r) = find(words, b'R') {
                rotation = r.value;
            }
            if linuxcnc && l == Some(20) {
                // LinuxCNC L20: the offset that makes the current position read the given
                // coordinates.
                let mut wanted = st.program_pos;
                for (i, letter) in [b'X', b'Y', b'Z'].iter().enumerate() {
                    if let Some(v) = find(words, *letter) {
                        wanted[i] = st.length(v);
                    }
                }
                let full =
                    st.position - crate::state::rotate_xy(wanted + st.local + st.shift, rotation);
                let given = |l: u8| find(words, l).is_some();
                // Under rotation X and Y are coupled: both are set when either is given.
                let xy = given(b'X') || given(b'Y');
                for (i, letter) in [b'X', b'Y', b'Z'].iter().enumerate() {
                    if given(*letter) || (i < 2 && xy && rotation != 0.0) {
                        offset[i] = full[i];
                    }
                }
            } else {
                for (i, letter) in [b'X', b'Y', b'Z'].iter().enumerate() {
                    if let Some(v) = find(words, *letter) {
                        let v = st.length(v);
                        offset[i] = if absolute || linuxcnc {
                            v
                        } else {
                            offset[i] + v
                        };
                    }
                }
            }
            st.setup.work_offsets.insert(name.clone(), offset);
            st.wcs_rotations.insert(name.clone(), rotation);
            if name == st.wcs {
                st.wcs_offset = offset;
                st.wcs_rotation = rotation;
                st.resync();
            }
        }
        Some(1 | 10 | 11 | 12 | 13) => {
            let linuxcnc = st.dialect == Dialect::LinuxCnc;
            let n = p.max(0) as u32;
            if linuxcnc
                && !known_register(st, n, find(words, b'P').map_or(w.span, |p| p.span), "tool")
            {
                return false;
            }
            let metric = st.metric;
            let mm = |x: f64| if metric { x } else { x * 25.4 };
            let r = find(words, b'R').map(|r| mm(r.value));
            let z = find(words, b'Z').map(|z| mm(z.value));
            // LinuxCNC L10 and L11: the length that makes the current position read Z with
            // this tool's offset, in the current coordinate system (L10) or in G59.3's, the
            // tool setter's, with no G52/G92 (L11). The gauge line is the tip plus the offset
            // in effect.
            let gauge = st.length_comp.map_or(0.0, |(_, o)| o);
            let length_for = |z: f64| match l {
                Some(10) => st.program_pos.z + gauge - z,
                Some(11) => st.position.z + gauge - st.setup.work_offset("G59.3").z - z,
                _ => z,
            };
            let z = z.map(length_for);
            let reg = st.setup.registers.entry(n).or_default();
            let slot = match (linuxcnc, l) {
                (true, _) => {
                    if let Some(z) = z {
                        reg.length = z;
                    }
                    if let Some(r) = r {
                        reg.radius = r;
                    }
                    return true;
                }
                (_, Some(10)) => &mut reg.length,
                (_, Some(11)) => &mut reg.length_wear,
                (_, Some(12)) => &mut reg.radius,
                _ => &mut reg.radius_wear,
            };
            if let Some(r) = r {
                *slot = if absolute { r } else { *slot + r };
            }
        }
        _ => st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-NOT-INTERPRETED",
            "this G10 data type is not interpreted yet and is ignored",
        )),
    }
    true
}

/// G28 (n = 1) / G30 Pn: rapid to the intermediate point, then to the reference point, for the
/// axes given.
fn reference(
    st: &mut State,
    words: &[Word],
    axes: &Axes<'_>,
    n: u8,
    source: Source,
    sink: &mut dyn Sink,
) {
    let point = if n == 1 {
        1
    } else {
        find(words, b'P').map_or(2, |p| p.value.round().clamp(1.0, 4.0) as usize)
    };
    let reference = st.setup.reference_point(point) - tool_tip_shift(st);
    if axes.iter().all(Option::is_none) {
        if st.dialect == Dialect::LinuxCnc {
            // LinuxCNC: G28 with no axis word goes to the stored position for all axes.
            rapid_to(st, reference, source, sink);
        }
        return;
    }
    let mid = target(st, axes);
    for (i, w) in axes.iter().enumerate() {
        if w.is_some() {
            st.intermediate[i] = Some(mid[i]);
        }
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    let mut end = st.position;
    for (i, w) in axes.iter().enumerate() {
        if w.is_some() {
            end[i] = reference[i];
        }
    }
    rapid_to(st, end, source, sink);
}

/// G29: from the reference point through the intermediate point to the programmed point.
fn from_reference(st: &mut State, axes: &Axes<'_>, source: Source, sink: &mut dyn Sink) {
    let mut mid = st.program_pos;
    for i in 0..3 {
        if axes[i].is_some()
            && let Some(m) = st.intermediate[i]
        {
            mid[i] = m;
        }
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    // G91: the target is relative to the intermediate point.
    let end = target(st, axes);
    let end_machine = st.to_machine(end);
    rapid_to(st, end_machine, source, sink);
}

/// G53: a one-shot move in machine coordinates, in the block's motion mode (G00 or G01).
/// Returns whether the block's axis words were used (`false`: they are an ordinary move).
fn machine_move(
    st: &mut State,
    block: &Block,
    g53: &Word,
    axes: &Axes<'_>,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    if !st.absolute {
        if st.dialect == Dialect::LinuxCnc {
            st.diagnostics.push(Diagnostic::error(
                g53.span,
                "E-G53-INCREMENTAL",
                "G53 cannot be used in G91: the block is not run",
            ));
            return true;
        }
        // Syntec: "only effective in G90; in G91 a plain incremental move"; LNC: "invalid in
        // G91"; Fanuc ignores it there too.
        st.diagnostics.push(Diagnostic::warning(
            g53.span,
            "W-G53-INCREMENTAL",
            format!(
                "{} ignores G53 in G91: the block is an ordinary incremental move",
                st.dialect.label()
            ),
        ));
        return false;
    }
    let mut to = st.position;
    // Machine coordinates place the spindle's gauge line: the tool tip is the active length
    // offset below it.
    let tip = tool_tip_shift(st);
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            to[i] = st.length(w) - tip[i];
        }
    }
    match st.motion {
        Some(MotionMode::Linear) => {
            let p = st.to_program(to);
            feed_to(st, block, p, to, source, sink);
        }
        _ => rapid_to(st, to, source, sink),
    }
    true
}

/// G37 / G37.1 (Syntec): with P, the return to reference point P (G30 style, all axes); G37
/// then rapids to R above Z when R is given; the measuring move is drawn in full to Z (a program
/// coordinate for G37, a machine coordinate for G37.1), and G37.1 retracts Z to the safety point
/// Q (machine coordinate) or the machine zero.
#[allow(clippy::too_many_arguments)]
fn measure(
    st: &mut State,
    block: &Block,
    g37: &Word,
    words: &[Word],
    machine_z: bool,
    source: Source,
    sink: &mut dyn Sink,
) {
    let Some(z) = find(words, b'Z') else {
        st.diagnostics.push(Diagnostic::error(
            g37.span,
            "E-WORD-MISSING",
            "tool measurement needs the measuring position in Z (alarm MAR-330)",
        ));
        return;
    };
    let z = st.length(z);
    st.diagnostics.push(Diagnostic::note(
        block.span,
        "N-PROBE",
        "a measuring move is drawn as its full programmed move (where the signal stops it is not known)",
    ));
    let tip = tool_tip_shift(st);
    if let Some(p) = find(words, b'P') {
        let n = p.value.round();
        if (1.0..=4.0).contains(&n) {
            let point = st.setup.reference_point(n as usize) - tip;
            rapid_to(st, point, source, sink);
        }
    }
    let end = if machine_z {
        let mut end = st.position;
        end.z = z - tip.z;
        end
    } else {
        let mut p = st.program_pos;
        if let Some(r) = find(words, b'R') {
            p.z = z + st.length(r);
            let start = st.to_machine(p);
            rapid_to(st, start, source, sink);
        }
        p.z = z;
        st.to_machine(p)
    };
    let program = st.to_program(end);
    feed_to(st, block, program, end, source, sink);
    if machine_z {
        let mut back = st.position;
        back.z = find(words, b'Q').map_or(0.0, |q| st.length(q)) - tip.z;
        rapid_to(st, back, source, sink);
    }
}

/// G22 X Y Z I J K: the programmable stroke limit (machine coordinates) / G23: off. Syntec pairs
/// X with I (either may be the larger), protects the zone between them and refuses an axis given
/// without its pair (COR-109); an axis whose pair is equal is not protected. LNC keeps the tool
/// inside the limits (X Y Z the + limits, I J K the − limits); an axis not given is not limited
/// here (its user parameter is not in the setup).
fn stroke_limit(st: &mut State, w: &Word, words: &[Word], on: bool) {
    st.stroke_check = on;
    if !on {
        return;
    }
    let syntec = st.dialect == Dialect::Syntec;
    let mut min = DVec3::NEG_INFINITY;
    let mut max = DVec3::INFINITY;
    let mut given = false;
    for (i, (plus, minus)) in [(b'X', b'I'), (b'Y', b'J'), (b'Z', b'K')]
        .iter()
        .enumerate()
    {
        let hi = find(words, *plus).map(|x| st.length(x));
        let lo = find(words, *minus).map(|x| st.length(x));
        given |= hi.is_some() || lo.is_some();
        match (hi, lo) {
            (Some(a), Some(b)) if syntec => {
                if (a - b).abs() > 1e-9 {
                    min[i] = a.min(b);
                    max[i] = a.max(b);
                }
            }
            (None, None) => {}
            _ if syntec => {
                st.diagnostics.push(Diagnostic::error(
                    w.span,
                    "E-WORD-MISSING",
                    format!(
                        "G22 needs both limits of an axis ({} with {}): alarm COR-109, the protection is not activated",
                        *plus as char, *minus as char
                    ),
                ));
                st.stroke_check = false;
                return;
            }
            (hi, lo) => {
                if let Some(hi) = hi {
                    max[i] = hi;
                }
                if let Some(lo) = lo {
                    min[i] = lo;
                }
            }
        }
    }
    // Without limits in the block the machine's parameters apply (not in the setup).
    st.stroke_zone = given.then_some(StrokeZone {
        min,
        max,
        inside_forbidden: syntec,
    });
    if syntec && (0..3).all(|i| min[i] == f64::NEG_INFINITY) {
        // Every pair was equal: nothing is protected.
        st.stroke_zone = None;
    }
}

/// G92.1 X Y Z R (Syntec): the program zero is preset at X Y Z from the work origin (the G92
/// offsets #1901…) and the program XY plane turned by R degrees about it (#1930). K is not
/// explained by the manual and is not used.
fn preset_zero(st: &mut State, words: &[Word]) {
    for (i, l) in [b'X', b'Y', b'Z'].iter().enumerate() {
        if let Some(w) = find(words, *l) {
            st.shift[i] = st.length(w);
        }
    }
    if let Some(r) = find(words, b'R') {
        st.preset_rotation = st.angle(r);
    }
    st.resync();
}

/// Where the tool tip is relative to the gauge line under the active length offset (along the
/// plane's normal axis).
fn tool_tip_shift(st: &State) -> DVec3 {
    let mut shift = DVec3::ZERO;
    if let Some((_, offset)) = st.length_comp {
        let (u, v) = plane_axes(st.plane);
        shift[3 - u - v] = offset;
    }
    shift
}

fn rapid_to(st: &mut State, to: DVec3, source: Source, sink: &mut dyn Sink) {
    st.position = to;
    st.program_pos = st.to_program(to);
    crate::corners::emit(st, sink, source, &Canon::Rapid { to });
}

/// G65 P L args.
fn macro_call(it: &mut Interpreter, at: usize, block: &Block, words: &[Word], g65: &Word) -> Flow {
    let Some(p) = find(words, b'P') else {
        it.st.diagnostics.push(Diagnostic::error(
            g65.span,
            "E-WORD-MISSING",
            "G65 needs the macro program number in P",
        ));
        return Flow::Next;
    };
    let repeats = repeat_count(&mut it.st, find(words, b'L'));
    let args = arguments(&it.st, words);
    match it.call_macro(at, block, p.value, repeats, &args) {
        Ok(flow) => flow,
        Err(e) => {
            it.st.diagnostics.push(e);
            Flow::Stop
        }
    }
}

/// Macro-call arguments (argument specification I): letter → local variable, value as read.
fn arguments(st: &State, words: &[Word]) -> Vec<(u8, f64)> {
    words
        .iter()
        .filter(|w| w.form == WordForm::Plain && !b"GLNOP".contains(&w.letter))
        .filter_map(|w| {
            let value = if b"XYZUVWIJKRQ".contains(&w.letter) {
                st.dialect
                    .read(w, Quantity::Length, st.calculator(), !st.metric)
            } else {
                w.value
            };
            argument_variable(w.letter).map(|n| (n, value))
        })
        .collect()
}

/// M codes, and the flow they ask for (subprogram calls and returns, program end).
fn m_codes(
    it: &mut Interpreter,
    at: usize,
    block: &Block,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Flow {
    let mut flow = Flow::Next;
    for word in words
        .iter()
        .filter(|w| w.letter == b'M' && w.form == WordForm::Plain)
    {
        let Some(code) = Code::from_value(b'M', word.value) else {
            continue;
        };
        let st = &mut it.st;
        let event = match code.tenths {
            0 => Canon::Pause { optional: false },
            10 => Canon::Pause { optional: true },
            20 | 300 => {
                flow = Flow::Stop;
                Canon::End
            }
            600 if st.dialect == Dialect::LinuxCnc => Canon::Pause { optional: false },
            30 => Canon::Spindle {
                clockwise: Some(true),
                rpm: st.spindle_rpm,
            },
            40 => Canon::Spindle {
                clockwise: Some(false),
                rpm: st.spindle_rpm,
            },
            50 => Canon::Spindle {
                clockwise: None,
                rpm: 0.0,
            },
            60 => Canon::ToolChange { tool: st.tool },
            70 | 80 => Canon::Coolant { on: true },
            90 => Canon::Coolant { on: false },
            190 => continue,
            // M198: a program from outside the control's memory (the files linked to the
            // program), called as M98 calls one.
            980 | 1980 => {
                flow = match it.call_subprogram(at, block, words) {
                    Ok(f) => f,
                    Err(e) => {
                        it.st.diagnostics.push(e);
                        Flow::Stop
                    }
                };
                continue;
            }
            990 => {
                flow = match it.return_from(at, block, find(words, b'P')) {
                    Ok(f) => f,
                    Err(e) => {
                        it.st.diagnostics.push(e);
                        Flow::Stop
                    }
                };
                continue;
            }
            _ => {
                // Codes outside the dialect's list were reported by the parser.
                if let Some(def) = codes::lookup(st.dialect, code) {
                    st.diagnostics.push(Diagnostic::warning(
                        word.span,
                        "W-NOT-INTERPRETED",
                        format!("{} ({}) is not interpreted yet", def.code, def.name),
                    ));
                }
                continue;
            }
        };
        if let Canon::Spindle { clockwise, .. } = event {
            st.spindle_dir = clockwise;
        }
        crate::corners::emit(st, sink, source, &event);
    }
    flow
}
