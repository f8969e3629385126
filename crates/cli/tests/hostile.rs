//! Hostile inputs: every one finishes with diagnostics and exit status 0 or 1, never a panic,
//! a hang or a usage error.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;

/// Runs `swarf ARGS` in-process; returns the exit status and standard error.
fn swarf(args: &[&str]) -> (i32, String) {
    let (code, _, err) = support::swarf(args);
    (code, err)
}

/// The start of a long text, for failure messages.
fn head(text: &str) -> String {
    text.chars().take(2000).collect()
}

/// A deterministic byte soup (xorshift), so a failure can be reproduced.
fn random_bytes(n: usize, mut seed: u64) -> Vec<u8> {
    (0..n)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 24) as u8
        })
        .collect()
}

#[test]
fn hostile_inputs_end_with_diagnostics_not_panics() {
    let cases: Vec<(&str, Vec<u8>, &str, Option<&str>)> = vec![
        ("random bytes", random_bytes(256 << 10, 0x9E37_79B9_7F4A_7C15), "fanuc", None),
        ("nul bytes", b"G1 X1\0\0 Y2\n".repeat(1000), "fanuc", Some("E-")),
        ("unclosed comments", b"G1 X1 (never closed\n".repeat(1000), "fanuc", Some("E-COMMENT-UNCLOSED")),
        (
            "absurd numbers",
            b"G1 X1e308 Y99999999999999999999999999999999 Z-1e400 F1e300\nG2 X1 Y0 R0.0000000001\nG1 X.\nG4 P99999999999999\nS1e300 M3\n".to_vec(),
            "fanuc",
            Some("E-"),
        ),
        (
            "100k-deep brackets",
            format!("#1={}1{}\nG1 X#1\n", "[".repeat(100_000), "]".repeat(100_000)).into_bytes(),
            "fanuc",
            Some("E-"),
        ),
        ("endless WHILE", b"#1=0\nWHILE[1EQ1]DO1\n#1=#1+1\nEND1\nM30\n".to_vec(), "fanuc", Some("E-RUNAWAY")),
        (
            "endless M99 main with moves",
            b"G1 X1. F100\nX0\nM99\n".to_vec(),
            "fanuc",
            Some("N-M99-MAIN-REPEATS"),
        ),
        ("self-calling subprogram", b"O1\nM98 P1\nM99\n".to_vec(), "fanuc", Some("E-NESTING")),
        ("self-calling o-word", b"o100 sub\no100 call\no100 endsub\no100 call\nM2\n".to_vec(), "linuxcnc", Some("E-NESTING")),
        ("a million words on a line", format!("G1{}\n", " X1".repeat(1_000_000)).into_bytes(), "fanuc", Some("E-WORD-TWICE")),
        ("a 20 MB comment", format!("({})\nG0 X1\n", "x".repeat(20_000_000)).into_bytes(), "fanuc", None),
        ("empty file", Vec::new(), "fanuc", None),
        ("only newlines", b"\n".repeat(100_000), "fanuc", None),
        ("a billion arc turns", b"G2 X0 Y0 I1 P1000000000 F100\n".to_vec(), "linuxcnc", Some("E-NUMBER-RANGE")),
        ("a billion spiral turns", b"G2 X0 Y0 I1. L100000000 F100\n".to_vec(), "syntec", Some("E-NUMBER-RANGE")),
        ("a billion subprogram repeats", b"M98 P100 L999999999\nM30\nO100\nG1 X1. F100\nM99\n".to_vec(), "fanuc", Some("E-NUMBER-RANGE")),
        ("a billion holes", b"G0 Z10.\nG99 G81 X1. R1. Z-1. K4000000000 F10\n".to_vec(), "syntec", Some("E-NUMBER-RANGE")),
        (
            "a repeat count past K's range",
            b"G0 X0 Y0 Z10.\nG91 G81 X1. Y1. Z-5. R2. K999999999 F100\nG80\nM30\n".to_vec(),
            "fanuc",
            Some("E-NUMBER-RANGE"),
        ),
        (
            "a billion LinuxCNC repeats in one block",
            b"G0 X0 Y0 Z10\nG91 G81 X1 Y1 Z-5 R2 L1000000000 F100\nG80\nM2\n".to_vec(),
            "linuxcnc",
            Some("E-MOTION-LIMIT"),
        ),
        (
            "a billion pecks in one hole",
            b"G0 X0 Y0 Z10.\nG83 X1. Y1. Z-99999.999 R2. Q0.001 F100\nG80\nM30\n".to_vec(),
            "fanuc",
            Some("E-MOTION-LIMIT"),
        ),
        (
            "a peck too small to go deeper",
            b"G0 X0 Y0 Z10.\n#1=1/100000000/100000000/10\nG83 X1. Y1. Z-50. R2. Q#1 F100\nG80\nM30\n".to_vec(),
            "fanuc",
            Some("E-CYCLE-PECK"),
        ),
        (
            "Syntec peck tapping with a tiny peck",
            b"M3 S100\nG0 X0 Y0 Z10.\n#1=0.0000001\nG84 X1. Y1. Z-1000. R2. Q#1 F100\nG80\nM30\n".to_vec(),
            "syntec",
            Some("E-MOTION-LIMIT"),
        ),
        (
            "an endless loop of full circles",
            b"G0 X0 Y0 Z0\nN10 G2 X0 Y0 I10. F100\nGOTO10\n".to_vec(),
            "fanuc",
            Some("E-MOTION-LIMIT"),
        ),
        ("a huge hole grid", b"G91 G81 Z-10. R5. K0 F100\nG137.1 X0 Y0 I1. P9999 J1. K9999\n".to_vec(), "syntec", Some("E-PATTERN-SIZE")),
        ("invalid UTF-8 and GBK mix", b"G1 X1 (\xd6\xd0\xce\xc4)\n\xff\xfe G0 X2\n".to_vec(), "fanuc", None),
    ];
    let dir = tempfile::tempdir().unwrap();
    let setup = dir.path().join("SETUP.toml");
    // Smaller budgets keep the endless programs quick; the limits are the same mechanism.
    std::fs::write(
        &setup,
        "[machine]\nmax_blocks = 200000\nmax_motions = 50000\n",
    )
    .unwrap();
    for (name, bytes, dialect, expect) in cases {
        let file = dir.path().join("hostile.nc");
        std::fs::write(&file, &bytes).unwrap();
        let file = file.to_str().unwrap();
        for command in ["check", "stats"] {
            let (code, err) = swarf(&[
                command,
                file,
                "--dialect",
                dialect,
                "--setup",
                setup.to_str().unwrap(),
            ]);
            assert!(
                code == 0 || code == 1,
                "{name} ({command}): exit {code}\n{}",
                head(&err)
            );
            if let Some(code_prefix) = expect {
                assert!(
                    err.contains(&format!("[{code_prefix}")),
                    "{name} ({command}): no {code_prefix} diagnostic in\n{}",
                    head(&err)
                );
            }
        }
    }
}

#[test]
fn every_diagnostic_of_a_broken_file_is_printed() {
    // Two errors a line on 100,000 lines: all printed, in order, the last ones too.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("broken.nc");
    std::fs::write(&file, "QQ\n".repeat(100_000)).unwrap();
    let (code, err) = swarf(&["check", file.to_str().unwrap(), "--dialect", "fanuc"]);
    assert_eq!(code, 1);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 200_000, "{}", head(&err));
    assert!(lines[0].ends_with(":1:1: error[E-WORD-VALUE]: address `Q` needs a number after it"));
    assert!(
        lines[199_999].contains(":100000:2: error[E-WORD-VALUE]"),
        "{}",
        lines[199_999]
    );
}

/// A called subroutine is read only from the program's own folder: a name with a folder, `..`
/// or a root is refused with an error, and no other file is read (nor quoted).
#[test]
fn a_call_never_reads_a_file_outside_the_program_folder() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("job");
    std::fs::create_dir(&inner).unwrap();
    std::fs::write(
        dir.path().join("secret.ngc"),
        "o<secret> sub\n(SECRET-TEXT)\nG0 X99\no<secret> endsub\n",
    )
    .unwrap();
    let secret = dir.path().join("secret.ngc");
    for call in [
        "o<../secret> call".to_string(),
        format!("o<{}> call", secret.display()),
        "o</etc/passwd> call".to_string(),
    ] {
        let file = inner.join("main.ngc");
        std::fs::write(&file, format!("G21\n{call}\nM2\n")).unwrap();
        let (code, err) = swarf(&["check", file.to_str().unwrap(), "--dialect", "linuxcnc"]);
        assert_eq!(code, 1, "{call}: {err}");
        assert!(
            err.contains("E-OWORD") && err.contains("only beside the program"),
            "{call}: {err}"
        );
        assert!(
            !err.contains("SECRET") && !err.contains("root:"),
            "{call}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{call}: {err}");
    }
}

/// A warning met at every pass of an endless loop is printed once with its count; past a
/// thousand different ones, `check` says how many more there were.
#[test]
fn check_prints_a_repeated_diagnostic_once_and_counts_the_ones_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("loop.nc");
    let looped = format!("WHILE [1 EQ 1] DO1\n{}END1\n", "G05.1 Q1\n".repeat(10));
    std::fs::write(&file, looped).unwrap();
    let setup = dir.path().join("SETUP.toml");
    std::fs::write(&setup, "[machine]\nmax_blocks = 120000\n").unwrap();
    let (code, err) = swarf(&[
        "check",
        file.to_str().unwrap(),
        "--setup",
        setup.to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 11, "{err}");
    assert!(
        lines[0].ends_with("this block is not run (10000 times)"),
        "{err}"
    );
    assert!(lines[10].contains("error[E-RUNAWAY]"), "{err}");

    std::fs::write(&file, "G05.1 Q1\n".repeat(1200)).unwrap();
    let (code, err) = swarf(&["check", file.to_str().unwrap()]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1001, "{}", head(&err));
    assert!(
        lines[1000].contains(":1001:1: note[N-DIAGNOSTICS-LEFT-OUT]: 200 more diagnostics"),
        "{}",
        lines[1000]
    );
}

/// `stats` of programs whose numbers run away prints no `inf` or `NaN`: the block that
/// computes an absurd coordinate, feed or dwell is an error and the run stops there.
#[test]
fn stats_never_prints_inf_or_nan() {
    let huge = "#1=99999999\n#1=#1*#1\n#1=#1*#1\n#1=#1*#1\n#1=#1*#1\n#1=#1*#1\n";
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("absurd.nc");
    for text in [
        format!("{huge}G00 X#1\nG00 X-#1\n"),
        format!("{huge}G04 P#1\nG04 P#1\n"),
        "G51 X0 Y0 P99999999\nG00 X99999.\n".to_string(),
        format!(
            "#2=0.0000001\n{}G01 X1000. F#2\n",
            "#2=#2*#2*#2*#2\n".repeat(2)
        ),
    ] {
        std::fs::write(&file, &text).unwrap();
        for json in [false, true] {
            let mut args = vec!["stats", file.to_str().unwrap()];
            if json {
                args.push("--json");
            }
            let (code, out, err) = support::swarf(&args);
            assert_eq!(code, 1, "{text}: {err}");
            assert!(err.contains("error[E-COORDINATE-RANGE]"), "{text}: {err}");
            let lower = out.to_lowercase();
            assert!(
                !lower.contains("inf") && !lower.contains("nan"),
                "{text}: {out}"
            );
        }
    }
}

/// `canon` runs a program piece by piece until it finds that it needs the whole program (a
/// call after the moves here); the whole run then prints only the events not printed yet,
/// so every event is printed once, as a run of the whole program prints them.
#[test]
fn canon_prints_each_event_once_when_the_run_turns_whole() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("late-call.nc");
    let mut text = String::from("G90 G01 F500.\n");
    for i in 0..10_000 {
        text.push_str(&format!("X{i}. Y1.\n"));
    }
    text.push_str("M98 P100\nM30\nO100\nG00 Z5.\nM99\n");
    std::fs::write(&file, &text).unwrap();
    let (code, out, err) = support::swarf(&["canon", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let program = swarf_syntax::parse(&text, swarf_syntax::Dialect::Fanuc);
    let mut whole = swarf_interp::CanonRecorder::default();
    swarf_interp::run(&program, swarf_interp::Setup::default(), &mut whole);
    let expected: Vec<String> = whole
        .events
        .iter()
        .map(|(source, event)| event.to_json(*source).to_string())
        .collect();
    assert_eq!(out.lines().collect::<Vec<_>>(), expected);
}

/// A program, setup or called file larger than `--max-file-mb` is refused before it is read;
/// a device that never ends (`/dev/zero`) is read no further than the limit.
#[test]
fn a_file_larger_than_the_limit_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.nc");
    std::fs::write(&big, "G0 X1.\n".repeat(300_000)).unwrap();
    let big = big.to_str().unwrap();
    for command in ["check", "canon", "stats"] {
        let (code, err) = swarf(&[command, big, "--max-file-mb", "1"]);
        assert_eq!(code, 2, "{err}");
        assert_eq!(
            err.trim_end(),
            format!("swarf: {big} is larger than 1 MiB, the most read (--max-file-mb)")
        );
    }
    let (code, err) = swarf(&["check", big]);
    assert_eq!(code, 0, "{err}");
    #[cfg(unix)]
    {
        let (code, err) = swarf(&["check", big, "--setup", "/dev/zero", "--max-file-mb", "1"]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("setup: /dev/zero is larger than 1 MiB"),
            "{err}"
        );
        let (code, err) = swarf(&["check", "/dev/zero", "--max-file-mb", "1"]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("/dev/zero is larger than 1 MiB"), "{err}");
    }
}

/// A called program whose file is found and cannot be linked (a folder, too large, past the
/// most files a program links) is an error at the call that names the file and the reason.
#[test]
fn a_call_whose_file_cannot_be_read_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let main = dir.path().join("main.nc");
    std::fs::create_dir(dir.path().join("O1000")).unwrap();
    std::fs::write(dir.path().join("O2000.nc"), "G0 X1.\n".repeat(300_000)).unwrap();
    std::fs::write(&main, "M98 P1000\nM30\n").unwrap();
    let main = main.to_str().unwrap();
    let (code, err) = swarf(&["check", main]);
    assert_eq!(code, 1, "{err}");
    let folder = dir.path().join("O1000");
    assert_eq!(
        err.trim_end(),
        format!(
            "{main}:1:1: error[E-SUBPROGRAM]: program O1000 is not in this program: {} is not a file",
            folder.display()
        )
    );
    std::fs::write(main, "G65 P2000\nM30\n").unwrap();
    let (code, err) = swarf(&["check", main, "--max-file-mb", "1"]);
    assert_eq!(code, 1, "{err}");
    let big = dir.path().join("O2000.nc");
    assert!(
        err.contains(&format!(
            "error[E-SUBPROGRAM]: macro program O2000 is not in this program: {} is larger than 1 MiB",
            big.display()
        )),
        "{err}"
    );

    // Sixty-five called files: the last one is not looked for.
    let calls: String = (1..=65).map(|n| format!("M98 P{n}\n")).collect();
    std::fs::write(main, format!("{calls}M30\n")).unwrap();
    for n in 1..=65 {
        let called = dir.path().join(format!("O{n:04}.nc"));
        std::fs::write(called, "G91 G0 X1.\nM99\n").unwrap();
    }
    let (code, err) = swarf(&["check", main]);
    assert_eq!(code, 1, "{err}");
    assert_eq!(
        err.trim_end(),
        format!(
            "{main}:65:1: error[E-SUBPROGRAM]: program O0065 is not in this program: not looked for: the program links 64 files, the most it may"
        )
    );
}

/// A diagnostic in a linked file quotes a short excerpt of a long line there.
#[test]
fn a_linked_file_diagnostic_quotes_a_short_excerpt() {
    let dir = tempfile::tempdir().unwrap();
    let main = dir.path().join("main.nc");
    std::fs::write(&main, "M98 P3000\nM30\n").unwrap();
    let long = format!(
        "O<{}>\nG0 X1 {}\nM99\n",
        "p".repeat(50_000),
        "_".repeat(50_000)
    );
    std::fs::write(dir.path().join("O3000.nc"), long).unwrap();
    let (code, err) = swarf(&["check", main.to_str().unwrap()]);
    assert_eq!(code, 1, "{}", head(&err));
    assert!(
        err.contains("O3000.nc:2:7: error[E-SYNTAX-CHAR]"),
        "{}",
        head(&err)
    );
    for line in err.lines() {
        assert!(line.len() < 600, "{}", head(line));
    }
}

/// A file whose length differs after it is read from what it was before (here a file of the
/// kernel's, whose length reads as zero) gets a warning.
#[cfg(target_os = "linux")]
#[test]
fn a_file_that_changes_while_it_is_read_is_reported() {
    let (_, err) = swarf(&["check", "/proc/self/status"]);
    assert!(
        err.lines().next().unwrap().starts_with(
            "/proc/self/status:1:1: warning[W-FILE-CHANGED]: /proc/self/status changed while it was read"
        ),
        "{}",
        head(&err)
    );
}
