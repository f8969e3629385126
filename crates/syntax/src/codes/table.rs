//! The code and address tables, derived from the G-code reference (`gcode-reference.md`, §2–§5
//! and §8) for KT, LNC, GSK and Syntec, and from the Fanuc 0i-M and LinuxCNC code lists for the
//! `fanuc` and `linuxcnc` dialects.

use super::{AddressDef, Code, CodeDef, DialectSet, Documented, Group, Modality};

const FANUC: DialectSet = DialectSet::FANUC;
const SYNTEC: DialectSet = DialectSet::SYNTEC;
const LNC: DialectSet = DialectSet::LNC;
const KT: DialectSet = DialectSet::KT;
const GSK: DialectSet = DialectSet::GSK;
const LINUXCNC: DialectSet = DialectSet::LINUXCNC;
const NONE: DialectSet = DialectSet::NONE;

/// Builds one entry; `documented` is `Full` unless changed with [`CodeDef`] struct update.
#[allow(clippy::too_many_arguments)]
const fn def(
    code: Code,
    dialects: DialectSet,
    group: Group,
    modality: Modality,
    power_on: DialectSet,
    name: &'static str,
    format: &'static str,
    words: &'static str,
    required: &'static [&'static str],
    summary: &'static str,
    section: &'static str,
) -> CodeDef {
    CodeDef {
        code,
        dialects,
        group,
        modality,
        power_on,
        documented: Documented::Full,
        name,
        format,
        words,
        required,
        summary,
        section,
    }
}

/// The same entry marked as only listed (no documented format).
const fn list_only(d: CodeDef) -> CodeDef {
    CodeDef {
        documented: Documented::ListOnly,
        ..d
    }
}

/// The same entry marked as only mentioned.
const fn mentioned(d: CodeDef) -> CodeDef {
    CodeDef {
        documented: Documented::Mentioned,
        ..d
    }
}

use Group::*;
use Modality::{Modal, OneShot};

const fn g(t: u32) -> Code {
    Code::g(t)
}

const fn m(t: u32) -> Code {
    Code::m(t)
}

/// Every code of every dialect. Where dialects give a code different meanings (G134, G70, G98 …)
/// it has one entry per meaning; the first entry whose `dialects` holds the dialect wins.
pub static CODES: &[CodeDef] = &[
    def(
        g(0),
        DialectSet::ALL,
        Motion,
        Modal,
        DialectSet::ALL,
        "Rapid positioning",
        "G00 X_ Y_ Z_",
        "XYZABCUVW",
        &[],
        "Moves at rapid traverse to the end point; F does not apply.",
        "4.1",
    ),
    def(
        g(10),
        DialectSet::ALL,
        Motion,
        Modal,
        NONE,
        "Linear interpolation",
        "G01 X_ Y_ Z_ F_",
        "XYZABCUVWF",
        &[],
        "Feeds in a straight line to the end point at the F feedrate.",
        "4.2",
    ),
    def(
        g(40),
        DialectSet::ALL,
        NonModal,
        OneShot,
        NONE,
        "Dwell",
        "G04 X_ | G04 P_",
        "XPU",
        &["XPU"],
        "Waits for the given time before the next block.",
        "4.4",
    ),
    list_only(def(
        g(1340),
        LNC,
        NonModal,
        OneShot,
        NONE,
        "Tapping with reverse spindle",
        "G134 Z_ I_ J_ S_",
        "ZIJS",
        &[],
        "Tapping with the spindle direction changed to reverse.",
        "4.62",
    )),
    def(
        g(1340),
        SYNTEC,
        NonModal,
        OneShot,
        NONE,
        "Bolt-hole circle pattern",
        "G134 X_ Y_ I_ J_ K_",
        "XYIJK",
        &["IK"],
        "Runs the stored canned cycle at K holes on a circle of radius I centred at X Y, starting at angle J.",
        "4.63",
    ),
    mentioned(def(
        g(1420),
        KT,
        NonModal,
        OneShot,
        NONE,
        "G142 (meaning not documented)",
        "G142",
        "",
        &[],
        "Named only as a code not allowed in a length-compensation block.",
        "4.64",
    )),
];

/// What each address letter means, per dialect (§2.2).
pub static ADDRESSES: &[AddressDef] = &[AddressDef {
    letter: b'X',
    dialects: DialectSet::ALL,
    meaning: "X axis coordinate (G04: dwell time; G22: + stroke limit; G68: rotation centre)",
}];

// Keep the short dialect names in use while the table grows.
const _: [DialectSet; 5] = [FANUC, GSK, LINUXCNC, KT, SYNTEC];
