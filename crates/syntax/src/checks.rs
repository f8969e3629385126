//! Checks that need no execution: the same-block rules of each dialect, read from the code
//! tables. An error marks the block so the interpreter does not run it; a warning does not.

use std::ops::RangeInclusive;

use crate::codes::{self, Code, CodeDef, DialectSet, Group, letter_bit, letter_mask};
use crate::{Block, Diagnostic, Dialect, Program, Severity, Span, Word, WordForm};

/// Letters any block may carry whatever its codes: they set modal values (feed, speed, tool,
/// offset numbers) or are codes themselves.
const ALWAYS: u32 = letter_mask(b"NOGMFSTDH");

const ARC: &[u32] = &[20, 30];
const COMP: &[u32] = &[400, 410, 420];
const LENGTH: &[u32] = &[430, 440, 490];

/// Same-block combinations the manuals forbid, one a row: the dialects, the G codes (tenths) of
/// which one may not share a block with one of the second list, and why.
#[rustfmt::skip]
const FORBIDDEN: &[(DialectSet, &[u32], &[u32], &str)] = &[
    (DialectSet::FANUC_FAMILY, ARC, COMP, "cutter compensation starts and ends only in a G00/G01 block"),
    (DialectSet::LNC, ARC, LENGTH, "LNC changes length compensation only in a G00/G01 block (priority table 1)"),
    (DialectSet::KT, LENGTH, &[20, 30, 40, 920, 310, 1420, 1430], "KT does not allow G02, G03, G04, G92, G31, G142 or G143 in a length-compensation block"),
    (DialectSet::LNC, &[220, 230], &[40, 100, 280, 290, 300, 360, 370, 380, 390, 400, 410, 420, 430, 440, 490], "LNC priority table 1: G22/G23 may not share a block with this code"),
    (DialectSet::LNC, COMP, &[40, 100, 280, 290, 300, 360, 370, 380, 390], "LNC priority table 1: G40–G42 may not share a block with this code"),
    (DialectSet::LNC, LENGTH, &[40, 100], "LNC priority table 1: G43/G44/G49 may not share a block with this code"),
    (DialectSet::LNC, &[541], &[40, 100, 280, 290, 300, 360, 370, 380, 390], "LNC priority table 1: G54.1 may not share a block with this code"),
    (DialectSet::LNC, &[40], &[100], "LNC priority table 4: G04 and G10 may not share a block"),
    (DialectSet::LNC, &[360, 370, 380, 390], ARC, "LNC priority table 1: the coordinate calculations G36–G39 are not allowed with G02/G03"),
    (DialectSet::LNC, &[650, 660, 670], &[0, 10, 20, 30, 220, 230, 400, 410, 420, 430, 440, 490, 680, 690, 1680, 730, 740, 760, 770, 780, 800, 810, 820, 830, 840, 850, 860, 870, 880, 890, 900, 910], "LNC priority table 2: a macro call G65/G66/G67 must be alone in its block"),
    (DialectSet::LNC, &[680, 690, 1680], &[730, 740, 760, 770, 780, 810, 820, 830, 840, 850, 860, 870, 880, 890], "LNC priority table 2: rotation and a canned cycle may not share a block"),
    (DialectSet::LNC, &[1310, 1320, 1330, 1340, 1730, 1830], &[40, 100, 220, 230, 400, 410, 420, 430, 440, 490, 650, 920, 1000, 1200, 1210, 1220, 1230, 1240, 1250, 1260, 1270, 1280, 1290], "LNC priority tables 3, 5 and 6: measuring feed, tap reversal and G173/G183 must not share a block with this code"),
];

/// A code found in a block, and the span of its word.
type Found = (&'static CodeDef, Span);

/// Runs the same-block checks on each block as the parser finishes it (while the block is still
/// in cache), collecting their diagnostics to merge into the program's at the end.
#[derive(Debug)]
pub(crate) struct Checker {
    dialect: Dialect,
    /// For G00, G01, G02 and G03 (at their numbers) in the dialect, the letters a block with
    /// the code may carry, or `None` where such a block takes the full check (the code is not a
    /// motion there, or needs words).
    motions: [Option<u32>; 4],
    scratch: Vec<Found>,
    out: Vec<Diagnostic>,
}

impl Checker {
    /// A checker for blocks read as `dialect`.
    pub(crate) fn new(dialect: Dialect) -> Self {
        let motion = |value: f64| {
            let def = Code::from_value(b'G', value).and_then(|c| codes::lookup(dialect, c))?;
            (def.group == Group::Motion && def.required.is_empty())
                .then(|| ALWAYS | letter_mask(def.words.as_bytes()))
        };
        Checker {
            dialect,
            motions: [0.0, 1.0, 2.0, 3.0].map(motion),
            scratch: Vec::new(),
            out: Vec::new(),
        }
    }

    /// Checks `block`; an error marks it so the interpreter does not run it.
    #[inline(always)]
    pub(crate) fn check(&mut self, block: &mut Block) {
        self.check_scanned(block, &PlainScan::of(&block.words));
    }

    /// Checks `block`, whose words `scan` has seen (a reader that makes the words scans them as
    /// it goes, sparing [`Checker::check`]'s pass over them). The common block with nothing to
    /// report costs only that pass, inlined into the reader.
    #[inline(always)]
    pub(crate) fn check_scanned(&mut self, block: &mut Block, scan: &PlainScan) {
        if !self.nothing_to_report(scan) {
            self.check_fully(block);
        }
    }

    /// Whether `scan` saw a block [`check_block`] finds nothing in: literal plain words, no M
    /// code, at most one G code and that one G00 to G03, each letter once, in range and taken
    /// by the G code, and an arc's centre or radius and end point as [`arcs`] wants them.
    #[inline(always)]
    fn nothing_to_report(&self, scan: &PlainScan) -> bool {
        if scan.other || scan.findings {
            return false;
        }
        match usize::from(scan.motion).checked_sub(1) {
            None => true,
            Some(motion) => {
                self.motions[motion].is_some_and(|taken| scan.seen & !taken == 0)
                    && (motion < 2 || arc_words_fit(scan.seen))
            }
        }
    }

    #[inline(never)]
    fn check_fully(&mut self, block: &mut Block) {
        let before = self.out.len();
        check_block(self.dialect, block, &mut self.scratch, &mut self.out);
        let found = &self.out[before..];
        if found.iter().any(|d| d.severity == Severity::Error) {
            block.extras_mut().has_error = true;
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

/// Whether an arc block's letters (`seen`) give [`arcs`] nothing to report: the centre or the
/// radius, not both, and an end point with the radius.
#[inline(always)]
fn arc_words_fit(seen: u32) -> bool {
    let has_r = seen & letter_bit(b'R') != 0;
    has_r != (seen & letter_mask(b"IJK") != 0) && (!has_r || seen & letter_mask(b"XYZ") != 0)
}

/// A block's words seen one at a time (by [`Checker::check`], or by a reader as it makes
/// them), for [`Checker::nothing_to_report`].
#[derive(Debug, Default)]
pub(crate) struct PlainScan {
    /// The G code's number plus one (0: none yet).
    motion: u8,
    /// The letters seen besides G.
    seen: u32,
    /// Whether there may be something to report (a letter seen twice or that is not one, a
    /// value out of range).
    findings: bool,
    /// Whether a word makes the block one that the scan does not judge (a word that is not a
    /// literal plain one, an M code, a G code other than one G00 to G03, a second G code).
    other: bool,
}

impl PlainScan {
    #[inline(always)]
    fn of(words: &[Word]) -> Self {
        let mut scan = PlainScan::default();
        for w in words {
            scan.other |= w.form != WordForm::Plain || w.expr.is_some();
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
                let number = [0.0, 1.0, 2.0, 3.0].iter().position(|&g| g == v);
                self.other |= self.motion != 0 || number.is_none();
                self.motion = number.map_or(0, |i| i as u8 + 1);
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
}

/// Checks a block: its codes, their conflicts, and the words they take.
fn check_block(
    dialect: Dialect,
    block: &Block,
    scratch: &mut Vec<Found>,
    out: &mut Vec<Diagnostic>,
) {
    scratch.clear();
    let codes = scratch;
    for word in &block.words {
        let code_word = matches!(word.letter, b'G' | b'M') && word.form == WordForm::Plain;
        if !code_word || word.expr.is_some() {
            continue;
        }
        let Some(code) = Code::from_value(word.letter, word.value) else {
            let (text, letter) = (word_text(word), word.letter());
            let message = format!("`{text}` is not a valid {letter} code number");
            out.push(Diagnostic::error(word.span, "E-CODE-NUMBER", message));
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

/// A word as written, for messages.
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
    let label = dialect.label();
    let elsewhere = codes::meanings(code)
        .map(|d| format!("{} on {}", d.name, d.dialects.labels()))
        .collect::<Vec<_>>()
        .join("; ");
    if code.letter == b'M' {
        let it_is = (!elsewhere.is_empty()).then(|| format!(" (it is {elsewhere})"));
        let also = it_is.unwrap_or_default();
        let message = format!(
            "{code} is not in the {label} code list: a machine-specific M code, not drawn{also}"
        );
        Diagnostic::warning(span, "W-UNKNOWN-M", message)
    } else if elsewhere.is_empty() {
        let message =
            format!("{code} is not a code of {label} (nor of any other supported control)");
        Diagnostic::error(span, "E-UNKNOWN-CODE", message)
    } else {
        let inch_metric = code == Code::g(200) || code == Code::g(210);
        let hint = (inch_metric && dialect == Dialect::Syntec)
            .then_some(" — Syntec selects inch/metric with G70/G71");
        let hint = hint.unwrap_or_default();
        let message = format!("{code} is not a code of {label}; it is {elsewhere}{hint}");
        Diagnostic::error(span, "E-CODE-DIALECT", message)
    }
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
        // LinuxCNC (rs274) accepts G80 with another motion code in one block (`G0 G17 G80
        // G90`): the other motion code is the one used.
        let g80_with_motion = |d: &CodeDef| {
            dialect == Dialect::LinuxCnc
                && def.group == Group::Motion
                && (d.code == Code::g(800) || def.code == Code::g(800))
        };
        let Some((earlier, _)) = codes[..i].iter().rev().find(|(d, _)| {
            d.group == def.group && d.code.letter == def.code.letter && !g80_with_motion(d)
        }) else {
            continue;
        };
        let (a, b, group) = (earlier.code, def.code, def.group.name());
        let both = format!("{a} and {b} are both in the {group} group");
        out.push(if dialect == Dialect::LinuxCnc {
            let message = format!("{both} and cannot share a block");
            Diagnostic::error(*span, "E-MODAL-CONFLICT", message)
        } else {
            let message = format!("{both}: {b}, the last one, is used");
            Diagnostic::warning(*span, "W-MODAL-LAST", message)
        });
    }
}

fn forbidden_pairs(dialect: Dialect, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let g = |t: &[u32]| {
        (codes.iter()).find(|(d, _)| d.code.letter == b'G' && t.contains(&d.code.tenths))
    };
    if codes.len() < 2 {
        return;
    }
    for (_, first, second, why) in FORBIDDEN.iter().filter(|rule| rule.0.contains(dialect)) {
        if let (Some((a, _)), Some((b, wb))) = (g(first), g(second))
            && a.code != b.code
        {
            let message = format!("{} and {} in one block: {why}", a.code, b.code);
            out.push(Diagnostic::error(*wb, "E-SAME-BLOCK", message));
        }
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
            (block.words[..i].iter()).any(|w| w.letter == word.letter && w.form == word.form)
        };
        if repeated {
            let shown = match word.form {
                WordForm::Comma => format!(",{}", word.letter()),
                WordForm::Indexed(n) => format!("{}{n}=", word.letter()),
                WordForm::Plain => word.letter().to_string(),
            };
            let message = format!("address `{shown}` appears twice in the block");
            out.push(Diagnostic::error(word.span, "E-WORD-TWICE", message));
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
    let taken = (codes.iter()).fold(ALWAYS, |m, (d, _)| m | letter_mask(d.words.as_bytes()));
    let names =
        (codes.iter().filter(|(d, _)| d.code.letter == b'G')).map(|(d, _)| d.code.to_string());
    let names = names.collect::<Vec<_>>().join(" ");
    for word in block.words.iter().filter(|w| w.form == WordForm::Plain) {
        if taken & letter_bit(word.letter) != 0 {
            continue;
        }
        let letter = word.letter();
        let message = format!("address `{letter}` is not used by {names} and is ignored");
        // An error in LinuxCNC; the Fanuc family ignores the word.
        out.push(if dialect == Dialect::LinuxCnc {
            Diagnostic::error(word.span, "E-WORD-UNUSED", message)
        } else {
            Diagnostic::warning(word.span, "W-WORD-UNUSED", message)
        });
    }
}

fn has_any(block: &Block, letters: &str) -> bool {
    let mask = letter_mask(letters.as_bytes());
    (block.words.iter()).any(|w| w.form == WordForm::Plain && mask & letter_bit(w.letter) != 0)
}

fn required_words(block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    for (def, span) in codes {
        for group in def.required {
            if has_any(block, group) {
                continue;
            }
            let letters: Vec<String> = group.chars().map(|c| format!("`{c}`")).collect();
            let (code, name, letters) = (def.code, def.name, letters.join(" or "));
            let message = format!("{code} ({name}) needs {letters}");
            out.push(Diagnostic::error(*span, "E-WORD-MISSING", message));
        }
    }
}

fn arcs(dialect: Dialect, block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let is_arc = |(d, _): &&Found| d.code == Code::g(20) || d.code == Code::g(30);
    let Some((def, span)) = codes.iter().find(is_arc) else {
        return;
    };
    let (span, code) = (*span, def.code);
    let has_r = has_any(block, "R");
    let has_ijk = has_any(block, "IJK");
    if has_r && has_ijk {
        let r = block.word(b'R').map_or(span, |w| w.span);
        out.push(if dialect == Dialect::LinuxCnc {
            let message = "an arc takes either R or I/J/K, not both";
            Diagnostic::error(r, "E-ARC-R-AND-IJK", message)
        } else {
            let message = "R and I/J/K in one arc: R takes precedence and I/J/K are ignored";
            Diagnostic::warning(r, "W-ARC-R-AND-IJK", message)
        });
    }
    if !has_r && !has_ijk {
        out.push(if dialect == Dialect::Syntec {
            let message = format!(
                "{code} with neither R nor I/J/K moves in a straight line (G01), as Syntec documents"
            );
            Diagnostic::warning(span, "W-ARC-AS-LINE", message)
        } else {
            let message = format!("{code} needs the centre (I, J, K) or the radius (R)");
            Diagnostic::error(span, "E-ARC-CENTER", message)
        });
    }
    if has_r && !has_any(block, "XYZ") {
        let message = format!("{code} with R needs an end point (a full circle needs I/J/K)");
        out.push(Diagnostic::error(span, "E-ARC-NO-END", message));
    }
}

fn ranges(dialect: Dialect, block: &Block, codes: &[Found], out: &mut Vec<Diagnostic>) {
    let has = |t: u32| codes.iter().any(|(d, _)| d.code == Code::g(t));
    let whole_in = |v: f64, range: RangeInclusive<f64>| range.contains(&v) && v.fract() == 0.0;
    for word in block.words.iter().filter(|w| w.expr.is_none()) {
        let (v, letter) = (word.value, word.letter());
        let message = match (word.letter, word.form) {
            (b'F', WordForm::Indexed(2)) if word.has_point && v.fract() != 0.0 => {
                "the retract feed `F2=` must be a whole number (alarm COR-045)".to_string()
            }
            (b'F' | b'S', WordForm::Plain) if v < 0.0 => format!("`{letter}` cannot be negative"),
            // LinuxCNC's G41.1/G42.1 D is the tool's diameter, and G96 D a speed limit.
            (b'D', WordForm::Plain) if has(411) || has(421) || has(960) => continue,
            (b'T' | b'H' | b'D', WordForm::Plain) if v < 0.0 || v.fract() != 0.0 => {
                let text = word_text(word);
                format!("`{text}` takes a whole number that is not negative")
            }
            (b'P', WordForm::Plain) if has(541) => {
                let fanuc = dialect == Dialect::Fanuc;
                let max = if fanuc { 300.0 } else { 48.0 };
                if whole_in(v, 1.0..=max) {
                    continue;
                }
                format!("G54.1 takes P1 to P{max} (extended work coordinate systems)")
            }
            (b'P', WordForm::Plain) if has(300) => {
                let min = if dialect == Dialect::Syntec { 1.0 } else { 2.0 };
                if whole_in(v, min..=4.0) {
                    continue;
                }
                format!("G30 takes P{min} to P4 (the reference point number)")
            }
            (b'E', WordForm::Plain)
                if dialect == Dialect::Gsk
                    && codes.iter().any(|(d, _)| d.group == Group::Cycle)
                    && (v == 0.0 || v.abs() > 60.0) =>
            {
                "the slant angle E must be between −60° and 60° and not 0".to_string()
            }
            _ => continue,
        };
        out.push(Diagnostic::error(word.span, "E-NUMBER-RANGE", message));
    }
}

#[cfg(test)]
#[cfg(not(target_arch = "wasm32"))] // proptest is a native-only dev-dependency.
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use proptest::prelude::*;

    use super::*;

    /// Words a plain CAM block may have, and some that make it a block of another kind.
    const WORDS: &[&str] = &[
        "G0", "G1", "G01", "G00", "G2", "G3 R5.", "G81", "G1.5", "G17", "M3", "M30", "X1.", "X-2",
        "Y3.5", "Z-0.25", "A90.", "F100.", "F-5", "S1200", "S-1", "T1", "T1.5", "H-2", "D3", "P2",
        "Q1.", "R2.", "I1.", "E5.", "L3", "X#1", ",C1.", "F2=100", "G02", "G03", "G3", "J-1.",
        "K.5", "R-2.", "Z1.", "U1.", "G4", "G-0", "G3.0",
    ];

    /// Whether the short check passes `block` in `dialect` without the full one.
    fn passed(dialect: Dialect, block: &Block) -> bool {
        Checker::new(dialect).nothing_to_report(&PlainScan::of(&block.words))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn the_short_check_passes_only_blocks_the_full_one_finds_nothing_in(
            words in prop::collection::vec(prop::sample::select(WORDS), 0..7),
            dialect in prop::sample::select(&Dialect::ALL[..]),
        ) {
            let line = words.join(" ");
            let program = crate::parse(&line, dialect);
            for block in &program.blocks {
                let mut any = Vec::new();
                check_block(dialect, block, &mut Vec::new(), &mut any);
                if passed(dialect, block) {
                    prop_assert!(any.is_empty(), "{}", line);
                }
            }
        }
    }

    #[test]
    fn clean_plain_blocks_take_the_short_check() {
        for line in ["G1 X1. Y2. F100.", "X1. Z-2.", "G0 Z5. S1000"] {
            for dialect in Dialect::ALL {
                let program = crate::parse(line, dialect);
                assert!(passed(dialect, &program.blocks[0]), "{line} {dialect:?}");
            }
        }
        for line in ["G2 X1. R1.", "G3 X1. Y2. I1. J0."] {
            for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
                let program = crate::parse(line, dialect);
                assert!(passed(dialect, &program.blocks[0]), "{line} {dialect:?}");
            }
        }
        for line in [
            "G1 X1 X2 F-1 T1.5",
            "G02 R1.",
            "G4 X1.",
            "G1 M3 X1.",
            "G0 G1 X1.",
        ] {
            let program = crate::parse(line, Dialect::Fanuc);
            assert!(!passed(Dialect::Fanuc, &program.blocks[0]), "{line}");
        }
    }
}
