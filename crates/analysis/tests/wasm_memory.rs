//! The web page's analysis worker's wasm memory on hostile programs (docs/performance.md's
//! "Hostile programs"): each runs through the worker's path (a job to the [`Service`], its
//! pieces, the finished reply as the worker's message parts) with the default setup, and the
//! wasm memory must stay under 1.5 GB. Run on demand, in Node:
//! `cargo test -p swarf-analysis --release --target wasm32-unknown-unknown --test wasm_memory -- --include-ignored --nocapture`.
//! Wasm memory never shrinks, so the programs run from the lightest to the heaviest, and the
//! figure printed after each is the most memory any program up to it took; to measure one
//! program alone, build with `SWARF_HOSTILE=` a part of its name in the environment.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]
#![cfg(target_arch = "wasm32")]

use swarf_analysis::{Job, ProgramText, Reply, Request, Service, wire};
use swarf_interp::Setup;
use swarf_syntax::Dialect;
use wasm_bindgen_test::{console_log, wasm_bindgen_test};

/// The most wasm memory the page's worker may take.
const LIMIT: usize = 1_500_000_000;

/// The wasm memory in bytes.
fn memory() -> usize {
    core::arch::wasm32::memory_size(0) * 65536
}

/// Analyses `text` as the worker does; the problems' codes, and the segments drawn.
fn analyse(text: String, setup: Setup) -> (Vec<&'static str>, usize) {
    let mut service = Service::default();
    let job = Job {
        generation: 1,
        text: ProgramText::from(text),
        dialect: Dialect::Fanuc,
        setup,
        others: Some(Vec::new()),
        lod: None,
    };
    assert!(service.handle(Request::Analyse(Box::new(job))).is_none());
    loop {
        let reply = service.step().expect("an analysis under way replies");
        if let Reply::Done(results) = &reply {
            let (head, arrays) = wire::reply_parts(&reply);
            assert!(!head.is_empty() && arrays.len() == 6);
            let mut codes: Vec<&'static str> = results.problems.iter().map(|p| p.code).collect();
            codes.dedup();
            return (codes, results.stats.motions);
        }
        assert!(matches!(reply, Reply::Progress { .. }), "{reply:?}");
    }
}

/// A hostile program: what it is, its text (made when it runs), the setup it runs on and a
/// diagnostic its run must end with.
type Case = (&'static str, fn() -> String, fn() -> Setup, &'static str);

/// The default setup with a travel of ±100 mm on each axis.
fn travel() -> Setup {
    let mut setup = Setup::default();
    setup.machine.travel_mm = Some([[-100.0; 3], [100.0; 3]]);
    setup
}

/// A program of the most the page opens (256 MiB) that opens with `head`, an endless loop (so
/// the program is held whole, as much of it as may be), then moves; made at its length, as the
/// worker takes a text from the page.
fn largest(head: &str) -> String {
    let moves = ((256 << 20) - head.len() - 4) / 7;
    let mut text = String::with_capacity(head.len() + moves * 7 + 4);
    text.push_str(head);
    for _ in 0..moves {
        text.push_str("X1.\nX0\n");
    }
    text + "M30\n"
}

const CASES: &[Case] = &[
    (
        "a 13-line endless WHILE of ten G05.1 Q1 lines",
        || format!("WHILE [1 EQ 1] DO1\n{}END1\nM30\n", "G05.1 Q1\n".repeat(10)),
        Setup::default,
        "E-RUNAWAY",
    ),
    (
        "an overtravel in an endless loop (a setup with travel_mm)",
        || "G01 F100\nWHILE [1 EQ 1] DO1\nX50.\nX150.\nX0\nEND1\n".into(),
        travel,
        "E-OVERTRAVEL",
    ),
    (
        "an endless loop of a 1,000-term expression",
        || {
            format!(
                "WHILE [1 EQ 1] DO1\n#1=[{}]\nEND1\n",
                vec!["1"; 1000].join("+")
            )
        },
        Setup::default,
        "E-RUNAWAY",
    ),
    (
        "M99 in the main program",
        || "G91 G00 X1.\nM99\n".into(),
        Setup::default,
        "N-M99-MAIN-REPEATS",
    ),
    (
        "a subprogram file alone, ending in M99",
        || "O100\nG91 G01 X1. F100\nM99\n".into(),
        Setup::default,
        "N-M99-MAIN-REPEATS",
    ),
    (
        "a 1e12 mm coordinate",
        || "#1=1000000\n#1=#1*#1\nG00 X1.\nG00 X#1 Y1.\nG00 X2.\nM30\n".into(),
        Setup::default,
        "E-COORDINATE-RANGE",
    ),
    (
        "30 MB of #1=[#1+1] lines",
        || "#1=[#1+1]\n".repeat(3_000_000),
        Setup::default,
        "E-PROGRAM-SIZE",
    ),
    (
        "WHILE [1 EQ 1] with two moves",
        || "G01 F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n".into(),
        Setup::default,
        "E-RUNAWAY",
    ),
    (
        "G83 Q.000001 over 1000 mm",
        || "G00 X0 Y0 Z10.\nG83 X1. Y1. Z-1000. R2. Q.000001 F100\nG80\nM30\n".into(),
        Setup::default,
        "E-MOTION-LIMIT",
    ),
    (
        "M98 L9999 calls nested 16 deep",
        || {
            let mut s = String::from("G01 F100\nM98 P1 L9999\nM30\n");
            for i in 1..16 {
                s.push_str(&format!("O{i}\nM98 P{} L9999\nM99\n", i + 1));
            }
            s + "O16\nX1.\nX0\nM99\n"
        },
        Setup::default,
        "E-MOTION-LIMIT",
    ),
    (
        "an endless GOTO loop of full circles",
        || "G0 X0 Y0 Z0\nN10 G2 X0 Y0 I10. F100\nGOTO10\n".into(),
        Setup::default,
        "E-MOTION-LIMIT",
    ),
    (
        "256 MiB: an endless loop of moves each changing tool and feed, then moves",
        || largest("WHILE [1 EQ 1] DO1\nT1 M6 G01 X1. F100\nT2 M6 X0 F200\nEND1\n"),
        Setup::default,
        "E-MOTION-LIMIT",
    ),
    (
        "256 MiB: an endless loop of cutter-compensated moves, then moves",
        || {
            largest(
                "G10 L12 P1 R2.\nG17 G01 F100\nG41 D1 X0 Y0\nWHILE [1 EQ 1] DO1\nX10. Y0\nY10.\nX0\nY0\nEND1\n",
            )
        },
        Setup::default,
        "E-MOTION-LIMIT",
    ),
    (
        "256 MiB: an endless loop of moves, then moves",
        || largest("G01 F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n"),
        Setup::default,
        "E-RUNAWAY",
    ),
    (
        "256 MiB: an endless loop of G81 holes, then moves",
        || largest("G00 Z10.\nG99 G81 X0 Y0 Z-1. R1. F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n"),
        Setup::default,
        "E-MOTION-LIMIT",
    ),
];

#[wasm_bindgen_test]
#[ignore = "a measurement, run on demand"]
fn hostile_programs_stay_under_the_worker_memory_limit() {
    let only = option_env!("SWARF_HOSTILE");
    let mut over = Vec::new();
    for &(name, text, setup, code) in CASES {
        if only.is_some_and(|only| !name.contains(only)) {
            continue;
        }
        let start = js_sys::Date::now();
        let (codes, motions) = analyse(text(), setup());
        let secs = (js_sys::Date::now() - start) / 1000.0;
        let held = memory();
        console_log!(
            "{name}: wasm memory {:.0} MB; {motions} segments, {codes:?}, {secs:.1} s",
            held as f64 / 1e6
        );
        assert!(codes.contains(&code), "{name}: {codes:?}");
        if held >= LIMIT {
            over.push(name);
        }
    }
    assert!(
        over.is_empty(),
        "over {LIMIT} bytes of wasm memory: {over:?}"
    );
}
