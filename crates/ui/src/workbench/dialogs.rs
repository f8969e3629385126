//! The go-to-line, renumber, settings and unsaved-changes windows.

use super::{HostRequest, Workbench};
use crate::i18n::{tr, trf};
use crate::settings::{drag_row, settings_ui};

impl Workbench {
    /// The go-to-line, renumber, settings and unsaved-changes windows.
    pub(super) fn dialogs(&mut self, ctx: &egui::Context) {
        if let Some(mut input) = self.goto.take() {
            let mut open = true;
            let mut go = false;
            small_window(tr("Go to line"), &mut open).show(ctx, |ui| {
                ui.horizontal(|ui| {
                    let label = ui.label(tr("Line number"));
                    let edit = egui::TextEdit::singleline(&mut input).desired_width(80.0);
                    let field = ui.add(edit).labelled_by(label.id);
                    if !field.has_focus() && !field.lost_focus() && input.is_empty() {
                        field.request_focus();
                    }
                    go = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                    self.keep_rect(ui, "goto_field", &field);
                    go |= self.kept_button(ui, tr("Go"), "goto_button");
                });
                ui.label(format!("1 – {}", self.tab.text.line_count()));
            });
            let escape = ctx.input(|i| i.key_pressed(egui::Key::Escape));
            // `go_to_line` clamps to the text.
            match input.trim().parse::<u32>().ok().filter(|&n| n >= 1) {
                Some(line) if go => self.go_to_line(line),
                _ if open && !(go || escape) => self.goto = Some(input),
                _ => {}
            }
        }
        if let Some(mut options) = self.renumber.take() {
            let mut open = true;
            let mut run = false;
            small_window(tr("Renumber blocks"), &mut open).show(ctx, |ui| {
                egui::Grid::new("swarf-renumber")
                    .num_columns(2)
                    .show(ui, |ui| {
                        let start = egui::DragValue::new(&mut options.start);
                        drag_row(ui, tr("Start"), start.range(0..=99_999_999));
                        let step = egui::DragValue::new(&mut options.step);
                        drag_row(ui, tr("Step"), step.range(1..=10_000));
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
            let mut dialect = self.tab.dialect;
            let mut request = None;
            egui::Window::new(tr("Settings"))
                .open(&mut open)
                .default_pos([240.0, 60.0])
                .default_width(480.0)
                .default_height(600.0)
                .vscroll(true)
                .show(ctx, |ui| {
                    request = settings_ui(ui, &mut dialect, &mut setup, &mut self.new_offset);
                });
            self.settings_open = open;
            if dialect != self.tab.dialect {
                self.set_dialect(dialect);
            }
            self.set_setup(setup);
            self.requests.extend(request);
        }
        if let Some(action) = self.confirm.clone() {
            let mut answer = None;
            egui::Modal::new(egui::Id::unique("swarf-unsaved")).show(ctx, |ui| {
                ui.heading(tr("Unsaved changes"));
                let name = &self.tab.document.name;
                ui.label(trf("{} has changes that are not saved.", &[name]));
                ui.horizontal(|ui| {
                    let buttons = [tr("Save"), tr("Discard changes"), tr("Cancel")];
                    for (i, label) in buttons.into_iter().enumerate() {
                        if ui.button(label).clicked() {
                            answer = Some(i);
                        }
                    }
                });
            });
            if answer.is_some() {
                self.confirm = None;
            }
            match answer {
                Some(0) => {
                    self.after_save = Some(action);
                    self.requests.push(HostRequest::Save);
                }
                Some(1) => self.run_action(action),
                _ => {}
            }
        }
    }
}

/// A small fixed window titled `title`, closed by its × through `open`.
fn small_window<'a>(title: &str, open: &'a mut bool) -> egui::Window<'a> {
    egui::Window::new(title)
        .open(open)
        .default_pos([240.0, 80.0])
        .collapsible(false)
        .resizable(false)
}
