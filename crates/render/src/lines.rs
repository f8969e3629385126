//! Line-list renderer: one pipeline, one uniform, a grid batch and a toolpath batch.

use std::borrow::Cow;

use glam::{Mat4, Vec3};

/// WGSL source of the line shader (vertex `vs_main`, fragments `fs_main_gamma_framebuffer`
/// and `fs_main_linear_framebuffer`); public so tests can validate it with naga.
pub const LINES_WGSL: &str = include_str!("lines.wgsl");

/// One line-list vertex: position relative to the caller's origin and an sRGB colour.
///
/// Two consecutive vertices make one segment. The colour is gamma-encoded with straight
/// (unpremultiplied) alpha, like egui's `Color32::from_rgba_unmultiplied`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Position in world units, relative to the origin chosen by the caller.
    pub position: [f32; 3],
    /// sRGB colour with straight alpha, read by the shader as `Unorm8x4`.
    pub color: [u8; 4],
}

const _: () = assert!(size_of::<Vertex>() == 16);

impl Vertex {
    /// A vertex at `position` with `color` (sRGB, straight alpha).
    #[must_use]
    pub fn new(position: Vec3, color: [u8; 4]) -> Self {
        Self {
            position: position.to_array(),
            color,
        }
    }
}

/// Size of one vertex in bytes.
const VERTEX_SIZE: u64 = size_of::<Vertex>() as u64;

/// Vertex attributes matching [`Vertex`]: location 0 position, location 1 colour.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Unorm8x4];

/// Contents of the uniform buffer. Its size is a multiple of 16 bytes, as WebGL2
/// (std140) and the downlevel limits require.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct Uniforms {
    view_proj: [[f32; 4]; 4],
}

const _: () = assert!(size_of::<Uniforms>().is_multiple_of(16));

/// A growable GPU vertex buffer holding one line list.
struct LineBatch {
    label: &'static str,
    buffer: Option<wgpu::Buffer>,
    /// Capacity of `buffer` in vertices.
    capacity: u64,
    /// Vertices to draw (always even).
    count: u32,
}

impl LineBatch {
    fn new(label: &'static str) -> Self {
        Self {
            label,
            buffer: None,
            capacity: 0,
            count: 0,
        }
    }

    /// Uploads `vertices`, growing the buffer when needed. Input beyond the device's maximum
    /// buffer size is dropped (the count says what was kept).
    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, vertices: &[Vertex]) {
        let max_vertices = (device.limits().max_buffer_size / VERTEX_SIZE).min(u64::from(u32::MAX));
        // Whole segments only.
        let wanted = (vertices.len() as u64).min(max_vertices) & !1;
        if wanted == 0 {
            self.count = 0;
            return;
        }
        if self.buffer.is_none() || self.capacity < wanted {
            let capacity = wanted
                .next_power_of_two()
                .clamp(1024, max_vertices.max(wanted));
            self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size: capacity * VERTEX_SIZE,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
            self.capacity = capacity;
        }
        if let Some(buffer) = &self.buffer {
            // `wanted` fits in u32, hence in usize.
            let kept = &vertices[..usize::try_from(wanted).unwrap_or(0)];
            queue.write_buffer(buffer, 0, bytemuck::cast_slice(kept));
            self.count = u32::try_from(wanted).unwrap_or(0);
        }
    }

    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if self.count == 0 {
            return;
        }
        if let Some(buffer) = &self.buffer {
            pass.set_vertex_buffer(0, buffer.slice(..u64::from(self.count) * VERTEX_SIZE));
            pass.draw(0..self.count, 0..1);
        }
    }
}

/// Draws line lists (the toolpath, then the grid and axes under it) with one pipeline.
///
/// It has no depth attachment (egui's render pass has none by default) and uses only a
/// uniform buffer and vertex attributes, so it works on WebGPU, native and WebGL2 alike.
pub struct LineRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform_buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    grid: LineBatch,
    lines: LineBatch,
}

impl LineRenderer {
    /// Creates the pipeline for a colour target of `color_format` with `sample_count` MSAA
    /// samples (1 for none; must match the render pass it will paint into).
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        color_format: wgpu::TextureFormat,
        sample_count: u32,
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("swarf_lines_shader"),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(LINES_WGSL)),
        });

        let uniform_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("swarf_lines_uniforms"),
            size: size_of::<Uniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // wgpu zero-initialises buffers: a zero matrix draws nothing until `prepare`.

        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("swarf_lines_bind_group_layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size_of::<Uniforms>() as u64),
                },
                count: None,
            }],
        });

        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("swarf_lines_bind_group"),
            layout: &bind_group_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform_buffer.as_entire_binding(),
            }],
        });

        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("swarf_lines_pipeline_layout"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });

        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("swarf_lines_pipeline"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: VERTEX_SIZE,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &VERTEX_ATTRIBUTES,
                })],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::LineList,
                strip_index_format: None,
                front_face: wgpu::FrontFace::default(),
                cull_mode: None,
                unclipped_depth: false,
                polygon_mode: wgpu::PolygonMode::Fill,
                conservative: false,
            },
            depth_stencil: None,
            multisample: wgpu::MultisampleState {
                count: sample_count.max(1),
                mask: !0,
                alpha_to_coverage_enabled: false,
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(if color_format.is_srgb() {
                    "fs_main_linear_framebuffer"
                } else {
                    "fs_main_gamma_framebuffer"
                }),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: color_format,
                    blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });

        Self {
            pipeline,
            uniform_buffer,
            bind_group,
            grid: LineBatch::new("swarf_grid_vertices"),
            lines: LineBatch::new("swarf_toolpath_vertices"),
        }
    }

    /// Replaces the toolpath line list, reusing the vertex buffer when it is big enough.
    /// An empty slice draws nothing; an odd trailing vertex is ignored.
    pub fn set_lines(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, vertices: &[Vertex]) {
        self.lines.upload(device, queue, vertices);
    }

    /// Replaces the grid/axes line list (see [`crate::grid_vertices`]), drawn under the toolpath.
    pub fn set_grid(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, vertices: &[Vertex]) {
        self.grid.upload(device, queue, vertices);
    }

    /// Number of toolpath vertices that will be drawn (the device may cap huge inputs).
    #[must_use]
    pub fn line_vertex_count(&self) -> u32 {
        self.lines.count
    }

    /// Number of grid/axes vertices that will be drawn.
    #[must_use]
    pub fn grid_vertex_count(&self) -> u32 {
        self.grid.count
    }

    /// Writes the view-projection matrix used by the next [`Self::paint`].
    ///
    /// There is one uniform per renderer, so two views painted in the same frame share the
    /// last matrix written; use one `LineRenderer` per simultaneously visible view.
    pub fn prepare(&self, queue: &wgpu::Queue, view_proj: Mat4) {
        let uniforms = Uniforms {
            view_proj: view_proj.to_cols_array_2d(),
        };
        queue.write_buffer(&self.uniform_buffer, 0, bytemuck::bytes_of(&uniforms));
    }

    /// Records the draws (grid and axes, then toolpath) into `pass`; viewport and scissor are
    /// the caller's (egui sets them to the callback rectangle).
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        self.grid.draw(pass);
        self.lines.draw(pass);
    }
}
