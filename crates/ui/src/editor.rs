//! What the code editor ([`crate::rows::CodeEditor`]) draws: highlighting, hover help, squiggles.

use egui::text::LayoutJob;
use egui::{Color32, FontId, Stroke, TextFormat};
use swarf_syntax::{Dialect, Severity};

use crate::analysis::Problem;
use crate::commands;
use crate::i18n::trf;

/// Colours of the token classes (and of line numbers), for a dark background.
pub(crate) mod palette {
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
    let bytes = text.as_bytes();
    let mut i = 0;
    let append = |job: &mut LayoutJob, from: usize, to: usize, color: Color32| {
        if let Some(s) = text.get(from..to) {
            job.append(s, 0.0, TextFormat::simple(font.clone(), color));
        }
    };
    // Past `close` from `i` on (before a line break, which it never goes past).
    let past = |i: usize, close: u8| {
        let end = memchr::memchr2(close, b'\n', &bytes[i..]).map_or(bytes.len(), |j| i + j);
        end + usize::from(close != b'\n' && bytes.get(end) == Some(&close))
    };
    // Past the bytes from `from` on that `f` accepts.
    let run =
        |from: usize, f: fn(&u8) -> bool| from + bytes[from..].iter().take_while(|b| f(b)).count();
    let syntec = dialect == Dialect::Syntec;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        let color = match c {
            b'(' | b';' | b'/'
                if c == b'('
                    || (c == b';' && dialect.semicolon_is_comment())
                    || (c == b'/' && syntec && bytes.get(i + 1) == Some(&b'/')) =>
            {
                i = past(i, if c == b'(' { b')' } else { b'\n' });
                palette::COMMENT
            }
            b'#' => {
                // A variable: `#12`, `#<name>` (the index of `#[…]` is coloured as it comes).
                i += 1;
                if bytes.get(i) == Some(&b'<') {
                    i = past(i, b'>');
                } else {
                    i = run(i, u8::is_ascii_digit);
                }
                palette::VARIABLE
            }
            c if c.is_ascii_alphabetic()
                && bytes.get(i + 1).is_some_and(u8::is_ascii_alphabetic) =>
            {
                // A run of letters: a macro keyword, operator or function (IF, GOTO, SIN …).
                i = run(i, u8::is_ascii_alphabetic);
                palette::KEYWORD
            }
            c if c.is_ascii_alphabetic() => {
                i += 1;
                while i < bytes.len() && (bytes[i].is_ascii_digit() || b".+- ".contains(&bytes[i]))
                {
                    // Stop before the spaces that separate words.
                    let next = bytes.get(i + 1);
                    if bytes[i] == b' ' && !next.is_some_and(|n| n.is_ascii_digit() || *n == b'.') {
                        break;
                    }
                    i += 1;
                }
                match c.to_ascii_uppercase() {
                    b'G' => palette::G_CODE,
                    b'M' => palette::M_CODE,
                    u if b"XYZABCIJKR".contains(&u) => palette::AXIS,
                    b'F' | b'S' => palette::FEED,
                    b'T' | b'D' | b'H' => palette::TOOL,
                    b'N' | b'O' => palette::NUMBER,
                    _ => palette::TEXT,
                }
            }
            _ => {
                // Any other run up to the next interesting character (ASCII: a byte of its own).
                i = run(i + 1, |b| !b.is_ascii_alphabetic() && !b"(;/#".contains(b));
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
    /// The selection in characters (start ≤ end).
    pub selection: std::ops::Range<usize>,
}

/// Most find matches marked in the text at once.
pub const HIGHLIGHTS_SHOWN: usize = 5000;

/// The tooltip of the gutter marker on 1-based `line`: each diagnostic there with its code,
/// and the alarm the control's manual names for it.
pub fn gutter_tooltip(problems: &[Problem], line: u32) -> Option<String> {
    let lines: Vec<String> = problems
        .iter()
        .filter(|p| p.line == line)
        .map(|p| {
            let alarm = commands::alarm_in(&p.message);
            let alarm = alarm.map(|a| trf("Control alarm: {}", &[&a]));
            let alarm = alarm.map_or(String::new(), |a| format!("\n{a}"));
            format!("{} [{}]: {}{alarm}", p.severity.as_str(), p.code, p.message)
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
    let byte = commands::byte_of_char(text, at);
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
        let gm = letter == b'G' || letter == b'M';
        let number = value.parse::<f64>().ok().filter(|_| gm);
        let code = number.and_then(|v| swarf_syntax::Code::from_value(letter, v));
        let address = swarf_syntax::codes::address(dialect, letter).next();
        let address = address.filter(|_| !value.is_empty());
        let label = dialect.label();
        match code.map(|code| (code, swarf_syntax::codes::lookup(dialect, code))) {
            Some((_, Some(d))) => lines.push(format!(
                "{} — {}\n{}\n{}",
                d.code, d.name, d.format, d.summary
            )),
            Some((code, None)) => lines.push(trf("{} is not a code of {}", &[&code, &label])),
            None => lines.extend(address.map(|a| format!("{}: {}", char::from(letter), a.meaning))),
        }
    }
    (!lines.is_empty()).then(|| lines.join("\n\n"))
}

/// Keeps the arrow keys (and Tab, Escape, when asked) with the focused widget `id` next frame.
pub(crate) fn keep_keys(ui: &egui::Ui, id: egui::Id, tab: bool, escape: bool) {
    let filter = egui::EventFilter {
        tab,
        horizontal_arrows: true,
        vertical_arrows: true,
        escape,
    };
    ui.memory_mut(|m| m.set_focus_lock_filter(id, filter));
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
