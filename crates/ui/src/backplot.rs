//! The 3D backplot widget (orbit/pan/zoom, views, picking, playback) via an `egui_wgpu` callback:
//! `prepare` draws with depth into an offscreen target on change, `paint` composites it into egui.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use egui::epaint::ViewportInPixels;
use glam::{DVec3, Mat4, Vec2, Vec3};
use swarf_analysis::{Lod, LodLevel, ProgramText, Request, StockCut};
use swarf_render::{
    ColorMode, Compositor, DEPTH_FORMAT, FRAME_WORK, Kind, OrbitCamera, PathLod, PathPoint,
    PathRenderer, Projection, RenderTarget, StandardView, StockSurface, ViewParams, lod_level,
    pick_kept_segment, pick_segment, pixels_per_unit, reference_points, segment_bounds,
    view_bounds,
};
use swarf_toolpath::Timeline;

use crate::i18n::{tr, trf};

mod playback;
mod stock;
pub use playback::{PLAYBACK_SPEEDS, Playback};
pub use stock::RAPID_INTO_STOCK_COLOR;

/// The flag [`Backplot::install`] leaves in egui's memory; without it `show` draws a notice.
fn installed_key() -> egui::Id {
    egui::Id::unique("swarf-backplot-installed")
}

/// GPU views not painted for this many frames release their buffers (re-created on demand).
const STALE_FRAMES: u64 = 600;

/// Scroll points per e-fold of zoom (≈ 1.16× per 100-point wheel notch).
const SCROLL_ZOOM_POINTS: f32 = 667.0;

/// One arrow-key press orbits as much as a drag of this many points.
const KEY_ORBIT_POINTS: f32 = 15.0;
/// One Shift+arrow press pans by this many points.
const KEY_PAN_POINTS: f32 = 40.0;
/// One `+` press zooms in by this factor.
const KEY_ZOOM: f32 = 1.25;

/// Width of the outline that shows the view has the keyboard focus, in points.
const FOCUS_OUTLINE_POINTS: f32 = 2.0;

/// Space left between the view's buttons and what a fit frames, in points.
const FIT_GAP_POINTS: f32 = 4.0;

/// The standard views: their buttons and keys.
const STANDARD_VIEWS: [(&str, egui::Key, StandardView); 4] = [
    ("Iso", egui::Key::Num1, StandardView::Iso),
    ("Top", egui::Key::Num2, StandardView::Top),
    ("Front", egui::Key::Num3, StandardView::Front),
    ("Right", egui::Key::Num4, StandardView::Right),
];

/// How far from a segment (in points) the cursor may be to pick it.
pub const PICK_RADIUS: f32 = 6.0;

/// Points added to a chord's tolerance on screen when picking over the chords drawn, for the
/// rounding of the two measures.
const PICK_SLACK_ROUNDING: f32 = 0.01;

/// Colour format of the offscreen target (gamma-encoded, premultiplied, as egui blends).
const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Longest block text shown in the hover tooltip, in characters.
const TOOLTIP_TEXT_CHARS: usize = 120;

/// The program text with its line starts, so tooltips can show a block's text.
#[derive(Clone, Debug)]
pub struct SourceText {
    text: ProgramText,
    /// The line starts of a flat text, found on the first look-up (not when the analysis ends).
    starts: std::sync::OnceLock<Vec<usize>>,
}

impl SourceText {
    /// Indexes `text` (not copied; lines end at `\n`, and a trailing `\r` is dropped from each).
    pub fn new(text: impl Into<ProgramText>) -> Self {
        let (text, starts) = (text.into(), std::sync::OnceLock::new());
        Self { text, starts }
    }

    /// The text of 1-based `line` without its line ending, if the text has that line.
    pub fn line(&self, line: u32) -> Option<Cow<'_, str>> {
        let index = usize::try_from(line).ok()?.checked_sub(1)?;
        let text = match &self.text {
            ProgramText::Flat(text) => text,
            ProgramText::Rope(rope) => return crate::buffer::line_of(rope, index).map(Cow::from),
        };
        let starts = self.starts.get_or_init(|| {
            let mut starts = Vec::with_capacity(text.len() / 24 + 1);
            starts.push(0);
            starts.extend(memchr::memchr_iter(b'\n', text.as_bytes()).map(|i| i + 1));
            starts
        });
        let start = *starts.get(index)?;
        let next = starts.get(index + 1);
        let end = next.map_or(text.len(), |next| next.saturating_sub(1));
        let text = text.get(start..end.max(start))?;
        Some(text.strip_suffix('\r').unwrap_or(text).into())
    }
}

/// What the view shows: a [`swarf_render::Drawing`] (shared) with each segment's line, feed,
/// time and tool.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Changes whenever the geometry changes; the GPU upload happens only then.
    pub generation: u64,
    /// One point per path vertex: the start point (pen up), then the end of each segment,
    /// so segment `i` runs from point `i` to point `i + 1` and carries point `i + 1`'s kind.
    pub points: Arc<Vec<PathPoint>>,
    /// 1-based source line of each segment.
    pub lines: Arc<Vec<u32>>,
    /// Blocks that move the tool, as the analysis counted them (`None`: counted from `lines`
    /// when playback first asks).
    pub block_count: Option<usize>,
    /// Feed of each segment in mm/min (0 for rapids).
    pub feeds: Arc<Vec<f32>>,
    /// When each segment runs (one not covered takes a second, as in a scene built by hand).
    pub timeline: Arc<Timeline>,
    /// The tool in the spindle during each segment (may be empty).
    pub tools: Arc<Vec<u32>>,
    /// Radius in mm of the tools the setup knows, by number (the tool marker's size).
    pub tool_radii: Arc<BTreeMap<u32, f32>>,
    /// Axis-aligned bounds of the geometry, `None` when there is none.
    pub bounds: Option<(Vec3, Vec3)>,
    /// Where machine zero lies in the scene's frame: the grid and the axes are drawn there.
    pub zero: Vec3,
    /// Machine coordinates (mm) of the scene's origin, to report positions.
    pub origin: DVec3,
    /// The program text, for the hover tooltip (`None` when not known).
    pub source: Option<Arc<SourceText>>,
    /// Reference marks drawn with the grid, not picked ([`swarf_render::Drawing::marks`]).
    pub marks: Arc<Vec<PathPoint>>,
    /// The last cut of the stock received for this scene (see [`Backplot::stock_request`]).
    pub stock: Option<Arc<StockCut>>,
    /// (segments cut, segments to cut) while a cut of the stock is under way.
    pub stock_progress: Option<(usize, usize)>,
    /// Whether the analysis simplifies the path for the view (see [`Backplot::lod_request`]);
    /// otherwise the view does, in its frames (a scene made by hand).
    pub lod_from_analysis: bool,
    /// The path's points kept at the level of detail last received from the analysis.
    pub lod: Option<Lod>,
}

impl Scene {
    /// Number of segments (one fewer than points).
    pub fn segment_count(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// The segments of source `line` as runs in order (several if it ran more than once).
    pub fn segments_of_line(&self, line: u32) -> Vec<Range<usize>> {
        let mut runs: Vec<Range<usize>> = Vec::new();
        for (i, _) in self.lines.iter().enumerate().filter(|(_, l)| **l == line) {
            match runs.last_mut() {
                Some(run) if run.end == i => run.end = i + 1,
                _ => runs.push(i..i + 1),
            }
        }
        runs
    }

    /// The box a fit frames: the toolpath and its marks, not the machine's travel box.
    pub fn view_bounds(&self) -> Option<(Vec3, Vec3)> {
        view_bounds(self.bounds, &self.marks)
    }

    /// Whether the timeline covers every segment (otherwise each takes one second).
    fn timed(&self) -> bool {
        self.timeline.len() == self.segment_count()
    }

    /// Seconds from the program start to the end of the last segment's move or dwell.
    pub fn total_secs(&self) -> f64 {
        if self.timed() {
            self.timeline.total_secs()
        } else {
            self.segment_count() as f64
        }
    }

    /// When segment `i` starts and ends moving, in seconds from the program start.
    pub fn segment_span(&self, i: usize) -> Option<(f64, f64)> {
        if self.timed() {
            self.timeline.span(i)
        } else {
            (i < self.segment_count()).then_some((i as f64, i as f64 + 1.0))
        }
    }

    /// How many segments have finished at time `t` (the executed part of the path).
    pub fn finished_at(&self, t: f64) -> usize {
        if self.timed() {
            self.timeline.finished_at(t)
        } else {
            (t.max(0.0).floor() as usize).min(self.segment_count())
        }
    }

    /// The segment running at time `t` (at a segment's end, it; past the end, the last).
    pub fn segment_at(&self, t: f64) -> Option<usize> {
        let last = self.segment_count().checked_sub(1)?;
        if self.timed() {
            self.timeline.segment_at(t)
        } else {
            Some(((t.ceil() - 1.0).max(0.0) as usize).min(last))
        }
    }

    /// Where the tool is at time `t`, in the scene's frame (linear along the running segment).
    pub fn position_at(&self, t: f64) -> Option<Vec3> {
        let i = self.segment_at(t)?;
        let (start, end) = self.segment_span(i)?;
        let f = if end > start {
            ((t - start) / (end - start)).clamp(0.0, 1.0)
        } else {
            f64::from(u8::from(t >= end))
        };
        let from = self.points.get(i)?.position();
        let to = self.points.get(i + 1)?.position();
        Some(from.lerp(to, f as f32))
    }
}

/// Runs of consecutive segments (a block's, which may have run more than once).
type Runs = Arc<Vec<Range<usize>>>;

/// What is under the cursor in the backplot (or was clicked).
#[derive(Clone, Debug, PartialEq)]
pub struct HoverInfo {
    /// Segment index in the scene.
    pub segment: usize,
    /// 1-based source line of the block that made it.
    pub line: u32,
    /// Point of the segment nearest to the cursor, in machine coordinates (mm).
    pub position: DVec3,
    /// Feed in mm/min (0 for rapids).
    pub feed: f32,
    /// Kind of motion.
    pub kind: Option<Kind>,
}

/// What a hover pick depended on, so it is not repeated while nothing changes: the scene's
/// generation, the pointer, the view's rect and camera, the kinds hidden and the stock drawn (by
/// address, 0: none).
type HoverKey = (u64, egui::Pos2, egui::Rect, OrbitCamera, u32, usize);

/// State of one backplot view: camera, selection, playback and display options (by default
/// the isometric view, fitting the first geometry shown).
#[derive(Clone, Debug, Default)]
pub struct Backplot {
    camera: OrbitCamera,
    /// Generation of the last scene shown, to notice new geometry.
    last_generation: Option<u64>,
    /// Whether the last scene shown had geometry (fit again when it reappears).
    had_geometry: bool,
    /// Whether the last fit asked for is done; if not, fit on the next frame …
    fitted: bool,
    /// … or once the scene has caught up with [`Self::coming`] (a program just opened).
    fit_waits: bool,
    /// The generation of a scene still being made for the text shown, if any.
    coming: Option<u64>,
    /// Fit to the selected block on the next frame.
    zoom_to_selection_pending: bool,
    /// The block whose segments are highlighted.
    selected_line: Option<u32>,
    /// A line clicked in the view, or playback moved to, not yet taken by
    /// [`Self::take_picked_line`].
    picked_line: Option<u32>,
    /// The playback bar's state.
    playback: Playback,
    /// Kinds not drawn (and not picked).
    hidden_kinds: u32,
    /// Colour by kind or by tool.
    color_mode: ColorMode,
    /// What the cursor is over.
    hover: Option<HoverInfo>,
    /// Where the cursor meets the stock's surface (machine mm).
    stock_hover: Option<DVec3>,
    hover_key: Option<HoverKey>,
    /// Whether the cut stock is drawn (and asked of the analysis).
    stock_on: bool,
    /// Whether the stock is drawn without the toolpath.
    stock_alone: bool,
    /// The cut last asked for: (analysis generation, segments).
    stock_asked: Option<(u64, usize)>,
    /// The last cut with heights received, drawn until the next one comes (an edit's cut).
    shown_stock: Option<Arc<StockCut>>,
    /// Where the Stock button was drawn at the last frame.
    stock_button: Option<egui::Rect>,
    /// Highlighted segments cached per (generation, line).
    selection: Option<(u64, u32, Runs)>,
    /// Where the view was last drawn, for [`Self::screen_pos`].
    last_rect: Option<egui::Rect>,
    /// The view's widget id at the last frame (whose keyboard focus [`Self::has_focus`] asks).
    last_id: Option<egui::Id>,
    /// The level of detail the last frame's view needs of the scene of a generation.
    lod_wanted: Option<(u64, LodLevel)>,
    /// The level of detail last asked of the analysis.
    lod_asked: Option<(u64, LodLevel)>,
    /// Whether the GPU view is still drawing a picture over several frames (set by its paint
    /// callback).
    painting: Arc<AtomicBool>,
}

impl Backplot {
    /// Registers the GPU resources; call once with eframe's `cc.wgpu_render_state` (one sample).
    pub fn install(ctx: &egui::Context, render_state: &egui_wgpu::RenderState) {
        let resources = BackplotResources {
            compositor: Compositor::new(&render_state.device, render_state.target_format, 1),
            views: HashMap::new(),
        };
        (render_state.renderer.write().callback_resources).insert(resources);
        ctx.data_mut(|d| d.insert_temp(installed_key(), true));
    }

    /// Frames everything drawn once the scene of a text being made is shown (a program opened).
    pub fn fit(&mut self) {
        (self.fitted, self.fit_waits) = (false, true);
    }

    /// Frames everything drawn on the next frame, whatever is being made (Fit, keys, views).
    fn fit_now(&mut self) {
        (self.fitted, self.fit_waits) = (false, false);
    }

    /// Looks from a standard direction, framing everything drawn.
    fn set_view(&mut self, view: StandardView) {
        self.camera.set_view(view);
        self.fit_now();
    }

    /// The generation of the scene being made for the text shown, which [`Self::fit`] awaits.
    pub fn set_coming_generation(&mut self, generation: Option<u64>) {
        self.coming = generation;
    }

    /// Fit to the selected block's segments on the next frame (nothing without a selection).
    pub fn zoom_to_selection(&mut self) {
        self.zoom_to_selection_pending = true;
    }

    /// The camera, e.g. to persist it.
    pub fn camera(&self) -> &OrbitCamera {
        &self.camera
    }

    /// The 1-based source line clicked in the view, or playback moved to, since the last call
    /// (the editor goes there).
    pub fn take_picked_line(&mut self) -> Option<u32> {
        self.picked_line.take()
    }

    /// The block (1-based source line) whose segments are highlighted.
    pub fn selected_line(&self) -> Option<u32> {
        self.selected_line
    }

    /// Highlights the segments of 1-based source `line` (the editor's cursor line), or none.
    pub fn set_selected_line(&mut self, line: Option<u32>) {
        self.selected_line = line;
    }

    /// The playback bar's state (time, speed, block).
    pub fn player(&self) -> &Playback {
        &self.playback
    }

    /// Mutable access to the playback bar's state, e.g. to play or step from code.
    pub fn player_mut(&mut self) -> &mut Playback {
        &mut self.playback
    }

    /// The playback bar (before [`Self::show`]); its block is highlighted and reported.
    pub fn playback_bar(&mut self, ui: &mut egui::Ui, scene: &Scene) {
        self.playback.ui(ui, scene);
        if let Some(line) = self.playback.take_line() {
            (self.selected_line, self.picked_line) = (Some(line), Some(line));
        }
    }

    /// Whether segments of `kind` are drawn.
    pub fn kind_visible(&self, kind: Kind) -> bool {
        self.hidden_kinds & kind.mask() == 0
    }

    /// The colouring in use: by kind of move or by tool.
    pub fn color_mode(&self) -> ColorMode {
        self.color_mode
    }

    /// Switches between colours by kind of move and by tool.
    pub fn toggle_color_by_tool(&mut self) {
        self.color_mode = match self.color_mode {
            ColorMode::ByKind => ColorMode::ByIndex,
            ColorMode::ByIndex => ColorMode::ByKind,
        };
    }

    /// Switches between the perspective and the orthographic projection.
    fn toggle_projection(&mut self) {
        self.camera.projection = match self.camera.projection {
            Projection::Perspective => Projection::Orthographic,
            Projection::Orthographic => Projection::Perspective,
        };
    }

    /// Shows `kind` if hidden, hides it if shown (hidden segments are not picked).
    fn toggle_kind(&mut self, kind: Kind) {
        self.hidden_kinds ^= kind.mask();
    }

    /// What the cursor was over at the last frame.
    pub fn hovered(&self) -> Option<&HoverInfo> {
        self.hover.as_ref()
    }

    /// Where a point of the scene appeared on screen at the last frame; `None` if it did not.
    pub fn screen_pos(&self, p: Vec3) -> Option<egui::Pos2> {
        let rect = self.last_rect?;
        let clip = self.camera.view_proj(rect.width() / rect.height()) * p.extend(1.0);
        if clip.w <= 0.0 || clip.z < 0.0 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(egui::pos2(
            rect.min.x + (ndc.x + 1.0) * 0.5 * rect.width(),
            rect.min.y + (1.0 - ndc.y) * 0.5 * rect.height(),
        ))
    }

    /// Draws the scene filling the available space, handles input and picking, and fits to
    /// extents the first time geometry appears. A click or drag gives the view the keyboard
    /// (shown by an outline); its keys act only then, so they never reach the editor.
    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) -> egui::Response {
        let size = ui.available_size().max(egui::vec2(64.0, 64.0));
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        let background = ui.visuals().extreme_bg_color;
        ui.painter().rect_filled(rect, 0.0, background);

        let installed = ui.ctx().data(|d| d.get_temp::<bool>(installed_key()));
        if installed != Some(true) {
            // A real label (not painter text) so screen readers and tests can find it.
            let notice = egui::RichText::new(tr("3D view unavailable")).weak();
            ui.put(rect, egui::Label::new(notice));
            self.lod_wanted = None;
            return response;
        }

        self.track_scene(scene);
        self.take_focus(ui, &response);
        self.handle_input(ui, &response, rect);
        // The paint slot now (buttons on top of it), the callback last (clicks act at once).
        let slot = ui.painter().add(egui::Shape::Noop);
        let (buttons, clicked) = self.overlay_buttons(ui, rect);
        if self.stock_buttons(ui, rect, scene) || clicked {
            // A button of the view keeps the keyboard with the view.
            response.request_focus();
        }

        let aspect = rect.width() / rect.height();
        if self.fit_due(scene) {
            (self.fitted, self.fit_waits) = (true, false);
            self.frame_scene(scene, rect, buttons);
        }
        // Picked with this frame's camera, before the highlight, so a click shows at once.
        self.handle_picking(&response, rect, scene);
        self.last_rect = Some(rect);
        let selection = self.selection_runs(scene);
        if std::mem::take(&mut self.zoom_to_selection_pending) {
            let bounds = selection
                .iter()
                .filter_map(|run| segment_bounds(&scene.points, run.clone()))
                .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)));
            if let Some((min, max)) = bounds {
                self.camera.zoom_to_selection(min, max, aspect);
            }
        }

        let to_u32 = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        // One run goes to the shader as a range; several are flagged on the points instead.
        let (highlight, flagged) = match selection.as_slice() {
            [] => (0..0, Arc::new(Vec::new())),
            [run] => (to_u32(run.start)..to_u32(run.end), Arc::new(Vec::new())),
            _ => (0..0, Arc::clone(&selection)),
        };
        let view_proj = self.camera.view_proj(aspect);
        if scene.lod_from_analysis {
            let view = ViewParams {
                view_proj,
                viewport_px: Vec2::new(rect.width(), rect.height()) * ui.ctx().pixels_per_point(),
                ..ViewParams::default()
            };
            let shown = scene.lod.as_ref().and_then(|l| l.level);
            let level = scene.bounds.and_then(|b| lod_level(&view, b, shown));
            self.lod_wanted = Some((scene.generation, level));
        }
        let params = ViewParams {
            view_proj,
            executed_segments: self.playback.executed(scene).map(to_u32),
            highlight,
            hidden_kinds: self.hidden(),
            color_mode: self.color_mode,
            ..ViewParams::default()
        };
        let callback = BackplotCallback {
            id: response.id,
            frame: ui.ctx().cumulative_frame_nr(),
            scene: scene.clone(),
            flagged,
            stock: self.drawn_stock(scene),
            rect,
            params,
            ctx: ui.ctx().clone(),
            painting: Arc::clone(&self.painting),
        };
        ui.painter().set(
            slot,
            egui_wgpu::Callback::new_paint_callback(rect, callback),
        );
        self.paint_rapids_into_stock(ui, rect, scene);
        self.paint_tool(ui, rect, scene);
        if response.has_focus() {
            // The keyboard is the view's: an outline in the focus colour says so.
            let stroke =
                egui::Stroke::new(FOCUS_OUTLINE_POINTS, ui.visuals().selection.stroke.color);
            ui.painter()
                .rect_stroke(rect, 0.0, stroke, egui::StrokeKind::Inside);
        }
        if self.hover.is_none() && self.stock_hover.is_none() {
            return response;
        }
        response.on_hover_ui_at_pointer(|ui| {
            if let Some(hover) = &self.hover {
                hover_tooltip(ui, hover, scene);
            }
            if let Some(p) = self.stock_hover {
                let [x, y, z] = p.to_array().map(|v| format!("{v:.3}"));
                ui.label(trf("Stock X{} Y{} Z{}", &[&x, &y, &z]));
            }
        })
    }

    /// The level of detail to ask the analysis for after [`Self::show`], when the view needs
    /// one the scene does not have: a dense path is simplified beside the frames, and the
    /// level received last is drawn until the new one comes.
    pub fn lod_request(&mut self, scene: &Scene) -> Option<Request> {
        let (generation, level) = self.lod_wanted?;
        let due = scene.lod_from_analysis
            && generation == scene.generation
            && scene.segment_count() > 0
            && scene.lod.as_ref().is_none_or(|l| l.level != level)
            && self.lod_asked != Some((generation, level));
        if !due {
            return None;
        }
        self.lod_asked = Some((generation, level));
        Some(Request::Lod { generation, level })
    }

    /// Whether the view's picture is not complete on screen yet: it waits for the path of
    /// `scene` at the level of detail it needs, or is still drawing it over several frames.
    pub fn drawing_pending(&self, scene: &Scene) -> bool {
        self.lod_pending(scene) || self.painting.load(Ordering::Relaxed)
    }

    /// Whether the view still waits for the path of `scene` at the level of detail it needs
    /// (a view that draws nothing waits for none).
    pub fn lod_pending(&self, scene: &Scene) -> bool {
        let Some((generation, level)) = self.lod_wanted else {
            return false;
        };
        let shown = scene.lod.as_ref().map(|l| l.level);
        scene.lod_from_analysis
            && scene.segment_count() > 0
            && if generation == scene.generation {
                shown != Some(level)
            } else {
                shown.is_none()
            }
    }

    /// The level of detail an analysis of the text shown should simplify its path at: the
    /// view's, unless it is about to frame a new program (its zoom then changes).
    pub fn lod_for_job(&self, scene: &Scene) -> Option<LodLevel> {
        let level = scene.lod.as_ref().map(|l| l.level)?;
        (self.fitted || !self.fit_waits).then_some(level)
    }

    /// Whether a fit asked for is due with `scene` (at once, or once the awaited scene is shown).
    fn fit_due(&self, scene: &Scene) -> bool {
        !self.fitted && (!self.fit_waits || self.coming.is_none_or(|g| g <= scene.generation))
    }

    /// Whether the view has the keyboard focus (its keys act only then).
    pub fn has_focus(&self, ctx: &egui::Context) -> bool {
        self.last_id
            .is_some_and(|id| ctx.memory(|m| m.has_focus(id)))
    }

    /// A press, click or drag gives the view the keyboard; the arrows and Escape then stay.
    fn take_focus(&mut self, ui: &egui::Ui, response: &egui::Response) {
        self.last_id = Some(response.id);
        let pressed = response.is_pointer_button_down_on()
            || response.clicked()
            || response.secondary_clicked()
            || response.middle_clicked()
            || response.drag_started();
        if pressed && !response.has_focus() {
            response.request_focus();
        }
        if response.has_focus() {
            crate::editor::keep_keys(ui, response.id, false, true);
        }
    }

    /// Frames [`Scene::view_bounds`] in the part of `rect` below the view's `buttons`.
    fn frame_scene(&mut self, scene: &Scene, rect: egui::Rect, buttons: egui::Rect) {
        let top = if buttons.is_positive() {
            (buttons.max.y + FIT_GAP_POINTS).min(rect.max.y - 1.0)
        } else {
            rect.min.y
        };
        let viewport = Vec2::new(rect.width(), rect.height());
        let (free_min, free_max) = (Vec2::new(0.0, top - rect.min.y), viewport);
        let mut bounds = scene.view_bounds();
        // With the Stock view on, the whole block is framed too.
        if let Some((lo, hi)) = self.shown_field().map(stock::stock_box) {
            let (lo, hi) = ((lo - scene.origin).as_vec3(), (hi - scene.origin).as_vec3());
            bounds = Some(bounds.map_or((lo, hi), |(min, max)| (min.min(lo), max.max(hi))));
        }
        match bounds {
            Some((min, max)) => self.camera.fit_in(min, max, viewport, free_min, free_max),
            // Nothing to frame: the default view of the origin.
            None => self
                .camera
                .fit_aspect(Vec3::ONE, Vec3::ZERO, rect.width() / rect.height()),
        }
    }

    /// The tool marker at the playback position: the tool's cylinder, or a small cone and shank.
    fn paint_tool(&self, ui: &egui::Ui, rect: egui::Rect, scene: &Scene) {
        let Some(tip) = self.playback.position(scene) else {
            return;
        };
        let segment = self.playback.current_segment(scene);
        let tool = segment.and_then(|i| scene.tools.get(i));
        let radius = tool.and_then(|t| scene.tool_radii.get(t)).copied();
        let radius = radius.filter(|r| r.is_finite() && *r > 0.0);
        let outline: Vec<(Vec3, Vec3)> = if let Some(r) = radius {
            tool_outline(tip, r, 0.0, 3.0 * r)
        } else {
            let r = self.camera.units_per_px(rect.height()) * TOOL_MARKER_POINTS;
            tool_outline(tip, r, 2.0 * r, 2.0 * r)
        };
        let painter = ui.painter_at(rect);
        let stroke = egui::Stroke::new(1.5, TOOL_MARKER_COLOR);
        for (a, b) in outline {
            if let (Some(a), Some(b)) = (self.screen_pos(a), self.screen_pos(b)) {
                painter.line_segment([a, b], stroke);
            }
        }
        if let Some(p) = self.screen_pos(tip) {
            painter.circle_filled(p, 2.5, TOOL_MARKER_COLOR);
        }
    }

    /// Notices new scene generations and schedules a fit when geometry first appears.
    fn track_scene(&mut self, scene: &Scene) {
        if self.last_generation == Some(scene.generation) {
            return;
        }
        self.last_generation = Some(scene.generation);
        let has_geometry = scene.bounds.is_some();
        // Geometry appearing (again) is fitted.
        self.fitted &= !has_geometry || self.had_geometry;
        self.had_geometry = has_geometry;
    }

    /// The selected block's segments, as runs (cached per scene generation and line).
    fn selection_runs(&mut self, scene: &Scene) -> Runs {
        let Some(line) = self.selected_line else {
            return Arc::new(Vec::new());
        };
        if let Some((generation, cached, runs)) = &self.selection
            && (*generation, *cached) == (scene.generation, line)
        {
            return Arc::clone(runs);
        }
        let runs = Arc::new(scene.segments_of_line(line));
        self.selection = Some((scene.generation, line, Arc::clone(&runs)));
        runs
    }

    /// The segments of the selected block highlighted at the last frame, as runs.
    pub fn highlighted_segments(&self) -> Vec<Range<usize>> {
        match (&self.selection, self.selected_line) {
            (Some((_, line, runs)), Some(selected)) if *line == selected => runs.to_vec(),
            _ => Vec::new(),
        }
    }

    /// The segment within [`PICK_RADIUS`] of `pointer` (screen position), if any.
    fn pick(&self, scene: &Scene, rect: egui::Rect, pointer: egui::Pos2) -> Option<HoverInfo> {
        let viewport = Vec2::new(rect.width(), rect.height());
        let cursor = pointer - rect.min;
        let cursor = Vec2::new(cursor.x, cursor.y);
        let view_proj = self.camera.view_proj(rect.width() / rect.height());
        // Over the chords drawn first, each within its tolerance on screen of what it stands
        // for, so a hover costs what is drawn rather than the path's length.
        let drawn = scene.lod.as_ref().filter(|_| scene.lod_from_analysis);
        let slack = drawn.and_then(|lod| {
            let scale = pixels_per_unit(view_proj, viewport, scene.bounds?)?;
            Some((
                &lod.kept,
                (lod.level? as f32).exp2() * scale + PICK_SLACK_ROUNDING,
            ))
        });
        let hit = match slack {
            Some((kept, slack)) => pick_kept_segment(
                &scene.points,
                kept,
                (view_proj, viewport, cursor),
                PICK_RADIUS,
                self.hidden(),
                slack,
            ),
            None => pick_segment(
                &scene.points,
                view_proj,
                viewport,
                cursor,
                PICK_RADIUS,
                self.hidden(),
            ),
        }?;
        Some(HoverInfo {
            segment: hit.segment,
            line: *scene.lines.get(hit.segment)?,
            position: scene.origin + hit.position(&scene.points)?.as_dvec3(),
            feed: scene.feeds.get(hit.segment).copied().unwrap_or(0.0),
            kind: scene.points.get(hit.segment + 1).and_then(PathPoint::kind),
        })
    }

    /// A click selects the block under the cursor; hovering picks for the tooltip on a change.
    fn handle_picking(&mut self, response: &egui::Response, rect: egui::Rect, scene: &Scene) {
        if response.clicked()
            && let Some(pointer) = response.interact_pointer_pos()
        {
            let line = self.pick(scene, rect, pointer).map(|h| h.line);
            self.selected_line = line;
            self.picked_line = line.or(self.picked_line);
        }
        let Some(pointer) = response.hover_pos().filter(|_| !response.dragged()) else {
            (self.hover, self.stock_hover, self.hover_key) = (None, None, None);
            return;
        };
        let stock = self.drawn_stock(scene);
        let stock = stock.map_or(0, |s| Arc::as_ptr(&s) as usize);
        let (generation, camera, hidden) = (scene.generation, self.camera, self.hidden());
        let key = (generation, pointer, rect, camera, hidden, stock);
        if self.hover_key != Some(key) {
            self.hover = self.pick(scene, rect, pointer);
            self.stock_hover = self.stock_point(scene, rect, pointer);
            self.hover_key = Some(key);
        }
    }

    /// Orbit (left drag, one finger), pan (right/middle or shift+left drag, two fingers),
    /// zoom (scroll, pinch), fit (double click) and the keyboard (see [`Self::handle_keys`]).
    fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response, rect: egui::Rect) {
        let viewport = Vec2::new(rect.width(), rect.height());
        let shift = ui.input(|i| i.modifiers.shift);
        let delta = response.drag_delta();
        let delta = Vec2::new(delta.x, delta.y);
        let touch = ui.input(egui::InputState::multi_touch);
        let touch = touch.filter(|t| t.num_touches >= 2 && response.hovered());
        if let Some(touch) = touch {
            // Two fingers pan; their pinch zooms below (egui's zoom delta).
            let moved = touch.translation_delta;
            self.camera.pan(Vec2::new(moved.x, moved.y), viewport);
        } else if response.dragged_by(egui::PointerButton::Secondary)
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
            self.fit_now();
        }
        // A key goes to one place: the view's keys act only while it has the keyboard focus.
        if response.has_focus() {
            self.handle_keys(ui, viewport);
        }
    }

    /// Keys while the view has the keyboard: arrows orbit (pan with Shift), `+`/`-` zoom, `F`
    /// fits, `S` zooms to the selection, `1`–`4` standard views, `P` perspective, `R` rapids, `T`
    /// colours by tool, Escape clears the selection.
    fn handle_keys(&mut self, ui: &egui::Ui, viewport: Vec2) {
        use egui::Key;
        let (shift, pressed) = ui.input(|i| {
            use egui::Key::*;
            let keys = [
                ArrowLeft, ArrowRight, ArrowUp, ArrowDown, Plus, Equals, Minus, F, S, Num1, Num2,
                Num3, Num4, P, R, T, Escape,
            ];
            let pressed: Vec<Key> = keys.into_iter().filter(|k| i.key_pressed(*k)).collect();
            (i.modifiers.shift, pressed)
        });
        for key in pressed {
            let step = match key {
                Key::ArrowLeft => Vec2::new(-1.0, 0.0),
                Key::ArrowRight => Vec2::new(1.0, 0.0),
                Key::ArrowUp => Vec2::new(0.0, -1.0),
                Key::ArrowDown => Vec2::new(0.0, 1.0),
                _ => Vec2::ZERO,
            };
            let moved = step != Vec2::ZERO;
            match key {
                _ if moved && shift => self.camera.pan(step * KEY_PAN_POINTS, viewport),
                _ if moved => self.camera.orbit(step * KEY_ORBIT_POINTS),
                Key::Plus | Key::Equals => self.camera.zoom(KEY_ZOOM),
                Key::Minus => self.camera.zoom(1.0 / KEY_ZOOM),
                Key::F => self.fit_now(),
                Key::S => self.zoom_to_selection(),
                _ if let Some(&(_, _, view)) = STANDARD_VIEWS.iter().find(|v| v.1 == key) => {
                    self.set_view(view);
                }
                Key::P => self.toggle_projection(),
                Key::R => self.toggle_kind(Kind::Rapid),
                Key::T => self.toggle_color_by_tool(),
                Key::Escape => self.selected_line = None,
                _ => {}
            }
        }
    }

    /// The buttons in the view's top-left corner; where they lie and whether one was clicked.
    fn overlay_buttons(&mut self, ui: &mut egui::Ui, rect: egui::Rect) -> (egui::Rect, bool) {
        let mut child = button_row(ui, rect, "swarf_backplot_buttons", egui::Align::Min);
        let hint = tr("Fit to extents (double-click)");
        let mut clicked = child.small_button(tr("Fit")).on_hover_text(hint).clicked();
        if clicked {
            self.fit_now();
        }
        for (label, _, view) in STANDARD_VIEWS {
            if child.small_button(tr(label)).clicked() {
                clicked = true;
                self.set_view(view);
            }
        }
        let mut toggle = |on: bool, label: &'static str, hint: &'static str| {
            let label = child.selectable_label(on, tr(label));
            let hit = label.on_hover_text(tr(hint)).clicked();
            clicked |= hit;
            hit
        };
        let perspective = self.camera.projection == Projection::Perspective;
        let hint = "Perspective / orthographic projection";
        if toggle(perspective, "Persp", hint) {
            self.toggle_projection();
        }
        let by_tool = self.color_mode == ColorMode::ByIndex;
        let hint = "Colour the path by tool instead of by kind of move (T)";
        if toggle(by_tool, "By tool", hint) {
            self.toggle_color_by_tool();
        }
        let contour = self.kind_visible(Kind::Programmed);
        let hint =
            "Show the programmed contour beside the tool centre's path under cutter compensation";
        if toggle(contour, "Contour", hint) {
            self.toggle_kind(Kind::Programmed);
        }
        let rapids = self.kind_visible(Kind::Rapid);
        if toggle(rapids, "Rapids", "Show or hide rapid moves") {
            self.toggle_kind(Kind::Rapid);
        }
        if self.selected_line.is_some()
            && child
                .small_button(tr("Zoom sel"))
                .on_hover_text(tr("Zoom to the selected block"))
                .clicked()
        {
            clicked = true;
            self.zoom_to_selection();
        }
        (child.min_rect(), clicked)
    }

    /// The stock's buttons and progress in the bottom-left corner; whether one was clicked.
    fn stock_buttons(&mut self, ui: &mut egui::Ui, rect: egui::Rect, scene: &Scene) -> bool {
        let mut clicked = false;
        let mut child = button_row(ui, rect, "swarf_backplot_stock_buttons", egui::Align::Max);
        let stock = child.selectable_label(self.stock_on, tr("Stock"));
        let stock = stock.on_hover_text(tr(
            "Show the stock as the program cuts it (up to the playback position while playing)",
        ));
        self.stock_button = Some(stock.rect);
        if stock.clicked() {
            clicked = true;
            self.stock_on = !self.stock_on;
        }
        if !self.stock_on {
            return clicked;
        }
        let path = child.selectable_label(!self.stock_alone, tr("Path"));
        let hint = tr("Draw the toolpath over the stock");
        if path.on_hover_text(hint).clicked() {
            clicked = true;
            self.stock_alone = !self.stock_alone;
        }
        let error = scene.stock.as_ref().and_then(|c| c.error.as_deref());
        if let Some((done, upto)) = scene.stock_progress {
            let percent = done * 100 / upto.max(1);
            let fraction = done as f32 / upto.max(1) as f32;
            let bar = egui::ProgressBar::new(fraction).desired_width(110.0);
            child.add(bar.text(trf("Stock {}%", &[&percent])));
        } else if let Some(error) = error {
            let hint = trf("Stock: {}", &[&error]);
            child.weak(tr("No stock")).on_hover_text(hint);
        }
        clicked
    }
}

/// A row of the view's buttons from its left edge, along its top (`Min`) or bottom (`Max`).
fn button_row(ui: &mut egui::Ui, rect: egui::Rect, salt: &str, align: egui::Align) -> egui::Ui {
    let layout = egui::Layout::left_to_right(align);
    let builder = egui::UiBuilder::new().id_salt(salt).layout(layout);
    ui.new_child(builder.max_rect(rect.shrink(6.0)))
}

/// Radius of the tool marker, in points, when the setup gives no tool radius.
const TOOL_MARKER_POINTS: f32 = 7.0;

/// Colour of the tool marker's lines.
const TOOL_MARKER_COLOR: egui::Color32 = egui::Color32::from_rgb(250, 250, 250);

/// Line segments of a tool standing on `tip` along +Z: a cone from the tip up to radius
/// `radius` over `cone` (none when 0: a flat end), then a cylinder of that radius `shank` high.
fn tool_outline(tip: Vec3, radius: f32, cone: f32, shank: f32) -> Vec<(Vec3, Vec3)> {
    const SIDES: usize = 24;
    let ring = |z: f32| -> Vec<Vec3> {
        (0..SIDES)
            .map(|k| {
                let a = k as f32 / SIDES as f32 * std::f32::consts::TAU;
                tip + Vec3::new(radius * a.cos(), radius * a.sin(), z)
            })
            .collect()
    };
    let low = ring(cone);
    let high = ring(cone + shank);
    let mut lines = Vec::with_capacity(SIDES * 2 + 12);
    for k in 0..SIDES {
        let next = (k + 1) % SIDES;
        lines.push((low[k], low[next]));
        lines.push((high[k], high[next]));
    }
    for k in (0..SIDES).step_by(SIDES / 4) {
        lines.push((low[k], high[k]));
        if cone > 0.0 {
            lines.push((tip, low[k]));
        }
    }
    lines
}

/// The names of the kinds of motion, in [`Kind`]'s order.
const KIND_NAMES: &str = "rapid feed arc plunge retract cycle compensated programmed";

/// The hover tooltip: line and block text, position, kind and feed.
fn hover_tooltip(ui: &mut egui::Ui, hover: &HoverInfo, scene: &Scene) {
    let kind = hover.kind.map_or(usize::MAX, |k| k as usize);
    let kind = tr(KIND_NAMES.split(' ').nth(kind).unwrap_or("move"));
    ui.strong(trf("Line {}", &[&hover.line]));
    if let Some(text) = scene.source.as_ref().and_then(|s| s.line(hover.line)) {
        let text = text.trim();
        let shown: String = text.chars().take(TOOLTIP_TEXT_CHARS).collect();
        let ellipsis = if shown.len() < text.len() { "…" } else { "" };
        ui.monospace(format!("{shown}{ellipsis}"));
    }
    let p = hover.position;
    ui.label(format!("X{:.3} Y{:.3} Z{:.3}", p.x, p.y, p.z));
    if hover.kind == Some(Kind::Rapid) || hover.feed <= 0.0 {
        ui.label(kind);
    } else {
        ui.label(format!("{kind} F{}", hover.feed));
    }
}

/// GPU state shared by all backplots, stored in egui-wgpu's `callback_resources`.
pub struct BackplotResources {
    compositor: Compositor,
    views: HashMap<egui::Id, GpuView>,
}

/// One backplot's renderer, offscreen target and what it last drew.
struct GpuView {
    renderer: PathRenderer,
    /// The scene's path at the level of detail of the last image.
    path: PathLod,
    /// The picture shown, and the bind group that composites it.
    target: Option<(RenderTarget, wgpu::BindGroup)>,
    /// A picture of new points drawn a piece a frame while `target` keeps showing the last
    /// one, or the target it will be drawn into next.
    next: Option<Next>,
    generation: Option<u64>,
    /// Parameters of the picture in `target` (or being drawn into `next`); drawing again is
    /// skipped while they hold.
    drawn: Option<ViewParams>,
    /// Whether the points changed since `drawn`: the next picture is then drawn over several
    /// frames when it is more than [`FRAME_WORK`].
    new_points: bool,
    /// The runs of segments whose points carry the highlight flag on the GPU.
    flagged: Runs,
    /// The stock on the GPU.
    stock: Option<Arc<StockCut>>,
    last_frame: u64,
}

/// A picture drawn into its own target a piece a frame.
struct Next {
    /// The target and the bind group that composites it.
    target: (RenderTarget, wgpu::BindGroup),
    /// The work drawn so far (see [`PathRenderer::paint_part`]); `None`: nothing is being
    /// drawn, the target waits to be used.
    done: Option<u64>,
}

/// The per-frame paint callback: what to draw and from where.
struct BackplotCallback {
    id: egui::Id,
    frame: u64,
    /// The scene drawn (its arrays shared, not copied).
    scene: Scene,
    /// Runs of segments to highlight by flagging their points (a single run: `params.highlight`).
    flagged: Runs,
    /// The cut stock drawn under the path, if any.
    stock: Option<Arc<StockCut>>,
    rect: egui::Rect,
    /// View parameters in points, for the whole rectangle.
    params: ViewParams,
    /// To ask for the next frame while a picture is drawn over several.
    ctx: egui::Context,
    /// Set while a picture is drawn over several frames.
    painting: Arc<AtomicBool>,
}

impl egui_wgpu::CallbackTrait for BackplotCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        screen_descriptor: &egui_wgpu::ScreenDescriptor,
        egui_encoder: &mut wgpu::CommandEncoder,
        callback_resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(BackplotResources { compositor, views }) =
            callback_resources.get_mut::<BackplotResources>()
        else {
            return Vec::new();
        };
        views.retain(|_, view| view.last_frame + STALE_FRAMES >= self.frame);
        let view = views.entry(self.id).or_insert_with(|| GpuView {
            renderer: PathRenderer::new(device, OFFSCREEN_FORMAT, Some(DEPTH_FORMAT), 1),
            path: PathLod::default(),
            target: None,
            next: None,
            generation: None,
            drawn: None,
            new_points: false,
            flagged: Arc::new(Vec::new()),
            stock: None,
            last_frame: self.frame,
        });
        view.last_frame = self.frame;
        let same_stock =
            view.stock.as_ref().map(Arc::as_ptr) == self.stock.as_ref().map(Arc::as_ptr);
        let scene = &self.scene;
        if !same_stock || view.generation != Some(scene.generation) {
            let surface = self.stock.as_ref().and_then(|c| c.field.as_ref());
            let surface = surface.map(|f| StockSurface {
                heights: &f.heights,
                size: f.size,
                cell_mm: f.cell_mm,
                min: f.min,
                top: f.top,
                origin: scene.origin,
            });
            view.renderer.set_stock(device, queue, surface.as_ref());
            view.stock.clone_from(&self.stock);
            // A cut of the stock (one a playback step) is drawn at once.
            view.drawn = None;
        }
        if view.generation != Some(scene.generation) {
            let points = Arc::clone(&scene.points);
            view.path = if scene.lod_from_analysis {
                PathLod::given(points, scene.bounds)
            } else {
                PathLod::new(points, scene.bounds)
            };
            let reference = reference_points(scene.zero, scene.bounds, &scene.marks);
            view.renderer.set_grid(device, queue, &reference);
            view.generation = Some(scene.generation);
            view.new_points = true;
        }
        if let Some(lod) = scene.lod.as_ref().filter(|_| scene.lod_from_analysis)
            && view.path.set_base(lod.level, &lod.kept)
        {
            (view.drawn, view.new_points) = (None, true);
        }
        if !Arc::ptr_eq(&view.flagged, &self.flagged) && view.flagged != self.flagged {
            view.flagged = Arc::clone(&self.flagged);
            view.drawn = None;
        }

        let ppp = screen_descriptor.pixels_per_point;
        let visible =
            ViewportInPixels::from_points(&self.rect, ppp, screen_descriptor.size_in_pixels);
        let full = self.rect * ppp;
        let Some(remap) = ndc_remap(full, &visible) else {
            self.painting.store(false, Ordering::Relaxed);
            return Vec::new();
        };
        // `ndc_remap` checked both sides are positive.
        let [w, h] = [visible.width_px, visible.height_px].map(i32::unsigned_abs);
        let new_target = || {
            // Without a target nothing is drawn (nor painted) until one can be made.
            let target = RenderTarget::new(device, w, h, OFFSCREEN_FORMAT).ok()?;
            let bind_group = compositor.bind(device, &target);
            Some((target, bind_group))
        };
        if view.target.as_ref().map(|(t, _)| t.size()) != Some((w, h)) {
            (view.drawn, view.next) = (None, None);
            view.target = new_target();
        }
        let params = ViewParams {
            view_proj: remap * self.params.view_proj,
            viewport_px: Vec2::new(w as f32, h as f32),
            ..self.params.clone().scaled(ppp)
        };
        if view.drawn.as_ref() != Some(&params)
            && let Some((target, _)) = &view.target
        {
            let drawn =
                view.path
                    .prepare(&mut view.renderer, device, queue, &params, &view.flagged);
            view.renderer.prepare(queue, &drawn);
            // New points too many for one frame are drawn a piece a frame beside the picture
            // shown; anything else (the camera, the highlight, playback) at once, so the view
            // answers the hand that moves it.
            let piecewise = view.new_points && view.renderer.work() > FRAME_WORK;
            if piecewise && view.next.is_none() {
                view.next = new_target().map(|target| Next { target, done: None });
            }
            if let Some(next) = view.next.as_mut().filter(|_| piecewise) {
                next.done = Some(0);
            } else {
                target.draw(egui_encoder, wgpu::Color::TRANSPARENT, &view.renderer);
                if let Some(next) = &mut view.next {
                    next.done = None;
                }
            }
            view.drawn = Some(params);
            view.new_points = false;
        }
        if let Some(next) = &mut view.next
            && let Some(done) = next.done
        {
            let work = view.renderer.work();
            let part = done..(done + FRAME_WORK).min(work);
            let clear = (done == 0).then_some(wgpu::Color::TRANSPARENT);
            (next.target.0).draw_part(egui_encoder, clear, &view.renderer, part.clone());
            next.done = Some(part.end);
            if part.end >= work {
                // Complete: shown from now on; the picture it replaces takes its place.
                next.done = None;
                if let Some(target) = &mut view.target {
                    std::mem::swap(target, &mut next.target);
                }
            } else {
                self.ctx.request_repaint();
            }
        }
        let painting = view.next.as_ref().is_some_and(|n| n.done.is_some());
        self.painting.store(painting, Ordering::Relaxed);
        Vec::new()
    }

    fn paint(
        &self,
        info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        callback_resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(resources) = callback_resources.get::<BackplotResources>() else {
            return;
        };
        let view = resources.views.get(&self.id);
        let Some((_, bind_group)) = view.and_then(|v| v.target.as_ref()) else {
            return;
        };
        // The callback rect clamped to the screen, as `prepare` sized the target.
        let vp = info.viewport_in_pixels();
        if vp.width_px <= 0 || vp.height_px <= 0 {
            return;
        }
        let [x, y, w, h] = [vp.left_px, vp.top_px, vp.width_px, vp.height_px].map(|v| v as f32);
        render_pass.set_viewport(x, y, w, h, 0.0, 1.0);
        resources.compositor.paint(render_pass, bind_group);
    }
}

/// Maps NDC of the whole callback rectangle `full` (pixels) onto NDC of its on-screen part
/// `visible`, so a partly off-screen view is not squashed; `None` when nothing is visible.
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
        let px = f32::midpoint(p.x, 1.0) * 300.0;
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
        let mut plot = Backplot::default();
        let empty = Scene::default();
        plot.track_scene(&empty);
        plot.fitted = true;
        let scene = Scene {
            generation: 1,
            points: Arc::new(vec![PathPoint::default(); 2]),
            lines: Arc::new(vec![1]),
            feeds: Arc::new(vec![0.0]),
            bounds: Some((Vec3::ZERO, Vec3::ONE)),
            ..Scene::default()
        };
        plot.track_scene(&scene);
        assert!(!plot.fitted);
        plot.fitted = true;
        let edited = Scene {
            generation: 2,
            ..scene.clone()
        };
        plot.track_scene(&edited);
        assert!(plot.fitted);
        plot.track_scene(&Scene {
            generation: 3,
            ..Scene::default()
        });
        plot.track_scene(&Scene {
            generation: 4,
            ..scene
        });
        assert!(!plot.fitted);
    }

    #[test]
    fn a_fit_for_a_new_program_waits_for_its_scene() {
        let mut plot = Backplot::default();
        let old = Scene {
            generation: 4,
            bounds: Some((Vec3::ZERO, Vec3::ONE)),
            ..Scene::default()
        };
        plot.track_scene(&old);
        plot.fitted = true;
        // A program opened: its scene (generation 6) is still being made.
        plot.fit();
        plot.set_coming_generation(Some(6));
        assert!(!plot.fit_due(&old));
        assert!(!plot.fit_due(&Scene {
            generation: 5,
            ..old.clone()
        }));
        assert!(plot.fit_due(&Scene {
            generation: 6,
            ..old.clone()
        }));
        // Nothing being made: at once.
        plot.set_coming_generation(None);
        assert!(plot.fit_due(&old));
        // The view's own Fit does not wait.
        plot.set_coming_generation(Some(9));
        plot.fit_now();
        assert!(plot.fit_due(&old));
    }

    #[test]
    fn view_bounds_take_in_the_marks_but_not_the_travel_box() {
        let scene = Scene {
            bounds: Some((Vec3::ZERO, Vec3::ONE)),
            marks: Arc::new(vec![
                PathPoint::pen_up(Vec3::new(-5.0, 0.0, 0.0)),
                PathPoint::new(Vec3::new(0.0, 7.0, 0.0), Kind::Programmed),
                PathPoint::pen_up(Vec3::new(-500.0, 0.0, 0.0)),
                PathPoint::new(Vec3::new(0.0, 0.0, -400.0), Kind::Boundary),
            ]),
            ..Scene::default()
        };
        assert_eq!(
            scene.view_bounds(),
            Some((Vec3::new(-5.0, 0.0, 0.0), Vec3::new(1.0, 7.0, 1.0)))
        );
        assert_eq!(Scene::default().view_bounds(), None);
    }

    #[test]
    fn source_lines_and_segments_of_a_line() {
        let text = SourceText::new("G0 X1\r\nG1 X2\n\nM30".to_string());
        assert_eq!(text.line(1).as_deref(), Some("G0 X1"));
        assert_eq!(text.line(2).as_deref(), Some("G1 X2"));
        assert_eq!(text.line(3).as_deref(), Some(""));
        assert_eq!(text.line(4).as_deref(), Some("M30"));
        assert_eq!(text.line(5), None);
        assert_eq!(text.line(0), None);
        let scene = Scene {
            points: Arc::new(vec![PathPoint::default(); 8]),
            lines: Arc::new(vec![2, 3, 3, 5, 7, 3, 7]),
            ..Scene::default()
        };
        assert_eq!(scene.segment_count(), 7);
        // A line that ran twice (a subprogram, a loop) has two runs, and nothing between.
        assert_eq!(scene.segments_of_line(3), [1..3, 5..6]);
        let runs = scene.segments_of_line(5);
        assert_eq!((runs.len(), runs.first()), (1, Some(&(3..4))));
        assert_eq!(scene.segments_of_line(7), [4..5, 6..7]);
        assert!(scene.segments_of_line(4).is_empty());
    }
}
