//! The parsed program: blocks of address words, with byte spans back into the text.

use crate::{Diagnostic, Dialect, LineIndex, Span};

/// One address word such as `X-12.5`: a letter and its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// The address letter, uppercase ASCII.
    pub letter: u8,
    /// The value as written.
    pub value: f64,
    /// Whether the value was written with a decimal point (controls read the two differently).
    pub has_point: bool,
    /// The whole word, letter included.
    pub span: Span,
}

impl Word {
    /// The address letter as a `char`.
    pub fn letter(&self) -> char {
        char::from(self.letter)
    }
}

/// One block (a line, or part of a line ended by `;` in the Fanuc family).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// The block's text, from its first to its last byte (without the line ending).
    pub span: Span,
    /// 0-based line the block starts on.
    pub line: u32,
    /// The `N` sequence number, if any.
    pub number: Option<u32>,
    /// Block-delete level: `/` is 1, `/n` is n; `None` when there is no slash.
    pub block_delete: Option<u8>,
    /// The address words in the order written (without `N`).
    pub words: Vec<Word>,
    /// Spans of the comments in the block.
    pub comments: Vec<Span>,
    /// Whether the parser found an error in this block (it is not executed).
    pub has_error: bool,
}

impl Block {
    /// The first word with address `letter` (uppercase).
    pub fn word(&self, letter: u8) -> Option<&Word> {
        self.words.iter().find(|w| w.letter == letter)
    }

    /// Whether the block has neither words nor errors (blank, comment or tape mark).
    pub fn is_empty(&self) -> bool {
        self.words.is_empty()
    }
}

/// A parsed program: its blocks, the diagnostics found while reading it, and its line table.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    /// The dialect the text was read as.
    pub dialect: Dialect,
    /// Every block, in text order (blank lines give no block).
    pub blocks: Vec<Block>,
    /// Problems found while reading, in text order.
    pub diagnostics: Vec<Diagnostic>,
    /// Line starts, for turning spans into line and column.
    pub lines: LineIndex,
}
