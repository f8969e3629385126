//! Every diagnostic code the language crate gives, each with its exact span and severity.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_syntax::{Dialect, Severity, decode, parse};

use Dialect::{Fanuc, Gsk, Kt, LinuxCnc, Lnc, Syntec};

/// (dialect, program, code, the text its span covers).
const CASES: &[(Dialect, &str, &str, &str)] = &[
    (Fanuc, "G02 X10. Y5.\n", "E-ARC-CENTER", "G02"),
    (Fanuc, "G91 G02 R5. F100\n", "E-ARC-NO-END", "G02"),
    (LinuxCnc, "G2 X1 Y1 R1 I1 F100\n", "E-ARC-R-AND-IJK", "R1"),
    (
        Fanuc,
        "G02 X10. Y0 R5. I5. F100\n",
        "W-ARC-R-AND-IJK",
        "R5.",
    ),
    (Syntec, "G03 X10. Y5. F100\n", "W-ARC-AS-LINE", "G03"),
    (
        Fanuc,
        "G0 X1. G134 X0 Y0 I10. J0 K6\n",
        "E-CODE-DIALECT",
        "G134",
    ),
    (Fanuc, "G321 X1.\n", "E-UNKNOWN-CODE", "G321"),
    (Fanuc, "G1.25 X1.\n", "E-CODE-NUMBER", "G1.25"),
    (Fanuc, "M321\n", "W-UNKNOWN-M", "M321"),
    (Kt, "G01 X10. ,C2. F100\n", "E-COMMA-WORD", ",C2."),
    (Lnc, "G01 X10. ,Q2. F100\n", "E-COMMA-WORD", ","),
    (Fanuc, "G00 X1. (open\n", "E-COMMENT-UNCLOSED", "(open"),
    (Fanuc, "#1=5+\n", "E-EXPR", ""),
    (Fanuc, "#1=[5+1\n", "E-EXPR-BRACKET", "[5+1"),
    (Fanuc, "#1=[[[[[[1]]]]]]\n", "E-EXPR-DEPTH", "[1]]]]]]"),
    (Fanuc, "END7\n", "E-LOOP-NUMBER", "END7"),
    (Fanuc, "#1 X5.\n", "E-MACRO-SYNTAX", "#1"),
    (LinuxCnc, "G0 G1 X1 F100\n", "E-MODAL-CONFLICT", "G1"),
    (Fanuc, "G0 G1 X1. F100\n", "W-MODAL-LAST", "G1"),
    (Lnc, "G54.1 P49 G00 X0 Y0\n", "E-NUMBER-RANGE", "P49"),
    (Fanuc, "G54.1 P301 G00 X0 Y0\n", "E-NUMBER-RANGE", "P301"),
    (LinuxCnc, "o100 goto\n", "E-OWORD", "goto"),
    (Fanuc, "O123456789\n", "E-PROGRAM-NUMBER", "O123456789"),
    (
        Lnc,
        "G02 G41 X10. Y10. R5. D1 F100\n",
        "E-SAME-BLOCK",
        "G41",
    ),
    (Kt, "G43 G04 P100 H1\n", "E-SAME-BLOCK", "G04"),
    (Fanuc, "G0 X1. N10\n", "E-SEQUENCE-NUMBER", "N10"),
    (Fanuc, "G0 X1. $\n", "E-SYNTAX-CHAR", "$"),
    (
        Fanuc,
        "G81 X1. Z-1. R1. F2=100\n",
        "E-WORD-INDEXED",
        "F2=100",
    ),
    (Fanuc, "G04\n", "E-WORD-MISSING", "G04"),
    (Fanuc, "G0 X1. X2.\n", "E-WORD-TWICE", "X2."),
    (LinuxCnc, "G0 X1 Q2\n", "E-WORD-UNUSED", "Q2"),
    (Fanuc, "G0 X1. Q2.\n", "W-WORD-UNUSED", "Q2."),
    (Fanuc, "G0 X\n", "E-WORD-VALUE", "X"),
    (Syntec, "G01 Z-10.0:\n", "W-STRAY-COLON", ":"),
    (
        Fanuc,
        "%\nG0 X1.\n%\nG0 X2.\n",
        "N-AFTER-TAPE-END",
        "G0 X2.",
    ),
    (
        Gsk,
        "G83.1 X10 Z-20 R-5 Q5000 E70 F100\n",
        "E-NUMBER-RANGE",
        "E70",
    ),
    (
        Syntec,
        "G81 X5. Y5. Z-10. R-5. F2=10.5\n",
        "E-NUMBER-RANGE",
        "F2=10.5",
    ),
    (Fanuc, "#1=1e3\n", "E-EXPR", "1e3"),
    (LinuxCnc, "#1=2.5E-2\n", "E-EXPR", "2.5E-2"),
    (Fanuc, "G00.9999999 X10.\n", "E-CODE-NUMBER", "G00.9999999"),
];

#[test]
fn every_code_has_its_exact_span() {
    for &(dialect, text, code, covered) in CASES {
        let p = parse(text, dialect);
        let d = p
            .diagnostics
            .iter()
            .find(|d| d.code == code)
            .unwrap_or_else(|| panic!("{dialect} {text:?}: no {code} in {:?}", p.diagnostics));
        assert_eq!(&text[d.span.range()], covered, "{dialect} {text:?} {code}");
        let expected = match code.as_bytes()[0] {
            b'E' => Severity::Error,
            b'W' => Severity::Warning,
            _ => Severity::Note,
        };
        assert_eq!(d.severity, expected, "{code}");
        // An error keeps its block from running; a warning does not.
        let block = p
            .blocks
            .iter()
            .find(|b| b.span.start <= d.span.start && d.span.start <= b.span.end);
        if let Some(block) = block {
            assert_eq!(
                block.has_error(),
                expected == Severity::Error,
                "{code}: {text:?}"
            );
        }
    }
}

#[test]
fn invalid_bytes_are_an_encoding_diagnostic() {
    let d = decode(&[b'G', b'0', b' ', 0xFF, 0xFE, b'\n']);
    assert_eq!(d.diagnostics[0].code, "E-ENCODING");
    assert_eq!(d.diagnostics[0].severity, Severity::Error);
}

#[test]
fn a_line_past_one_mebibyte_is_read_up_to_the_limit() {
    let text = format!("G1 X1. ({})\nG0 X2.\n", "é".repeat(700_000));
    let p = parse(&text, Dialect::Fanuc);
    let d = p
        .diagnostics
        .iter()
        .find(|d| d.code == "E-LINE-LENGTH")
        .expect("a line-length diagnostic");
    assert_eq!(d.span.start, 1 << 20);
    assert_eq!(d.span.end as usize, text.find('\n').unwrap());
    // The next line is read as usual.
    assert_eq!(p.blocks.last().unwrap().words[1].value, 2.0);
}

#[test]
fn standard_codes_a_manual_leaves_out_are_read_without_a_note() {
    for dialect in [Lnc, Kt, Gsk] {
        let p = parse("G17 G21 G40\nG0 X1. M03 S500\nM30\n", dialect);
        assert!(p.diagnostics.is_empty(), "{dialect}: {:?}", p.diagnostics);
    }
}
