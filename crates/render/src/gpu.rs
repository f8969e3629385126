//! The wgpu set-up the passes share (path, stock, compositor): shaders and their pipelines,
//! bind group layouts and uniform buffers, with the options all of them use.

use std::borrow::Cow;

use wgpu::{
    BindGroupLayout, BindingType, BlendState, CompareFunction, DepthBiasState, Device,
    ShaderStages, TextureFormat, TextureSampleType,
};

/// The attachments of the render pass a pipeline paints into; all must match it.
#[derive(Clone, Copy)]
pub(crate) struct Targets {
    pub color: TextureFormat,
    /// `None` when the pass has no depth buffer (egui's).
    pub depth: Option<TextureFormat>,
    pub samples: u32,
}

/// A WGSL module and the pipeline layout of its bind groups.
pub(crate) struct Program {
    label: &'static str,
    module: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
}

impl Program {
    /// Compiles `wgsl` for bind groups `groups` (group 0 first).
    pub fn new(
        device: &Device,
        label: &'static str,
        wgsl: &'static str,
        groups: &[&BindGroupLayout],
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(wgsl)),
        });
        let groups: Vec<_> = groups.iter().copied().map(Some).collect();
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &groups,
            immediate_size: 0,
        });
        Self {
            label,
            module,
            layout,
        }
    }

    /// A triangle-list pipeline of `vs_main` and `fs_{part}_linear_framebuffer` on a self-encoding
    /// sRGB target, else `fs_{part}_gamma_framebuffer`; `depth` applies if the pass has depth.
    pub fn pipeline(
        &self,
        device: &Device,
        part: &str,
        targets: Targets,
        blend: Option<BlendState>,
        depth: Option<(bool, CompareFunction, DepthBiasState)>,
    ) -> wgpu::RenderPipeline {
        let encoding = if targets.color.is_srgb() {
            "linear"
        } else {
            "gamma"
        };
        let depth_stencil = targets
            .depth
            .zip(depth)
            .map(|(format, (write, compare, bias))| wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(write),
                depth_compare: Some(compare),
                stencil: wgpu::StencilState::default(),
                bias,
            });
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(self.label),
            layout: Some(&self.layout),
            vertex: wgpu::VertexState {
                module: &self.module,
                entry_point: Some("vs_main"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil,
            multisample: wgpu::MultisampleState {
                count: targets.samples.max(1),
                mask: !0,
                alpha_to_coverage_enabled: false,
            },
            fragment: Some(wgpu::FragmentState {
                module: &self.module,
                entry_point: Some(&format!("fs_{part}_{encoding}_framebuffer")),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: targets.color,
                    blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}

/// A bind group layout of `types` at bindings 0, 1, … in order, each seen by `visibility`.
pub(crate) fn bind_group_layout(
    device: &Device,
    label: &str,
    visibility: ShaderStages,
    types: &[BindingType],
) -> BindGroupLayout {
    let entries: Vec<_> = (0..)
        .zip(types)
        .map(|(binding, &ty)| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty,
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    })
}

/// A bind group of `layout` with `resources` at bindings 0, 1, … in order.
pub(crate) fn bind_group<'a>(
    device: &Device,
    label: &str,
    layout: &BindGroupLayout,
    resources: impl IntoIterator<Item = wgpu::BindingResource<'a>>,
) -> wgpu::BindGroup {
    let entries: Vec<_> = (0..)
        .zip(resources)
        .map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// The binding of a uniform buffer of `size` bytes.
pub(crate) fn uniform(size: u64) -> BindingType {
    BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: wgpu::BufferSize::new(size),
    }
}

/// The binding of a single-sampled 2D texture.
pub(crate) fn texture_2d(sample_type: TextureSampleType) -> BindingType {
    BindingType::Texture {
        sample_type,
        view_dimension: wgpu::TextureViewDimension::D2,
        multisampled: false,
    }
}

/// A single-sampled 2D texture of one mip level, `[width, height]` texels.
pub(crate) fn texture(
    device: &Device,
    label: &str,
    [width, height]: [u32; 2],
    format: TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A uniform buffer of `size` bytes, written with `Queue::write_buffer`.
pub(crate) fn uniform_buffer(device: &Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
