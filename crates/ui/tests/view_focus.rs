//! A key goes to exactly one place: the backplot's keys act only while the view has the
//! keyboard focus (taken by a click in it, shown by an outline), and then the program editor
//! gets none; a click in the editor takes the keyboard back.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use egui::Key;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;

const PROGRAM: &str = "G90 G21\nG0 X0 Y0 Z5.\nG1 Z0 F600.\nX20.\nY20.\nG0 Z5.\nM30\n";

fn harness(render_state: &egui_wgpu::RenderState) -> Harness<'static, Workbench> {
    support::drawn_workbench(
        render_state,
        Workbench::new(PROGRAM.to_string()),
        egui::vec2(1200.0, 700.0),
    )
}

fn yaw(harness: &Harness<'_, Workbench>) -> f32 {
    harness.state().backplot().camera().yaw
}

fn view_focused(harness: &Harness<'_, Workbench>) -> bool {
    harness.state().backplot().has_focus(&harness.ctx)
}

/// A real click (press, then release) at `at`.
fn click_at(harness: &mut Harness<'_, Workbench>, at: egui::Pos2) {
    harness.hover_at(at);
    harness.run();
    harness.drag_at(at);
    harness.run();
    harness.drop_at(at);
    harness.run();
}

/// The share of the pixels just inside the view's right edge (away from its corners) drawn in
/// `color`.
fn outline_share(harness: &mut Harness<'_, Workbench>, color: egui::Color32) -> f32 {
    let view = harness.state().widget_rect("backplot").unwrap();
    let image = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    let x = ((view.max.x - 1.0) * ppp) as u32;
    let rows: Vec<u32> =
        (((view.min.y + 60.0) * ppp) as u32..((view.max.y - 20.0) * ppp) as u32).collect();
    let lit = rows
        .iter()
        .filter(|&&y| {
            let p = image.get_pixel(x, y).0;
            p.iter()
                .zip(color.to_array())
                .take(3)
                .all(|(a, b)| a.abs_diff(b) <= 16)
        })
        .count();
    lit as f32 / rows.len() as f32
}

#[test]
fn the_view_takes_the_keyboard_when_clicked_and_the_editor_gets_none() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the view focus test");
        return;
    };
    let mut harness = harness(&render_state);
    harness.run();
    let focus_color = harness.ctx.global_style().visuals.selection.stroke.color;

    // The editor has the keyboard: arrows move its caret, the view does not orbit, even with
    // the pointer over the view.
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    harness.run();
    let view = harness.state().widget_rect("backplot").unwrap();
    let empty = egui::pos2(view.max.x - 30.0, view.max.y - 30.0);
    harness.hover_at(empty);
    harness.run();
    let before = yaw(&harness);
    harness.key_press(Key::ArrowDown);
    harness.run();
    assert_eq!(
        yaw(&harness),
        before,
        "an arrow key for the editor orbited the view"
    );
    assert!(!view_focused(&harness));
    assert!(
        outline_share(&mut harness, focus_color) < 0.2,
        "focus outline drawn without the focus"
    );

    // A click in the view takes the keyboard, shown by an outline.
    click_at(&mut harness, empty);
    assert!(
        view_focused(&harness),
        "a click in the view did not take the focus"
    );
    assert!(
        !harness
            .get_by_role(egui::accesskit::Role::MultilineTextInput)
            .is_focused(),
        "the editor kept the focus"
    );
    let share = outline_share(&mut harness, focus_color);
    assert!(share > 0.8, "no focus outline: {share}");

    // Now the keys are the view's alone: the text and the caret do not move.
    let text = harness.state().text().to_string();
    let selection = harness.state().selection();
    let before = yaw(&harness);
    harness.key_press(Key::ArrowLeft);
    harness.run();
    assert_ne!(
        yaw(&harness),
        before,
        "arrow key did not orbit the focused view"
    );
    assert!(view_focused(&harness), "an arrow key moved the focus");
    for key in [
        Key::ArrowDown,
        Key::ArrowRight,
        Key::Backspace,
        Key::Delete,
        Key::Enter,
    ] {
        harness.key_press(key);
        harness.run();
    }
    harness.event(egui::Event::Text("G".to_string()));
    harness.run();
    assert_eq!(harness.state().text(), text, "a key reached the editor");
    assert_eq!(harness.state().selection(), selection, "the caret moved");
    harness.key_press(Key::Num2);
    harness.run();
    let (top_yaw, top_pitch) = swarf_render::StandardView::Top.angles();
    let camera = *harness.state().backplot().camera();
    assert!((camera.yaw - top_yaw).abs() < 1e-6 && (camera.pitch - top_pitch).abs() < 1e-6);

    // A click on a segment selects its block and shows it in the editor, the keyboard
    // staying with the view; Escape clears the selection and leaves the keyboard there too.
    let wb = harness.state();
    let scene = &wb.analysis().scene;
    let segment = scene.segments_of_line(4)[0].start;
    let (a, b) = (
        scene.points[segment].position(),
        scene.points[segment + 1].position(),
    );
    let on_segment = wb.backplot().screen_pos(a.lerp(b, 0.5)).unwrap();
    click_at(&mut harness, on_segment);
    assert_eq!(harness.state().backplot().selected_line(), Some(4));
    assert_eq!(harness.state().cursor_line(), Some(4));
    assert!(
        view_focused(&harness),
        "picking a block gave the editor the keyboard"
    );
    harness.key_press(Key::Escape);
    harness.run();
    assert_eq!(harness.state().backplot().selected_line(), None);
    assert!(view_focused(&harness), "Escape took the focus away");

    // A button of the view keeps the keyboard with it.
    harness.get_by_label("Iso").click();
    harness.run();
    assert!(view_focused(&harness), "a view button took the focus");

    // A click in the editor takes the keyboard back: arrows no longer orbit.
    let editor = harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .rect();
    click_at(&mut harness, editor.center());
    assert!(!view_focused(&harness));
    let before = yaw(&harness);
    harness.key_press(Key::ArrowLeft);
    harness.run();
    assert_eq!(
        yaw(&harness),
        before,
        "the view orbited with the editor focused"
    );
    assert!(
        outline_share(&mut harness, focus_color) < 0.2,
        "focus outline left behind"
    );

    // Tab moves the focus on from the view.
    click_at(&mut harness, empty);
    assert!(view_focused(&harness));
    harness.key_press(Key::Tab);
    harness.run();
    assert!(!view_focused(&harness), "Tab did not move the focus on");
}
