//! No action that is not an edit changes the program: random sequences of view actions (a click
//! in the backplot, then its shortcut keys, sent as a browser sends them, with their text),
//! navigation keys, find (Enter steps through the matches), go to line, problem clicks and the
//! view's buttons leave the text exactly as it was. Also the completion list's rules: Enter
//! after a code typed in full ends the line, and a list made for older text is never applied.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use egui_kittest::wgpu::WgpuTestRenderer;
use proptest::prelude::*;
use swarf_ui::Workbench;
use swarf_ui::backplot::Backplot;

/// A compensated pocket, a drilling cycle and a line with an error (so the problems list has a
/// row to click).
const PROGRAM: &str = "%\nO1000\nG90 G17 G40 G49 G80\nG54 G00 X0 Y0\nG00 Z5.\nG01 Z-2. F200\n\
G41 X10. Y10. D1\nY40.\nX40.\nY10.\nX10.\nG40 X0 Y0\nG00 Z5.\nG81 X20. Y20. Z-5. R2. F100\n\
X30. Y30.\nG80\nG01 X$ F100\nM30\n%\n";

fn harness(
    render_state: Option<&egui_wgpu::RenderState>,
    text: &str,
) -> Harness<'static, Workbench> {
    let mut wb = Workbench::default();
    wb.open_document("trust.nc", text, swarf_syntax::Encoding::Utf8);
    wb.finish_analysis();
    let mut builder = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .with_step_dt(1.0 / 60.0)
        .with_render_cursor(false);
    if let Some(rs) = render_state {
        builder = builder.renderer(WgpuTestRenderer::from_render_state(rs.clone()));
    }
    let harness = builder.build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    if let Some(rs) = render_state {
        Backplot::install(&harness.ctx, rs);
    }
    let mut harness = harness;
    harness.run_steps(3);
    harness
}

/// A key as a browser sends it: pressed, the text it types (for a printable key), released.
fn press(harness: &Harness<'_, Workbench>, key: Key, modifiers: Modifiers) {
    harness.event(Event::Key {
        key,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers,
    });
    if modifiers.is_none()
        && let Some(text) = typed(key)
    {
        harness.event(Event::Text(text.to_string()));
    }
    harness.event(Event::Key {
        key,
        physical_key: None,
        pressed: false,
        repeat: false,
        modifiers,
    });
}

/// The text a key types without modifiers, for the keys these tests press.
fn typed(key: Key) -> Option<&'static str> {
    Some(match key {
        Key::Num1 => "1",
        Key::Num2 => "2",
        Key::Num3 => "3",
        Key::Num4 => "4",
        Key::F => "f",
        Key::S => "s",
        Key::P => "p",
        Key::R => "r",
        Key::T => "t",
        Key::Plus => "+",
        Key::Minus => "-",
        _ => return None,
    })
}

/// Types `text` one character at a time, as key presses with their text.
fn type_chars(harness: &mut Harness<'_, Workbench>, text: &str) {
    for c in text.chars() {
        if let Some(key) = Key::from_name(&c.to_ascii_uppercase().to_string()) {
            harness.event(Event::Key {
                key,
                physical_key: None,
                pressed: true,
                repeat: false,
                modifiers: Modifiers::NONE,
            });
        }
        harness.event(Event::Text(c.to_string()));
        if let Some(key) = Key::from_name(&c.to_ascii_uppercase().to_string()) {
            harness.event(Event::Key {
                key,
                physical_key: None,
                pressed: false,
                repeat: false,
                modifiers: Modifiers::NONE,
            });
        }
        harness.step();
    }
}

fn click(harness: &mut Harness<'_, Workbench>, pos: Pos2) {
    harness.event(Event::PointerMoved(pos));
    for pressed in [true, false] {
        harness.event(Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    harness.step();
}

/// A point inside the drawn toolpath, `fx`/`fy` of the way across its bounds.
fn in_view(harness: &Harness<'_, Workbench>, fx: f32, fy: f32) -> Option<Pos2> {
    let scene = &harness.state().analysis().scene;
    let (min, max) = scene.bounds?;
    let p = min + (max - min) * glam::Vec3::new(fx, fy, 0.5);
    harness.state().backplot().screen_pos(p)
}

#[derive(Debug, Clone)]
enum Action {
    /// A click in the backplot, then view shortcut keys.
    View { fx: f32, fy: f32, keys: Vec<Key> },
    /// A navigation key, with Shift or Ctrl, to whatever has the keyboard.
    Navigate(Key, Modifiers),
    /// Ctrl+F, a query typed, Enter pressed some times, then Escape or not.
    Find {
        query: &'static str,
        enters: usize,
        escape: bool,
    },
    /// Ctrl+G, a line number typed, Enter.
    GoTo(u32),
    /// A click on the first row of the problems list.
    Problem,
    /// A click on one of the view's buttons.
    Button(&'static str),
    /// The wheel turned over the view.
    Wheel { fx: f32, fy: f32, delta: f32 },
}

fn action() -> impl Strategy<Value = Action> {
    let view_key = prop::sample::select(vec![
        Key::Num1,
        Key::Num2,
        Key::Num3,
        Key::Num4,
        Key::F,
        Key::S,
        Key::P,
        Key::R,
        Key::T,
        Key::Plus,
        Key::Minus,
        Key::ArrowLeft,
        Key::ArrowUp,
        Key::Escape,
    ]);
    let nav_key = prop::sample::select(vec![
        Key::ArrowLeft,
        Key::ArrowRight,
        Key::ArrowUp,
        Key::ArrowDown,
        Key::Home,
        Key::End,
        Key::PageUp,
        Key::PageDown,
    ]);
    let modifiers = prop::sample::select(vec![
        Modifiers::NONE,
        Modifiers::SHIFT,
        Modifiers::COMMAND,
        Modifiers::COMMAND | Modifiers::SHIFT,
    ]);
    prop_oneof![
        (
            0.1f32..0.9,
            0.1f32..0.9,
            prop::collection::vec(view_key, 1..5)
        )
            .prop_map(|(fx, fy, keys)| Action::View { fx, fy, keys }),
        (nav_key, modifiers).prop_map(|(k, m)| Action::Navigate(k, m)),
        (
            prop::sample::select(vec!["Y0", "X", "G0", "Z5", "nothing"]),
            0usize..4,
            any::<bool>()
        )
            .prop_map(|(query, enters, escape)| Action::Find {
                query,
                enters,
                escape
            }),
        (1u32..25).prop_map(Action::GoTo),
        Just(Action::Problem),
        prop::sample::select(vec![
            "Fit", "Iso", "Top", "Front", "Right", "Rapids", "Persp"
        ])
        .prop_map(Action::Button),
        (0.1f32..0.9, 0.1f32..0.9, -200.0f32..200.0).prop_map(|(fx, fy, delta)| Action::Wheel {
            fx,
            fy,
            delta
        }),
    ]
}

fn act(harness: &mut Harness<'_, Workbench>, action: &Action) {
    match action {
        Action::View { fx, fy, keys } => {
            let Some(pos) = in_view(harness, *fx, *fy) else {
                return;
            };
            click(harness, pos);
            for key in keys {
                press(harness, *key, Modifiers::NONE);
                harness.step();
            }
        }
        Action::Navigate(key, modifiers) => {
            press(harness, *key, *modifiers);
            harness.step();
        }
        Action::Find {
            query,
            enters,
            escape,
        } => {
            harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
            harness.step();
            // Ctrl+F fills the field with a one-line selection: clear it first.
            harness.key_press_modifiers(Modifiers::COMMAND, Key::A);
            harness.step();
            press(harness, Key::Backspace, Modifiers::NONE);
            harness.step();
            type_chars(harness, query);
            for _ in 0..*enters {
                press(harness, Key::Enter, Modifiers::NONE);
                harness.event(Event::Text("\n".into()));
                harness.step();
            }
            if *escape {
                press(harness, Key::Escape, Modifiers::NONE);
                harness.step();
            }
        }
        Action::GoTo(line) => {
            harness.key_press_modifiers(Modifiers::COMMAND, Key::G);
            harness.step();
            harness.step();
            type_chars(harness, &line.to_string());
            press(harness, Key::Enter, Modifiers::NONE);
            harness.step();
            harness.step();
        }
        Action::Problem => {
            if let Some(node) = harness.query_by_label_contains("E-WORD-VALUE") {
                let pos = node.rect().center();
                click(harness, pos);
            }
        }
        Action::Button(label) => {
            if let Some(node) = harness.query_by_label(label) {
                let pos = node.rect().center();
                click(harness, pos);
            }
        }
        Action::Wheel { fx, fy, delta } => {
            let Some(pos) = in_view(harness, *fx, *fy) else {
                return;
            };
            harness.event(Event::PointerMoved(pos));
            harness.event(Event::MouseWheel {
                unit: egui::MouseWheelUnit::Point,
                delta: egui::vec2(0.0, *delta),
                modifiers: Modifiers::NONE,
                phase: egui::TouchPhase::Move,
                source: egui::MouseWheelSource::Wheel,
            });
            harness.step();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 32,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn looking_and_navigating_never_change_the_program(
        actions in prop::collection::vec(action(), 1..8)
    ) {
        let render_state = render_state();
        let mut harness = harness(render_state.as_ref(), PROGRAM);
        for a in &actions {
            act(&mut harness, a);
            prop_assert_eq!(harness.state().text(), PROGRAM, "after {:?}", a);
        }
        harness.run_steps(3);
        prop_assert_eq!(harness.state().text(), PROGRAM);
    }
}

#[test]
fn enter_in_the_find_field_steps_through_the_matches_and_never_edits() {
    let mut harness = harness(None, PROGRAM);
    harness.key_press_modifiers(Modifiers::COMMAND, Key::F);
    harness.step();
    type_chars(&mut harness, "Y10.");
    let mut seen = Vec::new();
    for _ in 0..3 {
        press(&harness, Key::Enter, Modifiers::NONE);
        harness.step();
        harness.step();
        seen.push(harness.state().selection());
        assert_eq!(harness.state().text(), PROGRAM);
    }
    let first = PROGRAM.find("Y10.").unwrap();
    let second = first + 1 + PROGRAM[first + 1..].find("Y10.").unwrap();
    // ASCII text: characters are bytes.
    assert_eq!(seen[0], first..first + 4);
    assert_eq!(seen[1], second..second + 4);
    assert_eq!(seen[2], first..first + 4, "wraps to the first match");
}

#[test]
fn enter_after_a_complete_code_ends_the_line() {
    let mut harness = harness(None, "");
    // Each key in a frame of its own, and then the last digit and Enter in one frame.
    type_chars(&mut harness, "G5");
    assert!(harness.state().completions().is_some(), "G5 offers codes");
    harness.event(Event::Text("4".into()));
    press(&harness, Key::Enter, Modifiers::NONE);
    harness.step();
    type_chars(&mut harness, "G00 X0 Y0");
    press(&harness, Key::Enter, Modifiers::NONE);
    harness.step();
    type_chars(&mut harness, "M3");
    press(&harness, Key::Enter, Modifiers::NONE);
    harness.step();
    type_chars(&mut harness, "M30");
    harness.run_steps(2);
    assert_eq!(harness.state().text(), "G54\nG00 X0 Y0\nM3\nM30");
}

#[test]
fn a_list_made_for_older_text_is_never_applied() {
    let mut harness = harness(None, "");
    type_chars(&mut harness, "G8");
    assert!(harness.state().completions().is_some());
    // A digit and Tab in the same frame: the list is worked out again for `G80` first.
    harness.event(Event::Text("0".into()));
    press(&harness, Key::Tab, Modifiers::NONE);
    harness.step();
    let text = harness.state().text().to_string();
    assert!(
        text == "G80" || text == "G80\t",
        "Tab acts on the list for G80, not G8: {text:?}"
    );
    // An arrow key picks an item, and then Enter takes it.
    let mut harness = harness_with_typed("M0");
    press(&harness, Key::ArrowDown, Modifiers::NONE);
    harness.step();
    let chosen = harness.state().completions().unwrap()[1].code.clone();
    press(&harness, Key::Enter, Modifiers::NONE);
    harness.step();
    assert_eq!(harness.state().text(), chosen);
}

fn harness_with_typed(text: &str) -> Harness<'static, Workbench> {
    let mut harness = harness(None, "");
    type_chars(&mut harness, text);
    assert!(
        harness.state().completions().is_some(),
        "{text} offers codes"
    );
    harness
}
