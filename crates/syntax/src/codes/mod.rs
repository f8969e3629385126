//! The code tables: every G and M code each dialect knows, as data.
//!
//! One table ([`table::CODES`]) lists each code once per distinct meaning, tagged with the set of
//! dialects that read it that way. Parsing, the same-block checks, the interpreter, hover help and
//! `swarf explain` all read this table, so a dialect difference is an entry, not an `if`.

mod matrix;
mod table;

pub use matrix::markdown_table;

use std::fmt;
use std::sync::OnceLock;

use crate::{Dialect, Word};

/// A G or M code as the control reads it: the letter and the number in tenths (`G54.1` is 541).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Code {
    /// `b'G'` or `b'M'`.
    pub letter: u8,
    /// The code number times ten (`G83.1` → 831).
    pub tenths: u32,
}

impl Code {
    /// `G` code `tenths / 10`.
    pub const fn g(tenths: u32) -> Code {
        Code {
            letter: b'G',
            tenths,
        }
    }

    /// `M` code `tenths / 10`.
    pub const fn m(tenths: u32) -> Code {
        Code {
            letter: b'M',
            tenths,
        }
    }

    /// The code a `G` or `M` word names, if its value is a valid code number (non-negative, at
    /// most one decimal digit, below 10000).
    pub fn of_word(word: &Word) -> Option<Code> {
        if !(word.letter == b'G' || word.letter == b'M') || word.expr.is_some() {
            return None;
        }
        Code::from_value(word.letter, word.value)
    }

    /// The code for `letter` and a numeric value, if the value is a valid code number.
    #[inline]
    pub fn from_value(letter: u8, value: f64) -> Option<Code> {
        let scaled = value * 10.0;
        // Tenths rounded to nearest (half away from zero) must lie in 0..100000: `scaled` in
        // (-0.5, 99999.5), NaN excluded. There `scaled + 0.5` is positive and truncating it
        // rounds without a libm call on every G and M word; next to a half, where the sum may
        // round differently, the value is far from a whole tenth and refused below anyway.
        if !(scaled > -0.5 && scaled < 99_999.5) {
            return None;
        }
        let tenths = (scaled + 0.5) as u32;
        // Exact but for the rounding of the decimal reading (`54.1 × 10`): `G00.9999999` is no
        // code, not G01.
        if (scaled - f64::from(tenths)).abs() > 1e-9 {
            return None;
        }
        Some(Code { letter, tenths })
    }

    /// Parses `G83.1`, `g0`, `M98` (case-insensitive, leading zeros optional).
    pub fn parse(text: &str) -> Option<Code> {
        let text = text.trim();
        let mut chars = text.chars();
        let letter = chars.next()?.to_ascii_uppercase();
        if letter != 'G' && letter != 'M' {
            return None;
        }
        let value: f64 = chars.as_str().trim().parse().ok()?;
        Code::from_value(letter as u8, value)
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let whole = self.tenths / 10;
        let frac = self.tenths % 10;
        write!(f, "{}{whole:02}", char::from(self.letter))?;
        if frac != 0 {
            write!(f, ".{frac}")?;
        }
        Ok(())
    }
}

/// A set of dialects (a bit per [`Dialect`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DialectSet(pub u8);

impl DialectSet {
    /// No dialect.
    pub const NONE: DialectSet = DialectSet(0);
    /// Generic Fanuc 0i-M.
    pub const FANUC: DialectSet = DialectSet(1);
    /// Syntec 900M.
    pub const SYNTEC: DialectSet = DialectSet(2);
    /// LNC / Baoyuan.
    pub const LNC: DialectSet = DialectSet(4);
    /// KT.
    pub const KT: DialectSet = DialectSet(8);
    /// GSK 988TD.
    pub const GSK: DialectSet = DialectSet(16);
    /// LinuxCNC.
    pub const LINUXCNC: DialectSet = DialectSet(32);
    /// The Fanuc family: every dialect but LinuxCNC.
    pub const FANUC_FAMILY: DialectSet = DialectSet(1 | 2 | 4 | 8 | 16);
    /// Every dialect.
    pub const ALL: DialectSet = DialectSet(63);

    /// The set holding only `dialect`.
    pub const fn of(dialect: Dialect) -> DialectSet {
        DialectSet(match dialect {
            Dialect::Fanuc => 1,
            Dialect::Syntec => 2,
            Dialect::Lnc => 4,
            Dialect::Kt => 8,
            Dialect::Gsk => 16,
            Dialect::LinuxCnc => 32,
        })
    }

    /// Whether `dialect` is in the set.
    pub const fn contains(self, dialect: Dialect) -> bool {
        self.0 & DialectSet::of(dialect).0 != 0
    }

    /// The union of two sets.
    pub const fn or(self, other: DialectSet) -> DialectSet {
        DialectSet(self.0 | other.0)
    }

    /// The set without `other`'s dialects.
    pub const fn minus(self, other: DialectSet) -> DialectSet {
        DialectSet(self.0 & !other.0)
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The dialects in the set, in menu order.
    pub fn iter(self) -> impl Iterator<Item = Dialect> {
        Dialect::ALL.into_iter().filter(move |d| self.contains(*d))
    }

    /// The dialects' menu labels joined with ", " (for messages).
    pub fn labels(self) -> String {
        self.iter()
            .map(Dialect::label)
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The modal group of a code: codes of one group replace each other, and two of one group in a
/// block is an error. Named after the Fanuc 0i-M groups; LinuxCNC's groups map onto them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Group {
    /// Group 00: one-shot codes (dwell, G10, G28, G53, G92 …).
    NonModal,
    /// Group 01: G00–G03 and other motions (in LinuxCNC also the canned cycles and G80).
    Motion,
    /// Group 02: plane selection G17/G18/G19.
    Plane,
    /// Group 03: G90/G91.
    Distance,
    /// LinuxCNC G90.1/G91.1: arc centre distance mode.
    ArcDistance,
    /// Group 04: stroke limits G22/G23.
    StrokeLimit,
    /// Group 05: feed mode G93/G94/G95.
    FeedMode,
    /// Group 06: inch/metric (G20/G21, Syntec G70/G71).
    Units,
    /// Group 07: cutter radius compensation G40/G41/G42.
    CutterComp,
    /// Group 08: tool length compensation G43/G44/G49.
    LengthComp,
    /// Group 09: canned cycles and G80 (Fanuc family).
    Cycle,
    /// Group 10: canned-cycle return level G98/G99.
    ReturnLevel,
    /// Group 11: scaling G50/G51.
    Scaling,
    /// Group 12: modal macro call G66/G67.
    MacroModal,
    /// Group 13: constant surface speed G96/G97.
    SpindleMode,
    /// Group 14: work coordinate systems G54–G59, G54.1, G59.n.
    WorkOffset,
    /// Group 15: cutting modes G61–G64.
    PathMode,
    /// Group 16: coordinate rotation G68/G69 (LNC G168).
    Rotation,
    /// Group 17: polar coordinate command G15/G16.
    Polar,
    /// Group 21: polar coordinate interpolation G12.1/G13.1.
    PolarInterp,
    /// Group 22: mirror image G50.1/G51.1.
    Mirror,
    /// High-speed / smoothing modes (Syntec G05, G05.1; LinuxCNC G64 P).
    Smoothing,
    /// Lathe diameter/radius mode (LinuxCNC G7/G8).
    LatheMode,
    /// Spindle M codes M03/M04/M05 (M19).
    Spindle,
    /// Coolant M codes M07/M08/M09.
    Coolant,
    /// Program stops and ends M00/M01/M02/M30/M60.
    Stop,
    /// Tool change M06.
    ToolChange,
    /// Subprogram call and return M98/M99 and similar.
    Subprogram,
    /// Feed/speed override switches (LinuxCNC M48–M53).
    Override,
    /// Any other M code (machine-specific outputs).
    OtherM,
}

impl Group {
    /// The group's name for messages and documentation.
    pub fn name(self) -> &'static str {
        match self {
            Group::NonModal => "one-shot (group 00)",
            Group::Motion => "motion (group 01)",
            Group::Plane => "plane (group 02)",
            Group::Distance => "absolute/incremental (group 03)",
            Group::ArcDistance => "arc centre mode",
            Group::StrokeLimit => "stroke limit (group 04)",
            Group::FeedMode => "feed mode (group 05)",
            Group::Units => "units (group 06)",
            Group::CutterComp => "cutter compensation (group 07)",
            Group::LengthComp => "tool length compensation (group 08)",
            Group::Cycle => "canned cycle (group 09)",
            Group::ReturnLevel => "cycle return level (group 10)",
            Group::Scaling => "scaling (group 11)",
            Group::MacroModal => "modal macro call (group 12)",
            Group::SpindleMode => "spindle speed mode (group 13)",
            Group::WorkOffset => "work coordinate system (group 14)",
            Group::PathMode => "cutting mode (group 15)",
            Group::Rotation => "coordinate rotation (group 16)",
            Group::Polar => "polar coordinates (group 17)",
            Group::PolarInterp => "polar interpolation (group 21)",
            Group::Mirror => "mirror image (group 22)",
            Group::Smoothing => "high-speed/smoothing mode",
            Group::LatheMode => "diameter/radius mode",
            Group::Spindle => "spindle (M)",
            Group::Coolant => "coolant (M)",
            Group::Stop => "program stop (M)",
            Group::ToolChange => "tool change (M)",
            Group::Subprogram => "subprogram (M)",
            Group::Override => "override switches (M)",
            Group::OtherM => "miscellaneous (M)",
        }
    }

    /// Whether two codes of this group may not share a block.
    pub fn exclusive(self) -> bool {
        !matches!(self, Group::NonModal | Group::OtherM)
    }
}

/// Whether a code stays in effect after its block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Modality {
    /// Stays in effect until another code of its group (常态 / 模态 / 模式).
    Modal,
    /// Effective only in its block (一次通过 / 單節有效).
    OneShot,
}

/// How completely the dialect's manual documents a code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Documented {
    /// Format and behaviour are documented.
    Full,
    /// Only in the manual's code list: the format is not documented.
    ListOnly,
    /// Mentioned in passing: neither format nor behaviour is documented.
    Mentioned,
}

/// One meaning of one code, shared by the dialects in `dialects`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CodeDef {
    /// The code.
    pub code: Code,
    /// The dialects that read the code this way.
    pub dialects: DialectSet,
    /// Its modal group.
    pub group: Group,
    /// Modal or one-shot.
    pub modality: Modality,
    /// The dialects (among `dialects`) in which the code is in effect at power-on.
    pub power_on: DialectSet,
    /// How well the manual documents it.
    pub documented: Documented,
    /// Whether a block with the code needs the whole program to run: the code calls a program
    /// or a macro (G65, G66, M98, M198) or returns from one (M99), so a reader that runs a
    /// program piece by piece runs it whole instead.
    pub whole: bool,
    /// Short name, e.g. "Peck drilling cycle".
    pub name: &'static str,
    /// The format line, e.g. "G83 X_ Y_ Z_ R_ Q_ F_ K_".
    pub format: &'static str,
    /// The address letters the code accepts (besides N, and the F S T M D H words any block
    /// may carry).
    pub words: &'static str,
    /// Groups of letters of which at least one must be given, e.g. `&["XP"]` for a dwell.
    pub required: &'static [&'static str],
    /// One line on what it does, for hover help and `swarf explain`.
    pub summary: &'static str,
    /// The section of the G-code reference it comes from ("" where the reference has none).
    pub section: &'static str,
}

pub use table::{ADDRESSES, CODES};

/// What an address letter means in a set of dialects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AddressDef {
    /// The letter, uppercase.
    pub letter: u8,
    /// The dialects this reading applies to.
    pub dialects: DialectSet,
    /// What it means.
    pub meaning: &'static str,
}

/// The dialect's index into [`CODES`], sorted by code, built on its first use (each dialect's
/// apart: a run reads one dialect, and building all six would cost every start).
fn index(dialect: Dialect) -> &'static Vec<(Code, u16)> {
    static INDEX: [OnceLock<Vec<(Code, u16)>>; 6] = [const { OnceLock::new() }; 6];
    INDEX[dialect_slot(dialect)].get_or_init(|| {
        let mut slot = Vec::new();
        // The first definition of each code the dialect has, in the table's order: a stable
        // sort keeps it first among the code's definitions.
        slot.extend(
            CODES
                .iter()
                .enumerate()
                .filter(|(_, def)| def.dialects.contains(dialect))
                .map(|(i, def)| (def.code, u16::try_from(i).unwrap_or(u16::MAX))),
        );
        slot.sort_by_key(|(c, _)| *c);
        slot.dedup_by_key(|(c, _)| *c);
        // The standard codes a dialect's manual leaves out are read as Fanuc reads them.
        if FANUC_READING.contains(&dialect) {
            let mut standard: Vec<(Code, u16)> = Vec::new();
            for (i, def) in CODES.iter().enumerate() {
                let seen = slot.binary_search_by_key(&def.code, |(c, _)| *c).is_ok()
                    || standard.iter().any(|(c, _)| *c == def.code);
                if FANUC_STANDARD.contains(&def.code)
                    && def.dialects.contains(Dialect::Fanuc)
                    && !seen
                {
                    standard.push((def.code, u16::try_from(i).unwrap_or(u16::MAX)));
                }
            }
            slot.extend(standard);
            slot.sort_by_key(|(c, _)| *c);
        }
        slot
    })
}

/// The dialects whose manuals (as the reference recovers them) leave out codes every Fanuc-family
/// control has: LNC's manual covers only the G codes, KT's and GSK's name a handful of M codes
/// and no inch/metric codes. A machinist writing M03 or G21 for them means what Fanuc means.
const FANUC_READING: [Dialect; 3] = [Dialect::Lnc, Dialect::Kt, Dialect::Gsk];

/// The codes read as on Fanuc where a [`FANUC_READING`] dialect's manual does not give them:
/// the planes G17–G19, G20/G21, G40, M00–M06, M08, M09, M30, M98, M99.
const FANUC_STANDARD: [Code; 18] = [
    Code {
        letter: b'G',
        tenths: 170,
    },
    Code {
        letter: b'G',
        tenths: 180,
    },
    Code {
        letter: b'G',
        tenths: 190,
    },
    Code {
        letter: b'G',
        tenths: 400,
    },
    Code {
        letter: b'G',
        tenths: 200,
    },
    Code {
        letter: b'G',
        tenths: 210,
    },
    Code {
        letter: b'M',
        tenths: 0,
    },
    Code {
        letter: b'M',
        tenths: 10,
    },
    Code {
        letter: b'M',
        tenths: 20,
    },
    Code {
        letter: b'M',
        tenths: 30,
    },
    Code {
        letter: b'M',
        tenths: 40,
    },
    Code {
        letter: b'M',
        tenths: 50,
    },
    Code {
        letter: b'M',
        tenths: 60,
    },
    Code {
        letter: b'M',
        tenths: 80,
    },
    Code {
        letter: b'M',
        tenths: 90,
    },
    Code {
        letter: b'M',
        tenths: 300,
    },
    Code {
        letter: b'M',
        tenths: 980,
    },
    Code {
        letter: b'M',
        tenths: 990,
    },
];

/// Whether `def` is in `dialect`'s table only as the Fanuc reading of a standard code its manual
/// does not give (see `FANUC_READING`).
pub fn is_fanuc_reading(dialect: Dialect, def: &CodeDef) -> bool {
    !def.dialects.contains(dialect) && FANUC_READING.contains(&dialect)
}

fn dialect_slot(dialect: Dialect) -> usize {
    match dialect {
        Dialect::Fanuc => 0,
        Dialect::Syntec => 1,
        Dialect::Lnc => 2,
        Dialect::Kt => 3,
        Dialect::Gsk => 4,
        Dialect::LinuxCnc => 5,
    }
}

/// The letters `def` accepts as a bit set (bit 0 = A), for the same-block checks.
pub fn words_mask(def: &CodeDef) -> u32 {
    static MASKS: OnceLock<Vec<u32>> = OnceLock::new();
    let masks = MASKS.get_or_init(|| {
        CODES
            .iter()
            .map(|d| {
                d.words.bytes().fold(0u32, |m, l| {
                    if l.is_ascii_uppercase() {
                        m | 1 << (l - b'A')
                    } else {
                        m
                    }
                })
            })
            .collect()
    });
    // `def` is an element of CODES when it came from a lookup; its position is its offset.
    let offset = (def as *const CodeDef as usize).wrapping_sub(CODES.as_ptr() as usize);
    let index = offset / std::mem::size_of::<CodeDef>().max(1);
    match masks.get(index) {
        Some(mask) if std::ptr::eq(&CODES[index], def) => *mask,
        _ => def.words.bytes().fold(0u32, |m, l| {
            if l.is_ascii_uppercase() {
                m | 1 << (l - b'A')
            } else {
                m
            }
        }),
    }
}

/// Codes below this number (in tenths) are found by direct indexing.
const DENSE: usize = 2000;

/// For the dialect, per letter (G, M), the entry of each code below [`DENSE`] (`u16::MAX`:
/// none): the lookup every G and M word of every block makes.
fn dense(dialect: Dialect) -> &'static [Vec<u16>; 2] {
    static DENSE_INDEX: [OnceLock<[Vec<u16>; 2]>; 6] = [const { OnceLock::new() }; 6];
    DENSE_INDEX[dialect_slot(dialect)].get_or_init(|| {
        let mut slots = [vec![u16::MAX; DENSE], vec![u16::MAX; DENSE]];
        for (code, i) in index(dialect) {
            let letter = usize::from(code.letter == b'M');
            if let Some(cell) = slots[letter].get_mut(code.tenths as usize) {
                *cell = *i;
            }
        }
        slots
    })
}

/// The meaning of `code` in `dialect`, if the dialect has it.
#[inline]
pub fn lookup(dialect: Dialect, code: Code) -> Option<&'static CodeDef> {
    if (code.letter == b'G' || code.letter == b'M') && (code.tenths as usize) < DENSE {
        let letter = usize::from(code.letter == b'M');
        let i = *dense(dialect)[letter].get(code.tenths as usize)?;
        return CODES.get(usize::from(i));
    }
    let slot = index(dialect);
    let at = slot.binary_search_by_key(&code, |(c, _)| *c).ok()?;
    CODES.get(usize::from(slot[at].1))
}

/// Every code `dialect` has, sorted by code.
pub fn codes_of(dialect: Dialect) -> impl Iterator<Item = &'static CodeDef> {
    index(dialect)
        .iter()
        .filter_map(|(_, i)| CODES.get(usize::from(*i)))
}

/// Every meaning `code` has across the dialects (for "G134 means … on Syntec but … on LNC").
pub fn meanings(code: Code) -> impl Iterator<Item = &'static CodeDef> {
    CODES.iter().filter(move |d| d.code == code)
}

/// The codes in effect at power-on in `dialect`.
pub fn power_on(dialect: Dialect) -> impl Iterator<Item = &'static CodeDef> {
    codes_of(dialect).filter(move |d| d.power_on.contains(dialect))
}

/// What `letter` means in `dialect` (every reading that applies).
pub fn address(dialect: Dialect, letter: u8) -> impl Iterator<Item = &'static AddressDef> {
    let letter = letter.to_ascii_uppercase();
    ADDRESSES
        .iter()
        .filter(move |a| a.letter == letter && a.dialects.contains(dialect))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The index by its plain definition: each code's first definition the dialect has, then
    /// the Fanuc reading of the standard codes its manual leaves out, sorted by code.
    fn plain_index(dialect: Dialect) -> Vec<(Code, u16)> {
        let mut slot: Vec<(Code, u16)> = Vec::new();
        for (i, def) in CODES.iter().enumerate() {
            let seen = slot.iter().any(|(c, _)| *c == def.code);
            if def.dialects.contains(dialect) && !seen {
                slot.push((def.code, u16::try_from(i).unwrap_or(u16::MAX)));
            }
        }
        if FANUC_READING.contains(&dialect) {
            for (i, def) in CODES.iter().enumerate() {
                let standard = FANUC_STANDARD.contains(&def.code);
                let seen = slot.iter().any(|(c, _)| *c == def.code);
                if standard && def.dialects.contains(Dialect::Fanuc) && !seen {
                    slot.push((def.code, u16::try_from(i).unwrap_or(u16::MAX)));
                }
            }
        }
        slot.sort_by_key(|(c, _)| *c);
        slot
    }

    #[test]
    fn the_index_is_its_plain_definition() {
        for dialect in Dialect::ALL {
            let slot = index(dialect);
            assert_eq!(*slot, plain_index(dialect), "{dialect:?}");
            assert!(!slot.is_empty());
        }
    }
}
