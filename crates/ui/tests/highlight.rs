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

#[test]
fn hover_explains_the_code_and_the_problem_under_the_pointer() {
    use swarf_ui::editor::hover_text;
    let text = "G90 G134 X0 Y0 I10. J0 K6\n";
    // Over `G134` on Syntec: the bolt-hole circle.
    let at = text.find("134").unwrap();
    let help = hover_text(text, Dialect::Syntec, at, &[]).unwrap();
    assert!(help.contains("Bolt-hole"), "{help}");
    // On Fanuc the same code is not one of its codes; with the parser's problem shown too.
    let job = swarf_analysis::Job {
        generation: 1,
        text: text.to_string().into(),
        dialect: Dialect::Fanuc,
        setup: swarf_interp::Setup::default(),
        others: None,
        lod: None,
    };
    let analysis = swarf_analysis::analyse(job).0;
    let help = hover_text(text, Dialect::Fanuc, at, &analysis.problems).unwrap();
    assert!(help.contains("E-CODE-DIALECT"), "{help}");
    assert!(help.contains("not a code of Fanuc"), "{help}");
    // Over an address word: what the letter means.
    let help = hover_text(text, Dialect::Syntec, text.find("X0").unwrap() + 1, &[]).unwrap();
    assert!(help.starts_with("X:"), "{help}");
    // Over a comment: nothing.
    assert!(hover_text("(note)\n", Dialect::Fanuc, 2, &[]).is_none());
}
