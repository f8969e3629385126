//! The workbench re-analyses on edits, locates problems for the editor and lists them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_syntax::{Dialect, Severity};
use swarf_ui::Workbench;

#[test]
fn example_program_runs_clean_and_draws() {
    let mut wb = Workbench::default();
    wb.finish_analysis();
    assert!(wb.problems().is_empty(), "{:?}", wb.problems());
    let s = wb.stats();
    assert!(s.motions > 10);
    assert!(s.bounds.is_some());
    assert_eq!(wb.analysis().scene.segment_count(), s.motions);
}

#[test]
fn edits_update_problems_with_lines_columns_and_character_ranges() {
    let mut wb = Workbench::default();
    let text = "(銑) G90\nG00 X0 Y0 Z5\nG01 X10 Y$ F100\n";
    wb.set_text(text);
    wb.finish_analysis();
    let p = wb
        .problems()
        .iter()
        .find(|p| p.code == "E-SYNTAX-CHAR")
        .expect("bad character reported");
    assert_eq!((p.line, p.col, p.severity), (3, 10, Severity::Error));
    let chars: Vec<char> = text.chars().collect();
    assert_eq!(chars[p.chars.clone()], ['$']);
    assert_eq!(wb.stats().motions, 1);
    let before = wb.analysis().scene.generation;
    wb.set_dialect(Dialect::LinuxCnc);
    wb.finish_analysis();
    assert!(wb.analysis().scene.generation > before);
    wb.set_text("G0 X1\n");
    wb.finish_analysis();
    assert!(wb.problems().is_empty());
}

#[test]
fn the_problems_panel_lists_each_diagnostic() {
    let mut wb = Workbench::default();
    wb.set_text("G01 X10 Y$ F100\n");
    wb.finish_analysis();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1000.0, 600.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("Problems (2)");
    harness.get_by_label_contains("error[E-SYNTAX-CHAR]  unexpected character `$`");
    harness.get_by_label_contains("1 blocks");
}

#[test]
fn typing_in_the_editor_re_plots_and_marks_errors() {
    let mut wb = Workbench::default();
    wb.set_text("");
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1000.0, 600.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    editor.type_text("G0 X5. Y7.\nG1 X$ F100\n");
    harness.run();
    harness.state_mut().finish_analysis();
    let wb = harness.state();
    assert_eq!(wb.text(), "G0 X5. Y7.\nG1 X$ F100\n");
    assert_eq!(wb.stats().motions, 1);
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert_eq!(codes, [(2, "E-WORD-VALUE"), (2, "E-SYNTAX-CHAR")]);
}

#[test]
fn state_at_a_line_shows_modes_position_and_tool() {
    let mut wb = Workbench::default();
    wb.set_text("G90 G21 G17\nT2 M06\nG00 X10. Y5.\nG01 Z-1. F300.\nM30\nG00 X99.\n");
    wb.finish_analysis();
    wb.go_to_line(4);
    // The panel shows the state just before the cursor's block runs.
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 700.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("State at cursor");
    assert!(harness.get_all_by_label("X10.000 Y5.000 Z0.000").count() >= 1);
    harness.get_by_label("T2");
    assert!(harness.get_all_by_label_contains("G00").count() >= 1);
    // A block past the program's end never runs.
    harness.state_mut().go_to_line(6);
    harness.run();
    harness.get_by_label("Line 6 does not run.");
}
