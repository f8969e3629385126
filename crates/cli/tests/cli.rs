//! The CLI contract: output formats, exit statuses and golden canonical streams.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use std::path::{Path, PathBuf};
use support::swarf;

fn golden(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/golden")
        .join(name)
}

fn temp_file(dir: &tempfile::TempDir, name: &str, bytes: &[u8]) -> String {
    let p = dir.path().join(name);
    std::fs::write(&p, bytes).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn canon_matches_the_golden_streams() {
    for (name, setup) in [
        ("incremental", None),
        ("offsets", Some("offsets.setup.toml")),
    ] {
        let nc = golden(&format!("{name}.nc"));
        let mut args = vec!["canon".to_string(), nc.to_str().unwrap().to_string()];
        if let Some(s) = setup {
            args.push("--setup".into());
            args.push(golden(s).to_str().unwrap().to_string());
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, out, err) = swarf(&args);
        assert_eq!(code, 0, "{err}");
        let expected = std::fs::read_to_string(golden(&format!("{name}.jsonl"))).unwrap();
        assert_eq!(out, expected, "{name}");
    }
}

#[test]
fn check_prints_path_line_col_severity_code() {
    let dir = tempfile::tempdir().unwrap();
    let f = temp_file(&dir, "bad.nc", b"G90\nG01 X10 Y$ F100\n");
    let (code, out, err) = swarf(&["check", &f]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 2, "{err}");
    assert_eq!(
        lines[0],
        format!("{f}:2:9: error[E-WORD-VALUE]: address `Y` needs a number after it")
    );
    assert_eq!(
        lines[1],
        format!("{f}:2:10: error[E-SYNTAX-CHAR]: unexpected character `$`")
    );
}

#[test]
fn check_clean_file_exits_zero_and_warnings_do_not_fail() {
    let dir = tempfile::tempdir().unwrap();
    let ok = temp_file(&dir, "ok.nc", b"G0 X1.\n");
    assert_eq!(swarf(&["check", &ok]), (0, String::new(), String::new()));
    let warn = temp_file(&dir, "warn.nc", b"G0 X1. Q5.\n");
    let (code, _, err) = swarf(&["check", &warn, "--dialect", "syntec"]);
    assert_eq!(code, 0);
    assert!(err.contains("warning[W-WORD-UNUSED]"), "{err}");
}

#[test]
fn usage_and_io_problems_exit_two() {
    assert_eq!(swarf(&["check"]).0, 2);
    assert_eq!(swarf(&["check", "/nonexistent/x.nc"]).0, 2);
    let (code, _, err) = swarf(&["canon", "x.nc", "--dialect", "heidenhain"]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown dialect"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let f = temp_file(&dir, "a.nc", b"G0 X1\n");
    let bad_setup = temp_file(&dir, "s.toml", b"[work_offsets]\nG99 = [0, 0, 0]\n");
    let (code, _, err) = swarf(&["canon", &f, "--setup", &bad_setup]);
    assert_eq!(code, 2);
    assert!(err.contains("G99"), "{err}");
    assert_eq!(swarf(&["--help"]).0, 0);
}

#[test]
fn never_panics_on_hostile_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes: Vec<u8> = (0..=255u8).cycle().take(4096).collect();
    bytes.extend_from_slice(b"\n((((\n[[[[#1=\nG1 X1e999999\n\0\0\0");
    let f = temp_file(&dir, "junk.nc", &bytes);
    for cmd in ["check", "canon", "stats"] {
        let (code, _, _) = swarf(&[cmd, &f]);
        assert!(code == 0 || code == 1, "{cmd}: {code}");
    }
    let empty = temp_file(&dir, "empty.nc", b"");
    assert_eq!(swarf(&["stats", &empty]).0, 0);
}

#[test]
fn stats_reports_blocks_motions_bounds_and_time() {
    let (code, out, err) = swarf(&[
        "stats",
        golden("incremental.nc").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["blocks"], 11);
    assert_eq!(v["motions"], 7);
    assert_eq!(v["bounds"]["min"], serde_json::json!([0.0, 0.0, -1.0]));
    assert_eq!(v["bounds"]["max"], serde_json::json!([30.0, 30.0, 5.0]));
    assert_eq!(v["feed_mm"], 86.0);
    assert!(v["estimated_secs"].as_f64().unwrap() > 10.0);
    let (code, text, _) = swarf(&["stats", golden("incremental.nc").to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(text.contains("motions         7"), "{text}");
}

#[test]
fn stats_counts_the_holes_of_each_tool() {
    let dir = tempfile::tempdir().unwrap();
    let nc = temp_file(
        &dir,
        "holes.nc",
        b"T1 M06\nG0 X0 Y0 Z20.\nG99 G81 X10. Y10. R2. Z-5. F100\nX20.\nX30.\nG80\n\
          T2 M06\nG83 X10. Y30. R2. Z-12. Q4. F80\nG80\nM30\n",
    );
    let (code, out, err) = swarf(&["stats", &nc, "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["holes"], 4);
    assert_eq!(
        v["holes_per_tool"],
        serde_json::json!([{"tool": 1, "holes": 3}, {"tool": 2, "holes": 1}])
    );
    let (_, text, _) = swarf(&["stats", &nc]);
    assert!(text.contains("holes           4 (T1: 3, T2: 1)"), "{text}");
}

/// Every program of the shared peer corpus runs through `check` without a panic and with an
/// exit status of 0 or 1 (skipped when `../shared` is not beside the repository).
#[test]
fn the_shared_corpus_checks_without_panics() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if !root.is_dir() {
        eprintln!("skipped: {} is not present", root.display());
        return;
    }
    let mut stack = vec![root];
    let mut checked = 0;
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !["nc", "ngc", "gcode", "gc", "tap"].contains(&ext) {
                continue;
            }
            let p = path.to_str().unwrap();
            let (code, _, err) = swarf(&["check", p, "--dialect", "linuxcnc"]);
            assert!(code == 0 || code == 1, "{p}: exit {code}\n{err}");
            checked += 1;
        }
    }
    assert!(checked > 10, "only {checked} corpus programs found");
}

/// The README's code table is the one `swarf explain --table` prints from the code tables.
#[test]
fn the_readme_code_table_is_generated_from_the_code_tables() {
    let (code, out, _) = swarf(&["explain", "--table"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("| group | fanuc | syntec | lnc | kt | gsk | linuxcnc |"));
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    let start = readme.find("<!-- code-table:begin -->\n").unwrap() + 26;
    let end = readme.find("<!-- code-table:end -->").unwrap();
    assert_eq!(
        readme[start..end],
        out,
        "README.md's code table is stale: replace it with `swarf explain --table`"
    );
}

#[test]
fn explain_gives_a_diagnostic_codes_severity_and_meaning() {
    let (code, out, err) = swarf(&["explain", "E-ARC-RADIUS"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "E-ARC-RADIUS — error\n  An arc's R is smaller than half the distance from its start to its end point.\n"
    );
    assert_eq!(
        swarf(&["explain", " w-offset-unset "]).1.lines().next(),
        Some("W-OFFSET-UNSET — warning")
    );
    let (code, out, _) = swarf(&["explain", "N-PROBE", "--json"]);
    assert_eq!(code, 0);
    let items: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(items[0]["code"], "N-PROBE");
    assert_eq!(items[0]["severity"], "note");
    assert!(
        items[0]["summary"]
            .as_str()
            .unwrap()
            .contains("measuring move")
    );
    let (code, out, err) = swarf(&["explain", "E-NO-SUCH-THING"]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(
        err.contains("E-NO-SUCH-THING is not a diagnostic code"),
        "{err}"
    );
}

#[test]
fn explain_diagnostics_lists_every_code() {
    let registry = swarf_syntax::DIAGNOSTICS;
    let (code, out, _) = swarf(&["explain", "--diagnostics"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), registry.len());
    for (line, d) in lines.iter().zip(registry) {
        let words: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(words[..2], [d.code, d.severity.as_str()], "{line}");
        assert!(line.ends_with(d.summary), "{line}");
    }
    let (code, out, _) = swarf(&["explain", "--diagnostics", "--json"]);
    assert_eq!(code, 0);
    let items: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(items.as_array().unwrap().len(), registry.len());
    assert_eq!(items[0]["code"], registry[0].code);
}

/// docs/interpreter.md's list of diagnostics is the one `swarf explain --diagnostics --table`
/// prints from the registry.
#[test]
fn the_diagnostics_doc_is_generated_from_the_registry() {
    let (code, out, _) = swarf(&["explain", "--diagnostics", "--table"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("| code | severity | meaning |\n"));
    assert_eq!(out.lines().count(), swarf_syntax::DIAGNOSTICS.len() + 2);
    let doc = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/interpreter.md"),
    )
    .unwrap();
    let begin = "<!-- diagnostics:begin -->\n";
    let start = doc.find(begin).unwrap() + begin.len();
    let end = doc.find("<!-- diagnostics:end -->").unwrap();
    assert_eq!(
        doc[start..end],
        out,
        "docs/interpreter.md's diagnostics are stale: replace them with `swarf explain --diagnostics --table`"
    );
}

/// Subprograms in files beside the program are linked: `M98`/`M198 P1234` finds `O1234.nc`,
/// LinuxCNC's `o<name> call` finds `name.ngc`, and their diagnostics name their own file.
#[test]
fn calls_reach_programs_in_files_beside_the_program() {
    let dir = tempfile::tempdir().unwrap();
    let main = temp_file(
        &dir,
        "main.nc",
        b"G90 G0 X0 Y0\nM98 P1234\nM198 P1234\nM98 P2000\nM30\n",
    );
    temp_file(
        &dir,
        "O1234.nc",
        b"%\nO1234 (STEP)\nG91 G1 X10. F100\nY$\nG90\nM99\n%\n",
    );
    let (code, out, err) = swarf(&["canon", &main]);
    assert_eq!(code, 1, "{err}");
    let feeds: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["kind"] == "feed")
        .collect();
    // Called twice (M98 and M198), 10 mm further each time.
    assert_eq!(feeds.len(), 2, "{out}");
    assert_eq!(feeds[1]["to"], serde_json::json!([20.0, 0.0, 0.0]));
    // Events from the linked file name it, with their line there.
    assert!(feeds[0]["file"].as_str().unwrap().ends_with("O1234.nc"));
    assert_eq!(feeds[0]["line"], 3);
    // The linked file's error is reported in that file; the missing program in the main one.
    assert!(err.contains("O1234.nc:4:1: error[E-WORD-VALUE]"), "{err}");
    assert!(err.contains("main.nc:4:1: error[E-SUBPROGRAM]"), "{err}");

    let main = temp_file(&dir, "main.ngc", b"o<square> call [10]\nM2\n");
    temp_file(
        &dir,
        "square.ngc",
        b"o<square> sub\nG1 X#1 F100\nY#1\no<side> call\no<square> endsub\n",
    );
    temp_file(&dir, "side.ngc", b"o<side> sub\nG1 Z-1\no<side> endsub\n");
    let (code, out, err) = swarf(&["canon", &main, "--dialect", "linuxcnc"]);
    assert_eq!(code, 0, "{err}");
    let ends: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["kind"] == "feed")
        .map(|v| v["to"].clone())
        .collect();
    assert_eq!(
        ends,
        [
            serde_json::json!([10.0, 0.0, 0.0]),
            serde_json::json!([10.0, 10.0, 0.0]),
            serde_json::json!([10.0, 10.0, -1.0]),
        ]
    );
}

/// A file found by its name is the program it is named for, with an `O` line or without one;
/// an `O` line that says another number is warned of, and the file still runs as the one
/// called.
#[test]
fn a_file_found_by_its_name_is_the_program_called() {
    let dir = tempfile::tempdir().unwrap();
    let main = temp_file(
        &dir,
        "main.nc",
        b"G90 G0 X0 Y0\nM98 P5001\nM98 P5001\nM98 P5003\nM30\n",
    );
    temp_file(&dir, "5001.nc", b"G91 G1 X1. F100.\nM99\n");
    temp_file(&dir, "5003.nc", b"O5002\nG91 G1 Y1. F100.\nM99\n");
    let (code, out, err) = swarf(&["canon", &main]);
    assert_eq!(code, 0, "{err}");
    let feeds: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["kind"] == "feed")
        .collect();
    assert_eq!(feeds.len(), 3, "{out}");
    assert_eq!(feeds[1]["to"], serde_json::json!([2.0, 0.0, 0.0]));
    assert_eq!(feeds[2]["to"], serde_json::json!([2.0, 1.0, 0.0]));
    assert!(feeds[0]["file"].as_str().unwrap().ends_with("5001.nc"));
    assert_eq!(feeds[0]["line"], 1);
    assert!(!err.contains("E-SUBPROGRAM"), "{err}");
    assert!(
        err.contains("5003.nc:1:1: warning[W-PROGRAM-NUMBER]"),
        "{err}"
    );
}

/// Lines ended by `\r\r\n` (some Windows tools) or by a `\r` alone are lines, in every dialect,
/// and the diagnostics' line numbers count those ends.
#[test]
fn lines_ended_by_carriage_returns_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let f = temp_file(&dir, "crcrlf.ngc", b"G21 G90\r\r\nG0 X1 Y2\r\r\nM2\r\r\n");
    for dialect in ["linuxcnc", "fanuc", "syntec", "lnc", "kt", "gsk"] {
        let (_, out, err) = swarf(&["canon", &f, "--dialect", dialect]);
        assert!(!err.contains("E-SYNTAX-CHAR"), "{dialect}: {err}");
        assert!(
            out.lines().next().unwrap().contains("\"rapid\""),
            "{dialect}: {out}"
        );
    }
    let (code, out, err) = swarf(&["canon", &f, "--dialect", "linuxcnc"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err}");
    assert_eq!(
        out.lines().next().unwrap(),
        r#"{"line":3,"kind":"rapid","to":[1.0,2.0,0.0]}"#
    );
    let f = temp_file(&dir, "cr.nc", b"G21 G90\rG0 X1 Y2\rG1 X$\rM2\r");
    let (code, _, err) = swarf(&["check", &f, "--dialect", "linuxcnc"]);
    assert_eq!(code, 1);
    assert!(err.contains("cr.nc:3:4: error"), "{err}");
}
