//! The G/M code completion popup shared by both editors (egui's `TextEdit` for smaller programs,
//! the row editor for large ones): when it opens, the keys that drive it, and the list itself.

use std::ops::Range;

use egui::{Key, Modifiers, Pos2, Rect};
use swarf_syntax::Dialect;

use crate::buffer::Buffer;
use crate::commands::{self, Completion};

/// Most completions listed at once.
const COMPLETIONS_SHOWN: usize = 12;

/// The completion popup: the word being typed and the codes it can become.
#[derive(Debug, Clone)]
pub(crate) struct Popup {
    /// Character range of the typed prefix (`G8`) in the text.
    pub chars: Range<usize>,
    /// The codes on offer.
    pub items: Vec<Completion>,
    /// The highlighted item.
    pub selected: usize,
    /// Where the list was drawn last frame.
    rect: Option<Rect>,
}

/// What the popup's keys asked for this frame.
pub(crate) enum PopupKey {
    /// Nothing for the text (no key, or a move through the list).
    None,
    /// Take this item.
    Accept(usize),
    /// Close the list.
    Close,
}

impl Popup {
    /// The popup for the G or M code prefix ending at byte `caret_byte` of `text` (which is
    /// also character `caret_char` of the whole program), if it has matches. `text` may be the
    /// whole program or only the caret's line.
    pub fn at(text: &str, caret_byte: usize, caret_char: usize, dialect: Dialect) -> Option<Popup> {
        let (range, prefix) = commands::completion_prefix(text, caret_byte)?;
        let items = commands::completions(dialect, &prefix, COMPLETIONS_SHOWN);
        // A code typed in full with nothing longer to offer needs no list.
        let exact = items.len() == 1 && items[0].code.eq_ignore_ascii_case(&prefix);
        // The prefix is ASCII: as many characters as bytes.
        let start = caret_char.checked_sub(range.len())?;
        (!items.is_empty() && !exact).then_some(Popup {
            chars: start..caret_char,
            items,
            selected: 0,
            rect: None,
        })
    }

    /// Up/Down choose a completion, Tab or Enter takes it, Escape closes the list; the keys are
    /// taken before the editor sees them.
    pub fn keys(&mut self, ctx: &egui::Context) -> PopupKey {
        let none = Modifiers::NONE;
        let (down, up, accept, close) = ctx.input_mut(|i| {
            (
                i.consume_key(none, Key::ArrowDown),
                i.consume_key(none, Key::ArrowUp),
                i.consume_key(none, Key::Tab) || i.consume_key(none, Key::Enter),
                i.consume_key(none, Key::Escape),
            )
        });
        let n = self.items.len().max(1);
        if down {
            self.selected = (self.selected + 1) % n;
        }
        if up {
            self.selected = (self.selected + n - 1) % n;
        }
        if close {
            PopupKey::Close
        } else if accept {
            PopupKey::Accept(self.selected)
        } else {
            PopupKey::None
        }
    }

    /// Whether the pointer is over the list (a click on it takes the keyboard focus for a
    /// moment, so the pointer keeps the list open).
    pub fn pointer_over(&self, ctx: &egui::Context) -> bool {
        ctx.pointer_hover_pos()
            .is_some_and(|pos| self.rect.is_some_and(|r| r.expand(4.0).contains(pos)))
    }

    /// Draws the list with its top-left corner at `at`; the item clicked, if any.
    pub fn show(&mut self, ctx: &egui::Context, id: egui::Id, at: Pos2) -> Option<usize> {
        let mut clicked = None;
        let area = egui::Area::new(id.with("completions"))
            .order(egui::Order::Foreground)
            .fixed_pos(at)
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    for (i, item) in self.items.iter().enumerate() {
                        let row = egui::RichText::new(format!("{}  {}", item.code, item.name))
                            .monospace();
                        if ui.selectable_label(i == self.selected, row).clicked() {
                            clicked = Some(i);
                        }
                    }
                });
            });
        self.rect = Some(area.response.rect);
        clicked
    }

    /// Replaces the typed prefix in `text` with item `index`; the character just after the
    /// inserted code, or `None` (nothing changed) when the prefix no longer lies in the text.
    pub fn accept(&self, index: usize, text: &mut Buffer) -> Option<usize> {
        let code = self.items.get(index)?;
        (self.chars.end <= text.len_chars()).then(|| text.replace(self.chars.clone(), &code.code))
    }
}
