//! Plain straight moves take a shorter path through the interpreter than other blocks; every
//! program must give the same events and diagnostics through it as through the general path
//! alone: random programs mixing plain moves with blocks that change the state the moves depend
//! on, the examples, the golden programs and (when `../shared` is present) the corpus, in every
//! dialect.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::path::Path;

#[path = "../../../tests/support/programs.rs"]
mod programs;
use programs::{check_each, corpus, programs_under};

use proptest::prelude::*;
use swarf_interp::{CanonRecorder, Interpreter, Setup, Status};
use swarf_syntax::{Dialect, Program, parse};

/// A setup with offset registers, so that compensation and length offsets have values.
const SETUP: &str =
    "[registers.1]\nradius = 3.0\nlength = 50.0\n[registers.2]\nradius = 1.5\nlength = 20.0\n";

fn run_both(program: &Program) -> Result<(), String> {
    run_both_with(program, &Setup::from_toml(SETUP).expect("setup"), 4096)
}

/// [`run_both`] with `setup`, stepping `budget` blocks at a time.
fn run_both_with(program: &Program, setup: &Setup, budget: usize) -> Result<(), String> {
    let mut out = Vec::new();
    for shortcut in [true, false] {
        let mut interp = Interpreter::new(setup.clone(), program.dialect);
        if !shortcut {
            interp.general_path_only();
        }
        let mut rec = CanonRecorder::default();
        while interp.step(program, &mut rec, budget) == Status::Running {}
        out.push((rec.events, interp.take_diagnostics()));
    }
    let (general_events, general_diags) = out.pop().ok_or("no run")?;
    let (short_events, short_diags) = out.pop().ok_or("no run")?;
    if let Some(i) = (0..short_events.len().max(general_events.len()))
        .find(|&i| short_events.get(i) != general_events.get(i))
    {
        return Err(format!(
            "event {i} differs: shortcut {:?}, general {:?}",
            short_events.get(i),
            general_events.get(i)
        ));
    }
    if short_diags != general_diags {
        return Err(format!(
            "diagnostics differ:\nshortcut {short_diags:#?}\ngeneral {general_diags:#?}"
        ));
    }
    Ok(())
}

fn check_text(text: &str, what: &str) {
    for dialect in Dialect::ALL {
        if let Err(e) = run_both(&parse(text, dialect)) {
            panic!("{what} read as {dialect:?}: {e}");
        }
    }
}

/// A program's text, cut to its first lines when it is large (the debug build is slow).
fn head(path: &Path) -> String {
    let bytes = std::fs::read(path).unwrap_or_default();
    let text = String::from_utf8_lossy(&bytes);
    text.lines().take(3000).collect::<Vec<_>>().join("\n")
}

#[test]
fn examples_and_golden_programs_agree() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = programs_under(&root.join("assets/examples"));
    files.extend(programs_under(&root.join("tests/golden")));
    assert!(files.len() >= 5, "examples not found: {files:?}");
    for file in files {
        check_text(&head(&file), &file.display().to_string());
    }
}

#[test]
fn corpus_programs_agree() {
    let Some(corpus) = corpus() else {
        return;
    };
    let files = programs_under(&corpus);
    assert!(!files.is_empty());
    check_each(&files, |file| {
        check_text(&head(file), &file.display().to_string());
    });
}

#[test]
fn runs_of_plain_moves_stop_at_the_runaway_limits_and_the_step_budget() {
    let mut text = String::from("G90 G21 G0 X0 Y0 F500.\n");
    for i in 0..120 {
        text.push_str(&format!("G1 X{}. Y{}.\n", i % 7, i % 5));
        if i % 40 == 39 {
            text.push_str("(a comment)\nS1000\nG91\nG90\n");
        }
    }
    text.push_str("M30\n");
    let program = parse(&text, Dialect::Fanuc);
    for (blocks, motions) in [(37, u64::MAX), (u64::MAX, 23), (50, 50), (1, 1), (0, 0)] {
        let mut setup = Setup::from_toml(SETUP).expect("setup");
        setup.machine.max_blocks = blocks;
        setup.machine.max_motions = motions;
        for budget in [1, 3, 4096] {
            if let Err(e) = run_both_with(&program, &setup, budget) {
                panic!("limits {blocks}/{motions}, budget {budget}: {e}");
            }
        }
    }
}

/// Blocks that change what a plain move does, or that are plain moves themselves.
const BLOCKS: &[&str] = &[
    "G0 X10. Y5.",
    "G1 X-3.5 Y2. F300.",
    "X12.5",
    "Y-4. Z1.",
    "Z-2.",
    "X1000 Y-250",
    "G1 X4 F150",
    "G0 Z5. S800",
    "S1200",
    "F0",
    "G01 X2. Y2. F1200. S400",
    "X5. X6.",
    "G1 G0 X3.",
    "G90",
    "G91",
    "G20",
    "G21",
    "G17",
    "G18",
    "G2 X5. Y5. R5.",
    "G3 X0 Y0 I-2.5 J-2.5",
    "G02 X1. Z1. R3.",
    "G41 D1 G1 X10. Y0",
    "G42 D2 X0 Y10.",
    "G40 G0 X0 Y0",
    "G43 H1 Z10.",
    "G49",
    "G81 X5. Y5. R2. Z-5. F100.",
    "G80",
    "G98 G83 X1. Y1. R1. Z-8. Q2. F80.",
    "G68 X0 Y0 R30.",
    "G69",
    "G51 X0 Y0 P2.",
    "G50",
    "G51.1 X0",
    "G50.1 X0",
    "G16",
    "G15",
    "G1 X10. ,C1.",
    "G1 Y10. ,R2.",
    "G93 G1 X3. F2.",
    "G94",
    "G95 F0.1",
    "G96 S150",
    "G97 S1000",
    "M3",
    "M5",
    "M8",
    "G52 X5. Y5.",
    "G92 X0 Y0",
    "G54",
    "G55 G0 X0",
    "G4 P100",
    "G28 Z0",
    "G53 G0 Z0",
    "G66 P9000 A1.",
    "G67",
    "T2 M6",
    "#1=5.",
    "G1 X#1",
    "G1 X#9 Y1.",
    "N10 G1 X3.",
    "/G1 X8.",
    "G1 X3. (cut) Y1.",
    "G45 X5. D1",
    "G22 X50. Y50. Z50. I-50. J-50. K-50.",
    "G23",
    "G1 A30.",
    "G1 X1. I1.",
    "X3. Y1. I1. J0.5",
    "G3 I2. J0",
    "G2 R5.",
    "G03 X2. Y2. R-3. F200. S500",
    "G2 X4 Y0 I2 J0",
    "G2 X1. Y1. I1. L2",
    "G2 X4. Y0 I2. J0 P2",
    "G19 G3 Y2. Z1. J1. K0.5",
    "G10 L2 P1 X5. Y-3. R15.",
    "G10 L2 P2 X-7. Y4. Z1.",
    "G92.1 X2. Y1. R20.",
    "G92.1 X0 Y0 R0",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn random_programs_agree(
        blocks in prop::collection::vec(prop::sample::select(BLOCKS), 1..40),
        dialect in prop::sample::select(&Dialect::ALL[..]),
    ) {
        let mut text = blocks.join("\n");
        text.push_str("\nM30\nO9000\nG91 G1 X1. F100.\nM99\n");
        // Half of them a block a step, as the editor's run with states steps.
        let setup = Setup::from_toml(SETUP).expect("setup");
        let budget = if blocks.len() % 2 == 0 { 1 } else { 4096 };
        let result = run_both_with(&parse(&text, dialect), &setup, budget);
        prop_assert!(result.is_ok(), "{text}\n{:?}", result.err());
    }
}
