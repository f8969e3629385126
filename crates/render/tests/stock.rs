//! Renders a cut stock offscreen when a wgpu adapter exists (e.g. Mesa lavapipe) and checks
//! its shading: the uncut top grey, a slot's floor in the cut colour, the walls lit apart from
//! the top, a path on the floor in front of it; skips (passing, with a note) otherwise.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use glam::{DVec3, Vec2, Vec3};
use swarf_render::{
    DEPTH_FORMAT, FEED_COLOR, HeadlessGpu, Kind, OrbitCamera, PathPoint, PathRenderer,
    RenderTarget, StandardView, StockSurface, ViewParams,
};

const W: u32 = 96;
const H: u32 = 64;

fn gpu() -> Option<HeadlessGpu> {
    if wgpu::Instance::enabled_backend_features().is_empty() {
        return None;
    }
    match pollster::block_on(HeadlessGpu::new()) {
        Ok(gpu) => Some(gpu),
        Err(e) => {
            eprintln!("SKIPPED: {e}");
            None
        }
    }
}

/// A block 60 × 40 × 10 mm (X-30..30, Y-20..20, Z-10..0) in 1 mm cells, around the scene's
/// origin at machine (100, 0, 50), with a slot 5 mm deep along Y0 from X-20 to X20, 10 mm wide.
fn slotted() -> Vec<f32> {
    let mut heights = vec![50.0f32; 60 * 40];
    for j in 0..40 {
        for i in 0..60 {
            let (x, y) = (i as f32 - 29.5, j as f32 - 19.5);
            if x.abs() < 20.0 && y.abs() < 5.0 {
                heights[j * 60 + i] = 45.0;
            }
        }
    }
    heights
}

fn surface(heights: &[f32]) -> StockSurface<'_> {
    StockSurface {
        heights,
        size: (60, 40),
        cell_mm: 1.0,
        min: DVec3::new(70.0, -20.0, 40.0),
        top: 50.0,
        origin: DVec3::new(100.0, 0.0, 50.0),
    }
}

fn camera(view: StandardView) -> OrbitCamera {
    let mut camera = OrbitCamera::new(view);
    camera.fit_aspect(
        Vec3::new(-40.0, -25.0, -10.0),
        Vec3::new(40.0, 25.0, 0.0),
        W as f32 / H as f32,
    );
    camera
}

/// Draws `stock` and `path` seen from `view`; pixels row by row, top first.
fn render(
    gpu: &HeadlessGpu,
    view: StandardView,
    stock: Option<&StockSurface<'_>>,
    path: &[PathPoint],
) -> Vec<[u8; 4]> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let target = RenderTarget::new(device, W, H, format).unwrap();
    let mut renderer = PathRenderer::new(device, format, Some(DEPTH_FORMAT), 1);
    // Set twice: the second keeps the texture of the first.
    renderer.set_stock(device, queue, stock);
    renderer.set_stock(device, queue, stock);
    renderer.set_path(device, queue, path);
    renderer.prepare(
        queue,
        &ViewParams {
            view_proj: camera(view).view_proj(W as f32 / H as f32),
            viewport_px: Vec2::new(W as f32, H as f32),
            line_width_px: 3.0,
            ..ViewParams::default()
        },
    );
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    target.draw(&mut encoder, wgpu::Color::BLACK, &renderer);
    queue.submit([encoder.finish()]);
    target
        .read_rgba8(device, queue)
        .unwrap()
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

/// The pixel over scene point `p` seen from `view`.
fn at(image: &[[u8; 4]], view: StandardView, p: Vec3) -> [u8; 4] {
    let ndc = camera(view)
        .view_proj(W as f32 / H as f32)
        .project_point3(p);
    let x = ((ndc.x + 1.0) * 0.5 * W as f32) as u32;
    let y = ((1.0 - ndc.y) * 0.5 * H as f32) as u32;
    image[(y * W + x) as usize]
}

fn grey(p: [u8; 4]) -> bool {
    p[0] > 60 && p[0].abs_diff(p[1]) < 12 && p[2].abs_diff(p[0]) < 16
}

fn bluish(p: [u8; 4]) -> bool {
    p[2] > 60 && p[2] > p[0].saturating_add(30)
}

#[test]
fn the_cut_stock_is_a_lit_surface_under_the_path() {
    let Some(gpu) = gpu() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let heights = slotted();
    let stock = surface(&heights);
    // A feed along the slot's floor.
    let path = [
        PathPoint::pen_up(Vec3::new(-15.0, 0.0, -5.0)),
        PathPoint::new(Vec3::new(15.0, 0.0, -5.0), Kind::Feed),
    ];
    let top = StandardView::Top;
    let image = render(&gpu, top, Some(&stock), &path);
    let uncut = at(&image, top, Vec3::new(-25.0, 12.0, 0.0));
    let floor = at(&image, top, Vec3::new(-10.0, 3.0, -5.0));
    assert!(grey(uncut), "uncut top {uncut:?}");
    assert!(bluish(floor), "slot floor {floor:?}");
    // Deeper is darker.
    assert!(u32::from(floor[0]) + u32::from(floor[1]) < u32::from(uncut[0]) + u32::from(uncut[1]));
    // The path on the floor shows; outside the block is the background.
    let line = at(&image, top, Vec3::new(0.0, 0.0, -5.0));
    assert!(
        line.iter()
            .zip(FEED_COLOR)
            .take(3)
            .all(|(a, b)| a.abs_diff(b) < 10),
        "path on the floor {line:?}"
    );
    assert_eq!(at(&image, top, Vec3::new(-36.0, 0.0, 0.0)), [0, 0, 0, 255]);

    // From the front the −Y wall faces the eye, lit less than the top, down to the bottom.
    let front = StandardView::Front;
    let image = render(&gpu, front, Some(&stock), &[]);
    let wall = at(&image, front, Vec3::new(0.0, -20.0, -8.0));
    assert!(grey(wall), "wall {wall:?}");
    assert!(
        wall[0] + 10 < uncut[0],
        "wall {wall:?} as bright as the top {uncut:?}"
    );
    assert_eq!(
        at(&image, front, Vec3::new(0.0, -20.0, 3.0)),
        [0, 0, 0, 255]
    );

    // No stock, or heights that do not fill the grid, draw nothing.
    let nothing = render(&gpu, top, None, &[]);
    assert!(nothing.iter().all(|p| *p == [0, 0, 0, 255]));
    let short = StockSurface {
        heights: &heights[1..],
        ..stock
    };
    assert_eq!(render(&gpu, top, Some(&short), &[]), nothing);
}
