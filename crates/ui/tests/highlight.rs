//! Editor highlighting: codes, words, comments, macro keywords and variables get their colours.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui::{Color32, FontId};
use swarf_syntax::Dialect;
use swarf_ui::editor::highlight;

/// The colour of the section that starts at the first occurrence of `needle`.
fn color_of(text: &str, dialect: Dialect, needle: &str) -> Color32 {
    let job = highlight(text, dialect, &FontId::monospace(12.0));
    let at = text.find(needle).unwrap();
    job.sections
        .iter()
        .find(|s| s.byte_range.start.0 == at)
        .unwrap_or_else(|| panic!("no section starts at {needle:?}: {:?}", job.sections))
        .format
        .color
}

#[test]
fn macro_keywords_and_variables_have_their_own_colours() {
    let text = "G01 X#1 (cut)\nIF [#1 GT 0] GOTO 10\n#<depth> = 2\n";
    let g = color_of(text, Dialect::Fanuc, "G01");
    let keyword = color_of(text, Dialect::Fanuc, "IF");
    let variable = color_of(text, Dialect::Fanuc, "#1 GT");
    let comment = color_of(text, Dialect::Fanuc, "(cut)");
    assert_ne!(keyword, g);
    assert_ne!(variable, g);
    assert_ne!(variable, keyword);
    assert_ne!(comment, keyword);
    assert_eq!(color_of(text, Dialect::Fanuc, "GOTO"), keyword);
    assert_eq!(color_of(text, Dialect::Fanuc, "GT"), keyword);
    assert_eq!(color_of(text, Dialect::LinuxCnc, "#<depth>"), variable);
}
