//! The editor commands on plain text: find/replace, comments, renumbering, completion, lines.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_syntax::Dialect;
use swarf_ui::commands::*;

#[test]
fn find_literal_is_case_insensitive_and_regex_replaces_with_groups() {
    let text = "G01 X10. F200\ng01 x20. f300\n";
    let literal = FindOptions::default();
    let f = Finder::new("g01", literal).unwrap();
    assert_eq!(f.find_all(text), [0..3, 14..17]);
    // Literal mode escapes regex syntax.
    assert!(
        Finder::new("X10.", literal)
            .unwrap()
            .find_all("X10A")
            .is_empty()
    );
    let re = FindOptions {
        regex: true,
        match_case: true,
    };
    let f = Finder::new(r"F(\d+)", re).unwrap();
    let (out, n) = f.replace_all(text, "F${1}0", re);
    assert_eq!(n, 1);
    assert_eq!(out, "G01 X10. F2000\ng01 x20. f300\n");
    // `$` stays literal outside regex mode.
    let f = Finder::new("F200", literal).unwrap();
    assert_eq!(
        f.replace_all(text, "$1", literal).0,
        "G01 X10. $1\ng01 x20. f300\n"
    );
    // Next and previous wrap around.
    let f = Finder::new("x", literal).unwrap();
    assert_eq!(f.next(text, 20), Some(4..5));
    assert_eq!(f.previous(text, 3), Some(18..19));
    assert!(Finder::new("(", re).is_err());
}

#[test]
fn comments_toggle_in_the_dialects_form() {
    let text = "G00 X0\nG01 X1 (cut)\n\n(note)\nM30\n";
    let fanuc = toggle_comment(text, 1..=4, Dialect::Fanuc);
    assert_eq!(fanuc, "(G00 X0)\n(G01 X1) (cut)\n\n(note)\nM30\n");
    assert_eq!(toggle_comment(&fanuc, 1..=2, Dialect::Fanuc), text);
    // Every selected line commented: all are uncommented, a comment line too.
    assert_eq!(
        toggle_comment(&fanuc, 4..=4, Dialect::Fanuc),
        "(G00 X0)\n(G01 X1) (cut)\n\nnote\nM30\n"
    );
    let lcnc = toggle_comment(text, 1..=2, Dialect::LinuxCnc);
    assert_eq!(lcnc, "; G00 X0\n; G01 X1 (cut)\n\n(note)\nM30\n");
    assert_eq!(toggle_comment(&lcnc, 1..=2, Dialect::LinuxCnc), text);
    // The commented program parses with no blocks on those lines.
    let program = swarf_syntax::parse(&fanuc, Dialect::Fanuc);
    assert!(program.diagnostics.is_empty(), "{:?}", program.diagnostics);
    assert_eq!(
        program
            .blocks
            .iter()
            .filter(|b| !b.words.is_empty())
            .count(),
        1
    );
}

#[test]
fn renumbering_keeps_n_on_numbered_blocks_and_follows_goto() {
    let text = "%\nO1000\nN5 G90\nG00 X0\nN7 #1=1\n/N9 X1\nIF [#1 LT 3] GOTO 7\nM30\n%\n";
    let out = renumber(text, RenumberOptions::default(), Dialect::Fanuc);
    assert_eq!(
        out.text,
        "%\nO1000\nN10 G90\nG00 X0\nN20 #1=1\n/N30 X1\nIF [#1 LT 3] GOTO 20\nM30\n%\n"
    );
    assert_eq!((out.numbered, out.targets), (3, 1));
    let all = RenumberOptions {
        start: 100,
        step: 5,
        all_blocks: true,
    };
    let out = renumber("(head)\nG90\nN1 G00 X0\n\nM30\n", all, Dialect::Fanuc);
    assert_eq!(out.text, "(head)\nN100 G90\nN105 G00 X0\n\nN110 M30\n");
    // LinuxCNC O-word lines and `;` comments are no blocks.
    let out = renumber(
        "o100 sub\nG0 X1\n; note\no100 endsub\n",
        all,
        Dialect::LinuxCnc,
    );
    assert_eq!(out.text, "o100 sub\nN100 G0 X1\n; note\no100 endsub\n");
}

#[test]
fn completion_offers_the_dialects_codes_with_their_meaning() {
    let g8 = completions(Dialect::Fanuc, "G8", 20);
    assert!(g8.iter().any(|c| c.code == "G81"), "{g8:?}");
    assert!(g8.iter().all(|c| c.code.starts_with("G8")), "{g8:?}");
    assert!(g8.iter().all(|c| !c.name.is_empty()));
    // `G1` offers G01 as well as G10…G19.
    let g1 = completions(Dialect::Fanuc, "g1", 50);
    assert!(g1.iter().any(|c| c.code == "G01") && g1.iter().any(|c| c.code == "G17"));
    // Syntec's G134 is not a Fanuc code.
    assert!(
        completions(Dialect::Syntec, "G13", 20)
            .iter()
            .any(|c| c.code == "G134")
    );
    assert!(
        !completions(Dialect::Fanuc, "G13", 20)
            .iter()
            .any(|c| c.code == "G134")
    );
    let text = "G90 G8";
    assert_eq!(
        completion_prefix(text, text.len()),
        Some((4..6, "G8".to_string()))
    );
    assert_eq!(completion_prefix("GOTO", 1), None);
    assert_eq!(completion_prefix("(G8", 3), None);
    assert_eq!(completion_prefix("X1", 2), None);
}

#[test]
fn lines_and_alarms() {
    let text = "a\nbb\nccc";
    assert_eq!(line_start(text, 3), 5);
    assert_eq!(line_start(text, 9), text.len());
    assert_eq!(line_of_byte(text, 4), 2);
    assert_eq!(line_count(text), 3);
    assert_eq!(line_count("a\n"), 1);
    assert_eq!(char_of_byte("銑a", 3), 1);
    assert_eq!(char_ranges("銑G1 銑G1", &[3..5, 9..11]), [1..3, 5..7]);
    assert_eq!(byte_of_char("銑a", 1), 3);
    assert_eq!(
        alarm_in("arc end point is off the circle (alarm COR-006)"),
        Some("COR-006")
    );
    assert_eq!(alarm_in("machine alarm 12."), Some("alarm 12"));
    assert_eq!(alarm_in("nothing here"), None);
}

mod never_panic {
    use proptest::prelude::*;
    use swarf_syntax::Dialect;
    use swarf_ui::commands::*;

    /// Program-like text: G-code letters, digits, comments, `;`, `/`, `%`, line ends and
    /// some multi-byte characters.
    fn gcode() -> impl Strategy<Value = String> {
        proptest::string::string_regex("[GMNOXYZPFgmno0-9 .;/%()\\n\\r\\t#銑é-]{0,80}").unwrap()
    }

    proptest! {
        #[test]
        fn commands_accept_any_text(text in gcode(), a in 0u32..12, b in 0u32..12, at in 0usize..100) {
            for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::LinuxCnc] {
                let (first, last) = (a.min(b), a.max(b));
                let once = toggle_comment(&text, first..=last, dialect);
                let _ = toggle_comment(&once, first..=last, dialect);
                let all = RenumberOptions { start: 1, step: 1, all_blocks: true };
                let out = renumber(&text, all, dialect);
                prop_assert_eq!(out.text.lines().count(), text.lines().count());
                let _ = renumber(&text, RenumberOptions::default(), dialect);
            }
            let byte = byte_of_char(&text, at);
            prop_assert!(text.is_char_boundary(byte));
            prop_assert_eq!(char_of_byte(&text, byte), at.min(text.chars().count()));
            if let Some((range, prefix)) = completion_prefix(&text, byte) {
                prop_assert_eq!(text[range].to_ascii_uppercase(), prefix.clone());
                let _ = completions(Dialect::Fanuc, &prefix, 5);
            }
            let line = line_of_byte(&text, byte);
            prop_assert!(line_start(&text, line) <= byte);
            let _ = alarm_in(&text);
            if let Ok(f) = Finder::new(&text, FindOptions { regex: true, match_case: false }) {
                let _ = f.replace_all(&text, "$1x", FindOptions { regex: true, match_case: false });
            }
        }
    }
}
