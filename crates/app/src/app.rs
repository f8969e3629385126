//! The eframe application: one workbench filling the window, its host's files and settings.

use swarf_ui::Workbench;
use swarf_ui::backplot::Backplot;

use crate::files;

#[cfg(not(target_arch = "wasm32"))]
use crate::desktop::Host;
#[cfg(target_arch = "wasm32")]
use crate::web_files::Host;

/// A hook run after each frame with the number of frames shown so far.
type FrameHook = Box<dyn FnMut(&egui::Context, u64)>;

/// A callback waiting for the page to show the current text's analysis.
type IdleWaiter = Box<dyn FnOnce()>;

/// The Swarf application: the workbench plus host bookkeeping.
pub struct SwarfApp {
    /// The editor, problems list and backplot.
    pub workbench: Workbench,
    /// Files: dialogs, the open file, recent files and crash recovery.
    pub host: Host,
    ctx: egui::Context,
    /// Frames shown so far.
    pub frames: u64,
    /// Hook called after each painted frame (the desktop screenshot mode uses it).
    after_frame: Option<FrameHook>,
    /// The window title last set.
    title: String,
    /// Callbacks waiting until a frame shows the finished analysis of the current text.
    idle_waiting: Vec<IdleWaiter>,
    /// Callbacks a frame ended, with its text generation: called next frame if that still holds.
    idle_drawn: Vec<(u64, IdleWaiter)>,
}

impl SwarfApp {
    /// Creates the app, registers the backplot's GPU resources with eframe's wgpu renderer,
    /// restores the settings of the last run and any unsaved program a crash left behind.
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        if let Some(render_state) = cc.wgpu_render_state.as_ref() {
            Backplot::install(&cc.egui_ctx, render_state);
        } else {
            log::warn!("no wgpu render state: the 3D view is unavailable");
        }
        // The editor palette is made for a dark background, whatever the system theme.
        cc.egui_ctx.set_theme(egui::Theme::Dark);
        // The page analyses in a worker (the desktop in a thread of its own).
        #[cfg(target_arch = "wasm32")]
        let workbench = match crate::web_worker::WorkerAnalyst::start(&cc.egui_ctx) {
            Ok(worker) => Workbench::example(Box::new(worker)),
            Err(error) => {
                log::warn!("no analysis worker ({error:?}): it runs in the frames");
                Workbench::default()
            }
        };
        #[cfg(not(target_arch = "wasm32"))]
        let workbench = Workbench::default();
        let mut app = SwarfApp {
            workbench,
            host: Host::new(),
            ctx: cc.egui_ctx.clone(),
            frames: 0,
            after_frame: None,
            title: String::new(),
            idle_waiting: Vec::new(),
            idle_drawn: Vec::new(),
        };
        // The dialect kept is the one new tabs start in; the example shown keeps its own.
        if let Some(storage) = cc.storage {
            let (active, shown) = (app.workbench.active_tab(), app.workbench.dialect());
            app.host.recent = files::restore_settings(storage, &mut app.workbench);
            app.workbench.set_tab_dialect(active, shown);
        }
        app.host.recover(&mut app.workbench);
        app
    }

    /// Runs `hook` after every frame with the number of frames shown so far.
    pub fn set_after_frame(&mut self, hook: impl FnMut(&egui::Context, u64) + 'static) {
        self.after_frame = Some(Box::new(hook));
    }

    /// Calls `done` once the analysis of the current text is finished and a frame showing it
    /// has been painted (when nothing is pending, at the start of the second frame from now).
    pub fn when_idle(&mut self, done: impl FnOnce() + 'static) {
        self.idle_waiting.push(Box::new(done));
        self.ctx.request_repaint();
    }

    /// Calls the idle callbacks whose frame was painted; those whose text changed, or whose
    /// picture that frame began to draw over several, wait again.
    fn wake_idle(&mut self) {
        let generation = self.workbench.generation();
        let drawing = self.workbench.drawing_pending();
        for (shown, done) in std::mem::take(&mut self.idle_drawn) {
            if shown == generation && !drawing {
                done();
            } else {
                self.idle_waiting.push(done);
            }
        }
    }

    /// After the workbench's frame: one that began with no analysis pending and kept its text
    /// shows the current analysis, so the waiting callbacks are called at the next one's start.
    fn note_idle(&mut self, ctx: &egui::Context, idle_before: bool, generation_before: u64) {
        if self.idle_waiting.is_empty() {
            return;
        }
        let generation = self.workbench.generation();
        if idle_before && generation == generation_before {
            self.idle_drawn
                .extend(self.idle_waiting.drain(..).map(|done| (generation, done)));
            // The next frame, which calls them, comes at once.
            ctx.request_repaint();
        }
        // Those still waiting are woken by the analysis's answer: waiting paints no frame.
    }

    /// Runs `f` on the workbench and schedules a repaint (for the JS API).
    pub fn edit<R>(&mut self, f: impl FnOnce(&mut Workbench) -> R) -> R {
        let out = f(&mut self.workbench);
        self.ctx.request_repaint();
        out
    }

    /// Where the machine point `p` (mm) was drawn in the backplot at the last frame, in CSS
    /// pixels from the canvas's top left; `None` before it, without geometry or behind the eye.
    #[cfg(target_arch = "wasm32")]
    pub fn project(&self, p: glam::DVec3) -> Option<[f64; 2]> {
        let p = (p - self.workbench.analysis().scene.origin).as_vec3();
        let pos = self.workbench.backplot().screen_pos(p)?;
        let zoom = f64::from(self.ctx.zoom_factor());
        Some([pos.x, pos.y].map(|v| f64::from(v) * zoom))
    }

    /// Where the workbench's widget `name` (or `stock`, the backplot's Stock button) was drawn
    /// at the last frame, as `[x, y, width, height]` in CSS pixels from the canvas's top left.
    #[cfg(target_arch = "wasm32")]
    pub fn widget_rect(&self, name: &str) -> Option<[f64; 4]> {
        let rect = match name {
            "stock" => self.workbench.backplot().stock_button_rect(),
            _ => self.workbench.widget_rect(name),
        }?;
        let zoom = f64::from(self.ctx.zoom_factor());
        Some([rect.min.x, rect.min.y, rect.width(), rect.height()].map(|v| f64::from(v) * zoom))
    }

    fn update_title(&mut self, ctx: &egui::Context) {
        let doc = self.workbench.document();
        let dirty = if doc.is_unsaved() { "*" } else { "" };
        let title = format!("{}{dirty} — Swarf", doc.name);
        if title != self.title {
            #[cfg(not(target_arch = "wasm32"))]
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            #[cfg(target_arch = "wasm32")]
            if let Some(doc) = web_sys::window().and_then(|w| w.document()) {
                doc.set_title(&title);
            }
            let _ = ctx;
            self.title = title;
        }
    }
}

impl eframe::App for SwarfApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // The window's close button: held back while there are unsaved changes.
        #[cfg(not(target_arch = "wasm32"))]
        if ctx.input(|i| i.viewport().close_requested())
            && self.workbench.any_dirty()
            && !self.host.quitting
        {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.workbench.request_quit();
        }
        let dropped = ctx.input(|i| i.raw.dropped_files.first().cloned());
        if let Some(file) = dropped {
            self.host.open_dropped(&mut self.workbench, &file);
        }
        // Nothing arrives later on the desktop (dialogs answer at once).
        #[cfg(target_arch = "wasm32")]
        self.host.poll(&mut self.workbench);
        self.wake_idle();
        // A finished analysis that has come is shown by this frame.
        self.workbench.take_replies();
        let idle_before =
            self.workbench.analysis_progress().is_none() && !self.workbench.drawing_pending();
        let generation_before = self.workbench.generation();
        self.workbench.ui(ui);
        self.note_idle(&ctx, idle_before, generation_before);
        self.host.handle(&mut self.workbench, &ctx);
        let now = ctx.input(|i| i.time);
        self.host.autosave(&mut self.workbench, now);
        if self.workbench.any_dirty() {
            // Wake up for the delayed autosave even when nothing else happens.
            ctx.request_repaint_after(std::time::Duration::from_millis(1200));
        }
        self.update_title(&ctx);
        self.frames += 1;
        if let Some(hook) = self.after_frame.as_mut() {
            hook(&ctx, self.frames);
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        files::store_settings(storage, &self.workbench, &self.host.recent);
        self.host.write_recovery(&mut self.workbench);
    }

    fn persist_egui_memory(&self) -> bool {
        false
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}
