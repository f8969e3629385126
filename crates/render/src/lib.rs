//! Swarf's wgpu renderer: line-list batches, an orbit camera, and grid/axes geometry.
//!
//! It knows nothing of egui or the interpreter: callers hand it plain [`Vertex`] slices
//! (positions as f32 relative to an origin they choose) and a view-projection matrix from
//! [`OrbitCamera`]. Everything works on the WebGL2 fallback (uniform buffers and vertex
//! attributes only, no storage buffers).

mod camera;
mod grid;
mod lines;

pub use camera::{MAX_DISTANCE, MIN_DISTANCE, OrbitCamera, Projection, StandardView};
pub use grid::{
    GRID_COLOR, GRID_MAJOR_COLOR, X_AXIS_COLOR, Y_AXIS_COLOR, Z_AXIS_COLOR, grid_vertices,
    nice_step,
};
pub use lines::{LINES_WGSL, LineRenderer, Vertex};
