//! The eframe application: one workbench filling the window.

use swarf_ui::Workbench;
use swarf_ui::backplot::Backplot;

/// A hook run after each frame with the number of frames shown so far.
type FrameHook = Box<dyn FnMut(&egui::Context, u64)>;

/// The Swarf application: the workbench plus host bookkeeping.
pub struct SwarfApp {
    /// The editor, problems list and backplot.
    pub workbench: Workbench,
    ctx: egui::Context,
    frames: u64,
    /// Hook called after each painted frame (the desktop screenshot mode uses it).
    after_frame: Option<FrameHook>,
}

impl SwarfApp {
    /// Creates the app and registers the backplot's GPU resources with eframe's wgpu renderer.
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        if let Some(render_state) = cc.wgpu_render_state.as_ref() {
            Backplot::install(&cc.egui_ctx, render_state);
        } else {
            log::warn!("no wgpu render state: the 3D view is unavailable");
        }
        // The editor palette is made for a dark background, whatever the system theme.
        cc.egui_ctx.set_theme(egui::Theme::Dark);
        SwarfApp {
            workbench: Workbench::default(),
            ctx: cc.egui_ctx.clone(),
            frames: 0,
            after_frame: None,
        }
    }

    /// Runs `hook` after every frame with the number of frames shown so far.
    pub fn set_after_frame(&mut self, hook: impl FnMut(&egui::Context, u64) + 'static) {
        self.after_frame = Some(Box::new(hook));
    }

    /// Frames shown so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Replaces the program text and schedules a repaint (for the JS API and file loading).
    pub fn set_text(&mut self, text: impl Into<String>) {
        self.workbench.set_text(text);
        self.ctx.request_repaint();
    }
}

impl eframe::App for SwarfApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.workbench.ui(ui);
        self.frames += 1;
        if let Some(hook) = self.after_frame.as_mut() {
            hook(ui.ctx(), self.frames);
        }
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}
