//! Tabs: several open files, each with its own text, undo history and unsaved-changes guard;
//! subprogram calls in the active tab reach the programs of the other tabs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_syntax::{Dialect, Encoding, Severity};
use swarf_ui::{HostRequest, Workbench};

const MAIN: &str = "G90 G21\nG0 X0 Y0 Z5\nM98 P1234\nM30\n";
const SUB: &str = "O1234\nG1 X5 F100\nG1 Y5\nM99\n";

fn harness(wb: Workbench) -> Harness<'static, Workbench> {
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness
}

fn errors(wb: &Workbench) -> Vec<&'static str> {
    wb.problems()
        .iter()
        .filter(|p| p.severity == Severity::Error)
        .map(|p| p.code)
        .collect()
}

#[test]
fn two_tabs_keep_their_text_history_and_program() {
    let mut wb = Workbench::default();
    let example_motions = wb.stats().motions;
    wb.open_document("a.nc", "G0 X1\n", Encoding::Utf8);
    wb.set_text("G0 X1\nG1 X2 F100\n");
    assert_eq!(wb.tab_count(), 2);
    assert_eq!(wb.active_tab(), 1);
    assert_eq!(wb.stats().motions, 2);
    let mut harness = harness(wb);
    // The strip shows both, the changed one marked.
    harness.get_by_label("pocket.nc").click();
    harness.run();
    assert_eq!(harness.state().active_tab(), 0);
    assert_eq!(harness.state().document().name, "pocket.nc");
    assert_eq!(harness.state().stats().motions, example_motions);
    assert!(!harness.state().is_dirty());
    assert!(harness.state().any_dirty());
    harness.get_by_label("a.nc *").click();
    harness.run();
    assert_eq!(harness.state().text(), "G0 X1\nG1 X2 F100\n");
    assert_eq!(harness.state().stats().motions, 2);
    // Undo belongs to the tab.
    harness.state_mut().undo();
    assert_eq!(harness.state().text(), "G0 X1\n");
    assert!(!harness.state().is_dirty());
    // + opens an empty untitled tab; a file opened next takes its place.
    harness.get_by_label("New tab").click();
    harness.run();
    assert_eq!(harness.state().tab_count(), 3);
    assert_eq!(harness.state().document().name, "untitled.nc");
    harness
        .state_mut()
        .open_document("b.nc", "G0 Y1\n", Encoding::Utf8);
    assert_eq!(harness.state().tab_count(), 3);
    assert_eq!(harness.state().document().name, "b.nc");
    // A file opened again from the same path gets its tab back.
    harness.state_mut().set_path(Some("/work/b.nc".into()));
    harness.state_mut().switch_tab(0);
    harness.state_mut().open_file(
        "b.nc",
        "G0 Y2\n".into(),
        Encoding::Utf8,
        Some("/work/b.nc".into()),
    );
    assert_eq!(harness.state().tab_count(), 3);
    assert_eq!(harness.state().active_tab(), 2);
    assert_eq!(harness.state().text(), "G0 Y2\n");
}

#[test]
fn a_call_resolves_in_another_tab_and_says_so_when_no_tab_has_it() {
    let mut wb = Workbench::default();
    wb.open_document("O1234.nc", SUB, Encoding::Utf8);
    wb.open_document("main.nc", MAIN, Encoding::Utf8);
    wb.finish_analysis();
    assert!(errors(&wb).is_empty(), "{:?}", wb.problems());
    // The rapid, then the subprogram's two feeds.
    assert_eq!(wb.stats().motions, 3);
    assert!(wb.analysis().elsewhere.is_empty());
    // Without the tab, the call is an error that names the open tabs.
    let mut harness = harness(wb);
    harness.get_by_label("Close O1234.nc").click();
    harness.run();
    assert_eq!(harness.state().tab_count(), 2);
    assert_eq!(harness.state().document().name, "main.nc");
    let wb = harness.state();
    let p = wb
        .problems()
        .iter()
        .find(|p| p.code == "E-SUBPROGRAM")
        .expect("the missing program is reported");
    assert_eq!(p.line, 3);
    assert!(p.message.contains("open tab"), "{}", p.message);
    assert!(p.message.contains("O1234.nc"), "{}", p.message);
    assert_eq!(wb.stats().motions, 1);
    // Other names the CLI looks for work too: `1234.nc`.
    harness
        .state_mut()
        .open_document("1234.nc", SUB, Encoding::Utf8);
    harness.state_mut().switch_tab(1);
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().document().name, "main.nc");
    assert!(errors(harness.state()).is_empty());
    assert_eq!(harness.state().stats().motions, 3);
}

#[test]
fn a_linuxcnc_subroutine_file_is_found_among_the_tabs() {
    let mut wb = Workbench::default();
    wb.set_dialect(Dialect::LinuxCnc);
    wb.open_document(
        "square.ngc",
        "o<square> sub\nG1 X#1 F100\nG1 Y#1\no<square> endsub\nM2\n",
        Encoding::Utf8,
    );
    wb.open_document(
        "main.ngc",
        "G90 G21\nG0 X0 Y0\no<square> call [4]\nM2\n",
        Encoding::Utf8,
    );
    wb.finish_analysis();
    assert!(errors(&wb).is_empty(), "{:?}", wb.problems());
    // The rapid, then the subroutine's two feeds.
    assert_eq!(wb.stats().motions, 3);
    wb.close_tab(0);
    wb.close_tab(0);
    wb.finish_analysis();
    assert_eq!(wb.tab_count(), 1);
    let p = wb
        .problems()
        .iter()
        .find(|p| p.severity == Severity::Error)
        .expect("the missing subroutine is reported");
    assert!(p.message.contains("open tab"), "{}", p.message);
}

#[test]
fn problems_in_a_called_tab_are_located_there_and_jump_to_it() {
    let mut wb = Workbench::default();
    wb.open_document("O1234.nc", "O1234\nG1 X5 Y$ F100\nM99\n", Encoding::Utf8);
    wb.open_document("main.nc", MAIN, Encoding::Utf8);
    wb.finish_analysis();
    // Nothing is marked in the caller's own text …
    assert!(
        wb.problems().iter().all(|p| p.code != "E-SYNTAX-CHAR"),
        "{:?}",
        wb.problems()
    );
    // … the called file's problem is listed with its own line and column.
    let l = wb
        .analysis()
        .elsewhere
        .iter()
        .find(|l| l.problem.code == "E-SYNTAX-CHAR")
        .expect("the sub's problem is listed");
    assert_eq!(l.file, "O1234.nc");
    assert_eq!((l.problem.line, l.problem.col), (2, 8));
    let chars = l.problem.chars.clone();
    let mut harness = harness(wb);
    harness
        .get_by_label_contains("O1234.nc:2:8  error[E-SYNTAX-CHAR]")
        .click();
    // A subprogram file on its own loops at its M99 until the runaway limit: its analysis goes
    // on over many frames, so step rather than wait for it to settle.
    harness.step();
    harness.step();
    assert_eq!(harness.state().document().name, "O1234.nc");
    assert_eq!(harness.state().selection(), chars);
    assert_eq!(harness.state().selected_text(), "$");
}

#[test]
fn closing_a_changed_tab_asks_and_quitting_asks_for_each() {
    let mut wb = Workbench::default();
    wb.open_document("a.nc", "G0 X1\n", Encoding::Utf8);
    wb.set_text("G0 X2\n");
    wb.open_document("b.nc", "G0 X3\n", Encoding::Utf8);
    wb.set_text("G0 X4\n");
    let mut harness = harness(wb);
    harness.get_by_label("Close a.nc").click();
    harness.run();
    // The tab asked about comes to the front.
    assert_eq!(harness.state().document().name, "a.nc");
    harness.get_by_label("Unsaved changes");
    harness.get_by_label("Cancel").click();
    harness.run();
    assert_eq!(harness.state().tab_count(), 3);
    // Quitting asks for a.nc, then for b.nc, then quits.
    harness.state_mut().request_quit();
    harness.run();
    assert!(harness.state_mut().take_requests().is_empty());
    assert_eq!(harness.state().document().name, "a.nc");
    harness.get_by_label("Discard changes").click();
    harness.run();
    assert!(harness.state_mut().take_requests().is_empty());
    assert_eq!(harness.state().document().name, "b.nc");
    harness.get_by_label("Discard changes").click();
    harness.run();
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::Quit]);
    // Closing the last tab leaves an empty untitled one.
    let mut wb = Workbench::default();
    wb.close_tab(0);
    assert_eq!(wb.tab_count(), 1);
    assert_eq!(wb.text(), "");
    assert_eq!(wb.document().name, "untitled.nc");
}

#[test]
fn every_tab_is_kept_and_restored() {
    let mut wb = Workbench::default();
    wb.open_document("O1234.nc", SUB, Encoding::Gb18030);
    wb.set_path(Some("/work/O1234.nc".into()));
    wb.open_document("main.nc", MAIN, Encoding::Utf8);
    wb.set_text(format!("{MAIN}(changed)\n"));
    let (records, active) = wb.tab_records();
    assert_eq!(records.len(), 3);
    assert_eq!(active, 2);
    assert!(records[2].dirty && !records[1].dirty);
    let mut back = Workbench::default();
    back.restore_tabs(records.clone(), active);
    back.finish_analysis();
    assert_eq!(back.tab_records(), (records, 2));
    assert_eq!(back.text(), format!("{MAIN}(changed)\n"));
    assert!(back.is_dirty());
    // The call still reaches the restored sub.
    assert!(errors(&back).is_empty(), "{:?}", back.problems());
    back.switch_tab(1);
    assert_eq!(back.document().encoding, Encoding::Gb18030);
    assert_eq!(back.document().path.as_deref(), Some("/work/O1234.nc"));
    assert!(!back.is_dirty());
}
