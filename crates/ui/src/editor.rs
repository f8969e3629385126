//! The code editor: G-code highlighting, a line-number gutter and diagnostic underlines.

use std::sync::Arc;

use egui::text::{CCursor, CCursorRange, LayoutJob};
use egui::{Color32, FontId, Galley, Pos2, Stroke, TextFormat, Ui};
use swarf_syntax::{Dialect, Severity};

use crate::analysis::Problem;
use crate::buffer::Buffer;
use crate::commands::{self, Completion};
use crate::completion::{Popup, PopupKey};
use crate::rows::{RowEditor, RowInput};

/// Colours of the token classes, for a dark background.
mod palette {
    use egui::Color32;
    pub const TEXT: Color32 = Color32::from_rgb(220, 220, 220);
    pub const G_CODE: Color32 = Color32::from_rgb(110, 170, 255);
    pub const M_CODE: Color32 = Color32::from_rgb(200, 140, 255);
    pub const AXIS: Color32 = Color32::from_rgb(230, 230, 230);
    pub const FEED: Color32 = Color32::from_rgb(255, 190, 90);
    pub const NUMBER: Color32 = Color32::from_rgb(120, 120, 120);
    pub const COMMENT: Color32 = Color32::from_rgb(110, 170, 110);
    pub const TOOL: Color32 = Color32::from_rgb(255, 120, 120);
    pub const ERROR: Color32 = Color32::from_rgb(255, 80, 80);
    pub const WARNING: Color32 = Color32::from_rgb(240, 200, 60);
    pub const NOTE: Color32 = Color32::from_rgb(120, 180, 255);
    pub const KEYWORD: Color32 = Color32::from_rgb(230, 120, 200);
    pub const VARIABLE: Color32 = Color32::from_rgb(100, 210, 210);
}

/// The colour of plain text.
pub(crate) const TEXT_COLOR: Color32 = palette::TEXT;
/// The colour of line numbers.
pub(crate) const NUMBER_COLOR: Color32 = palette::NUMBER;

/// The colour a diagnostic of `severity` is drawn in.
pub fn severity_color(severity: Severity) -> Color32 {
    match severity {
        Severity::Error => palette::ERROR,
        Severity::Warning => palette::WARNING,
        Severity::Note => palette::NOTE,
    }
}

/// Lays out `text` with G-code highlighting for `dialect`.
pub fn highlight(text: &str, dialect: Dialect, font: &FontId) -> LayoutJob {
    let mut job = LayoutJob::default();
    let fmt = |color: Color32| TextFormat::simple(font.clone(), color);
    let bytes = text.as_bytes();
    let mut i = 0;
    let append = |job: &mut LayoutJob, from: usize, to: usize, color: Color32| {
        if let Some(s) = text.get(from..to) {
            job.append(s, 0.0, fmt(color));
        }
    };
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        let color = match c {
            b'(' => {
                i = text[i..].find([')', '\n']).map_or(bytes.len(), |j| {
                    if bytes[i + j] == b')' {
                        i + j + 1
                    } else {
                        i + j
                    }
                });
                palette::COMMENT
            }
            b';' if dialect.semicolon_is_comment() => {
                i = text[i..].find('\n').map_or(bytes.len(), |j| i + j);
                palette::COMMENT
            }
            b'/' if dialect == Dialect::Syntec && bytes.get(i + 1) == Some(&b'/') => {
                i = text[i..].find('\n').map_or(bytes.len(), |j| i + j);
                palette::COMMENT
            }
            b'#' => {
                // A variable: `#12`, `#<name>` (the index of `#[…]` is coloured as it comes).
                i += 1;
                if bytes.get(i) == Some(&b'<') {
                    i = text[i..].find(['>', '\n']).map_or(bytes.len(), |j| {
                        if bytes[i + j] == b'>' {
                            i + j + 1
                        } else {
                            i + j
                        }
                    });
                } else {
                    while i < bytes.len() && bytes[i].is_ascii_digit() {
                        i += 1;
                    }
                }
                palette::VARIABLE
            }
            c if c.is_ascii_alphabetic()
                && bytes.get(i + 1).is_some_and(u8::is_ascii_alphabetic) =>
            {
                // A run of letters: a macro keyword, operator or function (IF, GOTO, WHILE,
                // DO, END, EQ, AND, SIN, sub, call …).
                while i < bytes.len() && bytes[i].is_ascii_alphabetic() {
                    i += 1;
                }
                palette::KEYWORD
            }
            c if c.is_ascii_alphabetic() => {
                i += 1;
                while i < bytes.len() && (bytes[i].is_ascii_digit() || b".+- ".contains(&bytes[i]))
                {
                    // Stop before the spaces that separate words.
                    if bytes[i] == b' '
                        && !bytes
                            .get(i + 1)
                            .is_some_and(|n| n.is_ascii_digit() || *n == b'.')
                    {
                        break;
                    }
                    i += 1;
                }
                match c.to_ascii_uppercase() {
                    b'G' => palette::G_CODE,
                    b'M' => palette::M_CODE,
                    b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'I' | b'J' | b'K' | b'R' => {
                        palette::AXIS
                    }
                    b'F' | b'S' => palette::FEED,
                    b'T' | b'D' | b'H' => palette::TOOL,
                    b'N' | b'O' => palette::NUMBER,
                    _ => palette::TEXT,
                }
            }
            _ => {
                // Any other run of characters up to the next interesting one.
                let len = text[i..].chars().next().map_or(1, char::len_utf8);
                i += len;
                while i < bytes.len()
                    && !bytes[i].is_ascii_alphabetic()
                    && !b"(;/#".contains(&bytes[i])
                {
                    i += text[i..].chars().next().map_or(1, char::len_utf8);
                }
                palette::TEXT
            }
        };
        append(&mut job, start, i, color);
    }
    job
}

/// What happened in the editor this frame.
#[derive(Debug, Clone, Default)]
pub struct EditorOutput {
    /// The text was edited by typing.
    pub changed: bool,
    /// The text was changed by accepting a completion (an undo step of its own).
    pub completed: bool,
    /// The edit ended a line (a typed line break), which closes a run of typing for undo.
    pub ends_line: bool,
    /// 1-based line of the cursor, when the editor has one.
    pub cursor_line: Option<u32>,
    /// The selection in characters (start ≤ end), when the editor has one.
    pub selection: Option<std::ops::Range<usize>>,
}

/// Most find matches marked in the text at once.
pub const HIGHLIGHTS_SHOWN: usize = 5000;

/// The G-code editor widget's state (the text itself is owned by the caller).
#[derive(Debug, Clone)]
pub struct CodeEditor {
    id: egui::Id,
    jump: Option<std::ops::Range<usize>>,
    popup: Option<Popup>,
    /// The list's top-left corner: under the caret.
    popup_pos: Pos2,
    /// Character ranges marked in the text (the find bar's matches).
    highlights: Vec<std::ops::Range<usize>>,
    /// The caret and view of a text edited row by row (see [`LARGE_TEXT_BYTES`]).
    rows: RowEditor,
}

/// Texts longer than this are edited by the row editor ([`RowEditor`]), which lays out only the
/// rows on screen: egui's text editor lays out (and keeps) the whole text every frame, which a
/// million-line program does not fit in a frame or in a browser tab's memory.
pub const LARGE_TEXT_BYTES: usize = 2 << 20;

impl Default for CodeEditor {
    fn default() -> Self {
        Self::new("swarf-code-editor")
    }
}

impl CodeEditor {
    /// An editor whose state is stored under `id_salt`.
    pub fn new(id_salt: &str) -> Self {
        CodeEditor {
            id: egui::Id::unique(id_salt),
            jump: None,
            popup: None,
            popup_pos: Pos2::ZERO,
            highlights: Vec::new(),
            rows: RowEditor::default(),
        }
    }

    /// Selects the character range on the next frame and scrolls to it.
    pub fn jump_to(&mut self, chars: std::ops::Range<usize>) {
        self.jump = Some(chars);
    }

    /// Marks these character ranges in the text (at most [`HIGHLIGHTS_SHOWN`] are drawn).
    pub fn set_highlights(&mut self, ranges: &[std::ops::Range<usize>]) {
        if self.highlights != ranges {
            self.highlights = ranges.iter().take(HIGHLIGHTS_SHOWN).cloned().collect();
        }
    }

    /// The text edit's widget id (for focus checks).
    pub fn id(&self) -> egui::Id {
        self.id
    }

    /// Whether the text has keyboard focus.
    pub fn has_focus(&self, ctx: &egui::Context) -> bool {
        ctx.memory(|m| m.has_focus(self.id))
    }

    /// The completions on offer (code and meaning), while the popup is open.
    pub fn completions(&self) -> Option<&[Completion]> {
        self.popup
            .as_ref()
            .map(|p| p.items.as_slice())
            .or_else(|| self.rows.completions())
    }

    /// Closes the completion popup.
    pub fn close_completions(&mut self) {
        self.popup = None;
        self.rows.close_completions();
    }

    /// Shows the editor with a gutter, filling the available space; `label` is the widget that
    /// names it for screen readers.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        label: egui::Id,
        text: &mut Buffer,
        dialect: Dialect,
        problems: &[Problem],
    ) -> EditorOutput {
        let font = egui::TextStyle::Monospace.resolve(ui.style());
        if text.len_bytes() > LARGE_TEXT_BYTES {
            self.popup = None;
            let input = RowInput {
                id: self.id,
                label,
                dialect,
                problems,
                highlights: &self.highlights,
                jump: self.jump.take(),
                font,
            };
            return self.rows.show(ui, text, input);
        }
        let mut output = EditorOutput::default();
        let focused = self.has_focus(ui.ctx());
        if focused && let Some(popup) = self.popup.as_mut() {
            match popup.keys(ui.ctx()) {
                PopupKey::None => {}
                PopupKey::Close => self.popup = None,
                PopupKey::Accept(i) => self.accept(text, i, &mut output),
            }
        }
        // Ctrl+Space asks for the list where the cursor is.
        let ask =
            focused && ui.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, egui::Key::Space));
        if let Some(range) = self.jump.take() {
            // Before the first frame there is no state yet: make one, so a program opened at
            // start-up shows its first line rather than the text edit's default (the end).
            let mut state = egui::TextEdit::load_state(ui.ctx(), self.id).unwrap_or_default();
            state.cursor.set_char_range(Some(CCursorRange::two(
                CCursor::new(range.start),
                CCursor::new(range.end),
            )));
            state.store(ui.ctx(), self.id);
            ui.ctx().memory_mut(|m| m.request_focus(self.id));
        }
        egui::ScrollArea::both()
            .id_salt("swarf-editor-scroll")
            .auto_shrink([false, false])
            .show(ui, |ui| {
                ui.horizontal_top(|ui| {
                    let lines = text.len_lines();
                    gutter(ui, lines, problems, &font);
                    let font_for_layout = font.clone();
                    let mut layouter = |ui: &Ui, buf: &dyn egui::TextBuffer, _wrap: f32| {
                        let job = highlight(buf.as_str(), dialect, &font_for_layout);
                        ui.painter().layout_job(job)
                    };
                    let edit = egui::TextEdit::multiline(text)
                        .id(self.id)
                        .font(font.clone())
                        .code_editor()
                        // Tab indents; Escape closes the completion list rather than leaving.
                        .event_filter(egui::EventFilter {
                            tab: true,
                            horizontal_arrows: true,
                            vertical_arrows: true,
                            escape: self.popup.is_some(),
                        })
                        .desired_width(f32::INFINITY)
                        .desired_rows(40)
                        .layouter(&mut layouter)
                        .show(ui);
                    let response = edit.response.response.clone().labelled_by(label);
                    output.changed = response.changed();
                    output.cursor_line = edit
                        .cursor_range
                        .map(|r| edit.galley.pos_from_cursor(r.primary))
                        .map(|rect| {
                            let row = (rect.top() / font_row_height(ui, &font)).round();
                            row.max(0.0) as u32 + 1
                        });
                    output.selection = edit.cursor_range.map(|r| {
                        let (a, b) = (r.primary.index.0, r.secondary.index.0);
                        a.min(b)..a.max(b)
                    });
                    let cursor_char = edit.cursor_range.map(|r| r.primary.index.0);
                    let popup_here = |text: &Buffer| {
                        cursor_char.and_then(|c| {
                            Popup::at(text, commands::byte_of_char(text, c), c, dialect)
                        })
                    };
                    if ask && !output.changed {
                        self.popup = popup_here(text);
                    } else if output.changed {
                        output.ends_line = cursor_char
                            .map(|c| commands::byte_of_char(text, c))
                            .and_then(|b| text.get(..b))
                            .is_some_and(|t| t.ends_with('\n'));
                        self.popup = popup_here(text);
                    } else if let Some(p) = &self.popup {
                        // The cursor moved away, or the keyboard went elsewhere (a click on the
                        // list itself takes the focus for a moment, so the pointer keeps it).
                        let moved = cursor_char.is_some_and(|c| c != p.chars.end);
                        if moved || (!response.has_focus() && !p.pointer_over(ui.ctx())) {
                            self.popup = None;
                        }
                    }
                    paint_squiggles(ui, &edit.galley, edit.galley_pos, problems);
                    paint_highlights(ui, &edit.galley, edit.galley_pos, &self.highlights);
                    // Hover help: the diagnostics there and what the code under the pointer is.
                    if let Some(pos) = response.hover_pos() {
                        let at = edit.galley.cursor_from_pos(pos - edit.galley_pos);
                        if let Some(help) = hover_text(text, dialect, at.index.0, problems) {
                            response.on_hover_text_at_pointer(help);
                        }
                    }
                    // Under the caret; where it was while a click on the list has the focus.
                    if let Some(r) = edit.cursor_range {
                        let caret = edit.galley.pos_from_cursor(r.primary);
                        self.popup_pos = edit.galley_pos + caret.left_bottom().to_vec2();
                    }
                    let at = self.popup_pos;
                    self.show_popup(ui, at, text, &mut output);
                });
            });
        output
    }

    /// Replaces the typed prefix with completion `index` and puts the cursor after it.
    fn accept(&mut self, text: &mut Buffer, index: usize, output: &mut EditorOutput) {
        let Some(end) = self.popup.take().and_then(|p| p.accept(index, text)) else {
            return;
        };
        self.jump = Some(end..end);
        output.completed = true;
    }

    fn show_popup(&mut self, ui: &Ui, at: Pos2, text: &mut Buffer, output: &mut EditorOutput) {
        let Some(popup) = self.popup.as_mut() else {
            return;
        };
        if let Some(i) = popup.show(ui.ctx(), self.id, at) {
            self.accept(text, i, output);
        }
    }
}

/// The tooltip of the gutter marker on 1-based `line`: each diagnostic there with its code,
/// and the alarm the control's manual names for it.
pub fn gutter_tooltip(problems: &[Problem], line: u32) -> Option<String> {
    let lines: Vec<String> = problems
        .iter()
        .filter(|p| p.line == line)
        .map(|p| {
            let mut s = format!("{} [{}]: {}", p.severity.as_str(), p.code, p.message);
            if let Some(alarm) = commands::alarm_in(&p.message) {
                s.push_str(&format!(
                    "\n{}",
                    crate::i18n::trf("Control alarm: {}", &[&alarm])
                ));
            }
            s
        })
        .collect();
    (!lines.is_empty()).then(|| lines.join("\n\n"))
}

/// What hovering at character `at` of `text` explains: the diagnostics covering it, and the G or
/// M code (or address letter) there, from the dialect's code table.
pub fn hover_text(text: &str, dialect: Dialect, at: usize, problems: &[Problem]) -> Option<String> {
    let mut lines: Vec<String> = problems
        .iter()
        .filter(|p| p.chars.start <= at && at < p.chars.end.max(p.chars.start + 1))
        .map(|p| format!("{} [{}]: {}", p.severity.as_str(), p.code, p.message))
        .collect();
    let byte = text.char_indices().nth(at).map_or(text.len(), |(b, _)| b);
    let bytes = text.as_bytes();
    // Back to the word's letter: over the digits, point and sign of its value.
    let mut start = byte.min(bytes.len());
    while start > 0 && (bytes[start - 1].is_ascii_digit() || b".+-".contains(&bytes[start - 1])) {
        start -= 1;
    }
    if start > 0 && !bytes.get(start).is_some_and(u8::is_ascii_alphabetic) {
        start -= 1;
    }
    if let Some(&letter) = bytes.get(start).filter(|b| b.is_ascii_alphabetic()) {
        let letter = letter.to_ascii_uppercase();
        let value: String = text[start + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        let code = value
            .parse::<f64>()
            .ok()
            .and_then(|v| swarf_syntax::Code::from_value(letter, v))
            .filter(|_| letter == b'G' || letter == b'M');
        match code {
            Some(code) => match swarf_syntax::codes::lookup(dialect, code) {
                Some(def) => lines.push(format!(
                    "{} — {}\n{}\n{}",
                    def.code, def.name, def.format, def.summary
                )),
                None => lines.push(crate::i18n::trf(
                    "{} is not a code of {}",
                    &[&code, &dialect.label()],
                )),
            },
            None if !value.is_empty() => {
                if let Some(a) = swarf_syntax::codes::address(dialect, letter).next() {
                    lines.push(format!("{}: {}", char::from(letter), a.meaning));
                }
            }
            None => {}
        }
    }
    (!lines.is_empty()).then(|| lines.join("\n\n"))
}

fn font_row_height(ui: &Ui, font: &FontId) -> f32 {
    ui.ctx().fonts_mut(|f| f.row_height(font)).max(1.0)
}

/// Line numbers, coloured by the worst diagnostic on each line.
fn gutter(ui: &mut Ui, lines: usize, problems: &[Problem], font: &FontId) {
    let mut worst: Vec<Option<Severity>> = vec![None; lines];
    for p in problems {
        if let Some(slot) = worst.get_mut((p.line as usize).saturating_sub(1)) {
            *slot = Some(slot.map_or(p.severity, |s| s.max(p.severity)));
        }
    }
    let digits = lines.to_string().len().max(3);
    let mut job = LayoutJob::default();
    for (i, w) in worst.iter().enumerate() {
        let color = w.map_or(palette::NUMBER, severity_color);
        let mark = if w.is_some() { '●' } else { ' ' };
        job.append(
            &format!("{mark}{:>digits$}\n", i + 1),
            0.0,
            TextFormat::simple(font.clone(), color),
        );
    }
    let galley = ui.painter().layout_job(job);
    // Align with the text edit's inner margin.
    ui.add_space(0.0);
    let (rect, response) = ui.allocate_exact_size(
        egui::vec2(galley.size().x + 6.0, galley.size().y + 4.0),
        egui::Sense::hover(),
    );
    ui.painter()
        .galley(rect.min + egui::vec2(0.0, 2.0), galley, palette::NUMBER);
    // A marker's tooltip: what is wrong on that line.
    if let Some(pos) = response.hover_pos() {
        let row = ((pos.y - rect.top() - 2.0) / font_row_height(ui, font)).floor();
        let line = row.max(0.0) as u32 + 1;
        if let Some(tip) = gutter_tooltip(problems, line) {
            response.on_hover_text_at_pointer(tip);
        }
    }
}

/// A translucent box over each highlighted range (one per row it spans).
fn paint_highlights(
    ui: &Ui,
    galley: &Arc<Galley>,
    origin: Pos2,
    ranges: &[std::ops::Range<usize>],
) {
    let fill = Color32::from_rgba_unmultiplied(255, 210, 80, 70);
    let clip = ui.clip_rect();
    for r in ranges {
        let start = galley.pos_from_cursor(CCursor::new(r.start));
        let end = galley.pos_from_cursor(CCursor::new(r.end));
        if (end.top() - start.top()).abs() < 1.0 {
            let rect = egui::Rect::from_min_max(
                origin + start.left_top().to_vec2(),
                origin + end.right_bottom().to_vec2(),
            );
            if rect.intersects(clip) {
                ui.painter().rect_filled(rect, 2.0, fill);
            }
        }
    }
}

/// Wavy underlines under each diagnostic's characters.
fn paint_squiggles(ui: &Ui, galley: &Arc<Galley>, origin: Pos2, problems: &[Problem]) {
    let painter = ui.painter();
    for p in problems {
        let start = galley.pos_from_cursor(CCursor::new(p.chars.start));
        let end = galley.pos_from_cursor(CCursor::new(p.chars.end));
        let y = origin.y + start.bottom() - 1.0;
        let x0 = origin.x + start.left();
        let same_row = (end.top() - start.top()).abs() < 1.0;
        let x1 = if same_row && end.left() > start.left() {
            origin.x + end.left()
        } else {
            x0 + 8.0
        };
        squiggle(painter, x0, x1, y, p.severity);
    }
}

/// A wavy underline from `x0` to `x1` at height `y`.
pub(crate) fn squiggle(painter: &egui::Painter, x0: f32, x1: f32, y: f32, severity: Severity) {
    let stroke = Stroke::new(1.2, severity_color(severity));
    let mut points = Vec::new();
    let mut x = x0;
    let mut up = true;
    while x <= x1 + 0.01 {
        points.push(egui::pos2(x, if up { y - 1.5 } else { y + 1.0 }));
        up = !up;
        x += 2.5;
    }
    if points.len() >= 2 {
        painter.add(egui::Shape::line(points, stroke));
    }
}
