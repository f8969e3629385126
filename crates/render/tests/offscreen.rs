//! Renders paths offscreen when a wgpu adapter exists (e.g. Mesa lavapipe) and checks
//! colours, widths, dashes, depth against the grid, highlight and playback dimming; skips
//! (passing, with a note) otherwise.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::sync::Arc;

use glam::{Vec2, Vec3};
use swarf_render::{
    ARC_COLOR, Compositor, DEPTH_FORMAT, FEED_COLOR, GRID_MAJOR_COLOR, HIGHLIGHT_COLOR,
    HeadlessGpu, Kind, OrbitCamera, PathLod, PathPoint, PathRenderer, RAPID_COLOR, RenderTarget,
    StandardView, ViewParams, grid_points,
};

const W: u32 = 96;
const H: u32 = 64;

fn gpu() -> Option<HeadlessGpu> {
    if wgpu::Instance::enabled_backend_features().is_empty() {
        return None;
    }
    match pollster::block_on(HeadlessGpu::new()) {
        Ok(gpu) => {
            eprintln!("adapter: {:?}", gpu.info);
            Some(gpu)
        }
        Err(e) => {
            eprintln!("SKIPPED: {e}");
            None
        }
    }
}

struct Image {
    pixels: Vec<u8>,
}

impl Image {
    fn at(&self, x: u32, y: u32) -> [u8; 4] {
        let i = ((y * W + x) * 4) as usize;
        [
            self.pixels[i],
            self.pixels[i + 1],
            self.pixels[i + 2],
            self.pixels[i + 3],
        ]
    }
    fn count(&self, want: impl Fn([u8; 4]) -> bool) -> usize {
        self.pixels
            .chunks_exact(4)
            .filter(|p| want([p[0], p[1], p[2], p[3]]))
            .count()
    }
}

fn close(a: [u8; 4], b: [u8; 4], tolerance: u8) -> bool {
    a.iter()
        .zip(&b)
        .take(3)
        .all(|(x, y)| x.abs_diff(*y) <= tolerance)
}

/// A top view of the box -40..40 × -25..25, so one unit is about one pixel.
fn top_camera() -> OrbitCamera {
    let mut camera = OrbitCamera::new(StandardView::Top);
    camera.fit_aspect(
        Vec3::new(-40.0, -25.0, -10.0),
        Vec3::new(40.0, 25.0, 10.0),
        W as f32 / H as f32,
    );
    camera
}

fn render(
    gpu: &HeadlessGpu,
    format: wgpu::TextureFormat,
    path: &[PathPoint],
    grid: &[PathPoint],
    tweak: impl FnOnce(&mut ViewParams),
) -> Image {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let target = RenderTarget::new(device, W, H, format).unwrap();
    let mut renderer = PathRenderer::new(device, format, Some(DEPTH_FORMAT), 1);
    // Upload twice to exercise buffer reuse.
    renderer.set_path(device, queue, &[]);
    renderer.set_path(device, queue, path);
    renderer.set_grid(device, queue, grid);
    let expected = if path.len() >= 2 { path.len() - 1 } else { 0 };
    assert_eq!(renderer.path_segment_count() as usize, expected);
    let mut params = ViewParams {
        view_proj: top_camera().view_proj(W as f32 / H as f32),
        viewport_px: Vec2::new(W as f32, H as f32),
        line_width_px: 3.0,
        rapid_width_px: 3.0,
        ..ViewParams::default()
    };
    tweak(&mut params);
    renderer.prepare(queue, &params);
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    target.draw(&mut encoder, wgpu::Color::BLACK, &renderer);
    queue.submit([encoder.finish()]);
    Image {
        pixels: target.read_rgba8(device, queue).unwrap(),
    }
}

/// Screen pixel of a world point in the top view.
fn pixel(p: Vec3) -> (u32, u32) {
    let ndc = top_camera()
        .view_proj(W as f32 / H as f32)
        .project_point3(p);
    (
        ((ndc.x + 1.0) * 0.5 * W as f32) as u32,
        ((1.0 - ndc.y) * 0.5 * H as f32) as u32,
    )
}

/// Feed along y = 10, then (pen up) a rapid along y = -10, then an arc chord along x = 0.
fn kinds_path() -> Vec<PathPoint> {
    vec![
        PathPoint::pen_up(Vec3::new(-35.0, 10.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, 10.0, 0.0), Kind::Feed),
        PathPoint::pen_up(Vec3::new(-35.0, -10.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, -10.0, 0.0), Kind::Rapid),
        PathPoint::pen_up(Vec3::new(20.0, -20.0, 0.0)),
        PathPoint::new(Vec3::new(20.0, 20.0, 0.0), Kind::Arc),
    ]
}

#[test]
fn colours_by_kind_with_pen_up_gaps_and_dashes() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    for format in [
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Rgba8UnormSrgb,
    ] {
        let image = render(&gpu, format, &kinds_path(), &[], |_| {});
        let feed = image.count(|p| close(p, FEED_COLOR, 8));
        let rapid = image.count(|p| close(p, RAPID_COLOR, 8));
        let arc = image.count(|p| close(p, ARC_COLOR, 8));
        assert!(feed > 100, "{format:?}: {feed} feed pixels");
        assert!(rapid > 40, "{format:?}: {rapid} rapid pixels");
        assert!(arc > 60, "{format:?}: {arc} arc pixels");
        // The feed line is where it should be.
        let (x, y) = pixel(Vec3::new(-10.0, 10.0, 0.0));
        assert!(close(image.at(x, y), FEED_COLOR, 8), "{:?}", image.at(x, y));
        // Pen-up: nothing between the feed's end and the rapid's start (x = -35 side).
        let (x, y) = pixel(Vec3::new(-35.0, 0.0, 0.0));
        assert_eq!(&image.at(x, y)[..3], &[0, 0, 0], "pen-up gap drawn");
        // The rapid is dashed: along its row some pixels are lit and some dark.
        let (_, ry) = pixel(Vec3::new(0.0, -10.0, 0.0));
        let (x0, _) = pixel(Vec3::new(-30.0, -10.0, 0.0));
        let (x1, _) = pixel(Vec3::new(10.0, -10.0, 0.0));
        let lit = (x0..x1)
            .filter(|&x| close(image.at(x, ry), RAPID_COLOR, 60))
            .count();
        let span = (x1 - x0) as usize;
        assert!(
            lit > span / 3 && lit < span * 9 / 10,
            "{format:?}: rapid not dashed ({lit} of {span} lit)"
        );
        // Anti-aliased edges: partly covered pixels exist beside the feed line.
        let (fx, fy) = pixel(Vec3::new(0.0, 10.0, 0.0));
        let column: Vec<[u8; 4]> = (fy.saturating_sub(4)..fy + 5)
            .map(|y| image.at(fx, y))
            .collect();
        assert!(
            column
                .iter()
                .any(|p| p[2] > 20 && p[2] < FEED_COLOR[2] - 20),
            "{format:?}: no anti-aliased edge in {column:?}"
        );
    }
}

#[test]
fn depth_decides_what_is_in_front_not_draw_order() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let format = wgpu::TextureFormat::Rgba8Unorm;
    // A feed at z = +5 (near the top-view eye) and an arc at z = -5 crossing it.
    let feed = [
        PathPoint::pen_up(Vec3::new(-30.0, 0.0, 5.0)),
        PathPoint::new(Vec3::new(30.0, 0.0, 5.0), Kind::Feed),
    ];
    let arc = [
        PathPoint::pen_up(Vec3::new(0.0, -20.0, -5.0)),
        PathPoint::new(Vec3::new(0.0, 20.0, -5.0), Kind::Arc),
    ];
    let crossing = pixel(Vec3::ZERO);
    for order in [[&feed[..], &arc[..]], [&arc[..], &feed[..]]] {
        let path: Vec<PathPoint> = order.concat();
        let image = render(&gpu, format, &path, &[], |_| {});
        let p = image.at(crossing.0, crossing.1);
        assert!(
            close(p, FEED_COLOR, 8),
            "near feed hidden at the crossing: {p:?}"
        );
    }

    // The grid (a major line along x = 0 at z = 0) is hidden by the path above it and drawn
    // over the path below it.
    let grid = [
        PathPoint::pen_up(Vec3::new(0.0, -30.0, 0.0)),
        PathPoint::new(Vec3::new(0.0, 30.0, 0.0), Kind::GridMajor),
    ];
    let reference = pixel(Vec3::new(-20.0, 0.0, 0.0));
    for (z, grid_visible) in [(5.0, false), (-5.0, true)] {
        let path = [
            PathPoint::pen_up(Vec3::new(-30.0, 0.0, z)),
            PathPoint::new(Vec3::new(30.0, 0.0, z), Kind::Feed),
        ];
        let image = render(&gpu, format, &path, &grid, |p| p.grid_width_px = 3.0);
        let plain = image.at(reference.0, reference.1);
        let at_grid = image.at(crossing.0, crossing.1);
        assert!(close(plain, FEED_COLOR, 8), "{plain:?}");
        assert_eq!(
            !close(at_grid, plain, 4),
            grid_visible,
            "path at z = {z}: crossing {at_grid:?} vs plain {plain:?}"
        );
        // Elsewhere the grid line is drawn.
        let (gx, gy) = pixel(Vec3::new(0.0, 20.0, 0.0));
        let g = image.at(gx, gy);
        assert!(
            g[0] > 40 && g[0] <= GRID_MAJOR_COLOR[0],
            "grid line missing: {g:?}"
        );
    }
}

#[test]
fn highlight_dim_and_hidden_kinds() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let path = kinds_path();
    let feed_px = pixel(Vec3::new(-10.0, 10.0, 0.0));
    let arc_px = pixel(Vec3::new(20.0, 0.0, 0.0));
    let rapid_row = pixel(Vec3::new(0.0, -10.0, 0.0)).1;

    // Highlight the arc (segment 4) by range, the feed (segment 0) by flag.
    let mut flagged = path.clone();
    flagged[1] = flagged[1].with_highlight(true);
    let image = render(&gpu, format, &flagged, &[], |p| p.highlight = 4..5);
    assert!(close(image.at(arc_px.0, arc_px.1), HIGHLIGHT_COLOR, 8));
    assert!(close(image.at(feed_px.0, feed_px.1), HIGHLIGHT_COLOR, 8));

    // Playback at segment 1: the feed (0) is executed, the arc (4) is the dimmed remainder.
    let image = render(&gpu, format, &path, &[], |p| {
        p.executed_segments = Some(1);
        p.dim_alpha = 0.25;
    });
    assert!(close(image.at(feed_px.0, feed_px.1), FEED_COLOR, 8));
    let dim = image.at(arc_px.0, arc_px.1);
    let want = ARC_COLOR.map(|c| (f32::from(c) * 0.25) as u8);
    assert!(
        close(dim, want, 8),
        "dimmed arc {dim:?}, want about {want:?}"
    );

    // Hidden kinds are not drawn.
    let image = render(&gpu, format, &path, &[], |p| {
        p.hidden_kinds = Kind::Rapid.mask();
    });
    assert_eq!(image.count(|p| close(p, RAPID_COLOR, 60)), 0);
    assert!(close(image.at(feed_px.0, feed_px.1), FEED_COLOR, 8));
    assert!((0..W).all(|x| image.at(x, rapid_row)[0] < 10 || x > W / 2));
}

#[test]
fn grid_and_axes_draw_and_buffers_grow() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let grid = grid_points(Vec3::new(-40.0, -25.0, 0.0), Vec3::new(40.0, 25.0, 0.0));
    let image = render(&gpu, wgpu::TextureFormat::Rgba8Unorm, &[], &grid, |_| {});
    let lit = image.count(|p| p[0] > 20 || p[1] > 20 || p[2] > 20);
    assert!(lit > 200, "grid drew only {lit} pixels");
    // The red X axis runs right from the origin.
    let (ox, oy) = pixel(Vec3::ZERO);
    let red = (ox + 2..W).filter(|&x| image.at(x, oy)[0] > 150).count();
    assert!(red > 5, "no X axis");

    // Growing past the first capacity reallocates; huge counts keep their exact size.
    let mut renderer = PathRenderer::new(
        &gpu.device,
        wgpu::TextureFormat::Rgba8Unorm,
        Some(DEPTH_FORMAT),
        1,
    );
    let many: Vec<PathPoint> = (0..100_000)
        .map(|i| PathPoint::new(Vec3::new(i as f32, 0.0, 0.0), Kind::Feed))
        .collect();
    renderer.set_path(&gpu.device, &gpu.queue, &many[..10]);
    renderer.set_path(&gpu.device, &gpu.queue, &many);
    assert_eq!(renderer.path_segment_count(), 99_999);
    assert!(renderer.path_buffer_bytes() <= 16 * (100_000 + 4096));
    renderer.set_path(&gpu.device, &gpu.queue, &many[..1]);
    assert_eq!(renderer.path_segment_count(), 0);
}

#[test]
fn composites_into_a_pass_without_depth() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let (device, queue) = (&gpu.device, &gpu.queue);
    let source = RenderTarget::new(device, W, H, wgpu::TextureFormat::Rgba8Unorm).unwrap();
    let mut renderer = PathRenderer::new(
        device,
        wgpu::TextureFormat::Rgba8Unorm,
        Some(DEPTH_FORMAT),
        1,
    );
    renderer.set_path(device, queue, &kinds_path());
    renderer.prepare(
        queue,
        &ViewParams {
            view_proj: top_camera().view_proj(W as f32 / H as f32),
            viewport_px: Vec2::new(W as f32, H as f32),
            line_width_px: 3.0,
            ..ViewParams::default()
        },
    );
    for format in [
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Rgba8UnormSrgb,
    ] {
        let dest = RenderTarget::new(device, W, H, format).unwrap();
        let compositor = Compositor::new(device, format, 1);
        let bind = compositor.bind(device, &source);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        // Transparent background: what is under the 3D view shows through.
        source.draw(&mut encoder, wgpu::Color::TRANSPARENT, &renderer);
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui-like pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: dest.color_view(),
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.0,
                            g: 0.0,
                            b: 1.0,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            compositor.paint(&mut pass, &bind);
        }
        queue.submit([encoder.finish()]);
        let image = Image {
            pixels: dest.read_rgba8(device, queue).unwrap(),
        };
        let (x, y) = pixel(Vec3::new(-10.0, 10.0, 0.0));
        assert!(
            close(image.at(x, y), FEED_COLOR, 8),
            "{format:?}: {:?}",
            image.at(x, y)
        );
        let (x, y) = pixel(Vec3::new(-20.0, 0.0, 0.0));
        assert_eq!(
            image.at(x, y),
            [0, 0, 255, 255],
            "{format:?}: background covered"
        );
    }
}

/// Draws `path` (with the points `highlight` flagged highlighted, or with the segments
/// `by_range` highlighted through [`ViewParams::highlight`]) into a fresh target with at most
/// `per_buffer` points in one GPU buffer.
fn render_split(
    gpu: &HeadlessGpu,
    path: &[PathPoint],
    per_buffer: Option<u64>,
    highlight: std::ops::Range<usize>,
) -> (Image, usize) {
    render_split_with(gpu, path, per_buffer, highlight, 0..0, None)
}

/// [`render_split`] with the segments `by_range` highlighted too, drawn in one pass or, with
/// `piece`, in passes of that much work each (as a picture drawn over several frames).
fn render_split_with(
    gpu: &HeadlessGpu,
    path: &[PathPoint],
    per_buffer: Option<u64>,
    highlight: std::ops::Range<usize>,
    by_range: std::ops::Range<u32>,
    piece: Option<u64>,
) -> (Image, usize) {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let target = RenderTarget::new(device, W, H, format).unwrap();
    let mut renderer = PathRenderer::new(device, format, Some(DEPTH_FORMAT), 1);
    renderer.set_points_per_buffer(per_buffer);
    let path: Vec<PathPoint> = path
        .iter()
        .enumerate()
        .map(|(i, p)| p.with_highlight(highlight.contains(&i)))
        .collect();
    renderer.set_path(device, queue, &path);
    assert_eq!(renderer.path_segment_count() as usize, path.len() - 1);
    assert_eq!(renderer.path_point_count() as usize, path.len());
    renderer.prepare(
        queue,
        &ViewParams {
            view_proj: top_camera().view_proj(W as f32 / H as f32),
            viewport_px: Vec2::new(W as f32, H as f32),
            line_width_px: 2.0,
            rapid_width_px: 2.0,
            highlight: by_range,
            ..ViewParams::default()
        },
    );
    let work = renderer.work();
    assert_eq!(work, 2 * u64::from(renderer.path_segment_count()));
    let piece = piece.unwrap_or(work).max(1);
    let mut done = 0;
    while done == 0 || done < work {
        let part = done..(done + piece).min(work);
        let clear = (done == 0).then_some(wgpu::Color::BLACK);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        target.draw_part(&mut encoder, clear, &renderer, part.clone());
        queue.submit([encoder.finish()]);
        done = part.end.max(1);
    }
    let buffers = renderer.path_buffer_count();
    (
        Image {
            pixels: target.read_rgba8(device, queue).unwrap(),
        },
        buffers,
    )
}

#[test]
fn a_path_split_over_several_buffers_draws_like_one() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    // A spiral of 1000 chords with a rapid (pen up) now and then.
    let path: Vec<PathPoint> = (0..1000)
        .map(|i| {
            let t = i as f32 * 0.05;
            let r = 2.0 + t * 1.2;
            let p = Vec3::new(r * t.cos(), 0.8 * r * t.sin(), 0.0);
            if i % 97 == 0 {
                PathPoint::pen_up(p)
            } else if i % 50 < 25 {
                PathPoint::new(p, Kind::Feed)
            } else {
                PathPoint::new(p, Kind::Arc)
            }
        })
        .collect();
    // The highlight crosses seams of the small buffers (every 6 points).
    let (whole, one) = render_split(&gpu, &path, None, 400..530);
    assert_eq!(one, 1);
    let (split, many) = render_split(&gpu, &path, Some(7), 400..530);
    assert_eq!(many, (1000 - 1usize).div_ceil(6));
    let lit = whole.count(|p| p[0] > 20 || p[1] > 20 || p[2] > 20);
    assert!(lit > 500, "the spiral drew only {lit} pixels");
    let highlighted = whole.count(|p| close(p, HIGHLIGHT_COLOR, 40));
    assert!(highlighted > 20, "no highlighted segment");
    assert_eq!(
        whole.pixels, split.pixels,
        "a path split over {many} buffers draws differently"
    );
    // A highlighted range of segment numbers counts from the path's start in every buffer.
    let (whole, _) = render_split_with(&gpu, &path, None, 0..0, 399..529, None);
    let (split, _) = render_split_with(&gpu, &path, Some(7), 0..0, 399..529, None);
    assert!(whole.count(|p| close(p, HIGHLIGHT_COLOR, 40)) > 20);
    assert_eq!(
        whole.pixels, split.pixels,
        "a highlighted range over {many} buffers draws differently"
    );
    // Drawn a piece at a time (pieces crossing the buffers' seams and the switch from the
    // cores to the edges), the picture is the same.
    for piece in [1, 5, 333, 998, 1000] {
        let (pieces, _) = render_split_with(&gpu, &path, Some(7), 0..0, 399..529, Some(piece));
        assert!(
            whole.pixels == pieces.pixels,
            "drawn {piece} at a time, the path draws differently"
        );
    }
    // Two points per buffer is the smallest split: one segment each.
    let (tiny, n) = render_split(&gpu, &path[..50], Some(1), 0..0);
    assert_eq!(n, 49);
    let (single, _) = render_split(&gpu, &path[..50], None, 0..0);
    assert_eq!(tiny.pixels, single.pixels);
}

#[test]
fn highlight_and_playback_ranges_touch_only_the_toolpath() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let format = wgpu::TextureFormat::Rgba8Unorm;
    // Toolpath: one feed along y = 10 (segment 0), one along y = 0 (segment 2).
    let path = [
        PathPoint::pen_up(Vec3::new(-35.0, 10.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, 10.0, 0.0), Kind::Feed),
        PathPoint::pen_up(Vec3::new(-35.0, 0.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, 0.0, 0.0), Kind::Feed),
    ];
    // Grid stream: a major grid line along y = -20 (its segment 0) and a programmed contour
    // mark along y = -12 (its segment 2), numbered like the path's highlighted segments.
    let grid = [
        PathPoint::pen_up(Vec3::new(-35.0, -20.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, -20.0, 0.0), Kind::GridMajor),
        PathPoint::pen_up(Vec3::new(-35.0, -12.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, -12.0, 0.0), Kind::Programmed),
    ];
    let feed = pixel(Vec3::new(-10.0, 10.0, 0.0));
    let grid_line = pixel(Vec3::new(-10.0, -20.0, 0.0));
    let image = render(&gpu, format, &path, &grid, |p| {
        p.highlight = 0..3;
        p.grid_width_px = 3.0;
    });
    assert!(close(image.at(feed.0, feed.1), HIGHLIGHT_COLOR, 8));
    let lit = image.count(|p| close(p, HIGHLIGHT_COLOR, 30));
    let plain = render(&gpu, format, &path, &grid, |p| p.grid_width_px = 3.0);
    let g = image.at(grid_line.0, grid_line.1);
    assert_eq!(
        g,
        plain.at(grid_line.0, grid_line.1),
        "grid line highlighted"
    );
    // Only the two path lines are lit: no mark or grid line in the highlight colour.
    let path_only = render(&gpu, format, &path, &[], |p| p.highlight = 0..3);
    assert_eq!(lit, path_only.count(|p| close(p, HIGHLIGHT_COLOR, 30)));
    let contour_row = pixel(Vec3::new(0.0, -12.0, 0.0)).1;
    assert!(
        (0..W).all(|x| !close(image.at(x, contour_row), HIGHLIGHT_COLOR, 30)),
        "contour mark highlighted"
    );

    // Playback before the first segment dims the path, never the marks.
    let dimmed = render(&gpu, format, &path, &grid, |p| {
        p.executed_segments = Some(0);
        p.dim_alpha = 0.25;
    });
    let row =
        |image: &Image| -> Vec<[u8; 4]> { (0..W).map(|x| image.at(x, contour_row)).collect() };
    assert_eq!(row(&dimmed), row(&plain), "contour mark dimmed by playback");
    let f = dimmed.at(feed.0, feed.1);
    assert!(
        u32::from(f[2]) * 2 < u32::from(FEED_COLOR[2]),
        "path not dimmed: {f:?}"
    );
}

#[test]
fn the_programmed_contour_is_dashed_in_its_own_colour() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let grid = [
        PathPoint::pen_up(Vec3::new(-35.0, 0.0, 0.0)),
        PathPoint::new(Vec3::new(35.0, 0.0, 0.0), Kind::Programmed),
    ];
    let image = render(&gpu, format, &[], &grid, |_| {});
    let (x0, y) = pixel(Vec3::new(-30.0, 0.0, 0.0));
    let (x1, _) = pixel(Vec3::new(30.0, 0.0, 0.0));
    let magenta = |p: [u8; 4]| p[0] > 120 && p[2] > 110 && p[1] + 60 < p[0];
    let lit = (x0..x1)
        .filter(|&x| (y.saturating_sub(1)..=y + 1).any(|y| magenta(image.at(x, y))))
        .count();
    let span = (x1 - x0) as usize;
    assert!(
        lit > span / 4 && lit < span * 9 / 10,
        "contour not dashed in its colour: {lit} of {span} lit"
    );
    // Not grey like a grid line.
    assert!(!close(swarf_render::PROGRAMMED_COLOR, GRID_MAJOR_COLOR, 60));
}

/// Draws `points` (whole, or through a [`PathLod`] with the segments `flagged` highlighted)
/// in an iso view fitted to them, `size` pixels; returns the image and the segments drawn.
fn render_iso(
    gpu: &HeadlessGpu,
    points: &Arc<Vec<PathPoint>>,
    lod: bool,
    size: (u32, u32),
    tweak: impl FnOnce(&mut ViewParams),
    flagged: &[std::ops::Range<usize>],
) -> (Vec<u8>, usize) {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let target = RenderTarget::new(device, size.0, size.1, format).unwrap();
    let mut renderer = PathRenderer::new(device, format, Some(DEPTH_FORMAT), 1);
    let (min, max) = points
        .iter()
        .map(PathPoint::position)
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    let aspect = size.0 as f32 / size.1 as f32;
    let mut camera = OrbitCamera::new(StandardView::Iso);
    camera.fit_aspect(min, max, aspect);
    let mut params = ViewParams {
        view_proj: camera.view_proj(aspect),
        viewport_px: Vec2::new(size.0 as f32, size.1 as f32),
        ..ViewParams::default()
    };
    tweak(&mut params);
    let drawn = if lod {
        let mut lod = PathLod::new(Arc::clone(points), Some((min, max)));
        params = lod.prepare(&mut renderer, device, queue, &params, flagged);
        lod.drawn_segments()
    } else {
        let lit: Vec<PathPoint> = points
            .iter()
            .enumerate()
            .map(|(i, p)| p.with_highlight(i > 0 && flagged.iter().any(|r| r.contains(&(i - 1)))))
            .collect();
        renderer.set_path(device, queue, &lit);
        points.len() - 1
    };
    renderer.prepare(queue, &params);
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    target.draw(&mut encoder, wgpu::Color::BLACK, &renderer);
    queue.submit([encoder.finish()]);
    (target.read_rgba8(device, queue).unwrap(), drawn)
}

/// Pixels `lit` in image `a` (`width` pixels wide) with no pixel `faint` in image `b` within
/// one pixel: what one draws and the other does not, beyond half a pixel's shift.
fn lit_apart(
    a: &[u8],
    b: &[u8],
    width: usize,
    lit: impl Fn(&[u8]) -> bool,
    faint: impl Fn(&[u8]) -> bool,
    near: isize,
) -> usize {
    let on = |image: &[u8], x: isize, y: isize, test: &dyn Fn(&[u8]) -> bool| {
        let height = (image.len() / 4 / width) as isize;
        (0..width as isize).contains(&x)
            && (0..height).contains(&y)
            && test(&image[(y as usize * width + x as usize) * 4..][..4])
    };
    (0..a.len() / 4)
        .filter(|&i| {
            let (x, y) = ((i % width) as isize, (i / width) as isize);
            on(a, x, y, &lit)
                && !(-near..=near).any(|dy| (-near..=near).any(|dx| on(b, x + dx, y + dy, &faint)))
        })
        .count()
}

#[test]
fn the_simplified_path_draws_what_the_whole_path_draws() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    // The web benchmark's surfacing program, 200 rows of 400 feeds, after a rapid down to it.
    let mut surfacing = vec![
        PathPoint::pen_up(Vec3::new(0.0, 0.0, 5.0)),
        PathPoint::new(Vec3::ZERO, Kind::Rapid),
    ];
    for n in 0..200 * 400 {
        let x = (n % 400) as f32 * 0.25;
        let y = (n / 400) as f32 * 0.5;
        let z = -((x * 0.07).sin() * (y * 0.05).cos()).abs() * 3.0;
        surfacing.push(PathPoint::new(Vec3::new(x, y, z), Kind::Feed));
    }
    // A flat spiral of ten turns in 40,000 chords, a tenth of a pixel each: where it bends, a
    // chord cuts across.
    let spiral: Vec<PathPoint> = (0..40_000)
        .map(|i| {
            let a = i as f32 * 0.0016;
            let r = 5.0 + a * 1.6;
            PathPoint::new(Vec3::new(r * a.cos(), r * a.sin(), 0.0), Kind::Arc)
        })
        .collect();
    let (surfacing, spiral) = (Arc::new(surfacing), Arc::new(spiral));
    let size = (320, 240);
    let total = (size.0 * size.1) as usize;
    type Tweak = fn(&mut ViewParams);
    let plain: Tweak = |_| {};
    let played: Tweak = |p| {
        p.highlight = 30_101..30_301;
        p.executed_segments = Some(40_001);
    };
    // (what, path, view, runs flagged, fewer segments by, near: how far apart in pixels a lit
    // pixel may be from one in the other image; the surfacing's rows are under a pixel apart).
    let cases = [
        ("surfacing", &surfacing, plain, vec![], 20, 1),
        (
            "surfacing with a block highlighted, half played",
            &surfacing,
            played,
            vec![],
            20,
            1,
        ),
        (
            "surfacing with two runs flagged",
            &surfacing,
            plain,
            vec![1_000..1_400, 60_000..60_390],
            20,
            1,
        ),
        ("spiral", &spiral, plain, vec![], 4, 0),
    ];
    let width = size.0 as usize;
    let strong = |p: &[u8]| p.iter().take(3).any(|c| *c > 160);
    let faint = |p: &[u8]| p.iter().take(3).any(|c| *c > 16);
    let highlight = |p: &[u8]| p[0] > 200 && p[1] > 200 && p[2] < 220;
    let highlight_faint = |p: &[u8]| p[0] > 100 && p[1] > 100 && p[2] < 220;
    type Pixel<'a> = &'a dyn Fn(&[u8]) -> bool;
    let count = |image: &[u8], test: Pixel| image.chunks_exact(4).filter(|p| test(p)).count();
    for (what, points, tweak, flagged, fewer, near) in cases {
        let (whole, all) = render_iso(&gpu, points, false, size, tweak, &flagged);
        let (simplified, drawn) = render_iso(&gpu, points, true, size, tweak, &flagged);
        assert!(
            drawn * fewer < all,
            "{what}: {drawn} of {all} segments drawn"
        );
        assert!(
            count(&whole, &faint) > total / 20,
            "{what}: the path drew little"
        );
        // Every pixel the simplified path lights, the whole path lights too, and nearly every
        // one the whole path lights: its tiny segments overdraw their anti-aliased edges, so
        // it is a little bolder, but no line moves by more than half a pixel.
        let tests: [(&str, Pixel, Pixel); 2] = [
            ("lit", &strong, &faint),
            ("highlighted", &highlight, &highlight_faint),
        ];
        for (kind, lit, faint) in tests {
            let extra = lit_apart(&simplified, &whole, width, lit, faint, near);
            let missing = lit_apart(&whole, &simplified, width, lit, faint, near);
            assert!(
                extra <= total / 2000 && missing <= total / 100,
                "{what}: {extra} pixels {kind} only simplified, {missing} only whole"
            );
        }
        let lit = !flagged.is_empty() || what.contains("highlighted");
        for image in [&whole, &simplified] {
            let n = count(image, &highlight);
            assert_eq!(n > 20, lit, "{what}: {n} pixels highlighted");
        }
    }
}
