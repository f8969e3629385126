//! Every G and M code each dialect knows, as data: [`table::CODES`] lists a code once per meaning,
//! tagged with its dialects, so a dialect difference is an entry, not an `if`.

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

    /// The code a `G` or `M` word names, if its value is a valid code number (non-negative, at
    /// most one decimal digit, below 10000).
    pub fn of_word(word: &Word) -> Option<Code> {
        let code_word = matches!(word.letter, b'G' | b'M') && word.expr.is_none();
        code_word.then(|| Code::from_value(word.letter, word.value))?
    }

    /// The code for `letter` and a numeric value, if the value is a valid code number.
    #[inline]
    pub fn from_value(letter: u8, value: f64) -> Option<Code> {
        let scaled = value * 10.0;
        // The nearest tenth must lie in 0..100000 (NaN refused); there truncating the positive
        // `scaled + 0.5` rounds without a libm call (near a half it is refused below anyway).
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
        let letter = text.bytes().next()?.to_ascii_uppercase();
        let value: f64 = text.get(1..)?.trim().parse().ok()?;
        matches!(letter, b'G' | b'M').then(|| Code::from_value(letter, value))?
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (letter, whole, frac) = (char::from(self.letter), self.tenths / 10, self.tenths % 10);
        match frac {
            0 => write!(f, "{letter}{whole:02}"),
            _ => write!(f, "{letter}{whole:02}.{frac}"),
        }
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
        DialectSet(1 << dialect as u8)
    }

    /// Whether `dialect` is in the set.
    pub const fn contains(self, dialect: Dialect) -> bool {
        self.0 & DialectSet::of(dialect).0 != 0
    }

    /// The union of two sets.
    pub const fn or(self, other: DialectSet) -> DialectSet {
        DialectSet(self.0 | other.0)
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
        let labels: Vec<&str> = self.iter().map(Dialect::label).collect();
        labels.join(", ")
    }
}

crate::ast::named_enum! {
    /// The modal group of a code: codes of one group replace each other, and two of one group
    /// in a block is an error. Named after the Fanuc 0i-M groups; LinuxCNC's groups map onto
    /// them.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Group;
    /// The group's name for messages and documentation.
    fn name;
    NonModal    "one-shot (group 00)"                 "Group 00: one-shot codes (dwell, G10, G28, G53, G92 …).";
    Motion      "motion (group 01)"                   "Group 01: G00–G03 and other motions (in LinuxCNC also the canned cycles and G80).";
    Plane       "plane (group 02)"                    "Group 02: plane selection G17/G18/G19.";
    Distance    "absolute/incremental (group 03)"     "Group 03: G90/G91.";
    ArcDistance "arc centre mode"                     "LinuxCNC G90.1/G91.1: arc centre distance mode.";
    StrokeLimit "stroke limit (group 04)"             "Group 04: stroke limits G22/G23.";
    FeedMode    "feed mode (group 05)"                "Group 05: feed mode G93/G94/G95.";
    Units       "units (group 06)"                    "Group 06: inch/metric (G20/G21, Syntec G70/G71).";
    CutterComp  "cutter compensation (group 07)"      "Group 07: cutter radius compensation G40/G41/G42.";
    LengthComp  "tool length compensation (group 08)" "Group 08: tool length compensation G43/G44/G49.";
    Cycle       "canned cycle (group 09)"             "Group 09: canned cycles and G80 (Fanuc family).";
    ReturnLevel "cycle return level (group 10)"       "Group 10: canned-cycle return level G98/G99.";
    Scaling     "scaling (group 11)"                  "Group 11: scaling G50/G51.";
    MacroModal  "modal macro call (group 12)"         "Group 12: modal macro call G66/G67.";
    SpindleMode "spindle speed mode (group 13)"       "Group 13: constant surface speed G96/G97.";
    WorkOffset  "work coordinate system (group 14)"   "Group 14: work coordinate systems G54–G59, G54.1, G59.n.";
    PathMode    "cutting mode (group 15)"             "Group 15: cutting modes G61–G64.";
    Rotation    "coordinate rotation (group 16)"      "Group 16: coordinate rotation G68/G69 (LNC G168).";
    Polar       "polar coordinates (group 17)"        "Group 17: polar coordinate command G15/G16.";
    PolarInterp "polar interpolation (group 21)"      "Group 21: polar coordinate interpolation G12.1/G13.1.";
    Mirror      "mirror image (group 22)"             "Group 22: mirror image G50.1/G51.1.";
    Smoothing   "high-speed/smoothing mode"           "High-speed / smoothing modes (Syntec G05, G05.1; LinuxCNC G64 P).";
    LatheMode   "diameter/radius mode"                "Lathe diameter/radius mode (LinuxCNC G7/G8).";
    Spindle     "spindle (M)"                         "Spindle M codes M03/M04/M05 (M19).";
    Coolant     "coolant (M)"                         "Coolant M codes M07/M08/M09.";
    Stop        "program stop (M)"                    "Program stops and ends M00/M01/M02/M30/M60.";
    ToolChange  "tool change (M)"                     "Tool change M06.";
    Subprogram  "subprogram (M)"                      "Subprogram call and return M98/M99 and similar.";
    Override    "override switches (M)"               "Feed/speed override switches (LinuxCNC M48–M53).";
    OtherM      "miscellaneous (M)"                   "Any other M code (machine-specific outputs).";
}

impl Group {
    /// Whether two codes of this group may not share a block.
    pub fn exclusive(self) -> bool {
        !matches!(self, Group::NonModal | Group::OtherM)
    }
}

crate::ast::named_enum! {
    /// Whether a code stays in effect after its block.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Modality;
    /// The name `swarf explain` shows.
    fn name;
    Modal   "modal"    "Stays in effect until another code of its group (常态 / 模态 / 模式).";
    OneShot "one-shot" "Effective only in its block (一次通过 / 單節有效).";
}

crate::ast::named_enum! {
    /// How completely the dialect's manual documents a code.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Documented;
    /// The name `swarf explain --json` gives.
    fn name;
    Full      "full"      "Format and behaviour are documented.";
    ListOnly  "list"      "Only in the manual's code list: the format is not documented.";
    Mentioned "mentioned" "Mentioned in passing: neither format nor behaviour is documented.";
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
    /// Whether a block with the code needs the whole program to run: it calls a program or a
    /// macro (G65, G66, M98, M198) or returns from one (M99).
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

/// A dialect's codes as entries of [`CODES`] (`u16::MAX`: none), per letter (G, M) and number in
/// tenths: the first definition of each it has, for the lookup every G and M word makes.
type Index = [Vec<u16>; 2];

/// The code numbers (in tenths) an [`Index`] covers: every code of [`CODES`] is below it.
const DENSE: usize = 2000;

/// The dialect's [`Index`], built on its first use (each dialect's apart: a run reads one
/// dialect, and building all six would cost every start).
fn index(dialect: Dialect) -> &'static Index {
    static INDEX: [OnceLock<Index>; 6] = [const { OnceLock::new() }; 6];
    INDEX[dialect as usize].get_or_init(|| {
        let mut index = [vec![u16::MAX; DENSE], vec![u16::MAX; DENSE]];
        // Each code's first definition the dialect has, else (in a [`FANUC_READING`] dialect)
        // its first Fanuc definition when it is a standard code.
        let reads_fanuc = FANUC_READING.contains(&dialect);
        let entries = CODES.iter().enumerate();
        let own = (entries.clone()).filter(|(_, d)| d.dialects.contains(dialect));
        let fanuc = entries.filter(|(_, d)| {
            reads_fanuc && d.dialects.contains(Dialect::Fanuc) && is_fanuc_standard(d.code)
        });
        for (i, def) in own.chain(fanuc) {
            let letter = usize::from(def.code.letter == b'M');
            if let Some(cell) = index[letter].get_mut(def.code.tenths as usize)
                && *cell == u16::MAX
            {
                *cell = u16::try_from(i).unwrap_or(u16::MAX);
            }
        }
        index
    })
}

/// The dialects whose manuals (as the reference recovers them) leave out codes every Fanuc-family
/// control has: LNC's manual covers only the G codes, KT's and GSK's name a handful of M codes
/// and no inch/metric codes. A machinist writing M03 or G21 for them means what Fanuc means.
const FANUC_READING: [Dialect; 3] = [Dialect::Lnc, Dialect::Kt, Dialect::Gsk];

/// Whether `code` is read as on Fanuc where a [`FANUC_READING`] dialect's manual does not give
/// it: the planes G17–G19, G20/G21, G40, M00–M06, M08, M09, M30, M98, M99.
fn is_fanuc_standard(code: Code) -> bool {
    match code.letter {
        b'G' => [170, 180, 190, 200, 210, 400].contains(&code.tenths),
        _ => [0, 10, 20, 30, 40, 50, 60, 80, 90, 300, 980, 990].contains(&code.tenths),
    }
}

/// Whether `def` is in `dialect`'s table only as the Fanuc reading of a standard code its manual
/// does not give (see `FANUC_READING`).
pub fn is_fanuc_reading(dialect: Dialect, def: &CodeDef) -> bool {
    !def.dialects.contains(dialect) && FANUC_READING.contains(&dialect)
}

/// The bit of an uppercase letter in a set of letters (0 for anything else).
#[inline(always)]
pub(crate) const fn letter_bit(letter: u8) -> u32 {
    if letter.is_ascii_uppercase() {
        1 << (letter - b'A')
    } else {
        0
    }
}

/// The bits of a set of letters (bit 0 = A).
pub(crate) const fn letter_mask(letters: &[u8]) -> u32 {
    let (mut mask, mut i) = (0, 0);
    while i < letters.len() {
        mask |= letter_bit(letters[i]);
        i += 1;
    }
    mask
}

/// The meaning of `code` in `dialect`, if the dialect has it.
#[inline]
pub fn lookup(dialect: Dialect, code: Code) -> Option<&'static CodeDef> {
    let letter = [b'G', b'M'].iter().position(|&l| l == code.letter)?;
    let i = *index(dialect)[letter].get(code.tenths as usize)?;
    CODES.get(usize::from(i))
}

/// Every code `dialect` has, sorted by code.
pub fn codes_of(dialect: Dialect) -> impl Iterator<Item = &'static CodeDef> {
    let entries = index(dialect).iter().flatten();
    entries.filter_map(|&i| CODES.get(usize::from(i)))
}

/// Every meaning `code` has across the dialects (for "G134 means … on Syntec but … on LNC").
pub fn meanings(code: Code) -> impl Iterator<Item = &'static CodeDef> {
    CODES.iter().filter(move |d| d.code == code)
}

/// What `letter` means in `dialect` (every reading that applies).
pub fn address(dialect: Dialect, letter: u8) -> impl Iterator<Item = &'static AddressDef> {
    let letter = letter.to_ascii_uppercase();
    (ADDRESSES.iter()).filter(move |a| a.letter == letter && a.dialects.contains(dialect))
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
                let standard = is_fanuc_standard(def.code);
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
        assert!(CODES.iter().all(|d| (d.code.tenths as usize) < DENSE));
        for dialect in Dialect::ALL {
            let entry = |d: &CodeDef| CODES.iter().position(|c| std::ptr::eq(c, d));
            let slot: Vec<(Code, u16)> = codes_of(dialect)
                .map(|d| (d.code, u16::try_from(entry(d).unwrap()).unwrap()))
                .collect();
            assert_eq!(slot, plain_index(dialect), "{dialect:?}");
            assert!(!slot.is_empty());
        }
    }
}
