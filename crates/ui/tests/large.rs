//! A program too large for egui's text editor is edited in full by the row editor: typing,
//! keys, the mouse, the clipboard, undo, and the workbench's commands, with markers for the
//! rows on screen; it still drives the backplot and the state panel.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;

/// Bytes of the large program the tests edit: over 2 MB, where laying out every row would not fit
/// in a frame.
const LARGE_TEXT_BYTES: usize = 2 << 20;

/// A program over [`LARGE_TEXT_BYTES`]: a setup line, a rapid, then straight feeds; and the
/// number of feeds.
fn big_program() -> (String, usize) {
    let mut text = String::from("G90 G21 G17\nG00 X0 Y0 Z5.\n");
    let mut n = 0;
    while text.len() <= LARGE_TEXT_BYTES {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", n % 100, n / 100));
        n += 1;
    }
    (text, n)
}

fn harness(text: String) -> Harness<'static, Workbench> {
    let mut wb = Workbench::default();
    wb.open_document("big.nc", text, swarf_syntax::Encoding::default());
    wb.finish_analysis();
    // Frames a 60th of a second apart, so two clicks can make a double click.
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .with_step_dt(1.0 / 60.0)
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.step();
    harness.step();
    harness
}

/// Runs a frame, waits for the analysis of the current text and shows it.
fn settle(harness: &mut Harness<'_, Workbench>) {
    harness.step();
    harness.state_mut().finish_analysis();
    harness.step();
}

fn line(wb: &Workbench, n: usize) -> &str {
    wb.text().lines().nth(n - 1).unwrap()
}

/// The screen position `x` points right of the editor's left edge on 1-based `line` (the view
/// scrolled to the top).
fn at(harness: &Harness<'_, Workbench>, line: usize, x: f32) -> Pos2 {
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    let top = editor.rect().min;
    let font = egui::TextStyle::Monospace.resolve(&harness.ctx.global_style());
    let row = harness.ctx.fonts_mut(|f| f.row_height(&font));
    egui::pos2(top.x + x, top.y + (line as f32 - 0.5) * row)
}

/// Where the text starts right of the editor's left edge: after the line numbers (a marker and
/// at least three digits) and two gaps of 6 points.
fn text_left(harness: &Harness<'_, Workbench>) -> f32 {
    let font = egui::TextStyle::Monospace.resolve(&harness.ctx.global_style());
    let char_width = harness.ctx.fonts_mut(|f| f.glyph_width(&font, '0'));
    let digits = (harness.state().text().lines().count() + 1)
        .to_string()
        .len()
        .max(3);
    (digits + 1) as f32 * char_width + 12.0
}

fn press(harness: &Harness<'_, Workbench>, pos: Pos2, pressed: bool) {
    harness.event(Event::PointerMoved(pos));
    harness.event(Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Modifiers::NONE,
    });
}

#[test]
fn typing_in_a_large_program_edits_it_and_marks_the_error() {
    let (text, n) = big_program();
    let lines = text.lines().count();
    let mut harness = harness(text.clone());
    assert!(
        harness.query_by_label_contains("read-only").is_none(),
        "no read-only notice"
    );
    harness.state_mut().go_to_line(1);
    harness.step();
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text("G01 X$ ");
    settle(&mut harness);
    let wb = harness.state();
    // The edit and its analysis (parse, markers, problems) read the rope: no flat copy made.
    assert!(!wb.text_is_flat());
    // The record kept for recovery is copied from the rope, once, without keeping a flat copy.
    let kept = wb.tab_text(wb.active_tab()).unwrap();
    assert!(kept.starts_with("G01 X$ G90 G21 G17\n"));
    assert_eq!(kept.len(), text.len() + 7);
    assert!(!wb.text_is_flat());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(line(wb, 1), "G01 X$ G90 G21 G17");
    assert_eq!(wb.text().len(), text.len() + 7);
    assert!(wb.document().is_unsaved());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.selection(), 7..7);
    assert_eq!(wb.cursor_line(), Some(1));
    // Undo takes the typing back (the workbench's history), redo brings it again.
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut harness);
    assert_eq!(harness.state().text(), text);
    assert!(harness.state().problems().is_empty());
    assert!(!harness.state().document().is_unsaved());
    // The whole program runs.
    assert_eq!(harness.state().stats().motions, n + 1);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Y);
    settle(&mut harness);
    assert_eq!(line(harness.state(), 1), "G01 X$ G90 G21 G17");
    assert_eq!(harness.state().text().lines().count(), lines);
}

#[test]
fn keys_move_the_caret_select_and_delete() {
    let (text, _) = big_program();
    let lines = text.lines().count();
    let mut harness = harness(text);
    harness.state_mut().go_to_line(2);
    harness.step();
    // End of line 2, then the start of line 3 by Right; Down to line 4; shift+End selects it.
    harness.key_press(Key::End);
    harness.key_press(Key::ArrowRight);
    harness.key_press(Key::ArrowDown);
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(4));
    harness.key_press_modifiers(Modifiers::SHIFT, Key::End);
    harness.step();
    assert_eq!(harness.state().selected_text(), "G01 X1. Y0. F500.");
    harness.key_press(Key::Backspace);
    settle(&mut harness);
    assert_eq!(line(harness.state(), 4), "");
    assert_eq!(line(harness.state(), 5), "G01 X2. Y0. F500.");
    // Delete joins the next line; Enter splits it again; shift+Left and Delete.
    harness.key_press(Key::Delete);
    harness.step();
    assert_eq!(line(harness.state(), 4), "G01 X2. Y0. F500.");
    harness.key_press(Key::Home);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::ArrowRight);
    harness.key_press_modifiers(Modifiers::SHIFT, Key::ArrowRight);
    harness.key_press_modifiers(Modifiers::SHIFT, Key::ArrowRight);
    harness.step();
    assert_eq!(harness.state().selected_text(), " X");
    harness.key_press(Key::Delete);
    harness.key_press(Key::Enter);
    harness.step();
    assert_eq!(line(harness.state(), 4), "G01");
    assert_eq!(line(harness.state(), 5), "2. Y0. F500.");
    // Page down moves by a screenful; Ctrl+End and Ctrl+Home reach the ends of the text.
    harness.key_press(Key::PageDown);
    harness.step();
    let paged = harness.state().cursor_line().unwrap();
    assert!(paged > 20, "{paged}");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::End);
    harness.step();
    assert_eq!(
        harness.state().cursor_line(),
        Some(lines as u32 + 1),
        "the empty line after the last newline"
    );
    harness.key_press(Key::ArrowUp);
    harness.key_press_modifiers(Modifiers::SHIFT, Key::ArrowUp);
    harness.step();
    assert!(harness.state().selected_text().starts_with("G01 X"));
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Home);
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(1));
    assert_eq!(harness.state().selection(), 0..0);
    // Ctrl+A selects everything.
    harness.key_press_modifiers(Modifiers::COMMAND, Key::A);
    harness.step();
    assert_eq!(
        harness.state().selection().end,
        harness.state().text().chars().count()
    );
}

#[test]
fn the_clipboard_cuts_copies_and_pastes() {
    let (text, _) = big_program();
    let mut harness = harness(text);
    harness.state_mut().select_line(3);
    harness.step();
    harness.event(Event::Copy);
    harness.step();
    let copied = harness
        .output()
        .platform_output
        .commands
        .iter()
        .any(|c| matches!(c, egui::OutputCommand::CopyText(t) if t == "G01 X0. Y0. F500."));
    assert!(copied, "{:?}", harness.output().platform_output.commands);
    harness.event(Event::Cut);
    harness.step();
    assert_eq!(line(harness.state(), 3), "");
    harness.key_press(Key::ArrowDown);
    harness.event(Event::Paste("N10 ".to_string()));
    settle(&mut harness);
    assert_eq!(line(harness.state(), 4), "N10 G01 X1. Y0. F500.");
    assert!(harness.state().problems().is_empty());
}

#[test]
fn the_mouse_places_the_caret_drags_a_selection_and_double_clicks_a_word() {
    let (text, _) = big_program();
    let mut harness = harness(text);
    // A click past the end of line 3 puts the caret at its end.
    let pos = at(&harness, 3, 400.0);
    press(&harness, pos, true);
    press(&harness, pos, false);
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(3));
    let end_of_3 = harness.state().selection();
    assert!(end_of_3.is_empty());
    assert_eq!(
        harness.state().text()[..end_of_3.start]
            .lines()
            .last()
            .unwrap(),
        "G01 X0. Y0. F500."
    );
    harness.run_steps(60);
    // A drag from there to line 5 selects the lines between.
    press(&harness, pos, true);
    harness.step();
    let to = at(&harness, 5, 400.0);
    harness.event(Event::PointerMoved(to));
    harness.step();
    press(&harness, to, false);
    harness.step();
    assert_eq!(
        harness.state().selected_text(),
        "\nG01 X1. Y0. F500.\nG01 X2. Y0. F500."
    );
    harness.run_steps(60);
    // A double click in the middle of `G90` on line 1 selects the word.
    let font = egui::TextStyle::Monospace.resolve(&harness.ctx.global_style());
    let char_width = harness.ctx.fonts_mut(|f| f.glyph_width(&font, '0'));
    let word = at(&harness, 1, text_left(&harness) + 1.5 * char_width);
    for pressed in [true, false, true, false] {
        press(&harness, word, pressed);
    }
    harness.step();
    assert_eq!(harness.state().selected_text(), "G90");
    assert_eq!(harness.state().selection(), 0..3);
}

#[test]
fn commands_work_on_a_large_program() {
    let (text, _) = big_program();
    let lines = text.lines().count();
    let mut harness = harness(text);
    // Go to a line far down: the caret goes there, and typing edits that line.
    harness.state_mut().go_to_line(90_000);
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(90_000));
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text("(far) ");
    harness.step();
    assert!(line(harness.state(), 90_000).starts_with("(far) G01 X"));
    // The selection becomes the find bar's query; find next goes to the match from far above.
    harness.key_press_modifiers(Modifiers::SHIFT, Key::Home);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
    harness.step();
    harness.state_mut().go_to_line(10);
    harness.step();
    assert!(harness.state_mut().find_next());
    harness.step();
    assert_eq!(harness.state().selected_text(), "(far) ");
    assert_eq!(harness.state().cursor_line(), Some(90_000));
    harness.state_mut().select_line(lines as u32);
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(lines as u32));
    // A problem's position is where "jump to problem" goes.
    harness.state_mut().go_to_line(1);
    harness.step();
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text("G01 X$\n");
    settle(&mut harness);
    let problem = harness
        .state()
        .problems()
        .iter()
        .find(|p| p.code == "E-SYNTAX-CHAR")
        .cloned()
        .unwrap();
    assert_eq!(problem.line, 1);
    harness.state_mut().go_to_line(50_000);
    harness.step();
    harness.get_by_label_contains("E-SYNTAX-CHAR").click();
    harness.step();
    assert_eq!(harness.state().cursor_line(), Some(1));
    assert_eq!(harness.state().selection(), problem.chars);
}

#[test]
fn the_view_follows_the_caret_along_a_long_line() {
    let (text, _) = big_program();
    let mut harness = harness(text);
    harness.state_mut().go_to_line(3);
    harness.step();
    let editor = |h: &Harness<'_, Workbench>| {
        h.get_by_role(egui::accesskit::Role::MultilineTextInput)
            .rect()
            .min
    };
    let home = editor(&harness);
    harness.event(Event::Paste(format!("({})", "x".repeat(400))));
    // The row is laid out, the view widened, then scrolled.
    harness.run_steps(4);
    let scrolled = editor(&harness);
    assert!(scrolled.x < home.x - 100.0, "{home:?} {scrolled:?}");
    assert_eq!(scrolled.y, home.y, "no scrolling down");
    harness.key_press(Key::Home);
    harness.run_steps(4);
    assert_eq!(editor(&harness), home);
}

#[test]
fn typing_a_code_in_a_large_program_offers_completions() {
    let (text, _) = big_program();
    let mut harness = harness(text.clone());
    harness.state_mut().go_to_line(1);
    harness.step();
    harness.key_press(Key::End);
    harness.step();
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text(" G8");
    // The list is measured in its first frame and shown in the next.
    harness.run_steps(2);
    let offered = swarf_ui::commands::completions(harness.state().dialect(), "G8", 12);
    assert!(offered.len() > 2, "{offered:?}");
    harness.get_by_label_contains(&format!("{}  {}", offered[0].code, offered[0].name));
    harness.get_by_label_contains(&format!("{}  {}", offered[1].code, offered[1].name));
    // Down chooses the second code; Enter takes it (no line break).
    harness.key_press(Key::ArrowDown);
    harness.step();
    harness.key_press(Key::Enter);
    settle(&mut harness);
    let wb = harness.state();
    assert_eq!(line(wb, 1), format!("G90 G21 G17 {}", offered[1].code));
    assert_eq!(wb.text().lines().count(), text.lines().count());
    let end = "G90 G21 G17 ".len() + offered[1].code.len();
    assert_eq!(wb.selection(), end..end, "the caret after the code");
    assert!(
        harness
            .query_by_label_contains(&format!("{}  ", offered[1].code))
            .is_none(),
        "the list closes"
    );
    // One undo takes the completion back to what was typed, another the typing.
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut harness);
    assert_eq!(line(harness.state(), 1), "G90 G21 G17 G8");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut harness);
    assert_eq!(harness.state().text(), text);
    // Ctrl+Space asks for the list again; Escape closes it and keeps the editor's focus.
    harness.key_press(Key::End);
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text(" M0");
    harness.step();
    harness.key_press(Key::Escape);
    harness.step();
    assert!(harness.query_by_label_contains("M03  ").is_none());
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Space);
    harness.run_steps(2);
    harness.get_by_label_contains("M03  ").click();
    settle(&mut harness);
    assert_eq!(line(harness.state(), 1), "G90 G21 G17 M03");
    harness.key_press(Key::Enter);
    harness.step();
    assert_eq!(line(harness.state(), 2), "", "the editor has the keyboard");
}

/// The screen rectangle the editor gives the input method for its caret, if it owns input.
fn ime_caret(harness: &Harness<'_, Workbench>) -> egui::Rect {
    harness
        .output()
        .platform_output
        .ime
        .expect("the focused editor places the input method")
        .cursor_rect
}

#[test]
#[allow(deprecated)]
fn an_input_method_composes_at_the_caret_and_commits_once() {
    let (text, _) = big_program();
    let mut harness = harness(text.clone());
    // The test's fonts have no CJK glyphs: they are drawn as boxes, as wide as a character.
    harness
        .ctx
        .set_missing_glyph_policy(egui::MissingGlyphPolicy::Tofu);
    harness.state_mut().go_to_line(1);
    harness.step();
    harness.key_press(Key::End);
    harness.step();
    let before = ime_caret(&harness);
    let editor = harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .rect();
    assert!(editor.contains(before.center()), "{before:?} in {editor:?}");
    let row = before.height();
    harness.event(Event::Ime(egui::ImeEvent::Enabled));
    harness.event(Event::Ime(egui::ImeEvent::Preedit {
        text: "中".to_string(),
        active_range_chars: None,
    }));
    harness.step();
    // Composing text is shown at the caret, which moves past it, but is not in the program.
    assert_eq!(harness.state().text(), text);
    let composing = ime_caret(&harness);
    assert!(
        composing.left() > before.left() + 4.0,
        "{before:?} {composing:?}"
    );
    assert!((composing.top() - before.top()).abs() < row / 2.0);
    // The input method's keys are its own while it composes.
    harness.key_press(Key::Enter);
    harness.key_press(Key::ArrowLeft);
    harness.key_press(Key::Backspace);
    harness.step();
    assert_eq!(harness.state().text(), text);
    let end = "G90 G21 G17".chars().count();
    assert_eq!(harness.state().selection(), end..end);
    harness.event(Event::Ime(egui::ImeEvent::Preedit {
        text: "中文".to_string(),
        active_range_chars: Some(2..2),
    }));
    harness.event(Event::Ime(egui::ImeEvent::Commit("中文".to_string())));
    harness.event(Event::Ime(egui::ImeEvent::Disabled));
    settle(&mut harness);
    let wb = harness.state();
    assert_eq!(line(wb, 1), "G90 G21 G17中文");
    assert_eq!(wb.text().matches("中文").count(), 1);
    assert_eq!(wb.text().chars().count(), text.chars().count() + 2);
    assert_eq!(wb.selection(), end + 2..end + 2);
    // The caret is after the committed text, where the composition ended.
    let after = ime_caret(&harness);
    assert!((after.left() - composing.left()).abs() > 1.0);
    assert!(after.left() > composing.left());
    // Typing goes on after it; the commit is one edit to undo.
    harness.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    settle(&mut harness);
    assert_eq!(harness.state().text(), text);
}
