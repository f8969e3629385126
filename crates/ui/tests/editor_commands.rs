//! The editor's commands driven through the UI: find/replace, go to line, comment toggling,
//! renumbering, undo/redo across them, completion, gutter tooltips and the unsaved-changes guard.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui::accesskit::Role;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_syntax::Dialect;
use swarf_ui::{HostRequest, Workbench};

fn harness(text: &str) -> Harness<'static, Workbench> {
    let mut wb = Workbench::default();
    wb.open_document("test.nc", text, swarf_syntax::Encoding::Utf8);
    wb.finish_analysis();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness
}

fn click_menu(harness: &mut Harness<'static, Workbench>, menu: &str, item: &str) {
    harness.get_by_label(menu).click();
    harness.run();
    harness.get_by_label(item).click();
    harness.run();
}

#[test]
fn find_and_replace_with_a_regex_then_undo() {
    let mut harness = harness("G01 X10. F200\nG01 X20. F300\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::H);
    harness.run();
    harness
        .get_by_role_and_label(Role::TextInput, "Find")
        .type_text(r"F(\d+)");
    harness.get_by_label("Regex").click();
    harness.run();
    harness.get_by_label("2 matches");
    let replace = harness.get_by_role_and_label(Role::TextInput, "Replace");
    replace.focus();
    replace.type_text("F${1}0");
    harness.get_by_label("Replace all").click();
    harness.run();
    assert_eq!(harness.state().text(), "G01 X10. F2000\nG01 X20. F3000\n");
    // Next selects a match.
    harness.get_by_label("Next").click();
    harness.run();
    assert_eq!(harness.state().selected_text(), "F2000");
    // One undo takes the whole replacement back.
    click_menu(&mut harness, "Edit", "Undo Ctrl+Z");
    assert_eq!(harness.state().text(), "G01 X10. F200\nG01 X20. F300\n");
    click_menu(&mut harness, "Edit", "Redo Ctrl+Y");
    assert_eq!(harness.state().text(), "G01 X10. F2000\nG01 X20. F3000\n");
}

#[test]
fn an_invalid_pattern_is_reported_not_applied() {
    let mut harness = harness("G01 X1\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
    harness.run();
    harness.get_by_label("Regex").click();
    harness.run();
    let find = harness.get_by_role_and_label(Role::TextInput, "Find");
    find.focus();
    find.type_text("(G");
    harness.run();
    harness.get_by_label("invalid pattern");
    harness.state_mut().replace_all();
    assert_eq!(harness.state().text(), "G01 X1\n");
    // Escape closes the bar and gives the program the keyboard back.
    harness.key_press(Key::Escape);
    harness.run();
    assert!(harness.query_by_label("invalid pattern").is_none());
    assert!(harness.get_by_role(Role::MultilineTextInput).is_focused());
}

#[test]
fn ctrl_g_goes_to_a_line() {
    let mut harness = harness("G90\nG00 X0\nG01 X5 F100\nM30\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::G);
    harness.run();
    harness
        .get_by_role_and_label(Role::TextInput, "Line number")
        .type_text("3");
    harness.run();
    harness.key_press(Key::Enter);
    harness.run();
    let wb = harness.state();
    assert_eq!(wb.cursor_line(), Some(3));
    assert_eq!(wb.selection(), 11..11);
    assert!(
        harness.query_by_label("Line number").is_none(),
        "the dialog closes"
    );
}

#[test]
fn ctrl_slash_comments_and_uncomments_the_selected_lines() {
    let mut harness = harness("G00 X0\nG01 X1 (cut)\nM30\n");
    harness.state_mut().select_line(2);
    harness.run();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Slash);
    harness.run();
    assert_eq!(harness.state().text(), "G00 X0\n(G01 X1) (cut)\nM30\n");
    harness.state_mut().finish_analysis();
    assert_eq!(harness.state().stats().motions, 1);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Slash);
    harness.run();
    assert_eq!(harness.state().text(), "G00 X0\nG01 X1 (cut)\nM30\n");
    // LinuxCNC comments with `;`.
    harness.state_mut().set_dialect(Dialect::LinuxCnc);
    harness.state_mut().select_line(1);
    harness.run();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Slash);
    harness.run();
    assert_eq!(harness.state().text(), "; G00 X0\nG01 X1 (cut)\nM30\n");
}

#[test]
fn renumbering_from_the_edit_menu_is_one_undo_step() {
    let text = "O1000\nN1 G90\nG00 X0\nN2 M30\n";
    let mut harness = harness(text);
    click_menu(&mut harness, "Edit", "Renumber blocks…");
    harness.get_by_label("Number every block").click();
    harness.run();
    harness.get_by_label("Renumber").click();
    harness.run();
    assert_eq!(
        harness.state().text(),
        "O1000\nN10 G90\nN20 G00 X0\nN30 M30\n"
    );
    harness.get_by_label_contains("Renumbered 3 blocks");
    harness.state_mut().undo();
    harness.run();
    assert_eq!(harness.state().text(), text);
}

#[test]
fn undo_and_redo_cross_typing_and_commands() {
    let mut harness = harness("");
    let editor = harness.get_by_role(Role::MultilineTextInput);
    editor.focus();
    editor.type_text("G0 X1\n");
    harness.run();
    harness.state_mut().select_line(1);
    harness.run();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Slash);
    harness.run();
    assert_eq!(harness.state().text(), "(G0 X1)\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    harness.run();
    assert_eq!(harness.state().text(), "G0 X1\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    harness.run();
    assert_eq!(harness.state().text(), "");
    harness.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    harness.run();
    assert_eq!(harness.state().text(), "G0 X1\n");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Y);
    harness.run();
    assert_eq!(harness.state().text(), "(G0 X1)\n");
    assert!(harness.state().document().is_unsaved());
}

#[test]
fn file_shortcuts_ask_the_host_and_shift_picks_save_as() {
    let mut harness = harness("G0 X1\n");
    harness.state_mut().take_requests();
    harness.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::S);
    harness.run();
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::SaveAs]);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::S);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::O);
    harness.run();
    let requests = harness.state_mut().take_requests();
    assert_eq!(requests, [HostRequest::Save, HostRequest::Open]);
    let tabs = harness.state().tab_documents().len();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::N);
    harness.run();
    assert_eq!(harness.state().tab_documents().len(), tabs + 1);
}

#[test]
fn typing_a_code_offers_completions_with_their_meaning() {
    let mut harness = harness("");
    let editor = harness.get_by_role(Role::MultilineTextInput);
    editor.focus();
    editor.type_text("G8");
    harness.run();
    let offered = harness.state().text().to_string();
    assert_eq!(offered, "G8");
    harness.get_by_label_contains("G81  ");
    harness.key_press(Key::ArrowDown);
    harness.run();
    harness.key_press(Key::ArrowUp);
    harness.run();
    harness.key_press(Key::Tab);
    harness.run();
    let wb = harness.state();
    assert_eq!(wb.text(), "G80");
    assert!(
        harness.query_by_label_contains("G81  ").is_none(),
        "the list closes"
    );
    // Undo takes the completion back to what was typed.
    harness.state_mut().undo();
    harness.run();
    assert_eq!(harness.state().text(), "G8");
}

#[test]
fn gutter_markers_explain_the_problem_on_hover() {
    let text = "G90\nG01 X10 Y$ F100\n";
    let mut harness = harness(text);
    let problems = harness.state().problems().to_vec();
    let tip = swarf_ui::editor::gutter_tooltip(&problems, 2).unwrap();
    assert!(tip.contains("error [E-SYNTAX-CHAR]"), "{tip}");
    assert!(swarf_ui::editor::gutter_tooltip(&problems, 1).is_none());
    // Hovering the marker of line 2 shows it.
    let rect = harness.get_by_role(Role::MultilineTextInput).rect();
    let row = 1.5
        * harness
            .ctx
            .fonts_mut(|f| f.row_height(&egui::FontId::monospace(12.0)));
    // The line numbers sit at the editor's left edge.
    harness.hover_at(egui::pos2(rect.left() + 8.0, rect.top() + row));
    harness.run();
    harness.get_by_label_contains("error [E-SYNTAX-CHAR]: unexpected character");
}

#[test]
fn unsaved_changes_are_confirmed_before_their_tab_closes() {
    let mut harness = harness("G0 X1\n");
    harness.state_mut().set_text("G0 X2\n");
    assert!(harness.state().document().is_unsaved());
    // New and Open leave the program where it is: a tab of their own.
    click_menu(&mut harness, "File", "New Ctrl+N");
    assert_eq!(harness.state().text(), "");
    assert_eq!(harness.state().document().name, "untitled.nc");
    harness.get_by_label("test.nc *").click();
    harness.run();
    assert_eq!(harness.state().text(), "G0 X2\n");
    click_menu(&mut harness, "File", "Close tab");
    harness.get_by_label("Unsaved changes");
    harness.get_by_label("Cancel").click();
    harness.run();
    assert_eq!(harness.state().text(), "G0 X2\n");
    let tabs = harness.state().tab_documents().len();
    // Save first: the host is asked to save, and the tab closes once it reports the save.
    click_menu(&mut harness, "File", "Close tab");
    harness.get_by_label("Save").click();
    harness.run();
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::Save]);
    assert_eq!(harness.state().tab_documents().len(), tabs);
    harness.state_mut().mark_saved("test.nc");
    harness.run();
    assert_eq!(harness.state().tab_documents().len(), tabs - 1);
    assert!(
        harness
            .state()
            .tab_documents()
            .iter()
            .all(|d| d.name != "test.nc")
    );
    // Discard drops the changes with the tab.
    harness.state_mut().set_text("G0 X3\n");
    let name = harness.state().document().name.clone();
    click_menu(&mut harness, "File", "Close tab");
    harness.get_by_label("Discard changes").click();
    harness.run();
    assert_eq!(harness.state().tab_documents().len(), tabs - 2);
    assert!(
        harness
            .state()
            .tab_documents()
            .iter()
            .all(|d| d.name != name)
    );
    // Open asks the host at once.
    click_menu(&mut harness, "File", "Open… Ctrl+O");
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::Open]);
}

#[test]
fn clicking_a_completion_inserts_it_and_leaving_the_editor_closes_the_list() {
    let mut harness = harness("");
    let editor = harness.get_by_role(Role::MultilineTextInput);
    editor.focus();
    editor.type_text("M0");
    harness.run();
    harness.get_by_label_contains("M03  ").click();
    harness.run();
    assert_eq!(harness.state().text(), "M03");
    assert!(harness.query_by_label_contains("M05  ").is_none());
    // Typing again opens it; moving the keyboard to the find field closes it.
    let editor = harness.get_by_role(Role::MultilineTextInput);
    editor.type_text(" G4");
    harness.run();
    harness.get_by_label_contains("G43  ");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
    harness.hover_at(egui::pos2(900.0, 400.0));
    harness.run();
    assert!(
        harness.query_by_label_contains("G43  ").is_none(),
        "the list closes"
    );
    assert_eq!(harness.state().text(), "M03 G4");
}

#[test]
fn quitting_with_unsaved_changes_asks_first() {
    let mut harness = harness("G0 X1\n");
    harness.state_mut().request_quit();
    harness.run();
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::Quit]);
    harness.state_mut().set_text("G0 X2\n");
    harness.state_mut().request_quit();
    harness.run();
    assert!(harness.state_mut().take_requests().is_empty());
    harness.get_by_label("Discard changes").click();
    harness.run();
    assert_eq!(harness.state_mut().take_requests(), [HostRequest::Quit]);
}

#[test]
fn ctrl_space_asks_for_the_list_after_escape_closed_it() {
    let mut harness = harness("");
    let editor = harness.get_by_role(Role::MultilineTextInput);
    editor.focus();
    editor.type_text("M");
    harness.run();
    harness.get_by_label_contains("M03  ");
    harness.key_press(Key::Escape);
    harness.run();
    assert!(harness.query_by_label_contains("M03  ").is_none());
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Space);
    harness.run();
    harness.get_by_label_contains("M03  ");
    assert_eq!(harness.state().text(), "M");
}

#[test]
fn a_program_opened_before_the_first_frame_starts_at_its_first_line() {
    let mut wb = Workbench::default();
    wb.open_document("a.nc", "G90\nG0 X1\nM30\n", swarf_syntax::Encoding::Utf8);
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    assert_eq!(harness.state().cursor_line(), Some(1));
    assert_eq!(harness.state().selection(), 0..0);
}
