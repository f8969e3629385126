//! Undo and redo over the whole program text, shared by typing and the editor commands: each
//! entry is the text (a rope, sharing unchanged chunks) and selection before a change; consecutive
//! typing is one entry until a line break, a pause or a command ends it.

use std::ops::Range;

use ropey::Rope;

/// What caused a change, for merging runs of typing into one undo step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EditKind {
    /// Keyboard input in the editor.
    Typing,
    /// A command (replace, renumber, comment, completion, open …): always its own step.
    Command,
}

/// A text and its selection (character indices).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Snapshot {
    /// The whole program text.
    pub text: Rope,
    /// The selection to restore, in characters.
    pub selection: Range<usize>,
}

/// The undo and redo stacks.
#[derive(Debug, Clone, Default)]
pub struct History {
    /// The steps and the bytes each is reckoned to keep alive.
    undo: Vec<(Snapshot, usize)>,
    redo: Vec<(Snapshot, usize)>,
    /// Whether the newest undo entry is a typing run that further typing may join.
    typing_open: bool,
    /// When the open typing run last grew (seconds, egui time).
    last_typing: f64,
}

/// The most undo steps kept.
const LIMIT: usize = 200;
/// The most bytes of text the undo steps keep together (the newest step is always kept).
const BYTES_LIMIT: usize = 64 << 20;
/// What a step of typing is reckoned to keep alive (a command's: the text's size).
const TYPING_BYTES: usize = 16 << 10;
/// A pause in typing this long (seconds) starts a new undo step.
const PAUSE: f64 = 1.5;

impl History {
    /// Records that the text is about to change from `before`; `now` is the time in seconds.
    /// Typing that continues an open run adds nothing, so it is undone in one step.
    pub fn record(&mut self, before: Snapshot, kind: EditKind, ends_line: bool, now: f64) {
        self.redo.clear();
        let joins = kind == EditKind::Typing && self.typing_open && now - self.last_typing < PAUSE;
        if !joins {
            let bytes = match kind {
                EditKind::Typing => TYPING_BYTES.min(before.text.len_bytes()),
                EditKind::Command => before.text.len_bytes(),
            };
            self.undo.push((before, bytes));
            self.trim();
        }
        self.typing_open = kind == EditKind::Typing && !ends_line;
        self.last_typing = now;
    }

    /// Drops the oldest undo steps past [`LIMIT`] steps or [`BYTES_LIMIT`] bytes.
    fn trim(&mut self) {
        let mut bytes: usize = self.undo.iter().map(|(_, b)| b).sum();
        let mut drop = 0;
        while self.undo.len() - drop > 1 && (self.undo.len() - drop > LIMIT || bytes > BYTES_LIMIT)
        {
            bytes -= self.undo[drop].1;
            drop += 1;
        }
        self.undo.drain(..drop);
    }

    /// Takes the state to go back to, given the `current` one (which becomes redoable).
    pub fn undo(&mut self, current: Snapshot) -> Option<Snapshot> {
        let (back, bytes) = self.undo.pop()?;
        self.redo.push((current, bytes));
        self.typing_open = false;
        Some(back)
    }

    /// Takes the state to go forward to, given the `current` one (which becomes undoable).
    pub fn redo(&mut self, current: Snapshot) -> Option<Snapshot> {
        let (forward, bytes) = self.redo.pop()?;
        self.undo.push((current, bytes));
        self.trim();
        self.typing_open = false;
        Some(forward)
    }

    /// Whether there is something to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether there is something to redo.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Ends the current typing run, so the next keystroke starts a new undo step.
    pub fn break_run(&mut self) {
        self.typing_open = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn snap(text: &str) -> Snapshot {
        Snapshot {
            text: Rope::from_str(text),
            selection: 0..0,
        }
    }

    #[test]
    fn typing_runs_merge_until_a_line_break_a_pause_or_a_command() {
        let mut h = History::default();
        h.record(snap(""), EditKind::Typing, false, 0.0);
        h.record(snap("G"), EditKind::Typing, false, 0.2);
        h.record(snap("G0"), EditKind::Typing, true, 0.4);
        assert_eq!(h.undo.len(), 1);
        h.record(snap("G0\n"), EditKind::Typing, false, 0.5);
        h.record(snap("G0\nX"), EditKind::Typing, false, 5.0);
        h.record(snap("G0\nX1"), EditKind::Command, true, 5.1);
        assert_eq!(h.undo.len(), 4);
        assert_eq!(
            h.undo(snap("now")).map(|s| s.text.to_string()),
            Some("G0\nX1".to_string())
        );
        assert!(h.can_redo());
        h.record(snap("other"), EditKind::Command, true, 6.0);
        assert!(!h.can_redo(), "a new change drops the redo steps");
    }

    #[test]
    fn old_steps_go_when_the_history_grows_too_large() {
        let mut h = History::default();
        for i in 0..(LIMIT + 10) {
            h.record(snap(&i.to_string()), EditKind::Command, true, i as f64);
        }
        assert_eq!(h.undo.len(), LIMIT);
        let big = "x".repeat(BYTES_LIMIT / 2 + 1);
        for _ in 0..3 {
            h.record(snap(&big), EditKind::Command, true, 0.0);
        }
        assert_eq!(
            h.undo.len(),
            1,
            "two copies of the big text would pass the byte limit"
        );
        // Typing in a big text keeps a step per run: its rope shares the text's chunks.
        let mut h = History::default();
        let big = snap(&big);
        for i in 0..LIMIT {
            h.record(big.clone(), EditKind::Typing, true, i as f64);
        }
        assert_eq!(h.undo.len(), LIMIT);
    }
}
