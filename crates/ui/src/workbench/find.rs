//! The find/replace bar and its commands.

use std::ops::Range;

use swarf_syntax::Severity;

use super::Workbench;
use crate::commands::{self, FindOptions, Finder};
use crate::editor::severity_color;
use crate::i18n::{tr, trf};

/// Matches in characters, or why the pattern is invalid.
type Matches = Result<Vec<Range<usize>>, String>;

/// The find/replace bar's state.
#[derive(Debug, Clone, Default)]
pub(super) struct FindBar {
    pub(super) open: bool,
    replace: bool,
    query: String,
    replacement: String,
    options: FindOptions,
    /// Ask for focus on the find field next frame.
    focus: bool,
    /// The matches in characters (or the pattern's error) for (text generation, query, options).
    pub(super) count: Option<((u64, String, FindOptions), Matches)>,
}

impl Workbench {
    pub(super) fn open_find(&mut self, replace: bool) {
        self.find.open = true;
        self.find.replace |= replace;
        self.find.focus = true;
        let selected = self.selected_text();
        if !selected.is_empty() && !selected.contains('\n') {
            self.find.query = selected.to_string();
        }
    }

    fn finder(&self) -> Option<Finder> {
        let query = Some(&self.find.query).filter(|q| !q.is_empty())?;
        Finder::new(query, self.find.options).ok()
    }

    /// Selects the next match of the find field after the selection (wrapping).
    pub fn find_next(&mut self) -> bool {
        self.find_step(true)
    }

    /// Selects the previous match of the find field before the selection (wrapping).
    pub fn find_previous(&mut self) -> bool {
        self.find_step(false)
    }

    /// Selects the match after (`forward`) or before the selection, keyboard left where it is.
    fn find_step(&mut self, forward: bool) -> bool {
        let text = &self.tab.text;
        let found = self.finder().and_then(|finder| match forward {
            true => finder.next(text, commands::byte_of_char(text, self.tab.selection.end)),
            false => finder.previous(text, commands::byte_of_char(text, self.tab.selection.start)),
        });
        let Some(bytes) = found else {
            return false;
        };
        let chars = commands::char_of_byte(&self.tab.text, bytes.start)
            ..commands::char_of_byte(&self.tab.text, bytes.end);
        self.tab.cursor_line = Some(commands::line_of_byte(&self.tab.text, bytes.start));
        self.tab.selection = chars.clone();
        self.editor.show_range(chars);
        true
    }

    /// Replaces the selected match with the replacement field and selects the next match; when
    /// the selection is no match, finds the next one first.
    pub fn replace_one(&mut self) {
        let Some(finder) = self.finder() else {
            return;
        };
        let (text, find) = (&self.tab.text, &self.find);
        let a = commands::byte_of_char(text, self.tab.selection.start);
        let b = commands::byte_of_char(text, self.tab.selection.end);
        let Some(with) = finder.replacement_at(text, a..b, &find.replacement, find.options) else {
            self.find_next();
            return;
        };
        let mut text = self.tab.text.to_string();
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
        let (text, find) = (&self.tab.text, &self.find);
        let (text, n) = finder.replace_all(text, &find.replacement, find.options);
        if n > 0 {
            let keep = self.tab.selection.start.min(text.chars().count());
            self.apply(text, keep..keep);
        }
        self.message = Some(trf("Replaced {} matches", &[&n]));
        n
    }

    pub(super) fn find_bar(&mut self, ui: &mut egui::Ui) {
        let (mut next, mut previous) = (false, false);
        let (mut replace, mut replace_all, mut close) = (false, false, false);
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(tr("Find"));
            let regex = self.find.options.regex;
            let hint = tr(if regex { "regular expression" } else { "text" });
            let field = egui::TextEdit::singleline(&mut self.find.query).desired_width(160.0);
            let field = ui.add(field.hint_text(hint));
            let field = field.labelled_by(label.id);
            self.keep_rect(ui, "find_field", &field);
            if std::mem::take(&mut self.find.focus) {
                field.request_focus();
            }
            if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                next = true;
                field.request_focus();
            }
            close = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Escape));
            ui.checkbox(&mut self.find.options.regex, tr("Regex"));
            ui.checkbox(&mut self.find.options.match_case, tr("Match case"));
            previous = self.kept_button(ui, tr("Previous"), "find_previous");
            next |= self.kept_button(ui, tr("Next"), "find_next");
            let key = (self.generation, self.find.query.clone(), self.find.options);
            if self.find.count.as_ref().map(|(k, _)| k) != Some(&key) {
                let count = if self.find.query.is_empty() {
                    Ok(Vec::new())
                } else {
                    Finder::new(&self.find.query, self.find.options)
                        .map(|f| commands::char_ranges(&self.tab.text, &f.find_all(&self.tab.text)))
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
            self.keep_rect(ui, "find_close", &close_button);
            close |= close_button.clicked();
        });
        if self.find.replace {
            ui.horizontal_wrapped(|ui| {
                let label = ui.label(tr("Replace"));
                let field = egui::TextEdit::singleline(&mut self.find.replacement);
                let field = ui.add(field.desired_width(160.0)).labelled_by(label.id);
                self.keep_rect(ui, "replace_field", &field);
                replace = self.kept_button(ui, tr("Replace"), "replace");
                replace_all = self.kept_button(ui, tr("Replace all"), "replace_all");
            });
        }
        if close {
            // Back to the program, the selection kept.
            self.find.open = false;
            self.select_chars(self.tab.selection.clone());
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
}
