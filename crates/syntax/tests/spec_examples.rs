//! The worked examples E1–E75 of the G-code reference (§7 of `gcode-reference.md`), parsed in
//! their manual's dialect: none may raise an error except the few the reference itself marks as
//! damaged in the source, and each example's parse is pinned by a snapshot.
//!
//! The reference lives outside the repository (`../shared/spec`); without it the test passes
//! with a note.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::fmt::Write as _;
use std::path::PathBuf;

use swarf_syntax::{
    Block, Dialect, Expr, ExprId, OLabel, OWord, Program, ProgramNumber, Severity, Statement,
    WordForm, parse,
};

/// Examples whose text is damaged in the source, with how many of each error code the damage
/// raises. Every other example must parse without an error.
const DAMAGED: &[(u32, &[(&str, usize)])] = &[
    // §7 E18 "ways to specify rigid slanted tapping" prints format lines, not a program: every
    // value is a `__` placeholder (`M29 S__;`, `G84.1 X__ C__ R__ P__ F__ K__ (M__) E __;`), so
    // each of the 32 placeholder words is an address without a number followed by `__`.
    (18, &[("E-SYNTAX-CHAR", 32), ("E-WORD-VALUE", 32)]),
    // §7 E30: "(`IO.` is OCR for `I0.`)". On each of the two lines `I` has no number, nor has
    // `O`, and the `.` is left over.
    (30, &[("E-SYNTAX-CHAR", 2), ("E-WORD-VALUE", 4)]),
    // E45's subprogram label `N100;subprogram label`: the source has the remark without `//`
    // (`[004 L2337]` reads `N100;副程式代號`); the reference does not flag it.
    (45, &[("E-WORD-VALUE", 2)]),
    // §7 E51: "⚠ `Y80.793.` has a stray `.` (OCR)."
    (51, &[("E-SYNTAX-CHAR", 1)]),
    // §7 E75: "(`X10,` is printed with a comma, ⚠ OCR)": `X10, F500`.
    (75, &[("E-COMMA-WORD", 1)]),
];

/// Examples of §7 that have no code block (E9 is a formula, E67 refers to §4.55).
const WITHOUT_CODE: &[u32] = &[9, 67];

fn reference() -> Option<String> {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/spec/gcode-reference.md");
    match std::fs::read_to_string(&path) {
        Ok(text) => Some(text),
        Err(err) => {
            eprintln!(
                "note: {} not readable ({err}); the worked examples are not checked",
                path.display()
            );
            None
        }
    }
}

/// The dialect of example `n`, as §7's contents line gives it: "E1–E6 KT, E7–E14 LNC, E15–E18
/// GSK, E19–E75 SYN".
fn dialect_of(n: u32) -> Dialect {
    match n {
        1..=6 => Dialect::Kt,
        7..=14 => Dialect::Lnc,
        15..=18 => Dialect::Gsk,
        _ => Dialect::Syntec,
    }
}

/// One worked example: its number and the text of each of its code blocks.
struct Example {
    number: u32,
    blocks: Vec<String>,
}

/// The examples of §7, in order: each `### En.` / `#### En.` heading and the fenced blocks under
/// it up to the next heading.
fn examples(reference: &str) -> Vec<Example> {
    let start = reference
        .find("\n## 7.")
        .expect("the reference has a §7 of worked examples");
    let section = &reference[start + 1..];
    let end = section.find("\n## 8.").unwrap_or(section.len());
    let section = &section[..end];

    let mut out: Vec<Example> = Vec::new();
    let mut fence: Option<String> = None;
    for line in section.lines() {
        if let Some(body) = fence.as_mut() {
            if line.trim_start().starts_with("```") {
                let body = fence.take().unwrap_or_default();
                out.last_mut()
                    .expect("a code block belongs to an example")
                    .blocks
                    .push(body);
            } else {
                body.push_str(line);
                body.push('\n');
            }
            continue;
        }
        if line.trim_start().starts_with("```") {
            if !out.is_empty() {
                fence = Some(String::new());
            }
            continue;
        }
        if line.starts_with('#') {
            let heading = line.trim_start_matches('#').trim_start();
            if let Some(rest) = heading.strip_prefix('E') {
                let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
                // `### E53–E64.` introduces a group and is not an example itself.
                if rest[digits.len()..].starts_with('.') {
                    out.push(Example {
                        number: digits.parse().expect("example number"),
                        blocks: Vec::new(),
                    });
                }
            }
        }
    }
    out
}

/// The example as the control would see it. §7's conventions: comments on KT/LNC/GSK blocks "were
/// prose next to the block and are shown here as `// …`", so for those dialects `//` to the end
/// of the line is the digest's annotation and is removed (Syntec reads `//` itself). A line of
/// dots (`...`, `…`, and the manuals' own `. .`) is an elision, and so is a trailing `. .` after
/// a block's `;`.
fn program_text(block: &str, dialect: Dialect) -> String {
    let mut out = String::new();
    for line in block.lines() {
        let line = if dialect == Dialect::Syntec {
            line
        } else {
            line.find("//").map_or(line, |at| &line[..at])
        };
        let line = match line.rfind(';') {
            Some(at) if is_elision(&line[at + 1..]) => &line[..=at],
            _ => line,
        };
        if is_elision(line) && !line.trim().is_empty() {
            continue;
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

fn is_elision(text: &str) -> bool {
    let text = text.trim();
    !text.is_empty() && text.chars().all(|c| matches!(c, '.' | '…' | ' '))
}

// ---- rendering ----

fn number(value: f64, has_point: bool) -> String {
    if has_point && value.fract() == 0.0 {
        format!("{value}.")
    } else {
        format!("{value}")
    }
}

fn expr(p: &Program, id: ExprId) -> String {
    let Some(node) = p.expr(id) else {
        return "?".into();
    };
    match &node.expr {
        Expr::Num(v) => format!("{v}"),
        Expr::Var(i) => format!("#{}", expr(p, *i)),
        Expr::Named(n) => format!("#<{n}>"),
        Expr::Neg(i) => format!("-{}", expr(p, *i)),
        Expr::Binary(op, a, b) => format!("[{} {} {}]", expr(p, *a), op.symbol(), expr(p, *b)),
        Expr::Call(f, a, None) => format!("{}[{}]", f.name(), expr(p, *a)),
        Expr::Call(f, a, Some(b)) => format!("{}[{},{}]", f.name(), expr(p, *a), expr(p, *b)),
    }
}

fn statement(p: &Program, stmt: &Statement) -> String {
    match stmt {
        Statement::Assign { target, value } => format!("{}={}", expr(p, *target), expr(p, *value)),
        Statement::Goto { target } => format!("GOTO{}", expr(p, *target)),
        Statement::If { cond, then } => format!("IF[{}] {}", expr(p, *cond), statement(p, then)),
        Statement::While {
            cond: Some(c),
            label,
        } => format!("WHILE[{}] DO{label}", expr(p, *c)),
        Statement::While { cond: None, label } => format!("DO{label}"),
        Statement::End { label } => format!("END{label}"),
        Statement::OWord { label, kind } => {
            let label = match label {
                OLabel::Number(n) => n.to_string(),
                OLabel::Name(n) => format!("<{n}>"),
                OLabel::Expr(e) => expr(p, *e),
            };
            format!("o{label} {}", o_word(p, kind))
        }
    }
}

fn o_word(p: &Program, kind: &OWord) -> String {
    let arg = |e: &Option<ExprId>| e.map_or(String::new(), |e| format!(" [{}]", expr(p, e)));
    match kind {
        OWord::Sub => "sub".into(),
        OWord::EndSub(e) => format!("endsub{}", arg(e)),
        OWord::Call(args) => {
            let args: Vec<String> = args.iter().map(|a| format!(" [{}]", expr(p, *a))).collect();
            format!("call{}", args.concat())
        }
        OWord::Return(e) => format!("return{}", arg(e)),
        OWord::If(c) => format!("if [{}]", expr(p, *c)),
        OWord::ElseIf(c) => format!("elseif [{}]", expr(p, *c)),
        OWord::Else => "else".into(),
        OWord::EndIf => "endif".into(),
        OWord::While(c) => format!("while [{}]", expr(p, *c)),
        OWord::EndWhile => "endwhile".into(),
        OWord::Do => "do".into(),
        OWord::Repeat(c) => format!("repeat [{}]", expr(p, *c)),
        OWord::EndRepeat => "endrepeat".into(),
        OWord::Break => "break".into(),
        OWord::Continue => "continue".into(),
    }
}

fn block_line(p: &Program, text: &str, block: &Block) -> String {
    let mut out = String::new();
    if let Some(level) = block.block_delete() {
        let _ = write!(out, "/{level} ");
    }
    match block.program() {
        Some(ProgramNumber::Number(n)) => {
            let _ = write!(out, "O{n} ");
        }
        Some(ProgramNumber::Name(n)) => {
            let _ = write!(out, "O<{n}> ");
        }
        None => {}
    }
    if let Some(n) = block.number() {
        let _ = write!(out, "N{n} ");
    }
    for w in &block.words {
        let value = match w.expr {
            Some(id) => expr(p, id),
            None => number(w.value, w.has_point),
        };
        let _ = match w.form {
            WordForm::Plain => write!(out, "{}{value} ", w.letter()),
            WordForm::Comma => write!(out, ",{}{value} ", w.letter()),
            WordForm::Indexed(i) => write!(out, "{}{i}={value} ", w.letter()),
        };
    }
    for s in block.statements() {
        let _ = write!(out, "{} ", statement(p, s));
    }
    if !block.comments().is_empty() {
        let _ = write!(out, "({}) ", block.comments().len());
    }
    if block.has_error() {
        out.push_str("!error ");
    }
    for d in p.diagnostics.iter().filter(|d| within(block, d.span)) {
        let _ = write!(out, "{}`{}` ", d.code, &text[d.span.range()]);
    }
    out.trim_end().to_string()
}

fn within(block: &Block, span: swarf_syntax::Span) -> bool {
    block.span.start <= span.start && span.start < block.span.end.max(block.span.start + 1)
}

/// The parse of one code block, one line per block, then any diagnostic outside every block.
fn render(p: &Program, text: &str) -> String {
    let mut out = String::new();
    for block in &p.blocks {
        out.push_str(&block_line(p, text, block));
        out.push('\n');
    }
    for d in &p.diagnostics {
        if !p.blocks.iter().any(|b| within(b, d.span)) {
            let _ = writeln!(
                out,
                "outside a block: {}`{}`",
                d.code,
                &text[d.span.range()]
            );
        }
    }
    out
}

#[test]
fn worked_examples_parse_in_their_dialect() {
    let Some(reference) = reference() else {
        return;
    };
    let examples = examples(&reference);
    let numbers: Vec<u32> = examples.iter().map(|e| e.number).collect();
    assert_eq!(numbers, (1..=75).collect::<Vec<_>>(), "§7 lists E1–E75");
    let without: Vec<u32> = examples
        .iter()
        .filter(|e| e.blocks.is_empty())
        .map(|e| e.number)
        .collect();
    assert_eq!(without, WITHOUT_CODE, "examples without a code block");

    let mut failures = Vec::new();
    for example in examples.iter().filter(|e| !e.blocks.is_empty()) {
        let n = example.number;
        let dialect = dialect_of(n);
        let mut snapshot = format!("dialect: {dialect}\n");
        let mut errors = Vec::new();
        for (i, block) in example.blocks.iter().enumerate() {
            let text = program_text(block, dialect);
            let p = parse(&text, dialect);
            let _ = writeln!(snapshot, "--- block {}", i + 1);
            snapshot.push_str(&render(&p, &text));
            errors.extend(
                p.diagnostics
                    .iter()
                    .filter(|d| d.severity == Severity::Error)
                    .map(|d| (d.code, text[d.span.range()].to_string())),
            );
        }
        let mut codes: Vec<(&str, usize)> = Vec::new();
        for (code, _) in &errors {
            match codes.iter_mut().find(|(c, _)| c == code) {
                Some((_, count)) => *count += 1,
                None => codes.push((code, 1)),
            }
        }
        codes.sort_unstable();
        let expected: &[(&str, usize)] = DAMAGED
            .iter()
            .find(|(m, _)| *m == n)
            .map_or(&[], |(_, codes)| codes);
        if codes != expected {
            failures.push(format!(
                "E{n} ({dialect}): errors {errors:?}, expected {expected:?}"
            ));
        }
        insta::assert_snapshot!(format!("E{n}"), snapshot);
    }
    assert!(
        failures.is_empty(),
        "worked examples with unexpected errors:\n{}",
        failures.join("\n")
    );
}
