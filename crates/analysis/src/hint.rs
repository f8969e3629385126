//! Which dialect a program's own codes point to: a program read in one dialect whose lines read
//! with fewer errors in another (Syntec's `G71` metric and `//` comments in a Fanuc tab, say)
//! gets that dialect offered, never switched to silently.

use std::collections::{HashMap, HashSet};

use swarf_syntax::{Block, Dialect, Program, Severity, codes};

use crate::run::Problem;
use crate::text::ProgramText;

/// Lines from the start of a program read again in every dialect (all of a short program).
const HEAD_LINES: usize = 200;

/// Further lines, past the head, read again in every dialect: those with a problem here and
/// those with a code that not every dialect has, at most this many of each.
const MORE_LINES: usize = 2_000;

/// Longest text shown for what gave the dialect away.
const WHAT_CHARS: usize = 16;

/// A dialect that reads a program with fewer errors than the one it was analysed in.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct DialectHint {
    /// The dialect the program was analysed in (the hint is stale once the tab has another).
    pub from: Dialect,
    /// The dialect offered.
    pub to: Dialect,
    /// The first problem the switch removes, as written (`G71`), with its 1-based line.
    pub first: Option<(String, u32)>,
}

/// One dialect's reading of the lines compared: its score and the (line, code) of each
/// diagnostic counted.
type Reading = (Dialect, Score, HashSet<(usize, &'static str)>);

/// Errors and unknown M codes of one reading of the lines compared.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Score {
    errors: usize,
    unknown_m: usize,
}

/// Whether a problem is one another dialect may not have: an error, or an M code the dialect's
/// list lacks.
fn telling(p: &Problem) -> bool {
    p.severity == Severity::Error || p.code == "W-UNKNOWN-M"
}

/// Whether some dialects have `code` and others do not.
fn differs(code: codes::Code) -> bool {
    let have = Dialect::ALL
        .iter()
        .filter(|&&d| codes::lookup(d, code).is_some())
        .count();
    have > 0 && have < Dialect::ALL.len()
}

/// The lines past the head with a code not every dialect has (at most [`MORE_LINES`]), noted
/// as the blocks are read.
#[derive(Debug, Default)]
pub struct Sensitive {
    lines: Vec<usize>,
    /// Whether each code seen differs between dialects, looked up once (a program uses few).
    seen: HashMap<codes::Code, bool>,
}

impl Sensitive {
    /// Notes the lines of `blocks` (read in order) with such a code.
    pub fn note(&mut self, blocks: &[Block]) {
        for block in blocks {
            if self.lines.len() >= MORE_LINES {
                return;
            }
            let seen = &mut self.seen;
            let mut differ = |code| *seen.entry(code).or_insert_with(|| differs(code));
            let line = block.line as usize;
            if line >= HEAD_LINES
                && (block.words.iter()).any(|w| codes::Code::of_word(w).is_some_and(&mut differ))
            {
                self.lines.push(line);
            }
        }
    }
}

/// The dialect that would read `program` with strictly fewer errors, if any: the lines that may
/// differ are parsed again in every dialect; fewest errors, then fewest unknown M codes, wins.
pub fn suggest(
    text: &ProgramText,
    program: &Program,
    problems: &[Problem],
    sensitive: &Sensitive,
) -> Option<DialectHint> {
    let from = program.dialect;
    // A program with nothing wrong reads no better elsewhere.
    if !problems.iter().any(telling) {
        return None;
    }
    // The program's own lines (those of the files linked after it follow).
    let index = &program.lines;
    let last = program
        .linked
        .first()
        .map_or(index.line_count(), |l| l.first_line as usize)
        .min(index.line_count());
    let mut lines: Vec<usize> = (0..HEAD_LINES.min(last)).collect();
    lines.extend(
        problems
            .iter()
            .filter(|p| telling(p))
            .map(|p| p.line.saturating_sub(1) as usize)
            .filter(|&l| l >= HEAD_LINES && l < last)
            .take(MORE_LINES),
    );
    lines.extend(sensitive.lines.iter().filter(|&&l| l < last));
    lines.sort_unstable();
    lines.dedup();
    let mut sample = String::new();
    for &l in &lines {
        sample.push_str(&text.line(index, l));
        sample.push('\n');
    }
    // Each dialect's score, and the (sample line, code) of each diagnostic it counts.
    let readings: Vec<Reading> = Dialect::ALL
        .iter()
        .map(|&d| {
            let program = swarf_syntax::parse(&sample, d);
            let mut score = Score::default();
            let mut found = HashSet::new();
            for diag in &program.diagnostics {
                if diag.severity == Severity::Error {
                    score.errors += 1;
                } else if diag.code == "W-UNKNOWN-M" {
                    score.unknown_m += 1;
                } else {
                    continue;
                }
                found.insert((program.lines.line_of(diag.span.start), diag.code));
            }
            (d, score, found)
        })
        .collect();
    let here = readings.iter().find(|(d, ..)| *d == from)?.1;
    let (to, best, found) = readings
        .iter()
        .filter(|(d, ..)| *d != from)
        .min_by_key(|(_, score, _)| *score)?;
    if best.errors >= here.errors {
        return None;
    }
    // The first problem here that the other reading does not have on its line.
    let first = problems.iter().filter(|p| telling(p)).find_map(|p| {
        let line = p.line.saturating_sub(1) as usize;
        let at = lines.binary_search(&line).ok()?;
        if found.contains(&(at, p.code)) {
            return None;
        }
        let row = text.line(index, line);
        let (col, len) = (p.col.saturating_sub(1) as usize, p.chars.len());
        let mut what: String = row.chars().skip(col).take(len).collect();
        // A stray character is shown with its repeats: `//` rather than `/`.
        if let [c] = what.chars().collect::<Vec<_>>()[..]
            && !c.is_alphanumeric()
        {
            let after = row.chars().skip(col + len).take(WHAT_CHARS);
            what.extend(after.take_while(|&a| a == c));
        }
        let what: String = what.trim().chars().take(WHAT_CHARS).collect();
        (!what.is_empty()).then_some((what, p.line))
    });
    let to = *to;
    Some(DialectHint { from, to, first })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;

    fn hint(text: &str, dialect: Dialect) -> Option<DialectHint> {
        let job = crate::Job {
            generation: 1,
            text: ProgramText::from(text.to_string()),
            dialect,
            setup: swarf_interp::Setup::default(),
            others: None,
            lod: None,
        };
        crate::analyse(job).0.hint
    }

    /// The example program the editor starts with.
    const EXAMPLE_PROGRAM: &str = include_str!("../../../assets/examples/pocket.nc");

    #[test]
    fn a_syntec_program_read_as_fanuc_points_to_syntec() {
        let text = "%\nO3001\nN10 G90 G71 G17 G54\nG00 X0. Y0. Z20.\nM30\n%\n";
        let h = hint(text, Dialect::Fanuc).expect("offered");
        assert_eq!(h.from, Dialect::Fanuc);
        assert_eq!(h.to, Dialect::Syntec);
        assert_eq!(h.first, Some(("G71".to_string(), 3)));
        assert_eq!(hint(text, Dialect::Syntec), None);
    }

    #[test]
    fn slash_comments_point_to_syntec() {
        let text = "G90 G54 // absolute\nG00 X0 Y0 Z5 // over the part\nM30\n";
        let h = hint(text, Dialect::Fanuc).expect("offered");
        assert_eq!(h.to, Dialect::Syntec);
        assert_eq!(h.first, Some(("//".to_string(), 1)));
    }

    #[test]
    fn a_fanuc_program_read_as_syntec_points_back_to_fanuc() {
        let h = hint(EXAMPLE_PROGRAM, Dialect::Syntec).expect("offered");
        assert_eq!(h.to, Dialect::Fanuc);
        assert_eq!(h.first.map(|(what, _)| what), Some("G21".to_string()));
    }

    #[test]
    fn a_clean_program_or_an_error_every_dialect_has_gets_no_offer() {
        assert_eq!(hint(EXAMPLE_PROGRAM, Dialect::Fanuc), None);
        assert_eq!(hint("G1 X$ F100\nM30\n", Dialect::Fanuc), None);
        assert_eq!(hint("", Dialect::Fanuc), None);
    }

    #[test]
    fn a_code_far_down_a_long_program_is_seen() {
        let mut text = String::from("G90 G54\n");
        for i in 0..5_000 {
            text.push_str(&format!("G01 X{} Y1 F500\n", i % 50));
        }
        text.push_str("G71\nM30\n");
        let h = hint(&text, Dialect::Fanuc).expect("offered");
        assert_eq!(h.to, Dialect::Syntec);
        assert_eq!(h.first, Some(("G71".to_string(), 5_002)));
    }
}
