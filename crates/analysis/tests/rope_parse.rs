//! A program edited as a rope is parsed and located from the rope in place: the result is the
//! same as from the text as one string (blocks, diagnostics, spans, problems), whatever the
//! chunks the rope holds the text in.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::sync::Arc;

use proptest::prelude::*;
use ropey::{Rope, RopeBuilder};
use swarf_analysis::{Job, OpenFile, PendingAnalysis, ProgramText, RopeLines};
use swarf_interp::Setup;
use swarf_syntax::{Dialect, ParseRun, Program};

/// The rope of `text` built from pieces of `piece` bytes (cut at character boundaries), so its
/// chunk boundaries fall inside lines, multibyte characters' neighbours and `\r\n` pairs alike.
fn rope_in_pieces(text: &str, piece: usize) -> Rope {
    let mut builder = RopeBuilder::new();
    let mut at = 0;
    while at < text.len() {
        let mut end = (at + piece.max(1)).min(text.len());
        while !text.is_char_boundary(end) {
            end += 1;
        }
        builder.append(&text[at..end]);
        at = end;
    }
    builder.finish()
}

/// Parses the rope's lines in place, `per_step` lines per step.
fn parse_rope(rope: &Rope, dialect: Dialect, per_step: usize) -> Program {
    let mut run = ParseRun::new(dialect);
    let mut joined = String::new();
    while !run.step_from(&mut RopeLines::new(rope, &mut joined), per_step) {}
    run.finish()
}

/// Whether some line of the rope is split between two chunks.
fn a_line_straddles_chunks(rope: &Rope) -> bool {
    let chunks: Vec<&str> = rope.chunks().collect();
    chunks.len() > 1
        && chunks[..chunks.len() - 1]
            .iter()
            .any(|c| !c.ends_with('\n'))
}

/// A program with every kind of line the reader treats specially.
fn mixed_program(lines: usize) -> String {
    let mut text = String::from("%\r\nO1234 (主程序 铣削)\r\n");
    for i in 0..lines {
        let line = match i % 9 {
            0 => format!("N{i} G01 X{}. Y-{}.5 F800 ; 注释 {i}\r\n", i % 71, i % 13),
            1 => format!("G02 X{} Y{} I1.5 J0 (圆弧 µm)\n", i % 50, i % 20),
            2 => "#100 = [#1 + 2] * SIN[30]\n".to_string(),
            3 => format!("G01 X$ Y{i}\n"),
            4 => format!("(一条很长的注释 {})\n", "长".repeat(400 + i % 300)),
            5 => "\n".to_string(),
            6 => "IF [#100 GT 2] GOTO 10\r\n".to_string(),
            7 => format!("/ M98 P{} ;\n", 2000 + i % 3),
            _ => format!("G0 Z{i}.\t; é\n"),
        };
        text.push_str(&line);
    }
    text.push_str("M30\r\n%\r\n(after the tape end 尾)\n  \n");
    text
}

#[test]
fn parsing_a_rope_in_place_gives_the_program_of_the_flat_text() {
    let text = mixed_program(600);
    for piece in [7, 64, 333, 1000, 4096] {
        let rope = rope_in_pieces(&text, piece);
        assert_eq!(rope.to_string(), text);
        assert!(a_line_straddles_chunks(&rope), "pieces of {piece} bytes");
        for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
            let flat = swarf_syntax::parse(&text, dialect);
            assert!(
                flat.diagnostics
                    .iter()
                    .any(|d| d.code == "N-AFTER-TAPE-END"),
                "the text after the closing % is reported"
            );
            assert!(flat.blocks.len() > 400, "{}", flat.blocks.len());
            for per_step in [1, 5, 1000, usize::MAX] {
                let in_place = parse_rope(&rope, dialect, per_step);
                assert_eq!(
                    in_place, flat,
                    "{dialect:?}, pieces {piece}, {per_step}/step"
                );
            }
        }
    }
}

#[test]
fn a_rope_edited_in_place_parses_as_its_text() {
    let mut text = mixed_program(300);
    let mut rope = Rope::from_str(&text);
    // Edits split and merge the rope's chunks where they fall.
    for (i, insert) in ["G01 X$\r\n", "(中文)", "%\n", ";", "\r\n"]
        .iter()
        .enumerate()
    {
        let at_char = rope.len_chars() * (i + 1) / 7;
        rope.insert(at_char, insert);
        let at = text
            .char_indices()
            .nth(at_char)
            .map_or(text.len(), |(b, _)| b);
        text.insert_str(at, insert);
        assert_eq!(rope.to_string(), text);
        assert_eq!(
            parse_rope(&rope, Dialect::Fanuc, 17),
            swarf_syntax::parse(&text, Dialect::Fanuc)
        );
    }
}

/// Analyses `text` opened beside `others`, 50 blocks' worth a step.
fn analyse_in_steps(
    text: ProgramText,
    others: Vec<OpenFile>,
) -> (swarf_analysis::Results, swarf_analysis::Kept) {
    let mut pending = PendingAnalysis::start(Job {
        generation: 3,
        text,
        dialect: Dialect::Fanuc,
        setup: Setup::default(),
        others: Some(others),
        lod: None,
    });
    while !pending.step(50) {}
    pending.finish()
}

#[test]
fn an_analysis_of_a_rope_locates_its_problems_as_the_flat_one() {
    let text = mixed_program(400);
    let rope = rope_in_pieces(&text, 97);
    let flat_text = ProgramText::Flat(Arc::new(text.clone()));
    let rope_text = ProgramText::Rope(rope);
    let (flat, flat_kept) = analyse_in_steps(flat_text.clone(), Vec::new());
    let (roped, roped_kept) = analyse_in_steps(rope_text.clone(), Vec::new());
    assert!(flat.problems.len() > 40, "{}", flat.problems.len());
    assert!(flat.problems.iter().any(|p| p.code == "E-SYNTAX-CHAR"));
    assert_eq!(roped.problems, flat.problems);
    assert_eq!(roped_kept.program, flat_kept.program);
    assert_eq!(roped.stats, flat.stats);
    let lines = &flat_kept.program.lines;
    for line in [0, 1, 2, 6, 99, 1999, 100_000] {
        assert_eq!(
            rope_text.line(lines, line),
            flat_text.line(lines, line),
            "line {line}"
        );
    }
    assert_eq!(rope_text.line(lines, 1), "O1234 (主程序 铣削)");
}

#[test]
fn a_program_calling_another_tab_held_as_a_rope_links_it() {
    let main = "O1\nM98 P2000\nM30\n";
    let sub = "O2000\nG01 X$ Y1\nM99\n";
    let run = |t: ProgramText| {
        analyse_in_steps(
            ProgramText::Rope(Rope::from_str(main)),
            vec![OpenFile {
                name: "O2000.nc".to_string(),
                revision: 1,
                text: t,
            }],
        )
        .0
    };
    let flat = run(ProgramText::Flat(Arc::new(sub.to_string())));
    let roped = run(ProgramText::Rope(rope_in_pieces(sub, 5)));
    assert!(!flat.elsewhere.is_empty());
    assert!(
        flat.elsewhere
            .iter()
            .all(|p| p.file == "O2000.nc" && p.problem.line == 2),
        "{:?}",
        flat.elsewhere
    );
    assert_eq!(roped.elsewhere, flat.elsewhere);
    assert_eq!(roped.problems, flat.problems);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn any_text_in_any_chunks_parses_as_the_flat_text(
        lines in proptest::collection::vec(
            proptest::string::string_regex(
                "[GMNOXYZIJPF0-9 .;/%()#\\[\\]=+*\\t\\r$注释铣é-]{0,60}"
            ).unwrap(),
            0..60,
        ),
        piece in 1usize..200,
        per_step in 1usize..20,
        crlf in any::<bool>(),
    ) {
        let text = lines.join(if crlf { "\r\n" } else { "\n" });
        let rope = rope_in_pieces(&text, piece);
        for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
            let flat = swarf_syntax::parse(&text, dialect);
            // Debug text: a NaN in a parsed value compares unequal to itself.
            prop_assert_eq!(
                format!("{:?}", parse_rope(&rope, dialect, per_step)),
                format!("{flat:?}")
            );
        }
    }
}
