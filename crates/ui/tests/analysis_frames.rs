//! Analysis spread over frames: small programs are ready in the frame of the edit, long ones
//! run behind a progress bar while the last results stay, and a newer edit starts over.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_interp::Setup;
use swarf_syntax::Dialect;
use swarf_ui::analysis::{Analysis, PendingAnalysis};
use swarf_ui::{FRAME_BUDGET, Workbench};

/// `lines` straight moves, then `tail`.
fn program(lines: usize, tail: &str) -> String {
    let mut text = String::from("G90 G21 G17 G54\n");
    for i in 1..lines {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 100, i % 37));
    }
    text.push_str(tail);
    text
}

fn harness(wb: Workbench) -> Harness<'static, Workbench> {
    Harness::builder()
        .with_size(egui::vec2(1000.0, 600.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb)
}

#[test]
fn a_pending_analysis_in_steps_equals_the_one_call_run() {
    let text = program(3000, "G01 X$\nM30\n");
    let setup = Setup::default();
    let whole = Analysis::run(&text, Dialect::Fanuc, &setup, 7);
    let mut pending = PendingAnalysis::start(&text, Dialect::Fanuc, &setup, 7);
    // The text is read first (two lines per block of budget), then run.
    assert_eq!(pending.parse_progress(), Some((0, 3003)));
    assert_eq!(pending.progress(), (0, 0));
    let mut steps = 0;
    let mut read_steps = 0;
    while !pending.step(100) {
        steps += 1;
        if let Some((read, lines)) = pending.parse_progress() {
            assert_eq!(read, 200 * steps);
            assert!(read < lines);
            read_steps += 1;
        } else {
            let (done, total) = pending.progress();
            assert_eq!(total, 3002);
            assert!(done <= total);
        }
    }
    assert_eq!(read_steps, 15);
    assert!(steps >= 15 + 29, "{steps}");
    assert!(pending.is_finished());
    let stepped = pending.finish();
    assert_eq!(stepped.problems, whole.problems);
    assert_eq!(stepped.stats(), whole.stats());
    assert_eq!(stepped.scene.generation, 7);
}

#[test]
fn typing_in_a_10k_line_program_marks_the_error_in_the_same_frame() {
    let mut wb = Workbench::default();
    wb.open_document(
        "long.nc",
        program(10_000, "M30\n"),
        swarf_syntax::Encoding::default(),
    );
    assert!(wb.analysis_progress().is_none());
    assert!(wb.problems().is_empty(), "{:?}", wb.problems());
    let mut harness = harness(wb);
    harness.run();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    harness.run();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.type_text("G01 X$\n");
    // One frame: the typed text, its analysis and the markers.
    harness.step();
    let wb = harness.state();
    assert!(wb.text().starts_with("G01 X$\n"));
    assert!(wb.analysis_progress().is_none());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.analysis().scene.generation, wb.generation());
}

#[test]
fn a_long_program_runs_over_frames_behind_a_progress_bar_keeping_the_old_results() {
    let mut wb = Workbench::default();
    wb.set_text("G01 X$ F100\n");
    let old = wb.problems().to_vec();
    assert!(!old.is_empty());
    let mut harness = harness(wb);
    harness.run();
    let lines = 5 * FRAME_BUDGET;
    harness
        .state_mut()
        .set_text(program(lines, "G01 Y$\nM30\n"));
    // The first frame's budget reads the first lines of the text.
    assert_eq!(harness.state().analysis_progress(), Some((0, 0)));
    assert_eq!(
        harness.state().problems(),
        old.as_slice(),
        "old problems stay"
    );
    harness.step();
    harness.get_by_label_contains("Analysing");
    assert_eq!(harness.state().problems(), old.as_slice());
    let mut last = 0;
    let mut frames = 1;
    let mut run_frames = 0;
    while let Some((done, total)) = harness.state().analysis_progress() {
        if total > 0 {
            assert_eq!(total, lines + 2);
            // All blocks reached: the problems are being located, the scene prepared.
            assert!(done >= last && done <= total, "{done} of {total}");
            last = done;
            run_frames += 1;
        }
        harness.step();
        frames += 1;
        assert!(frames < 100, "the analysis ends");
    }
    assert!(run_frames >= 3, "{run_frames} frames running");
    assert!(frames >= 5, "{frames} frames");
    let wb = harness.state();
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(
        codes.contains(&(lines as u32 + 1, "E-SYNTAX-CHAR")),
        "{codes:?}"
    );
    assert!(!codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.stats().blocks, lines + 2);
    harness.step();
    assert!(harness.query_by_label_contains("Analysing").is_none());
}

#[test]
fn a_newer_edit_cancels_an_unfinished_run() {
    let mut wb = Workbench::default();
    wb.set_text(program(3 * FRAME_BUDGET, "M30\n"));
    assert!(wb.analysis_progress().is_some());
    wb.set_text("G0 X1\nG01 X$\n");
    assert!(wb.analysis_progress().is_none());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(2, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.stats().blocks, 2);
}

#[test]
fn finishing_the_analysis_gives_the_current_texts_results_at_once() {
    let mut wb = Workbench::default();
    wb.set_text(program(3 * FRAME_BUDGET, "G01 Z$\n"));
    assert!(wb.analysis_progress().is_some());
    wb.finish_analysis();
    assert!(wb.analysis_progress().is_none());
    assert_eq!(wb.stats().blocks, 3 * FRAME_BUDGET + 1);
    assert!(wb.problems().iter().any(|p| p.code == "E-SYNTAX-CHAR"));
    assert_eq!(wb.analysis().scene.generation, wb.generation());
}
