//! Checks that need no execution: the same-block rules of each dialect, read from the code
//! tables. An error marks the block so the interpreter does not run it; a warning does not.

use crate::codes::{self, Code, CodeDef, DialectSet, Group};
use crate::{Block, Diagnostic, Dialect, Program, Span, Word, WordForm};

/// Letters any block may carry whatever its codes: they set modal values (feed, speed, tool,
/// offset numbers) or are codes themselves.
const ALWAYS: &[u8] = b"NOGMFSTDH";

/// [`ALWAYS`] as a bit set.
const ALWAYS_MASK: u32 = {
    let mut mask = 0u32;
    let mut i = 0;
    while i < ALWAYS.len() {
        mask |= 1 << (ALWAYS[i] - b'A');
        i += 1;
    }
    mask
};

/// Two kinds of code that may not share a block in some dialects.
struct Forbidden {
    dialects: DialectSet,
    first: &'static [u32],
    second: &'static [u32],
    why: &'static str,
}

const ARC: &[u32] = &[20, 30];
const COMP: &[u32] = &[400, 410, 420];
const LENGTH: &[u32] = &[430, 440, 490];
const STROKE: &[u32] = &[220, 230];
const COORD_CALC: &[u32] = &[360, 370, 380, 390];
const LNC_MEASURE: &[u32] = &[1310, 1320, 1330, 1340, 1730, 1830];
const CYCLES: &[u32] = &[
    730, 740, 760, 770, 780, 810, 820, 830, 840, 850, 860, 870, 880, 890,
];
const LNC_ALL_MODAL: &[u32] = &[
    0, 10, 20, 30, 220, 230, 400, 410, 420, 430, 440, 490, 680, 690, 1680, 730, 740, 760, 770, 780,
    800, 810, 820, 830, 840, 850, 860, 870, 880, 890, 900, 910,
];

/// Same-block combinations the manuals forbid. LNC's come from its priority tables (§6 of the
/// reference, the cells recovered as "(2) alarm"); KT's from its G43 rules; the start-up rule for
/// cutter compensation is common to the Fanuc family.
const FORBIDDEN: &[Forbidden] = &[
    Forbidden {
        dialects: DialectSet::FANUC_FAMILY,
        first: ARC,
        second: COMP,
        why: "cutter compensation starts and ends only in a G00/G01 block",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: ARC,
        second: LENGTH,
        why: "LNC changes length compensation only in a G00/G01 block (priority table 1)",
    },
    Forbidden {
        dialects: DialectSet::KT,
        first: LENGTH,
        second: &[20, 30, 40, 920, 310, 1420, 1430],
        why: "KT does not allow G02, G03, G04, G92, G31, G142 or G143 in a length-compensation block",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: STROKE,
        second: &[
            40, 100, 280, 290, 300, 360, 370, 380, 390, 400, 410, 420, 430, 440, 490,
        ],
        why: "LNC priority table 1: G22/G23 may not share a block with this code",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: COMP,
        second: &[40, 100, 280, 290, 300, 360, 370, 380, 390],
        why: "LNC priority table 1: G40–G42 may not share a block with this code",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: LENGTH,
        second: &[40, 100],
        why: "LNC priority table 1: G43/G44/G49 may not share a block with this code",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: &[541],
        second: &[40, 100, 280, 290, 300, 360, 370, 380, 390],
        why: "LNC priority table 1: G54.1 may not share a block with this code",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: &[40],
        second: &[100],
        why: "LNC priority table 4: G04 and G10 may not share a block",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: COORD_CALC,
        second: ARC,
        why: "LNC priority table 1: the coordinate calculations G36–G39 are not allowed with G02/G03",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: &[650, 660, 670],
        second: LNC_ALL_MODAL,
        why: "LNC priority table 2: a macro call G65/G66/G67 must be alone in its block",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: &[680, 690, 1680],
        second: CYCLES,
        why: "LNC priority table 2: rotation and a canned cycle may not share a block",
    },
    Forbidden {
        dialects: DialectSet::LNC,
        first: LNC_MEASURE,
        second: &[
            40, 100, 220, 230, 400, 410, 420, 430, 440, 490, 650, 920, 1000, 1200, 1210, 1220,
            1230, 1240, 1250, 1260, 1270, 1280, 1290,
        ],
        why: "LNC priority tables 3, 5 and 6: measuring feed, tap reversal and G173/G183 must not share a block with this code",
    },
];

/// A code found in a block, and the span of its word.
type Found = (&'static CodeDef, Span);

/// Runs the same-block checks on each block as the parser finishes it (while the block is still
/// in cache), collecting their diagnostics to merge into the program's at the end.
#[derive(Debug)]
pub(crate) struct Checker {
    dialect: Dialect,
    /// G00 and G01 as the plain-block check reads them in the dialect.
    motions: PlainMotions,
    scratch: Vec<Found>,
    out: Vec<Diagnostic>,
}

impl Checker {
    /// A checker for blocks read as `dialect`.
    pub(crate) fn new(dialect: Dialect) -> Self {
        Checker {
            dialect,
            motions: PlainMotions::of(dialect),
            scratch: Vec::new(),
            out: Vec::new(),
        }
    }

    /// Checks `block`; an error marks it so the interpreter does not run it. The common block
    /// with nothing to report costs one pass over its words here, inlined into the reader.
    #[inline(always)]
    pub(crate) fn check(&mut self, block: &mut Block) {
        let scan = PlainScan::of(&block.words);
        self.check_scanned(block, &scan);
    }

    /// Checks `block`, whose words `scan` has seen (a reader that makes the words scans them as
    /// it goes, sparing [`Checker::check`]'s pass over them).
    #[inline(always)]
    pub(crate) fn check_scanned(&mut self, block: &mut Block, scan: &PlainScan) {
        if !self.nothing_to_report(scan) {
            self.check_fully(block);
        }
    }

    /// Whether the words `scan` saw make a block that [`check_plain_block`] takes and finds
    /// nothing in.
    #[inline(always)]
    fn nothing_to_report(&self, scan: &PlainScan) -> bool {
        match scan.result() {
            Some((Some(motion), seen, false)) => {
                self.motions.0[motion].is_some_and(|(_, taken)| seen & !taken == 0)
                    && (motion < 2 || arc_words_fit(seen))
            }
            Some((None, _, false)) => true,
            _ => false,
        }
    }

    #[inline(never)]
    fn check_fully(&mut self, block: &mut Block) {
        let before = self.out.len();
        if !check_plain_block(self.dialect, &self.motions, block, &mut self.out) {
            check_any_block(self.dialect, block, &mut self.scratch, &mut self.out);
        }
        if self.out[before..]
            .iter()
            .any(|d| d.severity == crate::Severity::Error)
        {
            block.set_error();
        }
    }

    /// The diagnostics found so far (merged into the program's by [`Checker::finish`]).
    pub(crate) fn diagnostics(&self) -> &[Diagnostic] {
        &self.out
    }

    /// Merges the diagnostics found into `program`'s, in text order.
    pub(crate) fn finish(self, program: &mut Program) {
        if !self.out.is_empty() {
            program.diagnostics.extend(self.out);
            program.diagnostics.sort_by_key(|d| d.span.start);
        }
    }
}

/// G00, G01, G02 and G03 (at their numbers) in one dialect, looked up once: the definition and
/// the letters a block with the code may carry, or `None` where such a block takes the general
/// check (the code is not a motion there, or needs words).
#[derive(Debug, Clone, Copy)]
struct PlainMotions([Option<(&'static CodeDef, u32)>; 4]);

impl PlainMotions {
    fn of(dialect: Dialect) -> Self {
        let motion = |value: f64| {
            let def = Code::from_value(b'G', value).and_then(|c| codes::lookup(dialect, c))?;
            (def.group == Group::Motion && def.required.is_empty())
                .then(|| (def, ALWAYS_MASK | codes::words_mask(def)))
        };
        PlainMotions([motion(0.0), motion(1.0), motion(2.0), motion(3.0)])
    }
}

/// Whether an arc block's letters (`seen`) give [`arcs`] nothing to report: the centre or the
/// radius, not both, and an end point with the radius.
#[inline(always)]
fn arc_words_fit(seen: u32) -> bool {
    const R: u32 = 1 << (b'R' - b'A');
    const IJK: u32 = 1 << (b'I' - b'A') | 1 << (b'J' - b'A') | 1 << (b'K' - b'A');
    const XYZ: u32 = 1 << (b'X' - b'A') | 1 << (b'Y' - b'A') | 1 << (b'Z' - b'A');
    let has_r = seen & R != 0;
    has_r != (seen & IJK != 0) && (!has_r || seen & XYZ != 0)
}

/// The first pass of [`check_plain_block`] over a block's words: `None` when the block is not
/// one it takes (a word that is not a literal plain one, an M code, a G code other than one
/// G00 to G03); else the G code's number if any, the letters seen besides G, and whether there
/// may be something to report (a letter seen twice or that is not one, a value out of range).
#[inline(always)]
fn plain_pass(words: &[Word]) -> Option<(Option<usize>, u32, bool)> {
    PlainScan::of(words).result()
}

/// The pass of [`plain_pass`], a word at a time.
#[derive(Debug, Default)]
pub(crate) struct PlainScan {
    /// The G code's number plus one (0: none yet).
    motion: u8,
    /// The letters seen besides G.
    seen: u32,
    /// Whether there may be something to report.
    findings: bool,
    /// Whether a word makes the block one that the plain check does not take.
    other: bool,
}

impl PlainScan {
    #[inline(always)]
    fn of(words: &[Word]) -> Self {
        let mut scan = PlainScan::default();
        for w in words {
            if w.form != WordForm::Plain || w.expr.is_some() {
                scan.other = true;
            }
            scan.word(w.letter, w.value);
        }
        scan
    }

    /// Notes a literal plain word.
    #[inline(always)]
    pub(crate) fn word(&mut self, letter: u8, v: f64) {
        match letter {
            b'M' => self.other = true,
            b'G' => {
                let number = if v == 0.0 {
                    1
                } else if v == 1.0 {
                    2
                } else if v == 2.0 {
                    3
                } else if v == 3.0 {
                    4
                } else {
                    0
                };
                self.other |= self.motion != 0 || number == 0;
                self.motion = number;
                return;
            }
            b'F' | b'S' => self.findings |= v < 0.0,
            b'T' | b'H' | b'D' => self.findings |= v < 0.0 || v.fract() != 0.0,
            _ => {}
        }
        let bit = letter_bit(letter);
        self.findings |= bit == 0 || self.seen & bit != 0;
        self.seen |= bit;
    }

    #[inline(always)]
    fn result(&self) -> Option<(Option<usize>, u32, bool)> {
        if self.other {
            return None;
        }
        let motion = usize::from(self.motion).checked_sub(1);
        Some((motion, self.seen, self.findings))
    }
}

/// Checks the common block of CAM output — literal plain words, no M code, at most one G code
/// and that one G00 to G03 — with exactly the findings (in the same order) of
/// [`check_any_block`]; returns `false`, having checked nothing, for any other block. A block
/// with nothing to report costs one pass over its words.
fn check_plain_block(
    dialect: Dialect,
    motions: &PlainMotions,
    block: &Block,
    out: &mut Vec<Diagnostic>,
) -> bool {
    let Some((motion, seen, findings)) = plain_pass(&block.words) else {
        return false;
    };
    // The G code's definition: it decides which words the block may have.
    let (def, taken) = match motion {
        Some(i) => match motions.0[i] {
            Some((def, taken)) => (Some(def), taken),
            None => return false,
        },
        None => (None, u32::MAX),
    };
    if !findings && seen & !taken == 0 && (motion < Some(2) || arc_words_fit(seen)) {
        return true;
    }
    let mut seen = 0u32;
    for word in &block.words {
        if word.letter == b'G' {
            continue;
        }
        // What `words_twice`, `words_used` and `ranges` find, in that order.
        let bit = letter_bit(word.letter);
        if seen & bit != 0 {
            out.push(Diagnostic::error(
                word.span,
                "E-WORD-TWICE",
                format!("address `{}` appears twice in the block", word.letter()),
            ));
        }
        seen |= bit;
        if taken & bit == 0
            && let Some(def) = def
        {
            out.push(unused(dialect, word, &def.code.to_string()));
        }
        let v = word.value;
        match word.letter {
            b'F' | b'S' if v < 0.0 => out.push(negative(word)),
            b'T' | b'H' | b'D' if v < 0.0 || v.fract() != 0.0 => out.push(not_whole(word)),
            _ => {}
        }
    }
    if let Some(def) = def
        && motion >= Some(2)
        && let Some(g) = block.words.iter().find(|w| w.letter == b'G')
    {
        arcs(dialect, block, &[(def, g.span)], out);
    }
    true
}

/// Checks any block: its codes, their conflicts, and the words they take.
fn check_any_block(
    dialect: Dialect,
    block: &Block,
    scratch: &mut Vec<Found>,
    out: &mut Vec<Diagnostic>,
) {
    scratch.clear();
    let codes = scratch;
    for word in &block.words {
        if !(word.letter == b'G' || word.letter == b'M') || word.form != WordForm::Plain {
            continue;
        }
        if word.expr.is_some() {
            continue;
        }
        let Some(code) = Code::from_value(word.letter, word.value) else {
            out.push(Diagnostic::error(
                word.span,
                "E-CODE-NUMBER",
                format!(
                    "`{}` is not a valid {} code number",
                    word_text(word),
                    word.letter()
                ),
            ));
            continue;
        };
        // The standard codes a dialect's manual leaves out (G17, M30 …) are read as on Fanuc
        // without a note: every Fanuc-family control has them.
        match codes::lookup(dialect, code) {
            Some(def) => codes.push((def, word.span)),
            None => out.push(unknown_code(dialect, code, word.span)),
        }
    }
    modal_conflicts(dialect, codes, out);
    forbidden_pairs(dialect, codes, out);
    words_twice(block, out);
    words_used(dialect, block, codes, out);
    required_words(block, codes, out);
    arcs(dialect, block, codes, out);
    ranges(dialect, block, codes, out);
}

fn word_text(word: &Word) -> String {
    let v = word.value;
    if word.has_point {
        format!("{}{v:?}", word.letter())
    } else {
        format!("{}{v}", word.letter())
    }
}

/// The diagnostic for a code the dialect does not have, naming the dialects that do.
fn unknown_code(dialect: Dialect, code: Code, span: Span) -> Diagnostic {
    let elsewhere: Vec<String> = codes::meanings(code)
        .map(|d| format!("{} on {}", d.name, d.dialects.labels()))
        .collect();
    if code.letter == b'M' {
        let also = if elsewhere.is_empty() {
            String::new()
        } else {
            format!(" (it is {})", elsewhere.join("; "))
        };
        return Diagnostic::warning(
            span,
            "W-UNKNOWN-M",
            format!(
                "{code} is not in the {} code list: a machine-specific M code, not drawn{also}",
                dialect.label()
            ),
        );
    }
    if elsewhere.is_empty() {
        Diagnostic::error(
            span,
            "E-UNKNOWN-CODE",
            format!(
                "{code} is not a code of {} (nor of any other supported control)",
                dialect.label()
            ),
        )
    } else {
        let inch_metric = code == Code::g(200) || code == Code::g(210);
        let hint = if inch_metric && dialect == Dialect::Syntec {
            " — Syntec selects inch/metric with G70/G71"
        } else {
            ""
        };
        Diagnostic::error(
            span,
            "E-CODE-DIALECT",
            format!(
                "{code} is not a code of {}; it is {}{hint}",
                dialect.label(),
                elsewhere.join("; ")
            ),
        )
    }
}

/// Whether `a` and `b` are G80 and another motion code in LinuxCNC, which rs274 accepts in one
/// block (`G0 G17 G80 G90`): the other motion code is the one used.
fn g80_with_motion(dialect: Dialect, a: &CodeDef, b: &CodeDef) -> bool {
    dialect == Dialect::LinuxCnc
        && a.group == Group::Motion
        && b.group == Group::Motion
        && (a.code == Code::g(800) || b.code == Code::g(800))
}

fn modal_conflicts(dialect: Dialect, codes: &[Found], out: &mut Vec<Diagnostic>) {
    for (i, (def, span)) in codes.iter().enumerate() {
        if !def.group.exclusive() {
            continue;
        }
        // M codes: only the spindle group conflicts (LinuxCNC allows M7 with M8, say).
        if def.code.letter == b'M' && def.group != Group::Spindle {
            continue;
        }
        let Some((earlier, _)) = codes[..i].iter().rev().find(|(d, _)| {
            d.group == def.group
                && d.code.letter == def.code.letter
                && !g80_with_motion(dialect, d, def)
        }) else {
            continue;
        };
        if dialect == Dialect::LinuxCnc {
            out.push(Diagnostic::error(
                *span,
                "E-MODAL-CONFLICT",
                format!(
                    "{} and {} are both in the {} group and cannot share a block",
                    earlier.code,
                    def.code,
                    def.group.name()
                ),
            ));
        } else {
            out.push(Diagnostic::warning(
                *span,
                "W-MODAL-LAST",
                format!(
                    "{} and {} are both in the {} group: {}, the last one, is used",
                    earlier.code,
                    def.code,
                    def.group.name(),
                    def.code
                ),
            ));
        }
    }
}

fn forbidden_pairs(dialect: Dialect, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let g = |t: &[u32]| {
        codes
            .iter()
            .find(|(d, _)| d.code.letter == b'G' && t.contains(&d.code.tenths))
    };
    if codes.len() < 2 {
        return;
    }
    for rule in FORBIDDEN {
        if !rule.dialects.contains(dialect) {
            continue;
        }
        let (Some((a, _)), Some((b, wb))) = (g(rule.first), g(rule.second)) else {
            continue;
        };
        if a.code == b.code {
            continue;
        }
        out.push(Diagnostic::error(
            *wb,
            "E-SAME-BLOCK",
            format!("{} and {} in one block: {}", a.code, b.code, rule.why),
        ));
    }
}

fn words_twice(block: &Block, out: &mut Vec<Diagnostic>) {
    let mut seen = 0u32;
    for (i, word) in block.words.iter().enumerate() {
        if word.letter == b'G' || word.letter == b'M' {
            continue;
        }
        let repeated = if word.form == WordForm::Plain {
            // The common case: one bit per plain letter.
            let bit = letter_bit(word.letter);
            let again = seen & bit != 0;
            seen |= bit;
            again
        } else {
            block.words[..i]
                .iter()
                .any(|w| w.letter == word.letter && w.form == word.form)
        };
        if repeated {
            let shown = match word.form {
                WordForm::Comma => format!(",{}", word.letter()),
                WordForm::Indexed(n) => format!("{}{n}=", word.letter()),
                WordForm::Plain => word.letter().to_string(),
            };
            out.push(Diagnostic::error(
                word.span,
                "E-WORD-TWICE",
                format!("address `{shown}` appears twice in the block"),
            ));
        }
    }
}

/// A word no code of the block uses, when the block's codes decide what the words mean.
fn words_used(dialect: Dialect, block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    // Without a motion, cycle or one-shot code, the words belong to the modal motion.
    let decides = codes.iter().any(|(d, _)| {
        d.code.letter == b'G' && matches!(d.group, Group::Motion | Group::Cycle | Group::NonModal)
    });
    if !decides {
        return;
    }
    // One bit per letter: what any block may carry and what the block's codes take.
    let taken = codes
        .iter()
        .fold(ALWAYS_MASK, |m, (d, _)| m | codes::words_mask(d));
    for word in block.words.iter().filter(|w| w.form == WordForm::Plain) {
        if taken & letter_bit(word.letter) != 0 {
            continue;
        }
        let names: Vec<String> = codes
            .iter()
            .filter(|(d, _)| d.code.letter == b'G')
            .map(|(d, _)| d.code.to_string())
            .collect();
        out.push(unused(dialect, word, &names.join(" ")));
    }
}

/// A word none of the block's codes (`names`) takes: an error in LinuxCNC, ignored with a
/// warning in the Fanuc family.
fn unused(dialect: Dialect, word: &Word, names: &str) -> Diagnostic {
    let message = format!(
        "address `{}` is not used by {names} and is ignored",
        word.letter()
    );
    if dialect == Dialect::LinuxCnc {
        Diagnostic::error(word.span, "E-WORD-UNUSED", message)
    } else {
        Diagnostic::warning(word.span, "W-WORD-UNUSED", message)
    }
}

fn has_any(block: &Block, letters: &str) -> bool {
    let mask = letter_mask(letters.as_bytes());
    block
        .words
        .iter()
        .any(|w| w.form == WordForm::Plain && mask & letter_bit(w.letter) != 0)
}

/// The bit of an uppercase letter (0 for anything else).
fn letter_bit(letter: u8) -> u32 {
    if letter.is_ascii_uppercase() {
        1 << (letter - b'A')
    } else {
        0
    }
}

/// The bits of a set of letters.
fn letter_mask(letters: &[u8]) -> u32 {
    letters.iter().fold(0, |m, &l| m | letter_bit(l))
}

fn required_words(block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    for (def, span) in codes {
        for group in def.required {
            if has_any(block, group) {
                continue;
            }
            let letters: Vec<String> = group.chars().map(|c| format!("`{c}`")).collect();
            out.push(Diagnostic::error(
                *span,
                "E-WORD-MISSING",
                format!("{} ({}) needs {}", def.code, def.name, letters.join(" or ")),
            ));
        }
    }
}

fn arcs(dialect: Dialect, block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let Some((def, span)) = codes
        .iter()
        .find(|(d, _)| d.code == Code::g(20) || d.code == Code::g(30))
    else {
        return;
    };
    let span = *span;
    let has_r = has_any(block, "R");
    let has_ijk = has_any(block, "IJK");
    let has_end = has_any(block, "XYZ");
    if has_r && has_ijk {
        let r = block.word(b'R').map_or(span, |w| w.span);
        if dialect == Dialect::LinuxCnc {
            out.push(Diagnostic::error(
                r,
                "E-ARC-R-AND-IJK",
                "an arc takes either R or I/J/K, not both",
            ));
        } else {
            out.push(Diagnostic::warning(
                r,
                "W-ARC-R-AND-IJK",
                "R and I/J/K in one arc: R takes precedence and I/J/K are ignored",
            ));
        }
    }
    if !has_r && !has_ijk {
        if dialect == Dialect::Syntec {
            out.push(Diagnostic::warning(
                span,
                "W-ARC-AS-LINE",
                format!("{} with neither R nor I/J/K moves in a straight line (G01), as Syntec documents", def.code),
            ));
        } else {
            out.push(Diagnostic::error(
                span,
                "E-ARC-CENTER",
                format!("{} needs the centre (I, J, K) or the radius (R)", def.code),
            ));
        }
    }
    if has_r && !has_end {
        out.push(Diagnostic::error(
            span,
            "E-ARC-NO-END",
            format!(
                "{} with R needs an end point (a full circle needs I/J/K)",
                def.code
            ),
        ));
    }
}

/// An F or S word below zero.
fn negative(word: &Word) -> Diagnostic {
    Diagnostic::error(
        word.span,
        "E-NUMBER-RANGE",
        format!("`{}` cannot be negative", word.letter()),
    )
}

/// A T, H or D word that is not a whole number of zero or more.
fn not_whole(word: &Word) -> Diagnostic {
    Diagnostic::error(
        word.span,
        "E-NUMBER-RANGE",
        format!(
            "`{}` takes a whole number that is not negative",
            word_text(word)
        ),
    )
}

fn ranges(dialect: Dialect, block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let has = |t: u32| codes.iter().any(|(d, _)| d.code == Code::g(t));
    for word in &block.words {
        if word.expr.is_some() {
            continue;
        }
        let v = word.value;
        match (word.letter, word.form) {
            (b'F', WordForm::Indexed(2)) if word.has_point && v.fract() != 0.0 => {
                out.push(Diagnostic::error(
                    word.span,
                    "E-NUMBER-RANGE",
                    "the retract feed `F2=` must be a whole number (alarm COR-045)",
                ));
            }
            (b'F' | b'S', WordForm::Plain) if v < 0.0 => out.push(negative(word)),
            // LinuxCNC's G41.1/G42.1 D is the tool's diameter, and G96 D a speed limit.
            (b'D', WordForm::Plain) if has(411) || has(421) || has(960) => {}
            (b'T' | b'H' | b'D', WordForm::Plain) if v < 0.0 || v.fract() != 0.0 => {
                out.push(not_whole(word));
            }
            (b'P', WordForm::Plain) if has(541) => {
                let max = match dialect {
                    Dialect::Fanuc => 300.0,
                    _ => 48.0,
                };
                if !(1.0..=max).contains(&v) || v.fract() != 0.0 {
                    out.push(Diagnostic::error(
                        word.span,
                        "E-NUMBER-RANGE",
                        format!("G54.1 takes P1 to P{max} (extended work coordinate systems)"),
                    ));
                }
            }
            (b'P', WordForm::Plain) if has(300) => {
                let min = if dialect == Dialect::Syntec { 1.0 } else { 2.0 };
                if !(min..=4.0).contains(&v) || v.fract() != 0.0 {
                    out.push(Diagnostic::error(
                        word.span,
                        "E-NUMBER-RANGE",
                        format!("G30 takes P{min} to P4 (the reference point number)"),
                    ));
                }
            }
            (b'E', WordForm::Plain)
                if dialect == Dialect::Gsk
                    && codes.iter().any(|(d, _)| d.group == Group::Cycle)
                    && (v == 0.0 || v.abs() > 60.0) =>
            {
                out.push(Diagnostic::error(
                    word.span,
                    "E-NUMBER-RANGE",
                    "the slant angle E must be between −60° and 60° and not 0",
                ));
            }
            _ => {}
        }
    }
}

// proptest is a native-only dev-dependency.
#[cfg(all(test, not(target_arch = "wasm32")))]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use proptest::prelude::*;

    use super::*;

    /// Words a plain CAM block may have, and some that make it a block of another kind.
    const WORDS: &[&str] = &[
        "G0", "G1", "G01", "G00", "G2", "G3 R5.", "G81", "G1.5", "G17", "M3", "M30", "X1.", "X-2",
        "Y3.5", "Z-0.25", "A90.", "F100.", "F-5", "S1200", "S-1", "T1", "T1.5", "H-2", "D3", "P2",
        "Q1.", "R2.", "I1.", "E5.", "L3", "X#1", ",C1.", "F2=100", "G02", "G03", "G3", "J-1.",
        "K.5", "R-2.", "Z1.", "U1.", "G4",
    ];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn the_plain_block_check_finds_what_the_general_one_does(
            words in prop::collection::vec(prop::sample::select(WORDS), 0..7),
            dialect in prop::sample::select(&Dialect::ALL[..]),
        ) {
            let line = words.join(" ");
            let program = crate::parse(&line, dialect);
            for block in &program.blocks {
                let mut plain = Vec::new();
                if !check_plain_block(dialect, &PlainMotions::of(dialect), block, &mut plain) {
                    continue;
                }
                let mut any = Vec::new();
                check_any_block(dialect, block, &mut Vec::new(), &mut any);
                if Checker::new(dialect).nothing_to_report(&PlainScan::of(&block.words)) {
                    prop_assert!(any.is_empty(), "{}", line);
                }
                // The order after the merge: stable by position.
                plain.sort_by_key(|d| d.span.start);
                any.sort_by_key(|d| d.span.start);
                prop_assert_eq!(plain, any, "{}", line);
            }
        }
    }

    #[test]
    fn plain_blocks_take_the_short_check() {
        for line in [
            "G1 X1. Y2. F100.",
            "X1. Z-2.",
            "G0 Z5. S1000",
            "G1 X1 X2 F-1 T1.5",
        ] {
            for dialect in Dialect::ALL {
                let program = crate::parse(line, dialect);
                let block = program.blocks.first().unwrap();
                assert!(
                    check_plain_block(dialect, &PlainMotions::of(dialect), block, &mut Vec::new()),
                    "{line} {dialect:?}"
                );
            }
        }
        for line in ["G2 X1. R1.", "G3 X1. Y2. I1. J0.", "G02 R1."] {
            for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
                let program = crate::parse(line, dialect);
                let block = program.blocks.first().unwrap();
                assert!(
                    check_plain_block(dialect, &PlainMotions::of(dialect), block, &mut Vec::new()),
                    "{line} {dialect:?}"
                );
            }
        }
        let program = crate::parse("G4 X1.", Dialect::Fanuc);
        assert!(!check_plain_block(
            Dialect::Fanuc,
            &PlainMotions::of(Dialect::Fanuc),
            &program.blocks[0],
            &mut Vec::new()
        ));
    }
}
