//! Offscreen colour + depth targets, a headless device and RGBA8 read-back for `swarf render` and
//! tests; the backplot draws into a [`RenderTarget`] too, as egui's pass has no depth buffer.

#[cfg(not(target_arch = "wasm32"))]
use {
    crate::{PathLod, PathPoint, StockSurface, ViewParams, segment_bounds},
    glam::Vec2,
    std::sync::Arc,
};

use std::ops::Range;

use crate::path::{DEPTH_FORMAT, PathRenderer};

/// Why an offscreen render failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No GPU adapter (hardware or software such as Mesa lavapipe) is available.
    #[error("no GPU adapter available ({0}); install Mesa's lavapipe (mesa-vulkan-drivers)")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("could not open the GPU device: {0}")]
    Device(String),
    /// The requested image size is zero or beyond the device's limit.
    #[error("image size {width}×{height} is not supported (1 to {max} pixels per side)")]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// Largest side the device supports.
        max: u32,
    },
    /// Copying the image back from the GPU failed.
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
}

/// A device and queue with no window, for offscreen work.
pub struct HeadlessGpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Which adapter it runs on (name, backend, driver), for logs and reports.
    pub info: wgpu::AdapterInfo,
}

impl HeadlessGpu {
    /// Opens the first surfaceless adapter (`WGPU_BACKEND`, `WGPU_POWER_PREF`) with WebGL2's limits
    /// but the adapter's sizes, so huge paths fit; errors with [`RenderError::NoAdapter`] or
    /// [`RenderError::Device`].
    pub async fn new() -> Result<Self, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::from_env()
                    .unwrap_or(wgpu::PowerPreference::HighPerformance),
                force_fallback_adapter: false,
                compatible_surface: None,
                apply_limit_buckets: false,
            })
            .await
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let available = adapter.limits();
        let required_limits = wgpu::Limits {
            max_buffer_size: available.max_buffer_size,
            ..wgpu::Limits::downlevel_webgl2_defaults().using_resolution(available)
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("swarf_headless"),
                required_limits,
                ..Default::default()
            })
            .await
            .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self {
            device,
            queue,
            info,
        })
    }

    /// Draws `stock`, `path` (at the view's detail, see [`crate::PathLod`]) and `grid` into a new
    /// `width`×`height` RGBA8 image over `background` (sRGB), top row first; errors with
    /// [`RenderError::Size`] or [`RenderError::Readback`].
    #[cfg(not(target_arch = "wasm32"))]
    pub fn render_rgba8(
        &self,
        stock: Option<&StockSurface<'_>>,
        path: &[PathPoint],
        grid: &[PathPoint],
        params: &ViewParams,
        (width, height): (u32, u32),
        background: [u8; 4],
    ) -> Result<Vec<u8>, RenderError> {
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let target = RenderTarget::new(&self.device, width, height, format)?;
        let mut renderer = PathRenderer::new(&self.device, format, Some(DEPTH_FORMAT), 1);
        renderer.set_stock(&self.device, &self.queue, stock);
        renderer.set_grid(&self.device, &self.queue, grid);
        let params = ViewParams {
            viewport_px: Vec2::new(width as f32, height as f32),
            ..params.clone()
        };
        let bounds = segment_bounds(path, 0..path.len());
        let mut lod = PathLod::new(Arc::new(path.to_vec()), bounds);
        let params = lod.prepare(&mut renderer, &self.device, &self.queue, &params, &[]);
        renderer.prepare(&self.queue, &params);
        let label = Some("swarf_render_rgba8");
        let mut encoder =
            (self.device).create_command_encoder(&wgpu::CommandEncoderDescriptor { label });
        // Gamma-space target: the clear colour is stored as given.
        let [r, g, b, a] = background.map(|c| f64::from(c) / 255.0);
        target.draw(&mut encoder, wgpu::Color { r, g, b, a }, &renderer);
        self.queue.submit([encoder.finish()]);
        target.read_rgba8(&self.device, &self.queue)
    }
}

/// A colour texture with a matching [`DEPTH_FORMAT`] depth buffer, one sample.
pub struct RenderTarget {
    color: wgpu::Texture,
    color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
}

impl RenderTarget {
    /// A `width`×`height` target of `format` (8-bit RGBA for [`Self::read_rgba8`]); errors with
    /// [`RenderError::Size`] when a side is zero or larger than the device allows.
    pub fn new(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> Result<Self, RenderError> {
        let max = device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::Size { width, height, max });
        }
        let texture = |label, format, usage| {
            crate::gpu::texture(device, label, [width, height], format, usage)
        };
        let target = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let copy = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC;
        let color = texture("swarf_target_color", format, target | copy);
        let depth = texture("swarf_target_depth", DEPTH_FORMAT, target);
        let color_view = color.create_view(&wgpu::TextureViewDescriptor::default());
        let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
        Ok(Self {
            color,
            color_view,
            depth_view,
        })
    }

    /// Width and height in pixels.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.color.width(), self.color.height())
    }

    /// The colour texture's view (e.g. to composite it, see [`crate::Compositor`]).
    #[must_use]
    pub fn color_view(&self) -> &wgpu::TextureView {
        &self.color_view
    }

    /// Records a pass that clears colour to `background` (premultiplied, in the target's
    /// encoding) and depth to 1, then paints `renderer` (made for this target's format,
    /// [`DEPTH_FORMAT`] and one sample, with its uniforms already written).
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        background: wgpu::Color,
        renderer: &PathRenderer,
    ) {
        self.draw_part(encoder, Some(background), renderer, 0..renderer.work());
    }

    /// Records a pass that paints the part `part` of `renderer`'s work (see
    /// [`PathRenderer::paint_part`]), clearing colour to `clear` and depth to 1 first when
    /// `clear` is given (the first part), else drawing over what earlier parts drew.
    pub fn draw_part(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        clear: Option<wgpu::Color>,
        renderer: &PathRenderer,
        part: Range<u64>,
    ) {
        let (load, depth_load) = match clear {
            Some(background) => (wgpu::LoadOp::Clear(background), wgpu::LoadOp::Clear(1.0)),
            None => (wgpu::LoadOp::Load, wgpu::LoadOp::Load),
        };
        // Depth is kept only for the parts still to come.
        let depth_store = if part.end >= renderer.work() {
            wgpu::StoreOp::Discard
        } else {
            wgpu::StoreOp::Store
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("swarf_offscreen_pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: depth_load,
                    store: depth_store,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        renderer.paint_part(&mut pass, part);
    }

    /// Copies the colour texture into packed RGBA8 rows (top first, BGRA swizzled), waiting for the
    /// GPU; [`RenderError::Readback`] when mapping fails or the device is lost.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn read_rgba8(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<u8>, RenderError> {
        // Bytes per pixel of the RGBA8 formats the targets use.
        const BYTES_PER_PIXEL: u32 = 4;
        let (width, height) = self.size();
        let row = (width * BYTES_PER_PIXEL).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("swarf_readback"),
            size: u64::from(row) * u64::from(height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("swarf_readback"),
        });
        encoder.copy_texture_to_buffer(
            self.color.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: None,
                },
            },
            self.color.size(),
        );
        queue.submit([encoder.finish()]);
        let (sender, receiver) = std::sync::mpsc::channel();
        (readback.slice(..)).map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        fn failed(e: impl std::fmt::Display) -> RenderError {
            RenderError::Readback(e.to_string())
        }
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(failed)?;
        receiver.recv().map_err(failed)?.map_err(failed)?;
        let bgra = matches!(
            self.color.format(),
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        );
        let width_bytes = (width * BYTES_PER_PIXEL) as usize;
        let data = readback.slice(..).get_mapped_range().map_err(failed)?;
        let lines = data.chunks_exact(row as usize).map(|l| &l[..width_bytes]);
        let mut pixels = lines.collect::<Vec<_>>().concat();
        drop(data);
        readback.unmap();
        if bgra {
            for p in pixels.chunks_exact_mut(4) {
                p.swap(0, 2);
            }
        }
        Ok(pixels)
    }
}
