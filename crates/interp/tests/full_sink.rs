//! A sink that holds all it may (a toolpath at its memory's limit) stops the run: before the
//! next block, inside a canned cycle's holes and pecks, and in the loop of plain moves and arcs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_interp::{Canon, Setup, Sink, Source, run};
use swarf_syntax::{Dialect, parse};

/// Counts motion events and is full past `room` of them.
struct Small {
    motions: usize,
    room: usize,
}

impl Sink for Small {
    fn emit(&mut self, _: Source, event: &Canon) {
        if event.end_point().is_some() {
            self.motions += 1;
        }
    }

    fn full(&self) -> bool {
        self.motions >= self.room
    }
}

/// Runs `text` into a sink with room for `room` motions: how many it got, and the codes of
/// the errors.
fn run_into_small(text: &str, dialect: Dialect, room: usize) -> (usize, Vec<&'static str>) {
    let mut sink = Small { motions: 0, room };
    let diagnostics = run(&parse(text, dialect), Setup::default(), &mut sink);
    let errors = diagnostics.iter().filter(|d| d.code.starts_with("E-"));
    (sink.motions, errors.map(|d| d.code).collect())
}

#[test]
fn a_full_sink_stops_a_run_of_plain_moves_and_arcs() {
    let mut text = String::from("G0 X0 Y0\nG1 F100\n");
    for i in 0..5000 {
        text.push_str(&format!("G1 X{}.\nG2 X{}. I1.\n", i + 1, i + 3));
    }
    text.push_str("M30\n");
    let (motions, codes) = run_into_small(&text, Dialect::Fanuc, 100);
    assert!((100..=102).contains(&motions), "{motions} motions");
    assert_eq!(codes, ["E-MOTION-LIMIT"]);
}

#[test]
fn a_full_sink_stops_a_canned_cycle_within_its_block() {
    // LinuxCNC's L has no bound of its own: a billion holes in one block.
    let (motions, codes) = run_into_small(
        "G0 X0 Y0 Z10\nG91 G81 X1 Y1 Z-5 R2 L1000000000 F100\nG80\nM2\n",
        Dialect::LinuxCnc,
        1000,
    );
    assert!(motions < 1010, "{motions} motions");
    assert_eq!(codes, ["E-MOTION-LIMIT", "E-MOTION-LIMIT"]);
    // A hundred million pecks in one hole: the last one in the program, so the cycle's own
    // diagnostic is the only one.
    let (motions, codes) = run_into_small(
        "G0 X0 Y0 Z10.\nG83 X1. Y1. Z-99999.999 R2. Q0.001 F100",
        Dialect::Fanuc,
        1000,
    );
    assert!(motions < 1010, "{motions} motions");
    assert_eq!(codes, ["E-MOTION-LIMIT"]);
}

#[test]
fn a_peck_too_small_to_go_deeper_is_reported_and_the_hole_finished() {
    let (motions, codes) = run_into_small(
        "G0 X0 Y0 Z10.\n#1=1/100000000/100000000/10\nG83 X1. Y1. Z-50. R2. Q#1 F100\nG80\nM30\n",
        Dialect::Fanuc,
        usize::MAX,
    );
    assert!(motions < 20, "{motions} motions");
    assert_eq!(codes, ["E-CYCLE-PECK"]);
}

#[test]
fn the_fanuc_familys_repeat_count_ends_at_9999() {
    for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::Lnc] {
        let (_, codes) = run_into_small(
            "G0 X0 Y0 Z10.\nG91 G81 X1. Y1. Z-5. R2. K10000 F100\nG80\nM30\n",
            dialect,
            usize::MAX,
        );
        assert_eq!(codes, ["E-NUMBER-RANGE"], "{dialect:?}");
        let (motions, codes) = run_into_small(
            "G0 X0 Y0 Z10.\nG91 G81 X1. Y1. Z-5. R2. K9999 F100\nG80\nM30\n",
            dialect,
            usize::MAX,
        );
        assert!(codes.is_empty(), "{dialect:?}: {codes:?}");
        assert!(motions > 9999 * 3, "{dialect:?}: {motions}");
    }
}

#[test]
fn a_cycles_repeat_count_is_not_noted_as_a_length() {
    let notes = |text: &str| {
        let program = parse(text, Dialect::Fanuc);
        let diagnostics = run(
            &program,
            Setup::default(),
            &mut Small {
                motions: 0,
                room: usize::MAX,
            },
        );
        diagnostics.iter().map(|d| d.code).collect::<Vec<_>>()
    };
    // K5 repeats the hole five times: no least-increment note for it.
    assert!(notes("G0 X0. Y0. Z10.\nG91 G81 X1. Y1. Z-5. R2. K5 F100\nG80\nM30\n").is_empty());
    // An arc's K is a length, as is a cycle's X.
    assert_eq!(
        notes("G0 X0. Y0. Z0.\nG18 G2 X0. Z.01 K5 F100\nM30\n"),
        ["N-LEAST-INCREMENT"]
    );
    assert_eq!(
        notes("G0 X0. Y0. Z10.\nG91 G81 X1 Y1. Z-5. R2. K5 F100\nG80\nM30\n"),
        ["N-LEAST-INCREMENT"]
    );
}
