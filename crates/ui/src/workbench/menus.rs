//! The top bar, its File, Edit and View menus, the keyboard shortcuts and the actions they run.

use swarf_syntax::Dialect;

use super::{HostRequest, Workbench};
use crate::commands::RenumberOptions;
use crate::examples::EXAMPLES;
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
            ui.menu_button(tr("Edit"), |ui| self.edit_menu(ui));
            ui.menu_button(tr("View"), |ui| self.view_menu(ui));
            if ui.button(tr("Settings…")).clicked() {
                self.settings_open = true;
            }
            ui.separator();
            let mut dialect = self.dialect;
            let (id, label) = ("swarf-dialect", tr("Dialect"));
            choice(ui, id, label, &mut dialect, Dialect::ALL, Dialect::label);
            // The active tab's dialect, and the one new tabs start in.
            if dialect != self.dialect {
                self.set_dialect(dialect);
            }
            ui.separator();
            let fit = ui.button(tr("Fit view"));
            self.keep_rect(ui, "fit_view", &fit);
            if fit.clicked() {
                self.backplot.fit();
            }
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui) {
        if item(ui, tr("New"), egui::Key::N, true) {
            self.new_tab();
        }
        if item(ui, tr("Open…"), egui::Key::O, true) {
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
        if item(ui, tr("Save"), egui::Key::S, true) {
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
        if item(ui, tr("Undo"), egui::Key::Z, self.history.can_undo()) {
            self.undo();
        }
        if item(ui, tr("Redo"), egui::Key::Y, self.history.can_redo()) {
            self.redo();
        }
        ui.separator();
        if item(ui, tr("Find…"), egui::Key::F, true) {
            self.open_find(false);
        }
        if item(ui, tr("Replace…"), egui::Key::H, true) {
            self.open_find(true);
        }
        if item(ui, tr("Go to line…"), egui::Key::G, true) {
            self.goto = Some(String::new());
        }
        ui.separator();
        if item(ui, tr("Toggle comment"), egui::Key::Slash, true) {
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

    /// Keyboard shortcuts of the editor commands, taken before the widgets see them.
    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
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
        if redo {
            self.redo();
        }
        if undo {
            self.undo();
        }
        // Ctrl+Shift+S before Ctrl+S, which would take it too.
        let commands: [Shortcut; 8] = [
            (cmd, Key::F, |wb| wb.open_find(false)),
            (cmd, Key::H, |wb| wb.open_find(true)),
            (cmd, Key::G, |wb| wb.goto = Some(String::new())),
            (cmd, Key::Slash, Workbench::toggle_comment),
            (cmd_shift, Key::S, |wb| {
                wb.requests.push(HostRequest::SaveAs);
            }),
            (cmd, Key::S, |wb| wb.requests.push(HostRequest::Save)),
            (cmd, Key::O, |wb| wb.requests.push(HostRequest::Open)),
            (cmd, Key::N, Workbench::new_tab),
        ];
        let pressed: Vec<fn(&mut Workbench)> = ctx.input_mut(|i| {
            (commands.into_iter())
                .filter(|(modifiers, key, _)| i.consume_key(*modifiers, *key))
                .map(|(_, _, run)| run)
                .collect()
        });
        for run in pressed {
            run(self);
        }
    }
}

/// A menu item showing its shortcut, Ctrl (Cmd on macOS) and `key`; whether it was clicked.
fn item(ui: &mut egui::Ui, label: &str, key: egui::Key, enabled: bool) -> bool {
    let shortcut = egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, key);
    let text = ui.ctx().format_shortcut(&shortcut);
    ui.add_enabled(enabled, egui::Button::new(label).shortcut_text(text))
        .clicked()
}

/// A keyboard shortcut: its modifiers, its key and the command it runs.
type Shortcut = (egui::Modifiers, egui::Key, fn(&mut Workbench));
