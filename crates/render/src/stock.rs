//! The cut stock as a lit surface: the vertex stage reads its height field (an `R32Float` texture,
//! `textureLoad`) to place a grid of quads with walls at the edges, so it works on WebGL2 too.

use std::borrow::Cow;

use glam::DVec3;

use crate::gpu::{self, Program, Targets};

/// WGSL source of the stock shader (vertex `vs_main`, fragments `fs_main_gamma_framebuffer` and
/// `fs_main_linear_framebuffer`); public so tests can validate it with naga.
pub const STOCK_WGSL: &str = include_str!("stock.wgsl");

/// The most cells drawn along a side: a finer field is drawn at the lowest height of each block
/// of cells (WebGL2 guarantees textures of 2048 texels a side).
pub const MAX_STOCK_CELLS: usize = 2048;

/// A stock's height field as [`crate::PathRenderer::set_stock`] draws it.
#[derive(Clone, Copy, Debug)]
pub struct StockSurface<'a> {
    /// The height of each cell (machine Z, mm), row by row from the lowest Y: cell `(i, j)` at
    /// index `j · nx + i`, over the cell's centre.
    pub heights: &'a [f32],
    /// Cells along X and along Y (`nx`, `ny`).
    pub size: (usize, usize),
    /// Side of one square cell, mm.
    pub cell_mm: f64,
    /// The stock's lowest corner, machine mm: the grid's corner in X and Y, the bottom in Z.
    pub min: DVec3,
    /// The uncut stock's top, machine Z.
    pub top: f64,
    /// Machine coordinates of the scene's origin (the drawing's `origin`).
    pub origin: DVec3,
}

/// Contents of the stock's uniform buffer, laid out like the WGSL `Stock`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct StockUniforms {
    first: [f32; 3],
    cell: f32,
    size: [u32; 2],
    bottom: f32,
    top: f32,
}

/// Size of the stock's uniform buffer in bytes.
pub const STOCK_UNIFORMS_SIZE: u64 = size_of::<StockUniforms>() as u64;

/// The heights on the GPU and what draws them.
struct Mesh {
    texture: wgpu::Texture,
    bind_group: wgpu::BindGroup,
    vertices: u32,
}

/// The stock's pipeline, uniforms and, once given, its heights.
pub(crate) struct StockPass {
    /// Made with the first surface, so that a view that never shows the stock compiles no
    /// shader for it.
    pipeline: Option<wgpu::RenderPipeline>,
    /// The path renderer's frame uniforms (group 0) and targets, for the pipeline.
    frame_layout: wgpu::BindGroupLayout,
    targets: Targets,
    layout: wgpu::BindGroupLayout,
    uniforms: wgpu::Buffer,
    mesh: Option<Mesh>,
}

impl StockPass {
    /// The pass for the path renderer's frame uniforms (`frame_layout`, group 0) and its
    /// targets, its pipeline made with the first surface; the surface lies a little behind
    /// lines drawn on it, so a path along a cut floor shows.
    pub(crate) fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        targets: Targets,
    ) -> Self {
        let layout = gpu::bind_group_layout(
            device,
            "swarf_stock_bind_group_layout",
            wgpu::ShaderStages::VERTEX,
            &[
                gpu::uniform(STOCK_UNIFORMS_SIZE),
                gpu::texture_2d(wgpu::TextureSampleType::Float { filterable: false }),
            ],
        );
        StockPass {
            pipeline: None,
            frame_layout: frame_layout.clone(),
            targets,
            layout,
            uniforms: gpu::uniform_buffer(device, "swarf_stock_uniforms", STOCK_UNIFORMS_SIZE),
            mesh: None,
        }
    }

    /// Replaces the surface (`None`, or one whose heights do not fill its size, draws none);
    /// the texture is kept while the size is the same.
    pub(crate) fn set(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        surface: Option<&StockSurface<'_>>,
    ) {
        let Some(s) = surface
            .filter(|s| s.size.0 > 0 && s.size.1 > 0 && s.heights.len() == s.size.0 * s.size.1)
        else {
            self.mesh = None;
            return;
        };
        if self.pipeline.is_none() {
            let bias = wgpu::DepthBiasState {
                constant: 8,
                slope_scale: 1.0,
                clamp: 0.0,
            };
            let depth = Some((true, wgpu::CompareFunction::LessEqual, bias));
            let groups = [&self.frame_layout, &self.layout];
            let program = Program::new(device, "swarf_stock", STOCK_WGSL, &groups);
            self.pipeline = Some(program.pipeline(device, "main", self.targets, None, depth));
        }
        let side = MAX_STOCK_CELLS.min(device.limits().max_texture_dimension_2d as usize);
        let step = s.size.0.max(s.size.1).div_ceil(side.max(1));
        let (heights, (nx, ny)) = coarsened(s.heights, s.size, step);
        let cell = s.cell_mm * step as f64;
        let first = s.min + DVec3::new(cell / 2.0, cell / 2.0, 0.0) - s.origin;
        let uniforms = StockUniforms {
            first: [first.x as f32, first.y as f32, -s.origin.z as f32],
            cell: cell as f32,
            size: [nx as u32, ny as u32],
            bottom: (s.min.z - s.origin.z) as f32,
            top: (s.top - s.origin.z) as f32,
        };
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
        let extent = wgpu::Extent3d {
            width: nx as u32,
            height: ny as u32,
            depth_or_array_layers: 1,
        };
        let mesh = self.mesh.take().filter(|m| m.texture.size() == extent);
        let mesh = mesh.unwrap_or_else(|| {
            let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
            let (size, format) = ([extent.width, extent.height], wgpu::TextureFormat::R32Float);
            let texture = gpu::texture(device, "swarf_stock_heights", size, format, usage);
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            let resources = [
                self.uniforms.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
            ];
            let bind_group =
                gpu::bind_group(device, "swarf_stock_bind_group", &self.layout, resources);
            // Six vertices a quad over the cells and the two rings round them.
            let vertices = u32::try_from((nx + 3) * (ny + 3) * 6).unwrap_or(0);
            Mesh {
                texture,
                bind_group,
                vertices,
            }
        });
        queue.write_texture(
            mesh.texture.as_image_copy(),
            bytemuck::cast_slice(&heights),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(nx as u32 * 4),
                rows_per_image: None,
            },
            extent,
        );
        self.mesh = Some(mesh);
    }

    /// Records the surface's draw; the frame's bind group (group 0) is the caller's.
    pub(crate) fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        if let (Some(mesh), Some(pipeline)) = (&self.mesh, &self.pipeline) {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(1, &mesh.bind_group, &[]);
            pass.draw(0..mesh.vertices, 0..1);
        }
    }
}

/// `heights` over `(nx, ny)` cells with each `step` × `step` block of cells made one at its
/// lowest height, and the new size.
fn coarsened(
    heights: &[f32],
    (nx, ny): (usize, usize),
    step: usize,
) -> (Cow<'_, [f32]>, (usize, usize)) {
    if step <= 1 {
        return (Cow::Borrowed(heights), (nx, ny));
    }
    let (cx, cy) = (nx.div_ceil(step), ny.div_ceil(step));
    let mut out = vec![f32::INFINITY; cx * cy];
    for (j, row) in heights.chunks_exact(nx).enumerate() {
        let base = (j / step) * cx;
        for (i, &h) in row.iter().enumerate() {
            if let Some(cell) = out.get_mut(base + i / step) {
                *cell = cell.min(h);
            }
        }
    }
    (Cow::Owned(out), (cx, cy))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fine_field_is_drawn_at_the_lowest_height_of_each_block() {
        let heights: Vec<f32> = (0..15).map(|i| i as f32).collect();
        let (same, size) = coarsened(&heights, (5, 3), 1);
        assert_eq!((&*same, size), (&heights[..], (5, 3)));
        let (coarse, size) = coarsened(&heights, (5, 3), 2);
        assert_eq!(size, (3, 2));
        assert_eq!(&*coarse, &[0.0, 2.0, 4.0, 10.0, 12.0, 14.0]);
        assert_eq!(STOCK_UNIFORMS_SIZE, 32);
    }
}
