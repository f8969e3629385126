//! The language: macro statements and expressions, comma and indexed words, O-words, program
//! numbers, and each diagnostic code with its exact span.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_syntax::{
    BinOp, Dialect, Expr, ExprId, Func, OLabel, OWord, Program, ProgramNumber, Severity, Statement,
    WordForm, parse,
};

/// Renders an expression back to a canonical bracketed form, for compact assertions.
fn show(p: &Program, id: ExprId) -> String {
    match &p.expr(id).unwrap().expr {
        Expr::Num(v) => format!("{v}"),
        Expr::Var(i) => format!("#{}", show(p, *i)),
        Expr::Named(n) => format!("#<{n}>"),
        Expr::Neg(i) => format!("-{}", show(p, *i)),
        Expr::Binary(op, a, b) => format!("({} {} {})", show(p, *a), op.symbol(), show(p, *b)),
        Expr::Call(f, a, None) => format!("{}[{}]", f.name(), show(p, *a)),
        Expr::Call(f, a, Some(b)) => format!("{}[{},{}]", f.name(), show(p, *a), show(p, *b)),
    }
}

fn codes(p: &Program) -> Vec<&'static str> {
    p.diagnostics.iter().map(|d| d.code).collect()
}

/// The text of the first diagnostic with `code`.
fn spanned<'t>(p: &Program, text: &'t str, code: &str) -> &'t str {
    let d = p
        .diagnostics
        .iter()
        .find(|d| d.code == code)
        .unwrap_or_else(|| panic!("no {code} in {:?}", p.diagnostics));
    &text[d.span.range()]
}

fn assign(p: &Program, stmt: &Statement) -> (String, String) {
    match stmt {
        Statement::Assign { target, value } => (show(p, *target), show(p, *value)),
        other => panic!("not an assignment: {other:?}"),
    }
}

#[test]
fn assignments_and_fanuc_precedence() {
    let p = parse(
        "#1=2+3*4\n#2 = #1 AND 3 + 1\n#[#1+1]=-#2\n#3=ATAN[1]/[2]+POW[2,3]\n",
        Dialect::Fanuc,
    );
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let got: Vec<_> = p
        .blocks
        .iter()
        .map(|b| assign(&p, &b.statements()[0]))
        .collect();
    assert_eq!(got[0], ("#1".into(), "(2 + (3 * 4))".into()));
    // Fanuc: AND binds like `*`, so `#1 AND 3 + 1` is `(#1 AND 3) + 1`.
    assert_eq!(got[1], ("#2".into(), "((#1 AND 3) + 1)".into()));
    assert_eq!(got[2], ("#(#1 + 1)".into(), "-#2".into()));
    assert_eq!(got[3].1, "(ATAN[1,2] + POW[2,3])");
}

#[test]
fn linuxcnc_logic_binds_loosest_and_power_is_right_associative() {
    let p = parse(
        "#1 = [1 + 2 GT 2 AND 1]\n#2 = [2 ** 3 ** 2]\n",
        Dialect::LinuxCnc,
    );
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    assert_eq!(
        assign(&p, &p.blocks[0].statements()[0]).1,
        "(((1 + 2) GT 2) AND 1)"
    );
    assert_eq!(
        assign(&p, &p.blocks[1].statements()[0]).1,
        "(2 ** (3 ** 2))"
    );
}

#[test]
fn words_take_variables_brackets_and_functions() {
    let p = parse("G#30 X#1 Y-#2 Z[#3+1] A SIN[30]\n", Dialect::Fanuc);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let b = &p.blocks[0];
    let shown: Vec<_> = b
        .words
        .iter()
        .map(|w| (w.letter(), show(&p, w.expr.unwrap())))
        .collect();
    assert_eq!(
        shown,
        [
            ('G', "#30".to_string()),
            ('X', "#1".into()),
            ('Y', "-#2".into()),
            ('Z', "(#3 + 1)".into()),
            ('A', "SIN[30]".into()),
        ]
    );
    assert!(b.has_macro());
}

#[test]
fn macro_b_control_statements() {
    let text = "N10 IF [#1 GT 10] GOTO 20\nIF [#2 EQ 0] THEN #3=1\nWHILE [#1 LT 5] DO1\n#1=#1+1\nEND1\nGOTO #4\nDO2\nEND2\n";
    let p = parse(text, Dialect::Fanuc);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    match &p.blocks[0].statements()[0] {
        Statement::If { cond, then } => {
            assert_eq!(show(&p, *cond), "(#1 GT 10)");
            assert!(matches!(**then, Statement::Goto { target } if show(&p, target) == "20"));
        }
        s => panic!("{s:?}"),
    }
    assert_eq!(p.blocks[0].number(), Some(10));
    assert!(
        matches!(&p.blocks[1].statements()[0], Statement::If { then, .. } if matches!(**then, Statement::Assign { .. }))
    );
    assert!(matches!(
        p.blocks[2].statements()[0],
        Statement::While {
            cond: Some(_),
            label: 1
        }
    ));
    assert!(matches!(
        p.blocks[4].statements()[0],
        Statement::End { label: 1 }
    ));
    assert!(matches!(
        p.blocks[5].statements()[0],
        Statement::Goto { .. }
    ));
    assert!(matches!(
        p.blocks[6].statements()[0],
        Statement::While {
            cond: None,
            label: 2
        }
    ));
}

#[test]
fn loop_numbers_are_one_to_three() {
    let text = "WHILE [1] DO4\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(codes(&p), ["E-LOOP-NUMBER"]);
    assert!(p.blocks[0].has_error());
}

#[test]
fn syntec_macro_header_and_colon_assignment() {
    let p = parse(
        "%@MACRO\n#30 := #1000; // modal\nG#30 G#31;\n",
        Dialect::Syntec,
    );
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    assert!(p.syntec_macro);
    assert_eq!(
        assign(&p, &p.blocks[0].statements()[0]),
        ("#30".into(), "#1000".into())
    );
    assert_eq!(p.blocks[1].words.len(), 2);
}

#[test]
fn colon_assignment_is_syntec_only() {
    let text = "#1 := 5\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(codes(&p), ["E-MACRO-SYNTAX"]);
    assert_eq!(spanned(&p, text, "E-MACRO-SYNTAX"), "#1");
}

#[test]
fn linuxcnc_o_words_and_named_parameters() {
    let text = "o100 sub\n#<depth> = #1\no100 endsub\no<drill> call [1.5] [#<depth>]\nO101 if [#1 GT 0]\no101 else\nO101 endif\no102 repeat [3]\no102 endrepeat\no103 return [2]\n";
    let p = parse(text, Dialect::LinuxCnc);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let kinds: Vec<_> = p
        .blocks
        .iter()
        .filter_map(|b| match b.statements().first() {
            Some(Statement::OWord { label, kind }) => Some((label.clone(), kind.clone())),
            _ => None,
        })
        .collect();
    assert_eq!(kinds[0], (OLabel::Number(100), OWord::Sub));
    assert!(
        matches!(&kinds[2], (OLabel::Name(n), OWord::Call(args)) if &**n == "drill" && args.len() == 2)
    );
    assert!(matches!(kinds[3].1, OWord::If(_)));
    assert_eq!(kinds[4].1, OWord::Else);
    assert!(matches!(kinds[8].1, OWord::Return(Some(_))));
    assert_eq!(
        assign(&p, &p.blocks[1].statements()[0]),
        ("#<depth>".into(), "#1".into())
    );
}

#[test]
fn named_parameters_are_linuxcnc_only() {
    let text = "#<x> = 1\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(codes(&p), ["E-MACRO-SYNTAX"]);
}

#[test]
fn bad_o_word_keyword() {
    let text = "o100 jump\n";
    let p = parse(text, Dialect::LinuxCnc);
    assert_eq!(codes(&p), ["E-OWORD"]);
    assert_eq!(spanned(&p, text, "E-OWORD"), "jump");
}

#[test]
fn program_numbers() {
    let p = parse("O0012\n:0034\nO<part> \n", Dialect::Fanuc);
    assert_eq!(p.blocks[0].program(), Some(&ProgramNumber::Number(12)));
    assert_eq!(p.blocks[1].program(), Some(&ProgramNumber::Number(34)));
    assert!(p.blocks[2].has_error());
    let l = parse("O<part>\n", Dialect::LinuxCnc);
    assert_eq!(
        l.blocks[0].program(),
        Some(&ProgramNumber::Name("part".into()))
    );
}

#[test]
fn comma_words_on_lnc_and_fanuc() {
    let text = "G01 X10. Y10. ,C2. F100\nG01 X20.,R5.\n";
    let p = parse(text, Dialect::Lnc);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let c = p.blocks[0].comma_word(b'C').unwrap();
    assert_eq!((c.value, c.form), (2.0, WordForm::Comma));
    assert_eq!(&text[c.span.range()], ",C2.");
    assert!(p.blocks[0].word(b'C').is_none());
    assert_eq!(p.blocks[1].comma_word(b'R').unwrap().value, 5.0);
    let kt = parse(text, Dialect::Kt);
    assert_eq!(spanned(&kt, text, "E-COMMA-WORD"), ",C2.");
}

#[test]
fn indexed_words_on_syntec() {
    let text = "G81 X5. Y5. Z-10. R-5. F2=1000\nM03 S1=150\n";
    let p = parse(text, Dialect::Syntec);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let f2 = p.blocks[0].words.last().unwrap();
    assert_eq!(
        (f2.letter, f2.value, f2.form),
        (b'F', 1000.0, WordForm::Indexed(2))
    );
    assert!(p.blocks[0].word(b'F').is_none());
    let s1 = &p.blocks[1].words[1];
    assert_eq!(s1.form, WordForm::Indexed(1));
    let fanuc = parse(text, Dialect::Fanuc);
    assert_eq!(spanned(&fanuc, text, "E-WORD-INDEXED"), "F2=1000");
}

#[test]
fn retract_feed_must_be_whole() {
    let text = "G81 X5. Y5. Z-10. R-5. F2=10.5\n";
    let p = parse(text, Dialect::Syntec);
    assert_eq!(spanned(&p, text, "E-NUMBER-RANGE"), "F2=10.5");
    assert!(p.diagnostics[0].message.contains("COR-045"));
}

#[test]
fn expression_errors_have_spans() {
    let text = "#1=[2+3\n#2=FOO[1]\n#3=\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(codes(&p), ["E-EXPR-BRACKET", "E-EXPR", "E-EXPR"]);
    assert_eq!(spanned(&p, text, "E-EXPR-BRACKET"), "[2+3");
    assert_eq!(&text[p.diagnostics[1].span.range()], "FOO");
    assert_eq!(p.blocks.len(), 3);
}

#[test]
fn bracket_depth_is_limited_per_dialect_and_never_overflows() {
    let deep = format!("#1={}1{}\n", "[".repeat(6), "]".repeat(6));
    let p = parse(&deep, Dialect::Fanuc);
    assert_eq!(codes(&p), ["E-EXPR-DEPTH"]);
    assert!(parse(&deep, Dialect::LinuxCnc).diagnostics.is_empty());
    let hostile = format!("#1={}\nG0 X1.\n", "[".repeat(100_000));
    for d in Dialect::ALL {
        let p = parse(&hostile, d);
        assert!(
            p.diagnostics
                .iter()
                .any(|x| x.code == "E-EXPR-DEPTH" || x.code == "E-MACRO-SYNTAX"),
            "{d}: {:?}",
            p.diagnostics
        );
        assert_eq!(p.blocks.len(), 2);
    }
}

#[test]
fn stray_colon_at_block_end_is_a_warning() {
    let text = "G01 Z-10.0:\n";
    let p = parse(text, Dialect::Syntec);
    assert_eq!(codes(&p), ["W-STRAY-COLON"]);
    assert_eq!(p.diagnostics[0].severity, Severity::Warning);
    assert!(!p.blocks[0].has_error());
}

#[test]
fn digits_beyond_the_control_are_an_error() {
    let text = "G01 X1234567890.\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(spanned(&p, text, "E-NUMBER-RANGE"), "X1234567890.");
    assert!(parse(text, Dialect::LinuxCnc).diagnostics.is_empty());
}

#[test]
fn sequence_number_range() {
    let text = "N123456 G00 X1.\n";
    let p = parse(text, Dialect::Fanuc);
    assert_eq!(spanned(&p, text, "E-NUMBER-RANGE"), "N123456");
}

#[test]
fn functions_and_operators_are_known() {
    for (name, f) in Func::names() {
        assert!(!f.name().is_empty());
        let text = if matches!(f, Func::Pow) {
            format!("#1={name}[2,3]\n")
        } else if matches!(f, Func::Exists) {
            continue;
        } else {
            format!("#1={name}[2]\n")
        };
        let p = parse(&text, Dialect::Fanuc);
        assert!(p.diagnostics.is_empty(), "{name}: {:?}", p.diagnostics);
    }
    assert_eq!(BinOp::Mod.symbol(), "MOD");
}

#[test]
fn text_after_the_closing_tape_mark_is_not_read() {
    let text = "%\nG0 X1\n%\n(notes)\nO2 sub\nG0 Z3\n";
    let p = parse(text, Dialect::LinuxCnc);
    assert_eq!(p.blocks.len(), 1, "{:?}", p.blocks);
    assert_eq!(codes(&p), ["N-AFTER-TAPE-END"]);
    assert_eq!(p.diagnostics[0].severity, Severity::Note);
    assert_eq!(
        spanned(&p, text, "N-AFTER-TAPE-END"),
        "(notes)\nO2 sub\nG0 Z3"
    );
    // A `%` that does not open the program is only a mark; a closing one with nothing after it
    // says nothing.
    let p = parse("G0 X1\n%\nG0 X2\n", Dialect::Fanuc);
    assert_eq!(p.blocks.len(), 2);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let p = parse("\n %\nO1\nG0 X1\n%\n\n", Dialect::Fanuc);
    assert_eq!(p.blocks.len(), 2);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
}

#[test]
fn linuxcnc_o_word_numbers_may_be_computed() {
    let text = "#2 = 10\nO[#2 * 10] call\no#<sub> call [1]\nO[1]\n";
    let p = parse(text, Dialect::LinuxCnc);
    let labels: Vec<String> = p
        .blocks
        .iter()
        .filter_map(|b| match b.statements().first() {
            Some(Statement::OWord {
                label: OLabel::Expr(e),
                kind: OWord::Call(args),
            }) => Some(format!("{} {}", show(&p, *e), args.len())),
            _ => None,
        })
        .collect();
    assert_eq!(labels, ["(#2 * 10) 0", "#<sub> 1"]);
    assert_eq!(codes(&p), ["E-OWORD"]);
    assert_eq!(spanned(&p, text, "E-OWORD"), "O[1]");
}

#[test]
fn a_stray_comma_is_one_error_and_the_next_word_still_reads() {
    let text = "G01 X10, F500\n";
    let p = parse(text, Dialect::Syntec);
    assert_eq!(codes(&p), ["E-COMMA-WORD"]);
    assert_eq!(spanned(&p, text, "E-COMMA-WORD"), ",");
    assert_eq!(p.blocks[0].word(b'F').unwrap().value, 500.0);
}

#[test]
fn stray_characters_and_stray_text_are_one_error_per_run() {
    let text = "T1 S__;\nN100;副程式代號\nN100;subprogram label\nG1 X$ Y1\n";
    let p = parse(text, Dialect::Syntec);
    let got: Vec<(&str, &str)> = p
        .diagnostics
        .iter()
        .map(|d| (d.code, &text[d.span.range()]))
        .collect();
    assert_eq!(
        got,
        [
            ("E-WORD-VALUE", "S"),
            ("E-SYNTAX-CHAR", "__"),
            ("E-SYNTAX-CHAR", "副程式代號"),
            ("E-WORD-VALUE", "subprogram"),
            ("E-WORD-VALUE", "label"),
            ("E-WORD-VALUE", "X"),
            ("E-SYNTAX-CHAR", "$"),
        ]
    );
    assert!(p.diagnostics[1].message.contains("characters `__`"));
    assert!(p.diagnostics[6].message.contains("character `$`"));
    // A letter next to a letter is still reported on its own (`IO.` for `I0.`).
    let p = parse("X0. IO.\n", Dialect::Syntec);
    assert_eq!(codes(&p), ["E-WORD-VALUE", "E-WORD-VALUE", "E-SYNTAX-CHAR"]);
}

#[test]
fn errors_next_to_multibyte_characters_do_not_split_them() {
    for text in ["IF€", "iF€", "IF[1]€", "WHILE[1]€", "IF[1]", "If\u{FFFC}"] {
        let p = parse(text, Dialect::Fanuc);
        assert!(!p.diagnostics.is_empty(), "{text}");
        for d in &p.diagnostics {
            let (s, e) = (d.span.start as usize, d.span.end as usize);
            assert!(
                e <= text.len() && text.is_char_boundary(s) && text.is_char_boundary(e),
                "{text}: {d:?}"
            );
        }
    }
}

#[test]
fn linuxcnc_takes_g80_with_another_motion_code() {
    // rs274 accepts `G0 G80` (the cameo.nc header) and moves with G0; two real motions conflict.
    let p = parse(
        "G00 G17 G21 G40 G49 G80 G90\nG80 G1 X1 F10\n",
        Dialect::LinuxCnc,
    );
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    let text = "G0 G80 G1 X1\nG81 G0 X1 Z-1 R1\n";
    let p = parse(text, Dialect::LinuxCnc);
    let got: Vec<(&str, &str)> = p
        .diagnostics
        .iter()
        .map(|d| (d.code, &text[d.span.range()]))
        .collect();
    assert_eq!(
        got,
        [("E-MODAL-CONFLICT", "G1"), ("E-MODAL-CONFLICT", "G0")]
    );
}

#[test]
fn long_lines_of_brackets_and_words_parse_in_one_pass() {
    // Many sibling brackets on one line: nesting is tracked as it goes, not rescanned.
    let siblings = format!("#1={}1\n", "[1]+".repeat(200_000));
    let p = parse(&siblings, Dialect::Fanuc);
    assert!(p.diagnostics.is_empty(), "{:?}", &p.diagnostics[..1]);
    // A 250,000-word line (1 MB, just under the line-length limit).
    let words = format!("G01{}\n", " X1.".repeat(250_000));
    let p = parse(&words, Dialect::Fanuc);
    assert_eq!(p.blocks[0].words.len(), 250_001);
    assert!(p.diagnostics.iter().all(|d| d.code == "E-WORD-TWICE"));
}
