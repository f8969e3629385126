//! What the UI tests that draw through the GPU share.

use std::panic::AssertUnwindSafe;

use egui_kittest::wgpu::{create_render_state, default_wgpu_setup};

/// A wgpu render state on any adapter (Mesa lavapipe will do), or `None` where none can be
/// made: `create_render_state` panics then, and such a test skips itself.
pub fn render_state() -> Option<egui_wgpu::RenderState> {
    std::panic::catch_unwind(AssertUnwindSafe(|| {
        create_render_state(
            default_wgpu_setup(),
            egui_wgpu::RendererOptions::PREDICTABLE,
        )
    }))
    .ok()
}
