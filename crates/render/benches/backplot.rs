//! Backplot performance: preparing and uploading 1M and 10M segments, GPU bytes per segment,
//! picking at 1M segments, frame time at 1M segments whole and at the level of detail of a
//! fitted view (the spiral and the web benchmark's surfacing program) on whatever wgpu adapter
//! is found (Mesa lavapipe on a machine without a GPU).
//!
//! Run: `cargo bench -p swarf-render --bench backplot` (add `-- --quick` for fewer
//! repetitions). Prints a Markdown table for docs/performance.md.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{DVec3, Vec2, Vec3};
use swarf_render::{
    DEPTH_FORMAT, HeadlessGpu, Kind, OrbitCamera, POINT_SIZE, PathLod, PathPoint, PathRenderer,
    RenderTarget, StandardView, ViewParams, grid_points_at, pick_segment,
};

/// Frame size for the frame-time measurement.
const FRAME: (u32, u32) = (1280, 800);

/// A toolpath as the recorder keeps it: f64 end points, kinds, source lines and feeds.
struct SyntheticPath {
    start: DVec3,
    ends: Vec<DVec3>,
    kinds: Vec<u8>,
    lines: Vec<u32>,
    feeds: Vec<f32>,
}

/// `n` segments: a descending spiral pocket of short chords (arcs), straight feeds in
/// between, and a rapid every 1000 segments, in a 200 × 200 × 20 mm box far from zero.
fn synthetic(n: usize) -> SyntheticPath {
    let offset = DVec3::new(500.0, 300.0, -50.0);
    let mut ends = Vec::with_capacity(n);
    let mut kinds = Vec::with_capacity(n);
    let mut lines = Vec::with_capacity(n);
    let mut feeds = Vec::with_capacity(n);
    for i in 0..n {
        let t = i as f64 / n as f64;
        let a = i as f64 * 0.01;
        let r = 100.0 * (1.0 - 0.9 * t);
        ends.push(offset + DVec3::new(r * a.cos(), r * a.sin(), -20.0 * t));
        let kind = if i % 1000 == 999 {
            0
        } else if i % 7 == 0 {
            1
        } else {
            2
        };
        kinds.push(kind);
        lines.push(1 + (i / 8) as u32);
        feeds.push(if kind == 0 { 0.0 } else { 1200.0 });
    }
    SyntheticPath {
        start: offset,
        ends,
        kinds,
        lines,
        feeds,
    }
}

/// What the UI does for each program: f64 machine points to f32 points relative to the
/// bounds' centre with packed kinds, plus the per-segment line and feed arrays for picking.
struct Prepared {
    points: Vec<PathPoint>,
    lines: Vec<u32>,
    feeds: Vec<f32>,
    min: Vec3,
    max: Vec3,
}

fn prepare(path: &SyntheticPath) -> Prepared {
    let mut lo = path.start;
    let mut hi = path.start;
    for p in &path.ends {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let origin = (lo + hi) * 0.5;
    let rel = |p: DVec3| (p - origin).as_vec3();
    let mut points = Vec::with_capacity(path.ends.len() + 1);
    points.push(PathPoint::pen_up(rel(path.start)));
    points.extend(path.ends.iter().zip(&path.kinds).map(|(end, kind)| {
        let kind = match kind {
            0 => Kind::Rapid,
            1 => Kind::Feed,
            _ => Kind::Arc,
        };
        PathPoint::new(rel(*end), kind)
    }));
    Prepared {
        points,
        lines: path.lines.clone(),
        feeds: path.feeds.clone(),
        min: rel(lo),
        max: rel(hi),
    }
}

/// The web benchmark's surfacing program (tests/e2e/bench-web.mjs), `n` feeds: rows of 400
/// moves of 0.25 mm along X, 0.5 mm apart in Y, Z a smooth sine; relative to its centre.
fn surfacing(n: usize) -> Vec<PathPoint> {
    let centre = Vec3::new(50.0, n as f32 / 800.0, -1.5);
    let mut points = vec![
        PathPoint::pen_up(Vec3::new(0.0, 0.0, 5.0) - centre),
        PathPoint::new(-centre, Kind::Feed),
    ];
    points.extend((0..n).map(|i| {
        let x = (i % 400) as f32 * 0.25;
        let y = (i / 400) as f32 * 0.5;
        let z = -((x * 0.07).sin() * (y * 0.05).cos()).abs() * 3.0;
        PathPoint::new(Vec3::new(x, y, z) - centre, Kind::Feed)
    }));
    points
}

/// Rows for `points` drawn through a [`PathLod`] in a fitted iso view of [`FRAME`]: the
/// segments drawn, the time to simplify and upload them, and a frame.
fn lod_rows(
    gpu: &HeadlessGpu,
    what: &str,
    points: &Arc<Vec<PathPoint>>,
    runs: usize,
) -> Vec<(String, String)> {
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let (min, max) = points
        .iter()
        .map(PathPoint::position)
        .filter(|p| p.is_finite())
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    let aspect = FRAME.0 as f32 / FRAME.1 as f32;
    let mut camera = OrbitCamera::new(StandardView::Iso);
    camera.fit_aspect(min, max, aspect);
    let params = ViewParams {
        view_proj: camera.view_proj(aspect),
        viewport_px: Vec2::new(FRAME.0 as f32, FRAME.1 as f32),
        ..ViewParams::default()
    };
    let mut renderer = PathRenderer::new(&gpu.device, format, Some(DEPTH_FORMAT), 1);
    let mut drawn = 0;
    let make: Vec<Duration> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            let mut lod = PathLod::new(Arc::clone(points), Some((min, max)));
            lod.prepare(&mut renderer, &gpu.device, &gpu.queue, &params, &[]);
            gpu.queue.submit([]);
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .unwrap();
            drawn = lod.drawn_segments();
            t.elapsed()
        })
        .collect();
    renderer.prepare(&gpu.queue, &params);
    let target = RenderTarget::new(&gpu.device, FRAME.0, FRAME.1, format).unwrap();
    // The first frame warms pipelines up.
    let frames: Vec<Duration> = (0..=runs)
        .map(|_| timed_frame(gpu, &target, &renderer))
        .skip(1)
        .collect();
    let (width, height) = FRAME;
    vec![
        (
            format!(
                "level of detail of the {what} fitted in {width}×{height}: segments drawn / \
                 simplify + upload"
            ),
            format!("{drawn} / {}", median_and_first(make)),
        ),
        (
            format!("frame of the {what} at that level of detail (draw until done)"),
            ms(median(frames)),
        ),
    ]
}

/// Draws one frame of `renderer` into `target` and waits for the GPU: its wall time.
fn timed_frame(gpu: &HeadlessGpu, target: &RenderTarget, renderer: &PathRenderer) -> Duration {
    let t = Instant::now();
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    target.draw(&mut encoder, wgpu::Color::BLACK, renderer);
    gpu.queue.submit([encoder.finish()]);
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .unwrap();
    t.elapsed()
}

fn median(mut samples: Vec<Duration>) -> Duration {
    samples.sort_unstable();
    samples[samples.len() / 2]
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1000.0)
}

/// "median (first run)": the first run pays for fresh memory pages, later ones reuse them.
fn median_and_first(samples: Vec<Duration>) -> String {
    let first = samples[0];
    format!("{} (first run {})", ms(median(samples)), ms(first))
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let runs = if quick { 3 } else { 7 };
    let gpu = match pollster::block_on(HeadlessGpu::new()) {
        Ok(gpu) => gpu,
        Err(e) => {
            eprintln!("SKIPPED: {e}");
            return;
        }
    };
    let threads = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    println!(
        "adapter: {} ({:?}, {:?}), {threads} CPU threads",
        gpu.info.name, gpu.info.backend, gpu.info.device_type
    );
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let mut rows: Vec<(String, String)> = Vec::new();

    for n in [1_000_000, 10_000_000] {
        let label = if n == 1_000_000 { "1M" } else { "10M" };
        let path = synthetic(n);
        // Prepare (CPU): f64 toolpath → f32 point stream + line/feed arrays.
        let prepared = prepare(&path);
        let build: Vec<Duration> = (0..runs)
            .map(|_| {
                let t = Instant::now();
                let p = prepare(&path);
                let elapsed = t.elapsed();
                assert_eq!(p.points.len(), n + 1);
                elapsed
            })
            .collect();
        // Upload: into a fresh renderer each time (buffer creation + copy), waiting until
        // the GPU has the data.
        let upload: Vec<Duration> = (0..runs)
            .map(|_| {
                let mut renderer = PathRenderer::new(&gpu.device, format, Some(DEPTH_FORMAT), 1);
                let t = Instant::now();
                renderer.set_path(&gpu.device, &gpu.queue, &prepared.points);
                gpu.queue.submit([]);
                gpu.device
                    .poll(wgpu::PollType::wait_indefinitely())
                    .unwrap();
                let elapsed = t.elapsed();
                assert_eq!(renderer.path_segment_count() as usize, n);
                elapsed
            })
            .collect();
        let mut renderer = PathRenderer::new(&gpu.device, format, Some(DEPTH_FORMAT), 1);
        renderer.set_path(&gpu.device, &gpu.queue, &prepared.points);
        let used = (prepared.points.len() as u64 * POINT_SIZE) as f64 / n as f64;
        let allocated = renderer.path_buffer_bytes() as f64 / n as f64;
        rows.push((
            format!("prepare {label} segments (CPU: f64 path → f32 points, lines, feeds)"),
            median_and_first(build.clone()),
        ));
        rows.push((
            format!("upload {label} segments (texture + copy, until the GPU has it)"),
            median_and_first(upload.clone()),
        ));
        rows.push((
            format!("GPU bytes per segment at {label} (used / allocated)"),
            format!("{used:.2} / {allocated:.2}"),
        ));
        rows.push((
            format!("prepare + upload {label} segments"),
            median_and_first(build.iter().zip(&upload).map(|(b, u)| *b + *u).collect()),
        ));

        // Picking and frame time at 1M only (10M frames on lavapipe take seconds).
        let mut camera = OrbitCamera::new(StandardView::Iso);
        let aspect = FRAME.0 as f32 / FRAME.1 as f32;
        camera.fit_aspect(prepared.min, prepared.max, aspect);
        let view_proj = camera.view_proj(aspect);
        let viewport = Vec2::new(FRAME.0 as f32, FRAME.1 as f32);
        let mut pick_times = Vec::new();
        let mut hits = 0;
        for i in 0..25 {
            let cursor = Vec2::new(
                viewport.x * (0.2 + 0.6 * ((i % 5) as f32 / 4.0)),
                viewport.y * (0.2 + 0.6 * ((i / 5) as f32 / 4.0)),
            );
            let t = Instant::now();
            let hit = pick_segment(&prepared.points, view_proj, viewport, cursor, 6.0, 0);
            pick_times.push(t.elapsed());
            hits += usize::from(hit.is_some());
            if let Some(hit) = hit {
                assert!(prepared.lines.get(hit.segment).is_some());
                assert!(prepared.feeds.get(hit.segment).is_some());
            }
        }
        let worst = pick_times.iter().max().copied().unwrap_or_default();
        rows.push((
            format!("pick at {label} segments (25 cursors, {hits} hits; median / worst)"),
            format!("{} / {}", ms(median(pick_times)), ms(worst)),
        ));

        // Frames: at 1M in two sizes (to tell vertex from fragment work), at 10M once.
        let sizes: &[(u32, u32)] = match (n, quick) {
            (1_000_000, _) => &[FRAME, (320, 200)],
            (_, false) => &[FRAME],
            (_, true) => &[],
        };
        let zero = -prepared.min;
        let grid = grid_points_at(zero, prepared.min, prepared.max);
        renderer.set_grid(&gpu.device, &gpu.queue, &grid);
        for &(width, height) in sizes {
            let target = RenderTarget::new(&gpu.device, width, height, format).unwrap();
            let aspect = width as f32 / height as f32;
            let mut camera = OrbitCamera::new(StandardView::Iso);
            camera.fit_aspect(prepared.min, prepared.max, aspect);
            let frame_runs = if n == 1_000_000 { runs } else { 3 };
            let mut frames = Vec::new();
            for i in 0..=frame_runs {
                let mut camera = camera;
                camera.orbit(Vec2::new(i as f32 * 3.0, 0.0));
                renderer.prepare(
                    &gpu.queue,
                    &ViewParams {
                        view_proj: camera.view_proj(aspect),
                        viewport_px: Vec2::new(width as f32, height as f32),
                        ..ViewParams::default()
                    },
                );
                let frame = timed_frame(&gpu, &target, &renderer);
                // The first frame warms pipelines up.
                if i > 0 {
                    frames.push(frame);
                }
            }
            rows.push((
                format!(
                    "frame at {label} segments drawn whole, {width}×{height} (draw until done)"
                ),
                ms(median(frames)),
            ));
        }
        if n == 1_000_000 {
            let spiral = Arc::new(prepared.points.clone());
            rows.extend(lod_rows(&gpu, "spiral pocket", &spiral, runs));
            rows.extend(lod_rows(
                &gpu,
                "surfacing program",
                &Arc::new(surfacing(n)),
                runs,
            ));
        }
    }

    println!();
    println!("| measurement | result |");
    println!("|---|---|");
    for (what, result) in rows {
        println!("| {what} | {result} |");
    }
}
