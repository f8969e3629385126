//! The 3D backplot widget: an egui area painted by `swarf_render` through an `egui_wgpu`
//! paint callback, with orbit/pan/zoom input and standard-view buttons.
//!
//! GPU side: [`Backplot::install`] puts a [`BackplotResources`] into egui-wgpu's
//! `callback_resources` type map. Each frame [`Backplot::show`] adds a paint callback carrying
//! the scene's `Arc` and the camera matrix; its `prepare` uploads vertices only when the
//! scene's generation changed and writes the uniform, its `paint` records one draw per batch.

use std::collections::HashMap;
use std::sync::Arc;

use egui::epaint::ViewportInPixels;
use glam::{Mat4, Vec2, Vec3};
use swarf_render::{LineRenderer, OrbitCamera, Projection, StandardView, Vertex, grid_vertices};

/// Key of the flag [`Backplot::install`] leaves in the egui context's memory; without it `show`
/// draws a notice instead of a paint callback nobody would execute (e.g. on the glow backend).
fn installed_key() -> egui::Id {
    egui::Id::unique("swarf-backplot-installed")
}

/// GPU views not painted for this many frames release their buffers (re-created on demand).
const STALE_FRAMES: u64 = 600;

/// Scroll points per e-fold of zoom (≈ 1.16× per 100-point wheel notch).
const SCROLL_ZOOM_POINTS: f32 = 667.0;

/// Geometry to plot: line-list vertices relative to `origin`, bounds in the same frame.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Changes whenever `vertices` or `bounds` change; the GPU upload happens only then.
    pub generation: u64,
    /// Line-list vertices (two per segment), f32 relative to the caller's origin.
    pub vertices: Arc<Vec<Vertex>>,
    /// Axis-aligned bounds of the geometry, `None` when there is none.
    pub bounds: Option<(Vec3, Vec3)>,
    /// Where machine zero lies in the scene's frame: the grid and the axes are drawn there.
    pub zero: Vec3,
}

/// State of one backplot view: its camera and when to fit it to the scene.
#[derive(Clone, Debug)]
pub struct Backplot {
    camera: OrbitCamera,
    /// Generation of the last scene shown, to notice new geometry.
    last_generation: Option<u64>,
    /// Whether the last scene shown had geometry (fit again when it reappears).
    had_geometry: bool,
    /// Fit to the scene's extents on the next frame.
    fit_pending: bool,
}

impl Default for Backplot {
    fn default() -> Self {
        Self::new()
    }
}

impl Backplot {
    /// A backplot in the isometric view that fits to the first geometry it is shown.
    #[must_use]
    pub fn new() -> Self {
        Self {
            camera: OrbitCamera::new(StandardView::Iso),
            last_generation: None,
            had_geometry: false,
            fit_pending: true,
        }
    }

    /// Registers the GPU resources; call once with eframe's `cc.wgpu_render_state`.
    ///
    /// Assumes egui-wgpu's default render pass (as eframe configures it with the default
    /// `multisampling: 0`): one sample and no depth attachment. For other MSAA settings use
    /// [`Self::install_with_sample_count`].
    pub fn install(ctx: &egui::Context, render_state: &egui_wgpu::RenderState) {
        Self::install_with_sample_count(ctx, render_state, 1);
    }

    /// Like [`Self::install`] for an egui render pass with `sample_count` MSAA samples
    /// (eframe's `NativeOptions::multisampling`, 0 meaning 1).
    pub fn install_with_sample_count(
        ctx: &egui::Context,
        render_state: &egui_wgpu::RenderState,
        sample_count: u32,
    ) {
        let resources = BackplotResources {
            target_format: render_state.target_format,
            sample_count: sample_count.max(1),
            views: HashMap::new(),
        };
        render_state
            .renderer
            .write()
            .callback_resources
            .insert(resources);
        ctx.data_mut(|d| d.insert_temp(installed_key(), true));
    }

    /// Fit to extents on the next frame.
    pub fn fit(&mut self) {
        self.fit_pending = true;
    }

    /// The camera, e.g. to persist it.
    #[must_use]
    pub fn camera(&self) -> &OrbitCamera {
        &self.camera
    }

    /// Mutable access to the camera, e.g. to restore a persisted one.
    pub fn camera_mut(&mut self) -> &mut OrbitCamera {
        &mut self.camera
    }

    /// Draws the scene filling the available space; handles input; re-uploads when
    /// `scene.generation` changes; fits to extents the first time geometry appears.
    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) -> egui::Response {
        let size = ui.available_size().max(egui::vec2(64.0, 64.0));
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        let background = ui.visuals().extreme_bg_color;
        ui.painter().rect_filled(rect, 0.0, background);

        if !ui
            .ctx()
            .data(|d| d.get_temp::<bool>(installed_key()))
            .unwrap_or(false)
        {
            // A real label (not painter text) so screen readers and tests can find it.
            ui.put(
                rect,
                egui::Label::new(egui::RichText::new("3D view unavailable").weak()),
            );
            return response;
        }

        self.track_scene(scene);
        self.handle_input(ui, &response, rect);
        // Reserve the paint slot now so the overlay buttons land on top of the 3D lines, but
        // build the callback last so button clicks take effect this very frame.
        let slot = ui.painter().add(egui::Shape::Noop);
        self.overlay_buttons(ui, rect);

        let aspect = rect.width() / rect.height();
        if self.fit_pending {
            self.fit_pending = false;
            match scene.bounds {
                Some((min, max)) => self.camera.fit_aspect(min, max, aspect),
                // Nothing to frame: the default view of the origin.
                None => self.camera.fit_aspect(Vec3::ONE, Vec3::ZERO, aspect),
            }
        }

        let callback = BackplotCallback {
            id: response.id,
            frame: ui.ctx().cumulative_frame_nr(),
            generation: scene.generation,
            vertices: Arc::clone(&scene.vertices),
            bounds: scene.bounds,
            zero: scene.zero,
            rect,
            view_proj: self.camera.view_proj(aspect),
        };
        ui.painter().set(
            slot,
            egui_wgpu::Callback::new_paint_callback(rect, callback),
        );
        response
    }

    /// Notices new scene generations and schedules a fit when geometry first appears.
    fn track_scene(&mut self, scene: &Scene) {
        if self.last_generation == Some(scene.generation) {
            return;
        }
        self.last_generation = Some(scene.generation);
        let has_geometry = scene.bounds.is_some();
        if has_geometry && !self.had_geometry {
            self.fit_pending = true;
        }
        self.had_geometry = has_geometry;
    }

    /// Orbit (left drag), pan (right/middle or shift+left drag), zoom (scroll, pinch) and
    /// fit (double click).
    fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response, rect: egui::Rect) {
        let viewport = Vec2::new(rect.width(), rect.height());
        let shift = ui.input(|i| i.modifiers.shift);
        let delta = response.drag_delta();
        let delta = Vec2::new(delta.x, delta.y);
        if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (shift && response.dragged_by(egui::PointerButton::Primary))
        {
            self.camera.pan(delta, viewport);
        } else if response.dragged_by(egui::PointerButton::Primary) {
            self.camera.orbit(delta);
        }

        if let Some(pointer) = response.hover_pos() {
            let (scroll, pinch) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            let factor = pinch * (scroll / SCROLL_ZOOM_POINTS).exp();
            if factor.is_finite() && (factor - 1.0).abs() > 1.0e-6 {
                let cursor = pointer - rect.min;
                self.camera
                    .zoom_at(factor, Vec2::new(cursor.x, cursor.y), viewport);
                // The wheel zoomed the view; don't let an enclosing scroll area scroll too.
                ui.ctx()
                    .input_mut(|i| i.smooth_scroll_delta = egui::Vec2::ZERO);
            }
        }

        if response.double_clicked() {
            self.fit();
        }
    }

    /// Small buttons in the view's top-left corner: Fit, the standard views and the projection.
    fn overlay_buttons(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
        let mut child = ui.new_child(
            egui::UiBuilder::new()
                .id_salt("swarf_backplot_buttons")
                .max_rect(rect.shrink(6.0))
                .layout(egui::Layout::left_to_right(egui::Align::Min)),
        );
        if child
            .small_button("Fit")
            .on_hover_text("Fit to extents (double-click)")
            .clicked()
        {
            self.fit();
        }
        for (label, view) in [
            ("Iso", StandardView::Iso),
            ("Top", StandardView::Top),
            ("Front", StandardView::Front),
            ("Right", StandardView::Right),
        ] {
            if child.small_button(label).clicked() {
                self.camera.set_view(view);
                self.fit();
            }
        }
        let perspective = self.camera.projection == Projection::Perspective;
        if child
            .selectable_label(perspective, "Persp")
            .on_hover_text("Perspective / orthographic projection")
            .clicked()
        {
            self.camera.projection = if perspective {
                Projection::Orthographic
            } else {
                Projection::Perspective
            };
        }
    }
}

/// GPU state shared by all backplots, stored in egui-wgpu's `callback_resources`.
pub struct BackplotResources {
    target_format: wgpu::TextureFormat,
    sample_count: u32,
    views: HashMap<egui::Id, GpuView>,
}

/// One backplot's renderer and what it last uploaded.
struct GpuView {
    renderer: LineRenderer,
    generation: Option<u64>,
    last_frame: u64,
}

/// The per-frame paint callback: what to draw and from where.
struct BackplotCallback {
    id: egui::Id,
    frame: u64,
    generation: u64,
    vertices: Arc<Vec<Vertex>>,
    bounds: Option<(Vec3, Vec3)>,
    zero: Vec3,
    rect: egui::Rect,
    view_proj: Mat4,
}

impl egui_wgpu::CallbackTrait for BackplotCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        screen_descriptor: &egui_wgpu::ScreenDescriptor,
        _egui_encoder: &mut wgpu::CommandEncoder,
        callback_resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(resources) = callback_resources.get_mut::<BackplotResources>() else {
            return Vec::new();
        };
        let (format, samples) = (resources.target_format, resources.sample_count);
        resources
            .views
            .retain(|_, view| view.last_frame + STALE_FRAMES >= self.frame);
        let view = resources.views.entry(self.id).or_insert_with(|| GpuView {
            renderer: LineRenderer::new(device, format, samples),
            generation: None,
            last_frame: self.frame,
        });
        view.last_frame = self.frame;
        if view.generation != Some(self.generation) {
            view.renderer.set_lines(device, queue, &self.vertices);
            let zero = self.zero;
            let mut grid = match self.bounds {
                Some((min, max)) => grid_vertices(min - zero, max - zero),
                None => grid_vertices(Vec3::ONE, Vec3::ZERO),
            };
            for v in &mut grid {
                v.position = (Vec3::from_array(v.position) + zero).to_array();
            }
            view.renderer.set_grid(device, queue, &grid);
            view.generation = Some(self.generation);
        }
        let visible = ViewportInPixels::from_points(
            &self.rect,
            screen_descriptor.pixels_per_point,
            screen_descriptor.size_in_pixels,
        );
        let full = self.rect * screen_descriptor.pixels_per_point;
        if let Some(remap) = ndc_remap(full, &visible) {
            view.renderer.prepare(queue, remap * self.view_proj);
        }
        Vec::new()
    }

    fn paint(
        &self,
        info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        callback_resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(view) = callback_resources
            .get::<BackplotResources>()
            .and_then(|r| r.views.get(&self.id))
        else {
            return;
        };
        // egui-wgpu has already set the scissor to the clip rect and the viewport to the
        // callback rect clamped to the screen; set that viewport explicitly (prepare's matrix
        // maps the full rect into it) so we do not depend on that courtesy.
        let vp = info.viewport_in_pixels();
        if vp.width_px <= 0 || vp.height_px <= 0 {
            return;
        }
        render_pass.set_viewport(
            vp.left_px as f32,
            vp.top_px as f32,
            vp.width_px as f32,
            vp.height_px as f32,
            0.0,
            1.0,
        );
        view.renderer.paint(render_pass);
    }
}

/// Maps NDC of the whole callback rectangle `full` (pixels, may extend off screen) onto NDC
/// of the on-screen viewport `visible`, which egui clamps to the screen. Without it a
/// partly off-screen view would be squashed. `None` when nothing is visible.
fn ndc_remap(full: egui::Rect, visible: &ViewportInPixels) -> Option<Mat4> {
    if visible.width_px <= 0
        || visible.height_px <= 0
        || full.width() <= 0.0
        || full.height() <= 0.0
    {
        return None;
    }
    let (vl, vt) = (visible.left_px as f32, visible.top_px as f32);
    let (vw, vh) = (visible.width_px as f32, visible.height_px as f32);
    // x_px = full.left + (x + 1) / 2 * full.w ; x' = 2 (x_px - vl) / vw - 1
    let sx = full.width() / vw;
    let tx = (2.0 * (full.min.x - vl) + full.width()) / vw - 1.0;
    // y_px = full.top + (1 - y) / 2 * full.h ; y' = 1 - 2 (y_px - vt) / vh
    let sy = full.height() / vh;
    let ty = 1.0 - (2.0 * (full.min.y - vt) + full.height()) / vh;
    let m = Mat4::from_cols_array(&[
        sx, 0.0, 0.0, 0.0, //
        0.0, sy, 0.0, 0.0, //
        0.0, 0.0, 1.0, 0.0, //
        tx, ty, 0.0, 1.0,
    ]);
    m.is_finite().then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vp(left: i32, top: i32, w: i32, h: i32) -> ViewportInPixels {
        ViewportInPixels {
            left_px: left,
            top_px: top,
            from_bottom_px: 0,
            width_px: w,
            height_px: h,
        }
    }

    #[test]
    fn remap_is_identity_when_fully_visible() {
        let full = egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(300.0, 200.0));
        let m = ndc_remap(full, &vp(10, 20, 300, 200));
        assert!(m.is_some_and(|m| m.abs_diff_eq(Mat4::IDENTITY, 1e-6)));
    }

    #[test]
    fn remap_keeps_pixels_in_place_when_clipped() {
        // 400×300 view starting 100 px left of and 50 px above the screen.
        let full = egui::Rect::from_min_size(egui::pos2(-100.0, -50.0), egui::vec2(400.0, 300.0));
        let visible = vp(0, 0, 300, 250);
        let m = ndc_remap(full, &visible);
        assert!(m.is_some());
        let m = m.unwrap_or_default();
        // The full rect's centre (NDC 0,0) is at pixel (100, 100).
        let p = m.project_point3(Vec3::ZERO);
        let px = (p.x + 1.0) / 2.0 * 300.0;
        let py = (1.0 - p.y) / 2.0 * 250.0;
        assert!(
            (px - 100.0).abs() < 1e-3 && (py - 100.0).abs() < 1e-3,
            "{px},{py}"
        );
        // Its bottom-right corner (NDC 1,-1) is at pixel (300, 250).
        let q = m.project_point3(Vec3::new(1.0, -1.0, 0.5));
        assert!((q.x - 1.0).abs() < 1e-5 && (q.y + 1.0).abs() < 1e-5 && (q.z - 0.5).abs() < 1e-6);
        assert!(ndc_remap(full, &vp(0, 0, 0, 10)).is_none());
    }

    #[test]
    fn first_geometry_triggers_fit_later_edits_do_not() {
        let mut plot = Backplot::new();
        let empty = Scene::default();
        plot.track_scene(&empty);
        plot.fit_pending = false;
        let scene = Scene {
            generation: 1,
            vertices: Arc::new(vec![Vertex::default(); 2]),
            bounds: Some((Vec3::ZERO, Vec3::ONE)),
            zero: Vec3::ZERO,
        };
        plot.track_scene(&scene);
        assert!(plot.fit_pending);
        plot.fit_pending = false;
        let edited = Scene {
            generation: 2,
            ..scene.clone()
        };
        plot.track_scene(&edited);
        assert!(!plot.fit_pending);
        plot.track_scene(&Scene {
            generation: 3,
            ..Scene::default()
        });
        plot.track_scene(&Scene {
            generation: 4,
            ..scene
        });
        assert!(plot.fit_pending);
    }
}
