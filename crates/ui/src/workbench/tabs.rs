//! Tabs and the documents they hold: opening, closing, switching, parking and restoring them.

use std::ops::Range;

use ropey::Rope;

use swarf_syntax::{Dialect, Encoding};

use super::Workbench;
use super::analyst::no_analysis;
use super::menus::Action;
use crate::analysis::{Analysis, ProgramText};
use crate::buffer::Buffer;
use crate::examples::EXAMPLES;
use crate::history::History;
use crate::i18n::{tr, trf};

/// The open program as a file: its name, encoding and whether it has unsaved changes.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// The file name shown in the title and status bar (`untitled.nc` before the first save).
    pub name: String,
    /// Where the file is, as the host names it (a path, a browser handle's key); `None` if new.
    pub path: Option<String>,
    /// The encoding the file was read with; saving writes it back the same way.
    pub encoding: Encoding,
    /// The text as last opened or saved.
    pub(super) saved: Rope,
    pub(super) dirty: bool,
    /// Names this document while it is open (unique in the process).
    id: u64,
    /// Moves with every change of the text (unique in the process).
    pub(super) revision: u64,
}

impl Default for Document {
    /// An empty untitled program.
    fn default() -> Self {
        Document::new("untitled.nc", &Rope::new(), Encoding::Utf8)
    }
}

/// A tab's own state: the workbench's `tab` while it is active, its entry in `tabs` otherwise.
#[derive(Debug, Clone, Default)]
pub(super) struct Tab {
    pub(super) text: Buffer,
    pub(super) document: Document,
    /// Undo and redo over typing and commands.
    pub(super) history: History,
    /// The text as last recorded in the history (the "before" of the next typed change).
    pub(super) shadow: Rope,
    /// The editor's selection in characters, as last reported or set.
    pub(super) selection: Range<usize>,
    pub(super) cursor_line: Option<u32>,
    /// The dialect the tab's program is read in.
    pub(super) dialect: Dialect,
    /// The tab's last finished analysis while it is parked (`None` before its first is done).
    pub(super) analysis: Option<Analysis>,
}

impl Tab {
    /// A tab showing `text` as file `name` in `dialect`: a fresh undo history, no unsaved changes.
    pub(super) fn new(name: &str, text: String, encoding: Encoding, dialect: Dialect) -> Self {
        let text = Buffer::from(text);
        Tab {
            document: Document::new(name, text.rope(), encoding),
            shadow: text.rope().clone(),
            text,
            dialect,
            ..Tab::default()
        }
    }
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
    pub(super) fn new(name: &str, text: &Rope, encoding: Encoding) -> Self {
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

    /// Names the document while it is open, never shared with another of this process.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Changes with every change of the text, never to a value another text had.
    pub fn revision(&self) -> u64 {
        self.revision
    }
}

impl Workbench {
    /// Opens a program read from a file in a new tab (or the blank active one), nothing unsaved.
    pub fn open_document(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        self.open_file(name, text.into(), encoding, None);
    }

    /// Opens a program read from `path` as [`Workbench::open_document`]; one open has its tab back.
    pub fn open_file(
        &mut self,
        name: &str,
        text: String,
        encoding: Encoding,
        path: Option<String>,
    ) {
        let open_at = path.as_ref().and_then(|p| {
            (0..self.tabs.len()).find(|&i| self.tab_document(i).path.as_ref() == Some(p))
        });
        match open_at {
            Some(i) => {
                self.switch_tab(i);
                if self.tab.document.dirty {
                    self.message = Some(trf("{} is open here with unsaved changes", &[&name]));
                    return;
                }
            }
            // A new file starts in the default dialect (a tab keeps its own once open).
            None if self.is_blank() => self.tab.dialect = self.default_dialect,
            None => self.push_tab(),
        }
        // A built-in example (from the menu, or saved as a file) opens in its dialect.
        if let Some(example) = EXAMPLES.iter().find(|e| e.text == text) {
            self.tab.dialect = example.dialect;
        }
        self.load(name, text, encoding);
        self.tab.document.path = path;
    }

    /// Parks the active tab and makes a new empty one at the end active, in the default dialect.
    fn push_tab(&mut self) {
        let current = self.park();
        if let Some(slot) = self.tabs.get_mut(self.active) {
            *slot = current;
        }
        self.tabs.push(Tab::default());
        self.active = self.tabs.len() - 1;
        self.tab.dialect = self.default_dialect;
    }

    /// Replaces the active tab's program with a file's text, as after saving it as UTF-8.
    pub fn reload_document(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        let path = self.tab.document.path.take();
        self.load(name, text.into(), encoding);
        self.tab.document.path = path;
    }

    /// Shows `text` as the active tab's file `name`: a fresh undo history, no unsaved changes.
    fn load(&mut self, name: &str, text: String, encoding: Encoding) {
        self.tab = Tab::new(name, text, encoding, self.tab.dialect);
        self.synced_line = None;
        self.editor.jump_to(0..0);
        self.message = None;
        // The empty stand-in until the next analysis is done: what was shown is of another text.
        self.own_analysis = false;
        self.analysis = no_analysis();
        self.floor = self.generation + 1;
        self.reanalyse();
        self.backplot.fit();
    }

    /// Whether the active tab is empty, untitled and unchanged (a file opened replaces it).
    fn is_blank(&self) -> bool {
        self.tab.text.is_empty() && !self.tab.document.dirty && self.tab.document.path.is_none()
    }

    /// Records where the open document's file is (after opening or saving it).
    pub fn set_path(&mut self, path: Option<String>) {
        self.tab.document.path = path;
    }

    /// Replaces the active tab's program with `text` recovered after a crash, still unsaved.
    pub fn recover(&mut self, name: &str, text: impl Into<String>, encoding: Encoding) {
        self.load(name, text.into(), encoding);
        self.tab.document.saved = Rope::new();
        self.tab.document.dirty = true;
        self.tab.document.revision = next_stamp();
        self.message = recovered_message(&[name]);
    }

    /// Replaces every tab with `records` (none: nothing happens) and activates the `active`-th;
    /// unsaved texts come back as changes still to save, which the status bar names.
    pub fn restore_tabs(&mut self, records: Vec<TabRecord>, active: usize) {
        if records.is_empty() {
            return;
        }
        let active = active.min(records.len() - 1);
        let unsaved = records.iter().filter(|r| r.dirty).map(|r| r.name.as_str());
        let message = recovered_message(&unsaved.collect::<Vec<_>>());
        let tabs = records.into_iter().map(|r| {
            let dialect = r.dialect.unwrap_or(self.default_dialect);
            let mut tab = Tab::new(&r.name, r.text, r.encoding, dialect);
            tab.document.path = r.path;
            if r.dirty {
                tab.document.saved = Rope::new();
                tab.document.dirty = true;
            }
            tab
        });
        self.tabs = tabs.collect();
        self.activate(active);
        self.message = message.or(self.message.take());
    }

    /// The text of tab `i` (a copy), `None` past the last tab.
    pub fn tab_text(&self, i: usize) -> Option<String> {
        self.tab_at(i).map(|tab| tab.text.to_text())
    }

    /// The text of tab `i` shared, not copied (to write it out a piece at a time).
    pub fn tab_source(&self, i: usize) -> Option<ProgramText> {
        self.tab_at(i).map(|tab| tab.text.program_text())
    }

    /// Tab `i` (the active one's state is `tab`), `None` past the last tab.
    fn tab_at(&self, i: usize) -> Option<&Tab> {
        if i == self.active {
            Some(&self.tab)
        } else {
            self.tabs.get(i)
        }
    }

    /// Takes the active tab's state out of the workbench, with its last finished analysis.
    fn park(&mut self) -> Tab {
        self.pending = None;
        let analysis = std::mem::take(&mut self.own_analysis)
            .then(|| std::mem::replace(&mut self.analysis, no_analysis()));
        Tab {
            analysis,
            ..std::mem::take(&mut self.tab)
        }
    }

    /// Makes tab `i` active (the active one parked first), showing its own last analysis.
    fn activate(&mut self, i: usize) {
        self.tab = std::mem::take(&mut self.tabs[i]);
        self.active = i;
        self.synced_line = None;
        self.state_cache = None;
        self.select_chars(self.tab.selection.clone());
        self.pending = None;
        let analysis = self.tab.analysis.take();
        self.own_analysis = analysis.is_some();
        self.analysis = analysis.unwrap_or_else(no_analysis);
        self.floor = self.generation + 1;
        self.reanalyse();
        self.backplot.fit();
    }

    /// The document of tab `i` (which may be the active one; the active one's past the last).
    pub(super) fn tab_document(&self, i: usize) -> &Document {
        self.tab_at(i)
            .map_or(&self.tab.document, |tab| &tab.document)
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
        self.activate(i);
    }

    /// Closes tab `i`, asking about its unsaved changes first; the last leaves an untitled one.
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
            self.active -= usize::from(i < self.active);
            // The active program's calls may have reached the tab closed.
            self.reanalyse();
        }
    }

    /// Drops the active tab, unsaved changes and all.
    pub(super) fn remove_active_tab(&mut self) {
        if self.tabs.len() <= 1 {
            self.tab.dialect = self.default_dialect;
            self.load("untitled.nc", String::new(), Encoding::Utf8);
            return;
        }
        self.tabs.remove(self.active);
        self.activate(self.active.min(self.tabs.len() - 1));
    }

    /// Opens a new tab with an empty program: `untitled.nc` (`untitled-2.nc` … if taken).
    pub fn new_tab(&mut self) {
        self.push_tab();
        let taken = |name: &str| {
            (0..self.tabs.len()).any(|i| i != self.active && self.tab_document(i).name == name)
        };
        let mut name = "untitled.nc".to_string();
        let mut n = 1;
        while taken(&name) {
            n += 1;
            name = format!("untitled-{n}.nc");
        }
        self.load(&name, String::new(), Encoding::Utf8);
    }

    /// Whether any tab has unsaved changes.
    pub fn any_dirty(&self) -> bool {
        (0..self.tabs.len()).any(|i| self.tab_document(i).dirty)
    }

    /// The open document (name, encoding).
    pub fn document(&self) -> &Document {
        &self.tab.document
    }

    /// Records that the active tab's text was saved as `name`; runs an action waiting for it.
    pub fn mark_saved(&mut self, name: &str) {
        self.tab.document.name = name.to_string();
        self.tab.document.saved = self.tab.text.rope().clone();
        self.tab.document.dirty = false;
        self.message = Some(trf("Saved {}", &[&name]));
        if let Some(action) = self.after_save.take() {
            self.run_action(action);
        }
    }

    /// The dialect the active tab's program is read in.
    pub fn dialect(&self) -> Dialect {
        self.tab.dialect
    }

    /// Reads the active tab's program in `dialect`, the one new tabs start in (as the selector).
    pub fn set_dialect(&mut self, dialect: Dialect) {
        self.default_dialect = dialect;
        self.set_tab_dialect(self.active, dialect);
    }

    /// The dialect tab `i`'s program is read in; `None` past the last tab.
    pub fn tab_dialect(&self, i: usize) -> Option<Dialect> {
        self.tab_at(i).map(|tab| tab.dialect)
    }

    /// Reads tab `i`'s program in `dialect` (another tab's when next shown), nothing else's.
    pub fn set_tab_dialect(&mut self, i: usize, dialect: Dialect) {
        if i == self.active {
            if dialect != self.tab.dialect {
                self.tab.dialect = dialect;
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

    /// Opens the built-in example `name` ([`EXAMPLES`]) in its dialect; false if there is none.
    pub fn open_example(&mut self, name: &str) -> bool {
        let Some(ex) = EXAMPLES.iter().find(|e| e.name == name) else {
            return false;
        };
        self.open_file(ex.name, ex.text.to_string(), Encoding::Utf8, None);
        true
    }

    /// The tabs over the editor: one per open file (click to switch, × to close) and +.
    pub(super) fn tab_strip(&mut self, ui: &mut egui::Ui) {
        let mut switch = None;
        let mut close = None;
        let mut new = false;
        super::sideways(ui, "swarf-tabs", |ui| {
            ui.horizontal(|ui| {
                for i in 0..self.tabs.len() {
                    let doc = self.tab_document(i);
                    let dirty = if doc.dirty { " *" } else { "" };
                    let label = format!("{}{dirty}", doc.name);
                    let hover = doc.path.clone().unwrap_or_else(|| doc.name.clone());
                    let close_label = trf("Close {}", &[&doc.name]);
                    let tab = ui.selectable_label(i == self.active, label);
                    self.keep_rect(ui, format!("tab {}", i + 1), &tab);
                    if tab.on_hover_text(hover).clicked() {
                        switch = Some(i);
                    }
                    let name = format!("close_tab {}", i + 1);
                    if self.small_button(ui, "×", &close_label, name) {
                        close = Some(i);
                    }
                    ui.separator();
                }
                new = self.small_button(ui, "+", tr("New tab"), "new_tab".to_string());
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

    /// A small button named and hinted `label`, kept as `widget`; whether it was clicked.
    fn small_button(&mut self, ui: &mut egui::Ui, text: &str, label: &str, widget: String) -> bool {
        let button = ui.small_button(text);
        button
            .widget_info(|| egui::WidgetInfo::labeled(egui::accesskit::Role::Button, true, label));
        self.keep_rect(ui, widget, &button);
        button.on_hover_text(label).clicked()
    }
}

/// What the status bar says after the unsaved changes of tabs `names` were recovered.
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
pub(super) fn next_stamp() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}
