//! The machine's state between blocks: modal codes, positions, the coordinate chain (mirror,
//! scaling, rotation, then G52, G92 and the work offset) and the system variables. G91 moves add
//! up in the program frame (`program_pos`), so a new frame applies from the next end point on.

use glam::{DVec2, DVec3};
use swarf_syntax::{Diagnostic, Dialect, Quantity, Span, Word};

use crate::Setup;
use crate::macros::Value;
use crate::{Axis, StrokeZone};

/// The motion mode of modal group 01 that the interpreter runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MotionMode {
    Rapid,
    Linear,
    /// G02 (clockwise) or G03 (counter-clockwise) seen from the plane normal's positive end.
    Arc {
        ccw: bool,
    },
    /// G33 thread cutting: a feed along the programmed line at the lead per revolution.
    Thread,
    /// A canned cycle (G code in tenths: 810 for G81), expanded by `cycles`.
    Cycle(u32),
}

/// Feed-rate mode (group 05).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum FeedMode {
    #[default]
    PerMinute,
    PerRevolution,
    InverseTime,
}

/// G68 rotation in the selected plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rotation {
    pub plane: Axis,
    /// Centre in the program frame (plane coordinates).
    pub center: DVec2,
    /// Angle in degrees, counter-clockwise.
    pub degrees: f64,
}

/// G51 scaling and G51.1 mirroring: per-axis factors about a centre (negative = mirrored).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scaling {
    pub center: DVec3,
    pub factors: DVec3,
}

impl StrokeZone {
    /// Whether the straight move from `a` to `b` (machine coordinates) breaks the limit.
    pub(crate) fn violated_by(&self, a: DVec3, b: DVec3) -> bool {
        if !self.inside_forbidden {
            // The box is convex: a move stays inside exactly when both ends do.
            let inside =
                |p: DVec3| (0..3).all(|i| p[i] >= self.min[i] - 1e-9 && p[i] <= self.max[i] + 1e-9);
            return !(inside(a) && inside(b));
        }
        // Slab test against the open box: touching its boundary is allowed.
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for i in 0..3 {
            let (lo, hi) = (self.min[i] + 1e-9, self.max[i] - 1e-9);
            let d = b[i] - a[i];
            if d.abs() < 1e-15 {
                if a[i] <= lo || a[i] >= hi {
                    return false;
                }
                continue;
            }
            let (mut ta, mut tb) = ((lo - a[i]) / d, (hi - a[i]) / d);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 >= t1 {
                return false;
            }
        }
        true
    }
}

/// A macro call: G65's, or G66's, called after each move until G67.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MacroCall {
    /// Program number (P).
    pub number: f64,
    /// How many times it runs (L).
    pub repeats: u32,
    /// The arguments, as local variable number and value.
    pub args: Vec<(u8, f64)>,
}

/// Everything the machine remembers between blocks, apart from macro variables.
#[derive(Debug, Clone, Default)]
pub(crate) struct State {
    pub setup: Setup,
    pub dialect: Dialect,
    /// Tool-tip position in the machine frame, millimetres.
    pub position: DVec3,
    /// The current point in the program frame (work coordinates before rotation/scaling), mm.
    pub program_pos: DVec3,
    pub motion: Option<MotionMode>,
    pub plane: Axis,
    pub absolute: bool,
    pub metric: bool,
    /// The active work coordinate system by canonical name (`G54`, `G54.1P7`, `G59.3`).
    pub wcs: String,
    pub wcs_offset: DVec3,
    /// LinuxCNC's XY rotation of the active coordinate system (`G10 L2 … R`), degrees.
    pub wcs_rotation: f64,
    /// The rotation of each coordinate system by name (LinuxCNC).
    pub wcs_rotations: std::collections::HashMap<String, f64>,
    /// G52 local coordinate system.
    pub local: DVec3,
    /// G92 shift.
    pub shift: DVec3,
    pub rotation: Option<Rotation>,
    pub scaling: Option<Scaling>,
    /// Mirror factors (±1 per axis) of G51.1, about `mirror_center`.
    pub mirror: DVec3,
    pub mirror_center: DVec3,
    /// G16 polar coordinates: the pole in the program frame (plane coordinates).
    pub polar: Option<DVec2>,
    pub feed_mode: FeedMode,
    pub feed_mm_per_min: f64,
    /// The last F word as written (program units; the lead of G33).
    pub feed_word: f64,
    /// Whether the block being run has an F word (G93 needs one in every cutting block).
    pub block_has_feed: bool,
    /// The spindle speed in rpm (under G96 computed from the surface speed and the tool).
    pub spindle_rpm: f64,
    /// The spindle: `Some(true)` clockwise (M03), `Some(false)` (M04), `None` stopped.
    pub spindle_dir: Option<bool>,
    pub css: bool,
    /// The surface speed of G96 (m/min, or ft/min in inch).
    pub surface_speed: f64,
    /// The spindle-speed clamp (`G92 S`) for G96.
    pub spindle_clamp: Option<f64>,
    pub tool: u32,
    /// The tool `M06` last put in the spindle (whose offsets LinuxCNC's G43/G41 take).
    pub spindle_tool: u32,
    /// Whether the setup listed registers, which the program's must then be among.
    pub registers_listed: bool,
    /// LinuxCNC G90.1: arc centres are program positions, not offsets from the start (G91.1).
    pub arc_centres_absolute: bool,
    /// Active length compensation: register number and signed offset (mm).
    pub length_comp: Option<(u32, f64)>,
    /// Whether the active length compensation is G43 (add) rather than G44 (subtract).
    pub length_plus: bool,
    /// Cutter compensation code in effect (400, 410, 420).
    pub cutter_comp: u32,
    /// The compensation radius from the D register (mm; negative swaps the side).
    pub comp_radius: f64,
    /// The compensation filter's state between events.
    pub comp: crate::comp::Comp,
    /// The span of the block being run (for diagnostics raised by later blocks' moves).
    pub block_span: swarf_syntax::Span,
    /// How many blocks have run, this one included.
    pub blocks_run: u64,
    /// Cutting mode G61–G64 (tenths).
    pub path_mode: u32,
    /// Canned-cycle return level: G98 (true) or G99.
    pub return_initial: bool,
    /// G22 on.
    pub stroke_check: bool,
    /// The limits of the last G22 (`None`: the machine's parameters, not in the setup).
    pub stroke_zone: Option<StrokeZone>,
    /// Modal macro call (G66).
    pub modal_macro: Option<MacroCall>,
    /// The canned cycles' modal hole data.
    pub cycle: crate::cycles::CycleData,
    /// Holes drilled so far in the run (the next hole's number is one more).
    pub holes: u32,
    /// Syntec's G92.1 rotation of the program plane about the preset zero point, degrees.
    pub preset_rotation: f64,
    /// G28/G30 intermediate point per axis, in the program frame.
    pub intermediate: [Option<f64>; 3],
    /// The last T, D and H words.
    pub d_word: u32,
    pub h_word: u32,
    /// A G01 move held back for its `,C`/`,R` corner.
    pub pending: Option<crate::corners::Pending>,
    /// An alarm raised by writing #3000.
    pub alarm: Option<Diagnostic>,
    /// The run's diagnostics (repeats counted, bounded).
    pub diagnostics: crate::diagnostics::Diagnostics,
    /// Whether the least-increment note has been given in this run.
    pub noted_least_increment: bool,
}

impl State {
    /// Power-on state.
    pub fn new(setup: Setup, dialect: Dialect) -> State {
        let wcs_offset = setup.work_offset("G54");
        // Syntec cuts at 1000 mm/min until an F is programmed (§5.2).
        let syntec = dialect == Dialect::Syntec;
        let feed = if syntec { 1000.0 } else { 0.0 };
        State {
            registers_listed: !setup.registers.is_empty(),
            setup,
            dialect,
            program_pos: -wcs_offset,
            // G00 at power-on in the Fanuc family; LinuxCNC starts in G80 (no motion mode).
            motion: (dialect != Dialect::LinuxCnc).then_some(MotionMode::Rapid),
            absolute: true,
            metric: true,
            wcs: "G54".into(),
            wcs_offset,
            mirror: DVec3::ONE,
            feed_mm_per_min: feed,
            feed_word: feed,
            length_plus: true,
            cutter_comp: 400,
            path_mode: 640,
            return_initial: true,
            ..State::default()
        }
    }

    /// Reports a warning of the block being run.
    pub fn warning(&mut self, span: Span, code: &'static str, m: impl Into<String>) {
        self.diagnostics.push(Diagnostic::warning(span, code, m));
    }

    /// Reports a note on the block being run.
    pub fn note(&mut self, span: Span, code: &'static str, message: impl Into<String>) {
        self.diagnostics.push(Diagnostic::note(span, code, message));
    }

    /// Reports an error of the block being run.
    pub fn error(&mut self, span: Span, code: &'static str, m: impl Into<String>) {
        self.diagnostics.push(Diagnostic::error(span, code, m));
    }

    /// Reports an error refusing the block; gives a refused block's result (`false`, `None`).
    pub fn fail<T: Default>(&mut self, span: Span, code: &'static str, m: impl Into<String>) -> T {
        self.error(span, code, m);
        T::default()
    }

    /// Millimetres from a value in the active unit.
    pub fn mm(&self, value: f64) -> f64 {
        if self.metric { value } else { value * 25.4 }
    }

    /// Whether numbers without a decimal point are read in mm (calculator-type input).
    pub fn calculator(&self) -> bool {
        (self.setup.machine.calculator_input).unwrap_or(self.dialect.rules().calculator_input)
    }

    /// A coordinate or distance word in millimetres, read with the dialect's decimal-point rule.
    pub fn length(&self, word: &Word) -> f64 {
        self.mm(self
            .dialect
            .read(word, Quantity::Length, self.calculator(), !self.metric))
    }

    /// An angle word in degrees.
    pub fn angle(&self, word: &Word) -> f64 {
        self.dialect
            .read(word, Quantity::Angle, self.calculator(), false)
    }

    /// The offset from the program frame (after rotation and scaling) to the machine frame.
    pub fn base(&self) -> DVec3 {
        self.wcs_offset + self.local + self.shift
    }

    /// Program frame → machine frame.
    #[inline]
    pub fn to_machine(&self, p: DVec3) -> DVec3 {
        self.place(self.scaled(p))
    }

    /// Mirror and scaling of a program-frame point (the first steps of the chain).
    #[inline]
    pub fn scaled(&self, p: DVec3) -> DVec3 {
        let mut q = p;
        if self.mirror != DVec3::ONE {
            q = self.mirror_center + (q - self.mirror_center) * self.mirror;
        }
        if let Some(s) = self.scaling {
            q = s.center + (q - s.center) * s.factors;
        }
        q
    }

    /// A mirrored and scaled point → machine frame: G68, Syntec's G92.1 rotation, the offsets.
    #[inline]
    pub fn place(&self, q: DVec3) -> DVec3 {
        let q = self.rotated(q, 1.0);
        if self.wcs_rotation != 0.0 {
            // LinuxCNC rotates the coordinate system about its origin, after G52/G92.
            return rotate_xy(q + self.local + self.shift, self.wcs_rotation) + self.wcs_offset;
        }
        rotate_xy(q, self.preset_rotation) + self.base()
    }

    /// G68 rotation of a mirrored and scaled point (`sign` -1: the inverse).
    #[inline]
    fn rotated(&self, mut q: DVec3, sign: f64) -> DVec3 {
        if let Some(r) = self.rotation {
            let (u, v) = plane_axes(r.plane);
            let (sin, cos) = (sign * r.degrees).to_radians().sin_cos();
            let du = q[u] - r.center.x;
            let dv = q[v] - r.center.y;
            q[u] = r.center.x + du * cos - dv * sin;
            q[v] = r.center.y + du * sin + dv * cos;
        }
        q
    }

    /// Machine frame → program frame (the inverse of [`State::to_machine`]).
    pub fn to_program(&self, m: DVec3) -> DVec3 {
        let q = if self.wcs_rotation == 0.0 {
            rotate_xy(m - self.base(), -self.preset_rotation)
        } else {
            rotate_xy(m - self.wcs_offset, -self.wcs_rotation) - self.local - self.shift
        };
        let mut q = self.rotated(q, -1.0);
        if let Some(s) = self.scaling {
            let f = DVec3::select(s.factors.cmpeq(DVec3::ZERO), DVec3::ONE, s.factors);
            q = s.center + (q - s.center) / f;
        }
        if self.mirror != DVec3::ONE {
            q = self.mirror_center + (q - self.mirror_center) * self.mirror;
        }
        q
    }

    /// Re-reads the program-frame position after the frame changed (new offsets, rotation …).
    pub fn resync(&mut self) {
        self.program_pos = self.to_program(self.position);
    }

    /// Whether the transform reverses arc direction (an odd number of mirrored plane axes).
    pub fn reverses_arcs(&self) -> bool {
        let (u, v) = plane_axes(self.plane);
        let mut f = self.mirror;
        if let Some(s) = self.scaling {
            f *= s.factors;
        }
        (f[u] < 0.0) != (f[v] < 0.0)
    }

    /// The active G codes, one per group, for a state view.
    pub fn active_codes(&self) -> Vec<String> {
        let g = |n: u32| (self.modal_code(n)).map_or_else(String::new, |v| format!("G{v}"));
        let motion = match self.motion {
            Some(MotionMode::Cycle(t)) if t % 10 != 0 => 80.0,
            _ => self.modal_code(4001).unwrap_or(80.0),
        };
        let on_off = |on: bool, yes: &str, no: &str| if on { yes } else { no }.to_string();
        let mut out = vec![format!("G{motion:02}")];
        out.extend([4002, 4003, 4006, 4005, 4007, 4008].map(g));
        out.extend([self.wcs.clone(), format!("G{}", self.path_mode / 10)]);
        out.extend([4010, 4017, 4016].map(g));
        out.extend([
            on_off(self.scaling.is_some(), "G51", "G50"),
            on_off(self.mirror != DVec3::ONE, "G51.1", "G50.1"),
            on_off(self.css, "G96", "G97"),
        ]);
        out.dedup();
        out
    }

    /// The number of a modal group's active code as #4001–#4017 give it, `None` for others.
    fn modal_code(&self, n: u32) -> Option<f64> {
        let pick = |on: bool, yes: f64, no: f64| if on { yes } else { no };
        Some(match n {
            4001 => match self.motion {
                Some(MotionMode::Rapid) => 0.0,
                Some(MotionMode::Linear) => 1.0,
                Some(MotionMode::Arc { ccw: false }) => 2.0,
                Some(MotionMode::Arc { ccw: true }) => 3.0,
                Some(MotionMode::Thread) => 33.0,
                Some(MotionMode::Cycle(t)) => f64::from(t) / 10.0,
                None => 80.0,
            },
            // G19 for the normal X, G18 for Y, G17 for Z.
            4002 => 19.0 - f64::from(self.plane as u8),
            4003 => pick(self.absolute, 90.0, 91.0),
            4005 => match self.feed_mode {
                FeedMode::InverseTime => 93.0,
                FeedMode::PerMinute => 94.0,
                FeedMode::PerRevolution => 95.0,
            },
            4006 if self.dialect == Dialect::Syntec => pick(self.metric, 71.0, 70.0),
            4006 => pick(self.metric, 21.0, 20.0),
            4007 => f64::from(self.cutter_comp / 10),
            4008 if self.length_comp.is_none() => 49.0,
            4008 => pick(self.length_plus, 43.0, 44.0),
            4010 => pick(self.return_initial, 98.0, 99.0),
            4014 => f64::from(wcs_number(&self.wcs)) + 53.0,
            4015 => f64::from(self.path_mode) / 10.0,
            4016 => pick(self.rotation.is_some(), 68.0, 69.0),
            4017 => pick(self.polar.is_some(), 16.0, 15.0),
            _ => return None,
        })
    }
}

impl crate::macros::SystemVariables for State {
    /// A system variable (Fanuc numbering; LinuxCNC's where it differs), `None` if not one.
    fn read(&self, n: u32) -> Option<Value> {
        let work = self.program_pos;
        let unit = |mm: f64| if self.metric { mm } else { mm / 25.4 };
        if self.dialect == Dialect::LinuxCnc {
            return match n {
                5220 => Some(Some(f64::from(wcs_number(&self.wcs)))),
                5221..=5399 => {
                    let k = (n - 5221) / 20;
                    let axis = ((n - 5221) % 20) as usize;
                    let o = self.setup.work_offset(WCS_NAMES.get(k as usize)?);
                    Some(Some(if axis < 3 { unit(o[axis]) } else { 0.0 }))
                }
                5211..=5213 => Some(Some(unit(self.shift[(n - 5211) as usize]))),
                5400 => Some(Some(f64::from(self.tool))),
                5420..=5422 => Some(Some(unit(work[(n - 5420) as usize]))),
                _ => None,
            };
        }
        let wcs_axis = |name: &str, i: u32| unit(self.setup.work_offset(name)[i as usize]);
        let syntec = self.dialect == Dialect::Syntec;
        match n {
            // Syntec: the motion mode (0 unless G01–G03), and G90/G91.
            1000 if syntec => Some(self.modal_code(4001).filter(|&g| g <= 3.0).or(Some(0.0))),
            1004 if syntec => Some(self.modal_code(4003)),
            // Syntec: the G92 offset of each axis, and the G92.1 rotation.
            1901..=1916 if syntec => {
                let i = (n - 1901) as usize;
                Some(Some(if i < 3 { unit(self.shift[i]) } else { 0.0 }))
            }
            1930 if syntec => Some(Some(self.preset_rotation)),
            2001..=2400 => Some(Some(unit(self.setup.offsets(n - 2000).0))),
            3000 | 3006 => Some(None),
            4001..=4017 => self.modal_code(n).map(Some),
            4107 => Some(Some(f64::from(self.d_word))),
            4109 => Some(Some(unit(self.feed_mm_per_min))),
            4111 => Some(Some(f64::from(self.h_word))),
            4119 => Some(Some(self.spindle_rpm)),
            4120 => Some(Some(f64::from(self.tool))),
            5001..=5003 => Some(Some(unit(work[(n - 5001) as usize]))),
            5021..=5023 => Some(Some(unit(self.position[(n - 5021) as usize]))),
            5041..=5043 => Some(Some(unit(work[(n - 5041) as usize]))),
            5201..=5203 => Some(Some(0.0)),
            5221..=5343 => {
                let k = (n - 5221) / 20;
                let axis = (n - 5221) % 20;
                (axis < 3).then(|| Some(wcs_axis(&format!("G{}", 54 + k), axis)))
            }
            7001..=7943 => {
                let k = (n - 7001) / 20 + 1;
                let axis = (n - 7001) % 20;
                (axis < 3).then(|| Some(wcs_axis(&format!("G54.1P{k}"), axis)))
            }
            _ => None,
        }
    }

    /// Writes a system variable: `Ok(false)` when `n` is not one, an error for read-only ones.
    fn write(&mut self, n: u32, v: Value) -> Result<bool, String> {
        let mm = self.mm(v.unwrap_or(0.0));
        match n {
            3000 => {
                let number = v.unwrap_or(0.0);
                let message =
                    format!("the program raised macro alarm {number} (#3000) and stops here");
                self.alarm = Some(Diagnostic::error(Span::default(), "E-MACRO-ALARM", message));
                Ok(true)
            }
            3006 => Ok(true),
            2001..=2400 => {
                let r = self.setup.registers.entry(n - 2000).or_default();
                r.length = mm;
                r.length_wear = 0.0;
                Ok(true)
            }
            5221..=5343 if self.dialect != Dialect::LinuxCnc && (n - 5221) % 20 < 3 => {
                let k = (n - 5221) / 20;
                let axis = ((n - 5221) % 20) as usize;
                let name = format!("G{}", 54 + k);
                let mut o = self.setup.work_offset(&name);
                o[axis] = mm;
                self.setup.work_offsets.insert(name.clone(), o);
                if name == self.wcs {
                    self.wcs_offset = o;
                    self.resync();
                }
                Ok(true)
            }
            4001..=4130 | 5001..=5043 => Err(format!("#{n} is read-only")),
            _ => Ok(false),
        }
    }
}

/// `p` turned by `degrees` counter-clockwise about the Z axis.
pub(crate) fn rotate_xy(p: DVec3, degrees: f64) -> DVec3 {
    if degrees == 0.0 {
        // The usual case: no rotation, no trigonometry on every move.
        return p;
    }
    let (sin, cos) = degrees.to_radians().sin_cos();
    DVec3::new(p.x * cos - p.y * sin, p.x * sin + p.y * cos, p.z)
}

/// LinuxCNC's coordinate systems 1–9 (G54 … G59.3), which #5220 numbers from 1.
const WCS_NAMES: [&str; 9] = [
    "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
];

/// 1 for G54 … 6 for G59, 7–9 for G59.1–G59.3 (1 for the extended systems G54.1 Pn).
fn wcs_number(name: &str) -> u32 {
    (WCS_NAMES.iter().position(|n| *n == name)).map_or(1, |i| i as u32 + 1)
}

/// The two in-plane axes (first, second) of the plane with normal `normal`.
pub(crate) fn plane_axes(normal: Axis) -> (usize, usize) {
    [(1, 2), (2, 0), (0, 1)][normal as usize]
}
