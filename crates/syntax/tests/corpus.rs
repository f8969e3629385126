//! Every program of the peer corpus (`../shared/corpus`: LinuxCNC's interpreter tests, the NIST
//! examples, CAM output, real surfacing jobs) reads as LinuxCNC without a panic, with spans on
//! character boundaries inside the text, and without an error, except the programs that are
//! wrong on purpose.
//!
//! The corpus lives outside the repository; without it the test passes with a note.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_syntax::{Dialect, Severity, decode, parse};

#[path = "../../../tests/support/programs.rs"]
mod programs;
use programs::{corpus, programs_under};

/// Programs LinuxCNC's rs274 rejects, with the error codes Swarf reports for them (sorted; none
/// where the fault only shows when the program runs). Every other program must read without an
/// error. The quoted messages are rs274's (`../shared/tools/rs274/oracle.sh`).
const ERRONEOUS: &[(&str, &[&str])] = &[
    // "Found 'm98' code with no P-word" (the test expects the failure).
    (
        "linuxcnc-tests/interp/m98m99/03-error-M98-no-P-word/test.ngc",
        &["E-WORD-MISSING"],
    ),
    // "Failed to find sub 'O1' before EOF": found when the call runs.
    (
        "linuxcnc-tests/interp/m98m99/04-M98-but-no-sub/test.ngc",
        &[],
    ),
    // Fanuc-style and O-word subprograms mixed up: found when the calls run.
    (
        "linuxcnc-tests/interp/m98m99/06-error-mixed-sub-styles/O...-called-with-O..._call.ngc",
        &[],
    ),
    (
        "linuxcnc-tests/interp/m98m99/06-error-mixed-sub-styles/O...-ended-with-O..._endsub.ngc",
        &[],
    ),
    (
        "linuxcnc-tests/interp/m98m99/06-error-mixed-sub-styles/O...-sub-called-with-M98.ngc",
        &[],
    ),
    (
        "linuxcnc-tests/interp/m98m99/06-error-mixed-sub-styles/O...-sub-ended-with-M99.ngc",
        &[],
    ),
    // "File ended with no percent sign or program end": a whole-program rule.
    (
        "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-end-main-with-eof.ngc",
        &[],
    ),
    // "sub: o2 found in illegal location" (a subprogram defined before the main program's end).
    (
        "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-no-m30-before-osub.ngc",
        &[],
    ),
    // "Failed to find sub 'O2' before EOF": the sub follows the closing `%`, so it is not read.
    (
        "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-sub-after-percent.ngc",
        &[],
    ),
    // cncjs's fixtures are written for GRBL senders, which take what rs274 refuses.
    // `G02` alone on a line: "R i j k words all missing for arc" (and the same for `G03`).
    ("programs/cncjs/arc-r.nc", &["E-ARC-CENTER", "E-ARC-CENTER"]),
    // `G4 S2`: "Dwell time missing with g4".
    ("programs/cncjs/dwell.nc", &["E-WORD-MISSING"]),
    // A bare `g92`: "All axes missing with g52 or g92".
    ("programs/cncjs/g92offset.nc", &["E-WORD-MISSING"]),
    // A bare `G92` ("All axes missing with g52 or g92") and bare `G38.2`–`G38.5` ("All axes
    // missing with motion code").
    (
        "programs/cncjs/motion.nc",
        &[
            "E-WORD-MISSING",
            "E-WORD-MISSING",
            "E-WORD-MISSING",
            "E-WORD-MISSING",
            "E-WORD-MISSING",
        ],
    ),
];

#[test]
fn every_corpus_program_reads_as_linuxcnc() {
    let Some(root) = corpus() else {
        return;
    };
    let files = programs_under(&root);
    assert!(files.len() > 50, "only {} programs found", files.len());

    let mut failures = Vec::new();
    let mut seen_erroneous = Vec::new();
    for path in &files {
        let name = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let bytes = std::fs::read(path).unwrap();
        let decoded = decode(&bytes);
        let text = &decoded.text;
        let program = parse(text, Dialect::LinuxCnc);

        let spans = decoded
            .diagnostics
            .iter()
            .map(|d| d.span)
            .chain(program.diagnostics.iter().map(|d| d.span))
            .chain(program.blocks.iter().map(|b| b.span))
            .chain(
                program
                    .blocks
                    .iter()
                    .flat_map(|b| b.comments().iter().copied()),
            )
            .chain(
                program
                    .blocks
                    .iter()
                    .flat_map(|b| b.words.iter().map(|w| w.span)),
            )
            .chain(program.exprs.iter().map(|e| e.span));
        for span in spans {
            let (start, end) = (span.start as usize, span.end as usize);
            assert!(
                start <= end
                    && end <= text.len()
                    && text.is_char_boundary(start)
                    && text.is_char_boundary(end),
                "{name}: span {start}..{end} is not a character range of the text ({} bytes)",
                text.len()
            );
        }

        let mut errors: Vec<(&str, &str)> = decoded
            .diagnostics
            .iter()
            .chain(&program.diagnostics)
            .filter(|d| d.severity == Severity::Error)
            .map(|d| (d.code, &text[d.span.range()]))
            .collect();
        errors.sort_unstable();
        let codes: Vec<&str> = errors.iter().map(|(c, _)| *c).collect();
        let expected = match ERRONEOUS.iter().find(|(p, _)| *p == name) {
            Some((_, codes)) => {
                seen_erroneous.push(name.clone());
                *codes
            }
            None => &[],
        };
        if codes != expected {
            let shown: Vec<String> = errors
                .iter()
                .take(12)
                .map(|(c, t)| format!("{c} `{t}`"))
                .collect();
            failures.push(format!(
                "{name}: {} errors [{}{}], expected {expected:?}",
                errors.len(),
                shown.join(", "),
                if errors.len() > 12 { ", …" } else { "" }
            ));
        }
    }
    for (path, _) in ERRONEOUS {
        assert!(
            seen_erroneous.iter().any(|p| p == path),
            "{path} is listed as erroneous but is not in the corpus"
        );
    }
    assert!(
        failures.is_empty(),
        "corpus programs with unexpected errors:\n{}",
        failures.join("\n")
    );
}
