//! The top bar, its File, Edit and View menus, the keyboard shortcuts and the actions they run.

use egui::{Key, Modifiers};
use swarf_syntax::Dialect;

use super::HostRequest::{self, ExportSetup, ImportSetup, Open, Save, SaveAs};
use super::Workbench;
use crate::commands::RenumberOptions;
use crate::examples::EXAMPLES;
use crate::history::History;
use crate::i18n::{Lang, tr};
use crate::settings::choice;

/// An action that drops unsaved changes, held while they are confirmed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Action {
    /// Close the active tab.
    Close,
    /// Quit once the tabs from this index on are saved or discarded.
    Quit(usize),
}

impl Workbench {
    pub(super) fn top_bar(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.strong("Swarf");
            ui.separator();
            ui.menu_button(tr("File"), |ui| self.file_menu(ui));
            ui.menu_button(tr("Edit"), |ui| self.menu_items(ui, &EDIT));
            ui.menu_button(tr("View"), |ui| {
                ui.menu_button(tr("Language"), |ui| {
                    for lang in Lang::ALL {
                        let on = self.lang == lang;
                        if ui.selectable_label(on, lang.native_name()).clicked() {
                            self.set_language(lang);
                            ui.close();
                        }
                    }
                });
            });
            if ui.button(tr("Settings…")).clicked() {
                self.settings_open = true;
            }
            ui.separator();
            let mut dialect = self.tab.dialect;
            let (id, label) = ("swarf-dialect", tr("Dialect"));
            let dialects = Dialect::ALL.map(|d| (d, d.label()));
            choice(ui, id, label, &mut dialect, &dialects);
            // The active tab's dialect, and the one new tabs start in.
            if dialect != self.tab.dialect {
                self.set_dialect(dialect);
            }
            ui.separator();
            if self.kept_button(ui, tr("Fit view"), "fit_view") {
                self.backplot.fit();
            }
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        self.menu_items(ui, &FILE[..1]);
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
        self.menu_items(ui, &FILE[1..]);
    }

    /// The commands of `groups` as menu items with their first shortcut, groups separated.
    fn menu_items(&mut self, ui: &mut egui::Ui, groups: &[&[Command]]) {
        for (i, group) in groups.iter().enumerate() {
            if i > 0 {
                ui.separator();
            }
            for Command(label, keys, allowed, run) in *group {
                let mut button = egui::Button::new(tr(label));
                if let Some(&(modifiers, key)) = keys.first() {
                    let keys = egui::KeyboardShortcut::new(modifiers, key);
                    button = button.shortcut_text(ui.ctx().format_shortcut(&keys));
                }
                let enabled = allowed.is_none_or(|allowed| allowed(&self.tab.history));
                if ui.add_enabled(enabled, button).clicked() {
                    run(self);
                }
            }
        }
    }

    /// Asks to quit ([`HostRequest::Quit`]) once each tab's changes are saved or discarded.
    pub fn request_quit(&mut self) {
        self.run_action(Action::Quit(0));
    }

    pub(super) fn run_action(&mut self, action: Action) {
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

    /// Keyboard shortcuts of the menus' commands, taken before the widgets see them.
    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
        // Undo belongs to the program unless another text field has the keyboard.
        let others_typing = ctx
            .memory(egui::Memory::focused)
            .is_some_and(|f| f != self.editor.id() && egui::TextEdit::load_state(ctx, f).is_some());
        let mut keys: Vec<_> = (FILE.iter().chain(&EDIT))
            .flat_map(|group| group.iter())
            .filter(|Command(_, _, allowed, _)| !(allowed.is_some() && others_typing))
            .flat_map(|Command(_, keys, _, run)| keys.iter().map(|&(m, key)| (m, key, *run)))
            .collect();
        // Ctrl+Shift+S before Ctrl+S, which would take it too.
        keys.sort_by_key(|(modifiers, _, _)| !modifiers.shift);
        ctx.input_mut(|i| keys.retain(|(m, key, _)| i.consume_key(*m, *key)));
        for (_, _, run) in keys {
            run(self);
        }
    }
}

/// A command of the menus and the keyboard: its label (looked up with `tr`), its shortcuts (the
/// first shown in its menu item), for undo and redo whether the history allows it (their
/// shortcuts are left to another text field that has the keyboard), and what it does.
struct Command(
    &'static str,
    &'static [(Modifiers, Key)],
    Option<fn(&History) -> bool>,
    fn(&mut Workbench),
);

/// Ctrl (Cmd on macOS).
const CTRL: Modifiers = Modifiers::COMMAND;
/// Ctrl (Cmd on macOS) and Shift.
const CTRL_SHIFT: Modifiers = Modifiers::COMMAND.plus(Modifiers::SHIFT);

/// The File menu's commands in groups between separators (Open recent and Examples end the first).
#[rustfmt::skip]
const FILE: [&[Command]; 3] = [
    &[
        Command("New", &[(CTRL, Key::N)], None, Workbench::new_tab),
        Command("Open…", &[(CTRL, Key::O)], None, |wb| wb.requests.push(Open)),
    ],
    &[
        Command("Save", &[(CTRL, Key::S)], None, |wb| wb.requests.push(Save)),
        Command("Save as…", &[(CTRL_SHIFT, Key::S)], None, |wb| wb.requests.push(SaveAs)),
        Command("Close tab", &[], None, |wb| wb.close_tab(wb.active)),
    ],
    &[
        Command("Import setup…", &[], None, |wb| wb.requests.push(ImportSetup)),
        Command("Export setup…", &[], None, |wb| wb.requests.push(ExportSetup)),
    ],
];

/// The Edit menu's commands in groups between separators.
#[rustfmt::skip]
const EDIT: [&[Command]; 3] = [
    &[
        Command("Undo", &[(CTRL, Key::Z)], Some(History::can_undo), Workbench::undo),
        Command("Redo", &[(CTRL, Key::Y), (CTRL_SHIFT, Key::Z)], Some(History::can_redo),
            Workbench::redo),
    ],
    &[
        Command("Find…", &[(CTRL, Key::F)], None, |wb| wb.open_find(false)),
        Command("Replace…", &[(CTRL, Key::H)], None, |wb| wb.open_find(true)),
        Command("Go to line…", &[(CTRL, Key::G)], None, |wb| wb.goto = Some(String::new())),
    ],
    &[
        Command("Toggle comment", &[(CTRL, Key::Slash)], None, Workbench::toggle_comment),
        Command("Renumber blocks…", &[], None, |wb| wb.renumber = Some(RenumberOptions::default())),
    ],
];
