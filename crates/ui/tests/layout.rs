//! The workbench's layout does not jump: the backplot keeps its place and size whatever the
//! caret's line shows in the state panel and whether the find bar is open; an empty problems
//! list takes one line. And a new program is framed once, whole, below the view's buttons.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;
use swarf_ui::backplot::Scene;

/// A short first line, then a block with a lot of modal state and a long line.
const MODAL: &str = "%\nO1\nG90 G17 G21 G40 G49 G80 G94 G54 G64 G69 G15 G50.1 G98 G97 T12 M06 \
S12000 M03 M08 F1234.5 (A LONG COMMENT THAT GOES ON AND ON ACROSS THE LINE)\n\
G43 H12 G00 X-1234.567 Y-2345.678 Z345.678\nG01 Z-2. F200\nX10.\nM30\n%\n";

/// A square pocket under cutter radius compensation: its programmed contour is drawn beside
/// the tool centre's path, outside it (the tool runs inside the square).
const POCKET: &str = "%\nO1000\nG90 G17 G40 G49 G80\nG54 G00 X25. Y25.\nG00 Z5.\nG01 Z-2. F200\n\
G42 X10. Y10. D1\nY40.\nX40.\nY10.\nX10.\nG40 X25. Y25.\nG00 Z5.\nM30\n%\n";

fn plain(wb: Workbench) -> Harness<'static, Workbench> {
    Harness::builder()
        .with_size(egui::vec2(1200.0, 700.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb)
}

fn drawn(wb: Workbench, render_state: &egui_wgpu::RenderState) -> Harness<'static, Workbench> {
    // A wide window: the view is framed by its height, where the buttons are.
    support::drawn_workbench(render_state, wb, egui::vec2(1800.0, 600.0))
}

fn view(harness: &Harness<'_, Workbench>) -> egui::Rect {
    harness
        .state()
        .widget_rect("backplot")
        .expect("backplot drawn")
}

#[test]
fn the_view_keeps_its_rect_whatever_the_caret_shows_and_the_find_bar() {
    let mut harness = plain(Workbench::new(MODAL.to_string()));
    harness.run();
    let first = view(&harness);
    assert!(first.width() > 300.0 && first.height() > 300.0, "{first:?}");
    // Every line in turn: one that does not run, short blocks and the long one.
    for line in [1, 3, 4, 2, 5, 3, 7, 1] {
        harness.state_mut().go_to_line(line);
        harness.run();
        assert_eq!(harness.state().cursor_line(), Some(line));
        assert_eq!(
            view(&harness),
            first,
            "the view moved with the caret on line {line}"
        );
    }
    harness.get_by_label("State at cursor");
    // The find bar, then find and replace, open and closed.
    harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
    harness.run();
    harness.get_by_label("Find");
    assert_eq!(view(&harness), first, "the find bar moved the view");
    harness.key_press_modifiers(Modifiers::COMMAND, Key::H);
    harness.run();
    assert_eq!(view(&harness), first, "the replace bar moved the view");
    harness.get_by_label("×").click();
    harness.run();
    assert_eq!(view(&harness), first, "closing the find bar moved the view");
}

#[test]
fn an_empty_problems_list_takes_one_line() {
    let mut clean = plain(Workbench::new(
        "(CLEAN)\nG90 G21\nG0 X0 Y0 Z5.\nG1 Z0 F600.\nX20.\nM30\n".to_string(),
    ));
    clean.run();
    assert!(clean.state().problems().is_empty());
    clean.get_by_label("No problems");
    let mut faulty = plain(Workbench::new("G0 X1 Y1\nG1 X$ F100\n".to_string()));
    faulty.run();
    faulty.get_by_label_contains("Problems (");
    let (tall, short) = (view(&clean), view(&faulty));
    assert!(
        tall.height() - short.height() > 90.0,
        "the empty list takes {} points more than one line",
        140.0 - (tall.height() - short.height())
    );
}

/// Runs frames, waits for the analysis of the current text, and runs the frames that show it.
fn settle(harness: &mut Harness<'_, Workbench>) {
    harness.run();
    harness.state_mut().finish_analysis();
    harness.run();
}

/// Whether every point drawn (path and marks but the travel box) lies in `free`.
fn drawn_inside(harness: &Harness<'_, Workbench>, free: egui::Rect) -> Result<(), String> {
    let wb = harness.state();
    let scene: &Scene = &wb.analysis().scene;
    let points = scene.points.iter().chain(scene.marks.iter());
    for p in points {
        let at = wb
            .backplot()
            .screen_pos(p.position())
            .ok_or("behind the eye")?;
        if !free.expand(0.5).contains(at) {
            return Err(format!("{:?} drawn at {at:?}, outside {free:?}", p));
        }
    }
    Ok(())
}

#[test]
fn a_new_program_is_framed_whole_below_the_buttons_once() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the fit test");
        return;
    };
    let mut wb = Workbench::new(String::new());
    wb.set_setup(swarf_interp::Setup::from_toml("[registers.1]\nradius = 3.0\n").unwrap());
    let mut harness = drawn(wb, &render_state);
    harness.run();
    harness.state_mut().set_text(POCKET);
    settle(&mut harness);
    let scene = harness.state().analysis().scene.clone();
    assert!(scene.segment_count() > 5);
    assert!(
        scene
            .marks
            .iter()
            .any(|p| p.kind() == Some(swarf_render::Kind::Programmed)),
        "no programmed contour"
    );
    let buttons = harness.get_by_label("Fit").rect();
    let view = view(&harness);
    let free = egui::Rect::from_min_max(egui::pos2(view.min.x, buttons.max.y), view.max);
    drawn_inside(&harness, free).unwrap();
    // Framed, not lost: the pocket spans much of the free part.
    let wb = harness.state();
    let (min, max) = scene.view_bounds().unwrap();
    let a = wb.backplot().screen_pos(min).unwrap();
    let b = wb.backplot().screen_pos(max).unwrap();
    assert!(
        (b - a).length() > 0.4 * free.height(),
        "{a:?} {b:?} in {free:?}"
    );

    // Each standard view frames the same, below the buttons.
    for label in ["Top", "Front", "Right", "Iso"] {
        harness.get_by_label(label).click();
        harness.run();
        drawn_inside(&harness, free)
            .map_err(|e| format!("{label}: {e}"))
            .unwrap();
    }

    // Edits do not fit again: the camera the user set stays.
    harness.state_mut().go_to_line(9);
    harness.run();
    let camera = *harness.state().backplot().camera();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    harness.run();
    let edited = POCKET.replace("X40.", "X60.");
    harness.state_mut().set_text(edited.clone());
    settle(&mut harness);
    let after_set = *harness.state().backplot().camera();
    assert_ne!(after_set, camera, "a new text set is framed");
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text("(NOTE)");
    settle(&mut harness);
    assert_ne!(
        harness.state().text(),
        edited,
        "typing did not reach the editor"
    );
    assert_eq!(
        *harness.state().backplot().camera(),
        after_set,
        "typing re-framed the view"
    );

    // An example chosen is framed whole, as is a program pasted into an empty tab.
    for example in ["fanuc-drill-plate.nc", "syntec-bolt-circle.nc"] {
        assert!(harness.state_mut().open_example(example));
        settle(&mut harness);
        drawn_inside(&harness, free)
            .map_err(|e| format!("{example}: {e}"))
            .unwrap();
    }
    harness.state_mut().new_tab();
    harness.run();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    harness.run();
    harness.event(egui::Event::Paste(POCKET.to_string()));
    settle(&mut harness);
    assert_eq!(
        harness.state().text(),
        POCKET,
        "the paste did not reach the editor"
    );
    drawn_inside(&harness, free)
        .map_err(|e| format!("pasted: {e}"))
        .unwrap();
}
