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
