//! Hostile programs end in bounded work and memory: repeated diagnostics are counted, not
//! repeated; endless loops and long expressions stop at the runaway limits, naming the loop; an
//! M99 in the main program runs one pass; absurd coordinates are an error. Every test measures
//! work (blocks, moves, diagnostics), never time.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_interp::{Canon, CanonRecorder, Interpreter, Piece, Setup, Sink, Source, Status};
use swarf_syntax::{Diagnostic, Dialect, Severity, parse};

/// Counts the moves it is given and keeps the largest coordinate, holding none of them.
#[derive(Default)]
struct Counter {
    moves: u64,
    largest: f64,
}

impl Sink for Counter {
    fn emit(&mut self, _: Source, event: &Canon) {
        if let Some(p) = event.end_point() {
            self.moves += 1;
            self.largest = self.largest.max(p.abs().max_element());
        }
    }
}

/// Runs `text` whole; the run's diagnostics and how many blocks it executed.
fn run(text: &str, dialect: Dialect, setup: Setup, sink: &mut dyn Sink) -> (Vec<Diagnostic>, u64) {
    let program = parse(text, dialect);
    assert!(
        program
            .diagnostics
            .iter()
            .all(|d| d.severity != Severity::Error),
        "{:?}",
        program.diagnostics
    );
    let mut interp = Interpreter::new(setup, dialect);
    while interp.step(&program, sink, 4096) == Status::Running {}
    (interp.take_diagnostics(), interp.executed_blocks())
}

fn codes(diags: &[Diagnostic]) -> Vec<&'static str> {
    diags.iter().map(|d| d.code).collect()
}

fn small_limits() -> Setup {
    let mut setup = Setup::default();
    setup.machine.max_blocks = 10_000;
    setup.machine.max_work = 1_000_000;
    setup.machine.max_motions = 1_000;
    setup
}

#[test]
fn a_warning_met_at_every_pass_is_reported_once_with_its_count() {
    let text = format!("WHILE [1 EQ 1] DO1\n{}END1\n", "G05.1 Q1\n".repeat(10));
    let (diags, blocks) = run(
        &text,
        Dialect::Fanuc,
        small_limits(),
        &mut Counter::default(),
    );
    assert_eq!(blocks, 10_000);
    let mut expected = vec!["W-NOT-INTERPRETED"; 10];
    expected.push("E-RUNAWAY");
    assert_eq!(codes(&diags), expected);
    // Twelve blocks a pass: 833 passes, and the WHILE and three lines of the last.
    for (i, d) in diags[..10].iter().enumerate() {
        let times = if i < 3 { 834 } else { 833 };
        assert!(
            d.message.ends_with(&format!(" ({times} times)")),
            "{}",
            d.message
        );
    }
    // The runaway names the loop and sits on its END line.
    let runaway = &diags[10];
    assert!(
        runaway
            .message
            .contains("in the loop from line 1 to the jump back at line 12"),
        "{}",
        runaway.message
    );
    assert_eq!(&text[runaway.span.range()], "END1");
}

#[test]
fn different_diagnostics_are_kept_up_to_a_thousand_then_counted() {
    let text = "G05.1 Q1\n".repeat(1500);
    let (diags, _) = run(
        &text,
        Dialect::Fanuc,
        Setup::default(),
        &mut Counter::default(),
    );
    assert_eq!(diags.len(), 1001);
    assert!(diags[..1000].iter().all(|d| d.code == "W-NOT-INTERPRETED"));
    let note = &diags[1000];
    assert_eq!(note.code, "N-DIAGNOSTICS-LEFT-OUT");
    assert!(
        note.message.starts_with("500 more diagnostics"),
        "{}",
        note.message
    );
    // At the first one left out: line 1001.
    assert_eq!(note.span.start as usize, 1000 * "G05.1 Q1\n".len());
}

#[test]
fn an_overtravel_in_a_loop_is_one_error_and_ends_the_run() {
    let mut setup = Setup::default();
    setup.machine.travel_mm = Some([[-100.0; 3], [100.0; 3]]);
    let text = "G01 F100\nWHILE [1 EQ 1] DO1\nX50.\nX150.\nX0\nEND1\n";
    let mut moves = Counter::default();
    let (diags, blocks) = run(text, Dialect::Fanuc, setup, &mut moves);
    assert_eq!(codes(&diags), ["E-OVERTRAVEL"]);
    assert!(
        diags[0].message.ends_with("(the run stops here)"),
        "{}",
        diags[0].message
    );
    assert_eq!(blocks, 4);
}

#[test]
fn an_error_met_again_ends_the_run() {
    // G01 without F alarms on the control; a loop brings the run back to it.
    let text = "WHILE [1 EQ 1] DO1\nG01 X10.\nX0\nEND1\n";
    let (diags, blocks) = run(
        text,
        Dialect::Fanuc,
        Setup::default(),
        &mut Counter::default(),
    );
    assert_eq!(codes(&diags), ["E-NO-FEED", "E-NO-FEED"]);
    assert!(
        diags[0]
            .message
            .contains("(2 times: the run came back to it"),
        "{}",
        diags[0].message
    );
    assert!(!diags[1].message.contains("times"), "{}", diags[1].message);
    // The loop's first pass, then its head and the failing block again.
    assert_eq!(blocks, 6);
}

#[test]
fn a_loop_of_long_expressions_stops_at_the_work_limit() {
    // About 2 KB of text: one assignment of a thousand terms, run over and over.
    let terms = vec!["1"; 1000].join("+");
    let text = format!("WHILE [1 EQ 1] DO1\n#1=[{terms}]\nEND1\n");
    assert!(text.len() < 2100);
    let (diags, blocks) = run(
        &text,
        Dialect::Fanuc,
        small_limits(),
        &mut Counter::default(),
    );
    assert_eq!(codes(&diags), ["E-RUNAWAY"]);
    assert!(
        diags[0].message.contains("[machine] max_work"),
        "{}",
        diags[0].message
    );
    // About 2,000 expression nodes a pass (a thousand numbers, 999 additions, the condition),
    // three blocks a pass: the work limit of a million ends it near 500 passes, long before
    // the block limit.
    assert!((1_450..=1_550).contains(&blocks), "{blocks} blocks");
    // The default limit bounds the same program the same way.
    assert!(Setup::default().machine.max_work <= 200_000_000);
}

#[test]
fn m99_in_the_main_program_runs_one_pass_with_a_note() {
    for (text, dialect) in [
        ("G91 G00 X1.\nM99\n", Dialect::Fanuc),
        ("O100\nG91 G01 X1. F100\nM99\n", Dialect::Fanuc),
        ("G91 G00 X1.\nN10 X1.\nM99 P10\n", Dialect::Syntec),
        ("G91 G00 X1.\nM99\n", Dialect::LinuxCnc),
    ] {
        let mut moves = Counter::default();
        let (diags, _) = run(text, dialect, Setup::default(), &mut moves);
        assert_eq!(codes(&diags), ["N-M99-MAIN-REPEATS"], "{text}");
        assert!(diags[0].message.starts_with("M99 in the main program"));
        assert_eq!(moves.moves, text.matches("X1.").count() as u64, "{text}");
    }
    // A missing target is still an error.
    let (diags, _) = run(
        "G00 X1.\nM99 P20\n",
        Dialect::Fanuc,
        Setup::default(),
        &mut Counter::default(),
    );
    assert_eq!(codes(&diags), ["E-MACRO-GOTO"]);
}

#[test]
fn m99_ends_a_program_run_piece_by_piece_without_needing_it_whole() {
    let program = parse("G91 G00 X1.\n#1=[#1+1]\nM99\n", Dialect::Fanuc);
    let mut interp = Interpreter::new(Setup::default(), Dialect::Fanuc);
    let mut moves = Counter::default();
    assert_eq!(interp.run_piece(&program, &mut moves), Piece::Ended);
    assert_eq!(moves.moves, 1);
    assert_eq!(codes(&interp.take_diagnostics()), ["N-M99-MAIN-REPEATS"]);
}

#[test]
fn endless_loops_with_moves_stop_at_the_limits_naming_the_loop() {
    for (text, code, line) in [
        (
            "G01 F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n",
            "E-MOTION-LIMIT",
            "at line 5",
        ),
        (
            "G01 F100\nN10 X1.\nX0\nGOTO 10\n",
            "E-MOTION-LIMIT",
            "at line 4",
        ),
        ("#1=0\nN10 #1=#1+1\nGOTO 10\n", "E-RUNAWAY", "at line 3"),
    ] {
        let mut moves = Counter::default();
        let (diags, blocks) = run(text, Dialect::Fanuc, small_limits(), &mut moves);
        assert_eq!(codes(&diags), [code], "{text}");
        assert!(diags[0].message.contains(line), "{}", diags[0].message);
        assert!(moves.moves <= 10_000 && blocks <= 10_000, "{text}");
    }
}

#[test]
fn a_peck_too_small_and_deep_calls_stop_at_the_motion_limit() {
    let deep = {
        let mut s = String::from("G01 F100\nM98 P1 L9999\nM30\n");
        for i in 1..8 {
            s.push_str(&format!("O{i}\nM98 P{} L9999\nM99\n", i + 1));
        }
        s + "O8\nX1.\nX0\nM99\n"
    };
    for text in [
        "G00 X0 Y0 Z10.\nG83 X1. Y1. Z-1000. R2. Q.000001 F100\nG80\nM30\n",
        deep.as_str(),
    ] {
        let mut moves = Counter::default();
        let (diags, _) = run(text, Dialect::Fanuc, small_limits(), &mut moves);
        assert!(codes(&diags).contains(&"E-MOTION-LIMIT"), "{diags:?}");
        assert!(
            (1_000..1_010).contains(&moves.moves),
            "{} moves",
            moves.moves
        );
    }
}

#[test]
fn absurd_coordinates_feeds_and_dwells_are_an_error_where_computed() {
    let huge = "#1=99999999\n#1=#1*#1\n#1=#1*#1\n#1=#1*#1\n#1=#1*#1\n";
    for (text, line) in [
        (format!("{huge}G00 X1.\nG00 X#1\nY1.\n"), 7),
        (format!("{huge}G01 X1. F100\nG02 X0 Y0 R#1\n"), 7),
        ("G51 X0 Y0 P99999999\nG00 X1.\nX99999.\n".to_string(), 3),
        (format!("{huge}G04 P#1\nG00 X1.\n"), 6),
        (
            format!(
                "#2=0.0000001\n{}G01 X1. F#2\n",
                "#2=#2*#2*#2*#2\n".repeat(2)
            ),
            4,
        ),
    ] {
        let program = parse(&text, Dialect::Fanuc);
        let mut moves = Counter::default();
        let (diags, _) = run(&text, Dialect::Fanuc, Setup::default(), &mut moves);
        assert_eq!(codes(&diags), ["E-COORDINATE-RANGE"], "{text}");
        let at = program.lines.line_col(&text, diags[0].span.start).0;
        assert_eq!(at, line, "{text}");
        assert!(moves.largest <= 1e9, "{text}");
    }
}

#[test]
fn no_event_past_an_absurd_one_reaches_the_sink() {
    let text = "#1=99999999\n#1=#1*#1\nG00 X1.\nG00 X#1 Y1.\nG00 X2.\n";
    let program = parse(text, Dialect::Fanuc);
    let mut rec = CanonRecorder::default();
    let diags = swarf_interp::run(&program, Setup::default(), &mut rec);
    assert_eq!(codes(&diags), ["E-COORDINATE-RANGE"]);
    assert_eq!(rec.events.len(), 1);
}

/// A call whose program's file was found and not linked says why, naming the file, instead of
/// saying that no file holds it.
#[test]
fn a_call_whose_file_was_not_linked_says_why() {
    for (dialect, text, missing) in [
        (
            Dialect::Fanuc,
            "M98 P1234\nM30\n",
            swarf_syntax::Missing::Number(1234),
        ),
        (
            Dialect::Fanuc,
            "G65 P1234 A1.\nM30\n",
            swarf_syntax::Missing::Number(1234),
        ),
        (
            Dialect::LinuxCnc,
            "o<part> call\nM2\n",
            swarf_syntax::Missing::Name("part".into()),
        ),
    ] {
        let mut program = parse(text, dialect);
        let why = "/jobs/O1234.nc is larger than 1 MiB, the most read (--max-file-mb)";
        program.unlinked.push((missing, why.to_string()));
        let diags = swarf_interp::run(&program, Setup::default(), &mut CanonRecorder::default());
        let call = diags
            .iter()
            .find(|d| matches!(d.code, "E-SUBPROGRAM" | "E-OWORD"))
            .unwrap();
        assert!(
            call.message.ends_with(&format!(" in this program: {why}")),
            "{}",
            call.message
        );
        assert!(!call.message.contains("beside it"), "{}", call.message);
    }
}

/// A diagnostic that names a subroutine or parameter quotes a short excerpt of a long name.
#[test]
fn a_long_name_is_quoted_short() {
    let name = "n".repeat(100_000);
    for text in [
        format!("o<{name}> call\nM2\n"),
        format!("#1 = #<{name}>\nM2\n"),
    ] {
        let program = parse(&text, Dialect::LinuxCnc);
        let diags = swarf_interp::run(&program, Setup::default(), &mut CanonRecorder::default());
        assert!(!diags.is_empty());
        for d in &diags {
            assert!(d.message.len() < 400, "{}: {}", d.code, &d.message[..400]);
        }
    }
}
