//! Behaviours held to LinuxCNC's reference interpreter (rs274: the expected numbers are its
//! output for the same programs) and to the Fanuc family's manuals where they differ: absolute
//! arc centres, a tool length offset changed without a move, the tools a setup lists, and the
//! words LinuxCNC refuses.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

mod support;

use glam::DVec3;
use support::run_with;
use swarf_interp::{Arc, Canon, Register, Setup};
use swarf_syntax::{Diagnostic, Dialect, Severity};

/// A setup whose registers hold tools 1 (12.9794 mm long, as LinuxCNC's sample table's
/// `T1 Z0.511`) and 2.
fn two_tools() -> Setup {
    let mut setup = Setup::default();
    for (n, length) in [(1, 12.9794), (2, 2.54)] {
        setup.registers.insert(
            n,
            Register {
                length,
                radius: 1.5875,
                ..Register::default()
            },
        );
    }
    setup
}

/// The motions' end points, rounded to 0.0001.
fn ends(events: &[Canon]) -> Vec<[f64; 3]> {
    support::ends_rounded(events, 10_000.0)
}

/// The arcs' centres and directions.
fn arcs(events: &[Canon]) -> Vec<(DVec3, bool)> {
    events
        .iter()
        .filter_map(|e| match e {
            Canon::Arc(Arc { center, ccw, .. }) => Some((*center, *ccw)),
            _ => None,
        })
        .collect()
}

fn codes(diags: &[Diagnostic]) -> Vec<&'static str> {
    diags.iter().map(|d| d.code).collect()
}

fn near(a: DVec3, b: [f64; 3]) -> bool {
    (a - DVec3::from_array(b)).length() < 1e-9
}

#[test]
fn g90_1_makes_arc_centres_absolute_in_every_plane() {
    // Plane, the program, and rs274's centres (in X, Y, Z; the coordinate along the plane's
    // normal is the start's).
    let cases: [(&str, &[[f64; 3]]); 4] = [
        (
            "G21 G17 G90 G90.1\nG0 X10 Y0\nG3 X0 Y10 I5 J5 F100\nG91.1\nG2 X10 Y0 I5 J-5\nM2\n",
            &[[5.0, 5.0, 0.0], [5.0, 5.0, 0.0]],
        ),
        (
            "G21 G18 G90.1\nG0 X10 Z0\nG3 X0 Z10 I5 K5 F100\nM2\n",
            &[[5.0, 0.0, 5.0]],
        ),
        (
            "G21 G19 G90.1\nG0 Y10 Z0\nG3 Y0 Z10 J5 K5 F100\nG91.1 G2 Y10 Z0 J5 K-5\nM2\n",
            &[[0.0, 5.0, 5.0], [0.0, 5.0, 5.0]],
        ),
        // Absolute under G91 too, and in the work frame: G92 makes the machine's zero read
        // (1, 1) in G54 at (100, 100), so the work's (5, 5) is the machine's (4, 4).
        (
            "G21 G90.1\nG10 L2 P1 X100 Y100\nG92 X1 Y1\nG0 X10 Y0\nG91 G3 X-10 Y10 I5 J5 F100\nM2\n",
            &[[4.0, 4.0, 0.0]],
        ),
    ];
    for (text, centres) in cases {
        let (events, diags) = run_with(text, Dialect::LinuxCnc, Setup::default());
        assert!(diags.is_empty(), "{text}: {diags:?}");
        let found = arcs(&events);
        assert_eq!(found.len(), centres.len(), "{text}");
        for ((c, _), want) in found.iter().zip(centres) {
            assert!(near(*c, *want), "{text}: {c} != {want:?}");
        }
    }
    // Both centre words of the plane are needed (rs274: "I word missing in absolute center
    // arc"); the block is not run.
    let (events, diags) = run_with(
        "G21 G90.1\nG0 X10 Y5\nG3 X0 Y5 J5 F100\nM2\n",
        Dialect::LinuxCnc,
        Setup::default(),
    );
    assert_eq!(codes(&diags), ["E-ARC-CENTER"]);
    assert!(diags[0].message.contains("`I`"), "{}", diags[0].message);
    assert!(arcs(&events).is_empty());
    // The Fanuc family has no G90.1: it is not read as a mode there.
    for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::Kt, Dialect::Lnc] {
        let (_, diags) = run_with("G90.1\n", dialect, Setup::default());
        assert!(
            diags.iter().any(|d| d.severity == Severity::Error),
            "{dialect}: {diags:?}"
        );
    }
}

#[test]
fn a_linuxcnc_length_offset_changes_the_program_z_without_moving() {
    // G43 without H takes the tool in the spindle (not the one a later T selects); the next
    // move keeps the machine's Z, so the program's Z changes by the offset (rs274's output).
    for text in [
        "G21 G90\nT1 M6\nG43\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
        "G21 G90\nT1 M6\nT2\nG43\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
        "G21 G90\nT1 M6 G43\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
        "G21 G90\nG43 H1\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
    ] {
        let (events, diags) = run_with(text, Dialect::LinuxCnc, two_tools());
        assert!(diags.is_empty(), "{text}: {diags:?}");
        assert_eq!(
            ends(&events),
            [
                [10.0, 10.0, -12.9794],
                [10.0, 10.0, 5.0],
                [0.0, 10.0, 17.9794]
            ],
            "{text}"
        );
    }
    // The Fanuc family moves the tool by the offset at once (KT's manual: G43 without a Z
    // move still moves by the offset, G49 cancels at once): the tip keeps the program's Z.
    for dialect in [Dialect::Fanuc, Dialect::Kt] {
        let (events, diags) = run_with(
            "G21 G90\nT1 M6\nG43 H1\nG0 X10. Y10.\nG0 Z5.\nG49\nG0 X0\nM30\n",
            dialect,
            two_tools(),
        );
        assert!(diags.is_empty(), "{dialect}: {diags:?}");
        assert_eq!(
            ends(&events),
            [[10.0, 10.0, 0.0], [10.0, 10.0, 5.0], [0.0, 10.0, 5.0]],
            "{dialect}"
        );
    }
}

#[test]
fn linuxcnc_g10_l10_and_l11_set_the_length_from_the_position() {
    // Tool 1 touched off on the setter (G59.3 at Z-27) with the tool at machine Z-30: length -3
    // (L11); tool 2's length so that the current Z (2, with tool 1's offset on) reads 5: -6
    // (L10). rs274's moves, the tools 12.7 and 2.54 mm long before.
    let mut setup = two_tools();
    setup.registers.get_mut(&1).unwrap().length = 12.7;
    let (events, diags) = run_with(
        "G21 G90\nG10 L2 P9 Z-27\nG10 L2 P1 Z-3\nG54\nT1 M6\nG53 G0 Z-30\nG10 L11 P1 Z0\nG43\n\
         G0 X1\nG0 Z2\nG10 L10 P2 Z5\nT2 M6\nG43\nG0 X2\nG49\nG0 X3\nM2\n",
        Dialect::LinuxCnc,
        setup,
    );
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [0.0, 0.0, -30.0],
            [1.0, 0.0, -27.0],
            [1.0, 0.0, -1.0],
            [2.0, 0.0, 2.0],
            [3.0, 0.0, -4.0]
        ]
    );
}

#[test]
fn linuxcnc_stops_at_a_tool_its_table_does_not_hold() {
    for (text, word) in [
        ("G21\nG0 X1\nT8 M6\nG0 X2\nM2\n", "T8"),
        (
            "G21\nT1 M6\nG0 X1\nG41 D8 G1 X2 F100\nG40 G0 X5\nM2\n",
            "D8",
        ),
        ("G21\nG0 X1\nG43 H8\nG0 X2\nM2\n", "G43"),
        ("G21\nG0 X1\nG10 L1 P8 Z1\nG0 X2\nM2\n", "P8"),
    ] {
        let (events, diags) = run_with(text, Dialect::LinuxCnc, two_tools());
        assert_eq!(codes(&diags), ["E-TOOL-UNKNOWN"], "{text}");
        let d = &diags[0];
        assert!(d.message.contains("tool 8"), "{}", d.message);
        assert_eq!(
            &text[d.span.start as usize..d.span.end as usize],
            word,
            "{text}"
        );
        // The run stops there, as rs274's does.
        assert_eq!(ends(&events), [[1.0, 0.0, 0.0]], "{text}");
    }
    // A setup that lists no tools knows nothing of the table: a note for an offset, and on.
    let (events, diags) = run_with(
        "G21\nT8 M6\nG43 H8\nG0 X2\nM2\n",
        Dialect::LinuxCnc,
        Setup::default(),
    );
    assert_eq!(codes(&diags), ["N-OFFSET-UNSET"]);
    assert_eq!(ends(&events), [[2.0, 0.0, 0.0]]);
    // Nor do the tools such a program sets itself make a table of them.
    let (events, diags) = run_with(
        "G21\nG10 L1 P8 Z1\nT1 M6\nG43\nG0 X2\nM2\n",
        Dialect::LinuxCnc,
        Setup::default(),
    );
    assert_eq!(codes(&diags), ["N-OFFSET-UNSET"]);
    assert_eq!(ends(&events), [[2.0, 0.0, 0.0]]);
}

#[test]
fn the_fanuc_family_warns_of_an_offset_register_the_setup_does_not_list() {
    for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::Lnc] {
        let (events, diags) = run_with(
            "G90\nT8 M6\nG43 H8 Z5.\nG41 D9 G1 X10. F100.\nG40 G0 X0\nM30\n",
            dialect,
            two_tools(),
        );
        let warned: Vec<&str> = diags
            .iter()
            .filter(|d| d.code == "W-OFFSET-UNSET")
            .map(|d| d.message.as_str())
            .collect();
        assert_eq!(warned.len(), 2, "{dialect}: {diags:?}");
        for (message, register) in warned.iter().zip(["register 8", "register 9"]) {
            assert!(message.contains(register), "{dialect}: {message}");
        }
        // The register reads as zeros and the program runs on.
        assert_eq!(ends(&events).len(), 3, "{dialect}: {diags:?}");
    }
    // KT (which has no G41/G42): the length register.
    let (_, diags) = run_with("G90\nG43 H8 Z5.\nM30\n", Dialect::Kt, two_tools());
    assert_eq!(codes(&diags), ["W-OFFSET-UNSET"]);
    // With no registers at all, the note of old.
    let (_, diags) = run_with("G90\nG43 H8 Z5.\nM30\n", Dialect::Fanuc, Setup::default());
    assert_eq!(codes(&diags), ["N-OFFSET-UNSET"]);
}

#[test]
fn linuxcnc_refuses_words_its_codes_do_not_take() {
    // K on an arc in the XY plane: refused, the block is not run (the next one is).
    let (events, diags) = run_with(
        "G21\nG17 G2 X1 Y1 I1 K1 F100\nG0 X5\nM2\n",
        Dialect::LinuxCnc,
        Setup::default(),
    );
    assert_eq!(codes(&diags), ["E-ARC-WORD"]);
    assert_eq!(ends(&events), [[5.0, 0.0, 0.0]]);
    // The same word out of the plane in G18 and G19.
    for text in [
        "G21 G18 G2 X1 Z1 I1 J1 F100\nM2\n",
        "G21 G19 G2 Y1 Z1 J1 I1 F100\nM2\n",
    ] {
        let (events, diags) = run_with(text, Dialect::LinuxCnc, Setup::default());
        assert_eq!(codes(&diags), ["E-ARC-WORD"], "{text}");
        assert!(events.iter().all(|e| !matches!(e, Canon::Arc(_))));
    }
    // The Fanuc family ignores it with a warning and cuts the arc.
    let (events, diags) = run_with(
        "G21\nG17 G2 X1. Y1. I1. K1. F100.\nM30\n",
        Dialect::Fanuc,
        Setup::default(),
    );
    assert_eq!(codes(&diags), ["W-WORD-IGNORED"]);
    assert_eq!(arcs(&events).len(), 1);
    // P on G73 and G83 (G82 takes it: the dwell).
    for (text, code) in [
        (
            "G21 G0 Z5\nG73 X1 Y1 Z-1 R1 Q0.5 P1 F100\nM2\n",
            Some("E-WORD-UNUSED"),
        ),
        (
            "G21 G0 Z5\nG83 X1 Y1 Z-1 R1 Q0.5 P1 F100\nM2\n",
            Some("E-WORD-UNUSED"),
        ),
        ("G21 G0 Z5\nG82 X1 Y1 Z-1 R1 P1 F100\nM2\n", None),
    ] {
        let (events, diags) = run_with(text, Dialect::LinuxCnc, Setup::default());
        assert_eq!(
            codes(&diags),
            code.into_iter().collect::<Vec<_>>(),
            "{text}"
        );
        // A refused cycle block is not run: the tool stays at Z5.
        assert_eq!(ends(&events).len() > 1, code.is_none(), "{text}");
    }
}
