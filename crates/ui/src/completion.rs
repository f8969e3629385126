//! The editor's G/M code completion popup. It never puts in a code the user did not choose: Tab
//! takes the highlighted code, Enter only one an arrow key picked (else it ends the line), and
//! only where the text still holds the prefix the list was made for.

use std::ops::Range;

use egui::{Key, Pos2, Rect};
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
    /// The typed prefix, as the text held it when the list was made.
    prefix: String,
    /// An arrow key picked the highlighted item, so Enter takes it.
    chosen: bool,
    /// The codes on offer.
    pub items: Vec<Completion>,
    /// The highlighted item.
    pub selected: usize,
    /// Where the list was drawn last frame.
    rect: Option<Rect>,
}

/// What a key does to the open popup.
pub(crate) enum PopupKey {
    /// Not the popup's key: the editor handles it.
    None,
    /// A move through the list.
    Handled,
    /// Take this item.
    Accept(usize),
    /// Close the list.
    Close,
}

impl Popup {
    /// The popup for the G or M code prefix ending at byte `caret_byte` of `text` (the program or
    /// the caret's line), which is character `caret_char` of the program, if it has matches.
    pub fn at(text: &str, caret_byte: usize, caret_char: usize, dialect: Dialect) -> Option<Popup> {
        let (range, prefix) = commands::completion_prefix(text, caret_byte)?;
        let items = commands::completions(dialect, &prefix, COMPLETIONS_SHOWN);
        // A code typed in full with nothing longer to offer needs no list.
        let exact = items.len() == 1 && items[0].code.eq_ignore_ascii_case(&prefix);
        // The prefix is ASCII: as many characters as bytes.
        let start = caret_char.checked_sub(range.len())?;
        (!items.is_empty() && !exact).then_some(Popup {
            chars: start..caret_char,
            prefix,
            chosen: false,
            items,
            selected: 0,
            rect: None,
        })
    }

    /// What `key` (pressed without modifiers) does: Up/Down move through the list, Tab takes
    /// the highlighted code, Enter takes it once an arrow key picked it, Escape closes the list.
    pub fn key(&mut self, key: Key) -> PopupKey {
        let n = self.items.len().max(1);
        match key {
            Key::ArrowDown | Key::ArrowUp => {
                let step = if key == Key::ArrowDown { 1 } else { n - 1 };
                self.selected = (self.selected + step) % n;
                self.chosen = true;
                PopupKey::Handled
            }
            Key::Tab => PopupKey::Accept(self.selected),
            Key::Enter if self.chosen => PopupKey::Accept(self.selected),
            Key::Escape => PopupKey::Close,
            _ => PopupKey::None,
        }
    }

    /// Whether the pointer is over the list (which a click takes the focus to for a moment).
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
    /// inserted code, or `None` (nothing changed) when the text no longer holds the prefix there.
    pub fn accept(&self, index: usize, text: &mut Buffer) -> Option<usize> {
        let code = self.items.get(index)?;
        let typed = text.slice(self.chars.clone());
        let holds = self.chars.end <= text.len_chars() && typed.eq_ignore_ascii_case(&self.prefix);
        holds.then(|| text.replace(self.chars.clone(), &code.code))
    }
}
