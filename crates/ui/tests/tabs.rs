//! Tabs: several open files, each with its own text, undo history and unsaved-changes guard;
//! subprogram calls in the active tab reach the programs of the other tabs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use swarf_syntax::{Dialect, Encoding, Severity};
use swarf_ui::{HostRequest, TabRecord, Workbench};

const MAIN: &str = "G90 G21\nG0 X0 Y0 Z5\nM98 P1234\nM30\n";
const SUB: &str = "O1234\nG1 X5 F100\nG1 Y5\nM99\n";

/// Every tab's file and text, as a host keeps them for recovery, and the active tab.
fn tab_records(wb: &Workbench) -> (Vec<TabRecord>, usize) {
    let docs = wb.tab_documents().into_iter().enumerate();
    let records = docs.map(|(i, d)| TabRecord {
        name: d.name.clone(),
        path: d.path.clone(),
        encoding: d.encoding,
        text: wb.tab_text(i).unwrap(),
        dirty: d.is_unsaved(),
        dialect: wb.tab_dialect(i),
    });
    (records.collect(), wb.active_tab())
}

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
    wb.finish_analysis();
    let example_motions = wb.stats().motions;
    wb.open_document("a.nc", "G0 X1\n", Encoding::Utf8);
    wb.set_text("G0 X1\nG1 X2 F100\n");
    wb.finish_analysis();
    assert_eq!(wb.tab_documents().len(), 2);
    assert_eq!(wb.active_tab(), 1);
    assert_eq!(wb.stats().motions, 2);
    let mut harness = harness(wb);
    // The strip shows both, the changed one marked.
    harness.get_by_label("pocket.nc").click();
    harness.run();
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().active_tab(), 0);
    assert_eq!(harness.state().document().name, "pocket.nc");
    assert_eq!(harness.state().stats().motions, example_motions);
    assert!(!harness.state().document().is_unsaved());
    assert!(harness.state().any_dirty());
    harness.get_by_label("a.nc *").click();
    harness.run();
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().text(), "G0 X1\nG1 X2 F100\n");
    assert_eq!(harness.state().stats().motions, 2);
    // Undo belongs to the tab.
    harness.state_mut().undo();
    assert_eq!(harness.state().text(), "G0 X1\n");
    assert!(!harness.state().document().is_unsaved());
    // + opens an empty untitled tab; a file opened next takes its place.
    harness.get_by_label("New tab").click();
    harness.run();
    assert_eq!(harness.state().tab_documents().len(), 3);
    assert_eq!(harness.state().document().name, "untitled.nc");
    harness
        .state_mut()
        .open_document("b.nc", "G0 Y1\n", Encoding::Utf8);
    assert_eq!(harness.state().tab_documents().len(), 3);
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
    assert_eq!(harness.state().tab_documents().len(), 3);
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
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().tab_documents().len(), 2);
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
    assert_eq!(wb.tab_documents().len(), 1);
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
    // A subprogram file on its own loops at its M99 until the runaway limit: its analysis takes
    // a while, so step rather than wait for it to settle.
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
    assert_eq!(harness.state().tab_documents().len(), 3);
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
    assert_eq!(wb.tab_documents().len(), 1);
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
    let (records, active) = tab_records(&wb);
    assert_eq!(records.len(), 3);
    assert_eq!(active, 2);
    assert!(records[2].dirty && !records[1].dirty);
    let mut back = Workbench::default();
    back.restore_tabs(records.clone(), active);
    back.finish_analysis();
    assert_eq!(tab_records(&back), (records, 2));
    assert_eq!(back.text(), format!("{MAIN}(changed)\n"));
    assert!(back.document().is_unsaved());
    // The call still reaches the restored sub.
    assert!(errors(&back).is_empty(), "{:?}", back.problems());
    back.switch_tab(1);
    assert_eq!(back.document().encoding, Encoding::Gb18030);
    assert_eq!(back.document().path.as_deref(), Some("/work/O1234.nc"));
    assert!(!back.document().is_unsaved());
}

/// The dialect the top bar's selector shows.
fn selector(harness: &Harness<'_, Workbench>) -> Option<String> {
    harness.get_by_label("Dialect").accesskit_node().value()
}

fn dialect_errors(wb: &Workbench) -> usize {
    wb.problems()
        .iter()
        .filter(|p| p.code == "E-CODE-DIALECT")
        .count()
}

/// Finishes the analysis of the active tab and checks its dialect, shown by the selector,
/// with no dialect errors.
fn analysed_in(harness: &mut Harness<'_, Workbench>, dialect: Dialect, shown: &str) {
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().dialect(), dialect);
    assert_eq!(selector(harness).as_deref(), Some(shown));
    assert_eq!(dialect_errors(harness.state()), 0);
}

/// A Syntec program: `G71` is its metric code, which Fanuc does not have.
const SYNTEC: &str =
    "%\nO3001\nN10 G90 G71 G17 G54\nG00 X0. Y0. Z20.\nG01 Z-2. F200.\nX40.\nM30\n%\n";

#[test]
fn each_tab_keeps_its_dialect_and_the_selector_follows_the_active_one() {
    let mut harness = harness(Workbench::default());
    assert!(harness.state_mut().open_example("syntec-bolt-circle.nc"));
    harness.run();
    analysed_in(&mut harness, Dialect::Syntec, "Syntec 900M");
    // The example shown at start keeps Fanuc.
    harness.get_by_label("pocket.nc").click();
    harness.run();
    analysed_in(&mut harness, Dialect::Fanuc, "Fanuc 0i-M");
    // The selector changes the active tab alone …
    harness.get_by_label("Dialect").click();
    harness.run();
    harness.get_by_label("LNC / Baoyuan").click();
    harness.run();
    assert_eq!(harness.state().dialect(), Dialect::Lnc);
    assert_eq!(harness.state().tab_dialect(1), Some(Dialect::Syntec));
    harness.get_by_label("syntec-bolt-circle.nc").click();
    harness.run();
    analysed_in(&mut harness, Dialect::Syntec, "Syntec 900M");
    harness.get_by_label("pocket.nc").click();
    harness.run();
    assert_eq!(harness.state().dialect(), Dialect::Lnc);
    // … and is what new tabs start in.
    assert_eq!(harness.state().default_dialect(), Dialect::Lnc);
    harness.get_by_label("New tab").click();
    harness.run();
    assert_eq!(harness.state().dialect(), Dialect::Lnc);
    assert_eq!(selector(&harness).as_deref(), Some("LNC / Baoyuan"));
    // A host can read and set each tab's dialect (for its recovery record).
    let wb = harness.state_mut();
    assert_eq!(wb.tab_dialect(3), None);
    wb.set_tab_dialect(0, Dialect::Kt);
    assert_eq!(wb.dialect(), Dialect::Lnc);
    wb.switch_tab(0);
    assert_eq!(wb.dialect(), Dialect::Kt);
    assert_eq!(wb.default_dialect(), Dialect::Lnc);
}

#[test]
fn a_file_opens_in_the_default_dialect_and_a_reopened_one_keeps_its_tabs() {
    let mut wb = Workbench::default();
    // As a host restoring its settings: the default changes, the tab already open keeps its own.
    wb.set_dialect(Dialect::Syntec);
    wb.set_tab_dialect(0, Dialect::Fanuc);
    assert_eq!(wb.dialect(), Dialect::Fanuc);
    wb.open_file(
        "flange.nc",
        SYNTEC.to_string(),
        Encoding::Utf8,
        Some("/work/flange.nc".into()),
    );
    assert_eq!(wb.dialect(), Dialect::Syntec);
    wb.finish_analysis();
    assert_eq!(dialect_errors(&wb), 0);
    wb.set_tab_dialect(1, Dialect::Kt);
    wb.switch_tab(0);
    wb.open_file(
        "flange.nc",
        SYNTEC.to_string(),
        Encoding::Utf8,
        Some("/work/flange.nc".into()),
    );
    assert_eq!(wb.active_tab(), 1);
    assert_eq!(wb.dialect(), Dialect::Kt);
}

#[test]
fn a_syntec_program_in_a_fanuc_tab_is_offered_syntec_and_one_click_switches() {
    let mut wb = Workbench::default();
    wb.open_document("flange.nc", SYNTEC, Encoding::Utf8);
    wb.finish_analysis();
    assert_eq!(wb.dialect(), Dialect::Fanuc);
    assert_eq!(dialect_errors(&wb), 1);
    assert_eq!(wb.suggested_dialect(), Some(Dialect::Syntec));
    let mut harness = harness(wb);
    harness.get_by_label_contains("This program looks like Syntec 900M (G71 on line 3)");
    // Offered, not switched.
    assert_eq!(harness.state().dialect(), Dialect::Fanuc);
    harness.get_by_label("Switch").click();
    harness.run();
    harness.state_mut().finish_analysis();
    harness.run();
    let wb = harness.state();
    assert_eq!(wb.dialect(), Dialect::Syntec);
    assert_eq!(dialect_errors(wb), 0);
    assert!(errors(wb).is_empty(), "{:?}", wb.problems());
    assert_eq!(wb.suggested_dialect(), None);
    assert!(
        harness
            .query_by_label_contains("This program looks like")
            .is_none()
    );
    assert_eq!(selector(&harness).as_deref(), Some("Syntec 900M"));
    // The switch is the tab's own: the other tab and new ones stay Fanuc.
    assert_eq!(harness.state().tab_dialect(0), Some(Dialect::Fanuc));
    assert_eq!(harness.state().default_dialect(), Dialect::Fanuc);
    // A clean Fanuc program gets no offer.
    harness.state_mut().switch_tab(0);
    harness.state_mut().finish_analysis();
    harness.run();
    assert_eq!(harness.state().suggested_dialect(), None);
    assert!(
        harness
            .query_by_label_contains("This program looks like")
            .is_none()
    );
}

/// `lines` straight feeds: long enough that its analysis takes a while.
fn long_program(lines: usize) -> String {
    let mut text = String::from("G90 G21 G17 G54\nG00 X0 Y0 Z5\n");
    for i in 0..lines {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 100, i % 37));
    }
    text.push_str("M30\n");
    text
}

#[test]
fn a_loading_tab_shows_none_of_the_tab_before() {
    /// The analysis run only when the test waits for it: no frame sees a run finish.
    struct Waited(swarf_analysis::Inline);
    impl swarf_analysis::Analyst for Waited {
        fn send(&mut self, request: swarf_analysis::Request) -> Option<swarf_analysis::Reply> {
            self.0.send(request)
        }
        fn try_reply(&mut self) -> Option<swarf_analysis::Reply> {
            None
        }
        fn wait_reply(&mut self) -> Option<swarf_analysis::Reply> {
            self.0.wait_reply()
        }
    }
    let mut wb = Workbench::default();
    wb.set_analyst(Box::new(Waited(swarf_analysis::Inline::default())));
    wb.finish_analysis();
    let example = wb.stats();
    assert!(example.motions > 0);
    assert!(wb.analysis_ready());
    wb.open_document("long.nc", long_program(100_000), Encoding::Utf8);
    // Its first analysis takes a while: until it is done the tab shows an empty
    // view, no problems and no counts, not the example's.
    assert!(wb.analysis_progress().is_some());
    assert!(!wb.analysis_ready());
    assert_eq!(wb.stats().motions, 0);
    assert_eq!(wb.stats().blocks, 0);
    assert!(wb.stats().bounds.is_none());
    assert_eq!(wb.analysis().scene.segment_count(), 0);
    assert!(wb.problems().is_empty());
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.step();
    // A frame that began with the analysis running showed its progress.
    assert!(
        harness.state().analysis_progress().is_none()
            || harness.query_by_label_contains("Reading… ").is_some()
            || harness.query_by_label_contains("Analysing… ").is_some()
    );
    assert_eq!(harness.state().stats().motions, 0);
    // Back to the example: its own analysis at once.
    harness.state_mut().switch_tab(0);
    assert!(harness.state().analysis_ready());
    assert_eq!(harness.state().stats(), example);
    harness.step();
    assert!(harness.query_by_label_contains("Reading… ").is_none());
    // The long tab's unfinished run was dropped: it shows nothing until a new one is done …
    harness.state_mut().switch_tab(1);
    assert!(!harness.state().analysis_ready());
    assert_eq!(harness.state().stats().motions, 0);
    harness.state_mut().finish_analysis();
    let long = harness.state().stats();
    assert_eq!(long.motions, 100_001);
    // … and once it has one, it is the tab's to show while it is analysed again.
    harness.state_mut().switch_tab(0);
    assert_eq!(harness.state().stats(), example);
    harness.state_mut().switch_tab(1);
    assert!(harness.state().analysis_progress().is_some());
    assert!(harness.state().analysis_ready());
    assert_eq!(harness.state().stats(), long);
    // Closing a tab leaves no trace of it on the other.
    harness.state_mut().close_tab(1);
    assert_eq!(harness.state().stats(), example);
}
