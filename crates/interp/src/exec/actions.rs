//! What each G code does in a dialect: the action [`super::execute`] takes for it.

use smallvec::SmallVec;
use swarf_syntax::codes::{self, Code, Group};
use swarf_syntax::{Dialect, Word, WordForm};

use crate::Axis;
use crate::state::{FeedMode, MotionMode, State};

/// What one G code does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Action {
    Motion(Option<MotionMode>),
    Plane(Axis),
    Absolute(bool),
    Metric(bool),
    WorkOffset,
    Dwell,
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
    /// Syntec G37 (`false`) / G37.1 (`true`, Z in machine coordinates): tool-length measurement.
    Measure(bool),
    /// Syntec G92.1: the program zero preset at X Y Z from the work origin, the plane turned by R.
    PresetZero,
    /// Syntec G134, G135, G136, G137.1: the stored canned cycle at each point of a hole pattern.
    Pattern(u32),
    StrokeLimit(bool),
    /// LinuxCNC G90.1 (`true`) / G91.1: whether arc centres I/J/K are absolute.
    ArcCentres(bool),
    /// A code with nothing to draw (G09 exact stop, cancels, lathe diameter mode).
    Nothing,
}

/// The action of a code in `dialect`, or `None` for the codes the interpreter does not run yet.
pub(super) fn action(dialect: Dialect, group: Group, tenths: u32) -> Option<Action> {
    let syntec = dialect == Dialect::Syntec;
    let linuxcnc = dialect == Dialect::LinuxCnc;
    let offsets = matches!(dialect, Dialect::Fanuc | Dialect::Syntec);
    // A pair `t @ (a | b)` sets a mode one way or the other by which of the two `t` is.
    Some(match (group, tenths) {
        (Group::Motion, 0) => Action::Motion(Some(MotionMode::Rapid)),
        (Group::Motion, 10) => Action::Motion(Some(MotionMode::Linear)),
        (Group::Motion, t @ (20 | 30)) => Action::Motion(Some(MotionMode::Arc { ccw: t == 30 })),
        (Group::Motion, 330) => Action::Motion(Some(MotionMode::Thread)),
        (Group::Motion | Group::Cycle, 800) => Action::Motion(None),
        (Group::Motion | Group::Cycle, t) if crate::cycles::runs(dialect, t) => {
            Action::Motion(Some(MotionMode::Cycle(t)))
        }
        (_, 40) => Action::Dwell,
        (_, 90) if !linuxcnc => Action::Nothing,
        (Group::Plane, 170) => Action::Plane(Axis::Z),
        (Group::Plane, 180) => Action::Plane(Axis::Y),
        (Group::Plane, 190) => Action::Plane(Axis::X),
        (Group::Distance, t @ (900 | 910)) => Action::Absolute(t == 900),
        (Group::Units, t @ (200 | 210)) if !syntec => Action::Metric(t == 210),
        (Group::Units, t @ (700 | 710)) if syntec => Action::Metric(t == 710),
        (Group::WorkOffset, _) => Action::WorkOffset,
        (Group::PathMode, t) => Action::PathMode(t),
        (Group::FeedMode, 930) => Action::FeedMode(FeedMode::InverseTime),
        // GSK's examples use G98/G99 for feed per minute / per revolution.
        (Group::FeedMode, 940 | 980) => Action::FeedMode(FeedMode::PerMinute),
        (Group::FeedMode, 950 | 990) => Action::FeedMode(FeedMode::PerRevolution),
        (Group::SpindleMode, t @ (960 | 970)) => Action::SpindleMode(t == 960),
        (Group::ReturnLevel, t @ (980 | 990)) => Action::ReturnLevel(t == 980),
        (Group::Polar, t @ (150 | 160)) => Action::Polar(t == 160),
        (Group::Rotation, t @ (680 | 690)) => Action::Rotation(t == 680),
        (Group::Rotation, 1680) => Action::MeasuredRotation,
        (Group::Scaling, t @ (500 | 510)) => Action::Scaling(t == 510),
        (Group::Mirror, t @ (501 | 511)) => Action::Mirror(t == 511),
        (Group::StrokeLimit, t @ (220 | 230)) => Action::StrokeLimit(t == 220),
        (Group::LengthComp, t @ (430 | 440)) => Action::LengthComp(Some(t == 430)),
        (Group::LengthComp, 490) => Action::LengthComp(None),
        (Group::LengthComp, 431 | 432) if linuxcnc => Action::DynamicLength,
        (Group::CutterComp, t) => Action::CutterComp(t),
        // G45–G48 change the block's move (`position::offset_line`, `offset_arc`).
        (Group::NonModal, 450 | 460 | 470 | 480) if offsets => Action::Nothing,
        (Group::MacroModal, t @ (660 | 670)) => Action::ModalMacro(t == 660),
        (Group::ArcDistance, t @ (901 | 911)) => Action::ArcCentres(t == 901),
        (Group::LatheMode, _) => Action::Nothing,
        (Group::NonModal, 520) => Action::Local,
        (Group::NonModal, 530) => Action::Machine,
        (Group::NonModal, 920) => Action::SetPosition,
        (Group::NonModal, 921 | 922) if linuxcnc => Action::ResetShift,
        (Group::NonModal, 280) => Action::Reference(1),
        (Group::NonModal, 300) => Action::Reference(2),
        (Group::NonModal, 290) => Action::FromReference,
        // G28.1 stores reference point 1, G30.1 point 2.
        (Group::NonModal, t @ (281 | 301)) if linuxcnc => Action::StoreReference(t as usize / 150),
        (Group::NonModal, 100) => Action::DataInput,
        (Group::NonModal, 650) => Action::MacroCall,
        (Group::NonModal, 310) if !linuxcnc => Action::Probe,
        (Group::NonModal, t @ (370 | 371)) if syntec => Action::Measure(t == 371),
        (Group::NonModal, 921) if syntec => Action::PresetZero,
        (Group::NonModal, t @ (1340 | 1350 | 1360 | 1371)) if syntec => Action::Pattern(t),
        _ => return None,
    })
}

/// The block's G codes with the actions they take, in the block's order.
pub(super) type Actions<'w> = SmallVec<[(Action, &'w Word); 4]>;

/// The actions of the block's G codes, warning of words not run; `None`: the block is not run.
pub(super) fn of_block<'w>(st: &mut State, words: &'w [Word]) -> Option<Actions<'w>> {
    let dialect = st.dialect;
    let mut actions: Actions<'w> = SmallVec::new();
    let mut runnable = true;
    for word in (words.iter()).filter(|w| w.letter == b'G' && w.form == WordForm::Plain) {
        let Some(def) = Code::from_value(b'G', word.value).and_then(|c| codes::lookup(dialect, c))
        else {
            continue;
        };
        match action(dialect, def.group, def.code.tenths) {
            Some(a) => {
                // Two codes of one group: the last one wins (the parser has warned or refused).
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
                // The manual lists the code but not its format: nothing can be drawn from it.
                let (code, name, control) = (def.code, def.name, dialect.label());
                let message = format!(
                    "{code} ({name}) is only listed in the {control} manual, which does not document its format or motion; this block is not run"
                );
                st.warning(word.span, "W-NOT-DOCUMENTED", message);
                runnable = false;
            }
            None => {
                let (code, name) = (def.code, def.name);
                let message =
                    format!("{code} ({name}) is not interpreted yet; this block is not run");
                st.warning(word.span, "W-NOT-INTERPRETED", message);
                runnable = false;
            }
        }
    }
    for word in words {
        match word.form {
            WordForm::Comma if matches!(word.letter, b'C' | b'R') => {}
            WordForm::Comma => {
                let message = format!(
                    "`,{}` (chamfer/corner rounding) is not drawn yet: the corner is drawn sharp",
                    word.letter()
                );
                st.warning(word.span, "W-NOT-INTERPRETED", message);
            }
            // Syntec's `F2=`: the retract feed of G81 (read by the cycle).
            WordForm::Indexed(2) if word.letter == b'F' && dialect == Dialect::Syntec => {}
            WordForm::Indexed(n) => {
                let l = word.letter();
                let message = format!("`{l}{n}=` is not interpreted yet and is ignored");
                st.warning(word.span, "W-NOT-INTERPRETED", message);
            }
            WordForm::Plain => {}
        }
    }
    runnable.then_some(actions)
}
