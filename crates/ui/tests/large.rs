//! A program too large for egui's text editor is shown read-only, a line laid out only while it
//! is on screen, and still drives the backplot and the state panel.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;
use swarf_ui::editor::LARGE_TEXT_BYTES;

#[test]
fn a_large_program_is_shown_read_only_and_a_click_selects_its_line() {
    let mut text = String::from("G90 G21 G17\nG00 X0 Y0 Z5.\n");
    let mut n = 0;
    while text.len() <= LARGE_TEXT_BYTES {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", n % 100, n / 100));
        n += 1;
    }
    let lines = text.lines().count();
    let mut wb = Workbench::default();
    wb.set_text(text);
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    let notice = format!("{} lines, ", lines + 1);
    assert!(
        harness.query_by_label_contains(&notice).is_some(),
        "the read-only notice"
    );
    // The third line is on screen; a click on it puts the cursor there.
    harness.get_by_label("G01 X0. Y0. F500.").click();
    harness.run();
    assert_eq!(harness.state().cursor_line(), Some(3));
    // The whole program still runs.
    assert_eq!(harness.state().stats().motions, n + 1);
}
