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

/// A workbench in a `size` window drawn through `render_state`, the backplot's renderer
/// installed: what a test of the drawn view clicks and reads back.
#[allow(dead_code)] // Not every test file that draws uses a whole workbench.
pub fn drawn_workbench(
    render_state: &egui_wgpu::RenderState,
    wb: swarf_ui::Workbench,
    size: egui::Vec2,
) -> egui_kittest::Harness<'static, swarf_ui::Workbench> {
    let harness = egui_kittest::Harness::builder()
        .with_size(size)
        .with_render_cursor(false)
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(
            render_state.clone(),
        ))
        .build_ui_state(|ui, wb: &mut swarf_ui::Workbench| wb.ui(ui), wb);
    swarf_ui::backplot::Backplot::install(&harness.ctx, render_state);
    harness
}
