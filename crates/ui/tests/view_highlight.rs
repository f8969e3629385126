//! The highlight of a block (the editor's line, a clicked segment's, playback's current block)
//! draws exactly that block's segments: none of another line's, none of the grid's or the
//! reference marks' (which are numbered apart), and every run of a line that ran more than once.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use std::ops::Range;

use egui_kittest::Harness;
use egui_kittest::wgpu::WgpuTestRenderer;
use swarf_render::HIGHLIGHT_COLOR;
use swarf_syntax::Dialect;
use swarf_ui::analysis::Analysis;
use swarf_ui::backplot::{Backplot, Scene};

/// A square pocket cut under cutter radius compensation (D1).
const POCKET: &str = "%\nO1000\nG90 G17 G40 G49 G80\nG54 G00 X0 Y0\nG00 Z5.\nG01 Z-2. F200\n\
G41 X10. Y10. D1\nY40.\nX40.\nY10.\nX10.\nG40 X0 Y0\nG00 Z5.\nM30\n%\n";

/// A Macro B loop: the two moves inside it run twice, one after the other.
const LOOP: &str = "G90 G00 X0 Y0 Z5.\nG01 Z0 F300\n#1=0\nWHILE[#1LT2]DO1\nG91 G01 X20. F300\n\
Y10.\n#1=#1+1\nEND1\nG90 G00 Z5.\nM30\n";

fn setup() -> swarf_interp::Setup {
    swarf_interp::Setup::from_toml("[registers.1]\nradius = 3.0\n").unwrap()
}

fn scene_of(text: &str) -> Scene {
    let text = swarf_analysis::ProgramText::from(text.to_string());
    let job = swarf_analysis::Job {
        generation: 1,
        text: text.clone(),
        dialect: Dialect::Fanuc,
        setup: setup(),
        others: None,
        lod: None,
    };
    let analysis = Analysis::of(swarf_analysis::analyse(job).0, &text);
    assert!(
        analysis
            .problems
            .iter()
            .all(|p| p.severity != swarf_syntax::Severity::Error),
        "{:?}",
        analysis.problems
    );
    analysis.scene
}

/// The segments whose line is `line`, one by one.
fn segments_with_line(scene: &Scene, line: u32) -> Vec<usize> {
    (0..scene.segment_count())
        .filter(|&i| scene.lines[i] == line)
        .collect()
}

fn flatten(runs: &[Range<usize>]) -> Vec<usize> {
    runs.iter().flat_map(Clone::clone).collect()
}

#[test]
fn every_line_highlights_exactly_its_own_segments() {
    for text in [POCKET, LOOP] {
        let scene = scene_of(text);
        assert!(scene.segment_count() > 5);
        let lines = text.lines().count() as u32;
        for line in 1..=lines + 1 {
            let runs = scene.segments_of_line(line);
            assert_eq!(
                flatten(&runs),
                segments_with_line(&scene, line),
                "line {line}: {runs:?}"
            );
            // Runs are apart (else they would be one) and in order.
            assert!(runs.windows(2).all(|w| w[0].end < w[1].start), "{runs:?}");
        }
    }
    // The loop's moves ran twice: two runs each, the other move between them not included.
    let scene = scene_of(LOOP);
    assert_eq!(scene.segments_of_line(5).len(), 2);
    assert_eq!(scene.segments_of_line(6).len(), 2);
}

type State = (Backplot, Scene);

fn harness(render_state: &egui_wgpu::RenderState, scene: Scene) -> Harness<'static, State> {
    let harness = Harness::builder()
        .with_size(egui::vec2(480.0, 360.0))
        .with_render_cursor(false)
        .renderer(WgpuTestRenderer::from_render_state(render_state.clone()))
        .build_ui_state(
            |ui, s: &mut State| drop(s.0.show(ui, &s.1)),
            (Backplot::default(), scene),
        );
    Backplot::install(&harness.ctx, render_state);
    harness
}

/// Distance from `p` to the segment `a`–`b`.
fn distance(p: egui::Pos2, a: egui::Pos2, b: egui::Pos2) -> f32 {
    let ab = b - a;
    let t = if ab.length_sq() > 0.0 {
        ((p - a).dot(ab) / ab.length_sq()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}

/// Pixels of the highlight colour in the frame, as points (the harness draws at one pixel per
/// point).
fn highlight_pixels(harness: &mut Harness<'_, State>) -> Vec<egui::Pos2> {
    let image = harness.render().expect("render");
    let ppp = harness.ctx.pixels_per_point();
    image
        .enumerate_pixels()
        .filter(|(_, _, p)| {
            p.0.iter()
                .zip(HIGHLIGHT_COLOR)
                .take(3)
                .all(|(a, b)| a.abs_diff(b) <= 12)
        })
        .map(|(x, y, _)| egui::pos2(x as f32 / ppp, y as f32 / ppp))
        .collect()
}

#[test]
fn the_highlight_draws_no_line_off_the_selected_block() {
    for text in [POCKET, LOOP] {
        let Some(render_state) = render_state() else {
            eprintln!("SKIPPED: no wgpu adapter available for the highlight pixel test");
            return;
        };
        let scene = scene_of(text);
        let mut harness = harness(&render_state, scene.clone());
        harness.run();
        let lines = text.lines().count() as u32;
        for line in 1..=lines {
            harness.state_mut().0.set_selected_line(Some(line));
            harness.run();
            let lit = highlight_pixels(&mut harness);
            let segments: Vec<(egui::Pos2, egui::Pos2)> = segments_with_line(&scene, line)
                .into_iter()
                .map(|i| {
                    let plot = &harness.state().0;
                    (
                        plot.screen_pos(scene.points[i].position()).unwrap(),
                        plot.screen_pos(scene.points[i + 1].position()).unwrap(),
                    )
                })
                .collect();
            assert_eq!(
                harness.state().0.highlighted_segments(),
                scene.segments_of_line(line)
            );
            // Every lit pixel lies on one of the line's segments (within the highlighted
            // line's half width and its anti-aliased edge).
            let stray: Vec<egui::Pos2> = lit
                .iter()
                .copied()
                .filter(|p| segments.iter().all(|(a, b)| distance(*p, *a, *b) > 4.0))
                .collect();
            assert!(
                stray.is_empty(),
                "line {line}: {} highlighted pixels off its segments, e.g. {:?}",
                stray.len(),
                &stray[..stray.len().min(5)]
            );
            // And a line that moved some way is lit (a rapid in dashes).
            let long = segments.iter().any(|(a, b)| (*b - *a).length() > 10.0);
            if long {
                assert!(lit.len() >= 5, "line {line}: only {} pixels lit", lit.len());
            }
        }
    }
}

#[test]
fn scene_points_are_those_the_highlight_numbers() {
    // The scene's segment `i` runs from point `i` to point `i + 1`: the compensated pocket's
    // retract (line 13) climbs straight up from where the cancel move (line 12) ends.
    let scene = scene_of(POCKET);
    let retract = segments_with_line(&scene, 13);
    assert_eq!(retract.len(), 1);
    let i = retract[0];
    let (from, to) = (scene.points[i].position(), scene.points[i + 1].position());
    assert!((to - from).truncate().length() < 1e-4, "{from} → {to}");
    assert!(to.z - from.z > 6.9, "{from} → {to}");
    let cancel = segments_with_line(&scene, 12);
    assert_eq!(cancel.last().map(|c| c + 1), Some(i));
}
