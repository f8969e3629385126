//! The whole editing surface: editor, problems list and backplot, wired to the pipeline.

use std::collections::VecDeque;
use std::ops::Range;
use std::sync::{Arc, OnceLock};

use ropey::Rope;

use swarf_analysis::{Analyst, Job, ProgramText, Progress, Reply, Request};
use swarf_interp::Setup;
use swarf_syntax::{Dialect, Encoding, Severity};

use crate::analysis::{Analysis, Problem, Stats};
use crate::backplot::Backplot;
use crate::buffer::Buffer;
use crate::commands::{self, FindOptions, Finder, RenumberOptions};
use crate::editor::{CodeEditor, severity_color};
use crate::examples::EXAMPLES;
use crate::history::{EditKind, History, Snapshot};
use crate::i18n::{Lang, tr, trf};

/// The example program the editor starts with.
pub const EXAMPLE_PROGRAM: &str = include_str!("../../../assets/examples/pocket.nc");

/// How soon after a reply of the analysis the frame that shows it comes: a finished analysis
/// or an answer at once (replies a moment apart share the frame), `progress` a few times a
/// second, so that the frames leave the analysis the processor.
pub fn reply_frame(progress: bool) -> std::time::Duration {
    std::time::Duration::from_millis(if progress { 100 } else { 2 })
}

/// Width of the editor's panel until the user drags its divider, in points.
const EDITOR_PANEL_WIDTH: f32 = 460.0;
/// Width of the "state at cursor" panel until the user drags its divider, in points: room for
/// a position in millimetres; longer contents wrap or scroll inside it.
const STATE_PANEL_WIDTH: f32 = 280.0;
/// Height of the problems list, when there are problems, until the user drags its divider.
const PROBLEMS_PANEL_HEIGHT: f32 = 140.0;

/// Editor, problems and backplot over the program of the active tab; re-analyses on every edit.
///
/// Each tab holds one file (a [`Document`] with its text, undo history and cursor) and the
/// dialect it is read in. The active tab's program is analysed with the other tabs as the files
/// its subprogram calls may reach.
///
/// The analysis runs beside the UI (a thread of its own, or the web page's worker) and a frame
/// only takes its replies; until a new one is finished, the tab's last finished analysis
/// (markers, problems, backplot) stays on screen — a tab with none yet shows an empty view and
/// its progress, never another tab's — and an edit made meanwhile replaces the unfinished run.
pub struct Workbench {
    text: Buffer,
    /// The active tab's dialect.
    dialect: Dialect,
    /// The dialect new tabs and files opened in them start in: the last one chosen in the
    /// dialect selector or the settings.
    default_dialect: Dialect,
    setup: Setup,
    generation: u64,
    /// The active tab's last finished analysis, or an empty one while its first is running.
    analysis: Analysis,
    /// Whether `analysis` is the active tab's own (false for the empty stand-in).
    own_analysis: bool,
    /// Where the analysis runs: the workbench sends it jobs and questions, takes its replies.
    analyst: Box<dyn Analyst>,
    /// The jobs sent and not yet answered, by generation, with their texts (a finished one's
    /// text goes with its scene, for the tooltips).
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
    cursor_line: Option<u32>,
    /// The cursor line last sent to the backplot as its selection.
    synced_line: Option<u32>,
    /// The state shown for ((generation, line)), asked again only when either changes.
    state_cache: Option<((u64, u32), Option<swarf_interp::BlockState>)>,
    /// Undo and redo over typing and commands.
    history: History,
    /// The text as last recorded in the history (the "before" of the next typed change).
    shadow: Rope,
    /// The editor's selection in characters, as last reported or set.
    selection: Range<usize>,
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
    document: Document,
    /// Every open tab, in order; the active one's entry is empty while its content lives in
    /// the fields above.
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
    /// Where the named widgets were drawn in the last frame, the part in sight, in points (see
    /// [`Workbench::widget_rect`]): the page's test API finds what to click through it.
    widgets: std::collections::BTreeMap<std::borrow::Cow<'static, str>, egui::Rect>,
}

/// Where the CJK font stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FontState {
    Absent,
    Requested,
    Ready,
}

/// The open program as a file: its name, encoding and whether it has unsaved changes.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// The file name shown in the title and status bar (`untitled.nc` before the first save).
    pub name: String,
    /// Where the file is, as the host names it (a full path on the desktop; on the web page the
    /// key of the browser's handle to the file, where it has the File System Access API);
    /// `None` before the first save.
    pub path: Option<String>,
    /// The encoding the file was read with; saving writes it back the same way.
    pub encoding: Encoding,
    /// The text as last opened or saved.
    saved: Rope,
    dirty: bool,
    /// Names this document while it is open (unique in the process), so a host can follow
    /// a tab over switches, moves and closes.
    id: u64,
    /// Moves with every change of the text (unique in the process): a host keeping a copy of
    /// the text writes it again only when this moved.
    revision: u64,
}

impl Default for Document {
    /// An empty untitled program.
    fn default() -> Self {
        Document::new("untitled.nc", &Rope::new(), Encoding::Utf8)
    }
}

/// What a tab holds while another one is active.
#[derive(Debug, Clone, Default)]
struct Tab {
    text: Buffer,
    document: Document,
    history: History,
    shadow: Rope,
    selection: Range<usize>,
    cursor_line: Option<u32>,
    /// The dialect the tab's program is read in.
    dialect: Dialect,
    /// The tab's last finished analysis (`None` before its first is done).
    analysis: Option<Analysis>,
}

/// One open tab's file and text, for keeping unsaved work over a crash or a reload.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TabRecord {
    /// The document's name.
    pub name: String,
    /// Its file, when the host knows it.
    pub path: Option<String>,
    /// The file's encoding.
    pub encoding: Encoding,
    /// The text (with its unsaved changes).
    pub text: String,
    /// Whether the text has changes that are not saved.
    pub dirty: bool,
    /// The tab's dialect; `None` for the one new tabs start in.
    pub dialect: Option<Dialect>,
}

impl Document {
    fn new(name: &str, text: &Rope, encoding: Encoding) -> Self {
        Document {
            name: name.to_string(),
            path: None,
            encoding,
            saved: text.clone(),
            dirty: false,
            id: next_stamp(),
            revision: next_stamp(),
        }
    }

    /// Whether the text has changes that are not saved.
    pub fn is_unsaved(&self) -> bool {
        self.dirty
    }

    /// Names the document while it is open: the same over tab switches, moves and closes of
    /// other tabs, never shared with another document of this process.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Changes with every change of the text, never to a value another text had in this
    /// process: a copy kept of a revision is a copy of that text.
    pub fn revision(&self) -> u64 {
        self.revision
    }
}

/// What the status bar says after unsaved changes of the tabs `names` were recovered; `None`
/// when there were none.
fn recovered_message(names: &[&str]) -> Option<String> {
    match names {
        [] => None,
        [name] => Some(trf("Recovered unsaved changes of {}", &[name])),
        _ => Some(trf(
            "Recovered unsaved changes of {} tabs: {}",
            &[&names.len(), &names.join(", ")],
        )),
    }
}

/// A number no earlier call returned (document ids and text revisions).
fn next_stamp() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// Something the workbench asks its host to do: file dialogs, reading and writing files, which
/// differ between the desktop and the web page.
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
    /// Get a CJK font for the Chinese interface languages and hand its bytes to
    /// [`Workbench::add_cjk_font`] (or say why not with [`Workbench::cjk_font_failed`]).
    LoadCjkFont,
}

/// An action that drops unsaved changes, held while they are confirmed.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Action {
    /// Close the active tab.
    Close,
    /// Quit once the tabs from this index on are saved or discarded.
    Quit(usize),
}

/// What a match count was computed for: (text generation, pattern, options).
type MatchKey = (u64, String, FindOptions);

/// Matches in characters, or why the pattern is invalid.
type Matches = Result<Vec<Range<usize>>, String>;

/// The find/replace bar's state.
#[derive(Debug, Clone, Default)]
struct FindBar {
    open: bool,
    replace: bool,
    query: String,
    replacement: String,
    options: FindOptions,
    /// Ask for focus on the find field next frame.
    focus: bool,
    /// The matches in characters (or the pattern's error) for (generation, query, options).
    count: Option<(MatchKey, Matches)>,
}

impl Default for Workbench {
    /// The example program, named as its file in `assets/examples/`.
    fn default() -> Self {
        let mut wb = Workbench::new(EXAMPLE_PROGRAM.to_string());
        wb.document.name = "pocket.nc".to_string();
        wb
    }
}

impl Workbench {
    /// A workbench showing `text`, read as Fanuc with a default setup, and its analysis (the
    /// first one is waited for; later ones come beside the frames).
    pub fn new(text: String) -> Self {
        let dialect = Dialect::default();
        let text = Buffer::from(text);
        let rope = text.rope().clone();
        let waker = Arc::new(OnceLock::new());
        let mut wb = Workbench {
            text,
            dialect,
            default_dialect: dialect,
            setup: Setup::default(),
            generation: 0,
            analysis: no_analysis(),
            own_analysis: false,
            analyst: default_analyst(&waker),
            sent: VecDeque::new(),
            pending: None,
            floor: 0,
            state_asked: None,
            waker,
            editor: CodeEditor::default(),
            backplot: Backplot::new(),
            cursor_line: None,
            synced_line: None,
            state_cache: None,
            history: History::default(),
            shadow: rope.clone(),
            selection: 0..0,
            now: 0.0,
            find: FindBar::default(),
            goto: None,
            renumber: None,
            settings_open: false,
            new_offset: String::new(),
            document: Document::new("untitled.nc", &rope, Encoding::Utf8),
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
        wb.finish_analysis();
        wb
    }

    /// Has `analyst` run the analysis from now on (the web page's worker), starting with the
    /// current text.
    pub fn set_analyst(&mut self, analyst: Box<dyn Analyst>) {
        self.analyst = analyst;
        self.sent.clear();
        self.state_asked = None;
        self.reanalyse();
    }

    /// The program text.
    pub fn text(&self) -> &str {
        self.text.as_str()
    }

    /// Whether the current text is also held as one string (made only where a whole-text
    /// copy is needed; an edit of a long program and its analysis read the rope instead).
    pub fn text_is_flat(&self) -> bool {
        self.text.is_flat()
    }

    /// Replaces the text and re-analyses it (one undo step; the document stays the same file).
    pub fn set_text(&mut self, text: impl Into<String>) {
        self.apply(text.into(), 0..0);
        self.backplot.fit();
    }

    /// Opens a program read from a file in a new tab (or in the active one when that is
    /// empty, untitled and unchanged): a fresh undo history, no unsaved changes.
    pub fn open_document(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        self.open_file(name, text.into(), encoding, None);
    }

    /// Opens a program read from a file in a tab, as [`Workbench::open_document`]; `path` is
    /// where it came from, when the host knows. A file already open from the same path gets
    /// its tab back (re-read when it has no unsaved changes).
    pub fn open_file(
        &mut self,
        name: &str,
        text: String,
        encoding: Encoding,
        path: Option<String>,
    ) {
        // A built-in example saved as a file opens in its dialect, as from the menu.
        let dialect = EXAMPLES.iter().find(|e| e.text == text).map(|e| e.dialect);
        self.open_in(name, text, encoding, path, dialect);
    }

    /// Opens a file in a tab as [`Workbench::open_file`] does, in `dialect` when given (a file
    /// opened again keeps its tab's dialect otherwise, a new one starts in the default).
    fn open_in(
        &mut self,
        name: &str,
        text: String,
        encoding: Encoding,
        path: Option<String>,
        dialect: Option<Dialect>,
    ) {
        let open_at = path.as_ref().and_then(|p| {
            (0..self.tabs.len()).find(|&i| self.tab_document(i).path.as_ref() == Some(p))
        });
        match open_at {
            Some(i) => {
                self.switch_tab(i);
                if self.document.dirty {
                    self.message = Some(trf("{} is open here with unsaved changes", &[&name]));
                    return;
                }
            }
            // A new file starts in the default dialect (a tab keeps its own once open).
            None if self.is_blank() => self.dialect = self.default_dialect,
            None => self.push_tab(),
        }
        if let Some(dialect) = dialect {
            self.dialect = dialect;
        }
        self.load(name, text, encoding);
        self.document.path = path;
    }

    /// Parks the active tab and makes a new empty one after the others active, in the default
    /// dialect, with no analysis yet.
    fn push_tab(&mut self) {
        let current = self.park();
        if let Some(slot) = self.tabs.get_mut(self.active) {
            *slot = current;
        }
        self.tabs.push(Tab::default());
        self.active = self.tabs.len() - 1;
        self.dialect = self.default_dialect;
    }

    /// Opens a file dropped on the window or the page in a tab (see [`Workbench::open_file`]).
    pub fn open_guarded(
        &mut self,
        name: &str,
        text: String,
        encoding: Encoding,
        path: Option<String>,
    ) {
        self.open_file(name, text, encoding, path);
    }

    /// Replaces the active tab's program with a file's text (no unsaved changes), as after
    /// saving it in another encoding.
    pub fn reload_document(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        let path = self.document.path.take();
        self.load(name, text.into(), encoding);
        self.document.path = path;
    }

    /// Shows `text` as the active tab's file `name`: a fresh undo history, no unsaved changes.
    fn load(&mut self, name: &str, text: String, encoding: Encoding) {
        self.text = Buffer::from(text);
        self.shadow = self.text.rope().clone();
        self.history.clear();
        self.document = Document::new(name, self.text.rope(), encoding);
        self.selection = 0..0;
        self.cursor_line = None;
        self.synced_line = None;
        self.editor.jump_to(0..0);
        self.message = None;
        self.drop_shown_analysis();
        self.reanalyse();
        self.backplot.fit();
    }

    /// Shows the empty stand-in until the active tab's next analysis is done (its text is
    /// another file now: what was shown is not of it).
    fn drop_shown_analysis(&mut self) {
        self.own_analysis = false;
        self.analysis = no_analysis();
        self.floor = self.generation + 1;
    }

    /// Whether the active tab is empty, untitled and unchanged (a file opened replaces it).
    fn is_blank(&self) -> bool {
        self.text.is_empty() && !self.document.dirty && self.document.path.is_none()
    }

    /// Records where the open document's file is (after opening or saving it).
    pub fn set_path(&mut self, path: Option<String>) {
        self.document.path = path;
    }

    /// Replaces the active tab's program with unsaved `text` recovered after a crash: shown as
    /// a change to `name` that still needs saving.
    pub fn recover(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        self.load(name, String::new(), encoding);
        self.text = Buffer::from(text.into());
        self.shadow = self.text.rope().clone();
        self.document.dirty = true;
        self.document.revision = next_stamp();
        self.message = recovered_message(&[name]);
        self.reanalyse();
        self.backplot.fit();
    }

    /// Every tab's file and text, in order, with the index of the active one.
    pub fn tab_records(&self) -> (Vec<TabRecord>, usize) {
        let records = (0..self.tabs.len())
            .map(|i| {
                let (doc, text) = if i == self.active {
                    (&self.document, &self.text)
                } else {
                    let tab = &self.tabs[i];
                    (&tab.document, &tab.text)
                };
                TabRecord {
                    name: doc.name.clone(),
                    path: doc.path.clone(),
                    encoding: doc.encoding,
                    text: text.to_text(),
                    dirty: doc.dirty,
                    dialect: self.tab_dialect(i),
                }
            })
            .collect();
        (records, self.active)
    }

    /// Replaces every tab with `records` (kept by [`Workbench::tab_records`]) and activates
    /// the `active`-th; unsaved texts come back as changes that still need saving, and the
    /// status bar names them (it says nothing of recovery when none had any). Nothing happens
    /// for an empty list.
    pub fn restore_tabs(&mut self, records: Vec<TabRecord>, active: usize) {
        if records.is_empty() {
            return;
        }
        let active = active.min(records.len() - 1);
        let unsaved: Vec<&str> = records
            .iter()
            .filter(|r| r.dirty)
            .map(|r| r.name.as_str())
            .collect();
        let message = recovered_message(&unsaved);
        let mut tabs = Vec::with_capacity(records.len());
        for r in records {
            let text = Buffer::from(r.text);
            let saved = if r.dirty {
                Rope::new()
            } else {
                text.rope().clone()
            };
            let mut document = Document::new(&r.name, &saved, r.encoding);
            document.path = r.path;
            document.dirty = r.dirty;
            tabs.push(Tab {
                shadow: text.rope().clone(),
                text,
                document,
                dialect: r.dialect.unwrap_or(self.default_dialect),
                ..Tab::default()
            });
        }
        let first = std::mem::take(&mut tabs[active]);
        self.tabs = tabs;
        self.active = active;
        self.unpark(first);
        if message.is_some() {
            self.message = message;
        }
        self.reanalyse();
        self.backplot.fit();
    }

    /// The text of tab `i` (a copy), `None` past the last tab.
    pub fn tab_text(&self, i: usize) -> Option<String> {
        if i == self.active {
            Some(self.text.to_text())
        } else {
            self.tabs.get(i).map(|t| t.text.to_text())
        }
    }

    /// The status bar's message, when it shows one.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// Takes the active tab's content out of the workbench's fields.
    ///
    /// The tab keeps its dialect and last finished analysis; an unfinished one is dropped (it
    /// starts over when the tab is active again), and the empty stand-in is shown meanwhile.
    fn park(&mut self) -> Tab {
        self.pending = None;
        let analysis = if std::mem::take(&mut self.own_analysis) {
            Some(std::mem::replace(&mut self.analysis, no_analysis()))
        } else {
            None
        };
        Tab {
            text: std::mem::take(&mut self.text),
            document: std::mem::take(&mut self.document),
            history: std::mem::take(&mut self.history),
            shadow: std::mem::take(&mut self.shadow),
            selection: std::mem::take(&mut self.selection),
            cursor_line: self.cursor_line.take(),
            dialect: self.dialect,
            analysis,
        }
    }

    /// Puts a tab's content into the workbench's fields: its own last analysis is shown (the
    /// empty stand-in when it has none yet), never the one of the tab before.
    fn unpark(&mut self, tab: Tab) {
        self.text = tab.text;
        self.document = tab.document;
        self.history = tab.history;
        self.shadow = tab.shadow;
        self.cursor_line = tab.cursor_line;
        self.synced_line = None;
        self.state_cache = None;
        self.select_chars(tab.selection);
        self.dialect = tab.dialect;
        self.pending = None;
        self.own_analysis = tab.analysis.is_some();
        self.analysis = tab.analysis.unwrap_or_else(no_analysis);
        self.floor = self.generation + 1;
    }

    /// The document of tab `i` (which may be the active one).
    fn tab_document(&self, i: usize) -> &Document {
        if i == self.active {
            &self.document
        } else {
            &self.tabs[i].document
        }
    }

    /// Number of open tabs.
    pub fn tab_count(&self) -> usize {
        self.tabs.len()
    }

    /// Index of the active tab.
    pub fn active_tab(&self) -> usize {
        self.active
    }

    /// The open tabs' documents, in order.
    pub fn tab_documents(&self) -> Vec<&Document> {
        (0..self.tabs.len()).map(|i| self.tab_document(i)).collect()
    }

    /// Makes tab `i` the active one (its program goes to the editor and the backplot).
    pub fn switch_tab(&mut self, i: usize) {
        if i == self.active || i >= self.tabs.len() {
            return;
        }
        let current = self.park();
        self.tabs[self.active] = current;
        let next = std::mem::take(&mut self.tabs[i]);
        self.active = i;
        self.unpark(next);
        self.reanalyse();
        self.backplot.fit();
    }

    /// Closes tab `i`, after asking to save or discard its unsaved changes (the tab is made
    /// active for the question). The last tab closed leaves an empty untitled one.
    pub fn close_tab(&mut self, i: usize) {
        if i >= self.tabs.len() {
            return;
        }
        if self.tab_document(i).dirty {
            self.switch_tab(i);
            self.confirm = Some(Action::Close);
        } else if i == self.active {
            self.remove_active_tab();
        } else {
            self.tabs.remove(i);
            if i < self.active {
                self.active -= 1;
            }
            // The active program's calls may have reached the tab closed.
            self.reanalyse();
        }
    }

    /// Drops the active tab, unsaved changes and all.
    fn remove_active_tab(&mut self) {
        if self.tabs.len() <= 1 {
            self.dialect = self.default_dialect;
            self.load("untitled.nc", String::new(), Encoding::Utf8);
            return;
        }
        self.tabs.remove(self.active);
        self.active = self.active.min(self.tabs.len() - 1);
        let next = std::mem::take(&mut self.tabs[self.active]);
        self.unpark(next);
        self.reanalyse();
        self.backplot.fit();
    }

    /// `untitled.nc`, or `untitled-2.nc` … when another tab has that name.
    fn untitled_name(&self) -> String {
        let taken = |name: &str| {
            (0..self.tabs.len()).any(|i| i != self.active && self.tab_document(i).name == name)
        };
        let mut name = "untitled.nc".to_string();
        let mut n = 1;
        while taken(&name) {
            n += 1;
            name = format!("untitled-{n}.nc");
        }
        name
    }

    /// Opens a new tab with an empty untitled program.
    pub fn new_tab(&mut self) {
        self.push_tab();
        let name = self.untitled_name();
        self.load(&name, String::new(), Encoding::Utf8);
    }

    /// Whether any tab has unsaved changes.
    pub fn any_dirty(&self) -> bool {
        self.document.dirty
            || self
                .tabs
                .iter()
                .enumerate()
                .any(|(i, t)| i != self.active && t.document.dirty)
    }

    /// The open document (name, encoding).
    pub fn document(&self) -> &Document {
        &self.document
    }

    /// Whether the text differs from what was last opened or saved.
    pub fn is_dirty(&self) -> bool {
        self.document.dirty
    }

    /// Records that the active tab's text was saved as `name`; runs an action that waited for
    /// the save.
    pub fn mark_saved(&mut self, name: &str) {
        self.document.name = name.to_string();
        self.document.saved = self.text.rope().clone();
        self.document.dirty = false;
        self.message = Some(trf("Saved {}", &[&name]));
        if let Some(action) = self.after_save.take() {
            self.run_action(action);
        }
    }

    /// The interface language.
    pub fn language(&self) -> Lang {
        self.lang
    }

    /// Switches the interface language (at once); a Chinese one asks the host for the CJK
    /// font the first time.
    pub fn set_language(&mut self, lang: Lang) {
        self.lang = lang;
        crate::i18n::set_current(lang);
        if lang.needs_cjk_font() && self.cjk_font == FontState::Absent {
            self.cjk_font = FontState::Requested;
            self.requests.push(HostRequest::LoadCjkFont);
            self.message = Some(tr("Loading the Chinese font…").to_string());
        }
    }

    /// Adds the CJK font's bytes (a `.ttf`, `.otf` or `.ttc` file) to the interface's fonts;
    /// `false` (with a message) when they are no font.
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

    /// Says that the CJK font could not be had (`why`); choosing a Chinese language again
    /// asks for it again.
    pub fn cjk_font_failed(&mut self, why: &str) {
        self.cjk_font = FontState::Absent;
        self.message = Some(trf("The Chinese font could not be loaded: {}", &[&why]));
    }

    /// Says that no CJK font is to be had here (the desktop found none among the system's
    /// fonts), with what to install.
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

    /// Reads a `SETUP.toml` text into the setup; on error the setup is unchanged.
    pub fn import_setup(&mut self, toml: &str) -> Result<(), String> {
        let setup = Setup::from_toml(toml).map_err(|e| format!("SETUP.toml: {e}"))?;
        self.set_setup(setup);
        Ok(())
    }

    /// Selects the whole of 1-based `line` in the editor (clamped to the text) and scrolls to it.
    pub fn select_line(&mut self, line: u32) {
        let line = line.clamp(1, commands::line_count(&self.text));
        let start = commands::line_start(&self.text, line);
        let end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |j| start + j);
        let chars =
            commands::char_of_byte(&self.text, start)..commands::char_of_byte(&self.text, end);
        self.select_chars(chars);
        self.cursor_line = Some(line);
    }

    /// The editor's selection in characters.
    pub fn selection(&self) -> Range<usize> {
        self.selection.clone()
    }

    /// The selected text.
    pub fn selected_text(&self) -> &str {
        let a = commands::byte_of_char(&self.text, self.selection.start);
        let b = commands::byte_of_char(&self.text, self.selection.end);
        self.text.get(a..b).unwrap_or_default()
    }

    /// The 1-based lines the selection covers (a selection ending at a line's start does not
    /// take that line).
    pub fn selected_lines(&self) -> std::ops::RangeInclusive<u32> {
        let a = commands::byte_of_char(&self.text, self.selection.start);
        let mut b = commands::byte_of_char(&self.text, self.selection.end);
        if b > a && self.text[..b].ends_with('\n') {
            b -= 1;
        }
        commands::line_of_byte(&self.text, a)..=commands::line_of_byte(&self.text, b)
    }

    fn select_chars(&mut self, chars: Range<usize>) {
        self.selection = chars.clone();
        self.editor.jump_to(chars);
    }

    /// Undoes the last change (typing run or command).
    pub fn undo(&mut self) {
        let current = self.snapshot();
        if let Some(back) = self.history.undo(current) {
            self.restore(back);
        }
    }

    /// Redoes the last undone change.
    pub fn redo(&mut self) {
        let current = self.snapshot();
        if let Some(forward) = self.history.redo(current) {
            self.restore(forward);
        }
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            text: self.text.rope().clone(),
            selection: self.selection.clone(),
        }
    }

    fn restore(&mut self, to: Snapshot) {
        self.text = Buffer::from(to.text);
        self.shadow = self.text.rope().clone();
        self.select_chars(to.selection);
        self.text_changed();
    }

    /// Replaces the text as one undoable command and selects `selection` (characters).
    fn apply(&mut self, text: String, selection: Range<usize>) {
        if text == self.text.as_str() {
            return;
        }
        let before = Snapshot {
            text: std::mem::replace(&mut self.text, Buffer::from(text))
                .rope()
                .clone(),
            selection: self.selection.clone(),
        };
        self.history
            .record(before, EditKind::Command, true, self.now);
        self.shadow = self.text.rope().clone();
        self.select_chars(selection);
        self.text_changed();
    }

    fn text_changed(&mut self) {
        self.document.dirty = self.text.rope() != &self.document.saved;
        self.document.revision = next_stamp();
        self.reanalyse();
    }

    /// The dialect the active tab's program is read in.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Reads the active tab's program in `dialect` (re-analysing it) and makes `dialect` the
    /// one new tabs start in, as choosing it in the dialect selector does; the other open tabs
    /// keep theirs.
    pub fn set_dialect(&mut self, dialect: Dialect) {
        self.default_dialect = dialect;
        self.set_tab_dialect(self.active, dialect);
    }

    /// The dialect tab `i`'s program is read in; `None` past the last tab.
    pub fn tab_dialect(&self, i: usize) -> Option<Dialect> {
        if i == self.active {
            Some(self.dialect)
        } else {
            self.tabs.get(i).map(|t| t.dialect)
        }
    }

    /// Reads tab `i`'s program in `dialect` (the active one is re-analysed at once, another
    /// when it is next shown); the other tabs and the default for new ones stay as they are.
    pub fn set_tab_dialect(&mut self, i: usize, dialect: Dialect) {
        if i == self.active {
            if dialect != self.dialect {
                self.dialect = dialect;
                self.reanalyse();
            }
        } else if let Some(tab) = self.tabs.get_mut(i) {
            tab.dialect = dialect;
        }
    }

    /// The dialect new tabs, and files opened in them, start in.
    pub fn default_dialect(&self) -> Dialect {
        self.default_dialect
    }

    /// Sets the dialect new tabs start in (the open tabs keep theirs), as a host restoring
    /// its settings does.
    pub fn set_default_dialect(&mut self, dialect: Dialect) {
        self.default_dialect = dialect;
    }

    /// The dialect offered for the active tab's program: one whose codes, by the code tables,
    /// leave strictly fewer errors than its own dialect (see the notice over the problems).
    pub fn suggested_dialect(&self) -> Option<Dialect> {
        self.analysis
            .hint
            .as_ref()
            .filter(|h| h.from == self.dialect && self.own_analysis)
            .map(|h| h.to)
    }

    /// Whether the analysis shown is the active tab's own; false while the first analysis of
    /// a tab just opened is still running (an empty view, problems and counts are shown).
    pub fn analysis_ready(&self) -> bool {
        self.own_analysis
    }

    /// The latest analysis.
    pub fn analysis(&self) -> &Analysis {
        &self.analysis
    }

    /// The codes the editor's completion list offers, while it is open.
    pub fn completions(&self) -> Option<&[commands::Completion]> {
        self.editor.completions()
    }

    /// Diagnostics of the current text, sorted by position.
    pub fn problems(&self) -> &[Problem] {
        &self.analysis.problems
    }

    /// Summary numbers of the current text.
    pub fn stats(&self) -> Stats {
        self.analysis.stats()
    }

    /// Sends the current text to the analysis (replacing an unfinished run there).
    fn reanalyse(&mut self) {
        self.generation += 1;
        // The texts are shared, not copied: a keystroke costs no copy of them (a rope is parsed
        // in place, another tab's text is copied only when the program calls into it).
        let others = self
            .tabs
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != self.active)
            .map(|(_, t)| (t.document.name.clone(), t.text.program_text()))
            .collect();
        let text = self.text.program_text();
        self.ask(Request::Analyse(Box::new(Job {
            generation: self.generation,
            text: text.clone(),
            dialect: self.dialect,
            setup: self.setup.clone(),
            others: Some(others),
        })));
        self.sent.push_back((self.generation, text));
        self.pending = Some(Progress::Reading { read: 0, lines: 0 });
    }

    /// Sends a request to the analysis, taking an answer given at once.
    fn ask(&mut self, request: Request) {
        if let Some(reply) = self.analyst.send(request) {
            self.receive(reply);
        }
    }

    /// Takes the replies the analysis has sent since the last look (each frame does so first;
    /// a host may before it, to know what the frame will show); whether any came.
    pub fn take_replies(&mut self) -> bool {
        let mut any = false;
        while let Some(reply) = self.analyst.try_reply() {
            self.receive(reply);
            any = true;
        }
        any
    }

    /// Takes one reply: progress of the current text's analysis, a finished analysis of the
    /// active tab (shown unless a newer one is), or the state at cursor asked for.
    fn receive(&mut self, reply: Reply) {
        match reply {
            Reply::Progress {
                generation,
                progress,
            } => {
                if generation == self.generation && self.pending.is_some() {
                    self.pending = Some(progress);
                }
            }
            Reply::Done(results) => {
                let generation = results.generation;
                // The jobs sent before this one were replaced.
                while self.sent.front().is_some_and(|(g, _)| *g < generation) {
                    self.sent.pop_front();
                }
                let text = match self.sent.front() {
                    Some((g, _)) if *g == generation => self.sent.pop_front().map(|(_, t)| t),
                    _ => None,
                };
                let newer = !self.own_analysis || generation > self.analysis.scene.generation;
                if let Some(text) = text
                    && generation >= self.floor
                    && newer
                {
                    self.analysis = Analysis::of(*results, &text);
                    self.own_analysis = true;
                    if generation == self.generation {
                        self.pending = None;
                    }
                }
            }
            Reply::State {
                generation,
                line,
                state,
            } => {
                // `None`: that analysis is no longer held; the next one shown is asked again.
                if let Some(state) = state
                    && self.state_asked == Some((generation, line))
                {
                    self.state_cache = Some(((generation, line), state));
                    self.state_asked = None;
                }
            }
        }
    }

    /// Progress of the current text's analysis, while it runs, as (different blocks run,
    /// blocks in the program); (0, 0) while the text is read. `None` when the analysis shown is
    /// of the current text.
    pub fn analysis_progress(&self) -> Option<(usize, usize)> {
        self.pending.map(|p| match p {
            Progress::Running { reached, blocks } => (reached, blocks),
            Progress::Reading { .. } => (0, 0),
        })
    }

    /// Waits for the analysis of the current text and shows it (for tests and scripts that want
    /// the current text's results rather than the last finished ones). Where the host cannot
    /// wait (a web page), it returns at once and the frames show the results as they come.
    pub fn finish_analysis(&mut self) {
        self.take_replies();
        while self.pending.is_some() {
            match self.analyst.wait_reply() {
                Some(reply) => self.receive(reply),
                None => return,
            }
        }
    }

    /// A number bumped by every change of the text, dialect or setup (the analysis shown
    /// carries it in its scene once it has caught up).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// Where the widget `name` was drawn in the last frame, in points; `None` when it was not
    /// drawn or scrolled out of sight; only the part in sight, where a click reaches it. The
    /// names: `editor`, `backplot`, `fit_view`, `find_field`, `find_previous`, `find_next`,
    /// `find_close`, `replace_field`, `replace`, `replace_all`, `goto_field`, `goto_button`,
    /// `problem_first` (the problems list's first row), `tab N` (the 1-based tab's label),
    /// `close_tab N` and `new_tab`.
    pub fn widget_rect(&self, name: &str) -> Option<egui::Rect> {
        self.widgets
            .get(name)
            .copied()
            .filter(egui::Rect::is_positive)
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
        // The panels keep their size (the user's, once a divider is dragged) whatever they
        // show: their contents wrap or scroll inside, so the view never jumps under the mouse.
        if self.problem_count() == 0 {
            // Nothing to list: one line, not an empty list's height.
            egui::Panel::bottom("swarf-problems-none")
                .resizable(false)
                .show(ui, |ui| self.problems_list(ui));
        } else {
            egui::Panel::bottom("swarf-problems")
                .resizable(true)
                .default_size(PROBLEMS_PANEL_HEIGHT)
                .show(ui, |ui| self.problems_list(ui));
        }
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
                    let dirty = if self.document.dirty { " *" } else { "" };
                    ui.label(format!("{}{dirty}", self.document.name));
                    title
                });
                if self.find.open {
                    // Scrolled sideways where it is wider than the panel, never widening it.
                    egui::ScrollArea::horizontal()
                        .id_salt("swarf-find-bar")
                        .show(ui, |ui| self.find_bar(ui));
                }
                let matches = match &self.find.count {
                    Some((_, Ok(m))) if self.find.open => m.as_slice(),
                    _ => &[],
                };
                self.editor.set_highlights(matches);
                // The editor fills the rest of the panel.
                let editor_rect = ui.available_rect_before_wrap();
                self.widgets.insert("editor".into(), editor_rect);
                let out = self.editor.show(
                    ui,
                    title.inner.id,
                    &mut self.text,
                    self.dialect,
                    &self.analysis.problems,
                );
                if out.changed || out.completed {
                    let before = Snapshot {
                        text: std::mem::replace(&mut self.shadow, self.text.rope().clone()),
                        selection: self.selection.clone(),
                    };
                    let kind = if out.completed {
                        EditKind::Command
                    } else {
                        EditKind::Typing
                    };
                    self.history.record(before, kind, out.ends_line, self.now);
                    self.text_changed();
                }
                if let Some(selection) = out.selection {
                    if selection != self.selection && !out.changed {
                        self.history.break_run();
                    }
                    self.selection = selection;
                }
                if out.cursor_line.is_some() {
                    self.cursor_line = out.cursor_line;
                }
            });
        self.dialogs(ui.ctx());
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                // The editor's block is highlighted in the backplot (set only when the cursor
                // moves, so a click in the backplot is not undone) …
                if self.cursor_line != self.synced_line {
                    self.backplot.set_selected_line(self.cursor_line);
                    self.synced_line = self.cursor_line;
                }
                egui::Panel::bottom("swarf-playback").show(ui, |ui| {
                    self.backplot.playback_bar(ui, &self.analysis.scene);
                });
                // A fit asked for a program just opened waits for its scene.
                self.backplot
                    .set_coming_generation(self.pending.map(|_| self.generation));
                let view = self.backplot.show(ui, &self.analysis.scene);
                self.widgets
                    .insert("backplot".into(), view.rect.intersect(ui.clip_rect()));
                self.loading_overlay(ui, view.rect);
                // … a click on a segment moves the editor to its block, and so does playback
                // (the backplot highlights the block itself).
                let played = self.backplot.take_playback_line();
                if let Some(line) = self.backplot.take_picked_line().or(played) {
                    // A move of a subprogram in another tab is named, not jumped to.
                    match self.analysis.linked_line(line.saturating_sub(1)) {
                        Some((file, at)) => {
                            self.message = Some(trf("{}, line {}", &[&file, &at]));
                        }
                        None => self.jump_to_line(line),
                    }
                }
            });
        // Each reply asks for a frame as it comes; those taken here (an analysis run in the
        // frames, where there are no threads and no worker, answers now) are shown by the next.
        if self.take_replies() {
            ui.ctx().request_repaint_after(reply_frame(false));
        }
    }

    /// The machine state just before the block on 1-based `line` first runs (modal codes,
    /// position, offsets, tool, feed, speed), asked of the current text's analysis once it is
    /// finished; `None` when no block there runs, or where the host cannot wait for the answer.
    pub fn state_at_line(&mut self, line: u32) -> Option<swarf_interp::BlockState> {
        self.finish_analysis();
        let generation = self.analysis.scene.generation;
        let mut now = self.analyst.send(Request::StateAt { generation, line });
        loop {
            match now.take().or_else(|| self.analyst.wait_reply())? {
                Reply::State {
                    generation: g,
                    line: l,
                    state,
                } if (g, l) == (generation, line) => return state.flatten(),
                other => self.receive(other),
            }
        }
    }

    /// The "state at cursor" panel.
    fn state_view(&mut self, ui: &mut egui::Ui) {
        ui.strong(tr("State at cursor"));
        let Some(line) = self.cursor_line else {
            ui.label(tr("Put the cursor on a block."));
            return;
        };
        // Asked of the analysis, which holds the program (answered at once where it is kept
        // on this side of the thread); the last answer stays until the next one comes.
        let key = (self.analysis.scene.generation, line);
        if self.own_analysis
            && self.state_cache.as_ref().map(|(k, _)| *k) != Some(key)
            && self.state_asked != Some(key)
        {
            self.state_asked = Some(key);
            self.ask(Request::StateAt {
                generation: key.0,
                line,
            });
        }
        let Some(((_, line), state)) = &self.state_cache else {
            return;
        };
        let line = *line;
        let Some(s) = state else {
            ui.label(trf("Line {} does not run.", &[&line]));
            return;
        };
        let mm = |v: glam::DVec3| format!("X{:.3} Y{:.3} Z{:.3}", v.x, v.y, v.z);
        // The modal codes, many on some lines, wrap within the panel's width (first, before
        // anything wider than the panel that scrolls).
        ui.label(tr("modes"));
        ui.add(egui::Label::new(s.codes.join(" ")).wrap());
        egui::Grid::new("swarf-state-grid")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label(tr("line"));
                ui.label(line.to_string());
                ui.end_row();
                ui.label(tr("work"));
                ui.monospace(mm(s.work));
                ui.end_row();
                ui.label(tr("machine"));
                ui.monospace(mm(s.machine));
                ui.end_row();
                ui.label(&s.work_offset_name);
                ui.monospace(mm(s.work_offset));
                ui.end_row();
                ui.label(tr("tool"));
                ui.label(match s.length_offset {
                    Some((h, v)) => format!("T{} H{h} ({v:+.3} mm)", s.tool),
                    None => format!("T{}", s.tool),
                });
                ui.end_row();
                ui.label(tr("feed"));
                ui.label(format!("F{}", s.feed));
                ui.end_row();
                ui.label(tr("spindle"));
                ui.label(format!("S{}", s.spindle_rpm));
                ui.end_row();
                ui.label(tr("blocks run"));
                ui.label(s.executed.to_string());
                ui.end_row();
            });
    }

    /// The problems of the active tab's program and of the files it called.
    fn problem_count(&self) -> usize {
        self.analysis.problems.len() + self.analysis.elsewhere.len()
    }

    /// The backplot (camera, selection, playback).
    pub fn backplot(&self) -> &Backplot {
        &self.backplot
    }

    /// The 1-based line of the editor's cursor, as last reported or moved there.
    pub fn cursor_line(&self) -> Option<u32> {
        self.cursor_line
    }

    /// Puts the editor's cursor at the start of 1-based `line`.
    /// Shows the line a click in the view or the playback reached in the editor; the keyboard
    /// stays with the view or the playback bar, so their keys never type into the program.
    fn jump_to_line(&mut self, line: u32) {
        let chars = self.text.line_to_char(line.saturating_sub(1) as usize);
        self.selection = chars..chars;
        self.editor.show_range(chars..chars);
        self.cursor_line = Some(line);
        self.synced_line = Some(line);
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.strong("Swarf");
            ui.separator();
            ui.menu_button(tr("File"), |ui| self.file_menu(ui));
            ui.menu_button(tr("Edit"), |ui| self.edit_menu(ui));
            ui.menu_button(tr("View"), |ui| self.view_menu(ui));
            if ui.button(tr("Settings…")).clicked() {
                self.settings_open = true;
            }
            ui.separator();
            let label = ui.label(tr("Dialect"));
            let mut dialect = self.dialect;
            egui::ComboBox::from_id_salt("swarf-dialect")
                .selected_text(dialect.label())
                .show_ui(ui, |ui| {
                    for d in Dialect::ALL {
                        ui.selectable_value(&mut dialect, d, d.label());
                    }
                })
                .response
                .labelled_by(label.id);
            // The active tab's dialect, and the one new tabs start in.
            if dialect != self.dialect {
                self.set_dialect(dialect);
            }
            ui.separator();
            let fit = ui.button(tr("Fit view"));
            self.widgets
                .insert("fit_view".into(), fit.rect.intersect(ui.clip_rect()));
            if fit.clicked() {
                self.backplot.fit();
            }
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        let cmd = |ui: &egui::Ui, key| ui.ctx().format_shortcut(&shortcut(key));
        if ui
            .add(egui::Button::new(tr("New")).shortcut_text(cmd(ui, egui::Key::N)))
            .clicked()
        {
            self.new_tab();
        }
        if ui
            .add(egui::Button::new(tr("Open…")).shortcut_text(cmd(ui, egui::Key::O)))
            .clicked()
        {
            self.requests.push(HostRequest::Open);
        }
        ui.add_enabled_ui(!self.recent.is_empty(), |ui| {
            ui.menu_button(tr("Open recent"), |ui| {
                for name in self.recent.clone() {
                    if ui.button(&name).clicked() {
                        self.requests.push(HostRequest::OpenRecent(name));
                    }
                }
            });
        });
        ui.menu_button(tr("Examples"), |ui| {
            for ex in EXAMPLES {
                let text = format!("{}  ({})", ex.name, ex.dialect.label());
                if ui.button(text).clicked() {
                    self.open_example(ex.name);
                }
            }
        });
        ui.separator();
        if ui
            .add(egui::Button::new(tr("Save")).shortcut_text(cmd(ui, egui::Key::S)))
            .clicked()
        {
            self.requests.push(HostRequest::Save);
        }
        if ui.button(tr("Save as…")).clicked() {
            self.requests.push(HostRequest::SaveAs);
        }
        if ui.button(tr("Close tab")).clicked() {
            self.close_tab(self.active);
        }
        ui.separator();
        if ui.button(tr("Import setup…")).clicked() {
            self.requests.push(HostRequest::ImportSetup);
        }
        if ui.button(tr("Export setup…")).clicked() {
            self.requests.push(HostRequest::ExportSetup);
        }
    }

    fn view_menu(&mut self, ui: &mut egui::Ui) {
        ui.menu_button(tr("Language"), |ui| {
            for lang in Lang::ALL {
                if ui
                    .selectable_label(self.lang == lang, lang.native_name())
                    .clicked()
                {
                    self.set_language(lang);
                    ui.close();
                }
            }
        });
    }

    fn edit_menu(&mut self, ui: &mut egui::Ui) {
        let cmd = |ui: &egui::Ui, key| ui.ctx().format_shortcut(&shortcut(key));
        let undo = egui::Button::new(tr("Undo")).shortcut_text(cmd(ui, egui::Key::Z));
        if ui.add_enabled(self.history.can_undo(), undo).clicked() {
            self.undo();
        }
        let redo = egui::Button::new(tr("Redo")).shortcut_text(cmd(ui, egui::Key::Y));
        if ui.add_enabled(self.history.can_redo(), redo).clicked() {
            self.redo();
        }
        ui.separator();
        if ui
            .add(egui::Button::new(tr("Find…")).shortcut_text(cmd(ui, egui::Key::F)))
            .clicked()
        {
            self.open_find(false);
        }
        if ui
            .add(egui::Button::new(tr("Replace…")).shortcut_text(cmd(ui, egui::Key::H)))
            .clicked()
        {
            self.open_find(true);
        }
        if ui
            .add(egui::Button::new(tr("Go to line…")).shortcut_text(cmd(ui, egui::Key::G)))
            .clicked()
        {
            self.goto = Some(String::new());
        }
        ui.separator();
        if ui
            .add(egui::Button::new(tr("Toggle comment")).shortcut_text(cmd(ui, egui::Key::Slash)))
            .clicked()
        {
            self.toggle_comment();
        }
        if ui.button(tr("Renumber blocks…")).clicked() {
            self.renumber = Some(RenumberOptions::default());
        }
    }

    /// Asks to close the application: at once when nothing is unsaved (the host gets
    /// [`HostRequest::Quit`]), otherwise after the user saves or discards the changes of each
    /// tab that has some.
    pub fn request_quit(&mut self) {
        self.run_action(Action::Quit(0));
    }

    fn run_action(&mut self, action: Action) {
        match action {
            Action::Close => self.remove_active_tab(),
            Action::Quit(from) => {
                let dirty = (from..self.tabs.len()).find(|&i| self.tab_document(i).dirty);
                match dirty {
                    Some(i) => {
                        self.switch_tab(i);
                        self.confirm = Some(Action::Quit(i + 1));
                    }
                    None => self.requests.push(HostRequest::Quit),
                }
            }
        }
    }

    /// Opens the built-in example `name` (see [`EXAMPLES`]) in its dialect; false when there is
    /// no such example.
    pub fn open_example(&mut self, name: &str) -> bool {
        let Some(ex) = EXAMPLES.iter().find(|e| e.name == name) else {
            return false;
        };
        self.open_in(
            ex.name,
            ex.text.to_string(),
            Encoding::Utf8,
            None,
            Some(ex.dialect),
        );
        true
    }

    /// Keyboard shortcuts of the editor commands, taken before the widgets see them.
    fn shortcuts(&mut self, ctx: &egui::Context) {
        use egui::{Key, Modifiers};
        let cmd = Modifiers::COMMAND;
        let cmd_shift = Modifiers::COMMAND | Modifiers::SHIFT;
        // Undo belongs to the program unless another text field has the keyboard.
        let others_typing = ctx
            .memory(egui::Memory::focused)
            .is_some_and(|f| f != self.editor.id() && egui::TextEdit::load_state(ctx, f).is_some());
        let (redo, undo) = if others_typing {
            (false, false)
        } else {
            ctx.input_mut(|i| {
                let redo = i.consume_key(cmd_shift, Key::Z) || i.consume_key(cmd, Key::Y);
                (redo, i.consume_key(cmd, Key::Z))
            })
        };
        let (find, replace, goto, comment, save_as, save, open, new) = ctx.input_mut(|i| {
            (
                i.consume_key(cmd, Key::F),
                i.consume_key(cmd, Key::H),
                i.consume_key(cmd, Key::G),
                i.consume_key(cmd, Key::Slash),
                i.consume_key(cmd_shift, Key::S),
                i.consume_key(cmd, Key::S),
                i.consume_key(cmd, Key::O),
                i.consume_key(cmd, Key::N),
            )
        });
        if redo {
            self.redo();
        }
        if undo {
            self.undo();
        }
        if find || replace {
            self.open_find(replace);
        }
        if goto {
            self.goto = Some(String::new());
        }
        if comment {
            self.toggle_comment();
        }
        if save_as {
            self.requests.push(HostRequest::SaveAs);
        } else if save {
            self.requests.push(HostRequest::Save);
        }
        if open {
            self.requests.push(HostRequest::Open);
        }
        if new {
            self.new_tab();
        }
    }

    /// Comments out the selected lines in the dialect's form, or uncomments them.
    pub fn toggle_comment(&mut self) {
        let lines = self.selected_lines();
        let (first, last) = (*lines.start(), *lines.end());
        let text = commands::toggle_comment(&self.text, lines, self.dialect);
        let start = commands::line_start(&text, first);
        let end_line_start = commands::line_start(&text, last);
        let end = text[end_line_start..]
            .find('\n')
            .map_or(text.len(), |j| end_line_start + j);
        let chars = commands::char_of_byte(&text, start)..commands::char_of_byte(&text, end);
        self.apply(text, chars);
    }

    /// Renumbers the program's N numbers (see [`commands::renumber`]).
    pub fn renumber(&mut self, options: RenumberOptions) {
        let out = commands::renumber(&self.text, options, self.dialect);
        self.message = Some(trf(
            "Renumbered {} blocks, {} jump targets",
            &[&out.numbered, &out.targets],
        ));
        let keep = self.selection.start.min(out.text.chars().count());
        self.apply(out.text, keep..keep);
    }

    /// Moves the cursor to the start of 1-based `line` (clamped to the text).
    pub fn go_to_line(&mut self, line: u32) {
        let line = line.clamp(1, commands::line_count(&self.text));
        let start = commands::line_start(&self.text, line);
        let chars = commands::char_of_byte(&self.text, start);
        self.select_chars(chars..chars);
        self.cursor_line = Some(line);
    }

    fn open_find(&mut self, replace: bool) {
        self.find.open = true;
        self.find.replace |= replace;
        self.find.focus = true;
        let selected = self.selected_text();
        if !selected.is_empty() && !selected.contains('\n') {
            self.find.query = selected.to_string();
        }
    }

    fn finder(&self) -> Option<Finder> {
        if self.find.query.is_empty() {
            return None;
        }
        Finder::new(&self.find.query, self.find.options).ok()
    }

    /// Selects the next match of the find field after the selection (wrapping).
    pub fn find_next(&mut self) -> bool {
        let Some(finder) = self.finder() else {
            return false;
        };
        let from = commands::byte_of_char(&self.text, self.selection.end);
        let Some(m) = finder.next(&self.text, from) else {
            return false;
        };
        self.show_match(m);
        true
    }

    /// Selects the previous match of the find field before the selection (wrapping).
    pub fn find_previous(&mut self) -> bool {
        let Some(finder) = self.finder() else {
            return false;
        };
        let before = commands::byte_of_char(&self.text, self.selection.start);
        let Some(m) = finder.previous(&self.text, before) else {
            return false;
        };
        self.show_match(m);
        true
    }

    /// Selects a find match (bytes) and scrolls to it; the keyboard stays where it is, so the
    /// find field keeps it while Enter steps through the matches.
    fn show_match(&mut self, bytes: Range<usize>) {
        let chars = commands::char_of_byte(&self.text, bytes.start)
            ..commands::char_of_byte(&self.text, bytes.end);
        self.cursor_line = Some(commands::line_of_byte(&self.text, bytes.start));
        self.selection = chars.clone();
        self.editor.show_range(chars);
    }

    /// Replaces the selected match with the replacement field and selects the next match; when
    /// the selection is no match, finds the next one first.
    pub fn replace_one(&mut self) {
        let Some(finder) = self.finder() else {
            return;
        };
        let a = commands::byte_of_char(&self.text, self.selection.start);
        let b = commands::byte_of_char(&self.text, self.selection.end);
        let with =
            finder.replacement_at(&self.text, a..b, &self.find.replacement, self.find.options);
        let Some(with) = with else {
            self.find_next();
            return;
        };
        let mut text = self.text.to_string();
        text.replace_range(a..b, &with);
        let after = commands::char_of_byte(&text, a + with.len());
        self.apply(text, after..after);
        self.find_next();
    }

    /// Replaces every match of the find field; the number replaced.
    pub fn replace_all(&mut self) -> usize {
        let Some(finder) = self.finder() else {
            return 0;
        };
        let (text, n) = finder.replace_all(&self.text, &self.find.replacement, self.find.options);
        if n > 0 {
            let keep = self.selection.start.min(text.chars().count());
            self.apply(text, keep..keep);
        }
        self.message = Some(trf("Replaced {} matches", &[&n]));
        n
    }

    fn find_bar(&mut self, ui: &mut egui::Ui) {
        let mut next = false;
        let mut previous = false;
        let mut replace = false;
        let mut replace_all = false;
        let mut close = false;
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(tr("Find"));
            let field = ui.add(
                egui::TextEdit::singleline(&mut self.find.query)
                    .desired_width(160.0)
                    .hint_text(if self.find.options.regex {
                        tr("regular expression")
                    } else {
                        tr("text")
                    }),
            );
            let field = field.labelled_by(label.id);
            self.widgets
                .insert("find_field".into(), field.rect.intersect(ui.clip_rect()));
            if std::mem::take(&mut self.find.focus) {
                field.request_focus();
            }
            if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                next = true;
                field.request_focus();
            }
            if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Escape)) {
                close = true;
            }
            ui.checkbox(&mut self.find.options.regex, tr("Regex"));
            ui.checkbox(&mut self.find.options.match_case, tr("Match case"));
            let previous_button = ui.button(tr("Previous"));
            let next_button = ui.button(tr("Next"));
            self.widgets.insert(
                "find_previous".into(),
                previous_button.rect.intersect(ui.clip_rect()),
            );
            self.widgets.insert(
                "find_next".into(),
                next_button.rect.intersect(ui.clip_rect()),
            );
            previous = previous_button.clicked();
            next |= next_button.clicked();
            let key = (self.generation, self.find.query.clone(), self.find.options);
            if self.find.count.as_ref().map(|(k, _)| k) != Some(&key) {
                let count = if self.find.query.is_empty() {
                    Ok(Vec::new())
                } else {
                    Finder::new(&self.find.query, self.find.options)
                        .map(|f| commands::char_ranges(&self.text, &f.find_all(&self.text)))
                };
                self.find.count = Some((key, count));
            }
            match self.find.count.as_ref().map(|(_, c)| c) {
                Some(Ok(matches)) => {
                    ui.label(trf("{} matches", &[&matches.len()]));
                }
                Some(Err(e)) => {
                    let first = e.lines().last().unwrap_or_default().to_string();
                    ui.colored_label(severity_color(Severity::Error), tr("invalid pattern"))
                        .on_hover_text(first);
                }
                None => {}
            }
            let close_button = ui.button("×").on_hover_text(tr("Close"));
            self.widgets.insert(
                "find_close".into(),
                close_button.rect.intersect(ui.clip_rect()),
            );
            close |= close_button.clicked();
        });
        if self.find.replace {
            ui.horizontal_wrapped(|ui| {
                let label = ui.label(tr("Replace"));
                let field = ui
                    .add(
                        egui::TextEdit::singleline(&mut self.find.replacement).desired_width(160.0),
                    )
                    .labelled_by(label.id);
                let one = ui.button(tr("Replace"));
                let all = ui.button(tr("Replace all"));
                self.widgets
                    .insert("replace_field".into(), field.rect.intersect(ui.clip_rect()));
                self.widgets
                    .insert("replace".into(), one.rect.intersect(ui.clip_rect()));
                self.widgets
                    .insert("replace_all".into(), all.rect.intersect(ui.clip_rect()));
                replace = one.clicked();
                replace_all = all.clicked();
            });
        }
        if close {
            // Back to the program, the selection kept.
            self.find.open = false;
            self.select_chars(self.selection.clone());
        }
        if next {
            self.find_next();
        }
        if previous {
            self.find_previous();
        }
        if replace {
            self.replace_one();
        }
        if replace_all {
            self.replace_all();
        }
    }

    /// The go-to-line, renumber, settings and unsaved-changes windows.
    fn dialogs(&mut self, ctx: &egui::Context) {
        if let Some(mut input) = self.goto.take() {
            let mut open = true;
            let mut go = false;
            egui::Window::new(tr("Go to line"))
                .open(&mut open)
                .default_pos([240.0, 80.0])
                .collapsible(false)
                .resizable(false)
                .show(ctx, |ui| {
                    ui.horizontal(|ui| {
                        let label = ui.label(tr("Line number"));
                        let field = ui
                            .add(egui::TextEdit::singleline(&mut input).desired_width(80.0))
                            .labelled_by(label.id);
                        if !field.has_focus() && !field.lost_focus() && input.is_empty() {
                            field.request_focus();
                        }
                        go = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                        let button = ui.button(tr("Go"));
                        self.widgets
                            .insert("goto_field".into(), field.rect.intersect(ui.clip_rect()));
                        self.widgets
                            .insert("goto_button".into(), button.rect.intersect(ui.clip_rect()));
                        go |= button.clicked();
                    });
                    ui.label(format!("1 – {}", self.text.line_count()));
                });
            let line = input.trim().parse::<u32>().ok().filter(|&n| n >= 1);
            match line.map(|n| n.min(self.text.line_count())) {
                Some(line) if go => self.go_to_line(line),
                _ if open && !(go || ctx.input(|i| i.key_pressed(egui::Key::Escape))) => {
                    self.goto = Some(input);
                }
                _ => {}
            }
        }
        if let Some(mut options) = self.renumber.take() {
            let mut open = true;
            let mut run = false;
            egui::Window::new(tr("Renumber blocks"))
                .open(&mut open)
                .default_pos([240.0, 80.0])
                .collapsible(false)
                .resizable(false)
                .show(ctx, |ui| {
                    egui::Grid::new("swarf-renumber")
                        .num_columns(2)
                        .show(ui, |ui| {
                            let label = ui.label(tr("Start"));
                            ui.add(egui::DragValue::new(&mut options.start).range(0..=99_999_999))
                                .labelled_by(label.id);
                            ui.end_row();
                            let label = ui.label(tr("Step"));
                            ui.add(egui::DragValue::new(&mut options.step).range(1..=10_000))
                                .labelled_by(label.id);
                            ui.end_row();
                        });
                    ui.checkbox(&mut options.all_blocks, tr("Number every block"));
                    run = ui.button(tr("Renumber")).clicked();
                });
            if run {
                self.renumber(options);
            } else if open {
                self.renumber = Some(options);
            }
        }
        if self.settings_open {
            let mut open = true;
            let mut setup = self.setup.clone();
            let mut dialect = self.dialect;
            let mut request = None;
            egui::Window::new(tr("Settings"))
                .open(&mut open)
                .default_pos([240.0, 60.0])
                .default_width(480.0)
                .default_height(600.0)
                .vscroll(true)
                .show(ctx, |ui| {
                    request = crate::settings::settings_ui(
                        ui,
                        &mut dialect,
                        &mut setup,
                        &mut self.new_offset,
                    );
                });
            self.settings_open = open;
            if dialect != self.dialect {
                self.set_dialect(dialect);
            }
            self.set_setup(setup);
            if let Some(r) = request {
                self.requests.push(r);
            }
        }
        if let Some(action) = self.confirm.clone() {
            let mut answer = None;
            egui::Modal::new(egui::Id::unique("swarf-unsaved")).show(ctx, |ui| {
                ui.heading(tr("Unsaved changes"));
                ui.label(trf(
                    "{} has changes that are not saved.",
                    &[&self.document.name],
                ));
                ui.horizontal(|ui| {
                    if ui.button(tr("Save")).clicked() {
                        answer = Some(0);
                    }
                    if ui.button(tr("Discard changes")).clicked() {
                        answer = Some(1);
                    }
                    if ui.button(tr("Cancel")).clicked() {
                        answer = Some(2);
                    }
                });
            });
            match answer {
                Some(0) => {
                    self.confirm = None;
                    self.after_save = Some(action);
                    self.requests.push(HostRequest::Save);
                }
                Some(1) => {
                    self.confirm = None;
                    self.run_action(action);
                }
                Some(_) => self.confirm = None,
                None => {}
            }
        }
    }

    fn status_bar(&self, ui: &mut egui::Ui) {
        let s = self.stats();
        ui.horizontal(|ui| {
            ui.label(trf("{} blocks", &[&s.blocks]));
            ui.separator();
            ui.label(trf("{} motions", &[&s.motions]));
            ui.separator();
            if let Some((min, max)) = s.bounds {
                let size = max - min;
                ui.label(trf(
                    "extent {} × {} × {} mm",
                    &[
                        &format!("{:.2}", size.x),
                        &format!("{:.2}", size.y),
                        &format!("{:.2}", size.z),
                    ],
                ));
                ui.separator();
            }
            ui.label(format!("≈ {}", format_duration(s.estimated_secs)));
            ui.separator();
            let errors = self.analysis.count(Severity::Error);
            let warnings = self.analysis.count(Severity::Warning);
            ui.colored_label(
                if errors > 0 {
                    severity_color(Severity::Error)
                } else {
                    ui.visuals().text_color()
                },
                trf("{} errors, {} warnings", &[&errors, &warnings]),
            );
            if let Some(line) = self.cursor_line {
                ui.separator();
                ui.label(trf("line {}", &[&line]));
            }
            ui.separator();
            ui.label(self.document.encoding.name());
            if let Some(Progress::Reading { read, lines }) = self.pending {
                ui.separator();
                ui.label("Analysing");
                ui.add(
                    egui::ProgressBar::new(read as f32 / lines.max(1) as f32)
                        .desired_width(180.0)
                        .text(format!("{read} / {lines} lines read")),
                );
            } else if let Some((done, total)) = self.analysis_progress() {
                ui.separator();
                ui.label(tr("Analysing"));
                let fraction = if total == 0 {
                    1.0
                } else {
                    done as f32 / total as f32
                };
                ui.add(
                    egui::ProgressBar::new(fraction)
                        .desired_width(180.0)
                        .text(trf("{} / {} blocks", &[&done, &total])),
                );
            }
            if let Some(message) = &self.message {
                ui.separator();
                ui.label(message);
            }
        });
    }

    /// "Reading… N %" over the empty view of a tab whose first analysis is still running.
    fn loading_overlay(&self, ui: &mut egui::Ui, view: egui::Rect) {
        if self.own_analysis {
            return;
        }
        let Some(progress) = self.pending else {
            return;
        };
        let percent = |done: usize, total: usize| {
            let (done, total) = (done as u64, total.max(1) as u64);
            done.min(total) * 100 / total
        };
        let text = match progress {
            Progress::Reading { read, lines } => trf("Reading… {} %", &[&percent(read, lines)]),
            Progress::Running { reached, blocks } => {
                trf("Analysing… {} %", &[&percent(reached, blocks)])
            }
        };
        let at = egui::Rect::from_center_size(view.center(), egui::vec2(260.0, 40.0));
        ui.put(
            at,
            egui::Label::new(egui::RichText::new(text).heading().weak()),
        );
    }

    /// The offer to read the active tab's program in the dialect its codes point to, over the
    /// problems: "This program looks like Syntec 900M (G71 on line 3)" and a Switch button.
    fn dialect_notice(&mut self, ui: &mut egui::Ui) {
        let Some(to) = self.suggested_dialect() else {
            return;
        };
        let first = self.analysis.hint.as_ref().and_then(|h| h.first.clone());
        let mut switch = false;
        ui.horizontal(|ui| {
            let text = match &first {
                Some((what, line)) => trf(
                    "This program looks like {} ({} on line {})",
                    &[&to.label(), what, line],
                ),
                None => trf("This program looks like {}", &[&to.label()]),
            };
            ui.colored_label(severity_color(Severity::Warning), text);
            switch = ui
                .button(tr("Switch"))
                .on_hover_text(trf("Read this tab's program as {}", &[&to.label()]))
                .clicked();
        });
        if switch {
            self.set_tab_dialect(self.active, to);
        }
    }

    /// The tabs over the editor: one per open file (click to switch, × to close) and + for a
    /// new one.
    fn tab_strip(&mut self, ui: &mut egui::Ui) {
        let mut switch = None;
        let mut close = None;
        let mut new = false;
        egui::ScrollArea::horizontal()
            .id_salt("swarf-tabs")
            .show(ui, |ui| {
                ui.horizontal(|ui| {
                    for i in 0..self.tabs.len() {
                        let doc = self.tab_document(i);
                        let dirty = if doc.dirty { " *" } else { "" };
                        let label = format!("{}{dirty}", doc.name);
                        let hover = doc.path.clone().unwrap_or_else(|| doc.name.clone());
                        let close_label = trf("Close {}", &[&doc.name]);
                        let tab = ui.selectable_label(i == self.active, label);
                        self.widgets.insert(
                            format!("tab {}", i + 1).into(),
                            tab.rect.intersect(ui.clip_rect()),
                        );
                        if tab.on_hover_text(hover).clicked() {
                            switch = Some(i);
                        }
                        let button = ui.small_button("×");
                        button.widget_info(|| {
                            egui::WidgetInfo::labeled(
                                egui::accesskit::Role::Button,
                                true,
                                &close_label,
                            )
                        });
                        self.widgets.insert(
                            format!("close_tab {}", i + 1).into(),
                            button.rect.intersect(ui.clip_rect()),
                        );
                        if button.on_hover_text(&close_label).clicked() {
                            close = Some(i);
                        }
                        ui.separator();
                    }
                    let button = ui.small_button("+");
                    button.widget_info(|| {
                        egui::WidgetInfo::labeled(
                            egui::accesskit::Role::Button,
                            true,
                            tr("New tab"),
                        )
                    });
                    self.widgets
                        .insert("new_tab".into(), button.rect.intersect(ui.clip_rect()));
                    new = button.on_hover_text(tr("New tab")).clicked();
                });
            });
        if let Some(i) = switch {
            self.switch_tab(i);
        }
        if let Some(i) = close {
            self.close_tab(i);
        }
        if new {
            self.new_tab();
        }
    }

    fn problems_list(&mut self, ui: &mut egui::Ui) {
        self.dialect_notice(ui);
        let own = self.analysis.problems.len();
        let total = own + self.analysis.elsewhere.len();
        if total == 0 {
            ui.label(tr("No problems"));
            return;
        }
        ui.strong(trf("Problems ({})", &[&total]));
        let row_height = ui.text_style_height(&egui::TextStyle::Monospace);
        egui::ScrollArea::vertical()
            .id_salt("swarf-problems-scroll")
            .auto_shrink([false, false])
            .show_rows(ui, row_height, total, |ui, rows| {
                // Only the rows on screen are laid out: a program can have many thousands. The
                // program's own problems come first, then those in the other tabs it called.
                let mut jump = None;
                let mut jump_elsewhere = None;
                for i in rows {
                    let (text, severity, hover) = if let Some(p) = self.analysis.problems.get(i) {
                        (
                            format!(
                                "{}:{}  {}[{}]  {}",
                                p.line, p.col, p.severity, p.code, p.message
                            ),
                            p.severity,
                            tr("Go to this position").to_string(),
                        )
                    } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                        let p = &l.problem;
                        (
                            format!(
                                "{}:{}:{}  {}[{}]  {}",
                                l.file, p.line, p.col, p.severity, p.code, p.message
                            ),
                            p.severity,
                            trf("Go to this position in {}", &[&l.file]),
                        )
                    } else {
                        continue;
                    };
                    let label = egui::RichText::new(text)
                        .monospace()
                        .color(severity_color(severity));
                    let row = ui.add(egui::Label::new(label).sense(egui::Sense::click()));
                    if i == 0 {
                        self.widgets
                            .insert("problem_first".into(), row.rect.intersect(ui.clip_rect()));
                    }
                    if row.on_hover_text(hover).clicked() {
                        if let Some(p) = self.analysis.problems.get(i) {
                            jump = Some(p.chars.clone());
                        } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                            jump_elsewhere = Some((l.file.clone(), l.problem.chars.clone()));
                        }
                    }
                }
                if let Some(chars) = jump {
                    self.select_chars(chars);
                }
                if let Some((file, chars)) = jump_elsewhere
                    && let Some(i) =
                        (0..self.tabs.len()).find(|&i| self.tab_document(i).name == file)
                {
                    self.switch_tab(i);
                    self.select_chars(chars);
                }
            });
    }
}

/// What a tab shows before its first analysis is done: no path, no problems, no counts.
fn no_analysis() -> Analysis {
    Analysis::of(
        swarf_analysis::Results::default(),
        &ProgramText::from(String::new()),
    )
}

/// The analysis beside the UI: a thread of its own, which has `waker`'s context repaint with
/// each reply; where there are no threads, the frames themselves (the web page hands its worker
/// over with [`Workbench::set_analyst`]).
fn default_analyst(waker: &Arc<OnceLock<egui::Context>>) -> Box<dyn Analyst> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let waker = Arc::clone(waker);
        let wake = move |progress| {
            if let Some(ctx) = waker.get() {
                ctx.request_repaint_after(reply_frame(progress));
            }
        };
        if let Ok(thread) = swarf_analysis::Thread::spawn(wake) {
            return Box::new(thread);
        }
    }
    let _ = waker;
    Box::new(swarf_analysis::Inline::default())
}

/// The shortcut of an editor command: Ctrl (Cmd on macOS) and `key`.
fn shortcut(key: egui::Key) -> egui::KeyboardShortcut {
    egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, key)
}

/// `1 h 02 min`, `3 min 04 s` or `12.5 s`.
pub fn format_duration(secs: f64) -> String {
    let secs = secs.max(0.0);
    if secs >= 3600.0 {
        format!(
            "{:.0} h {:02.0} min",
            (secs / 3600.0).floor(),
            ((secs % 3600.0) / 60.0).floor()
        )
    } else if secs >= 60.0 {
        format!(
            "{:.0} min {:02.0} s",
            (secs / 60.0).floor(),
            (secs % 60.0).floor()
        )
    } else {
        format!("{secs:.1} s")
    }
}
