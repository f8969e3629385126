//! The state at any block: modal codes, positions, offsets, tool, feed and speed before it runs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{CanonRecorder, Setup, Sink, States, StatesRun, Status};
use swarf_syntax::{Diagnostic, Dialect, Program, parse};

/// Runs a whole program in one call, recording its [`States`].
fn run_with_states(
    program: &Program,
    setup: Setup,
    sink: &mut dyn Sink,
) -> (Vec<Diagnostic>, States) {
    let mut run = StatesRun::new(program, setup);
    while run.step(program, sink, usize::MAX) == Status::Running {}
    run.finish()
}

#[test]
fn state_before_a_block_has_the_modes_position_and_tool() {
    let setup = Setup::from_toml("[work_offsets]\nG55 = [100.0, 0.0, 0.0]\n").unwrap();
    let text =
        "G90 G21 G17 G55\nT3 M06\nG00 X10. Y5.\nG01 Z-1. F250. S1200 M03\nG91 X1.\nM30\nG00 X99.\n";
    let program = parse(text, Dialect::Fanuc);
    let (_, states) = run_with_states(&program, setup, &mut CanonRecorder::default());
    let s = states.at(&program, 4).unwrap();
    assert_eq!(s.machine, DVec3::new(110.0, 5.0, -1.0));
    assert_eq!(s.work, DVec3::new(10.0, 5.0, -1.0));
    assert_eq!(s.work_offset_name, "G55");
    assert_eq!(s.tool, 3);
    assert_eq!(s.feed, 250.0);
    assert_eq!(s.spindle_rpm, 1200.0);
    for code in ["G01", "G17", "G90", "G21", "G55"] {
        assert!(s.codes.iter().any(|c| c == code), "{code} in {:?}", s.codes);
    }
    // Block 5 (M30) follows G91.
    assert!(
        states
            .at(&program, 5)
            .unwrap()
            .codes
            .iter()
            .any(|c| c == "G91")
    );
    // After M30 nothing runs.
    assert!(states.at(&program, 6).is_none());
}

#[test]
fn states_deep_into_a_long_run_come_from_the_nearest_copy() {
    let mut text = String::from("G91 G01 F100.\n");
    for _ in 0..10_000 {
        text.push_str("X1.\n");
    }
    let program = parse(&text, Dialect::Fanuc);
    let (_, states) = run_with_states(&program, Setup::default(), &mut CanonRecorder::default());
    assert!(states.checkpoints() >= 3);
    for block in [1, 4097, 9000, 10_000] {
        let s = states.at(&program, block).unwrap();
        assert_eq!(s.machine.x, (block - 1) as f64, "block {block}");
        assert_eq!(s.executed, block as u64);
    }
}

#[test]
fn a_run_in_small_steps_records_the_same_as_one_call() {
    let mut text =
        String::from("G90 G21 G17\n#1=0\nWHILE[#1LT40]DO1\nG01 X#1 F100.\n#1=#1+1\nEND1\n");
    for i in 0..5000 {
        text.push_str(&format!("G01 X{}. Y{}.\n", i % 50, i % 7));
    }
    text.push_str("G01 X1 Y\nM30\n");
    let program = parse(&text, Dialect::Fanuc);
    let mut whole = CanonRecorder::default();
    let (diags, states) = run_with_states(&program, Setup::default(), &mut whole);

    let mut stepped = CanonRecorder::default();
    let mut run = StatesRun::new(&program, Setup::default());
    let mut steps = 0;
    while run.step(&program, &mut stepped, 7) == Status::Running {
        steps += 1;
        assert!(run.blocks_reached() <= program.blocks.len());
    }
    assert!(steps > 100, "{steps} steps");
    assert_eq!(run.blocks_reached(), program.blocks.len());
    assert!(run.executed_blocks() > program.blocks.len() as u64);
    let (diags2, states2) = run.finish();
    assert_eq!(diags, diags2);
    assert_eq!(whole.events, stepped.events);
    assert_eq!(states.checkpoints(), states2.checkpoints());
    for block in [0, 3, 100, 4000, program.blocks.len() - 1] {
        assert_eq!(states.at(&program, block), states2.at(&program, block));
    }
}
