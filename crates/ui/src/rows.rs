//! The program editor: a rope ([`Buffer`]) laying out only on-screen rows, so a keystroke costs the
//! same at any length; completion ([`Popup`]), IME. Keys need a frame with the focus first (Enter
//! in the find bar never types).

use std::ops::Range;

use egui::text::CCursor;
use egui::{Event, FontId, ImeEvent, Key, Pos2, Rect, Sense, Stroke, Ui};
use swarf_syntax::Dialect;

use crate::analysis::Problem;
use crate::buffer::Buffer;
use crate::commands::{self, Completion};
use crate::completion::{Popup, PopupKey};
use crate::editor::{
    EditorOutput, HIGHLIGHTS_SHOWN, gutter_tooltip, highlight, hover_text, keep_keys, palette,
    severity_color, squiggle,
};
use crate::i18n::tr;

/// Space between the gutter and the text, and around the text.
const PAD: f32 = 6.0;

/// The G-code editor widget's state (the text itself is owned by the caller).
#[derive(Debug, Clone, Default)]
pub struct CodeEditor {
    /// A selection to show centred next frame, and whether the editor takes the keyboard.
    jump: Option<(Range<usize>, bool)>,
    /// Character ranges marked in the text (the find bar's matches), sorted.
    highlights: Vec<Range<usize>>,
    /// The caret, a character index.
    caret: usize,
    /// The other end of the selection (equal to the caret when nothing is selected).
    anchor: usize,
    /// The column (characters) Up and Down aim for, kept over short lines.
    column: Option<usize>,
    /// Scroll so the caret is on screen (after a key moved it or an edit).
    reveal: bool,
    /// Scroll so the caret's row is in the middle (after a jump).
    centre: bool,
    /// Scroll offset and height of the view last frame.
    offset: f32,
    view_height: f32,
    /// The widest row laid out so far (the scroll area's width).
    width: f32,
    /// The completion list, while it is open.
    popup: Option<Popup>,
    /// Where the caret was drawn this frame, if on screen (for the completion and IME windows).
    caret_rect: Option<Rect>,
    /// Where the completion list goes: under the caret, where it was last drawn.
    popup_pos: Pos2,
    /// The text an input method is composing, shown at the caret but not yet in the rope.
    preedit: Option<Preedit>,
    /// Whether the editor had the keyboard focus at the end of the last frame.
    had_focus: bool,
}

/// Text being composed by an input method.
#[derive(Debug, Clone, PartialEq)]
struct Preedit {
    text: String,
    /// The characters of `text` the input method is working on (the caret sits at their end).
    active: Option<Range<usize>>,
}

/// What a key, input-method or clipboard event does to the text at the selection.
#[derive(Clone, Copy)]
enum Edit<'a> {
    /// Replace the selection with this text.
    Insert(&'a str),
    /// Delete the selection, or the character before the caret.
    Backspace,
    /// Delete the selection, or the character after the caret.
    Delete,
}

impl CodeEditor {
    /// Selects the character range on the next frame, scrolls to it and takes the keyboard.
    pub fn jump_to(&mut self, chars: Range<usize>) {
        self.jump = Some((chars, true));
    }

    /// Selects the character range on the next frame and scrolls to it, keyboard left alone.
    pub fn show_range(&mut self, chars: Range<usize>) {
        self.jump = Some((chars, false));
    }

    /// Marks these character ranges in the text (at most [`HIGHLIGHTS_SHOWN`] are drawn).
    pub fn set_highlights(&mut self, ranges: &[Range<usize>]) {
        if self.highlights != ranges {
            self.highlights = ranges.iter().take(HIGHLIGHTS_SHOWN).cloned().collect();
        }
    }

    /// The editor's widget id (for focus checks).
    pub fn id(&self) -> egui::Id {
        egui::Id::unique("swarf-code-editor")
    }

    /// The selection as a sorted character range.
    pub fn selection(&self) -> Range<usize> {
        self.caret.min(self.anchor)..self.caret.max(self.anchor)
    }

    /// The completions on offer (code and meaning), while the list is open.
    pub fn completions(&self) -> Option<&[Completion]> {
        self.popup.as_ref().map(|p| p.items.as_slice())
    }

    /// The completion list for the G or M code being typed before the caret, if any.
    fn popup_here(&self, text: &Buffer, dialect: Dialect) -> Option<Popup> {
        if !self.selection().is_empty() {
            return None;
        }
        let line = text.char_to_line(self.caret);
        let col = self.caret - text.line_to_char(line);
        if col > text.line_len_chars(line) {
            return None;
        }
        let line_text = text.line_text(line);
        let byte = commands::byte_of_char(&line_text, col);
        Popup::at(&line_text, byte, self.caret, dialect)
    }

    /// Replaces the typed prefix with completion `index` and puts the caret after it.
    fn accept(&mut self, text: &mut Buffer, index: usize, output: &mut EditorOutput) {
        let Some(end) = self.popup.take().and_then(|p| p.accept(index, text)) else {
            return;
        };
        self.place(end);
        output.completed = true;
    }

    /// Applies one input method event; whether the text changed. Composed text stays out of the
    /// rope until it is committed, which replaces the selection as one edit.
    fn ime(&mut self, text: &mut Buffer, event: ImeEvent) -> bool {
        match event {
            // A line break is the Enter key's, as in egui's text editor.
            ImeEvent::Preedit { text: shown, .. } | ImeEvent::Commit(shown)
                if shown == "\n" || shown == "\r" =>
            {
                false
            }
            ImeEvent::Preedit {
                text: shown,
                active_range_chars,
            } => {
                self.preedit = (!shown.is_empty()).then_some(Preedit {
                    text: shown,
                    active: active_range_chars,
                });
                self.reveal = true;
                false
            }
            ImeEvent::Commit(committed) => {
                self.preedit = None;
                !committed.is_empty() && self.edit(text, Edit::Insert(&committed))
            }
            ImeEvent::DeleteSurrounding {
                before_chars,
                after_chars,
            } => {
                let sel = self.selection();
                let from = sel.start.saturating_sub(before_chars);
                let to = (sel.end + after_chars).min(text.len_chars());
                if from >= to {
                    return false;
                }
                (self.anchor, self.caret) = (from, to);
                self.edit(text, Edit::Delete)
            }
            // The enable and disable notices (no longer sent) change nothing.
            _ => false,
        }
    }

    /// Applies one edit at the selection; whether the text changed.
    fn edit(&mut self, text: &mut Buffer, edit: Edit) -> bool {
        let sel = self.selection();
        let range = match edit {
            Edit::Insert(_) => sel,
            _ if !sel.is_empty() => sel,
            Edit::Backspace if sel.start > 0 => {
                // A `\r\n` goes as one line ending.
                let mut start = sel.start - 1;
                if start > 0 && text.slice(start - 1..sel.start) == "\r\n" {
                    start -= 1;
                }
                start..sel.start
            }
            Edit::Delete if sel.end < text.len_chars() => {
                let mut end = sel.end + 1;
                if text.slice(sel.end..end + 1) == "\r\n" {
                    end += 1;
                }
                sel.end..end
            }
            _ => return false,
        };
        let insert = match edit {
            Edit::Insert(s) => s,
            Edit::Backspace | Edit::Delete => "",
        };
        if range.is_empty() && insert.is_empty() {
            return false;
        }
        self.place(text.replace(range, insert));
        true
    }

    /// Puts the caret at `at`, nothing selected, and brings it into view.
    fn place(&mut self, at: usize) {
        (self.caret, self.anchor, self.column, self.reveal) = (at, at, None, true);
    }

    /// Moves the caret to `to`, extending the selection when `extend`.
    fn move_to(&mut self, to: usize, extend: bool) {
        self.caret = to;
        if !extend {
            self.anchor = to;
        }
        self.reveal = true;
    }

    /// Handles the keyboard and clipboard events of this frame in order; the completion list is
    /// worked out again after each edit, so a key never acts on a list made for older text.
    fn keys(
        &mut self,
        ui: &Ui,
        text: &mut Buffer,
        dialect: Dialect,
        rows_per_page: usize,
        output: &mut EditorOutput,
    ) {
        let events = ui.input(|i| i.events.clone());
        for event in events {
            let len = text.len_chars();
            self.caret = self.caret.min(len);
            self.anchor = self.anchor.min(len);
            // While an input method composes, its keys are its own, not the text's.
            if self.preedit.is_some() && matches!(event, Event::Key { .. } | Event::Text(_)) {
                continue;
            }
            if let Some(popup) = self.popup.as_mut()
                && let Event::Key {
                    key,
                    pressed: true,
                    modifiers,
                    ..
                } = &event
                && !modifiers.any()
            {
                match popup.key(*key) {
                    PopupKey::None => {}
                    PopupKey::Handled => continue,
                    PopupKey::Close => {
                        self.popup = None;
                        continue;
                    }
                    PopupKey::Accept(i) => {
                        self.accept(text, i, output);
                        continue;
                    }
                }
            }
            if self.event(ui, text, event, rows_per_page, output) {
                output.changed = true;
                self.popup = self.popup_here(text, dialect);
            }
        }
    }

    /// Applies one keyboard or clipboard event; whether the text changed.
    fn event(
        &mut self,
        ui: &Ui,
        text: &mut Buffer,
        event: Event,
        rows_per_page: usize,
        output: &mut EditorOutput,
    ) -> bool {
        let len = text.len_chars();
        let mut changed = false;
        match event {
            Event::Ime(ime) => changed |= self.ime(text, ime),
            // A lone line break comes as the Enter key too.
            Event::Text(t) if t == "\n" || t == "\r" => {}
            Event::Text(t) | Event::Paste(t) if !t.is_empty() => {
                changed |= self.edit(text, Edit::Insert(&t));
            }
            Event::Copy | Event::Cut => {
                let sel = self.selection();
                if !sel.is_empty() {
                    ui.ctx().copy_text(text.slice(sel));
                    if matches!(event, Event::Cut) {
                        changed |= self.edit(text, Edit::Delete);
                    }
                }
            }
            Event::Key {
                key,
                pressed: true,
                modifiers,
                ..
            } => {
                let shift = modifiers.shift;
                let word = modifiers.command || modifiers.alt;
                let line = text.char_to_line(self.caret);
                let line_start = text.line_to_char(line);
                let col = self.caret - line_start;
                let last_line = text.len_lines().saturating_sub(1);
                let vertical = |this: &mut Self, to_line: usize| {
                    let want = *this.column.get_or_insert(col);
                    let start = text.line_to_char(to_line);
                    let to = start + want.min(text.line_len_chars(to_line));
                    this.move_to(to, shift);
                };
                match key {
                    Key::Enter => {
                        changed |= self.edit(text, Edit::Insert("\n"));
                        output.ends_line = true;
                    }
                    Key::Tab if !modifiers.any() => changed |= self.edit(text, Edit::Insert("\t")),
                    Key::Backspace | Key::Delete => {
                        let forward = key == Key::Delete;
                        if word && self.selection().is_empty() {
                            self.anchor = word_boundary(text, self.caret, forward);
                        }
                        changed |= self.edit(
                            text,
                            if forward {
                                Edit::Delete
                            } else {
                                Edit::Backspace
                            },
                        );
                    }
                    Key::A if modifiers.command => (self.anchor, self.caret) = (0, len),
                    Key::ArrowLeft | Key::ArrowRight => {
                        let forward = key == Key::ArrowRight;
                        let sel = self.selection();
                        let to = match (!shift && !sel.is_empty(), forward) {
                            (true, false) => sel.start,
                            (true, true) => sel.end,
                            _ if word => word_boundary(text, self.caret, forward),
                            (_, false) => self.caret.saturating_sub(1),
                            (_, true) => (self.caret + 1).min(len),
                        };
                        self.column = None;
                        self.move_to(to, shift);
                    }
                    Key::ArrowUp if line > 0 => vertical(self, line - 1),
                    Key::ArrowUp => self.move_to(0, shift),
                    Key::ArrowDown if line + 1 < text.len_lines() => vertical(self, line + 1),
                    Key::ArrowDown => self.move_to(len, shift),
                    Key::PageUp => vertical(self, line.saturating_sub(rows_per_page)),
                    Key::PageDown => vertical(self, (line + rows_per_page).min(last_line)),
                    Key::Home | Key::End => {
                        let to = match (key == Key::End, modifiers.command) {
                            (false, true) => 0,
                            (true, true) => len,
                            (false, false) => line_start,
                            (true, false) => line_start + text.line_len_chars(line),
                        };
                        self.column = None;
                        self.move_to(to, shift);
                    }
                    _ => {}
                }
            }
            _ => {}
        }
        changed
    }

    /// Shows the text with a gutter and its sorted `problems`, filling `ui`, named by `label`.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        label: egui::Id,
        text: &mut Buffer,
        dialect: Dialect,
        problems: &[Problem],
    ) -> EditorOutput {
        let id = self.id();
        let font = egui::TextStyle::Monospace.resolve(ui.style());
        // Lent to the frame's painting, which borrows the editor.
        let highlights = std::mem::take(&mut self.highlights);
        let mut output = EditorOutput::default();
        let row_height = ui.ctx().fonts_mut(|f| f.row_height(&font)).max(1.0);
        let char_width = ui.ctx().fonts_mut(|f| f.glyph_width(&font, '0')).max(1.0);
        if let Some((range, focus)) = self.jump.take() {
            // Selected, the caret at its end (both clamped to the text).
            let len = text.len_chars();
            (self.anchor, self.caret) = (range.start.min(len), range.end.min(len));
            self.column = None;
            self.popup = None;
            self.centre = true;
            if focus {
                ui.memory_mut(|m| m.request_focus(id));
            }
        }
        let focused = ui.memory(|m| m.has_focus(id));
        if focused && self.had_focus {
            // Ctrl+Space asks for the list where the caret is.
            let ask = self.preedit.is_none()
                && ui.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, Key::Space));
            if ask {
                self.popup = self.popup_here(text, dialect);
            }
            let rows_per_page = ((self.view_height / row_height).floor() as usize).max(1);
            self.keys(ui, text, dialect, rows_per_page, &mut output);
        }
        if focused {
            // Keys kept next frame: Escape closes the list or a composition rather than leaving.
            let escape = self.popup.is_some() || self.preedit.is_some();
            keep_keys(ui, id, true, escape);
        } else {
            self.preedit = None;
        }
        let len = text.len_chars();
        self.caret = self.caret.min(len);
        self.anchor = self.anchor.min(len);
        let lines = text.len_lines();
        let digits = lines.to_string().len().max(3);
        let gutter = (digits + 1) as f32 * char_width + PAD;
        let caret_line = text.char_to_line(self.caret);

        let mut area = egui::ScrollArea::both()
            .id_salt("swarf-editor-rows")
            .auto_shrink([false, false]);
        let caret_y = caret_line as f32 * row_height;
        // Whether the caret is to be brought into view across too (a long line).
        let reveal = self.reveal || self.centre;
        if std::mem::take(&mut self.centre) {
            area = area.vertical_scroll_offset((caret_y - self.view_height / 2.0).max(0.0));
            self.reveal = false;
        } else if std::mem::take(&mut self.reveal) {
            if caret_y < self.offset {
                area = area.vertical_scroll_offset(caret_y);
            } else if caret_y + row_height > self.offset + self.view_height {
                area = area.vertical_scroll_offset(caret_y + row_height - self.view_height);
            }
        }
        let scroll = area.show_viewport(ui, |ui, viewport| {
            let size = egui::vec2(
                gutter + PAD + self.width + 4.0 * char_width,
                lines as f32 * row_height + PAD,
            );
            let (_, rect) = ui.allocate_space(size.max(ui.available_size()));
            let response = ui.interact(rect, id, Sense::click_and_drag());
            let response = response.labelled_by(label);
            if response.hovered() {
                // The web page shows its on-screen keyboard and input method over editable text.
                ui.output_mut(|o| o.mutable_text_under_cursor = true);
            }
            let role = egui::Role::MultilineTextInput;
            response.widget_info(|| egui::WidgetInfo::labeled(role, true, tr("Program")));
            ui.ctx().accesskit_node_builder(id, |node| {
                node.set_role(egui::accesskit::Role::MultilineTextInput);
            });
            let text_left = rect.left() + gutter + PAD;
            let visible_rows = {
                let first = (viewport.min.y / row_height).floor().max(0.0) as usize;
                let last = ((viewport.max.y / row_height).ceil().max(0.0) as usize).min(lines);
                first.min(last)..last
            };
            // The character under a point: its row, and the column from that row's layout.
            let char_at = |ui: &Ui, pos: Pos2| -> usize {
                let row = ((pos.y - rect.top()) / row_height).floor().max(0.0) as usize;
                let row = row.min(lines.saturating_sub(1));
                let (start, len) = (text.line_to_char(row), text.line_len_chars(row));
                let job = highlight(&text.line_text(row), dialect, &font);
                let galley = ui.painter().layout_job(job);
                let cursor = galley.cursor_from_pos(egui::vec2(pos.x - text_left, 0.0));
                start + cursor.index.0.min(len)
            };
            let pointer = response.interact_pointer_pos().or(response.hover_pos());
            if response.double_clicked()
                && let Some(pos) = pointer
            {
                // The word under the pointer (an address word, a number, a name).
                let at = char_at(ui, pos);
                self.anchor = word_boundary(text, (at + 1).min(len), false);
                self.caret = word_boundary(text, at, true);
                self.column = None;
            } else if let Some(pos) = response.interact_pointer_pos() {
                let (pressed, extend) =
                    ui.input(|i| (i.pointer.primary_pressed(), i.modifiers.shift));
                if pressed {
                    self.move_to(char_at(ui, pos), extend);
                    self.column = None;
                    self.reveal = false;
                } else if response.dragged() {
                    self.caret = char_at(ui, pos);
                    self.column = None;
                }
                response.request_focus();
            }
            let focused = response.has_focus() || ui.memory(|m| m.has_focus(id));
            self.paint_rows(
                ui,
                text,
                &Rows {
                    rect,
                    rows: visible_rows.clone(),
                    row_height,
                    text_left,
                    digits,
                    font: &font,
                    dialect,
                    problems,
                    highlights: &highlights,
                    focused,
                    reveal,
                },
            );
            // Tooltips: a gutter marker's diagnostics; over the text, the code and problems.
            if let Some(pos) = response.hover_pos() {
                let row = ((pos.y - rect.top()) / row_height).floor().max(0.0) as usize;
                if row < lines {
                    let number = u32::try_from(row + 1).unwrap_or(u32::MAX);
                    let tip = if pos.x < text_left {
                        gutter_tooltip(problems, number)
                    } else {
                        let start = text.line_to_char(row);
                        let local: Vec<Problem> = problems_on_rows(problems, row..row + 1)
                            .iter()
                            .map(|p| Problem {
                                chars: p.chars.start.saturating_sub(start)
                                    ..p.chars.end.saturating_sub(start),
                                ..p.clone()
                            })
                            .collect();
                        let at = char_at(ui, pos) - start;
                        hover_text(&text.line_text(row), dialect, at, &local)
                    };
                    if let Some(tip) = tip {
                        response.on_hover_text_at_pointer(tip);
                    }
                }
            }
        });
        self.offset = scroll.state.clamped_offset().y;
        self.view_height = scroll.inner_rect.height();
        self.completion_list(ui, id, text, &mut output);
        if ui.memory(|m| m.owns_ime_events(id)) {
            // The input method's window: at the caret, or atop the view when it is scrolled away.
            let view = scroll.inner_rect;
            let top = Rect::from_min_size(view.min, egui::vec2(2.0, row_height));
            let cursor = self.caret_rect.filter(|r| view.intersects(*r));
            let to_global = ui.ctx().layer_transform_to_global(ui.layer_id());
            let to_global = to_global.unwrap_or_default();
            ui.output_mut(|o| {
                o.ime = Some(egui::output::IMEOutput {
                    purpose: egui::IMEPurpose::Normal,
                    rect: to_global * view,
                    cursor_rect: to_global * cursor.unwrap_or(top),
                    should_interrupt_composition: false,
                });
            });
        }
        output.cursor_line = u32::try_from(text.char_to_line(self.caret) + 1).ok();
        output.selection = self.selection();
        self.had_focus = ui.memory(|m| m.has_focus(id));
        self.highlights = highlights;
        output
    }

    /// Closes the completion list when the caret left the word or the keyboard went elsewhere,
    /// and draws it under the caret; a click on an item takes it.
    fn completion_list(
        &mut self,
        ui: &Ui,
        id: egui::Id,
        text: &mut Buffer,
        output: &mut EditorOutput,
    ) {
        if let Some(p) = &self.popup {
            let moved = self.caret != p.chars.end || self.caret != self.anchor;
            // A click on the list itself takes the focus for a moment: the pointer keeps it.
            let away = !ui.memory(|m| m.has_focus(id)) && !p.pointer_over(ui.ctx());
            if moved || away || self.preedit.is_some() {
                self.popup = None;
            }
        }
        if let Some(r) = self.caret_rect {
            self.popup_pos = r.left_bottom();
        }
        let at = self.popup_pos;
        if let Some(popup) = self.popup.as_mut()
            && let Some(i) = popup.show(ui.ctx(), id, at)
        {
            self.accept(text, i, output);
            ui.memory_mut(|m| m.request_focus(id));
        }
    }

    /// Paints the visible rows: gutter, text, selection, caret, find matches and diagnostics.
    fn paint_rows(&mut self, ui: &Ui, text: &Buffer, rows: &Rows<'_>) {
        let painter = ui.painter();
        let selection = self.selection();
        let sel_fill = ui.visuals().selection.bg_fill;
        let mark_fill = egui::Color32::from_rgba_unmultiplied(255, 210, 80, 70);
        let on_rows = problems_on_rows(rows.problems, rows.rows.clone());
        let first_char = text.line_to_char(rows.rows.start);
        let last_char = text.line_to_char(rows.rows.end);
        let marks_from = rows.highlights.partition_point(|r| r.end < first_char);
        let marks = rows.highlights[marks_from..].iter();
        let marks: Vec<&Range<usize>> = marks.take_while(|r| r.start <= last_char).collect();
        let caret_line = text.char_to_line(self.caret);
        let caret_col = self.caret - text.line_to_char(caret_line);
        self.caret_rect = None;
        for row in rows.rows.clone() {
            let top = rows.rect.top() + row as f32 * rows.row_height;
            let start = text.line_to_char(row);
            let len = text.line_len_chars(row);
            // Text being composed is shown in the caret's row, at the caret.
            let here = row == caret_line && rows.focused && caret_col <= len;
            let preedit = self.preedit.as_ref().filter(|_| here);
            let mut shown = text.line_text(row);
            if let Some(p) = preedit {
                let at = commands::byte_of_char(&shown, caret_col);
                shown.to_mut().insert_str(at, &p.text);
            }
            let extra = preedit.map_or(0, |p| p.text.chars().count());
            let galley = painter.layout_job(highlight(&shown, rows.dialect, rows.font));
            if galley.size().x > self.width {
                self.width = galley.size().x;
                // The view was narrower: bring the caret into view again next frame.
                if row == caret_line && rows.reveal {
                    self.reveal = true;
                }
            }
            let origin = egui::pos2(rows.text_left, top);
            let bottom = top + rows.row_height;
            // The row's height between `x0` and `x1`.
            let band =
                |x0: f32, x1: f32| Rect::from_min_max(egui::pos2(x0, top), egui::pos2(x1, bottom));
            let x_at = |col: usize| origin.x + galley.pos_from_cursor(CCursor::new(col)).left();
            // A column of the text: those after the caret sit past the composed text.
            let x_of = |col: usize| x_at(if col > caret_col { col + extra } else { col });
            // The part of a range on this row (past the line's end, the line ending too).
            let span = |r: &Range<usize>, fill: egui::Color32| {
                if r.start > start + len || r.end <= start {
                    return;
                }
                let a = x_of(r.start.clamp(start, start + len) - start);
                let b = x_of(r.end.clamp(start, start + len) - start);
                let b = if r.end > start + len { b + 6.0 } else { b };
                if b > a {
                    painter.rect_filled(band(a, b), 1.0, fill);
                }
            };
            if row == caret_line && rows.focused {
                let line = band(rows.rect.left(), rows.rect.right());
                painter.rect_filled(line, 0.0, ui.visuals().faint_bg_color);
            }
            span(&selection, sel_fill);
            for m in &marks {
                span(m, mark_fill);
            }
            painter.galley(origin, galley.clone(), palette::TEXT);
            // The line number, coloured (and marked) by the line's worst diagnostic.
            let number = u32::try_from(row + 1).unwrap_or(u32::MAX);
            let worst = on_rows.iter().filter(|p| p.line == number);
            let worst = worst.map(|p| p.severity).max();
            let (digits, mark) = (rows.digits, if worst.is_some() { '●' } else { ' ' });
            painter.text(
                egui::pos2(rows.rect.left(), top),
                egui::Align2::LEFT_TOP,
                format!("{mark}{number:>digits$}"),
                rows.font.clone(),
                worst.map_or(palette::NUMBER, severity_color),
            );
            for p in on_rows.iter().filter(|p| p.line == number) {
                let from = p.chars.start.clamp(start, start + len) - start;
                let to = p.chars.end.clamp(start, start + len) - start;
                let end = if to > from {
                    x_of(to)
                } else {
                    x_of(from) + 8.0
                };
                squiggle(painter, x_of(from), end, bottom - 1.0, p.severity);
            }
            if let Some(p) = preedit {
                // The composed text underlined, the part being converted more heavily.
                let color = ui.visuals().text_color();
                let underline = |from: usize, to: usize, width: f32| {
                    let (a, b) = (x_at(caret_col + from), x_at(caret_col + to));
                    let y = bottom - 1.0;
                    painter.line_segment([egui::pos2(a, y), egui::pos2(b, y)], (width, color));
                };
                underline(0, extra, 1.0);
                if let Some(active) = p.active.as_ref().filter(|a| a.end > a.start) {
                    underline(active.start.min(extra), active.end.min(extra), 2.0);
                }
            }
            if row == caret_line && rows.focused {
                // The caret: after the composed text (or its active part) while composing.
                let composed = preedit.map_or(0, |p| p.active.as_ref().map_or(extra, |a| a.end));
                let x = x_at(caret_col + composed.min(extra));
                self.caret_rect = Some(band(x, x + 1.0));
                painter.line_segment(
                    [egui::pos2(x, top), egui::pos2(x, bottom)],
                    Stroke::new(2.0, ui.visuals().text_cursor.stroke.color),
                );
                if rows.reveal {
                    // Near the line's start the gutter comes into view with it.
                    let from = Some(x - 24.0).filter(|from| *from >= rows.text_left);
                    ui.scroll_to_rect(band(from.unwrap_or(rows.rect.left()), x + 24.0), None);
                }
            }
        }
    }
}

/// Where and how the visible rows are painted.
struct Rows<'a> {
    rect: Rect,
    rows: Range<usize>,
    row_height: f32,
    text_left: f32,
    digits: usize,
    font: &'a FontId,
    dialect: Dialect,
    problems: &'a [Problem],
    highlights: &'a [Range<usize>],
    focused: bool,
    /// Scroll the caret into view across.
    reveal: bool,
}

/// The problems on 0-based `rows` (problems are sorted by line).
fn problems_on_rows(problems: &[Problem], rows: Range<usize>) -> &[Problem] {
    let first = u32::try_from(rows.start + 1).unwrap_or(u32::MAX);
    let last = u32::try_from(rows.end).unwrap_or(u32::MAX);
    let from = problems.partition_point(|p| p.line < first);
    let to = problems.partition_point(|p| p.line <= last);
    problems.get(from..to.max(from)).unwrap_or_default()
}

/// The next word boundary after `from` (`forward`) or before it, within `from`'s line.
fn word_boundary(text: &Buffer, from: usize, forward: bool) -> usize {
    let line = text.char_to_line(from);
    let start = text.line_to_char(line);
    let end = start + text.line_len_chars(line);
    let chars: Vec<char> = text.slice(start..end).chars().collect();
    let mut i = from.clamp(start, end) - start;
    match forward {
        true if i == chars.len() => return (end + 1).min(text.len_chars()),
        false if i == 0 => return start.saturating_sub(1),
        _ => {}
    }
    // The character the caret passes next (none at the line's ends).
    let at = |i: usize| if forward { i } else { i.wrapping_sub(1) };
    let next = |i: usize| chars.get(at(i)).copied();
    // Past any spaces, then past the word (an address word such as `X-12.5`, a name, a number).
    let is_word = |c: char| c.is_alphanumeric() || "_.#".contains(c);
    for word in [false, true] {
        while next(i).is_some_and(|c| is_word(c) == word) {
            i = if forward { i + 1 } else { i - 1 };
        }
    }
    start + i
}
