//! Swarf's wgpu renderer, free of egui: anti-aliased segments with depth, the lit stock, an orbit
//! camera, grid/axes, CPU picking and offscreen targets, drawing [`PathPoint`]s ([`Drawing`] with
//! `toolpath`) seen by an [`OrbitCamera`]. It keeps to WebGL2: no storage buffers.

mod camera;
mod composite;
mod gpu;
mod grid;
mod lod;
mod offscreen;
mod path;
mod pick;
#[cfg(feature = "toolpath")]
mod scene;
mod stock;

pub use camera::{MAX_DISTANCE, MIN_DISTANCE, OrbitCamera, Projection, StandardView};
pub use composite::{COMPOSITE_WGSL, Compositor};
pub use grid::{grid_points, grid_points_at, nice_step};
pub use lod::{LOD_TOLERANCE_PX, PathLod, lod_level, pixels_per_unit, simplify, simplify_at};
pub use offscreen::{HeadlessGpu, RenderError, RenderTarget};
pub use path::{
    ARC_COLOR, ColorMode, DEPTH_FORMAT, DRAW_UNIFORMS_SIZE, FEED_COLOR, FRAME_WORK,
    GRID_MAJOR_COLOR, HIGHLIGHT_COLOR, HIGHLIGHT_SLOT, Kind, PATH_WGSL, POINT_SIZE,
    PROGRAMMED_COLOR, Palette, PathPoint, PathRenderer, RAPID_COLOR, UNIFORMS_SIZE, ViewParams,
    Z_AXIS_COLOR, ZONE_COLOR, srgba,
};
pub use pick::{Pick, pick_kept_segment, pick_segment, segment_bounds};
#[cfg(feature = "toolpath")]
pub use scene::{Drawing, reference_points, view_bounds};
pub use stock::{MAX_STOCK_CELLS, STOCK_UNIFORMS_SIZE, STOCK_WGSL, StockSurface};
