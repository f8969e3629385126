//! The whole editing surface: editor, problems list and backplot, wired to the pipeline.

mod analyst;
mod dialogs;
mod edit;
mod find;
mod menus;
mod panels;
mod tabs;

use std::collections::VecDeque;
use std::sync::{Arc, OnceLock};

use swarf_analysis::{Analyst, ProgramText, Progress};
use swarf_interp::Setup;
use swarf_syntax::{Dialect, Encoding};

use crate::analysis::Analysis;
use crate::backplot::Backplot;
use crate::commands::{self, RenumberOptions};
use crate::examples::EXAMPLES;
use crate::history::{EditKind, Snapshot};
use crate::i18n::{Lang, tr, trf};
use crate::rows::CodeEditor;

use analyst::{default_analyst, no_analysis};
use find::FindBar;
use menus::Action;
use tabs::Tab;

pub use analyst::reply_frame;
pub use panels::format_duration;
pub use tabs::{Document, TabRecord};

/// The example program the editor starts with.
pub const EXAMPLE_PROGRAM: &str = EXAMPLES[0].text;

/// Width of the editor's panel until the user drags its divider, in points.
const EDITOR_PANEL_WIDTH: f32 = 460.0;
/// Width of the "state at cursor" panel until the user drags its divider: room for a position.
const STATE_PANEL_WIDTH: f32 = 280.0;
/// Height of the problems list, when there are problems, until the user drags its divider.
const PROBLEMS_PANEL_HEIGHT: f32 = 140.0;

/// Editor, problems and backplot over the active tab's program, re-analysed (beside the UI) on
/// every edit with the other tabs as the files its calls reach; the last analysis stays shown.
pub struct Workbench {
    /// The active tab's text, document, history, selection and dialect.
    tab: Tab,
    /// The dialect new tabs start in: the last one chosen in the selector or the settings.
    default_dialect: Dialect,
    setup: Setup,
    generation: u64,
    /// The active tab's last finished analysis, or an empty one while its first is running.
    analysis: Analysis,
    /// Whether `analysis` is the active tab's own (false for the empty stand-in).
    own_analysis: bool,
    /// Where the analysis runs: the workbench sends it jobs and questions, takes its replies.
    analyst: Box<dyn Analyst>,
    /// The jobs sent and not yet answered, with their texts (which go with their scenes).
    sent: VecDeque<(u64, ProgramText)>,
    /// How far the analysis of the current text has got, while it runs.
    pending: Option<Progress>,
    /// The first generation of the active tab's text: results of earlier ones are of another.
    floor: u64,
    /// The state at cursor asked of the analysis, (generation, line), until it answers.
    state_asked: Option<(u64, u32)>,
    /// The context a reply from the analysis' thread repaints (set by the first frame).
    waker: Arc<OnceLock<egui::Context>>,
    editor: CodeEditor,
    backplot: Backplot,
    /// The cursor line last sent to the backplot as its selection.
    synced_line: Option<u32>,
    /// The state shown for ((generation, line)), asked again only when either changes.
    state_cache: Option<((u64, u32), Option<swarf_interp::BlockState>)>,
    /// egui time of the current frame, for merging typing into undo steps.
    now: f64,
    find: FindBar,
    /// The go-to-line dialog's input, while it is open.
    goto: Option<String>,
    /// The renumber dialog's options, while it is open.
    renumber: Option<RenumberOptions>,
    settings_open: bool,
    /// A new work offset's name typed in the settings window.
    new_offset: String,
    /// Every open tab, in order; the active one's entry is empty while its content is `tab`.
    tabs: Vec<Tab>,
    /// Index of the active tab in `tabs`.
    active: usize,
    requests: Vec<HostRequest>,
    /// An action waiting for the answer to "discard unsaved changes?".
    confirm: Option<Action>,
    /// The action to run once the host reports the program saved.
    after_save: Option<Action>,
    recent: Vec<String>,
    /// A short message for the status bar (a command's result, an error).
    message: Option<String>,
    /// The interface language.
    lang: Lang,
    /// Whether the CJK font the Chinese languages need is added, asked for, or neither.
    cjk_font: FontState,
    /// Where the named widgets were drawn in the last frame (see [`Workbench::widget_rect`]).
    widgets: std::collections::BTreeMap<std::borrow::Cow<'static, str>, egui::Rect>,
}

/// Where the CJK font stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FontState {
    Absent,
    Requested,
    Ready,
}

/// Something the workbench asks its host to do (dialogs, files: they differ on the web page).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HostRequest {
    /// Show an open dialog and [`Workbench::open_document`] the chosen file.
    Open,
    /// Open the recent file with this name (as given to [`Workbench::set_recent`]).
    OpenRecent(String),
    /// Save to the current file (or ask for one), then call [`Workbench::mark_saved`].
    Save,
    /// Ask for a file name, save there, then call [`Workbench::mark_saved`].
    SaveAs,
    /// Ask for a `SETUP.toml` and pass its text to [`Workbench::import_setup`].
    ImportSetup,
    /// Ask for a file name and write [`Workbench::setup_toml`] there.
    ExportSetup,
    /// Close the application (unsaved changes were saved or discarded).
    Quit,
    /// Get a CJK font's bytes for [`Workbench::add_cjk_font`] (or [`Workbench::cjk_font_failed`]).
    LoadCjkFont,
}

impl Default for Workbench {
    /// The example program, named as its file in `assets/examples/`, its analysis waited for.
    fn default() -> Self {
        let mut wb = Workbench::new(EXAMPLE_PROGRAM.to_string());
        wb.tab.document.name = EXAMPLES[0].name.to_string();
        wb
    }
}

impl Workbench {
    /// A workbench showing `text`, read as Fanuc with a default setup, its analysis waited for.
    pub fn new(text: String) -> Self {
        let waker = Arc::new(OnceLock::new());
        let analyst = default_analyst(&waker);
        let mut wb = Workbench::with_analyst(text, analyst, waker);
        wb.finish_analysis();
        wb
    }

    /// The example program (as [`Workbench::default`]) analysed by `analyst`, shown and framed
    /// when it replies: the page starts without waiting for a run its worker makes anyway.
    pub fn example(analyst: Box<dyn Analyst>) -> Self {
        let text = EXAMPLE_PROGRAM.to_string();
        let mut wb = Workbench::with_analyst(text, analyst, Arc::new(OnceLock::new()));
        wb.tab.document.name = EXAMPLES[0].name.to_string();
        wb.backplot.fit();
        wb
    }

    /// A workbench showing `text`, its analysis asked of `analyst` (`waker` is the context a
    /// thread of [`default_analyst`] repaints).
    fn with_analyst(
        text: String,
        analyst: Box<dyn Analyst>,
        waker: Arc<OnceLock<egui::Context>>,
    ) -> Self {
        let dialect = Dialect::default();
        let mut wb = Workbench {
            tab: Tab::new("untitled.nc", text, Encoding::Utf8, dialect),
            default_dialect: dialect,
            setup: Setup::default(),
            generation: 0,
            analysis: no_analysis(),
            own_analysis: false,
            analyst,
            sent: VecDeque::new(),
            pending: None,
            floor: 0,
            state_asked: None,
            waker,
            editor: CodeEditor::default(),
            backplot: Backplot::default(),
            synced_line: None,
            state_cache: None,
            now: 0.0,
            find: FindBar::default(),
            goto: None,
            renumber: None,
            settings_open: false,
            new_offset: String::new(),
            tabs: vec![Tab::default()],
            active: 0,
            requests: Vec::new(),
            confirm: None,
            after_save: None,
            recent: Vec::new(),
            message: None,
            lang: Lang::En,
            cjk_font: FontState::Absent,
            widgets: std::collections::BTreeMap::new(),
        };
        wb.reanalyse();
        wb
    }

    /// The program text.
    pub fn text(&self) -> &str {
        self.tab.text.as_str()
    }

    /// Whether the current text is also held as one string (an edit reads the rope instead).
    pub fn text_is_flat(&self) -> bool {
        self.tab.text.is_flat()
    }

    /// Replaces the text and re-analyses it (one undo step; the document stays the same file).
    pub fn set_text(&mut self, text: impl Into<String>) {
        // Framed anew: its analysis simplifies the path once the view's zoom is known.
        self.backplot.fit();
        self.apply(text.into(), 0..0);
    }

    /// The status bar's message, when it shows one.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// The interface language.
    pub fn language(&self) -> Lang {
        self.lang
    }

    /// Switches the interface language; a Chinese one asks the host for the CJK font once.
    pub fn set_language(&mut self, lang: Lang) {
        self.lang = lang;
        crate::i18n::set_current(lang);
        if lang != Lang::En && self.cjk_font == FontState::Absent {
            self.cjk_font = FontState::Requested;
            self.requests.push(HostRequest::LoadCjkFont);
            self.message = Some(tr("Loading the Chinese font…").to_string());
        }
    }

    /// Adds the CJK font's bytes (`.ttf`, `.otf`, `.ttc`); `false` (with a message) if no font.
    pub fn add_cjk_font(&mut self, ctx: &egui::Context, bytes: Vec<u8>) -> bool {
        if crate::i18n::add_cjk_font(ctx, bytes) {
            self.cjk_font = FontState::Ready;
            if self.message.as_deref() == Some(tr("Loading the Chinese font…")) {
                self.message = None;
            }
            true
        } else {
            self.cjk_font_failed("not a font file");
            false
        }
    }

    /// Says why the CJK font could not be had; choosing a Chinese language asks for it again.
    pub fn cjk_font_failed(&mut self, why: &str) {
        self.cjk_font = FontState::Absent;
        self.message = Some(trf("The Chinese font could not be loaded: {}", &[&why]));
    }

    /// Says that the system has no CJK font (on the desktop), and what to install.
    pub fn cjk_font_missing(&mut self) {
        self.cjk_font = FontState::Absent;
        self.message = Some(
            tr("No Chinese font found: install fonts-wqy-microhei or fonts-noto-cjk, or set SWARF_CJK_FONT to a font file")
                .to_string(),
        );
    }

    /// Whether the CJK font has been added.
    pub fn has_cjk_font(&self) -> bool {
        self.cjk_font == FontState::Ready
    }

    /// The file requests made since the last call, in order.
    pub fn take_requests(&mut self) -> Vec<HostRequest> {
        std::mem::take(&mut self.requests)
    }

    /// The recent files offered in the File menu, newest first.
    pub fn set_recent(&mut self, names: Vec<String>) {
        self.recent = names;
    }

    /// Shows `message` in the status bar (a failed save, an unreadable file).
    pub fn set_message(&mut self, message: impl Into<String>) {
        self.message = Some(message.into());
    }

    /// The machine setup programs run with.
    pub fn setup(&self) -> &Setup {
        &self.setup
    }

    /// Replaces the machine setup and re-analyses.
    pub fn set_setup(&mut self, setup: Setup) {
        if setup != self.setup {
            self.setup = setup;
            self.reanalyse();
        }
    }

    /// The setup as a `SETUP.toml` text (the CLI's format).
    pub fn setup_toml(&self) -> Result<String, String> {
        self.setup.to_toml().map_err(|e| e.to_string())
    }

    /// Reads a `SETUP.toml` text into the setup; on the CLI's errors the setup is unchanged.
    pub fn import_setup(&mut self, toml: &str) -> Result<(), String> {
        let setup = Setup::from_toml(toml).map_err(|e| format!("SETUP.toml: {e}"))?;
        swarf_stock::StockSetup::from_setup(&setup).map_err(|e| format!("SETUP.toml: {e}"))?;
        self.set_setup(setup);
        Ok(())
    }

    /// The codes the editor's completion list offers, while it is open.
    pub fn completions(&self) -> Option<&[commands::Completion]> {
        self.editor.completions()
    }

    /// Widget `name`'s last visible rect (points): `editor`, `backplot`, `fit_view`, `find_field`,
    /// `find_previous`, `find_next`, `find_close`, `replace_field`, `replace`, `replace_all`,
    /// `goto_field`, `goto_button`, `problem_first`, `tab N`, `close_tab N` (1-based), `new_tab`.
    pub fn widget_rect(&self, name: &str) -> Option<egui::Rect> {
        let rect = self.widgets.get(name).copied();
        rect.filter(egui::Rect::is_positive)
    }

    /// Keeps where `widget` was drawn, the part in sight, as `name` ([`Self::widget_rect`]).
    fn keep_rect(
        &mut self,
        ui: &egui::Ui,
        name: impl Into<std::borrow::Cow<'static, str>>,
        widget: &egui::Response,
    ) {
        (self.widgets).insert(name.into(), widget.rect.intersect(ui.clip_rect()));
    }

    /// A button kept as `name` ([`Self::keep_rect`]); whether it was clicked.
    fn kept_button(&mut self, ui: &mut egui::Ui, text: &str, name: &'static str) -> bool {
        let button = ui.button(text);
        self.keep_rect(ui, name, &button);
        button.clicked()
    }

    /// Shows the workbench filling `ui`.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        self.now = ui.input(|i| i.time);
        self.widgets.clear();
        crate::i18n::set_current(self.lang);
        let _ = self.waker.set(ui.ctx().clone());
        self.take_replies();
        self.shortcuts(ui.ctx());
        egui::Panel::top("swarf-top").show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("swarf-status").show(ui, |ui| self.status_bar(ui));
        // The panels keep their size whatever they show, so the view never jumps under the mouse.
        let problems = if self.analysis.problems.is_empty() && self.analysis.elsewhere.is_empty() {
            // Nothing to list: one line, not an empty list's height.
            egui::Panel::bottom("swarf-problems-none").resizable(false)
        } else {
            (egui::Panel::bottom("swarf-problems").resizable(true))
                .default_size(PROBLEMS_PANEL_HEIGHT)
        };
        problems.show(ui, |ui| self.problems_list(ui));
        egui::Panel::right("swarf-state")
            .resizable(true)
            .default_size(STATE_PANEL_WIDTH)
            .min_size(120.0)
            .show(ui, |ui| {
                egui::ScrollArea::both()
                    .id_salt("swarf-state-scroll")
                    .auto_shrink([false, false])
                    .show(ui, |ui| self.state_view(ui));
            });
        egui::Panel::left("swarf-editor")
            .resizable(true)
            .default_size(EDITOR_PANEL_WIDTH)
            .show(ui, |ui| {
                self.tab_strip(ui);
                let title = ui.horizontal(|ui| {
                    let title = ui.strong(tr("Program"));
                    let dirty = if self.tab.document.dirty { " *" } else { "" };
                    ui.label(format!("{}{dirty}", self.tab.document.name));
                    title
                });
                if self.find.open {
                    sideways(ui, "swarf-find-bar", |ui| self.find_bar(ui));
                }
                let matches = match &self.find.count {
                    Some((_, Ok(m))) if self.find.open => m.as_slice(),
                    _ => &[],
                };
                self.editor.set_highlights(matches);
                // The editor fills the rest of the panel.
                let editor_rect = ui.available_rect_before_wrap();
                self.widgets.insert("editor".into(), editor_rect);
                let (label, problems) = (title.inner.id, &self.analysis.problems);
                let out =
                    self.editor
                        .show(ui, label, &mut self.tab.text, self.tab.dialect, problems);
                if out.changed || out.completed {
                    let before = Snapshot {
                        text: std::mem::replace(&mut self.tab.shadow, self.tab.text.rope().clone()),
                        selection: self.tab.selection.clone(),
                    };
                    let kind = if out.completed {
                        EditKind::Command
                    } else {
                        EditKind::Typing
                    };
                    (self.tab.history).record(before, kind, out.ends_line, self.now);
                    self.text_changed();
                }
                if out.selection != self.tab.selection && !out.changed {
                    self.tab.history.break_run();
                }
                self.tab.selection = out.selection;
                self.tab.cursor_line = out.cursor_line.or(self.tab.cursor_line);
            });
        self.dialogs(ui.ctx());
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                // The editor's block is highlighted in the backplot when the cursor moves …
                if self.tab.cursor_line != self.synced_line {
                    self.backplot.set_selected_line(self.tab.cursor_line);
                    self.synced_line = self.tab.cursor_line;
                }
                egui::Panel::bottom("swarf-playback").show(ui, |ui| {
                    self.backplot.playback_bar(ui, &self.analysis.scene);
                });
                // A fit asked for a program just opened waits for its scene.
                self.backplot
                    .set_coming_generation(self.pending.map(|_| self.generation));
                let view = self.backplot.show(ui, &self.analysis.scene);
                if let Some(request) = self.backplot.stock_request(&self.analysis.scene) {
                    self.ask(request);
                }
                if let Some(request) = self.backplot.lod_request(&self.analysis.scene) {
                    self.ask(request);
                    // One answered at once is drawn by the next frame (a later one wakes it).
                    if !self.backplot.lod_pending(&self.analysis.scene) {
                        ui.ctx().request_repaint();
                    }
                }
                self.keep_rect(ui, "backplot", &view);
                self.loading_overlay(ui, view.rect);
                // … and a click on a segment, or playback, moves the editor to its block.
                if let Some(line) = self.backplot.take_picked_line() {
                    // A move of a subprogram in another tab is named, not jumped to.
                    match self.analysis.linked_line(line.saturating_sub(1)) {
                        Some((file, at)) => self.message = Some(trf("{}, line {}", &[&file, &at])),
                        None => self.jump_to_line(line),
                    }
                }
            });
        // Replies taken here (an analysis run in the frames answers now) show in the next frame.
        if self.take_replies() {
            ui.ctx().request_repaint_after(reply_frame(false));
        }
    }

    /// The backplot (camera, selection, playback).
    pub fn backplot(&self) -> &Backplot {
        &self.backplot
    }

    /// The 1-based line of the editor's cursor, as last reported or moved there.
    pub fn cursor_line(&self) -> Option<u32> {
        self.tab.cursor_line
    }

    /// Puts the editor's cursor at the start of 1-based `line`, the keyboard left where it is.
    fn jump_to_line(&mut self, line: u32) {
        let chars = self.tab.text.line_to_char(line.saturating_sub(1) as usize);
        self.tab.selection = chars..chars;
        self.editor.show_range(chars..chars);
        self.tab.cursor_line = Some(line);
        self.synced_line = Some(line);
    }
}

/// A strip scrolled sideways where it is wider than the panel, never widening it; its bar
/// takes room below the strip, since a floating bar covers the strip's buttons as the pointer
/// comes near them.
fn sideways(ui: &mut egui::Ui, id: &str, add: impl FnOnce(&mut egui::Ui)) {
    ui.scope(|ui| {
        ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
        egui::ScrollArea::horizontal().id_salt(id).show(ui, add);
    });
}
