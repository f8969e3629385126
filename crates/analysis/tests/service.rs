//! The analysis as a service: in pieces it gives what one call gives, a newer job replaces one
//! under way at once, and the program stays on the analysis side to answer questions.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_analysis::{
    Analyst, Inline, Job, PendingAnalysis, ProgramText, Progress, Reply, Request, Thread, analyse,
};
use swarf_interp::Setup;
use swarf_syntax::Dialect;

/// `lines` straight moves, then `tail`.
fn program(lines: usize, tail: &str) -> String {
    let mut text = String::from("G90 G21 G17 G54\n");
    for i in 1..lines {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 100, i % 37));
    }
    text.push_str(tail);
    text
}

fn job(generation: u64, text: String) -> Job {
    Job {
        generation,
        text: ProgramText::from(text),
        dialect: Dialect::Fanuc,
        setup: Setup::default(),
        others: None,
        lod: None,
    }
}

/// Replies until the first finished analysis.
fn until_done(analyst: &mut dyn Analyst) -> (Vec<Reply>, swarf_analysis::Results) {
    let mut before = Vec::new();
    loop {
        match analyst.wait_reply().expect("a reply") {
            Reply::Done(results) => return (before, *results),
            other => before.push(other),
        }
    }
}

#[test]
fn an_analysis_in_steps_equals_the_one_call_run() {
    let text = program(3000, "G01 X$\nM30\n");
    let (whole, _) = analyse(job(7, text.clone()));
    let len = text.len();
    let mut pending = PendingAnalysis::start(job(7, text));
    // The text is read first (two lines per block of budget), then run.
    assert_eq!(
        pending.progress(),
        Progress::Reading {
            read: 0,
            bytes: len
        }
    );
    // A straight program is read and run a piece at a time: a block of budget reads two lines
    // or runs a block, so a step of 100 reads and runs 200 lines.
    let mut steps = 0;
    let mut before = 0;
    while !pending.step(100) {
        steps += 1;
        let Progress::Reading { read, bytes } = pending.progress() else {
            panic!("{:?}", pending.progress());
        };
        assert!(
            before < read && read < bytes,
            "{before} then {read} of {bytes}"
        );
        before = read;
    }
    assert_eq!(steps, 15);
    let (stepped, _) = pending.finish();
    assert_eq!(stepped, whole);
    assert_eq!(stepped.generation, 7);
    assert!(stepped.problems.iter().any(|p| p.code == "E-SYNTAX-CHAR"));
}

/// `lines` lines of moves, arcs, feeds, tool changes, a drilling cycle, cutter compensation,
/// comments, blank and block-delete lines.
fn varied(lines: usize) -> String {
    let mut text = String::from("N1 G90 G21 G17 G54 G94\n");
    for i in 1..lines {
        let (x, y) = (i % 50, i % 23);
        text.push_str(&match i % 12 {
            0 => format!(
                "T{} M06\nG43 H{} Z20. S{} M03\n",
                i % 5 + 1,
                i % 5 + 1,
                1000 + i
            ),
            1 => format!("G00 X{x}. Y{y}.\n"),
            2 => format!("G01 Z-1. F{}.\n", 100 + i % 400),
            3 => format!("G02 X{}. Y{y}. R5.\n", x + 3),
            4 => "(a comment)\n".to_string(),
            5 => format!("/G01 X{y}. Y{x}.\n"),
            6 => format!("G81 X{x}. Y{y}. Z-3. R2. F200.\nX{}.\nG80\n", x + 2),
            7 => String::new() + "\n",
            8 => format!(
                "G41 D1 G01 X{x}. Y{}.\nX{}.\nG40 G01 X{x}. Y{y}.\n",
                y + 2,
                x + 4
            ),
            9 => "G91 G01 X1. Y-1.\nG90\n".to_string(),
            _ => format!("G01 X{x}.5 Y{y}.25 Z-0.5\n"),
        });
    }
    text
}

#[test]
fn a_straight_program_read_in_pieces_gives_what_it_gives_read_whole() {
    let body = varied(7_000);
    // A jump after the end, which never runs, has the program read and run whole.
    let (pieces, in_pieces) = analyse(job(1, format!("{body}M30\nG01 X1.\n")));
    let (whole, held_whole) = analyse(job(1, format!("{body}M30\nGOTO1\n")));
    // The editor's rope, whose lines straddle its chunks: a piece is read again from it alone.
    let rope = ropey::Rope::from_str(&format!("{body}M30\nG01 X1.\n"));
    let (from_rope, in_rope) = analyse(Job {
        text: ProgramText::Rope(rope),
        ..job(1, String::new())
    });
    assert_eq!(from_rope, pieces);
    assert!(pieces.stats.blocks > 8_192, "{}", pieces.stats.blocks);
    assert_eq!(pieces.stats, whole.stats);
    assert_eq!(pieces.plot, whole.plot);
    assert_eq!(pieces.problems, whole.problems);
    // Lines throughout, and those about the ends of the pieces of 4096 lines.
    let lines = body.lines().count() as u32 + 2;
    let near_an_end = |line: u32| (line + 4) % 4096 < 8;
    let asked = (1..=lines).filter(|&line| line % 11 == 0 || near_an_end(line));
    let ran = asked.filter(|&line| {
        let state = in_pieces.state_at(line);
        assert_eq!(state, held_whole.state_at(line), "line {line}");
        assert_eq!(state, in_rope.state_at(line), "line {line} of the rope");
        state.is_some()
    });
    let ran = ran.count();
    assert!(ran > 700, "{ran} of {lines}");
}

#[test]
fn a_newer_job_replaces_one_under_way_on_the_thread() {
    let mut thread = Thread::spawn(|_| {}).unwrap();
    let long = Request::Analyse(Box::new(job(1, program(400_000, "M30\n"))));
    let newer = Request::Analyse(Box::new(job(2, "G0 X1\nG01 X$\n".to_string())));
    thread.send(long);
    thread.send(newer);
    let (before, results) = until_done(&mut thread);
    assert_eq!(results.generation, 2, "the long job never finishes");
    assert_eq!(results.stats.blocks, 2);
    // The long job, some 26 steps of reading, gives way within the few the thread may take
    // before the newer one comes.
    assert!(before.len() < 8, "{before:?}");
    let codes: Vec<_> = results.problems.iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(2, "E-SYNTAX-CHAR")), "{codes:?}");
}

#[test]
fn a_long_analysis_reports_its_progress_and_keeps_its_program_for_questions() {
    let mut thread = Thread::spawn(|_| {}).unwrap();
    let text = program(100_000, "M30\n");
    thread.send(Request::Analyse(Box::new(job(5, text.clone()))));
    let (before, results) = until_done(&mut thread);
    assert!(before.len() > 5, "{}", before.len());
    let mut last = 0;
    for reply in &before {
        let Reply::Progress {
            generation: 5,
            progress,
        } = reply
        else {
            panic!("{reply:?}");
        };
        if let Progress::Running { reached, blocks } = *progress {
            assert_eq!(blocks, 100_001);
            assert!(reached >= last);
            last = reached;
        }
    }
    assert_eq!(results, analyse(job(5, text)).0);
    // Questions about the finished analysis are answered at once, on the caller's side.
    let Some(Reply::State {
        generation: 5,
        line: 3,
        state: Some(Some(state)),
    }) = thread.send(Request::StateAt {
        generation: 5,
        line: 3,
    })
    else {
        panic!("the state at line 3");
    };
    assert_eq!((state.work.x, state.work.y), (1.0, 1.0));
    assert_eq!(state.executed, 2);
    // Another analysis is not held; a line without a block does not run.
    assert!(matches!(
        thread.send(Request::StateAt {
            generation: 4,
            line: 3,
        }),
        Some(Reply::State { state: None, .. })
    ));
    assert!(matches!(
        thread.send(Request::StateAt {
            generation: 5,
            line: 200_000,
        }),
        Some(Reply::State {
            state: Some(None),
            ..
        })
    ));
    // The state of the last line run, with its many blocks before it.
    let Some(Reply::State {
        state: Some(Some(last)),
        ..
    }) = thread.send(Request::StateAt {
        generation: 5,
        line: 100_000,
    })
    else {
        panic!("the state at line 100,000");
    };
    assert_eq!(last.executed, 99_999);
}

#[test]
fn inline_gives_the_thread_s_replies_when_asked() {
    let text = program(500, "G01 Y$\nM30\n");
    let mut inline = Inline::default();
    assert!(inline.try_reply().is_none());
    assert!(
        inline
            .send(Request::Analyse(Box::new(job(3, text.clone()))))
            .is_none()
    );
    let Some(Reply::Done(results)) = inline.try_reply() else {
        panic!("finished when asked");
    };
    assert_eq!(*results, analyse(job(3, text)).0);
    assert!(matches!(
        inline.send(Request::StateAt {
            generation: 3,
            line: 2,
        }),
        Some(Reply::State {
            state: Some(Some(_)),
            ..
        })
    ));
    assert!(inline.wait_reply().is_none());
}

#[test]
fn the_path_is_simplified_for_the_view_from_what_the_analysis_keeps() {
    let mut inline = Inline::default();
    assert!(
        inline
            .send(Request::Analyse(Box::new(job(3, program(500, "M30\n")))))
            .is_none()
    );
    let (_, results) = until_done(&mut inline);
    let points = &results.plot.drawing.points;
    for level in [Some(-3), Some(4), None] {
        let reply = inline.send(Request::Lod {
            generation: 3,
            level,
        });
        let Some(Reply::Lod {
            generation: 3,
            level: answered,
            kept: Some(kept),
        }) = reply
        else {
            panic!("{reply:?}");
        };
        assert_eq!(answered, level);
        assert_eq!(*kept, swarf_render::simplify_at(points, level));
    }
    // A coarser level keeps fewer points; every point without one.
    let mut count = |level| match inline.send(Request::Lod {
        generation: 3,
        level,
    }) {
        Some(Reply::Lod { kept: Some(k), .. }) => k.len(),
        other => panic!("{other:?}"),
    };
    assert!(count(Some(6)) < count(Some(-6)));
    assert_eq!(count(None), points.len());
    // An analysis no longer held is said to be so: the asker simplifies its own copy.
    assert!(matches!(
        inline.send(Request::Lod {
            generation: 2,
            level: Some(0)
        }),
        Some(Reply::Lod {
            generation: 2,
            kept: None,
            ..
        })
    ));
}
