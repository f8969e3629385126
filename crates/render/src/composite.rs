//! Compositing an offscreen [`RenderTarget`] into a render pass that has no depth buffer
//! (egui's): the 3D view is drawn with depth into its own target, then blitted here.

use crate::gpu::{self, Program, Targets};
use crate::offscreen::RenderTarget;

/// WGSL source of the compositor (vertex `vs_main`, fragments `fs_main_gamma_framebuffer` and
/// `fs_main_linear_framebuffer`); public so tests can validate it with naga.
pub const COMPOSITE_WGSL: &str = include_str!("composite.wgsl");

/// Draws a premultiplied, gamma-encoded [`RenderTarget`] over the current viewport.
pub struct Compositor {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
}

impl Compositor {
    /// A compositor for a pass with colour `target_format`, no depth and `sample_count`
    /// samples (egui's render pass).
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        target_format: wgpu::TextureFormat,
        sample_count: u32,
    ) -> Self {
        let layout = gpu::bind_group_layout(
            device,
            "swarf_composite_bind_group_layout",
            wgpu::ShaderStages::FRAGMENT,
            &[
                gpu::texture_2d(wgpu::TextureSampleType::Float { filterable: true }),
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            ],
        );
        let targets = Targets {
            color: target_format,
            depth: None,
            samples: sample_count,
        };
        let blend = Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING);
        let pipeline = Program::new(device, "swarf_composite", COMPOSITE_WGSL, &[&layout])
            .pipeline(device, "main", targets, blend, None);
        // Nearest: the target is drawn one texel per pixel.
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("swarf_composite_sampler"),
            ..Default::default()
        });
        Self {
            pipeline,
            layout,
            sampler,
        }
    }

    /// The bind group that samples `target`; rebuild it when the target is recreated.
    #[must_use]
    pub fn bind(&self, device: &wgpu::Device, target: &RenderTarget) -> wgpu::BindGroup {
        let resources = [
            wgpu::BindingResource::TextureView(target.color_view()),
            wgpu::BindingResource::Sampler(&self.sampler),
        ];
        gpu::bind_group(
            device,
            "swarf_composite_bind_group",
            &self.layout,
            resources,
        )
    }

    /// Draws the bound target over the pass's current viewport (premultiplied "over").
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>, bind_group: &wgpu::BindGroup) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
