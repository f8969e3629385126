//! `swarf stats` runs a program piece by piece as it parses it, keeping none of its blocks, and
//! falls back to the whole program for one that jumps, loops or calls: its report and
//! diagnostics must be those of the whole program held in memory (`--whole`).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::fmt::Write as _;
use std::path::Path;

#[path = "../../../tests/support/programs.rs"]
mod programs;
use programs::{check_each, corpus, programs_under};

/// Exit status, the JSON report without its timing, and the diagnostics.
fn stats(file: &Path, dialect: &str, whole: bool) -> (i32, String, String) {
    stats_with(file, dialect, if whole { "--whole" } else { "" })
}

/// [`stats`] with an extra option (`--whole`, or none).
fn stats_with(file: &Path, dialect: &str, option: &str) -> (i32, String, String) {
    let mut out = Vec::new();
    let mut err = Vec::new();
    let file = file.to_str().unwrap();
    let mut args = vec!["swarf", "stats", file, "--json", "--dialect", dialect];
    if !option.is_empty() {
        args.push(option);
    }
    let code = swarf_cli::run(args, &mut out, &mut err);
    let mut report: serde_json::Value = serde_json::from_slice(&out).unwrap();
    report
        .as_object_mut()
        .unwrap()
        .remove("interpretation_ms")
        .unwrap();
    (code, report.to_string(), String::from_utf8(err).unwrap())
}

fn assert_same(file: &Path, dialect: &str) {
    let pieces = stats(file, dialect, false);
    let whole = stats(file, dialect, true);
    assert_eq!(pieces, whole, "{} read as {dialect}", file.display());
}

/// A long program that runs straight through, with what a piece boundary must carry over: a
/// variable, a corner held for the next move, a canned cycle's modal data, arcs, a tool change,
/// and an error and warnings for the diagnostics.
fn long_program(lines: usize, tail: &str) -> String {
    let mut text = String::from("%\nO1000 (LONG)\nG90 G21 G17 G54\n#1=2.5\nT1 M6\nS1200 M3\n");
    for i in 0..lines {
        let x = f64::from(u32::try_from(i % 200).unwrap()) * 0.5;
        let y = f64::from(u32::try_from(i / 200).unwrap()) * 0.25;
        match i % 997 {
            0 => writeln!(text, "N{i} G0 X{x:.3} Y{y:.3} Z#1").unwrap(),
            1 => writeln!(text, "G81 X{x:.3} Y{y:.3} R1. Z-3. F80.").unwrap(),
            2 => writeln!(text, "X{:.3}", x + 1.0).unwrap(),
            3 => writeln!(text, "G80 G1 X{x:.3} Y{y:.3} ,C0.5 F500.").unwrap(),
            4 => writeln!(text, "G2 X{:.3} Y{y:.3} R2.", x + 4.0).unwrap(),
            5 => writeln!(text, "G1 X{x:.3} Y{y:.3} Q7").unwrap(),
            6 => writeln!(text, "G1 X{x} Y{y:.3} (no point)").unwrap(),
            _ => writeln!(text, "G1 X{x:.3} Y{y:.3} Z-1.").unwrap(),
        }
    }
    text.push_str(tail);
    text.push_str("M30\n%\n");
    text
}

#[test]
fn a_long_straight_program_reads_the_same_in_pieces() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("long.nc");
    std::fs::write(&file, long_program(30_000, "")).unwrap();
    for dialect in ["fanuc", "syntec", "linuxcnc"] {
        assert_same(&file, dialect);
    }
    let (_, report, diags) = stats(&file, "fanuc", false);
    assert!(report.contains("\"blocks\":30006"), "{report}");
    assert!(
        !diags.is_empty(),
        "the program's problems should be reported"
    );
}

#[test]
fn a_call_after_many_pieces_runs_the_program_whole() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("calls.nc");
    let tail = "M98 P2000\nM30\nO2000\nG91 G1 X1. F100.\nM99\n";
    std::fs::write(&file, long_program(20_000, tail)).unwrap();
    assert_same(&file, "fanuc");
    let (_, report, _) = stats(&file, "fanuc", false);
    // The subprogram ran: its move is in the toolpath.
    let (_, without, _) = {
        let plain = dir.path().join("plain.nc");
        std::fs::write(&plain, long_program(20_000, "")).unwrap();
        stats(&plain, "fanuc", false)
    };
    let motions = |r: &str| -> u64 {
        let v: serde_json::Value = serde_json::from_str(r).unwrap();
        v["motions"].as_u64().unwrap()
    };
    assert_eq!(motions(&report), motions(&without) + 1);
}

/// A long program in bytes that are not plain UTF-8 far into the file (read as it runs, it is
/// decoded whole and run again), with a byte-order mark, with Windows line endings, and with
/// text after its closing tape mark, far from where the file ends: each reads as it does whole.
#[test]
fn a_long_file_read_as_it_runs_reads_as_it_does_whole() {
    let dir = tempfile::tempdir().unwrap();
    let text = long_program(30_000, "");
    let gbk = {
        // `(加工)` in GB18030, after most of the program has run.
        let cut = text.len() - 2_000;
        let cut = cut + text[cut..].find('\n').unwrap() + 1;
        let mut bytes = text.as_bytes()[..cut].to_vec();
        bytes.extend_from_slice(b"(\xBC\xD3\xB9\xA4)\n");
        bytes.extend_from_slice(&text.as_bytes()[cut..]);
        bytes
    };
    let bom = [&[0xEF, 0xBB, 0xBF][..], text.as_bytes()].concat();
    let crlf = text.replace('\n', "\r\n").into_bytes();
    let after_end = format!("{text}{}", "G1 X$ (after the end)\n".repeat(20_000)).into_bytes();
    for (name, bytes) in [
        ("gbk.nc", gbk),
        ("bom.nc", bom),
        ("crlf.nc", crlf),
        ("after-end.nc", after_end),
    ] {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        assert_same(&file, "fanuc");
        let (code, report, diags) = stats(&file, "fanuc", false);
        assert_eq!(code, 1, "{name}: the program's one error");
        assert!(report.contains("\"motions\":"), "{name}");
        if name == "after-end.nc" {
            assert!(diags.contains("N-AFTER-TAPE-END"), "{diags}");
        }
        if name == "gbk.nc" {
            // Decoded, not replaced: no encoding error.
            assert!(!diags.contains("E-ENCODING"), "{diags}");
        }
    }
}

/// Programs a few pieces long, which the running thread may read to their end itself before
/// the reading thread is ready to take over (or only their first pieces), read as they do
/// whole: plain, not plain UTF-8 from their first line, and calling a subprogram at the end.
/// The shortest is longer than a piece in bytes but not in lines, so its first piece is all
/// of it.
#[test]
fn a_program_of_a_few_pieces_reads_as_it_does_whole() {
    let dir = tempfile::tempdir().unwrap();
    let comment = format!(" ({})", "-".repeat(600));
    for lines in [100, 1_200, 2_500, 5_000, 10_000] {
        let mut text = long_program(lines, "");
        if lines == 100 {
            text = text.replace('\n', &format!("{comment}\n"));
        }
        let gbk = [&b"(\xBC\xD3\xB9\xA4)\n"[..], text.as_bytes()].concat();
        let call = long_program(lines, "M98 P2000\nM30\nO2000\nG1 X1\nM99\n");
        for (name, bytes) in [
            ("plain", text.into_bytes()),
            ("gbk", gbk),
            ("call", call.into_bytes()),
        ] {
            let file = dir.path().join(format!("{name}-{lines}.nc"));
            std::fs::write(&file, &bytes).unwrap();
            assert_same(&file, "fanuc");
        }
    }
}

#[test]
fn a_loop_after_the_end_in_the_same_piece_runs_the_program_whole() {
    // The program ends in a piece that goes on with a loop, closed in the next piece: the
    // blocks after the end were never run, but they still send the program to be read whole,
    // where the loop is seen closed.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("after-end.nc");
    let mut tail = String::from("M30\n#1=1\nWHILE[#1 LT 3]DO1\n");
    for _ in 0..1100 {
        tail.push_str("G1 X1.\n");
    }
    tail.push_str("#1=#1+1\nEND1\n");
    std::fs::write(&file, long_program(20_000, &tail)).unwrap();
    assert_same(&file, "fanuc");
    let (_, _, diags) = stats(&file, "fanuc", false);
    assert!(!diags.contains("E-MACRO-LOOP"), "{diags}");
}

#[test]
fn the_examples_read_the_same_in_pieces() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = programs_under(&root.join("assets/examples"));
    files.extend(programs_under(&root.join("tests/golden")));
    assert!(files.len() >= 5);
    for file in &files {
        for dialect in ["fanuc", "syntec", "lnc", "kt", "gsk", "linuxcnc"] {
            assert_same(file, dialect);
        }
    }
}

#[test]
fn the_corpus_reads_the_same_in_pieces() {
    let Some(corpus) = corpus() else {
        return;
    };
    let files = programs_under(&corpus);
    assert!(!files.is_empty());
    check_each(&files, |file| {
        for dialect in ["fanuc", "linuxcnc"] {
            assert_same(file, dialect);
        }
    });
}
