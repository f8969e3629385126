//! `Workbench::widget_rect`: where the named widgets were drawn in the last frame (the page's
//! `window.swarf.widget` finds what to click through it), matched against the accessibility
//! tree's bounds of the same widgets.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;

fn harness() -> Harness<'static, Workbench> {
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), Workbench::default());
    harness.run();
    harness
}

fn rect(harness: &Harness<'_, Workbench>, name: &str) -> egui::Rect {
    harness
        .state()
        .widget_rect(name)
        .unwrap_or_else(|| panic!("`{name}` should have been drawn"))
}

fn near(a: egui::Rect, b: egui::Rect) -> bool {
    (a.min - b.min).length() < 0.5 && (a.max - b.max).length() < 0.5
}

#[test]
fn named_widgets_are_where_they_were_drawn() {
    let mut harness = harness();
    let fit = rect(&harness, "fit_view");
    assert!(
        near(fit, harness.get_by_label("Fit view").rect()),
        "{fit:?}"
    );
    let editor = rect(&harness, "editor");
    let view = rect(&harness, "backplot");
    assert!(
        editor.width() > 100.0 && editor.height() > 100.0,
        "{editor:?}"
    );
    assert!(view.width() > 100.0 && view.height() > 100.0, "{view:?}");
    assert!(!editor.intersects(view), "{editor:?} and {view:?} overlap");
    assert!(
        view.left() >= editor.right(),
        "the view is right of the editor"
    );
    // The example program has no problems: no first row.
    assert_eq!(harness.state().widget_rect("problem_first"), None);
    assert!(harness.state().widget_rect("tab 1").is_some());
    assert_eq!(harness.state().widget_rect("tab 2"), None);
    assert!(near(
        rect(&harness, "new_tab"),
        harness.get_by_label("New tab").rect()
    ));

    // The find bar's widgets exist while it is open, inside the editor's panel.
    assert_eq!(harness.state().widget_rect("find_field"), None);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::H);
    harness.run();
    let editor = rect(&harness, "editor");
    for name in [
        "find_field",
        "find_next",
        "find_previous",
        "replace_field",
        "replace",
        "replace_all",
    ] {
        let at = rect(&harness, name);
        assert!(
            at.right() <= view.left() + 0.5,
            "`{name}` {at:?} is not left of the view"
        );
        assert!(
            at.bottom() <= editor.top() + 0.5,
            "`{name}` {at:?} is not over the editor"
        );
    }
    // (The part in sight: the bar may be wider than the panel.)
    let next = rect(&harness, "find_next");
    assert!(
        harness.get_by_label("Next").rect().contains_rect(next),
        "{next:?}"
    );

    // A problem gives the list its first row, under the editor.
    harness.state_mut().set_text("G90\nG01 X10 Y$ F100\n");
    harness.run();
    harness.state_mut().finish_analysis();
    harness.run();
    let row = rect(&harness, "problem_first");
    let editor = rect(&harness, "editor");
    assert!(
        row.top() >= editor.bottom() - 0.5,
        "{row:?} is not under the editor"
    );
}
