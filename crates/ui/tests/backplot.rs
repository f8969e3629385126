//! The backplot widget really paints through the egui-wgpu callback (on any wgpu adapter,
//! e.g. Mesa lavapipe): colours by kind, depth against other segments, picking, highlight and
//! playback dimming; and it degrades to a label when the GPU resources were never installed.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use std::sync::Arc;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use egui_kittest::wgpu::WgpuTestRenderer;
use glam::{DVec3, Vec3};
use swarf_render::{ARC_COLOR, FEED_COLOR, HIGHLIGHT_COLOR, Kind, PathPoint, RAPID_COLOR};
use swarf_ui::backplot::{Backplot, Scene, SourceText};

/// A 100×60 rectangle at z = 0 (feed, feed, rapid, arc on lines 2–5), then a feed at z = +5
/// (line 7) crossed by an arc at z = −5 drawn after it (line 8).
fn scene() -> Scene {
    let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let points = vec![
        PathPoint::pen_up(p(0.0, 0.0, 0.0)),
        PathPoint::new(p(100.0, 0.0, 0.0), Kind::Feed),
        PathPoint::new(p(100.0, 60.0, 0.0), Kind::Feed),
        PathPoint::new(p(0.0, 60.0, 0.0), Kind::Rapid),
        PathPoint::new(p(0.0, 0.0, 0.0), Kind::Arc),
        PathPoint::pen_up(p(50.0, -10.0, 5.0)),
        PathPoint::new(p(50.0, 70.0, 5.0), Kind::Feed),
        PathPoint::pen_up(p(-10.0, 30.0, -5.0)),
        PathPoint::new(p(110.0, 30.0, -5.0), Kind::Arc),
    ];
    Scene {
        generation: 1,
        points: Arc::new(points),
        lines: Arc::new(vec![2, 3, 4, 5, 6, 7, 8, 8]),
        feeds: Arc::new(vec![300.0, 300.0, 0.0, 250.0, 0.0, 500.0, 0.0, 100.0]),
        bounds: Some((p(-10.0, -10.0, -5.0), p(110.0, 70.0, 5.0))),
        zero: Vec3::ZERO,
        origin: DVec3::new(1000.0, 0.0, 0.0),
        source: Some(Arc::new(SourceText::new(
            "%\nG1 X100 F300\nY60\nG0 X0\nG3 Y0 R30\n\nG1 Z5 Y70 F500\nG3 X110\n".to_string(),
        ))),
        ..Scene::default()
    }
}

fn close(p: [u8; 4], want: [u8; 4], tolerance: u8) -> bool {
    p.iter()
        .zip(&want)
        .take(3)
        .all(|(a, b)| a.abs_diff(*b) <= tolerance)
}

/// Pixels within `tolerance` of `want` in tightly packed RGBA8 data.
fn count(rgba: &[u8], want: [u8; 4], tolerance: u8) -> usize {
    rgba.chunks_exact(4)
        .filter(|p| close([p[0], p[1], p[2], p[3]], want, tolerance))
        .count()
}

type State = (Backplot, Scene);

fn app(ui: &mut egui::Ui, state: &mut State) {
    state.0.show(ui, &state.1);
}

fn harness(render_state: &egui_wgpu::RenderState) -> Harness<'static, State> {
    let harness = Harness::builder()
        .with_size(egui::vec2(320.0, 240.0))
        .with_render_cursor(false)
        .renderer(WgpuTestRenderer::from_render_state(render_state.clone()))
        .build_ui_state(app, (Backplot::default(), scene()));
    Backplot::install(&harness.ctx, render_state);
    harness
}

/// The screen pixel where scene point `p` was drawn at the last frame.
fn pixel_of(harness: &Harness<'_, State>, p: Vec3) -> (u32, u32) {
    let pos = harness.state().0.screen_pos(p).expect("on screen");
    let ppp = harness.ctx.pixels_per_point();
    ((pos.x * ppp) as u32, (pos.y * ppp) as u32)
}

/// A rendered frame as tightly packed RGBA8.
struct Shot {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

impl Shot {
    fn as_raw(&self) -> &[u8] {
        &self.rgba
    }
}

fn shot(harness: &mut Harness<'_, State>) -> Shot {
    let image = harness.render().expect("render");
    Shot {
        width: image.width(),
        height: image.height(),
        rgba: image.into_raw(),
    }
}

fn at(image: &Shot, (x, y): (u32, u32)) -> [u8; 4] {
    let i = ((y * image.width + x) * 4) as usize;
    [
        image.rgba[i],
        image.rgba[i + 1],
        image.rgba[i + 2],
        image.rgba[i + 3],
    ]
}

#[test]
fn backplot_paints_lines_or_says_unavailable() {
    // 1. Without `install`, the widget shows a notice and never panics.
    let mut plain = Harness::builder()
        .with_size(egui::vec2(320.0, 240.0))
        .build_ui_state(app, (Backplot::default(), scene()));
    plain.run();
    plain.get_by_label("3D view unavailable");

    // 2. With a wgpu adapter, the paint callback draws the scene.
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the backplot render test");
        return;
    };
    eprintln!("adapter: {:?}", render_state.adapter.get_info());
    let mut harness = harness(&render_state);
    harness.run();
    let image = shot(&mut harness);
    let feed = count(image.as_raw(), FEED_COLOR, 10);
    let rapid = count(image.as_raw(), RAPID_COLOR, 10);
    let arc = count(image.as_raw(), ARC_COLOR, 10);
    assert!(
        feed > 100,
        "only {feed} feed pixels: the paint callback did not draw"
    );
    assert!(rapid > 20, "only {rapid} rapid pixels");
    assert!(arc > 50, "only {arc} arc pixels");
    let background = at(&image, (image.width / 2, image.height - 3));
    assert!(!close(background, FEED_COLOR, 40));

    // The overlay buttons exist and work; the scene stays framed in the top view, with the
    // rectangle's edges in their kinds' colours.
    harness.get_by_label("Top").click();
    harness.run();
    let image = shot(&mut harness);
    let bottom = at(&image, pixel_of(&harness, Vec3::new(25.0, 0.0, 0.0)));
    assert!(close(bottom, FEED_COLOR, 10), "feed edge is {bottom:?}");
    let left = at(&image, pixel_of(&harness, Vec3::new(0.0, 15.0, 0.0)));
    assert!(close(left, ARC_COLOR, 10), "arc edge is {left:?}");
    // The thin rapid straddles pixel rows, so look for its amber hue around its row.
    let amber = |p: [u8; 4]| p[0] > 90 && p[0] > p[1] && p[1] > p[2] + 30;
    let rapids = (10..90)
        .filter(|&x| {
            let (px, py) = pixel_of(&harness, Vec3::new(x as f32, 60.0, 0.0));
            (py - 1..=py + 1).any(|y| amber(at(&image, (px, y))))
        })
        .count();
    assert!(
        rapids > 20 && rapids < 70,
        "rapid edge not dashed: {rapids} of 80 lit"
    );

    // Depth: the feed at z = +5 stays in front of the arc at z = −5 drawn after it. Take
    // the feed's brightest column away from the crossing and walk it across the arc: it
    // stays blue (an arc drawn over it would turn the crossing rows green).
    let (fx, fy) = pixel_of(&harness, Vec3::new(50.0, 15.0, 0.0));
    let column = (fx - 1..=fx + 1)
        .max_by_key(|&x| at(&image, (x, fy))[2])
        .unwrap();
    let reference = at(&image, (column, fy));
    assert!(
        reference[2] > reference[1] + 30,
        "feed column is {reference:?}"
    );
    let (_, cy) = pixel_of(&harness, Vec3::new(50.0, 30.0, 0.0));
    for y in cy - 2..=cy + 2 {
        let p = at(&image, (column, y));
        assert!(
            close(p, reference, 12),
            "feed hidden by the arc behind it at row {y}: {p:?}, elsewhere {reference:?}"
        );
    }

    // A new generation with nothing in it clears the plot (upload on generation change).
    harness.state_mut().1 = Scene {
        generation: 2,
        ..Scene::default()
    };
    harness.run();
    let image = shot(&mut harness);
    assert_eq!(
        count(image.as_raw(), FEED_COLOR, 10),
        0,
        "stale geometry drawn"
    );

    // Orbit, pan and zoom input never break the view.
    harness.state_mut().1 = scene();
    harness.state_mut().1.generation = 3;
    harness.run();
    let center = egui::pos2(160.0, 140.0);
    harness.drag_at(center);
    harness.hover_at(center + egui::vec2(30.0, 10.0));
    harness.drop_at(center + egui::vec2(30.0, 10.0));
    harness.run();
    let image = shot(&mut harness);
    assert!(
        count(image.as_raw(), FEED_COLOR, 10) > 50,
        "scene lost after an orbit drag"
    );
}

#[test]
fn click_picks_a_block_hover_describes_it_and_playback_dims() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the backplot picking test");
        return;
    };
    let mut harness = harness(&render_state);
    harness.run();
    harness.get_by_label("Top").click();
    harness.run();

    // Hover over the right edge (line 3, a feed at X100).
    let right = harness
        .state()
        .0
        .screen_pos(Vec3::new(100.0, 20.0, 0.0))
        .unwrap();
    harness.hover_at(right + egui::vec2(2.0, 0.0));
    harness.run();
    let hover = harness.state().0.hovered().cloned().expect("hover info");
    assert_eq!(hover.line, 3);
    assert_eq!(hover.segment, 1);
    assert_eq!(hover.kind, Some(Kind::Feed));
    assert_eq!(hover.feed, 300.0);
    // Machine coordinates: the scene origin is at X1000.
    assert!((hover.position.x - 1100.0).abs() < 0.01, "{hover:?}");
    assert!((hover.position.y - 20.0).abs() < 1.5, "{hover:?}");

    // Click: the line is reported once and its segments are highlighted.
    harness.drag_at(right);
    harness.run();
    harness.drop_at(right);
    harness.run();
    assert_eq!(harness.state_mut().0.take_picked_line(), Some(3));
    assert_eq!(harness.state_mut().0.take_picked_line(), None);
    assert_eq!(harness.state().0.selected_line(), Some(3));
    harness.get_by_label("Zoom sel");
    let image = shot(&mut harness);
    let edge = at(&image, pixel_of(&harness, Vec3::new(100.0, 20.0, 0.0)));
    assert!(
        close(edge, HIGHLIGHT_COLOR, 10),
        "selected edge is {edge:?}"
    );
    let other = at(&image, pixel_of(&harness, Vec3::new(25.0, 0.0, 0.0)));
    assert!(close(other, FEED_COLOR, 10), "unselected edge is {other:?}");

    // Clicking empty space clears the selection and reports nothing.
    let empty = harness
        .state()
        .0
        .screen_pos(Vec3::new(25.0, 45.0, 0.0))
        .unwrap();
    harness.hover_at(empty);
    harness.run();
    assert!(harness.state().0.hovered().is_none());
    harness.drag_at(empty);
    harness.run();
    harness.drop_at(empty);
    harness.run();
    assert_eq!(harness.state_mut().0.take_picked_line(), None);
    assert_eq!(harness.state().0.selected_line(), None);

    // Playback after the first segment (a second per segment): the rest is drawn dimmed.
    let scene = harness.state().1.clone();
    harness.state_mut().0.player_mut().seek(&scene, 1.0);
    harness.run();
    let image = shot(&mut harness);
    let executed = at(&image, pixel_of(&harness, Vec3::new(25.0, 0.0, 0.0)));
    let remainder = at(&image, pixel_of(&harness, Vec3::new(100.0, 20.0, 0.0)));
    assert!(close(executed, FEED_COLOR, 10), "executed is {executed:?}");
    assert!(
        u32::from(remainder[2]) * 2 < u32::from(FEED_COLOR[2]),
        "remainder not dimmed: {remainder:?}"
    );

    // Zoom to a selected block frames it: its segment fills much of the view.
    harness.state_mut().0.player_mut().stop();
    harness.state_mut().0.set_selected_line(Some(7));
    harness.run();
    harness.get_by_label("Zoom sel").click();
    harness.run();
    let a = harness
        .state()
        .0
        .screen_pos(Vec3::new(50.0, -10.0, 5.0))
        .unwrap();
    let b = harness
        .state()
        .0
        .screen_pos(Vec3::new(50.0, 70.0, 5.0))
        .unwrap();
    assert!((a - b).length() > 150.0, "{a:?} {b:?}");

    // The keyboard goes to the view only once it has the focus: the pointer over it is not
    // enough.
    harness.ctx.memory_mut(|m| {
        if let Some(id) = m.focused() {
            m.surrender_focus(id);
        }
    });
    let centre = egui::pos2(160.0, 140.0);
    harness.hover_at(centre);
    harness.run();
    assert!(!harness.state().0.has_focus(&harness.ctx));
    let yaw = harness.state().0.camera().yaw;
    harness.key_press(egui::Key::ArrowLeft);
    harness.run();
    assert_eq!(
        harness.state().0.camera().yaw,
        yaw,
        "keys reached an unfocused view"
    );
    // A click takes it (here on empty space, which clears the selection).
    harness.drag_at(centre);
    harness.run();
    harness.drop_at(centre);
    harness.run();
    assert!(harness.state().0.has_focus(&harness.ctx));
    harness.state_mut().0.set_selected_line(Some(7));
    // Arrows orbit, `2` is the top view, Escape clears the selection and keeps the focus.
    harness.key_press(egui::Key::ArrowLeft);
    harness.run();
    assert_ne!(
        harness.state().0.camera().yaw,
        yaw,
        "arrow key did not orbit"
    );
    assert!(
        harness.state().0.has_focus(&harness.ctx),
        "an arrow key moved the focus away"
    );
    harness.key_press(egui::Key::Num2);
    harness.run();
    let (top_yaw, top_pitch) = swarf_render::StandardView::Top.angles();
    let camera = *harness.state().0.camera();
    assert!((camera.yaw - top_yaw).abs() < 1e-6 && (camera.pitch - top_pitch).abs() < 1e-6);
    assert_eq!(harness.state().0.selected_line(), Some(7));
    harness.key_press(egui::Key::Escape);
    harness.run();
    assert_eq!(harness.state().0.selected_line(), None);
    assert!(harness.state().0.has_focus(&harness.ctx));
    harness.key_press(egui::Key::R);
    harness.run();
    assert!(!harness.state().0.kind_visible(Kind::Rapid));
    harness.key_press(egui::Key::T);
    harness.run();
    assert_eq!(
        harness.state().0.color_mode(),
        swarf_render::ColorMode::ByIndex
    );
}

#[test]
fn playback_draws_a_tool_marker_and_dims_the_remainder() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the backplot playback test");
        return;
    };
    let mut harness = harness(&render_state);
    harness.run();
    harness.get_by_label("Top").click();
    harness.run();
    let marker = |image: &Shot| count(image.as_raw(), [250, 250, 250, 255], 12);
    let before = marker(&shot(&mut harness));

    // Half-way along the first segment (this scene has no timeline: a second per segment).
    let scene = harness.state().1.clone();
    harness.state_mut().0.player_mut().seek(&scene, 0.5);
    harness.run();
    let image = shot(&mut harness);
    let drawn = marker(&image);
    assert!(
        drawn > before + 30,
        "tool marker not drawn: {drawn} vs {before}"
    );
    let (x, y) = pixel_of(&harness, Vec3::new(50.0, 0.0, 0.0));
    let near_tip = (x - 4..=x + 4)
        .flat_map(|x| (y - 4..=y + 4).map(move |y| (x, y)))
        .filter(|&p| close(at(&image, p), [250, 250, 250, 255], 12))
        .count();
    assert!(near_tip > 5, "no marker at the tip: {near_tip}");
    // The segment under way is not finished yet: the whole path after it is dimmed.
    let remainder = at(&image, pixel_of(&harness, Vec3::new(100.0, 20.0, 0.0)));
    assert!(
        u32::from(remainder[2]) * 2 < u32::from(FEED_COLOR[2]),
        "remainder not dimmed: {remainder:?}"
    );
    assert_eq!(harness.state().0.player().current_line(&scene), Some(2));

    // Stop: no marker, nothing dimmed.
    harness.state_mut().0.player_mut().stop();
    harness.run();
    let image = shot(&mut harness);
    assert!(marker(&image) <= before + 5, "marker left behind");
    let edge = at(&image, pixel_of(&harness, Vec3::new(100.0, 20.0, 0.0)));
    assert!(close(edge, FEED_COLOR, 10), "edge is {edge:?}");
}

#[test]
fn scene_of_colours_drilling_plunges_and_retracts() {
    let program = swarf_syntax::parse(
        "G0 X0 Y0 Z20.\nG98 G81 X10. Y10. R2. Z-5. F100\nG80\nG1 X30. F200\n",
        swarf_syntax::Dialect::Fanuc,
    );
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    // One ring of 12 sides around the hole's top (R, 2 mm) across its axis, then the axis
    // cross at the program zero.
    assert_eq!(scene.marks.len(), 13 + 6);
    assert!(scene.marks[0].is_pen_up());
    let top = (DVec3::new(10.0, 10.0, 2.0) - scene.origin).as_vec3();
    let zero = (DVec3::ZERO - scene.origin).as_vec3();
    assert_eq!(scene.marks[13].position(), zero);
    assert_eq!(scene.marks[14].kind(), Some(Kind::AxisX));
    let ring = &scene.marks[..13];
    let radii: Vec<f32> = ring.iter().map(|p| (p.position() - top).length()).collect();
    assert!(
        radii
            .iter()
            .all(|r| (r - radii[0]).abs() < 1e-4 && *r >= 0.499),
        "{radii:?}"
    );
    assert!(ring.iter().all(|p| (p.position().z - top.z).abs() < 1e-4));
    let kinds: Vec<Option<Kind>> = scene.points.iter().skip(1).map(PathPoint::kind).collect();
    assert_eq!(
        kinds,
        [
            Some(Kind::Rapid),
            Some(Kind::Cycle),
            Some(Kind::Cycle),
            Some(Kind::Plunge),
            Some(Kind::Retract),
            Some(Kind::Feed),
        ]
    );
}

#[test]
fn the_travel_box_has_twelve_edges_on_its_corners_and_is_not_framed() {
    let setup = swarf_interp::Setup::from_toml(
        "[machine]\ntravel_mm = [[-500.0, -300.0, -400.0], [0.0, 0.0, 0.0]]\n",
    )
    .unwrap();
    let program = swarf_syntax::parse("G0 X-100. Y-50. Z-10.\n", swarf_syntax::Dialect::Fanuc);
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, setup.clone(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &setup, 1);
    let edges: Vec<(Vec3, Vec3)> = scene
        .marks
        .windows(2)
        .filter(|w| w[0].is_pen_up() && w[1].kind() == Some(Kind::Boundary))
        .map(|w| (w[0].position(), w[1].position()))
        .collect();
    assert_eq!(edges.len(), 12);
    for (a, b) in &edges {
        let d = *b - *a;
        // Each edge runs along one axis, the whole length of the box on it.
        let along: Vec<f32> = [d.x, d.y, d.z].into_iter().filter(|c| *c != 0.0).collect();
        assert_eq!(along.len(), 1, "{d}");
        assert!([500.0, 300.0, 400.0].contains(&along[0].abs()));
    }
    let corner = (DVec3::new(-500.0, -300.0, -400.0) - scene.origin).as_vec3();
    assert!(
        edges
            .iter()
            .any(|(a, b)| (*a - corner).length() < 1e-3 || (*b - corner).length() < 1e-3)
    );
    // Fit frames the path and its marks, not the travel box.
    let (min, max) = scene.view_bounds().unwrap();
    assert!(
        min.x > corner.x + 100.0 && max.length() < 200.0,
        "{min} {max}"
    );
}

#[test]
fn a_g22_zone_is_outlined_in_the_scene() {
    let program = swarf_syntax::parse(
        "G22 X10. I0. Y20. J-5. Z1. K-1.\nG00 X-20. Y0 Z5.\nG01 X-20. Y40. F100.\n",
        swarf_syntax::Dialect::Syntec,
    );
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    let zone: Vec<&PathPoint> = scene
        .marks
        .iter()
        .filter(|p| p.kind() == Some(Kind::Zone))
        .collect();
    assert_eq!(zone.len(), 12);
    // The zone's corner (10, 20, 1) in machine coordinates, relative to the scene's origin.
    let corner = (DVec3::new(10.0, 20.0, 1.0) - scene.origin).as_vec3();
    assert!(
        zone.iter().any(|p| (p.position() - corner).length() < 1e-4),
        "{corner}"
    );
}

#[test]
fn scene_points_carry_their_tool_for_colouring_by_tool() {
    let program = swarf_syntax::parse(
        "T3 M06\nG0 X0 Y0 Z5.\nG1 X10. F100\nT7 M06\nG1 Y10.\nT3 M06\nG1 X0\n",
        swarf_syntax::Dialect::Fanuc,
    );
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    let indices: Vec<u16> = scene
        .points
        .iter()
        .skip(1)
        .map(PathPoint::color_index)
        .collect();
    // T3 is the first tool used (0), T7 the second (1).
    assert_eq!(indices, [0, 0, 1, 0]);
    assert_eq!(scene.points[2].kind(), Some(Kind::Feed));
    let mut plot = Backplot::default();
    assert_eq!(plot.color_mode(), swarf_render::ColorMode::ByKind);
    plot.toggle_color_by_tool();
    assert_eq!(plot.color_mode(), swarf_render::ColorMode::ByIndex);
}

#[test]
fn compensated_blocks_are_drawn_as_such_with_the_programmed_contour_beside() {
    let program = swarf_syntax::parse(
        "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nG02 X20. Y20. I10. J0\nG40 G00 X30.\nM30\n",
        swarf_syntax::Dialect::Fanuc,
    );
    let setup = swarf_interp::Setup::from_toml("[registers.1]\nradius = 2.0\n").unwrap();
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, setup, &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    assert!(
        scene
            .points
            .iter()
            .any(|p| p.kind() == Some(Kind::Compensated))
    );
    // The contour as programmed: the line up Y to 20 and the arc over to X20, as marks.
    let contour: Vec<Vec3> = scene
        .marks
        .iter()
        .filter(|p| p.kind() == Some(Kind::Programmed))
        .map(PathPoint::position)
        .collect();
    let at = |x: f64, y: f64| (DVec3::new(x, y, 0.0) - scene.origin).as_vec3();
    assert!(contour.iter().any(|p| (*p - at(0.0, 20.0)).length() < 1e-4));
    assert!(
        contour
            .iter()
            .any(|p| (*p - at(20.0, 20.0)).length() < 1e-4)
    );
    // The arc's chords stay on its R10 circle about (10, 20).
    let centre = at(10.0, 20.0);
    let on_arc = contour
        .iter()
        .filter(|p| p.y > centre.y + 0.5)
        .all(|p| ((*p - centre).length() - 10.0).abs() < 1e-3);
    assert!(on_arc, "{contour:?}");
}

#[test]
fn each_peck_of_a_deep_hole_is_marked_at_its_bottom() {
    // G83 from R2 down to Z-10 in pecks of 3 mm: bottoms at Z-1, -4, -7 and -10. Each peck's
    // retract runs back over the plunges, so only a mark at each bottom lets them be counted.
    let program = swarf_syntax::parse(
        "G0 X0 Y0 Z20.\nG98 G83 X10. Y10. R2. Z-10. Q3. F100\nG80\nG0 X40.\n",
        swarf_syntax::Dialect::Fanuc,
    );
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    let ticks: Vec<(Vec3, Vec3)> = scene
        .marks
        .windows(2)
        .filter(|w| w[0].is_pen_up() && w[1].kind() == Some(Kind::Plunge))
        .map(|w| (w[0].position(), w[1].position()))
        .collect();
    // A cross (two ticks) at each of the four bottoms.
    assert_eq!(ticks.len(), 8, "{ticks:?}");
    let mut bottoms: Vec<f64> = ticks
        .iter()
        .map(|(a, b)| {
            let mid = ((*a + *b) * 0.5).as_dvec3() + scene.origin;
            assert!(
                (mid.x - 10.0).abs() < 1e-3 && (mid.y - 10.0).abs() < 1e-3,
                "{mid}"
            );
            // Across the hole's axis, a little wider than nothing.
            assert!((a.z - b.z).abs() < 1e-4 && (*a - *b).length() > 0.5);
            (mid.z * 1000.0).round() / 1000.0
        })
        .collect();
    bottoms.dedup();
    assert_eq!(bottoms, [-1.0, -4.0, -7.0, -10.0]);

    // A hole drilled in one plunge (G81) gets no peck marks.
    let program = swarf_syntax::parse(
        "G0 X0 Y0 Z20.\nG98 G81 X10. Y10. R2. Z-10. F100\nG80\n",
        swarf_syntax::Dialect::Fanuc,
    );
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    assert!(scene.marks.iter().all(|p| p.kind() != Some(Kind::Plunge)));
}

#[test]
fn holes_past_the_hundred_thousandth_are_dots_not_rings() {
    // 100,010 holes in a row, 1 mm apart: a ring at the top of the first 100,000, then a dot
    // (a pen-up point and a point on it) at each of the last ten, so a runaway loop of holes
    // draws a bounded number of marks.
    let text = format!(
        "G0 X0 Y0 Z20.\nG91 G98 G81 X1. R-18. Z-7. K9999 F100\n{}X1. K20\nG80\n",
        "X1. K9999\n".repeat(9)
    );
    let program = swarf_syntax::parse(&text, swarf_syntax::Dialect::Fanuc);
    let mut path = swarf_toolpath::Toolpath::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
    assert_eq!(path.holes().len(), 100_010);
    let scene = swarf_ui::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
    let rings = 100_000 * 13;
    assert_eq!(scene.marks.len(), rings + 10 * 2 + 6);
    assert!(scene.marks[rings - 13].is_pen_up() && !scene.marks[rings - 12].is_pen_up());
    for (k, dot) in scene.marks[rings..rings + 20].chunks(2).enumerate() {
        let top = (DVec3::new(100_001.0 + k as f64, 0.0, 2.0) - scene.origin).as_vec3();
        assert!(dot[0].is_pen_up() && dot[1].kind() == Some(Kind::Cycle));
        assert!(
            (dot[0].position() - top).length() < 1e-2,
            "{k}: {:?}",
            dot[0]
        );
        assert_eq!(dot[1].position(), dot[0].position());
    }
}

/// The rectangle's box filled with a raster of `rows` feed rows: every row's ends turn back, so
/// nothing simplifies and the view draws every segment.
fn raster(generation: u64, rows: usize) -> Scene {
    let mut points = vec![PathPoint::pen_up(Vec3::ZERO)];
    for row in 0..rows {
        let y = 60.0 * row as f32 / rows as f32;
        let (from, to) = if row % 2 == 0 {
            (0.0, 100.0)
        } else {
            (100.0, 0.0)
        };
        points.push(PathPoint::new(Vec3::new(from, y, 0.0), Kind::Feed));
        points.push(PathPoint::new(Vec3::new(to, y, 0.0), Kind::Feed));
    }
    let segments = points.len() - 1;
    Scene {
        generation,
        points: Arc::new(points),
        lines: Arc::new((2..).take(segments).collect()),
        feeds: Arc::new(vec![300.0; segments]),
        ..scene()
    }
}

#[test]
fn new_points_too_many_for_a_frame_are_drawn_over_several_beside_the_picture_shown() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the backplot render test");
        return;
    };
    let mut harness = harness(&render_state);
    harness.run();
    let before = shot(&mut harness);
    let pending = |h: &Harness<'_, State>| h.state().0.drawing_pending(&h.state().1);
    assert!(!pending(&harness));

    harness.state_mut().1 = raster(2, 3000);
    harness.step();
    let first = shot(&mut harness);
    assert!(pending(&harness), "a dense raster was drawn in one frame");
    assert!(
        first.rgba == before.rgba,
        "the picture shown changed before the new one was complete"
    );
    let mut frames = 1;
    while pending(&harness) {
        assert!(frames < 20, "the drawing never ends");
        harness.step();
        shot(&mut harness);
        frames += 1;
    }
    // The view keeps one end of each turn (the rows lie under a pixel apart): about 6,000
    // pieces of work, two frames' worth.
    assert!(frames >= 2, "drawn in {frames} frame");
    let done = shot(&mut harness);
    assert!(
        count(&done.rgba, FEED_COLOR, 10) > count(&before.rgba, FEED_COLOR, 10) * 4,
        "the raster is not shown"
    );

    // What was drawn a piece a frame is what one frame draws: a resize (and back) draws the
    // same view at once.
    harness.set_size(egui::vec2(300.0, 240.0));
    harness.run();
    shot(&mut harness);
    harness.set_size(egui::vec2(320.0, 240.0));
    harness.run();
    let whole = shot(&mut harness);
    assert!(!pending(&harness), "a resize is drawn at once");
    assert!(
        whole.rgba == done.rgba,
        "the picture drawn over several frames differs from the one drawn at once"
    );

    // The hand that moves the view is answered at once: a view changed while new points are
    // being drawn shows them whole in that frame.
    harness.state_mut().1 = raster(3, 2999);
    harness.step();
    shot(&mut harness);
    assert!(pending(&harness));
    harness.get_by_label("Top").click();
    harness.run();
    shot(&mut harness);
    assert!(
        !pending(&harness),
        "a view change waited for the drawing in pieces"
    );
}
