//! Segment renderer: 16-byte points in a texture, a screen-space quad (vertices `6i..6i + 6`) per
//! segment, no instancing (software rasterisers pay per instance); [`PathPoint::PEN_UP`] starts a
//! polyline. Long paths span textures sharing seam points, each with its first segment's number.

use std::ops::Range;

use glam::{Mat4, Vec2, Vec3};

use crate::camera::finite_or;
use crate::gpu::{self, Program, Targets};
use crate::stock::{StockPass, StockSurface};

/// WGSL source of the path shader (vertex `vs_main`, fragments `fs_main_gamma_framebuffer`
/// and `fs_main_linear_framebuffer`); public so tests can validate it with naga.
pub const PATH_WGSL: &str = include_str!("path.wgsl");

/// Size of one [`PathPoint`] in bytes, which is also the GPU cost of one segment.
pub const POINT_SIZE: u64 = size_of::<PathPoint>() as u64;

/// Palette slot of the highlight colour (the selected block's segments).
pub const HIGHLIGHT_SLOT: usize = 15;

/// Depth format of the offscreen targets and the pipelines that draw into them: supported
/// everywhere, WebGL2 included.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Declares [`Kind`] from one row a kind, in palette order: the variant, what it is and its
/// default colour.
macro_rules! kinds {
    ($($variant:ident $doc:literal $color:expr;)*) => {
        /// What a segment is; selects its colour (palette slot), width and dash pattern.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u8)]
        pub enum Kind {
            $(#[doc = $doc] $variant,)*
        }

        impl Kind {
            /// Every kind, in palette order.
            pub const ALL: [Kind; [$($doc),*].len()] = [$(Kind::$variant),*];

            /// The default colour of each kind, in palette order.
            const COLORS: [[u8; 4]; [$($doc),*].len()] = [$($color),*];
        }
    };
}

kinds! {
    Rapid       "Rapid positioning (G00): thin and dashed."                            RAPID_COLOR;
    Feed        "Straight cutting move (G01)."                                         FEED_COLOR;
    Arc         "Chord of a circular or helical cutting move (G02/G03)."               ARC_COLOR;
    Plunge      "Drilling plunge into the hole."                                       [255, 90, 90, 255];
    Retract     "Retract out of a hole."                                               [255, 160, 210, 255];
    Cycle       "Any other move of a canned cycle."                                    [190, 130, 255, 255];
    Compensated "Contour with cutter-radius compensation applied (where the tool centre goes)." [240, 240, 240, 255];
    Programmed  "Contour as programmed (the overlay shown beside the compensated one)." PROGRAMMED_COLOR;
    Grid        "Ordinary grid line."                                                  [128, 128, 128, 60];
    GridMajor   "Every tenth grid line."                                               GRID_MAJOR_COLOR;
    AxisX       "The X axis."                                                          [230, 60, 60, 255];
    AxisY       "The Y axis."                                                          [60, 200, 60, 255];
    AxisZ       "The Z axis."                                                          Z_AXIS_COLOR;
    Boundary    "Machine travel box and other reference outlines."                     [200, 200, 200, 110];
    Zone        "A programmable stroke limit (G22): protected zone or soft limits."    ZONE_COLOR;
}

impl Kind {
    /// The kind stored as `bits`, if any.
    #[must_use]
    pub fn from_bits(bits: u8) -> Option<Kind> {
        Kind::ALL.get(usize::from(bits)).copied()
    }

    /// This kind's bit in [`ViewParams::hidden_kinds`].
    #[must_use]
    pub fn mask(self) -> u32 {
        1 << (self as u32)
    }

    /// Whether the kind is part of a toolpath (not grid, axes or outlines).
    #[must_use]
    pub fn is_motion(self) -> bool {
        (self as u8) < (Kind::Grid as u8)
    }
}

/// One point of the polyline stream: position relative to the scene origin and a packed word
/// (bits 0–7 kind of the segment ending here, 8–15 flags, 16–31 colour index).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PathPoint {
    /// Position in world units, relative to the scene origin (f32 keeps GPU maths cheap).
    pub position: [f32; 3],
    /// Kind, flags and colour index of the segment that ends at this point.
    pub packed: u32,
}

const _: () = assert!(size_of::<PathPoint>() == 16);

impl PathPoint {
    /// Flag: no segment ends at this point (it starts a new polyline).
    pub const PEN_UP: u32 = 1 << 8;
    /// Flag: the segment ending here is highlighted.
    pub const HIGHLIGHT: u32 = 1 << 9;

    /// The end of a segment of `kind` at `position`.
    #[must_use]
    pub fn new(position: Vec3, kind: Kind) -> Self {
        Self {
            position: position.to_array(),
            packed: kind as u32,
        }
    }

    /// The first point of a polyline: no segment arrives here.
    #[must_use]
    pub fn pen_up(position: Vec3) -> Self {
        Self {
            position: position.to_array(),
            packed: Self::PEN_UP,
        }
    }

    /// The same point with colour index `index` (used with [`ColorMode::ByIndex`], e.g. the
    /// tool number).
    #[must_use]
    pub fn with_color_index(self, index: u16) -> Self {
        Self {
            packed: (self.packed & 0xffff) | (u32::from(index) << 16),
            ..self
        }
    }

    /// The same point with the highlight flag set or cleared.
    #[must_use]
    pub fn with_highlight(self, on: bool) -> Self {
        let packed = (self.packed & !Self::HIGHLIGHT) | (u32::from(on) * Self::HIGHLIGHT);
        Self { packed, ..self }
    }

    /// Position as a vector.
    #[must_use]
    pub fn position(&self) -> Vec3 {
        Vec3::from_array(self.position)
    }

    /// Kind of the segment ending here (`None` for unknown bits).
    #[must_use]
    pub fn kind(&self) -> Option<Kind> {
        Kind::from_bits((self.packed & 0xff) as u8)
    }

    /// Whether no segment ends here.
    #[must_use]
    pub fn is_pen_up(&self) -> bool {
        self.packed & Self::PEN_UP != 0
    }

    /// Colour index (bits 16–31).
    #[must_use]
    pub fn color_index(&self) -> u16 {
        (self.packed >> 16) as u16
    }
}

/// sRGB bytes with straight alpha to the shader's palette floats.
#[must_use]
pub fn srgba(color: [u8; 4]) -> [f32; 4] {
    color.map(|c| f32::from(c) / 255.0)
}

/// Colours (sRGB with straight alpha, like egui's `Color32` / 255) by kind and by index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Palette {
    /// Colour of each [`Kind`] (indexed by its value); slot [`HIGHLIGHT_SLOT`] is the
    /// highlight colour.
    pub kinds: [[f32; 4]; 16],
    /// Colours for [`ColorMode::ByIndex`] (index modulo 16), e.g. one per tool.
    pub indexed: [[f32; 4]; 16],
}

/// Default colour of rapid moves: amber.
pub const RAPID_COLOR: [u8; 4] = [235, 170, 40, 255];
/// Default colour of straight cutting moves: blue.
pub const FEED_COLOR: [u8; 4] = [80, 200, 255, 255];
/// Default colour of arc cutting moves: green.
pub const ARC_COLOR: [u8; 4] = [120, 230, 140, 255];
/// Default colour of the programmed contour overlay: magenta, drawn with short dashes, so it
/// never reads as a grid line even where it runs along one.
pub const PROGRAMMED_COLOR: [u8; 4] = [255, 90, 240, 235];
/// Colour of every tenth grid line.
pub const GRID_MAJOR_COLOR: [u8; 4] = [128, 128, 128, 130];
/// Colour of the Z axis (blue).
pub const Z_AXIS_COLOR: [u8; 4] = [70, 110, 255, 255];
/// Colour of G22 stroke limits (protected zones, soft limits).
pub const ZONE_COLOR: [u8; 4] = [255, 90, 70, 200];
/// Colour of highlighted (selected) segments: white-yellow.
pub const HIGHLIGHT_COLOR: [u8; 4] = [255, 250, 170, 255];

impl Default for Palette {
    fn default() -> Self {
        let mut kinds = [srgba([255, 0, 255, 255]); 16];
        for (kind, color) in kinds.iter_mut().zip(Kind::COLORS) {
            *kind = srgba(color);
        }
        kinds[HIGHLIGHT_SLOT] = srgba(HIGHLIGHT_COLOR);
        // Distinct hues for colouring by tool, as 0xRRGGBB.
        let indexed = [
            0x50c8ff, 0xff963c, 0x78e68c, 0xf064a0, 0xc8c85a, 0x9678ff, 0x3cdcd2, 0xff6e64,
            0xaae63c, 0xe696ff, 0x6496ff, 0xffd278, 0x8cffc8, 0xff82c8, 0xb4b4b4, 0xffffff,
        ]
        .map(|rgb: u32| srgba(((rgb << 8) | 0xff).to_be_bytes()));
        Self { kinds, indexed }
    }
}

/// How motion segments are coloured (the shader's `color_mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorMode {
    /// By [`Kind`] (rapid, feed, arc, …).
    #[default]
    ByKind = 0,
    /// By each point's colour index (e.g. the tool), through [`Palette::indexed`].
    ByIndex = 1,
}

/// Everything the shader needs for one frame besides the points.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewParams {
    /// World (relative to the scene origin) to clip space, depth 0..1 (see
    /// [`crate::OrbitCamera::view_proj`]).
    pub view_proj: Mat4,
    /// Size of the render target in physical pixels.
    pub viewport_px: Vec2,
    /// Width of cutting moves in pixels.
    pub line_width_px: f32,
    /// Width of rapids in pixels.
    pub rapid_width_px: f32,
    /// Width of grid lines in pixels.
    pub grid_width_px: f32,
    /// Extra width of highlighted segments in pixels.
    pub highlight_extra_px: f32,
    /// Rapid dash pattern: lit pixels, then dark pixels.
    pub dash_px: Vec2,
    /// Opacity of the remainder (segments after the playback position), 0..1.
    pub dim_alpha: f32,
    /// Seconds, for animations.
    pub time_secs: f32,
    /// Playback position: toolpath segments with an index at or after it are drawn dimmed;
    /// `None` draws everything as executed. The grid and marks are never dimmed.
    pub executed_segments: Option<u32>,
    /// Toolpath segment indices drawn highlighted (the selected block), besides flagged
    /// points; the grid and marks are never highlighted by index.
    pub highlight: Range<u32>,
    /// Kinds not drawn: OR of [`Kind::mask`] (e.g. hide the programmed contour).
    pub hidden_kinds: u32,
    /// Colour by kind or by index.
    pub color_mode: ColorMode,
    /// The colours.
    pub palette: Palette,
}

impl Default for ViewParams {
    fn default() -> Self {
        Self {
            view_proj: Mat4::IDENTITY,
            viewport_px: Vec2::new(1.0, 1.0),
            line_width_px: 1.6,
            rapid_width_px: 1.2,
            grid_width_px: 1.0,
            highlight_extra_px: 2.0,
            dash_px: Vec2::new(6.0, 4.0),
            dim_alpha: 0.25,
            time_secs: 0.0,
            executed_segments: None,
            highlight: 0..0,
            hidden_kinds: 0,
            color_mode: ColorMode::ByKind,
            palette: Palette::default(),
        }
    }
}

impl ViewParams {
    /// Multiplies every width and the dash pattern by `scale` (pixels per point on HiDPI).
    #[must_use]
    pub fn scaled(self, scale: f32) -> Self {
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            1.0
        };
        Self {
            line_width_px: self.line_width_px * scale,
            rapid_width_px: self.rapid_width_px * scale,
            grid_width_px: self.grid_width_px * scale,
            highlight_extra_px: self.highlight_extra_px * scale,
            dash_px: self.dash_px * scale,
            ..self
        }
    }
}

/// Contents of the uniform buffer, laid out like the WGSL `Uniforms` (std140-compatible: a
/// multiple of 16 bytes, the palette array at a 16-byte boundary).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct Uniforms {
    view_proj: [[f32; 4]; 4],
    viewport: [f32; 2],
    line_width: f32,
    rapid_width: f32,
    grid_width: f32,
    highlight_extra: f32,
    dash_on: f32,
    dash_off: f32,
    dim_alpha: f32,
    time: f32,
    executed_end: u32,
    highlight_start: u32,
    highlight_end: u32,
    hidden_kinds: u32,
    color_mode: u32,
    _pad0: u32,
    palette: [[f32; 4]; 32],
}

/// Size of the uniform buffer in bytes.
pub const UNIFORMS_SIZE: u64 = size_of::<Uniforms>() as u64;

/// One draw call's uniforms, laid out like the WGSL `Draw`: its first segment's number in the
/// stream and whether it is the toolpath (only that is highlighted or dimmed by number).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct DrawUniforms {
    segment_base: u32,
    path: u32,
    _pad: [u32; 2],
}

/// Size of the per-draw uniform buffer in bytes.
pub const DRAW_UNIFORMS_SIZE: u64 = size_of::<DrawUniforms>() as u64;

const _: () = assert!(size_of::<DrawUniforms>() == 16);

const _: () = assert!(size_of::<Uniforms>() == 640);

impl Uniforms {
    fn new(params: &ViewParams) -> Self {
        let mut palette = [[0.0; 4]; 32];
        palette[..16].copy_from_slice(&params.palette.kinds);
        palette[16..].copy_from_slice(&params.palette.indexed);
        let view_proj = (Some(params.view_proj).filter(Mat4::is_finite)).unwrap_or(Mat4::ZERO);
        Self {
            view_proj: view_proj.to_cols_array_2d(),
            viewport: params
                .viewport_px
                .to_array()
                .map(|v| finite_or(v, 1.0).max(1.0)),
            line_width: finite_or(params.line_width_px, 1.0).clamp(0.0, 64.0),
            rapid_width: finite_or(params.rapid_width_px, 1.0).clamp(0.0, 64.0),
            grid_width: finite_or(params.grid_width_px, 1.0).clamp(0.0, 64.0),
            highlight_extra: finite_or(params.highlight_extra_px, 0.0).clamp(0.0, 64.0),
            dash_on: finite_or(params.dash_px.x, 6.0).max(0.0),
            dash_off: finite_or(params.dash_px.y, 0.0).max(0.0),
            dim_alpha: finite_or(params.dim_alpha, 1.0).clamp(0.0, 1.0),
            time: finite_or(params.time_secs, 0.0),
            executed_end: params.executed_segments.unwrap_or(u32::MAX),
            highlight_start: params.highlight.start,
            highlight_end: params.highlight.end,
            hidden_kinds: params.hidden_kinds,
            color_mode: params.color_mode as u32,
            _pad0: 0,
            palette,
        }
    }
}

/// Most points in one row of a point texture (each point one `Rgba32Uint` texel).
const ROW_POINTS: u64 = 4096;

/// Vertices of one segment's quad: two triangles (a list, so no segment joins the next).
const QUAD_VERTICES: u32 = 6;

/// Work of one frame of a picture drawn over several ([`PathRenderer::paint_part`]): a software
/// rasteriser draws this many segment passes in a few ms, so the frame stays short.
pub const FRAME_WORK: u64 = 2048;

/// One texture of a [`PointBatch`], holding `count` points of the stream, a row at a time.
struct Chunk {
    /// The stream's index of the texture's first point (and first segment).
    first: u64,
    texture: wgpu::Texture,
    /// The chunk's [`DrawUniforms`] and the bind group (group 1) that binds them and the
    /// texture.
    draw_buffer: wgpu::Buffer,
    draw_bind_group: wgpu::BindGroup,
    /// Points uploaded.
    count: u64,
}

impl Chunk {
    /// Capacity of the texture in points.
    fn capacity(&self) -> u64 {
        u64::from(self.texture.width()) * u64::from(self.texture.height())
    }

    /// Draws the stream's segments `part` that this texture holds.
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>, part: &Range<u64>) {
        let end = self.first + self.count.saturating_sub(1);
        let local = |i: u64| {
            let i = i.clamp(self.first, end) - self.first;
            u32::try_from(i)
                .unwrap_or(u32::MAX)
                .saturating_mul(QUAD_VERTICES)
        };
        let vertices = local(part.start)..local(part.end);
        if vertices.is_empty() {
            return;
        }
        pass.set_bind_group(1, &self.draw_bind_group, &[]);
        // Vertex v draws a corner of segment v / 6, which reads points v / 6 and v / 6 + 1.
        pass.draw(vertices, 0..1);
    }
}

/// Copies `points` into the first texels of `texture` (rows `width` texels long).
fn write_points(queue: &wgpu::Queue, texture: &wgpu::Texture, points: &[PathPoint]) {
    let width = texture.width() as usize;
    let whole = points.len() / width * width;
    let (rows, rest) = points.split_at(whole);
    for (part, row) in [(rows, 0), (rest, whole / width)] {
        if part.is_empty() {
            continue;
        }
        let texels = part.len().min(width);
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                origin: wgpu::Origin3d {
                    y: u32::try_from(row).unwrap_or(u32::MAX),
                    ..wgpu::Origin3d::ZERO
                },
                ..texture.as_image_copy()
            },
            bytemuck::cast_slice(part),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: u32::try_from(texels as u64 * POINT_SIZE).ok(),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: u32::try_from(texels).unwrap_or(u32::MAX),
                height: u32::try_from(part.len() / texels).unwrap_or(u32::MAX),
                depth_or_array_layers: 1,
            },
        );
    }
}

/// A polyline stream on the GPU in textures the vertex stage reads (WebGL2 has no storage
/// buffers), split into several overlapping by one point when one texture is too small.
struct PointBatch {
    label: &'static str,
    /// Whether the stream is the toolpath (highlight and playback ranges apply to it).
    path: bool,
    chunks: Vec<Chunk>,
    /// Points uploaded in all.
    count: u64,
    /// Largest points per texture, when lower than the device's (tests use a small one).
    chunk_limit: Option<u64>,
}

impl PointBatch {
    fn new(label: &'static str, path: bool) -> Self {
        Self {
            label,
            path,
            chunks: Vec::new(),
            count: 0,
            chunk_limit: None,
        }
    }

    /// Texels per row and points per texture on `device` (at least two, so every texture
    /// holds a segment; at most what `u32` vertices draw).
    fn shape(&self, device: &wgpu::Device) -> (u64, u64) {
        let side = u64::from(device.limits().max_texture_dimension_2d).max(2);
        let width = ROW_POINTS.min(side);
        let max = (width * side).min(u64::from(u32::MAX / QUAD_VERTICES));
        let per = self.chunk_limit.map_or(max, |l| l.min(max)).max(2);
        (width.min(per), per)
    }

    /// Uploads `points`, reusing each texture whose size fits and reallocating those too small
    /// or far too big; `layout` is the per-draw bind group's (group 1).
    fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layout: &wgpu::BindGroupLayout,
        points: &[PathPoint],
    ) {
        let total = points.len() as u64;
        if total < 2 {
            self.count = 0;
            self.chunks.clear();
            return;
        }
        let (width, per) = self.shape(device);
        // Chunk k holds points k·(per − 1) .. k·(per − 1) + per: one point shared at each seam.
        let stride = per - 1;
        let n_chunks = (total - 1).div_ceil(stride);
        let mut old = std::mem::take(&mut self.chunks).into_iter();
        for k in 0..n_chunks {
            let first = k * stride;
            let count = (total - first).min(per);
            let reuse = old.next().filter(|c| {
                u64::from(c.texture.width()) == width
                    && c.capacity() >= count
                    && c.capacity() <= 2 * count + width
            });
            let chunk = if let Some(c) = reuse {
                Chunk { first, count, ..c }
            } else {
                let size =
                    [width, count.div_ceil(width)].map(|n| u32::try_from(n).unwrap_or(u32::MAX));
                let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
                let format = wgpu::TextureFormat::Rgba32Uint;
                let texture = gpu::texture(device, self.label, size, format, usage);
                let draw_buffer =
                    gpu::uniform_buffer(device, "swarf_draw_uniforms", DRAW_UNIFORMS_SIZE);
                let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
                let resources = [
                    draw_buffer.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&view),
                ];
                let draw_bind_group =
                    gpu::bind_group(device, "swarf_draw_bind_group", layout, resources);
                Chunk {
                    first,
                    texture,
                    draw_buffer,
                    draw_bind_group,
                    count,
                }
            };
            let draw = DrawUniforms {
                segment_base: u32::try_from(first).unwrap_or(u32::MAX),
                path: u32::from(self.path),
                _pad: [0; 2],
            };
            queue.write_buffer(&chunk.draw_buffer, 0, bytemuck::bytes_of(&draw));
            let range = usize::try_from(first).unwrap_or(usize::MAX)
                ..usize::try_from(first + count).unwrap_or(usize::MAX);
            if let Some(slice) = points.get(range) {
                write_points(queue, &chunk.texture, slice);
            }
            self.chunks.push(chunk);
        }
        self.count = total;
    }

    /// Segments in the stream.
    fn segments(&self) -> u64 {
        self.count.saturating_sub(1)
    }

    /// Draws the segments `part` of the stream.
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>, part: &Range<u64>) {
        for chunk in &self.chunks {
            chunk.draw(pass, part);
        }
    }
}

/// The pipeline drawing `part` of the segments ("main": all, "core" or "edge", see the shader);
/// the grid and axes ("main") lose depth ties, so a path lying on them shows, and only the
/// cores write depth.
fn line_pipeline(
    device: &wgpu::Device,
    program: &Program,
    targets: Targets,
    part: &str,
) -> wgpu::RenderPipeline {
    let compare = if part == "main" {
        wgpu::CompareFunction::Less
    } else {
        wgpu::CompareFunction::LessEqual
    };
    let depth = Some((part == "core", compare, wgpu::DepthBiasState::default()));
    let blend = Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING);
    program.pipeline(device, part, targets, blend, depth)
}

/// Draws a toolpath and the grid/axes as anti-aliased segments: line cores write depth, edges do
/// not; the translucent grid is depth-tested without writes, so it never punches holes in the path.
pub struct PathRenderer {
    /// The path's cores, which write depth, then its anti-aliased edges, which do not: made
    /// with the first path, so that a view with none (the page's first frame) compiles only
    /// the grid's shaders.
    lines: Option<(wgpu::RenderPipeline, wgpu::RenderPipeline)>,
    overlay: wgpu::RenderPipeline,
    program: Program,
    targets: Targets,
    uniform_buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// Layout of each point texture's bind group (group 1: [`DrawUniforms`], the texture).
    draw_layout: wgpu::BindGroupLayout,
    path: PointBatch,
    grid: PointBatch,
    /// The cut stock, drawn before the path.
    stock: StockPass,
}

impl PathRenderer {
    /// Creates the pipelines for a colour target of `color_format`, a depth attachment of
    /// `depth_format` (`None` when the render pass has none, e.g. egui's) and `sample_count`
    /// MSAA samples; all three must match the render pass it will paint into.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        color_format: wgpu::TextureFormat,
        depth_format: Option<wgpu::TextureFormat>,
        sample_count: u32,
    ) -> Self {
        let uniform_buffer = gpu::uniform_buffer(device, "swarf_path_uniforms", UNIFORMS_SIZE);
        // Zero-initialised: a zero matrix draws nothing until `prepare`.
        let layout = gpu::bind_group_layout(
            device,
            "swarf_path_bind_group_layout",
            wgpu::ShaderStages::VERTEX_FRAGMENT,
            &[gpu::uniform(UNIFORMS_SIZE)],
        );
        let resources = [uniform_buffer.as_entire_binding()];
        let bind_group = gpu::bind_group(device, "swarf_path_bind_group", &layout, resources);
        let draw_layout = gpu::bind_group_layout(
            device,
            "swarf_draw_bind_group_layout",
            wgpu::ShaderStages::VERTEX,
            &[
                gpu::uniform(DRAW_UNIFORMS_SIZE),
                gpu::texture_2d(wgpu::TextureSampleType::Uint),
            ],
        );
        let program = Program::new(device, "swarf_path", PATH_WGSL, &[&layout, &draw_layout]);
        let targets = Targets {
            color: color_format,
            depth: depth_format,
            samples: sample_count,
        };
        Self {
            lines: None,
            overlay: line_pipeline(device, &program, targets, "main"),
            stock: StockPass::new(device, &layout, targets),
            program,
            targets,
            uniform_buffer,
            bind_group,
            draw_layout,
            path: PointBatch::new("swarf_path_points", true),
            grid: PointBatch::new("swarf_grid_points", false),
        }
    }

    /// Replaces the toolpath points, reusing the textures whose size fits. Fewer than two
    /// points draw nothing; any number more is kept (split over several textures if needed).
    pub fn set_path(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, points: &[PathPoint]) {
        if points.len() >= 2 && self.lines.is_none() {
            let (program, targets) = (&self.program, self.targets);
            let core = line_pipeline(device, program, targets, "core");
            self.lines = Some((core, line_pipeline(device, program, targets, "edge")));
        }
        self.path.upload(device, queue, &self.draw_layout, points);
    }

    /// Replaces the grid, axes and outlines (see [`crate::grid_points`]), drawn after the path.
    pub fn set_grid(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, points: &[PathPoint]) {
        self.grid.upload(device, queue, &self.draw_layout, points);
    }

    /// Replaces the cut stock drawn under the path (`None`: none).
    pub fn set_stock(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        stock: Option<&StockSurface<'_>>,
    ) {
        self.stock.set(device, queue, stock);
    }

    /// Caps the points one texture holds below what the device allows, so a long path is
    /// split into several textures sooner (for tests of the splitting; takes effect at the
    /// next upload). `None` goes back to the device's limit.
    pub fn set_points_per_buffer(&mut self, limit: Option<u64>) {
        self.path.chunk_limit = limit;
        self.grid.chunk_limit = limit;
    }

    /// Toolpath points uploaded (saturating at `u32::MAX`).
    #[must_use]
    pub fn path_point_count(&self) -> u32 {
        u32::try_from(self.path.count).unwrap_or(u32::MAX)
    }

    /// Toolpath segments (instances) drawn per frame, pen-up ones included (saturating at
    /// `u32::MAX`).
    #[must_use]
    pub fn path_segment_count(&self) -> u32 {
        u32::try_from(self.path.count.saturating_sub(1)).unwrap_or(u32::MAX)
    }

    /// Textures the toolpath is split into (one unless it exceeds the largest the device
    /// allows).
    #[must_use]
    pub fn path_buffer_count(&self) -> usize {
        self.path.chunks.len()
    }

    /// Bytes of GPU memory allocated for the toolpath points.
    #[must_use]
    pub fn path_buffer_bytes(&self) -> u64 {
        (self.path.chunks.iter())
            .map(|c| c.capacity() * POINT_SIZE)
            .sum()
    }

    /// Writes the uniforms for the next [`Self::paint`]. With one uniform buffer a renderer, each
    /// view visible at once needs its own `PathRenderer`.
    pub fn prepare(&self, queue: &wgpu::Queue, params: &ViewParams) {
        let uniforms = Uniforms::new(params);
        queue.write_buffer(&self.uniform_buffer, 0, bytemuck::bytes_of(&uniforms));
    }

    /// The work of one whole [`Self::paint`], as [`Self::paint_part`] counts it: each path
    /// segment once in each of its two passes.
    #[must_use]
    pub fn work(&self) -> u64 {
        self.lines.as_ref().map_or(0, |_| 2 * self.path.segments())
    }

    /// Records the draws (stock, path, then grid and axes) into `pass`; viewport and scissor
    /// are the caller's.
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.paint_part(pass, 0..self.work());
    }

    /// Records `part` of [`Self::work`] of [`Self::paint`], stock first, grid last: consecutive
    /// parts into one target (depth kept) draw one whole paint, a piece a frame.
    pub fn paint_part(&self, pass: &mut wgpu::RenderPass<'_>, part: Range<u64>) {
        let segments = self.path.segments();
        pass.set_bind_group(0, &self.bind_group, &[]);
        if part.start == 0 {
            self.stock.paint(pass);
        }
        if let Some((core, edge)) = &self.lines {
            let cores = part.start.min(segments)..part.end.min(segments);
            if !cores.is_empty() {
                pass.set_pipeline(core);
                self.path.draw(pass, &cores);
            }
            let edges = part.start.max(segments) - segments..part.end.max(segments) - segments;
            if !edges.is_empty() {
                pass.set_pipeline(edge);
                self.path.draw(pass, &edges);
            }
        }
        if part.end >= self.work() {
            pass.set_pipeline(&self.overlay);
            self.grid.draw(pass, &(0..self.grid.segments()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_round_trips() {
        let p = PathPoint::new(Vec3::new(1.0, 2.0, 3.0), Kind::Arc)
            .with_color_index(513)
            .with_highlight(true);
        assert_eq!(p.kind(), Some(Kind::Arc));
        assert_eq!(p.color_index(), 513);
        assert!(p.packed & PathPoint::HIGHLIGHT != 0);
        assert!(!p.is_pen_up());
        assert_eq!(p.position(), Vec3::new(1.0, 2.0, 3.0));
        let p = p.with_highlight(false).with_color_index(7);
        assert!(p.packed & PathPoint::HIGHLIGHT == 0);
        assert_eq!(p.color_index(), 7);
        assert_eq!(p.kind(), Some(Kind::Arc));
        assert!(PathPoint::pen_up(Vec3::ZERO).is_pen_up());
        assert_eq!(Kind::from_bits(200), None);
        for (i, kind) in Kind::ALL.iter().enumerate() {
            assert_eq!(*kind as usize, i);
            assert_eq!(Kind::from_bits(i as u8), Some(*kind));
        }
        assert!(Kind::Programmed.is_motion() && !Kind::Grid.is_motion());
    }

    #[test]
    fn uniforms_are_sanitised() {
        let params = ViewParams {
            view_proj: Mat4::from_cols_array(&[f32::NAN; 16]),
            viewport_px: Vec2::new(f32::NAN, 0.0),
            line_width_px: f32::INFINITY,
            executed_segments: Some(5),
            highlight: 3..9,
            ..ViewParams::default()
        };
        let u = Uniforms::new(&params);
        assert!(u.view_proj.iter().flatten().all(|v| *v == 0.0));
        assert_eq!(u.viewport, [1.0, 1.0]);
        assert_eq!(u.line_width, 1.0);
        assert_eq!(u.executed_end, 5);
        assert_eq!((u.highlight_start, u.highlight_end), (3, 9));
        assert_eq!(u.palette[HIGHLIGHT_SLOT], srgba(HIGHLIGHT_COLOR));
        assert_eq!(Uniforms::new(&ViewParams::default()).executed_end, u32::MAX);
        let scaled = ViewParams::default().scaled(2.0);
        assert_eq!(scaled.line_width_px, 3.2);
        assert_eq!(scaled.dash_px, Vec2::new(12.0, 8.0));
    }
}
