//! The code and address tables, from `gcode-reference.md` (§2–§5, §8) and the Fanuc 0i-M and
//! LinuxCNC code lists: one entry per meaning; `words` is permissive where a manual gives no
//! format, `required` holds only words whose absence is an error.

use super::{AddressDef, Code, CodeDef, DialectSet, Documented, Group, Modality};

/// Words of a KT canned cycle: Q and P are stored as modal data even by the cycles that ignore
/// them, and L is the number of holes along a line.
const KT_CYCLE: &str = "XYZRQPFL";
/// Words accepted by an LNC canned cycle whose format is not in the manual.
const LNC_CYCLE: &str = "XYZRQPFKL";
/// Words accepted where the manual gives no format at all.
const UNKNOWN: &str = "ABCEIJKLPQRUVWXYZ";
/// Words of a macro call (G65/G66): P program, L repeat count, and every argument letter.
const MACRO: &str = "PLABCDEFHIJKMQRSTUVWXYZ";

/// A set of dialects as a table writes it: `-`, one name, or `[NAME NAME …]`.
macro_rules! dialects {
    (-) => { DialectSet::NONE };
    ($one:ident) => { DialectSet::$one };
    ([$($name:ident)+]) => { DialectSet::NONE$(.or(DialectSet::$name))+ };
}

/// The code a table names (`G05` and the tenths after its point, `G05.1`).
const fn code(name: &str, tenths: u32) -> Code {
    let name = name.as_bytes();
    let mut number = 0;
    let mut at = 1;
    while at < name.len() {
        number = number * 10 + (name[at] - b'0') as u32;
        at += 1;
    }
    Code {
        letter: name[0],
        tenths: number * 10 + tenths,
    }
}

/// [`CODES`] from one row a meaning, the [`CodeDef`] fields in order: code (`G83.1`), dialects
/// (`ALL`, `[FANUC LNC]`, `-`), [`Group`], [`Modality`], power-on dialects, [`Documented`], whole
/// (`whole` or `-`), section, name, format, words, required (`[]`, `["XP"]`) and summary.
macro_rules! codes {
    ($(
        $code:ident $(. $tenths:literal)?, $dialects:tt, $group:ident, $modality:ident,
        $power_on:tt, $documented:ident, $whole:tt, $section:literal, $name:literal,
        $format:literal, $words:expr, $required:tt, $summary:literal;
    )*) => {
        &[$(CodeDef {
            code: code(stringify!($code), 0 $(+ $tenths)?),
            dialects: dialects!($dialects),
            group: Group::$group,
            modality: Modality::$modality,
            power_on: dialects!($power_on),
            documented: Documented::$documented,
            whole: matches!(stringify!($whole).as_bytes(), b"whole"),
            name: $name,
            format: $format,
            words: $words,
            required: &$required,
            summary: $summary,
            section: $section,
        }),*]
    };
}

/// [`ADDRESSES`] from one row a reading: the letter, the dialects and the meaning.
macro_rules! addresses {
    ($($letter:ident, $dialects:tt, $meaning:literal;)*) => {
        &[$(AddressDef {
            letter: stringify!($letter).as_bytes()[0],
            dialects: dialects!($dialects),
            meaning: $meaning,
        }),*]
    };
}

/// Every code of every dialect. Where dialects give a code different meanings (G134, G70, G98 …)
/// it has one entry per meaning; the first entry whose `dialects` holds the dialect wins.
pub static CODES: &[CodeDef] = codes! {
    // code,  dialects,                       group,       modality, power-on,                documented, whole, section, name, format, words, required, summary
    // ---- G00-G03: motion -------------------------------------------------------------------
    G00,      ALL,                            Motion,      Modal,    [FANUC LNC],             Full,       -,     "4.1",   "Rapid positioning", "G00 X_ Y_ Z_", "XYZABCUVW", [], "Moves at rapid traverse to the end point; F does not apply; cancels a canned cycle. LNC: each axis moves independently (dog-leg path, always exact-stop checked); SYN: Pr411 picks a straight line (0) or independent axes (1).";
    G01,      ALL,                            Motion,      Modal,    -,                       Full,       -,     "4.2",   "Linear interpolation", "G01 X_ Y_ Z_ F_ (LNC: ,C_ chamfer / ,R_ corner)", "XYZABCUVWF", [], "Feeds in a straight line at the modal F; cancels a canned cycle. LNC: ,C chamfer and ,R corner rounding (XY plane only, next block must be G01-G03), any two axes or XYZ together; SYN: default F1000 mm/min (G94) or 1 mm/rev (G95).";
    G02,      LNC,                            Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CW", "G02 X_ Y_ {I_ J_ | R_} F_", "XYZIJRF", [], "Clockwise arc in the XY plane only: I/J run start->centre and are always incremental, -R for more than 180 deg, I/J without X/Y = full circle; a Z word makes a helix (optional function; XY feed F, Z feed scaled).";
    G02,      SYNTEC,                         Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CW", "G17 G02 X_ Y_ {R_ | I_ J_} F_ (G18: X_ Z_ I_ K_; G19: Y_ Z_ J_ K_)", "XYZABCIJKRLF", [], "Clockwise arc in the G17/G18/G19 plane: I/J/K = centre - start, R- for 180-360 deg, full circle only with I/J/K; the third axis makes a helix; L turns make a spiral or conical path; no R/I/J/K runs as G01; COR-006 if the end is off the arc.";
    G02,      [FANUC KT],                     Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CW", "G02 X_ Y_ Z_ {I_ J_ K_ | R_} F_", "XYZABCIJKRF", [], "Clockwise arc in the selected plane (I/J/K = start->centre, R- for more than 180 deg); the axis normal to the plane makes a helix. KT: not in a block that sets length compensation.";
    G02,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Circular interpolation CW", "G2 X_ Y_ Z_ {I_ J_ K_ | R_} [P_] F_", "XYZABCUVWIJKRPF", [], "Clockwise arc or helix in the selected plane; I/J/K follow G90.1/G91.1, R- for more than 180 deg, P = number of turns.";
    G03,      LNC,                            Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CCW", "G03 X_ Y_ {I_ J_ | R_} F_", "XYZIJRF", [], "Counter-clockwise arc in the XY plane only: I/J run start->centre and are always incremental, -R for more than 180 deg, I/J without X/Y = full circle; a Z word makes a helix (optional function; XY feed F, Z feed scaled).";
    G03,      SYNTEC,                         Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CCW", "G17 G03 X_ Y_ {R_ | I_ J_} F_ (G18: X_ Z_ I_ K_; G19: Y_ Z_ J_ K_)", "XYZABCIJKRLF", [], "Counter-clockwise arc in the G17/G18/G19 plane: I/J/K = centre - start, R- for 180-360 deg, full circle only with I/J/K; the third axis makes a helix; L turns make a spiral or conical path; no R/I/J/K runs as G01; COR-006 if the end is off the arc.";
    G03,      [FANUC KT],                     Motion,      Modal,    -,                       Full,       -,     "4.3",   "Circular interpolation CCW", "G03 X_ Y_ Z_ {I_ J_ K_ | R_} F_", "XYZABCIJKRF", [], "Counter-clockwise arc in the selected plane (I/J/K = start->centre, R- for more than 180 deg); the axis normal to the plane makes a helix. KT: not in a block that sets length compensation.";
    G03,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Circular interpolation CCW", "G3 X_ Y_ Z_ {I_ J_ K_ | R_} [P_] F_", "XYZABCUVWIJKRPF", [], "Counter-clockwise arc or helix in the selected plane; I/J/K follow G90.1/G91.1, R- for more than 180 deg, P = number of turns.";
    // ---- G04-G11 -----------------------------------------------------------------------------
    G04,      LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.4",   "Dwell", "G04 P_ | G04 X_", "XP", ["XP"], "Waits P or X seconds, starting once the previous block is in position.";
    G04,      SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.4",   "Dwell", "G04 X_ | G04 P_", "XP", ["XP"], "Waits: X with a decimal point = seconds, without = ms (0.001-9999.999 s); P = ms and takes no decimal point (G04 P2.5 = 2 ms); the spindle keeps turning.";
    G04,      KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.4",   "Dwell", "G04 P_", "XP", ["XP"], "Dwell; not defined in the KT manual (the examples use G04 P2000, probably ms); not allowed in a block that sets length compensation.";
    G04,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Dwell", "G04 X_ | G04 P_", "XPU", ["XPU"], "Waits X (or U) seconds, or P milliseconds (P takes no decimal point).";
    G04,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Dwell", "G4 P_", "P", ["P"], "Waits P seconds (fractions allowed); spindle and coolant are not affected.";
    G05,      SYNTEC,                         Smoothing,   Modal,    -,                       Full,       -,     "4.5",   "High-speed high-precision mode", "G05 P10000 [E_] | G05 P0", "PE", [], "P10000 (or E alone) turns HPCC on with tolerance E (parameter optimisation needs Pr3808), P0 or a bare G05 turns it off; CE version with option 11; not with G93; COR-140 under G43.4.";
    G05,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Cubic spline", "G5 X_ Y_ [I_ J_] P_ Q_", "XYIJPQF", ["P", "Q"], "Cubic B-spline in the XY plane (G17 only): I/J = offset of the first control point from the start, P/Q = offset of the second from the end; I/J may be left out after the first G5.";
    G05.1,    SYNTEC,                         Smoothing,   Modal,    -,                       Full,       -,     "4.6",   "Path smoothing", "G5.1 Q1 E_ | G5.1 Q2 E_ | G5.1 Q0", "QE", ["Q"], "Smooths G01 blocks: Q1 for noisy points, Q2 for sparse points, tolerance E (2-20 um, clamped), Q0 off; COR-107 format error, COR-106 under G61/G63; CE version.";
    G05.1,    FANUC,                          Smoothing,   Modal,    -,                       Full,       -,     "",      "AI contour control", "G05.1 Q1 | G05.1 Q0", "Q", ["Q"], "Look-ahead (AI) contour control on (Q1) or off (Q0).";
    G05.1,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Quadratic spline", "G5.1 X_ Y_ I_ J_", "XYIJF", ["IJ"], "Quadratic B-spline in the XY plane (G17 only); I/J = control point offset from the start.";
    G05.2,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "NURBS block start", "G5.2 [P_] [X_ Y_] [L_]", "XYPLF", [], "Opens a NURBS block: the following X Y P lines are control points with weight P; L = order (default 3). Experimental.";
    G05.3,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "NURBS block end", "G5.3", "", [], "Closes the NURBS block opened by G5.2 and cuts the curve.";
    G06.2,    SYNTEC,                         Motion,      Modal,    -,                       Full,       -,     "4.7",   "NURBS interpolation", "G06.2 P_ K_ X_ Y_ Z_ R_ F_", "PKXYZRF", [], "NURBS curve inside G05 P10000: P = order 2-4 (⚠ manual ambiguous: order or degree; the example fits order), K knots, X Y Z control points, R weight, F maximum feed; CE version, no graphic simulation.";
    G07,      LINUXCNC,                       LatheMode,   Modal,    -,                       Full,       -,     "",      "Lathe diameter mode", "G7", "", [], "X words are diameters (lathe).";
    G07.1,    FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Cylindrical interpolation", "G07.1 C_ (G07.1 C0 cancels)", "ABC", [], "Cylindrical interpolation on the named rotary axis with the given cylinder radius; radius 0 cancels it.";
    G08,      LINUXCNC,                       LatheMode,   Modal,    LINUXCNC,                Full,       -,     "",      "Lathe radius mode", "G8", "", [], "X words are radii (lathe); the power-on default.";
    G09,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.8",   "Exact stop", "G09 [X_ Y_ Z_]", "XYZABC", [], "Exact-stop check for this block only: the next block starts once the axes are in position. SYN: windows Pr421-440 (G01) and Pr481-500 (G00); LNC: G00 is always checked anyway.";
    G10,      LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.9",   "Programmable data input", "G10 L_ P_ {X_ Y_ Z_ A_ B_ C_ | R_} [Q_]", "LPXYZABCRQ", ["L"], "Writes data: L2 origin of G54-G59 (P1-P6), L10/L12 length/diameter offset, L11/L13 fine offsets, L20 G54.1 Pn, L99/L98 work origins from a measurement (Q); G90 replaces, G91 adds.";
    G10,      SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.9",   "Programmable data input", "G10 {L10 | L11 | L12 | L13} P_ R_", "LPR", ["L", "P"], "Writes tool offset P: L10 H geometry, L11 H wear (⚠ manual ambiguous: its text is missing), L12 D geometry, L13 D wear; G90 replaces, G91 adds R.";
    G10,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Programmable data input", "G10 L2 P_ X_ Y_ Z_ | G10 L1x P_ R_ | G10 L50", "LPRXYZABC", ["L"], "Writes data: L2 work offsets (P0 external, P1-P6 = G54-G59), L20 G54.1 offsets, L10-L13 tool offsets, L50 parameter input until G11; G90 replaces, G91 adds.";
    G10,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Set tool table or coordinate system", "G10 L1|L10|L11 P_ axes [R_ I_ J_ Q_] | G10 L2|L20 P_ axes [R_] | G10 L0", "LPXYZABCUVWRIJQ", ["L"], "L0 reloads the tool table; L1/L10/L11 set tool P's entry; L2/L20 set coordinate system P (0 = active, 1-9 = G54-G59.3; R = rotation).";
    G11,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Parameter input mode cancel", "G11", "", [], "Ends the programmable parameter input started with G10 L50.";
    // ---- G12.1-G19: polar interpolation, polar coordinates, planes ---------------------------
    G12.1,    SYNTEC,                         PolarInterp, Modal,    -,                       Full,       -,     "4.10",  "Polar coordinate interpolation on", "G12.1 X_ C_", "XC", [], "Turns Cartesian contour moves into a linear-axis plus rotary (C) move; X/C = eccentricity of the program zero; plane selection and coordinate changes suspended; start only under G40.";
    G13.1,    SYNTEC,                         PolarInterp, Modal,    SYNTEC,                  Full,       -,     "4.10",  "Polar coordinate interpolation off", "G13.1", "", [], "Cancels G12.1 and restores the previous plane; power-off and reset also cancel G12.1.";
    G15,      [FANUC SYNTEC KT],              Polar,       Modal,    [FANUC KT],              Full,       -,     "4.11",  "Polar coordinate command off", "G15", "", [], "Cancels polar coordinate input (KT: G15 at power-on; reset also cancels).";
    G16,      [FANUC SYNTEC KT],              Polar,       Modal,    -,                       Full,       -,     "4.11",  "Polar coordinate command on", "G16", "", [], "1st plane axis = radius, 2nd = angle (+ = CCW). KT: pole = work origin (or G52 origin) if G90 is active at G16, the current position if G91; SYN: in G91 radius and angle accumulate.";
    G17,      [FANUC SYNTEC KT LINUXCNC],     Plane,       Modal,    [FANUC SYNTEC LINUXCNC], Full,       -,     "4.12",  "XY plane", "G17", "", [], "Selects the XY plane for arcs, cutter compensation, polar input and rotation; drilling and length-offset axis Z (SYN default).";
    G17,      GSK,                            Plane,       Modal,    -,                       Mentioned,  -,     "4.52",  "XY plane", "G17", "", [], "Named only in the rigid-tapping axis table (RTX=0): G84.1 taps along Xp, G88.1 along Yp.";
    G17.1,    LINUXCNC,                       Plane,       Modal,    -,                       Full,       -,     "",      "UV plane", "G17.1", "", [], "Selects the UV plane (no arcs); canned cycles run along W.";
    G18,      [FANUC SYNTEC KT LINUXCNC],     Plane,       Modal,    -,                       Full,       -,     "4.12",  "ZX plane", "G18", "", [], "Selects the ZX plane; drilling (SYN) and length-offset (KT) axis Y.";
    G18,      GSK,                            Plane,       Modal,    -,                       Mentioned,  -,     "4.52",  "ZX plane", "G18", "", [], "Named only in the rigid-tapping axis table (RTX=0): G84.1 taps along Zp, G88.1 along Xp.";
    G18.1,    LINUXCNC,                       Plane,       Modal,    -,                       Full,       -,     "",      "WU plane", "G18.1", "", [], "Selects the WU plane (no arcs); canned cycles run along V.";
    G19,      [FANUC SYNTEC KT LINUXCNC],     Plane,       Modal,    -,                       Full,       -,     "4.12",  "YZ plane", "G19", "", [], "Selects the YZ plane; drilling (SYN) and length-offset (KT) axis X.";
    G19,      GSK,                            Plane,       Modal,    -,                       Mentioned,  -,     "4.52",  "YZ plane", "G19", "", [], "Named only in the rigid-tapping axis table (RTX=0): G84.1 taps along Yp, G88.1 along Zp.";
    G19.1,    LINUXCNC,                       Plane,       Modal,    -,                       Full,       -,     "",      "VW plane", "G19.1", "", [], "Selects the VW plane (no arcs); canned cycles run along U.";
    // ---- G20-G39: units, stroke limits, reference points, skip, threads, measuring -----------
    G20,      [FANUC LINUXCNC],               Units,       Modal,    -,                       Full,       -,     "",      "Inch input", "G20", "", [], "Lengths in inches. Not used by Syntec (G70) nor by the KT, LNC and GSK manuals.";
    G21,      [FANUC LINUXCNC],               Units,       Modal,    [FANUC LINUXCNC],        Full,       -,     "",      "Metric input", "G21", "", [], "Lengths in millimetres. Not used by Syntec (G71) nor by the KT, LNC and GSK manuals.";
    G22,      [FANUC SYNTEC LNC],             StrokeLimit, Modal,    [FANUC LNC],             Full,       -,     "4.14",  "Stored stroke limit on", "G22 X_ Y_ Z_ I_ J_ K_", "XYZIJK", [], "Programmable soft limit in machine coordinates: X Y Z = + limits, I J K = - limits. LNC: axes not given use the user parameters; SYN: COR-109 for X without I, Pr2542 inside/outside zone, Pr3838 power-on state, reset does not cancel.";
    G23,      [FANUC SYNTEC LNC],             StrokeLimit, Modal,    -,                       Full,       -,     "4.14",  "Stored stroke limit off", "G23", "", [], "Turns the programmable stroke limit off (LNC: the machine stroke is the soft limit again; SYN: only G23 cancels G22, effective from the next block).";
    G27,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Reference position return check", "G27 X_ Y_ Z_", "XYZABC", [], "Rapids to the given point and checks that it is the reference position.";
    G28,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.15",  "Reference position return", "G28 X_ Y_ Z_", "XYZABC", [], "Rapids via the intermediate point X Y Z (stored for G29) to the reference position; only the commanded axes move. LNC: point stored in work coordinates; SYN: cancel compensation first.";
    G28,      KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.15",  "Reference position return", "G28 X_ Y_ Z_", "XYZ", [], "Mentioned only: not allowed in coordinate-rotation mode (alarm).";
    G28,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Go to predefined position", "G28 [axes]", "XYZABCUVW", [], "Rapids (via the optional intermediate point) to the position stored by G28.1 (parameters 5161-5169).";
    G28.1,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Store predefined position", "G28.1", "", [], "Stores the current absolute position in parameters 5161-5169 for G28.";
    G29,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.16",  "Return from reference position", "G29 X_ Y_ Z_", "XYZABC", [], "Rapids from the reference point via the intermediate point of the last G28 (LNC: or G30) to X Y Z; in G91 the target is relative to the intermediate point.";
    G30,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.17",  "2nd-4th reference position return", "G30 P_ X_ Y_ Z_", "PXYZABC", [], "Rapids via the intermediate point to reference point P (omitted = 2nd). LNC: P2-P4; SYN: P1 = machine origin, points in #2801-#2860.";
    G30,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Go to predefined position", "G30 [axes]", "XYZABCUVW", [], "Rapids (via the optional intermediate point) to the position stored by G30.1 (parameters 5181-5189).";
    G30.1,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Store predefined position", "G30.1", "", [], "Stores the current absolute position in parameters 5181-5189 for G30.";
    G31,      SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.18",  "Skip function", "G31 X_ Y_ Z_ F_ Q_", "XYZFQ", [], "Feeds like G01 until the skip C-bit turns on (Q101-Q132 = C101-C132, default C62), records the position and skips the rest of the move.";
    G31,      KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.18",  "Skip function", "G31 X_ Y_ Z_ F_", "XYZF", [], "Mentioned only: not allowed in a length-compensation block; parameter G31E (P021 bit3) sets the no-signal alarm (⚠ manual ambiguous: both settings say alarm).";
    G31,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Skip function", "G31 X_ Y_ Z_ F_", "XYZABCFP", [], "Feeds like G01 until the skip signal, then abandons the rest of the move.";
    G33,      [FANUC SYNTEC],                 Motion,      Modal,    -,                       Full,       -,     "4.19",  "Thread cutting", "G33 Z_ F_", "XYZF", [], "Cuts a thread along Z in step with the spindle; F = lead. SYN: rpm limited to max feed (#405) / lead; ⚠ manual ambiguous: F is listed in 0.01 mm but the example reads F1.5 as 1.5 mm.";
    G33,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Spindle-synchronized motion", "G33 X_ Y_ Z_ K_", "XYZK", ["K"], "Moves in step with the spindle, K = distance per revolution (threading).";
    G33.1,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Rigid tapping", "G33.1 X_ Y_ Z_ K_ [I_]", "XYZKI", ["K"], "Spindle-synchronized tap to the end point and back (spindle reversed twice); K = distance per revolution, I = return speed factor.";
    G36,      LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.20",  "Coordinate calculation: bolt-hole circle", "G36 (format not in the manual)", UNKNOWN, [], "Holes on a bolt-hole circle; explained in the missing chapter 6. Alarm in arc mode (G02/G03) or during rotation.";
    G37,      LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.20",  "Coordinate calculation: line (angle)", "G37 (format not in the manual)", UNKNOWN, [], "Holes on a line given by an angle; explained in the missing chapter 6. Alarm in arc mode (G02/G03) or during rotation.";
    G37,      SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.21",  "Automatic tool length measurement I", "G37 Z_ [R_] [D_] [F_] [P_]", "ZRDFP", ["Z"], "G30-style return to point P (PR4058), rapid, then measures along Z at F (PR4057) within R/D of Z (program coordinate) and writes the H tool's length; MAR-330 without Z, MAR-334 without H, MAR-335/336 signal errors.";
    G37,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Automatic tool length measurement", "G37 Z_", "XYZ", ["XYZ"], "Moves toward the measuring position until the measure signal and corrects the current length offset by the difference.";
    G37.1,    SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.21",  "Automatic tool length measurement II", "G37.1 [Z_] [R_] [F_] [P_] [Q_]", "ZRFPQ", [], "Air blow M90/M91, G30-style return to P, rapid, measure at F, back 1 mm, re-measure at F50, write the length, retract to safety point Q; Z is a machine coordinate (default PR4059).";
    G38,      LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.20",  "Coordinate calculation: line (X, Y)", "G38 (format not in the manual)", UNKNOWN, [], "Holes on a line given by X and Y steps; explained in the missing chapter 6. Alarm in arc mode (G02/G03) or during rotation.";
    G38.2,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Probe toward workpiece, error if no contact", "G38.2 axes F_", "XYZABCUVWF", ["XYZABCUVW"], "Probes in a straight line at F until contact; error if the end is reached first; result in #5061-#5070.";
    G38.3,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Probe toward workpiece", "G38.3 axes F_", "XYZABCUVWF", ["XYZABCUVW"], "Probes in a straight line at F until contact, no error if none; result in #5061-#5070.";
    G38.4,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Probe away from workpiece, error if no release", "G38.4 axes F_", "XYZABCUVWF", ["XYZABCUVW"], "Moves at F until contact is lost; error if the end is reached first; result in #5061-#5070.";
    G38.5,    LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Probe away from workpiece", "G38.5 axes F_", "XYZABCUVWF", ["XYZABCUVW"], "Moves at F until contact is lost, no error if it is not; result in #5061-#5070.";
    G39,      LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.20",  "Coordinate calculation: grid", "G39 (format not in the manual)", UNKNOWN, [], "Holes on a grid; explained in the missing chapter 6. Alarm in arc mode (G02/G03) or during rotation.";
    G39,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Corner offset circular interpolation", "G39 [I_ J_]", "IJK", [], "Inserts a corner arc of the cutter radius in cutter-compensation mode.";
    // ---- G40-G49: cutter and length compensation ---------------------------------------------
    G40,      [FANUC SYNTEC LINUXCNC],        CutterComp,  Modal,    [FANUC LINUXCNC],        Full,       -,     "4.22",  "Cutter compensation cancel", "G40", "", [], "Cancels cutter radius compensation (SYN: only in a G00/G01 block, not G02/G03).";
    G40,      LNC,                            CutterComp,  Modal,    LNC,                     ListOnly,   -,     "4.22",  "Cutter compensation cancel", "G40", "", [], "Listed (power-on state); details in the missing chapter 4. Alarm with G02/G03 in the block or in arc mode.";
    G40,      KT,                             CutterComp,  Modal,    -,                       Mentioned,  -,     "7",     "Cutter compensation cancel", "G40", "", [], "Appears only in the safety block of the G68 example (G90 G69 G54 G49 G40 G17); cutter compensation is not described.";
    G41,      [FANUC SYNTEC],                 CutterComp,  Modal,    -,                       Full,       -,     "4.22",  "Cutter compensation left", "G41 X_ Y_ D_", "XYZD", [], "Offsets the tool left of the path by offset D (a negative value flips the side). SYN: start/cancel only in G00/G01, not in MDI, ignored in canned cycles, COR-082 with G45-G48, overcut check Pr3819.";
    G41,      LNC,                            CutterComp,  Modal,    -,                       ListOnly,   -,     "4.22",  "Cutter compensation left", "G41 D_", "XYZD", [], "Listed (used as G41 D1); details in the missing chapter 4. Alarm with G02/G03 in the block or in arc mode; applied after G68 rotation.";
    G41,      LINUXCNC,                       CutterComp,  Modal,    -,                       Full,       -,     "",      "Cutter compensation left", "G41 [D_]", "D", [], "Compensates left of the path with tool D's radius (default: the loaded tool); XY or XZ plane only.";
    G41.1,    LINUXCNC,                       CutterComp,  Modal,    -,                       Full,       -,     "",      "Dynamic cutter compensation left", "G41.1 D_ [L_]", "DL", ["D"], "Compensates left of the path for cutter diameter D; L = lathe tool orientation.";
    G42,      [FANUC SYNTEC],                 CutterComp,  Modal,    -,                       Full,       -,     "4.22",  "Cutter compensation right", "G42 X_ Y_ D_", "XYZD", [], "Offsets the tool right of the path by offset D (a negative value flips the side). SYN: start/cancel only in G00/G01, not in MDI, ignored in canned cycles, COR-082 with G45-G48, overcut check Pr3819.";
    G42,      LNC,                            CutterComp,  Modal,    -,                       ListOnly,   -,     "4.22",  "Cutter compensation right", "G42 D_", "XYZD", [], "Listed; details in the missing chapter 4. Alarm with G02/G03 in the block or in arc mode; applied after G68 rotation.";
    G42,      LINUXCNC,                       CutterComp,  Modal,    -,                       Full,       -,     "",      "Cutter compensation right", "G42 [D_]", "D", [], "Compensates right of the path with tool D's radius (default: the loaded tool); XY or XZ plane only.";
    G42.1,    LINUXCNC,                       CutterComp,  Modal,    -,                       Full,       -,     "",      "Dynamic cutter compensation right", "G42.1 D_ [L_]", "DL", ["D"], "Compensates right of the path for cutter diameter D; L = lathe tool orientation.";
    G43,      [FANUC SYNTEC KT],              LengthComp,  Modal,    -,                       Full,       -,     "4.23",  "Tool length compensation +", "G43 Z_ H_", "XYZH", [], "Adds offset H to the end point of the length-compensation axis. KT: axis normal to the plane (G17 Z, G18 Y, G19 X), H01-H24, H00 cancels that axis, no G02/G03/G04/G92/G31/G142/G143 in the block; SYN: H = tool number.";
    G43,      LNC,                            LengthComp,  Modal,    -,                       ListOnly,   -,     "4.23",  "Tool length compensation +", "G43 (format not in the manual)", "XYZH", [], "Listed; details in the missing chapter 4. Alarm with G02/G03 in the block or in arc mode.";
    G43,      LINUXCNC,                       LengthComp,  Modal,    -,                       Full,       -,     "",      "Tool length offset", "G43 [H_]", "H", [], "Applies tool H's length offset from the tool table (default: the loaded tool); no motion.";
    G43.1,    LINUXCNC,                       LengthComp,  Modal,    -,                       Full,       -,     "",      "Dynamic tool length offset", "G43.1 axes", "XYZABCUVW", [], "Replaces the tool length offsets with the given axis values; no motion in the same block.";
    G43.2,    LINUXCNC,                       LengthComp,  Modal,    -,                       Full,       -,     "",      "Additional tool length offset", "G43.2 H_ | G43.2 axes", "HXYZABCUVW", [], "Adds tool H's offset (or the given axis values) to the active tool length offset.";
    G43.4,    SYNTEC,                         LengthComp,  Modal,    -,                       Full,       -,     "4.24",  "RTCP tool tip control", "G43.4 H_", "H", [], "5-axis tool centre point control: linear moves describe the tool tip and the rotary axes follow; not with G41/G42 or G43/G44; cancel with G49 before G28-G30/G53; COR-140 with G05 P10000.";
    G44,      [FANUC SYNTEC KT],              LengthComp,  Modal,    -,                       Full,       -,     "4.23",  "Tool length compensation -", "G44 Z_ H_", "XYZH", [], "Subtracts offset H from the end point of the length-compensation axis (KT: the axis normal to the plane; H00 cancels it; same block restrictions as G43).";
    G44,      LNC,                            LengthComp,  Modal,    -,                       ListOnly,   -,     "4.23",  "Tool length compensation -", "G44 (format not in the manual)", "XYZH", [], "Listed; details in the missing chapter 4. Alarm with G02/G03 in the block or in arc mode.";
    G45,      [FANUC SYNTEC],                 NonModal,    OneShot,  -,                       Full,       -,     "4.25",  "Tool position offset increase", "G45 X_ Y_ Z_ D_", "XYZD", [], "This block only: lengthens the move of each axis by 1x offset D; in G91 a zero move still offsets (the sign of -0 gives the direction). SYN: COR-082 with G41/G42; arcs only 90/270 deg with I/J/K (COR-081).";
    G46,      [FANUC SYNTEC],                 NonModal,    OneShot,  -,                       Full,       -,     "4.25",  "Tool position offset decrease", "G46 X_ Y_ Z_ D_", "XYZD", [], "This block only: shortens the move of each axis by 1x offset D; in G91 a zero move still offsets (the sign of -0 gives the direction). SYN: COR-082 with G41/G42; arcs only 90/270 deg (COR-081).";
    G47,      [FANUC SYNTEC],                 NonModal,    OneShot,  -,                       Full,       -,     "4.25",  "Tool position offset double increase", "G47 X_ Y_ Z_ D_", "XYZD", [], "This block only: lengthens the move of each axis by 2x offset D. SYN: COR-082 with G41/G42; arcs only 90/270 deg (COR-081).";
    G48,      [FANUC SYNTEC],                 NonModal,    OneShot,  -,                       Full,       -,     "4.25",  "Tool position offset double decrease", "G48 X_ Y_ Z_ D_", "XYZD", [], "This block only: shortens the move of each axis by 2x offset D. SYN: COR-082 with G41/G42; arcs only 90/270 deg (COR-081).";
    G49,      [FANUC SYNTEC KT LINUXCNC],     LengthComp,  Modal,    [FANUC LINUXCNC],        Full,       -,     "4.23",  "Tool length compensation cancel", "G49", "", [], "Cancels tool length compensation on every axis at once (SYN: also ends G43.4 RTCP).";
    G49,      LNC,                            LengthComp,  Modal,    LNC,                     ListOnly,   -,     "4.23",  "Tool length compensation cancel", "G49", "", [], "Listed (power-on state); details in the missing chapter 4.";
    // ---- G50-G59: scaling, mirror, coordinate systems ----------------------------------------
    G50,      [FANUC SYNTEC],                 Scaling,     Modal,    FANUC,                   Full,       -,     "4.26",  "Scaling cancel", "G50", "", [], "Cancels scaling.";
    G50.1,    [FANUC SYNTEC],                 Mirror,      Modal,    FANUC,                   Full,       -,     "4.27",  "Programmable mirror image cancel", "G50.1 [X_ Y_ Z_]", "XYZ", [], "Cancels mirror imaging; cancel at the mirror centre or reposition absolutely afterwards (SYN).";
    G51,      [FANUC SYNTEC],                 Scaling,     Modal,    -,                       Full,       -,     "4.26",  "Scaling", "G51 X_ Y_ Z_ {P_ | I_ J_ K_}", "XYZPIJK", [], "Scales about centre X Y Z by P (every axis) or I J K (per axis); arcs use the largest factor (SYN); not together with G51.1 (SYN).";
    G51.1,    [FANUC SYNTEC],                 Mirror,      Modal,    -,                       Full,       -,     "4.27",  "Programmable mirror image", "G51.1 X_ Y_ Z_", "XYZ", [], "Mirrors about the given axis positions; one mirrored plane axis reverses arcs, cutter compensation and rotation; not together with G51 (SYN).";
    G51.2,    SYNTEC,                         NonModal,    Modal,    -,                       Mentioned,  -,     "4.28",  "Polygon cutting", "G51.2 (format not in the manual)", UNKNOWN, [], "Mentioned only as a mode that blocks the M96 interrupt subprogram; group and format not documented.";
    G52,      [FANUC SYNTEC LINUXCNC],        NonModal,    OneShot,  -,                       Full,       -,     "4.29",  "Local coordinate system", "G52 X_ Y_ Z_", "XYZABCUVW", [], "Sets a local coordinate system offset inside the current work system; G52 X0 Y0 Z0 cancels it.";
    G52,      KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.29",  "Local coordinate system", "G52 X_ Y_ Z_", "XYZ", [], "Mentioned only: under G90 a G52 local origin becomes the pole of G16 polar input.";
    G53,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.30",  "Machine coordinate system", "G53 X_ Y_ Z_", "XYZABC", [], "This block only: the coordinates are machine coordinates (rapid move); ignored in G91 (SYN: a plain incremental move); unaffected by rotation (LNC); cancel compensation first.";
    G53,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Move in machine coordinates", "G53 G0|G1 axes", "XYZABCUVW", [], "The axis words of this line are machine coordinates; needs G0 or G1 active and cutter compensation off.";
    G53.1,    SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.31",  "Tool axis direction control", "G53.1", "", [], "Turns the tool axis normal to the G68.2 tilted plane (only after G68.2); use a positive tool length and G43 afterwards.";
    G54,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    [FANUC LNC LINUXCNC],    Full,       -,     "4.32",  "Work coordinate system 1", "G54", "", [], "Selects work coordinate system 1 (LNC: set on the work-origin screen or by G10 L2 P1; SYN: #3229 can disable work systems).";
    G54,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 1", "G54", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G54.1,    [FANUC LNC],                    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Additional work coordinate system", "G54.1 P_", "P", [], "Selects extended work coordinate system P1-P48 (set with G10 L20 P_).";
    G55,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 2", "G55", "", [], "Selects work coordinate system 2.";
    G55,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 2", "G55", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G56,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 3", "G56", "", [], "Selects work coordinate system 3.";
    G56,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 3", "G56", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G57,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 4", "G57", "", [], "Selects work coordinate system 4.";
    G57,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 4", "G57", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G58,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 5", "G58", "", [], "Selects work coordinate system 5.";
    G58,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 5", "G58", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G59,      [FANUC SYNTEC LNC LINUXCNC],    WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 6", "G59", "", [], "Selects work coordinate system 6.";
    G59,      KT,                             WorkOffset,  Modal,    -,                       Mentioned,  -,     "4.32",  "Work coordinate system 6", "G59", "", [], "Mentioned only: G54-G59 cannot be commanded during coordinate rotation (alarm).";
    G59.1,    [SYNTEC LINUXCNC],              WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 7", "G59.1", "", [], "Selects work coordinate system 7 (SYN has 15: G54-G59 and G59.1-G59.9; LinuxCNC 9: up to G59.3).";
    G59.2,    [SYNTEC LINUXCNC],              WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 8", "G59.2", "", [], "Selects work coordinate system 8.";
    G59.3,    [SYNTEC LINUXCNC],              WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 9", "G59.3", "", [], "Selects work coordinate system 9.";
    G59.4,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 10", "G59.4", "", [], "Selects work coordinate system 10.";
    G59.5,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 11", "G59.5", "", [], "Selects work coordinate system 11.";
    G59.6,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 12", "G59.6", "", [], "Selects work coordinate system 12.";
    G59.7,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 13", "G59.7", "", [], "Selects work coordinate system 13.";
    G59.8,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 14", "G59.8", "", [], "Selects work coordinate system 14.";
    G59.9,    SYNTEC,                         WorkOffset,  Modal,    -,                       Full,       -,     "4.32",  "Work coordinate system 15", "G59.9", "", [], "Selects work coordinate system 15.";
    // ---- G60-G72: cutting modes, macros, rotation, units --------------------------------------
    G60,      FANUC,                          NonModal,    OneShot,  -,                       Full,       -,     "",      "Single direction positioning", "G60 X_ Y_ Z_", "XYZABC", [], "Positions with the final approach from one direction to take out backlash.";
    G61,      [FANUC SYNTEC LNC LINUXCNC],    PathMode,    Modal,    -,                       Full,       -,     "4.33",  "Exact stop mode", "G61", "", [], "Every block decelerates and is checked in position before the next (LinuxCNC: exact path). SYN: suspends G05 HPCC and G05.1 smoothing until left.";
    G61.1,    LINUXCNC,                       PathMode,    Modal,    -,                       Full,       -,     "",      "Exact stop mode", "G61.1", "", [], "Motion stops at the end of every segment.";
    G62,      SYNTEC,                         PathMode,    Modal,    -,                       Full,       -,     "4.33",  "Curved-surface cutting mode", "G62 [P_]", "P", [], "No deceleration at block ends; P0-P9 selects a machining-condition set (the later command wins; reset restores P0 or the quick parameters).";
    G62,      FANUC,                          PathMode,    Modal,    -,                       Full,       -,     "",      "Automatic corner override", "G62", "", [], "Reduces the feed at inner corners in cutter-compensation mode.";
    G63,      [FANUC SYNTEC],                 PathMode,    Modal,    -,                       Full,       -,     "4.33",  "Tapping mode", "G63", "", [], "Feed override and feed hold are disabled and blocks do not decelerate (SYN: spindle and feed kept in the S:F ratio; suspends G05/G05.1).";
    G64,      [FANUC LNC],                    PathMode,    Modal,    [FANUC LNC],             Full,       -,     "4.33",  "Cutting mode", "G64", "", [], "Blocks blend without an exact stop (LNC: only cutting feed into cutting feed; positioning and exact-stop blocks are still checked).";
    G64,      SYNTEC,                         PathMode,    Modal,    SYNTEC,                  Full,       -,     "4.33",  "Cutting mode", "G64 [P_]", "P", [], "Default cutting mode: no deceleration at block ends; P0-P9 selects a machining-condition set as for G62.";
    G64,      LINUXCNC,                       PathMode,    Modal,    LINUXCNC,                Full,       -,     "",      "Path blending", "G64 [P_ [Q_]]", "PQ", [], "Blends for best speed; P = path tolerance, Q = naive-CAM collinearity tolerance.";
    G65,      [FANUC SYNTEC],                 NonModal,    OneShot,  -,                       Full,       whole, "4.34",  "Macro call", "G65 P_ L_ <arguments>", MACRO, ["P"], "Calls program P L times in this block only, passing the other words as arguments (SYN: the argument-to-variable mapping is not documented).";
    G65,      LNC,                            NonModal,    OneShot,  -,                       ListOnly,   whole, "4.34",  "Macro call", "G65 (format not in the manual)", MACRO, [], "Listed as a one-shot macro call; alarm with a modal code in the same block (priority tables).";
    G66,      [FANUC SYNTEC],                 MacroModal,  Modal,    -,                       Full,       whole, "4.34",  "Modal macro call", "G66 P_ L_ <arguments>", MACRO, ["P"], "After each move block, calls program P L times with the G66 arguments, until G67.";
    G66,      LNC,                            MacroModal,  Modal,    -,                       ListOnly,   whole, "4.34",  "Modal macro call", "G66 (format not in the manual)", MACRO, [], "Listed as a modal macro call.";
    G67,      [FANUC SYNTEC],                 MacroModal,  Modal,    FANUC,                   Full,       -,     "4.34",  "Modal macro call cancel", "G67", "", [], "Cancels the G66 modal macro call.";
    G67,      LNC,                            MacroModal,  Modal,    LNC,                     ListOnly,   -,     "4.34",  "Modal macro call cancel", "G67", "", [], "Listed (power-on state).";
    G68,      [FANUC SYNTEC KT],              Rotation,    Modal,    -,                       Full,       -,     "4.35",  "Coordinate rotation", "G68 X_ Y_ R_", "XYZR", [], "Rotates the program by R deg (+ = CCW, per G90/G91) about the absolute centre in the plane axes (SYN: G18 Z X, G19 Y Z). KT: centre omitted = current position; no G17-G19, G28 or G54-G59/G92 while active.";
    G68,      LNC,                            Rotation,    Modal,    -,                       Full,       -,     "4.35",  "Coordinate rotation", "G68 X_ Y_ R_", "XYR", ["R"], "Rotates by R deg (-360 to 360, + = CCW) about X Y (absolute; omitted = position at G69->G68, kept in machine coordinates); R omitted = alarm; alarm in MDI; cutter compensation applies after rotation.";
    G68.2,    SYNTEC,                         Rotation,    Modal,    -,                       Full,       -,     "4.31",  "Tilted working plane", "G68.2 X_ Y_ Z_ I_ J_ K_", "XYZIJK", [], "Defines a tilted frame: origin X Y Z from the G54 origin, Euler angles I J K (Z-X-Z); the tool turns only with G53.1; G69 cancels; Pr3014 keeps it over reset.";
    G69,      [FANUC SYNTEC LNC KT],          Rotation,    Modal,    [FANUC LNC],             Full,       -,     "4.35",  "Coordinate rotation cancel", "G69", "", [], "Cancels coordinate rotation (SYN: also G68.2; LNC: also G168, and M02 or RESET cancel rotation too).";
    G70,      SYNTEC,                         Units,       Modal,    -,                       Full,       -,     "4.36",  "Inch input", "G70", "", [], "Lengths in inches (Syntec's G20); offsets, tool data and parameters convert automatically.";
    G70,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe finishing cycle", "G70 Q_ [X_] [Z_] [D_] [E_] [P_]", "QXZDEP", ["Q"], "Finishes the profile in subroutine Q (after G71/G72) in P passes from distance D down to E; ZX plane only.";
    G71,      SYNTEC,                         Units,       Modal,    -,                       Full,       -,     "4.36",  "Metric input", "G71", "", [], "Lengths in millimetres (Syntec's G21); offsets, tool data and parameters convert automatically.";
    G71,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe roughing cycle", "G71 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "Roughs the profile of subroutine Q in layers along Z: I = cut depth, D = stock left, R = retract; ZX plane only.";
    G71.1,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe roughing cycle, no pockets", "G71.1 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "As G71 but does not cut pockets.";
    G71.2,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe roughing cycle, pockets only", "G71.2 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "As G71 but only cuts after the first pocket (continues where G71.1 stopped).";
    G72,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe facing cycle", "G72 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "Roughs the profile of subroutine Q in layers along X (facing); ZX plane only.";
    G72.1,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe facing cycle, no pockets", "G72.1 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "As G72 but does not cut pockets.";
    G72.2,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Lathe facing cycle, pockets only", "G72.2 Q_ [X_] [Z_] [D_] [I_] [R_]", "QXZDIR", ["Q"], "As G72 but only cuts after the first pocket.";
    // ---- G73-G89: canned cycles ------------------------------------------------------------
    G73,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.38",  "High-speed peck drilling cycle", "G73 X_ Y_ Z_ R_ Q_ F_ K_", "XYZRQFK", [], "Pecks Q at feed with a small rapid retract d between pecks (SYN: Pr4002; Fanuc: parameter 5114), then returns to the initial (G98) or R (G99) level; K repeats.";
    G73,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.38",  "High-speed peck drilling cycle", "G98/G99 G73 X_ Y_ R_ Z_ Q_ F_ L_", KT_CYCLE, [], "Pecks Q (default 0.1 mm, sign ignored) with a rapid retract d (data parameter P230, default 1 mm) between pecks; P ignored but kept; L holes along the line to X Y.";
    G73,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.38",  "High-speed peck drilling cycle", "G73 (format not in the manual)", LNC_CYCLE, [], "Listed as a high-speed hole drilling cycle; explained in the missing chapter 5.";
    G73,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Drilling cycle with chip breaking", "G73 X_ Y_ Z_ R_ Q_ [L_]", "XYZUVWRQLF", [], "Pecks Q at feed with a 0.010 in (0.254 mm) rapid retract between pecks, then rapids to clear Z; L repeats in G91.";
    G74,      SYNTEC,                         Cycle,       Modal,    -,                       Full,       -,     "4.39",  "Left-hand tapping cycle", "G74 X_ Y_ Z_ R_ P_ Q_ (F_ or E_) K_", "XYZRPQFEK", [], "Left-hand tap: dwell P (s) and spindle reversal at the bottom and at R; E = threads per inch; Q pecks (Pr4001: 1 high-speed with retract Pr4002, 0 back to R); overrides fixed at 100%.";
    G74,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.39",  "Reverse tapping cycle", "G98/G99 G74 X_ Y_ R_ Z_ P_ F(I)_ L_", "XYZRQPFIL", [], "Taps with the spindle CCW, dwells P, reverses to CW and feeds out to R; F = pitch (I = threads per inch), F modal, alarm if never given; ⚠ manual ambiguous: the cycle table gives CCW as the bottom action.";
    G74,      FANUC,                          Cycle,       Modal,    -,                       Full,       -,     "",      "Left-hand tapping cycle", "G74 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPQFK", [], "Taps with the spindle CCW, dwells, reverses and feeds out; rigid with M29 S_ (Q pecks).";
    G74,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.39",  "Canned cycle (listed as high-speed drilling)", "G74 (format not in the manual)", LNC_CYCLE, [], "⚠ manual ambiguous: the list describes G74 with the same words as G73 (high-speed hole drilling), almost certainly a copy error.";
    G74,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Left-hand tapping cycle with dwell", "G74 X_ Y_ Z_ R_ [L_] P_ F_", "XYZUVWRLPF", [], "Floating-chuck tap: feeds to Z, stops and restarts the spindle CW, dwells P s and feeds out; F = S x pitch; overrides disabled.";
    G76,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.40",  "Fine boring cycle", "G76 X_ Y_ Z_ R_ Q_ P_ F_ K_", "XYZRQPFK", [], "Bores to Z, dwells P, orients the spindle and shifts Q off the wall, rapids out, shifts back and restarts the spindle. SYN: shift direction Pr4020 (+-X, +-Y, +-Z); Q is modal and shared with G73/G83/G87.";
    G76,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.40",  "Fine boring cycle", "G76 X_ Y_ Z_ R_ Q_ P_ F_ L_", KT_CYCLE, [], "Bores, dwells P, shifts Q at the bottom (default 0.1 mm; axis and direction P018 bit4/5, +-X/+-Y only), rapids out, shifts back, spindle CW; ⚠ manual ambiguous: when the spindle orients is not given.";
    G76,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.40",  "Boring cycle", "G76 (format not in the manual)", LNC_CYCLE, [], "Listed as a boring cycle; explained in the missing chapter 5.";
    G76,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Threading cycle (lathe)", "G76 P_ Z_ I_ J_ R_ K_ Q_ H_ E_ L_", "PZIJRKQHEL", ["P", "Z", "I", "J", "K"], "Multi-pass lathe threading: P pitch, Z end, I peak offset, J first cut, K full depth, R degression, Q compound angle, H spring passes, E/L taper; ZX plane only. Not Fanuc fine boring.";
    G77,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.41",  "Tapping cycle (single-block mode)", "G77 (format not in the manual)", LNC_CYCLE, [], "Listed as a tapping canned cycle in single-block mode; format not in the manual.";
    G78,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.41",  "Reverse tapping cycle (single-block mode)", "G78 (format not in the manual)", LNC_CYCLE, [], "Listed as a reverse tapping canned cycle in single-block mode; format not in the manual.";
    G80,      [FANUC SYNTEC LNC KT GSK],      Cycle,       Modal,    [FANUC LNC],             Full,       -,     "4.42",  "Canned cycle cancel", "G80", "", [], "Cancels the canned cycle (a group-01 code does too). GSK: also clears hole position, R, P, K, F and the slanted-cycle mode.";
    G80,      LINUXCNC,                       Motion,      Modal,    LINUXCNC,                Full,       -,     "",      "Cancel canned cycle", "G80", "", [], "Cancels the canned cycle (motion group): no motion mode until the next G0-G3 or cycle; axis words while G80 is active are an error.";
    G81,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.43",  "Drilling cycle", "G81 X_ Y_ Z_ R_ F_ K_ (SYN: F2=_)", "XYZRFK", [], "Rapid to X Y and R, feed to Z, rapid out to the initial (G98) or R (G99) level; K repeats in G91 (K0 stores only). SYN: F2= retract feed (Pr4008 fast drilling), COR-045 if F2 is not an integer.";
    G81,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.43",  "Drilling cycle", "G98/G99 G81 X_ Y_ R_ Z_ F_ L_", KT_CYCLE, [], "Rapid to X Y and R, feed to Z, rapid to the initial or R plane; Q and P ignored but kept; L holes along the line to X Y.";
    G81,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.43",  "Drilling cycle", "G81 (format not in the manual)", LNC_CYCLE, [], "Listed as hole drilling; explained in the missing chapter 5.";
    G81,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Drilling cycle", "G81 X_ Y_ Z_ R_ [L_]", "XYZUVWRLF", [], "Feeds to Z and rapids to clear Z (G98: the old Z if above R; G99: R); L repeats in G91.";
    G82,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.44",  "Drilling cycle with dwell", "G82 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPFK", [], "As G81 with a dwell P at the bottom (SYN: seconds), then rapid out.";
    G82,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.44",  "Drilling cycle with dwell", "G98/G99 G82 X_ Y_ R_ Z_ P_ F_ L_", KT_CYCLE, [], "As G81 with a dwell P (as G04) at the bottom; Q ignored but kept; ⚠ manual ambiguous: the table prints the dwell unit as mm.";
    G82,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.44",  "Drilling cycle with dwell", "G82 (format not in the manual)", LNC_CYCLE, [], "Listed as hole drilling; explained in the missing chapter 5.";
    G82,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Drilling cycle with dwell", "G82 X_ Y_ Z_ R_ P_ [L_]", "XYZUVWRLPF", [], "Feeds to Z, dwells P seconds and rapids to clear Z.";
    G83,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.45",  "Peck drilling cycle", "G83 X_ Y_ Z_ R_ Q_ F_ K_", "XYZRQFK", [], "Pecks Q, rapids back to R after each peck and down to d above the last depth (SYN: Pr4002; Fanuc: parameter 5115), then returns to the initial or R level.";
    G83,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.45",  "Peck drilling cycle", "G98/G99 G83 X_ Y_ R_ Z_ Q_ F_ L_", KT_CYCLE, [], "Pecks Q (default 0.1 mm), rapids back to R, down to d (P230, default 1 mm) above the last depth; P ignored but kept; L holes along the line to X Y.";
    G83,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.45",  "Peck drilling cycle", "G83 (format not in the manual)", LNC_CYCLE, [], "Listed as a deep-hole drilling cycle; explained in the missing chapter 5.";
    G83,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Peck drilling cycle", "G83 X_ Y_ Z_ R_ Q_ [L_]", "XYZUVWRQLF", [], "Pecks Q, rapids back to R after each peck and down to 0.010 in (0.254 mm) above the last depth, then rapids to clear Z.";
    G83.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted end-face drilling cycle", "G83.1 X(U)_ C(H)_ Z(W)_ R_ P_ Q_ F_ K_ M_ E_", "XUCHZWRPQFKME", [], "Drills along Z tilted by E (-60 to 60 deg, modal, E0 = alarm): Z(W) = depth from R, R = signed radius distance from the initial plane, P dwell (1 ms IS-B), Q peck (RTR: high-speed or deep-hole), M = C-axis clamp code; group 10 in the GSK manual.";
    G84,      SYNTEC,                         Cycle,       Modal,    -,                       Full,       -,     "4.46",  "Tapping cycle", "G84 X_ Y_ Z_ R_ P_ Q_ (F_ or E_) K_", "XYZRPQFEK", [], "Right-hand tap with dwell and spindle reversal at the bottom and at R; E = threads per inch; Q pecks (Pr4001 types); overrides fixed at 100%; ⚠ manual ambiguous: P is listed in ms but the steps say seconds.";
    G84,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.46",  "Tapping cycle", "G98/G99 G84 X_ Y_ R_ Z_ P_ F(I)_ L_", "XYZRQPFIL", [], "Taps with the spindle CW, dwells P, reverses to CCW and feeds out to R; F = pitch (I = threads per inch), F modal, alarm if never given; Q ignored but kept.";
    G84,      FANUC,                          Cycle,       Modal,    -,                       Full,       -,     "",      "Tapping cycle", "G84 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPQFK", [], "Taps with the spindle CW, dwells, reverses and feeds out; rigid with M29 S_ (Q pecks).";
    G84,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.46",  "Tapping cycle", "G84 (format not in the manual)", LNC_CYCLE, [], "Listed as tapping; explained in the missing chapter 5 (see also G133/G134).";
    G84,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Right-hand tapping cycle with dwell", "G84 X_ Y_ Z_ R_ [L_] P_ F_", "XYZUVWRLPF", [], "Floating-chuck tap: feeds to Z, stops and restarts the spindle CCW, dwells P s and feeds out; F = S x pitch; overrides disabled.";
    G84.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted end-face tapping cycle", "G84.1 X(U)_ C(H)_ Z(W)_ R_ Q_ P_ F_ K_ M_ E_", "XUCHZWRQPFKMSE", [], "Taps along Z tilted by E: rigid with M29 S_ (before or in the block, or parameter 5200#0), Q pecks (PCP); normal tapping follows the spindle (M03 if none); lead = F/S or F; G80 clears R, depth, P, K, F; group 10 in the GSK manual.";
    G85,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.47",  "Boring cycle", "G85 X_ Y_ Z_ R_ F_ K_", "XYZRFK", [], "Feeds to Z and feeds back out to R, then rapids to the initial level (G98).";
    G85,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.47",  "Boring cycle", "G98/G99 G85 X_ Y_ R_ Z_ F_ L_", KT_CYCLE, [], "Feeds to Z and back out to R at feed, then to the initial plane if G98; Q and P ignored but kept; L holes along the line to X Y.";
    G85,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.47",  "Boring cycle", "G85 (format not in the manual)", LNC_CYCLE, [], "Listed as boring; explained in the missing chapter 5.";
    G85,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Boring cycle, feed out", "G85 X_ Y_ Z_ R_ [L_]", "XYZUVWRLF", [], "Feeds to Z, feeds back to R, then rapids to clear Z.";
    G85.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted end-face boring cycle", "G85.1 X(U)_ C(H)_ Z(W)_ R_ P_ F_ K_ M_ E_", "XUCHZWRPFKME", [], "Bores along Z tilted by E: feed in, dwell P, feed out to R; words as G83.1 (no Q); group 10 in the GSK manual.";
    G86,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.48",  "Boring cycle, spindle stop", "G98/G99 G86 X_ Y_ R_ Z_ F_ L_", KT_CYCLE, [], "Feeds to Z, stops the spindle (M05), rapids to the initial or R plane and restarts it CW (M03) whatever the direction before; Q and P ignored but kept.";
    G86,      SYNTEC,                         Cycle,       Modal,    -,                       Full,       -,     "4.48",  "High-speed drilling cycle", "G86 X_ Y_ Z_ R_ F_ K_", "XYZRFK", [], "Feeds to Z and rapids out to the initial (G98) or R (G99) level; ⚠ manual ambiguous: the cycle table adds a spindle stop at the bottom, the steps do not.";
    G86,      FANUC,                          Cycle,       Modal,    -,                       Full,       -,     "",      "Boring cycle, spindle stop", "G86 X_ Y_ Z_ R_ F_ K_", "XYZRFK", [], "Feeds to Z, stops the spindle, rapids out and restarts the spindle.";
    G86,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.48",  "Boring cycle", "G86 (format not in the manual)", LNC_CYCLE, [], "Listed as boring; explained in the missing chapter 5.";
    G86,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Boring cycle, spindle stop, rapid out", "G86 X_ Y_ Z_ R_ [L_] P_", "XYZUVWRLPF", [], "Feeds to Z, dwells P, stops the spindle, rapids to clear Z and restarts the spindle in its previous direction.";
    G87,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.49",  "Back boring cycle", "G87 X_ Y_ Z_ R_ Q_ P_ F_ K_", "XYZRQPFK", [], "At X Y orients and shifts off by Q, rapids down to R, shifts back, starts CW, feeds up to Z, dwells P, orients, shifts and rapids out to the initial level (SYN: shift direction Pr4020).";
    G87,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.49",  "Back boring cycle", "G87 X_ Y_ Z_ R_ Q_ P_ F_ L_", KT_CYCLE, [], "Back boring with shift Q (as G76, P018 bits); always returns to the initial plane (G99 ignored but kept); ⚠ manual ambiguous: the shift directions and orientation points are not given.";
    G87,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.49",  "Back boring cycle", "G87 (format not in the manual)", LNC_CYCLE, [], "Listed as back boring; explained in the missing chapter 5.";
    G87,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Back boring cycle", "G87 X_ Y_ Z_ R_ I_ J_ K_ [L_]", "XYZUVWRIJKLF", [], "Accepted but not implemented by LinuxCNC (behaviour undefined).";
    G87.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted side drilling cycle", "G87.1 Z(W)_ C(H)_ X(U)_ R_ P_ Q_ F_ K_ M_ E_", "XUCHZWRPQFKME", [], "Drills along X tilted by E: X(U) = depth from R, positioning on Z and C; otherwise as G83.1; group 10 in the GSK manual.";
    G88,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.50",  "Boring cycle, manual retract", "G98/G99 G88 X_ Y_ R_ Z_ P_ F_ L_", KT_CYCLE, [], "Feeds to Z, dwells P, stops the spindle and pauses for a manual retract; on cycle start rapids to the initial or R plane and restarts CW; Q ignored but kept.";
    G88,      SYNTEC,                         Cycle,       Modal,    -,                       Full,       -,     "4.50",  "Semi-automatic fine boring cycle", "G88 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPFK", [], "Feeds to Z, dwells P (s), stops the spindle for a manual move out; after restart feeds (G01) to R, rapids to the return level and restarts the spindle.";
    G88,      FANUC,                          Cycle,       Modal,    -,                       Full,       -,     "",      "Boring cycle, manual retract", "G88 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPFK", [], "Feeds to Z, dwells, stops the spindle and the program for a manual retract, then returns to the initial or R level and restarts the spindle.";
    G88,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Boring cycle, spindle stop, manual out", "G88 X_ Y_ Z_ R_ [L_] P_", "XYZUVWRLPF", [], "Accepted but not implemented by LinuxCNC (behaviour undefined).";
    G88.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted side tapping cycle", "G88.1 Z(W)_ C(H)_ X(U)_ R_ Q_ P_ F_ K_ M_ E_", "XUCHZWRQPFKMSE", [], "Taps along X tilted by E, rigid (M29) or normal, as G84.1; group 10 in the GSK manual.";
    G89,      [FANUC SYNTEC],                 Cycle,       Modal,    -,                       Full,       -,     "4.51",  "Boring cycle with dwell", "G89 X_ Y_ Z_ R_ P_ F_ K_", "XYZRPFK", [], "Feeds to Z, dwells P, feeds back to R, then rapids to the initial level (G98).";
    G89,      KT,                             Cycle,       Modal,    -,                       Full,       -,     "4.51",  "Boring cycle with dwell", "G98/G99 G89 X_ Y_ R_ Z_ P_ F_ L_", KT_CYCLE, [], "Feeds to Z, dwells P, feeds back to R, then to the initial plane if G98; Q ignored but kept; L holes along the line to X Y.";
    G89,      LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.51",  "Boring cycle", "G89 (format not in the manual)", LNC_CYCLE, [], "Listed as boring; explained in the missing chapter 5.";
    G89,      LINUXCNC,                       Motion,      Modal,    -,                       Full,       -,     "",      "Boring cycle, dwell, feed out", "G89 X_ Y_ Z_ R_ P_ [L_]", "XYZUVWRLPF", [], "Feeds to Z, dwells P seconds and feeds back to clear Z.";
    G89.1,    GSK,                            Cycle,       Modal,    -,                       Full,       -,     "4.52",  "Slanted side boring cycle", "G89.1 Z(W)_ C(H)_ X(U)_ R_ P_ F_ K_ M_ E_", "XUCHZWRPFKME", [], "Bores along X tilted by E: feed in, dwell P, feed out to R; words as G87.1 (no Q); group 10 in the GSK manual.";
    // ---- G90-G99: distance, G92, feed and spindle modes, return level -----------------------
    G90,      [FANUC SYNTEC LNC KT LINUXCNC], Distance,    Modal,    [FANUC LNC LINUXCNC],    Full,       -,     "4.53",  "Absolute programming", "G90", "", [], "End points are work coordinates. KT: also fixes how cycle R/Z, the G16 pole and the G68 angle read; LNC: a B axis without a B stroke takes the shorter way (ties +).";
    G90.1,    LINUXCNC,                       ArcDistance, Modal,    -,                       Full,       -,     "",      "Absolute arc centre mode", "G90.1", "", [], "I/J/K of arcs are absolute positions.";
    G91,      [FANUC SYNTEC LNC KT LINUXCNC], Distance,    Modal,    -,                       Full,       -,     "4.53",  "Incremental programming", "G91", "", [], "End points are distances from the current position (KT cycles: R from the initial plane, Z from R; LNC: B rotates by the commanded angle).";
    G91.1,    LINUXCNC,                       ArcDistance, Modal,    LINUXCNC,                Full,       -,     "",      "Incremental arc centre mode", "G91.1", "", [], "I/J/K of arcs are offsets from the start point (the default).";
    G92,      [FANUC SYNTEC LNC],             NonModal,    OneShot,  -,                       Full,       -,     "4.54",  "Set work coordinate system", "G92 X_ Y_ Z_", "XYZABC", [], "Gives the current position the commanded coordinates (absolute whatever G90/G91), shifting every work system; forbidden during rotation (LNC). SYN: offsets in #1901-#1916; G92 S_ clamps the G96 spindle speed.";
    G92,      KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.54",  "Set work coordinate system", "G92 X_ Y_ Z_", "XYZ", [], "Mentioned only: forbidden during coordinate rotation and in a length-compensation block; used in the rotation example (G92 G69 G17 X0 Y0).";
    G92,      LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Coordinate system offset", "G92 axes", "XYZABCUVW", ["XYZABCUVW"], "Offsets every coordinate system so the current point gets the given coordinates (parameters 5211-5219, kept between runs).";
    G92.1,    SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.55",  "Absolute zero-point preset with rotation", "G92.1 X_ Y_ K_ R_", "XYZKR", [], "Presets the program zero like G92 and rotates the program XY plane by R deg about program Z (#1930); ⚠ manual ambiguous: format text missing, K unexplained, example labels swapped.";
    G92.1,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Cancel G92 offsets", "G92.1", "", [], "Turns the G92 offsets off and zeroes parameters 5211-5219.";
    G92.2,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Suspend G92 offsets", "G92.2", "", [], "Turns the G92 offsets off but keeps parameters 5211-5219.";
    G92.3,    LINUXCNC,                       NonModal,    OneShot,  -,                       Full,       -,     "",      "Restore G92 offsets", "G92.3", "", [], "Sets the G92 offsets from parameters 5211-5219.";
    G93,      SYNTEC,                         FeedMode,    Modal,    -,                       Full,       -,     "4.56",  "Inverse time feed", "G93", "", [], "F applies to its own block only (Cor85 if missing); the manual defines the feed as F x block length (G01) or F x radius (G02/G03), not 1/time; modal until G94/G95; not in HPCC.";
    G93,      LINUXCNC,                       FeedMode,    Modal,    -,                       Full,       -,     "",      "Inverse time feed", "G93", "", [], "Each G1/G2/G3 block must carry F: the move takes 1/F minutes.";
    G94,      [FANUC SYNTEC LINUXCNC],        FeedMode,    Modal,    [FANUC SYNTEC LINUXCNC], Full,       -,     "4.57",  "Feed per minute", "G94", "", [], "F in mm/min (inch/min). SYN: the milling power-on default (Pr3836), default F1000.";
    G94,      LNC,                            FeedMode,    Modal,    -,                       ListOnly,   -,     "4.57",  "Feed per minute", "G94", "", [], "Listed without a modal flag or power-on mark.";
    G95,      [FANUC SYNTEC LINUXCNC],        FeedMode,    Modal,    -,                       Full,       -,     "4.57",  "Feed per revolution", "G95", "", [], "F in mm/rev (inch/rev). SYN: the lathe default, default F1.";
    G96,      [FANUC SYNTEC],                 SpindleMode, Modal,    -,                       Full,       -,     "4.58",  "Constant surface speed", "G96 S_", "S", [], "S = surface speed (m/min or ft/min); rpm = 1000 S / (pi D); G92 S_ clamps the maximum rpm (SYN).";
    G96,      LINUXCNC,                       SpindleMode, Modal,    -,                       Full,       -,     "",      "Constant surface speed", "G96 [D_] S_", "DS", ["S"], "S = surface speed, D = maximum rpm; X0 must be the rotation centre.";
    G97,      [FANUC SYNTEC LINUXCNC],        SpindleMode, Modal,    [FANUC LINUXCNC],        Full,       -,     "4.58",  "Constant surface speed cancel", "G97 S_", "S", [], "Spindle speed S in rpm.";
    G98,      [FANUC SYNTEC LNC KT LINUXCNC], ReturnLevel, Modal,    [FANUC LNC KT LINUXCNC], Full,       -,     "4.59",  "Return to initial level", "G98", "", [], "Canned cycles return to the initial plane (LinuxCNC: the old Z if above R). KT: power-on state from P021 bit5 FDMD, 0 = G98 (⚠ manual ambiguous: FDMD may be the feed mode); KT G87 always returns here.";
    G98,      GSK,                            FeedMode,    Modal,    -,                       Full,       -,     "4.59",  "Feed per minute", "G98", "", [], "In the manual's examples G98 selects feed per minute; ⚠ manual ambiguous: in G-code system B G98/G99 select the cycle return plane instead (slanted cycles must return to the initial plane).";
    G99,      [FANUC SYNTEC LNC KT LINUXCNC], ReturnLevel, Modal,    -,                       Full,       -,     "4.59",  "Return to R level", "G99", "", [], "Canned cycles return to the R plane (KT: ignored by G87 but kept modal).";
    G99,      GSK,                            FeedMode,    Modal,    -,                       Mentioned,  -,     "4.59",  "Feed per revolution", "G99", "", [], "Not shown in the manual: read as feed per revolution by analogy with G98 = feed per minute in the examples; ⚠ manual ambiguous: in G-code system B G99 returns to the R plane.";
    // ---- G100-G189: LNC and Syntec extensions --------------------------------------------
    G100,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Non-stop tool change", "G100 (format not in the manual)", UNKNOWN, [], "Non-stop ATC; one-shot; format not in the manual.";
    G114.1,   SYNTEC,                         NonModal,    Modal,    -,                       Mentioned,  -,     "4.28",  "Spindle synchronisation", "G114.1 (format not in the manual)", UNKNOWN, [], "Mentioned only as a mode that blocks the M96 interrupt subprogram; group and format not documented.";
    G114.3,   SYNTEC,                         NonModal,    Modal,    -,                       Mentioned,  -,     "4.28",  "Spindle load (lit.)", "G114.3 (format not in the manual)", UNKNOWN, [], "Mentioned only as a mode that blocks the M96 interrupt subprogram; meaning, group and format not documented.";
    G120,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Move to measuring position", "G120 (format not in the manual)", UNKNOWN, [], "Positions to the measuring position; one-shot; alarm during G68 rotation.";
    G120.1,   SYNTEC,                         NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Multiple machining-condition sets", "G120.1 (format not in the manual)", UNKNOWN, [], "In the G-code list only, no section (see the G62/G64 P0-P9 condition sets); modality not documented.";
    G121,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: angle (boss)", "G121 X_ Y_ I_ J_ Z_ R_", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G122,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: parallel (groove)", "G122 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G123,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: parallel (boss)", "G123 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G124,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: centre, 3 points in a hole", "G124 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G125,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: centre, 3 points on a boss", "G125 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G126,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: centre, 4 points in a hole", "G126 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G127,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: centre, 4 points on a boss", "G127 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G128,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: Z height", "G128 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G129,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.60",  "Automatic measurement: angle (groove)", "G129 (format not in the manual)", UNKNOWN, [], "Optional automatic measurement (separate manual); results feed G10 L98/L99 and G168; alarm during rotation.";
    G131,     LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.61",  "Measuring feed with alarm", "G131 X_ Y_ Z_ F_", "XYZF", [], "Feeds toward X Y Z (up to 3 axes) until the detection signal turns on; alarm 'detection signal OFF' if it never does; alarm under cutter compensation or rotation.";
    G132,     LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.61",  "Measuring feed without alarm", "G132 X_ Y_ Z_ F_", "XYZF", [], "Feeds toward X Y Z (up to 3 axes) until the detection signal turns on; no alarm if it never does; alarm under cutter compensation or rotation.";
    G133,     LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.62",  "Tapping with forward spindle", "G133 Z_ {I_ | J_} S_", "ZIJS", ["IJ"], "One-shot tapping to Z with Z synchronised to the spindle turning forward: I = pitch, J = number of thread starts (⚠ manual ambiguous: may be threads per inch), S = speed; repeat G133 in every block.";
    G134,     LNC,                            NonModal,    OneShot,  -,                       Full,       -,     "4.62",  "Tapping with reverse spindle", "G134 Z_ {I_ | J_} S_", "ZIJS", ["IJ"], "One-shot tapping to Z with Z synchronised to the spindle turning in reverse: I = pitch, J = number of thread starts (⚠ manual ambiguous: may be threads per inch), S = speed. Not the Syntec bolt-hole circle.";
    G134,     SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.63",  "Bolt-hole circle pattern", "G134 X_ Y_ I_ J_ K_", "XYIJK", ["I", "K"], "Runs the stored canned cycle (set with K0) at K holes on a circle of radius I about X Y, the first at angle J; ⚠ manual ambiguous: the sign of K presumably sets the direction.";
    G135,     SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.63",  "Angled line hole pattern", "G135 X_ Y_ I_ J_ K_", "XYIJK", ["I", "K"], "Runs the stored canned cycle at K holes (start included) from X Y, spacing I (negative = the other way), on a line at angle J from the X axis.";
    G136,     SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.63",  "Arc hole pattern", "G136 X_ Y_ I_ J_ P_ K_", "XYIJPK", ["I", "K"], "Runs the stored canned cycle at K holes on an arc of radius I about X Y, from angle J at angular pitch P (+ = CCW; an integer P is in 0.001 deg).";
    G137.1,   SYNTEC,                         NonModal,    OneShot,  -,                       Full,       -,     "4.63",  "Grid hole pattern", "G137.1 X_ Y_ I_ P_ J_ K_", "XYIPJK", ["P", "K"], "Runs the stored canned cycle on a grid from X Y: P holes at spacing I along X, K rows at spacing J along Y.";
    G142,     KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.64",  "G142 (meaning not documented)", "G142", UNKNOWN, [], "Named only as a code not allowed in a length-compensation block.";
    G143,     KT,                             NonModal,    OneShot,  -,                       Mentioned,  -,     "4.64",  "G143 (meaning not documented)", "G143", UNKNOWN, [], "Named only as a code not allowed in a length-compensation block.";
    G168,     LNC,                            Rotation,    Modal,    -,                       Full,       -,     "4.35",  "Rotation by a measured angle", "G168 X_ Y_ Q_", "XYQ", [], "Rotates by the angle of measurement result Q (1-4, default 1) about X Y (absolute; omitted = position at G69->G168); otherwise as G68.";
    G173,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.65",  "High-speed deep-hole drilling cycle", "G173 (format not in the manual)", LNC_CYCLE, [], "One-shot cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G177,     LNC,                            Cycle,       Modal,    -,                       Mentioned,  -,     "4.65",  "G177 (priority tables only)", "G177 (not in the G-code list)", LNC_CYCLE, [], "⚠ manual ambiguous: appears only in the priority tables as the group 'G177~G189', not in the G-code list (perhaps a typo for G173).";
    G181,     LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.65",  "Two-stage drilling cycle", "G181 (format not in the manual)", LNC_CYCLE, [], "Modal two-stage drilling cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G182,     LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.65",  "Two-stage drilling cycle", "G182 (format not in the manual)", LNC_CYCLE, [], "Modal two-stage drilling cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G183,     LNC,                            NonModal,    OneShot,  -,                       ListOnly,   -,     "4.65",  "Deep-hole drilling cycle", "G183 (format not in the manual)", LNC_CYCLE, [], "One-shot cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G185,     LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.65",  "Two-stage boring cycle", "G185 (format not in the manual)", LNC_CYCLE, [], "Modal two-stage boring cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G186,     LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.65",  "Two-stage boring cycle", "G186 (format not in the manual)", LNC_CYCLE, [], "Modal two-stage boring cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    G189,     LNC,                            Cycle,       Modal,    -,                       ListOnly,   -,     "4.65",  "Two-stage boring cycle", "G189 (format not in the manual)", LNC_CYCLE, [], "Modal two-stage boring cycle (⚠ manual ambiguous: the list's modal flags are interleaved); format not in the manual.";
    // ---- M codes -----------------------------------------------------------------------------
    M00,      [FANUC SYNTEC LINUXCNC],        Stop,        OneShot,  -,                       Full,       -,     "5.1",   "Program stop", "M00", "", [], "Stops the program until cycle start (SYN: spindle, feed and coolant stop; honours the M00 switch).";
    M01,      [FANUC SYNTEC LINUXCNC],        Stop,        OneShot,  -,                       Full,       -,     "5.1",   "Optional stop", "M01", "", [], "Stops like M00 only when the optional-stop switch is on.";
    M02,      [FANUC SYNTEC LINUXCNC],        Stop,        OneShot,  -,                       Full,       -,     "5.1",   "Program end", "M02", "", [], "Ends the program (SYN: in a subprogram it returns to the caller; LinuxCNC: resets the modes to their defaults).";
    M02,      LNC,                            Stop,        OneShot,  -,                       Mentioned,  -,     "5.1",   "Program end", "M02", "", [], "Mentioned only as cancelling G68 rotation (⚠ manual ambiguous: printed 'M02 (M03)', probably M30).";
    M03,      [FANUC SYNTEC GSK LINUXCNC],    Spindle,     Modal,    -,                       Full,       -,     "5.1",   "Spindle CW", "M03 S_", "S", [], "Starts the spindle clockwise at S (GSK: the spindle or live tool; SYN: S1= addresses spindle 1).";
    M03,      KT,                             Spindle,     Modal,    -,                       Mentioned,  -,     "5.1",   "Spindle CW", "M03", "S", [], "Mentioned only: G86 outputs M03 after its retract.";
    M04,      [FANUC SYNTEC GSK LINUXCNC],    Spindle,     Modal,    -,                       Full,       -,     "5.1",   "Spindle CCW", "M04 S_", "S", [], "Starts the spindle counter-clockwise at S (GSK: the spindle or live tool).";
    M05,      [FANUC SYNTEC GSK LINUXCNC],    Spindle,     Modal,    LINUXCNC,                Full,       -,     "5.1",   "Spindle stop", "M05", "", [], "Stops the spindle (SYN: before changing range or direction; GSK: also the live tool).";
    M05,      KT,                             Spindle,     Modal,    -,                       Mentioned,  -,     "5.1",   "Spindle stop", "M05", "", [], "Mentioned only: G86 outputs M05 at the hole bottom; parameter P021 bit2 chooses whether M05 turns the analog output off.";
    M06,      [FANUC SYNTEC LINUXCNC],        ToolChange,  OneShot,  -,                       Full,       -,     "5.1",   "Tool change", "M06", "", [], "Changes to the tool selected with T (T03 M06); does not select the tool itself.";
    M07,      LINUXCNC,                       Coolant,     Modal,    -,                       Full,       -,     "",      "Mist coolant on", "M7", "", [], "Turns mist coolant on.";
    M08,      [FANUC SYNTEC LINUXCNC],        Coolant,     Modal,    -,                       Full,       -,     "5.1",   "Coolant on", "M08", "", [], "Turns (flood) coolant on.";
    M09,      [FANUC SYNTEC LINUXCNC],        Coolant,     Modal,    LINUXCNC,                Full,       -,     "5.1",   "Coolant off", "M09", "", [], "Turns all coolant off.";
    M14,      GSK,                            OtherM,      Modal,    -,                       Mentioned,  -,     "5.1",   "C-axis indexing on (assumed)", "M14", "", [], "Used in the examples as C-axis indexing on, stated as an assumption; machine-specific.";
    M15,      GSK,                            OtherM,      Modal,    -,                       Mentioned,  -,     "5.1",   "C-axis indexing off (assumed)", "M15", "", [], "Used in the examples as C-axis indexing off, stated as an assumption; machine-specific.";
    M19,      [FANUC SYNTEC],                 Spindle,     Modal,    -,                       Full,       -,     "5.1",   "Spindle orientation", "M19", "", [], "Stops the spindle at a set angle.";
    M19,      LINUXCNC,                       Spindle,     Modal,    -,                       Full,       -,     "",      "Spindle orientation", "M19 R_ [Q_] [P_]", "RQP", [], "Orients the spindle to angle R (deg) within Q seconds; P = direction (0 shortest, 1 CW, 2 CCW); cleared by M3/M4/M5.";
    M20,      KT,                             OtherM,      Modal,    -,                       Mentioned,  -,     "A",     "M20 output", "M20", "", [], "Mentioned only in parameter RE20 (P021 bit6): 1 = reset or emergency stop does not turn the M20 output off.";
    M29,      [FANUC GSK],                    OtherM,      Modal,    -,                       Full,       -,     "4.52",  "Rigid tapping mode", "M29 S_", "S", [], "Makes the next tapping cycle rigid (GSK: G84.1/G88.1; stops the spindle; no S word or axis move between M29 and the cycle; M29 again in the cycle = alarm).";
    M30,      [FANUC SYNTEC KT GSK LINUXCNC], Stop,        OneShot,  -,                       Full,       -,     "5.1",   "Program end and rewind", "M30", "", [], "Ends the program and rewinds to its start (SYN: in a subprogram it returns to the caller; LinuxCNC: also pallet exchange and mode reset).";
    M48,      LINUXCNC,                       Override,    Modal,    LINUXCNC,                Full,       -,     "",      "Enable overrides", "M48", "", [], "Enables the feed and spindle speed override controls.";
    M49,      LINUXCNC,                       Override,    Modal,    -,                       Full,       -,     "",      "Disable overrides", "M49", "", [], "Disables the feed and spindle speed override controls.";
    M50,      LINUXCNC,                       Override,    Modal,    -,                       Full,       -,     "",      "Feed override control", "M50 [P_]", "P", [], "P1 (default) enables the feed override control, P0 disables it.";
    M51,      LINUXCNC,                       Override,    Modal,    -,                       Full,       -,     "",      "Spindle override control", "M51 [P_]", "P", [], "P1 (default) enables the spindle speed override control, P0 disables it.";
    M52,      LINUXCNC,                       Override,    Modal,    -,                       Full,       -,     "",      "Adaptive feed control", "M52 [P_]", "P", [], "P1 (default) scales the feed by the adaptive-feed input, P0 stops doing so.";
    M53,      LINUXCNC,                       Override,    Modal,    -,                       Full,       -,     "",      "Feed stop control", "M53 [P_]", "P", [], "P1 (default) enables the feed-stop switch, P0 disables it.";
    M60,      LINUXCNC,                       Stop,        OneShot,  -,                       Full,       -,     "",      "Pallet change pause", "M60", "", [], "Exchanges pallet shuttles and pauses the program until cycle start.";
    M61,      LINUXCNC,                       ToolChange,  OneShot,  -,                       Full,       -,     "",      "Set current tool", "M61 Q_", "Q", ["Q"], "Sets the tool number in the spindle to Q without a tool change.";
    M62,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Digital output on, synchronised", "M62 P_", "P", ["P"], "Turns digital output P on at the start of the next motion.";
    M63,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Digital output off, synchronised", "M63 P_", "P", ["P"], "Turns digital output P off at the start of the next motion.";
    M64,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Digital output on, immediate", "M64 P_", "P", ["P"], "Turns digital output P on at once.";
    M65,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Digital output off, immediate", "M65 P_", "P", ["P"], "Turns digital output P off at once.";
    M66,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Wait on input", "M66 P_ | E_ [L_] [Q_]", "PELQ", ["PE"], "Waits for digital input P or reads analog input E; L = wait mode (0 immediate, 1 rise, 2 fall, 3 high, 4 low), Q = timeout in seconds; result in #5399.";
    M67,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Analog output, synchronised", "M67 E_ Q_", "EQ", ["E"], "Sets analog output E to Q at the start of the next motion.";
    M68,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Analog output, immediate", "M68 E_ Q_", "EQ", ["E"], "Sets analog output E to Q at once.";
    M70,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Save modal state", "M70", "", [], "Saves the current modal state.";
    M71,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Invalidate stored modal state", "M71", "", [], "Invalidates the modal state saved by M70.";
    M72,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Restore modal state", "M72", "", [], "Restores the modal state saved by M70.";
    M73,      LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "Save modal state for autorestore", "M73", "", [], "Saves the modal state and restores it automatically when the subroutine returns.";
    M74,      KT,                             OtherM,      Modal,    -,                       Mentioned,  -,     "A",     "M74 output", "M74", "", [], "Mentioned only: data parameter 279 sets the M74 output port.";
    M90,      SYNTEC,                         OtherM,      Modal,    -,                       Full,       -,     "4.21",  "Tool-setter air blow on", "M90", "", [], "Turns the tool-setter air blow on (used by G37.1; not in the M-code table).";
    M91,      SYNTEC,                         OtherM,      Modal,    -,                       Full,       -,     "4.21",  "Tool-setter air blow off", "M91", "", [], "Turns the tool-setter air blow off (used by G37.1; not in the M-code table).";
    M96,      SYNTEC,                         Subprogram,  Modal,    -,                       Full,       -,     "5.3",   "Interrupt subprogram on", "M96 P_", "P", ["P"], "Arms interrupt subprogram P, called at once when C-bit C49 turns on; ignored under G5, G5.1, G12.1, G16, G41/G42, G51, G51.1, G51.2, G114.1, G114.3 and inside subprograms.";
    M97,      SYNTEC,                         Subprogram,  Modal,    -,                       Full,       -,     "5.3",   "Interrupt subprogram off", "M97", "", [], "Disarms the M96 interrupt subprogram.";
    M98,      SYNTEC,                         Subprogram,  OneShot,  -,                       Full,       whole, "5.3",   "Subprogram call", "M98 P_ H_ L_", "PHL", ["PH"], "Calls program P (omitted = this program) from sequence number H, L times; M98 H100 runs the block range from N100 of the same program up to M99.";
    M98,      [FANUC KT LINUXCNC],            Subprogram,  OneShot,  -,                       Full,       whole, "5.3",   "Subprogram call", "M98 P_ L_", "PL", ["P"], "Calls program O<P> L times (KT: M98 P2200 L7 runs O2200 seven times; subprograms may nest).";
    M99,      SYNTEC,                         Subprogram,  OneShot,  -,                       Full,       whole, "5.3",   "Subprogram return", "M99 [P_ | Q_]", "PQ", [], "Returns after the calling M98/M198, to sequence number P, or (from an interrupt subprogram) to line Q; a plain return from an interrupt re-executes the interrupted block.";
    M99,      [FANUC KT LINUXCNC],            Subprogram,  OneShot,  -,                       Full,       whole, "5.3",   "Subprogram return", "M99 [P_]", "P", [], "Returns to the calling program (Fanuc: to sequence number P if given).";
    M100,     LINUXCNC,                       OtherM,      OneShot,  -,                       Full,       -,     "",      "User-defined M code (M100-M199)", "M100 [P_] [Q_]", "PQ", [], "Runs the executable user file M1nn with P and Q as arguments; M101-M199 work the same way.";
    M198,     SYNTEC,                         Subprogram,  OneShot,  -,                       ListOnly,   whole, "5.1",   "External subprogram call", "M198 (format not in the manual)", UNKNOWN, [], "Calls an external subprogram (version 10.116.2); the format is not in the manual.";
    M198,     FANUC,                          Subprogram,  OneShot,  -,                       Full,       whole, "",      "External subprogram call", "M198 P_ L_", "PL", ["P"], "Calls a subprogram file from external memory (memory card or data server).";
};

/// What each address letter means, per dialect (§2.2, plus the Fanuc 0i-M and LinuxCNC
/// readings).
pub static ADDRESSES: &[AddressDef] = addresses! {
    A, LNC,                            "Optional rotary axis A (alarm if the axis is not purchased)";
    A, [FANUC LINUXCNC],               "A axis (rotary about X)";
    B, LNC,                            "Optional rotary axis B in degrees (without a B stroke an absolute move takes the shorter way)";
    B, SYNTEC,                         "B rotary axis (G43.4 RTCP example)";
    B, [FANUC LINUXCNC],               "B axis (rotary about Y)";
    C, LNC,                            "Optional rotary axis C (alarm if not purchased); ,C = chamfer on G01";
    C, GSK,                            "Spindle C axis: angular position of the hole (H = incremental C)";
    C, SYNTEC,                         "C rotary axis (G43.4 example); G12.1 C-direction eccentricity";
    C, [FANUC LINUXCNC],               "C axis (rotary about Z)";
    D, LNC,                            "Cutter radius offset number (G41 D1)";
    D, SYNTEC,                         "Radius offset number (G41/G42, G45-G48); G37 allowed trigger distance";
    D, FANUC,                          "Cutter radius offset number (G41/G42, G45-G48)";
    D, LINUXCNC,                       "Tool number for G41/G42; cutter diameter for G41.1/G42.1; maximum rpm for G96; G70-G72 stock distance";
    E, GSK,                            "Slant angle of the slanted-hole cycles, -60 to +60 deg, modal (E0 = alarm)";
    E, SYNTEC,                         "Threads per inch (G74/G84); tolerance (G05, G05.1)";
    E, LINUXCNC,                       "Analog channel (M66-M68); G76 taper length; G70 final distance";
    F, KT,                             "Cutting feed; in G74/G84 the thread pitch (modal; I = threads per inch)";
    F, LNC,                            "Feed in mm/min (deg/min when B moves); modal";
    F, GSK,                            "Feed per minute or per revolution; tapping lead = F/S or F";
    F, SYNTEC,                         "Feed (G94 mm/min, G95 mm/rev); G33 lead; G93 inverse-time factor; F2= retract feed (G81)";
    F, FANUC,                          "Feed (mm/min in G94, mm/rev in G95); G33 lead";
    F, LINUXCNC,                       "Feed rate (units/min in G94, units/rev in G95, 1/minutes in G93)";
    G, ALL,                            "Preparatory function (G code)";
    H, KT,                             "Tool length offset number H01-H24 (H00 cancels)";
    H, LNC,                            "Tool length offset number (G43/G44 are listed; the format is not in the manual)";
    H, GSK,                            "Incremental C, as in C(H)";
    H, SYNTEC,                         "Tool length offset (tool) number for G43/G44/G43.4; M98 H = sequence number to start from";
    H, FANUC,                          "Tool length offset number (G43/G44)";
    H, LINUXCNC,                       "Tool number for G43/G43.2; G76 spring passes";
    I, KT,                             "Threads per inch in G74/G84";
    I, LNC,                            "Arc centre X offset (start to centre, always incremental); G22 -X limit; G133/G134 thread pitch";
    I, SYNTEC,                         "Arc centre X offset (centre - start); G22 -X limit; G51 X scale; G68.2 Euler angle; G134-G137.1 radius or spacing";
    I, FANUC,                          "Arc centre X offset; G22 -X limit; G51 X scale factor";
    I, LINUXCNC,                       "Arc centre X offset (per G90.1/G91.1); G5/G5.1 control point; G76 thread peak offset; G71/G72 cut depth";
    J, LNC,                            "Arc centre Y offset (always incremental); G22 -Y limit; G133/G134 thread starts (⚠ manual ambiguous: may be threads per inch)";
    J, SYNTEC,                         "Arc centre Y offset (centre - start); G22 -Y limit; G51 Y scale; G68.2 Euler angle; G134-G136 start angle, G137.1 Y spacing";
    J, FANUC,                          "Arc centre Y offset; G22 -Y limit; G51 Y scale factor";
    J, LINUXCNC,                       "Arc centre Y offset; G5/G5.1 control point; G76 first cut depth";
    K, LNC,                            "G22 -Z limit";
    K, GSK,                            "Repeat count of the slanted-hole cycles (K0 = store the data only)";
    K, SYNTEC,                         "Arc centre Z offset; G22 -Z limit; G51 Z scale; G68.2 Euler angle; cycle repeat count (K0 = store only); G134-G137.1 hole count";
    K, FANUC,                          "Arc centre Z offset; G22 -Z limit; canned-cycle repeat count";
    K, LINUXCNC,                       "Arc centre Z offset; G33/G33.1 distance per revolution; G76 full thread depth";
    L, KT,                             "Number of holes on a line in canned cycles (non-modal); M98 repeat count";
    L, LNC,                            "G10 data type";
    L, SYNTEC,                         "G02/G03 spiral turns; G65/G66/M98 repeat count; G10 data type";
    L, FANUC,                          "G10 data type; M98/G65/G66 repeat count";
    L, LINUXCNC,                       "G10 data type; canned-cycle repeat count; G76 taper ends; M66 wait mode; G5.2 NURBS order";
    M, [FANUC SYNTEC LNC KT LINUXCNC], "Miscellaneous function (M code)";
    M, GSK,                            "Miscellaneous function; in a slanted-hole cycle block the C-axis clamp M code";
    N, SYNTEC,                         "Sequence number; also the label for M98 H and M99 P";
    N, [FANUC LNC KT GSK LINUXCNC],    "Sequence number";
    O, [FANUC SYNTEC LNC KT GSK],      "Program number (O####)";
    O, LINUXCNC,                       "O-word: subroutine and control-flow label (o100 sub, o100 call)";
    P, KT,                             "Dwell (as G04); M98 program number";
    P, LNC,                            "G04 dwell (s); G10 offset or coordinate-system number; G30 P2-P4; G54.1 P1-P48";
    P, GSK,                            "Bottom dwell: 1 ms (IS-B) / 0.1 ms (IS-C)";
    P, SYNTEC,                         "G04 dwell (ms); cycle dwell (s, G84 ms); G05 P10000/P0; G06.2 order; G30 point; G51 scale; G62/G64 condition set; G65/G66/M98/M96 program; G136 angle pitch; G137.1 X count; M99 return N";
    P, FANUC,                          "Dwell in ms; M98/G65/G66 program number; G10/G54.1 number; G30 reference point";
    P, LINUXCNC,                       "Dwell in seconds (G4, cycles); G10 tool or coordinate-system number; G2/G3 turns; G64 tolerance; M62-M66 I/O number; G76 pitch";
    Q, KT,                             "Peck depth (G73/G83); bottom shift (G76/G87); default 0.1 mm";
    Q, LNC,                            "G10 L98/L99 measurement-storage number; G168 result 1-4";
    Q, GSK,                            "Depth per cut: radius value, integer in least input units";
    Q, SYNTEC,                         "Peck depth (G73/G83, peck tapping); shift (G76/G87); G31 skip signal C101-C132; G05.1 mode; G37.1 safety point; M99 return line number";
    Q, FANUC,                          "Peck depth (G73/G83); shift (G76/G87)";
    Q, LINUXCNC,                       "Peck increment (G73/G83); G5 control point; G64 naive-CAM tolerance; G76 compound angle; M61 tool; G70-G72 subroutine; M66 timeout";
    R, KT,                             "Canned-cycle R plane; G68 rotation angle; arc radius";
    R, LNC,                            "Arc radius (-R for more than 180 deg); G10 value; G68 angle; ,R = corner rounding on G01";
    R, GSK,                            "Distance from the initial plane to the R point (radius value, signed)";
    R, SYNTEC,                         "Arc radius; cycle R point; G68 angle; G37/G37.1 measuring distance; G06.2 weight; G92.1 angle";
    R, FANUC,                          "Arc radius; canned-cycle R point; G68 angle; G10 offset value";
    R, LINUXCNC,                       "Arc radius; canned-cycle retract plane; G10 tool radius or rotation; G76 depth degression; M19 angle";
    S, KT,                             "Spindle speed (not described in the KT manual)";
    S, LNC,                            "Spindle speed (G133/G134)";
    S, GSK,                            "Spindle speed (M29 S_ for rigid tapping)";
    S, SYNTEC,                         "Spindle speed (rpm in G97, surface speed in G96); G92 S = maximum speed; S1= spindle 1";
    S, [FANUC LINUXCNC],               "Spindle speed (rpm; surface speed in G96)";
    T, SYNTEC,                         "Tool select, used with M06 (T03 M06)";
    T, [FANUC LINUXCNC],               "Tool select (M06 changes to it)";
    U, GSK,                            "Incremental X, as in X(U)";
    W, GSK,                            "Incremental Z, as in Z(W)";
    U, SYNTEC,                         "Incremental X when Pr3809 = 1";
    V, SYNTEC,                         "Incremental Y when Pr3809 = 1";
    W, SYNTEC,                         "Incremental Z when Pr3809 = 1";
    U, FANUC,                          "Additional linear axis U (parallel to X); G04 dwell";
    V, FANUC,                          "Additional linear axis V (parallel to Y)";
    W, FANUC,                          "Additional linear axis W (parallel to Z)";
    U, LINUXCNC,                       "U axis (linear, parallel to X)";
    V, LINUXCNC,                       "V axis (linear, parallel to Y)";
    W, LINUXCNC,                       "W axis (linear, parallel to Z)";
    X, KT,                             "X coordinate; under G16 the radius when X is the 1st plane axis; G68 centre";
    X, LNC,                            "X coordinate; G04 dwell (s); G22 +X limit; G68/G168 centre";
    X, GSK,                            "X coordinate (diameter programming implied); hole depth in G87.1/G89.1/G88.1";
    X, SYNTEC,                         "X coordinate; G04 dwell; G22 +X limit; G12.1 eccentricity; G51 centre; G51.1 mirror axis; G68 centre; G68.2 origin";
    X, FANUC,                          "X coordinate; G04 dwell (s); G22 +X limit";
    X, LINUXCNC,                       "X coordinate";
    Y, KT,                             "Y coordinate; under G16 the angle when Y is the 2nd plane axis; G68 centre";
    Y, LNC,                            "Y coordinate; G22 +Y limit; G68/G168 centre";
    Y, SYNTEC,                         "Y coordinate; G22 +Y limit; G51 centre; G51.1 mirror axis; G68 centre; G68.2 origin";
    Y, [FANUC LINUXCNC],               "Y coordinate";
    Z, KT,                             "Z coordinate; canned-cycle hole bottom";
    Z, LNC,                            "Z coordinate; G22 +Z limit";
    Z, GSK,                            "Z coordinate; hole depth (R to bottom) in G83.1/G85.1/G84.1";
    Z, SYNTEC,                         "Z coordinate; cycle Z point; G22 +Z limit; G37/G37.1 measuring position; G51 centre";
    Z, [FANUC LINUXCNC],               "Z coordinate; canned-cycle hole bottom";
};

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use std::collections::HashMap;

    use super::{ADDRESSES, CODES};
    use crate::Dialect;
    use crate::codes::{Code, Group, codes_of, lookup};

    fn code(text: &str) -> Code {
        Code::parse(text).unwrap()
    }

    #[test]
    fn no_dialect_in_two_entries_of_one_code() {
        for (i, a) in CODES.iter().enumerate() {
            assert!(!a.dialects.is_empty(), "{} has no dialect", a.code);
            assert!(matches!(a.code.letter, b'G' | b'M'), "{}", a.code);
            for b in &CODES[i + 1..] {
                if a.code == b.code {
                    let both = a.dialects.0 & b.dialects.0;
                    assert!(both == 0, "{} is listed twice for {both:#b}", a.code);
                }
            }
        }
    }

    #[test]
    fn only_calls_and_returns_need_the_whole_program() {
        let whole: Vec<String> = CODES
            .iter()
            .filter(|d| d.whole)
            .map(|d| d.code.to_string())
            .collect();
        assert_eq!(
            whole,
            [
                "G65", "G65", "G66", "G66", "M98", "M98", "M99", "M99", "M198", "M198"
            ]
        );
    }

    #[test]
    fn power_on_is_a_subset_of_dialects() {
        for d in CODES {
            assert!(
                d.power_on.0 & !d.dialects.0 == 0,
                "{} ({}) is on at power-on in a dialect it is not in",
                d.code,
                d.name
            );
        }
    }

    #[test]
    fn at_most_one_power_on_code_per_exclusive_group() {
        let mut clashes = Vec::new();
        for dialect in Dialect::ALL {
            let mut seen: HashMap<Group, Code> = HashMap::new();
            for d in codes_of(dialect).filter(|d| d.power_on.contains(dialect)) {
                if !d.group.exclusive() {
                    continue;
                }
                if let Some(other) = seen.insert(d.group, d.code) {
                    clashes.push(format!("{dialect}: {other} and {}", d.code));
                }
            }
        }
        assert!(
            clashes.is_empty(),
            "two power-on codes in one group: {clashes:?}"
        );
    }

    #[test]
    fn fanuc_and_linuxcnc_power_on_states() {
        let on = |dialect: Dialect| -> Vec<String> {
            let mut v: Vec<String> = codes_of(dialect)
                .filter(|d| d.power_on.contains(dialect))
                .map(|d| d.code.to_string())
                .collect();
            v.sort();
            v
        };
        let fanuc = on(Dialect::Fanuc);
        for c in [
            "G00", "G15", "G17", "G21", "G22", "G40", "G49", "G50", "G50.1", "G54", "G64", "G67",
            "G69", "G80", "G90", "G94", "G97", "G98",
        ] {
            assert!(fanuc.contains(&c.to_string()), "Fanuc power-on lacks {c}");
        }
        let linuxcnc = on(Dialect::LinuxCnc);
        for c in [
            "G17", "G21", "G40", "G49", "G54", "G64", "G80", "G90", "G91.1", "G94", "G97", "G98",
            "M05", "M09", "M48",
        ] {
            assert!(
                linuxcnc.contains(&c.to_string()),
                "LinuxCNC power-on lacks {c}"
            );
        }
        let lnc = on(Dialect::Lnc);
        for c in [
            "G00", "G22", "G40", "G49", "G54", "G64", "G67", "G69", "G80", "G90", "G98",
        ] {
            assert!(lnc.contains(&c.to_string()), "LNC power-on lacks {c}");
        }
        assert_eq!(on(Dialect::Kt), ["G15", "G98"]);
    }

    #[test]
    fn required_letters_are_words() {
        for d in CODES {
            for group in d.required {
                assert!(!group.is_empty(), "{}: empty required group", d.code);
                for c in group.chars() {
                    assert!(
                        d.words.contains(c),
                        "{} ({}): required {c} is not in words {:?}",
                        d.code,
                        d.name,
                        d.words
                    );
                }
            }
        }
    }

    #[test]
    fn words_are_distinct_uppercase_letters() {
        for d in CODES {
            let mut seen = [false; 26];
            for b in d.words.bytes() {
                assert!(b.is_ascii_uppercase(), "{}: bad word letter {b:?}", d.code);
                let i = usize::from(b - b'A');
                assert!(
                    !seen[i],
                    "{}: {} listed twice in words",
                    d.code,
                    char::from(b)
                );
                seen[i] = true;
            }
        }
    }

    #[test]
    fn text_is_plain_ascii_apart_from_the_warning_sign() {
        let plain = |s: &str| s.chars().all(|c| c.is_ascii() || c == '⚠');
        for d in CODES {
            assert!(!d.name.is_empty() && !d.summary.is_empty() && !d.format.is_empty());
            assert!(plain(d.name), "{}: name {:?}", d.code, d.name);
            assert!(plain(d.format), "{}: format {:?}", d.code, d.format);
            assert!(plain(d.summary), "{}: summary {:?}", d.code, d.summary);
            assert!(plain(d.section), "{}: section {:?}", d.code, d.section);
        }
        for a in ADDRESSES {
            assert!(
                plain(a.meaning),
                "{}: {:?}",
                char::from(a.letter),
                a.meaning
            );
        }
    }

    #[test]
    fn addresses_cover_every_letter_in_every_dialect() {
        for a in ADDRESSES {
            assert!(a.letter.is_ascii_uppercase());
            assert!(!a.dialects.is_empty());
        }
        for (i, a) in ADDRESSES.iter().enumerate() {
            for b in &ADDRESSES[i + 1..] {
                if a.letter == b.letter {
                    assert!(
                        a.dialects.0 & b.dialects.0 == 0,
                        "{} has two readings in one dialect",
                        char::from(a.letter)
                    );
                }
            }
        }
        for letter in b'A'..=b'Z' {
            assert!(
                ADDRESSES.iter().any(|a| a.letter == letter),
                "no reading for {}",
                char::from(letter)
            );
        }
        for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::LinuxCnc] {
            for letter in b"DFGHIJKLMNOPQRSTXYZ" {
                assert!(
                    crate::codes::address(dialect, *letter).next().is_some(),
                    "{dialect}: no reading for {}",
                    char::from(*letter)
                );
            }
        }
    }

    #[test]
    fn code_lists_per_dialect() {
        // The codes each dialect has: §8 of the reference for KT, LNC, GSK and Syntec; the
        // Fanuc 0i-M and LinuxCNC 2.9 code lists for the others.
        let expected = [
            (
                Dialect::Fanuc,
                "G00 G01 G02 G03 G04 G05.1 G07.1 G09 G10 G11 G15 G16 G17 G18 G19 G20 G21 G22 G23 G27 G28 G29 G30 G31 G33 G37 G39 G40 G41 G42 G43 G44 G45 G46 G47 G48 G49 G50 G50.1 G51 G51.1 G52 G53 G54 G54.1 G55 G56 G57 G58 G59 G60 G61 G62 G63 G64 G65 G66 G67 G68 G69 G73 G74 G76 G80 G81 G82 G83 G84 G85 G86 G87 G88 G89 G90 G91 G92 G94 G95 G96 G97 G98 G99 M00 M01 M02 M03 M04 M05 M06 M08 M09 M19 M29 M30 M98 M99 M198",
            ),
            (
                Dialect::Syntec,
                "G00 G01 G02 G03 G04 G05 G05.1 G06.2 G09 G10 G12.1 G13.1 G15 G16 G17 G18 G19 G22 G23 G28 G29 G30 G31 G33 G37 G37.1 G40 G41 G42 G43 G43.4 G44 G45 G46 G47 G48 G49 G50 G50.1 G51 G51.1 G51.2 G52 G53 G53.1 G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3 G59.4 G59.5 G59.6 G59.7 G59.8 G59.9 G61 G62 G63 G64 G65 G66 G67 G68 G68.2 G69 G70 G71 G73 G74 G76 G80 G81 G82 G83 G84 G85 G86 G87 G88 G89 G90 G91 G92 G92.1 G93 G94 G95 G96 G97 G98 G99 G114.1 G114.3 G120.1 G134 G135 G136 G137.1 M00 M01 M02 M03 M04 M05 M06 M08 M09 M19 M30 M90 M91 M96 M97 M98 M99 M198",
            ),
            (
                Dialect::Lnc,
                "G00 G01 G02 G03 G04 G09 G10 G22 G23 G28 G29 G30 G36 G37 G38 G39 G40 G41 G42 G43 G44 G49 G53 G54 G54.1 G55 G56 G57 G58 G59 G61 G64 G65 G66 G67 G68 G69 G73 G74 G76 G77 G78 G80 G81 G82 G83 G84 G85 G86 G87 G89 G90 G91 G92 G94 G98 G99 G100 G120 G121 G122 G123 G124 G125 G126 G127 G128 G129 G131 G132 G133 G134 G168 G173 G177 G181 G182 G183 G185 G186 G189 M02",
            ),
            (
                Dialect::Kt,
                "G00 G01 G02 G03 G04 G15 G16 G17 G18 G19 G28 G31 G40 G43 G44 G49 G52 G54 G55 G56 G57 G58 G59 G68 G69 G73 G74 G76 G80 G81 G82 G83 G84 G85 G86 G87 G88 G89 G90 G91 G92 G98 G99 G142 G143 M03 M05 M20 M30 M74 M98 M99",
            ),
            (
                Dialect::Gsk,
                "G00 G01 G17 G18 G19 G80 G83.1 G84.1 G85.1 G87.1 G88.1 G89.1 G98 G99 M03 M04 M05 M14 M15 M29 M30",
            ),
            (
                Dialect::LinuxCnc,
                "G00 G01 G02 G03 G04 G05 G05.1 G05.2 G05.3 G07 G08 G10 G17 G17.1 G18 G18.1 G19 G19.1 G20 G21 G28 G28.1 G30 G30.1 G33 G33.1 G38.2 G38.3 G38.4 G38.5 G40 G41 G41.1 G42 G42.1 G43 G43.1 G43.2 G49 G52 G53 G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3 G61 G61.1 G64 G70 G71 G71.1 G71.2 G72 G72.1 G72.2 G73 G74 G76 G80 G81 G82 G83 G84 G85 G86 G87 G88 G89 G90 G90.1 G91 G91.1 G92 G92.1 G92.2 G92.3 G93 G94 G95 G96 G97 G98 G99 M00 M01 M02 M03 M04 M05 M06 M07 M08 M09 M19 M30 M48 M49 M50 M51 M52 M53 M60 M61 M62 M63 M64 M65 M66 M67 M68 M70 M71 M72 M73 M98 M99 M100",
            ),
        ];
        for (dialect, list) in expected {
            // The manual's own codes (not the standard ones read as on Fanuc).
            let have: Vec<String> = codes_of(dialect)
                .filter(|d| !super::super::is_fanuc_reading(dialect, d))
                .map(|d| d.code.to_string())
                .collect();
            assert_eq!(have.join(" "), list, "{dialect}");
        }
    }

    #[test]
    fn standard_codes_missing_from_a_manual_are_read_as_on_fanuc() {
        for dialect in [Dialect::Lnc, Dialect::Kt, Dialect::Gsk] {
            for c in ["G21", "M03", "M05", "M30", "M98", "M99"] {
                assert!(lookup(dialect, code(c)).is_some(), "{dialect} {c}");
            }
        }
        let g21 = lookup(Dialect::Lnc, code("G21")).unwrap();
        assert!(g21.dialects.contains(Dialect::Fanuc));
        assert!(super::super::is_fanuc_reading(Dialect::Lnc, g21));
        // KT's own M03 stays KT's; Syntec's units stay G70/G71.
        assert!(!super::super::is_fanuc_reading(
            Dialect::Kt,
            lookup(Dialect::Kt, code("M03")).unwrap()
        ));
        assert!(lookup(Dialect::Syntec, code("G21")).is_none());
        assert!(lookup(Dialect::Lnc, code("M19")).is_none());
    }

    #[test]
    fn syntec_units_are_g70_g71() {
        let g70 = lookup(Dialect::Syntec, code("G70")).unwrap();
        let g71 = lookup(Dialect::Syntec, code("G71")).unwrap();
        assert_eq!(g70.group, Group::Units);
        assert_eq!(g71.group, Group::Units);
        assert!(lookup(Dialect::Syntec, code("G20")).is_none());
        assert!(lookup(Dialect::Syntec, code("G21")).is_none());
        assert_eq!(
            lookup(Dialect::Fanuc, code("G21")).unwrap().group,
            Group::Units
        );
        // LinuxCNC's G70/G71 are lathe cycles.
        assert_eq!(
            lookup(Dialect::LinuxCnc, code("G71")).unwrap().group,
            Group::NonModal
        );
    }

    #[test]
    fn g134_differs_between_syntec_and_lnc() {
        let syn = lookup(Dialect::Syntec, code("G134")).unwrap();
        let lnc = lookup(Dialect::Lnc, code("G134")).unwrap();
        assert!(syn.name.contains("Bolt-hole"));
        assert!(lnc.name.contains("Tapping"));
        assert_eq!(syn.section, "4.63");
        assert_eq!(lnc.section, "4.62");
    }

    #[test]
    fn canned_cycle_groups() {
        let linuxcnc = lookup(Dialect::LinuxCnc, code("G81")).unwrap();
        let fanuc = lookup(Dialect::Fanuc, code("G81")).unwrap();
        assert_eq!(linuxcnc.group, Group::Motion);
        assert_eq!(fanuc.group, Group::Cycle);
        assert_eq!(
            lookup(Dialect::LinuxCnc, code("G80")).unwrap().group,
            Group::Motion
        );
        assert_eq!(
            lookup(Dialect::Gsk, code("G83.1")).unwrap().group,
            Group::Cycle
        );
        assert!(lookup(Dialect::Gsk, code("G81")).is_none());
        assert!(lookup(Dialect::Lnc, code("G88")).is_none());
    }

    #[test]
    fn every_spec_dialect_has_g80() {
        for dialect in Dialect::ALL {
            assert!(
                lookup(dialect, code("G80")).is_some(),
                "{dialect} lacks G80"
            );
        }
    }

    #[test]
    fn clashing_meanings() {
        // G98 on the GSK lathe is feed per minute (examples); elsewhere the return level.
        assert_eq!(
            lookup(Dialect::Gsk, code("G98")).unwrap().group,
            Group::FeedMode
        );
        assert_eq!(
            lookup(Dialect::Kt, code("G98")).unwrap().group,
            Group::ReturnLevel
        );
        // G37: LNC coordinate calculation vs Syntec tool measurement.
        assert_ne!(
            lookup(Dialect::Lnc, code("G37")).unwrap().name,
            lookup(Dialect::Syntec, code("G37")).unwrap().name
        );
        // G76: LinuxCNC threading vs fine boring elsewhere.
        assert!(
            lookup(Dialect::LinuxCnc, code("G76"))
                .unwrap()
                .name
                .contains("Thread")
        );
        assert!(
            lookup(Dialect::Fanuc, code("G76"))
                .unwrap()
                .name
                .contains("boring")
        );
        // G86 and G88: KT vs Syntec.
        assert_ne!(
            lookup(Dialect::Kt, code("G86")).unwrap().name,
            lookup(Dialect::Syntec, code("G86")).unwrap().name
        );
        assert_ne!(
            lookup(Dialect::Kt, code("G88")).unwrap().name,
            lookup(Dialect::Syntec, code("G88")).unwrap().name
        );
        // Dwell words per dialect.
        assert_eq!(lookup(Dialect::LinuxCnc, code("G4")).unwrap().words, "P");
        assert_eq!(lookup(Dialect::Syntec, code("G4")).unwrap().words, "XP");
        assert_eq!(lookup(Dialect::Fanuc, code("G4")).unwrap().words, "XPU");
        // M98: Syntec allows H instead of P.
        assert_eq!(
            lookup(Dialect::Syntec, code("M98")).unwrap().required,
            ["PH"]
        );
        assert_eq!(lookup(Dialect::Kt, code("M98")).unwrap().required, ["P"]);
    }
}
