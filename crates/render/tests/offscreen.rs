//! Renders lines offscreen when a wgpu adapter exists (e.g. Mesa lavapipe); skips otherwise.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use glam::Vec3;
use swarf_render::{LineRenderer, OrbitCamera, StandardView, Vertex, grid_vertices};

const SIZE: u32 = 64;

fn device() -> Option<(wgpu::Device, wgpu::Queue)> {
    if wgpu::Instance::enabled_backend_features().is_empty() {
        return None;
    }
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::LowPower,
        force_fallback_adapter: false,
        compatible_surface: None,
        apply_limit_buckets: false,
    }))
    .ok()?;
    eprintln!("adapter: {:?}", adapter.get_info());
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("swarf-render test"),
        required_limits:
            wgpu::Limits::downlevel_webgl2_defaults().using_resolution(adapter.limits()),
        ..Default::default()
    }))
    .ok()
}

/// Renders `vertices` (and optionally a grid) seen from the top and returns RGBA8 pixels.
fn render(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    format: wgpu::TextureFormat,
    vertices: &[Vertex],
) -> Vec<[u8; 4]> {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("target"),
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());

    let mut renderer = LineRenderer::new(device, format, 1);
    // Upload twice to exercise buffer reuse, and an empty grid.
    renderer.set_lines(device, queue, &[]);
    renderer.set_lines(device, queue, vertices);
    renderer.set_grid(device, queue, &[]);
    assert_eq!(renderer.line_vertex_count() as usize, vertices.len() & !1);

    let mut camera = OrbitCamera::new(StandardView::Top);
    camera.fit(Vec3::new(-10.0, -10.0, 0.0), Vec3::new(10.0, 10.0, 0.0));
    renderer.prepare(queue, camera.view_proj(1.0));

    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("lines"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        renderer.paint(&mut pass);
    }
    let row = (SIZE * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(row * SIZE),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    readback
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.unwrap());
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    let data = readback.slice(..).get_mapped_range().unwrap();
    data.chunks_exact(row as usize)
        .flat_map(|r| r[..(SIZE * 4) as usize].chunks_exact(4))
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

#[test]
fn draws_coloured_lines_offscreen() {
    let Some((device, queue)) = device() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let red = [255, 0, 0, 255];
    let green = [0, 255, 0, 255];
    let lines = [
        Vertex::new(Vec3::new(-8.0, 0.0, 0.0), red),
        Vertex::new(Vec3::new(8.0, 0.0, 0.0), red),
        Vertex::new(Vec3::new(0.0, -8.0, 0.0), green),
        Vertex::new(Vec3::new(0.0, 8.0, 0.0), green),
        Vertex::new(Vec3::ZERO, red), // odd trailing vertex is ignored
    ];
    for format in [
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Rgba8UnormSrgb,
    ] {
        let pixels = render(&device, &queue, format, &lines);
        let reds = pixels.iter().filter(|p| p[0] > 200 && p[1] < 50).count();
        let greens = pixels.iter().filter(|p| p[1] > 200 && p[0] < 50).count();
        assert!(reds >= 20, "{format:?}: only {reds} red pixels");
        assert!(greens >= 20, "{format:?}: only {greens} green pixels");
        // Top view: the red X line is horizontal through the middle row.
        let mid = (SIZE / 2) as usize;
        let row_reds = (0..SIZE as usize)
            .filter(|&x| {
                let p = pixels[(mid - 1) * SIZE as usize + x];
                let q = pixels[mid * SIZE as usize + x];
                p[0] > 200 || q[0] > 200
            })
            .count();
        assert!(
            row_reds >= 20,
            "{format:?}: red line not horizontal ({row_reds})"
        );
    }
}

#[test]
fn draws_grid_and_axes_offscreen() {
    let Some((device, queue)) = device() else {
        eprintln!("SKIPPED: no wgpu adapter available");
        return;
    };
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let mut renderer = LineRenderer::new(&device, format, 1);
    let grid = grid_vertices(Vec3::splat(-10.0), Vec3::splat(10.0));
    renderer.set_grid(&device, &queue, &grid);
    assert_eq!(renderer.grid_vertex_count() as usize, grid.len());
    // Growing past the first capacity reallocates without error.
    let many: Vec<Vertex> = (0..5000)
        .map(|i| Vertex::new(Vec3::new(i as f32, 0.0, 0.0), [255; 4]))
        .collect();
    renderer.set_lines(&device, &queue, &many);
    assert_eq!(renderer.line_vertex_count(), 5000);
    // And the grid really draws something via the same pipeline.
    let pixels = render(&device, &queue, format, &grid);
    let lit = pixels
        .iter()
        .filter(|p| p[0] > 20 || p[1] > 20 || p[2] > 20)
        .count();
    assert!(lit > 50, "grid drew only {lit} pixels");
}
