//! The code editor: G-code highlighting, hover help and diagnostic underlines, over the row
//! editor ([`RowEditor`]) that edits every program.

use egui::text::LayoutJob;
use egui::{Color32, FontId, Stroke, TextFormat, Ui};
use swarf_syntax::{Dialect, Severity};

use crate::analysis::Problem;
use crate::buffer::Buffer;
use crate::commands::{self, Completion};
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

/// The G-code editor widget's state (the text itself is owned by the caller). Every program,
/// short or a million lines long, is edited by the same [`RowEditor`], which lays out only the
/// rows on screen.
#[derive(Debug, Clone)]
pub struct CodeEditor {
    id: egui::Id,
    /// A selection to show next frame, and whether the editor takes the keyboard with it.
    jump: Option<(std::ops::Range<usize>, bool)>,
    /// Character ranges marked in the text (the find bar's matches).
    highlights: Vec<std::ops::Range<usize>>,
    /// The caret, selection, view and completion list.
    rows: RowEditor,
}

impl Default for CodeEditor {
    fn default() -> Self {
        CodeEditor {
            id: egui::Id::unique("swarf-code-editor"),
            jump: None,
            highlights: Vec::new(),
            rows: RowEditor::default(),
        }
    }
}

impl CodeEditor {
    /// Selects the character range on the next frame, scrolls to it and gives the editor the
    /// keyboard.
    pub fn jump_to(&mut self, chars: std::ops::Range<usize>) {
        self.jump = Some((chars, true));
    }

    /// Selects the character range on the next frame and scrolls to it, leaving the keyboard
    /// where it is (the find bar's field keeps it while it steps through the matches).
    pub fn show_range(&mut self, chars: std::ops::Range<usize>) {
        self.jump = Some((chars, false));
    }

    /// Marks these character ranges in the text (at most [`HIGHLIGHTS_SHOWN`] are drawn).
    pub fn set_highlights(&mut self, ranges: &[std::ops::Range<usize>]) {
        if self.highlights != ranges {
            self.highlights = ranges.iter().take(HIGHLIGHTS_SHOWN).cloned().collect();
        }
    }

    /// The editor's widget id (for focus checks).
    pub fn id(&self) -> egui::Id {
        self.id
    }

    /// The completions on offer (code and meaning), while the popup is open.
    pub fn completions(&self) -> Option<&[Completion]> {
        self.rows.completions()
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
        let input = RowInput {
            id: self.id,
            label,
            dialect,
            problems,
            highlights: &self.highlights,
            jump: self.jump.take(),
            font,
        };
        self.rows.show(ui, text, input)
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
