//! Parser behaviour: words, comments, block ends, recovery and spans.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_syntax::{Dialect, Expr, ProgramNumber, Severity, Statement, decode, parse};

fn words(text: &str, dialect: Dialect) -> Vec<Vec<(char, f64)>> {
    parse(text, dialect)
        .blocks
        .iter()
        .map(|b| b.words.iter().map(|w| (w.letter(), w.value)).collect())
        .collect()
}

#[test]
fn reads_words_without_spaces_and_in_lowercase() {
    assert_eq!(
        words("G00X50.Y-50.5z.5\ng1 x 10 f 200\n", Dialect::Fanuc),
        vec![
            vec![('G', 0.0), ('X', 50.0), ('Y', -50.5), ('Z', 0.5)],
            vec![('G', 1.0), ('X', 10.0), ('F', 200.0)],
        ]
    );
}

#[test]
fn sequence_numbers_comments_and_tape_marks() {
    let p = parse(
        "%\nO1000 (MAIN)\nN10 G90 G21 (metric)\n\nN20 G0 X1\n%\n",
        Dialect::Fanuc,
    );
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    assert_eq!(p.blocks.len(), 3);
    assert_eq!(p.blocks[0].program(), Some(&ProgramNumber::Number(1000)));
    assert!(p.blocks[0].words.is_empty());
    assert_eq!(p.blocks[0].comments().len(), 1);
    assert_eq!(p.blocks[1].number(), Some(10));
    assert_eq!(p.blocks[1].line, 2);
    assert_eq!(p.blocks[2].number(), Some(20));
    assert_eq!(p.blocks[2].line, 4);
}

#[test]
fn semicolon_ends_block_in_fanuc_and_comments_in_linuxcnc() {
    assert_eq!(
        words("G0 X1; G1 X2 ;\n", Dialect::Fanuc),
        vec![vec![('G', 0.0), ('X', 1.0)], vec![('G', 1.0), ('X', 2.0)]]
    );
    assert_eq!(
        words("G0 X1 ; G1 X2\n", Dialect::LinuxCnc),
        vec![vec![('G', 0.0), ('X', 1.0)]]
    );
}

#[test]
fn block_delete_levels() {
    let p = parse("/G0 X1\n/3 G1 X2\n", Dialect::Fanuc);
    assert_eq!(p.blocks[0].block_delete(), Some(1));
    assert_eq!(p.blocks[1].block_delete(), Some(3));
}

#[test]
fn bad_character_is_reported_with_span_and_the_rest_still_parses() {
    let text = "G01 X10 Y$ F100\nG00 Z5\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(p.diagnostics.len(), 2, "{:?}", p.diagnostics);
    let codes: Vec<_> = p.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["E-WORD-VALUE", "E-SYNTAX-CHAR"]);
    let d = &p.diagnostics[1];
    assert_eq!(d.severity, Severity::Error);
    assert_eq!(&text[d.span.range()], "$");
    assert_eq!(p.lines.line_col(text, d.span.start), (1, 10));
    assert!(p.blocks[0].has_error());
    assert_eq!(p.blocks[1].words.len(), 2);
    assert!(!p.blocks[1].has_error());
}

#[test]
fn unclosed_comment_and_missing_value() {
    let p = parse("G0 X1 (oops\nG1 X\n", Dialect::Fanuc);
    let codes: Vec<_> = p.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["E-COMMENT-UNCLOSED", "E-WORD-VALUE"]);
    assert_eq!(
        p.lines
            .line_col("G0 X1 (oops\nG1 X\n", p.diagnostics[1].span.start),
        (2, 4)
    );
}

#[test]
fn columns_count_characters_not_bytes() {
    let text = "(銑削) G0 X$\n";
    let p = parse(text, Dialect::Fanuc);
    let d = p
        .diagnostics
        .iter()
        .find(|d| d.code == "E-SYNTAX-CHAR")
        .unwrap();
    assert_eq!(p.lines.line_col(text, d.span.start), (1, 10));
}

#[test]
fn crlf_and_absurd_numbers() {
    let p = parse("G0 X1\r\nG1 X99999999999999999999999\r\n", Dialect::Fanuc);
    assert_eq!(p.blocks[0].words.len(), 2);
    assert_eq!(p.diagnostics[0].code, "E-NUMBER-RANGE");
}

#[test]
fn dialect_names_round_trip() {
    for d in Dialect::ALL {
        assert_eq!(d.name().parse::<Dialect>().unwrap(), d);
    }
    assert!("heidenhain".parse::<Dialect>().is_err());
}

#[test]
fn decoding_detects_gbk_and_big5_and_round_trips() {
    let gbk: &[u8] = &[b'(', 0xB5, 0xB6, 0xBE, 0xDF, b')', b'\n'];
    let d = decode(gbk);
    assert_eq!(d.encoding, swarf_syntax::Encoding::Gb18030);
    assert_eq!(d.text, "(刀具)\n");
    assert_eq!(d.encoding.encode(&d.text), gbk);
    let utf8 = decode("G0 X1\n".as_bytes());
    assert_eq!(utf8.encoding, swarf_syntax::Encoding::Utf8);
    assert!(utf8.diagnostics.is_empty());
}

#[test]
fn invalid_bytes_become_diagnostics() {
    let d = decode(&[b'G', b'0', 0xFF, 0xFF, 0xFF, b'\n', 0x81]);
    assert!(!d.diagnostics.is_empty());
    assert!(d.text.starts_with("G0"));
}

#[test]
fn the_line_cursor_agrees_with_line_col_in_any_order() {
    let text = "G0 X1 (é)\nG1 Xé Y2\n\nG2 X1 R\n";
    let p = parse(text, Dialect::Fanuc);
    let mut cursor = p.lines.cursor(text);
    let offsets: Vec<u32> = (0..text.len() as u32)
        .filter(|o| text.is_char_boundary(*o as usize))
        .collect();
    for &o in offsets.iter().chain(offsets.iter().rev()) {
        assert_eq!(cursor.line_col(o), p.lines.line_col(text, o), "offset {o}");
    }
}

#[test]
fn a_linked_program_keeps_its_meaning_past_the_main_text() {
    let main = "#1=2\nM98 P1234\no<sq> call [#1+1]\nM30\n";
    let mut p = parse(main, Dialect::Fanuc);
    assert_eq!(
        p.missing_calls(),
        [swarf_syntax::Missing::Number(1234)],
        "o-word calls are LinuxCNC's"
    );
    let sub_text = "O1234\n#2=[#1*3]\nG1 X#2\nM99\n";
    let sub = parse(sub_text, Dialect::Fanuc);
    let exprs_before = p.exprs.len();
    p.link(sub, "O1234.nc", main.len(), sub_text.len());
    assert!(p.missing_calls().is_empty());
    let l = &p.linked[0];
    assert_eq!((l.first_byte as usize, l.first_line), (main.len() + 1, 5));
    let first = &p.blocks[4];
    assert_eq!(first.line, 5);
    assert_eq!(first.span.start as usize, main.len() + 1);
    // The linked expressions are renumbered after the main program's: `#2=[#1*3]` still reads
    // `#1 * 3`.
    let Statement::Assign { value, .. } = &p.blocks[5].statements()[0] else {
        panic!("{:?}", p.blocks[5]);
    };
    assert!(value.index() >= exprs_before);
    let Expr::Binary(_, a, b) = &p.expr(*value).unwrap().expr else {
        panic!()
    };
    assert!(matches!(p.expr(*b).unwrap().expr, Expr::Num(n) if n == 3.0));
    assert!(matches!(p.expr(*a).unwrap().expr, Expr::Var(_)));
    assert!(p.blocks[6].words[1].expr.unwrap().index() >= exprs_before);
    assert_eq!(
        p.linked_at_offset(first.span.start)
            .map(|i| p.linked[i].name.as_str()),
        Some("O1234.nc")
    );
    assert!(p.linked_at_offset(3).is_none());
    assert_eq!(p.linked_at_line(first.line), Some(0));
    assert!(p.linked_at_line(4).is_none());
    // LinuxCNC: named subroutines.
    let l = parse("o<sq> call [1]\nM2\n", Dialect::LinuxCnc);
    assert_eq!(
        l.missing_calls(),
        [swarf_syntax::Missing::Name("sq".into())]
    );
}

/// A file found by its name for `M98 P n` is program `O n`, with an `O` line or without one;
/// one that opens with another number runs as `O n`, with a warning.
#[test]
fn a_file_found_by_its_name_is_that_program() {
    let main = "M98 P5001\nM98 P5003\nM98 P5004\nM30\n";
    let mut p = parse(main, Dialect::Fanuc);
    let files = [
        (5001, "5001.nc", "G91 G1 X1. F100.\nM99\n"),
        (5003, "5003.nc", "O5002\nG1 Y1.\nM99\n"),
        (5004, "O5004.nc", "O5004\nG1 Z1.\nM99\n"),
    ];
    let linked = p.link_calls(main.len(), Dialect::Fanuc, 8, |missing| {
        files.iter().find_map(|(n, name, text)| {
            (*missing == swarf_syntax::Missing::Number(*n))
                .then(|| (name.to_string(), text.to_string()))
        })
    });
    assert_eq!(linked.len(), 3);
    assert!(p.missing_calls().is_empty(), "{:?}", p.missing_calls());
    let start = |n: u32| {
        p.blocks
            .iter()
            .position(|b| b.program() == Some(&ProgramNumber::Number(n)))
            .unwrap()
    };
    // Without an `O` line: an empty `O5001` block on the file's first line, before its own.
    let at = start(5001);
    assert!(p.blocks[at].words.is_empty());
    assert_eq!(p.blocks[at].line, p.linked[0].first_line);
    assert_eq!(p.blocks[at + 1].words[0].letter(), 'G');
    assert_eq!(p.blocks[at + 1].line, p.linked[0].first_line);
    // A contradicting `O` line: the program runs as O5003, with a warning in that file.
    assert!(
        p.blocks
            .iter()
            .all(|b| b.program() != Some(&ProgramNumber::Number(5002)))
    );
    let warned: Vec<_> = p
        .diagnostics
        .iter()
        .filter(|d| d.code == "W-PROGRAM-NUMBER")
        .collect();
    assert_eq!(warned.len(), 1, "{:?}", p.diagnostics);
    assert!(warned[0].message.contains("O5002") && warned[0].message.contains("O5003"));
    assert_eq!(
        p.linked_at_offset(warned[0].span.start)
            .map(|i| p.linked[i].name.as_str()),
        Some("5003.nc")
    );
    // A file that holds its program is linked as it is.
    assert_eq!(start(5004) + 1, p.blocks.len() - 2);
}

/// A line ends at `\n`, `\r\n` or a `\r` alone, so the `\r\r\n` some Windows tools write is two
/// line ends and no stray character.
#[test]
fn a_carriage_return_ends_a_line_alone_or_before_a_line_feed() {
    for (text, lines) in [
        ("G90\r\r\nG0 X1. Y2.\r\r\nM30\r\r\n", [0, 2, 4]),
        ("G90\rG0 X1. Y2.\rM30", [0, 1, 2]),
        ("G90\r\nG0 X1. Y2.\nM30\r\n", [0, 1, 2]),
    ] {
        for dialect in Dialect::ALL {
            let p = parse(text, dialect);
            assert!(
                p.diagnostics.iter().all(|d| d.code != "E-SYNTAX-CHAR"),
                "{dialect:?} {text:?}: {:?}",
                p.diagnostics
            );
            let found: Vec<u32> = p.blocks.iter().map(|b| b.line).collect();
            assert_eq!(found, lines, "{dialect:?} {text:?}");
            // The second block's words, where the text has them.
            let x = p.blocks[1].words[1].span;
            assert_eq!(&text[x.start as usize..x.end as usize], "X1.");
            assert_eq!(
                p.lines.line_col(text, x.start),
                (lines[1] + 1, 4),
                "{dialect:?} {text:?}"
            );
        }
    }
    // A diagnostic's line counts the `\r` alone as a line end.
    let text = "G90\rG1 X$\rM30\r";
    let p = parse(text, Dialect::Fanuc);
    let bad = p
        .diagnostics
        .iter()
        .find(|d| d.severity == Severity::Error)
        .unwrap();
    assert_eq!(p.lines.line_col(text, bad.span.start), (2, 4));
    // Lines read a few at a time end where the text's do (a rope's chunks cut anywhere:
    // crates/analysis/tests/rope_parse.rs).
    let text = "G90\r\r\nG0 X1.\rY2.\r\nM30\r";
    let whole = parse(text, Dialect::LinuxCnc);
    assert_eq!(whole.lines, swarf_syntax::LineIndex::new(text));
    let mut run = swarf_syntax::ParseRun::new(Dialect::LinuxCnc);
    while !run.step(text, 2) {}
    assert_eq!(run.finish(), whole);
}

#[test]
fn a_block_keeps_its_rare_parts_in_one_box_and_gives_them_back() {
    let text = "O0012 (part)\nG1 X1. Y2. Z3.\n#1 = 5 (set) (twice)\n";
    let p = parse(text, Dialect::Fanuc);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let [program, plain, macro_line] = &p.blocks[..] else {
        panic!("three blocks expected: {:?}", p.blocks);
    };
    assert_eq!(program.program(), Some(&ProgramNumber::Number(12)));
    assert_eq!(program.comments().len(), 1);
    assert!(program.statements().is_empty());
    // A plain line has none of them.
    assert_eq!(plain.program(), None);
    assert!(plain.statements().is_empty() && plain.comments().is_empty());
    assert_eq!(plain.words.len(), 4);
    assert!(!plain.is_empty() && !plain.has_macro());
    assert_eq!(macro_line.statements().len(), 1);
    assert_eq!(macro_line.comments().len(), 2);
    assert!(macro_line.has_macro());
    let c = macro_line.comments()[1];
    assert_eq!(&text[c.start as usize..c.end as usize], "(twice)");
    // The common block pays one pointer for them: four words inline and a few fields, two
    // cache lines in all.
    #[cfg(target_pointer_width = "64")]
    assert!(std::mem::size_of::<swarf_syntax::Block>() <= 128);
}
