//! Selection, undo and redo, and the editing commands applied as one undo step each.

use std::ops::Range;

use super::Workbench;
use super::tabs::next_stamp;
use crate::buffer::Buffer;
use crate::commands::{self, RenumberOptions};
use crate::history::{EditKind, History, Snapshot};
use crate::i18n::trf;

impl Workbench {
    /// Selects the whole of 1-based `line` in the editor (clamped to the text) and scrolls to it.
    pub fn select_line(&mut self, line: u32) {
        let line = line.clamp(1, commands::line_count(&self.tab.text));
        self.select_chars(lines_chars(&self.tab.text, line, line));
        self.tab.cursor_line = Some(line);
    }

    /// The editor's selection in characters.
    pub fn selection(&self) -> Range<usize> {
        self.tab.selection.clone()
    }

    /// The selected text.
    pub fn selected_text(&self) -> &str {
        let a = commands::byte_of_char(&self.tab.text, self.tab.selection.start);
        let b = commands::byte_of_char(&self.tab.text, self.tab.selection.end);
        self.tab.text.get(a..b).unwrap_or_default()
    }

    /// The 1-based lines the selection covers (a selection ending at a line's start does not
    /// take that line).
    pub fn selected_lines(&self) -> std::ops::RangeInclusive<u32> {
        let a = commands::byte_of_char(&self.tab.text, self.tab.selection.start);
        let mut b = commands::byte_of_char(&self.tab.text, self.tab.selection.end);
        if b > a && self.tab.text[..b].ends_with('\n') {
            b -= 1;
        }
        commands::line_of_byte(&self.tab.text, a)..=commands::line_of_byte(&self.tab.text, b)
    }

    pub(super) fn select_chars(&mut self, chars: Range<usize>) {
        self.tab.selection = chars.clone();
        self.editor.jump_to(chars);
    }

    /// Undoes the last change (typing run or command).
    pub fn undo(&mut self) {
        self.step_history(History::undo);
    }

    /// Redoes the last undone change.
    pub fn redo(&mut self) {
        self.step_history(History::redo);
    }

    /// Goes to the state `step` takes from the history, given the current one.
    fn step_history(&mut self, step: fn(&mut History, Snapshot) -> Option<Snapshot>) {
        let current = Snapshot {
            text: self.tab.text.rope().clone(),
            selection: self.tab.selection.clone(),
        };
        if let Some(to) = step(&mut self.tab.history, current) {
            self.tab.text = Buffer::from(to.text);
            self.tab.shadow = self.tab.text.rope().clone();
            self.select_chars(to.selection);
            self.text_changed();
        }
    }

    /// Replaces the text as one undoable command and selects `selection` (characters).
    pub(super) fn apply(&mut self, text: String, selection: Range<usize>) {
        if text == self.tab.text.as_str() {
            return;
        }
        let before = Snapshot {
            text: std::mem::replace(&mut self.tab.text, Buffer::from(text))
                .rope()
                .clone(),
            selection: self.tab.selection.clone(),
        };
        (self.tab.history).record(before, EditKind::Command, true, self.now);
        self.tab.shadow = self.tab.text.rope().clone();
        self.select_chars(selection);
        self.text_changed();
    }

    pub(super) fn text_changed(&mut self) {
        self.tab.document.dirty = self.tab.text.rope() != &self.tab.document.saved;
        self.tab.document.revision = next_stamp();
        self.reanalyse();
    }

    /// Comments out the selected lines in the dialect's form, or uncomments them.
    pub fn toggle_comment(&mut self) {
        let lines = self.selected_lines();
        let (first, last) = (*lines.start(), *lines.end());
        let text = commands::toggle_comment(&self.tab.text, lines, self.tab.dialect);
        let chars = lines_chars(&text, first, last);
        self.apply(text, chars);
    }

    /// Renumbers the program's N numbers (see [`commands::renumber`]).
    pub fn renumber(&mut self, options: RenumberOptions) {
        let out = commands::renumber(&self.tab.text, options, self.tab.dialect);
        self.message = Some(trf(
            "Renumbered {} blocks, {} jump targets",
            &[&out.numbered, &out.targets],
        ));
        let keep = self.tab.selection.start.min(out.text.chars().count());
        self.apply(out.text, keep..keep);
    }

    /// Moves the cursor to the start of 1-based `line` (clamped to the text).
    pub fn go_to_line(&mut self, line: u32) {
        let line = line.clamp(1, commands::line_count(&self.tab.text));
        let start = commands::line_start(&self.tab.text, line);
        let chars = commands::char_of_byte(&self.tab.text, start);
        self.select_chars(chars..chars);
        self.tab.cursor_line = Some(line);
    }
}

/// The characters of `text` from the start of 1-based line `first` to the end of line `last`,
/// without its line break.
fn lines_chars(text: &str, first: u32, last: u32) -> Range<usize> {
    let start = commands::line_start(text, first);
    let last_start = commands::line_start(text, last);
    let end = text[last_start..]
        .find('\n')
        .map_or(text.len(), |j| last_start + j);
    commands::char_of_byte(text, start)..commands::char_of_byte(text, end)
}
