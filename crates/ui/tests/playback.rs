//! Playback in the workbench: the bar's buttons step through the program's blocks and play
//! it, the backplot highlights the current block and the editor's cursor follows it.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::Workbench;

/// Motion blocks on lines 3 to 7.
const PROGRAM: &str = "(PLAYBACK)\nG90 G21\nG0 X0 Y0 Z5.\nG1 Z0 F600.\nX20.\nY20.\nG0 Z5.\nM30\n";

fn harness() -> Harness<'static, Workbench> {
    let wb = Workbench::new(PROGRAM.to_string());
    assert!(wb.problems().is_empty(), "{:?}", wb.problems());
    Harness::builder()
        .with_size(egui::vec2(1200.0, 700.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb)
}

/// The playback's current line, the editor's cursor line and the highlighted block.
fn lines(harness: &Harness<'_, Workbench>) -> (Option<u32>, Option<u32>, Option<u32>) {
    let wb = harness.state();
    let scene = &wb.analysis().scene;
    (
        wb.backplot().player().current_line(scene),
        wb.cursor_line(),
        wb.backplot().selected_line(),
    )
}

#[test]
fn stepping_blocks_moves_the_editor_cursor() {
    let mut harness = harness();
    harness.run();
    assert_eq!(harness.state().backplot().player().time(), None);
    // Before playback the backplot highlights the editor's line, whatever it is.
    let (current, cursor, selected) = lines(&harness);
    assert_eq!(current, None);
    assert_eq!(selected, cursor);

    harness.get_by_label("Block »").click();
    harness.run();
    assert_eq!(lines(&harness), (Some(3), Some(3), Some(3)));
    harness.get_by_label("block 1 of 5, line 3");
    harness.get_by_label("Block »").click();
    harness.run();
    harness.get_by_label("Block »").click();
    harness.run();
    assert_eq!(lines(&harness), (Some(5), Some(5), Some(5)));
    // Only the finished blocks count as executed: the rapid, the plunge and the X move.
    let wb = harness.state();
    assert_eq!(
        wb.backplot().player().executed(&wb.analysis().scene),
        Some(3)
    );

    harness.get_by_label("« Block").click();
    harness.run();
    assert_eq!(lines(&harness), (Some(4), Some(4), Some(4)));
    harness.get_by_label("block 2 of 5, line 4");
    harness.get_by_label("line 4");

    // Stop: playback is off and the whole path is drawn again.
    harness.get_by_label("Stop").click();
    harness.run();
    let wb = harness.state();
    assert_eq!(wb.backplot().player().time(), None);
    assert_eq!(wb.backplot().player().executed(&wb.analysis().scene), None);
}

#[test]
fn playing_advances_and_the_editor_follows() {
    let mut harness = harness();
    harness.run();
    harness.get_by_label("Speed").click();
    harness.run();
    harness.get_by_label("×2").click();
    harness.run();
    assert_eq!(harness.state().backplot().player().speed(), 2.0);

    harness.get_by_label("Play").click();
    harness.step();
    // The Play button reads Pause while playing (from the frame after the click).
    harness.step();
    assert!(harness.query_by_label("Pause").is_some());
    let mut last = 0.0;
    let mut seen = Vec::new();
    // Each frame is a quarter of a second in the test harness; no timing is asserted, only
    // that the position moves forward and the editor keeps up with the block.
    for _ in 0..40 {
        harness.step();
        let wb = harness.state();
        let player = wb.backplot().player();
        let t = player.time().expect("playing");
        assert!(t >= last, "time went back from {last} to {t}");
        last = t;
        let (current, cursor, selected) = lines(&harness);
        assert_eq!(cursor, current);
        assert_eq!(selected, current);
        if seen.last() != current.as_ref() {
            seen.extend(current);
        }
        if harness.query_by_label("Pause").is_none() {
            break;
        }
    }
    assert!(last > 0.0);
    // Short blocks may pass within one frame; the others are shown in program order.
    assert!(seen.windows(2).all(|w| w[0] < w[1]), "{seen:?}");
    assert!(seen.len() >= 3 && seen.last() == Some(&7), "{seen:?}");
    assert!(
        harness.query_by_label("Pause").is_none(),
        "stops at the end"
    );
    // Settled: the editor itself reports its cursor on the last block.
    harness.run();
    assert_eq!(lines(&harness), (Some(7), Some(7), Some(7)));
    harness.get_by_label("Play");
}

#[test]
fn the_current_block_is_highlighted_exactly() {
    let Ok(render_state) = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        egui_kittest::wgpu::create_render_state(
            egui_kittest::wgpu::default_wgpu_setup(),
            egui_wgpu::RendererOptions::PREDICTABLE,
        )
    })) else {
        eprintln!("SKIPPED: no wgpu adapter available for the playback highlight test");
        return;
    };
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 700.0))
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(
            render_state.clone(),
        ))
        .build_ui_state(
            |ui, wb: &mut Workbench| wb.ui(ui),
            Workbench::new(PROGRAM.to_string()),
        );
    swarf_ui::backplot::Backplot::install(&harness.ctx, &render_state);
    harness.run();
    for _ in 0..5 {
        harness.get_by_label("Block »").click();
        harness.run();
        let wb = harness.state();
        let scene = &wb.analysis().scene;
        let line = wb.backplot().player().current_line(scene).expect("a block");
        let lit = wb.backplot().highlighted_segments();
        assert!(!lit.is_empty(), "line {line} not highlighted");
        assert_eq!(lit, scene.segments_of_line(line), "line {line}");
        assert!(
            lit.iter()
                .flat_map(Clone::clone)
                .all(|i| scene.lines[i] == line),
            "line {line}: {lit:?}"
        );
    }
}
