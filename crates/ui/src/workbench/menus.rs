//! The top bar, its File, Edit and View menus, the keyboard shortcuts and the actions they run.

use swarf_syntax::Dialect;

use super::{HostRequest, Workbench};
use crate::commands::RenumberOptions;
use crate::examples::EXAMPLES;
use crate::i18n::{Lang, tr};

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
}

/// The shortcut of an editor command: Ctrl (Cmd on macOS) and `key`.
fn shortcut(key: egui::Key) -> egui::KeyboardShortcut {
    egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, key)
}
