//! The analysis runs beside the frames: a frame sends the text and takes the replies, long
//! programs run behind a progress bar while the last results stay, and a newer edit replaces
//! an unfinished run.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;

use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_analysis::{Analyst, Progress, Reply, Request, analyse};
use swarf_ui::Workbench;

/// `lines` straight moves, then `tail`.
fn program(lines: usize, tail: &str) -> String {
    let mut text = String::from("G90 G21 G17 G54\n");
    for i in 1..lines {
        text.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 100, i % 37));
    }
    text.push_str(tail);
    text
}

fn harness(wb: Workbench) -> Harness<'static, Workbench> {
    Harness::builder()
        .with_size(egui::vec2(1000.0, 600.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb)
}

/// An analysis that answers only when the test says: the requests sent, the replies to give.
#[derive(Default, Clone)]
struct Scripted(Rc<RefCell<(Vec<Request>, VecDeque<Reply>)>>);

impl Analyst for Scripted {
    fn send(&mut self, request: Request) -> Option<Reply> {
        self.0.borrow_mut().0.push(request);
        None
    }

    fn try_reply(&mut self) -> Option<Reply> {
        self.0.borrow_mut().1.pop_front()
    }

    fn wait_reply(&mut self) -> Option<Reply> {
        self.try_reply()
    }
}

impl Scripted {
    /// The last job sent.
    fn last_job(&self) -> swarf_analysis::Job {
        self.0
            .borrow()
            .0
            .iter()
            .rev()
            .find_map(|r| match r {
                Request::Analyse(job) => Some(job.as_ref().clone()),
                Request::StateAt { .. } | Request::Stock { .. } | Request::Lod { .. } => None,
            })
            .expect("a job was sent")
    }

    fn reply(&self, reply: Reply) {
        self.0.borrow_mut().1.push_back(reply);
    }
}

#[test]
fn a_frame_sends_the_text_and_shows_the_replies_as_they_come() {
    let mut wb = Workbench::default();
    wb.open_document(
        "long.nc",
        program(10_000, "M30\n"),
        swarf_syntax::Encoding::default(),
    );
    wb.finish_analysis();
    assert!(wb.problems().is_empty(), "{:?}", wb.problems());
    let analyst = Scripted::default();
    wb.set_analyst(Box::new(analyst.clone()));
    let job = analyst.last_job();
    analyst.reply(Reply::Done(Box::new(analyse(job).0)));
    let mut harness = harness(wb);
    harness.run();
    assert!(harness.state().analysis_progress().is_none());
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.focus();
    harness.run();
    let editor = harness.get_by_role(egui::accesskit::Role::MultilineTextInput);
    editor.type_text("G01 X$\n");
    harness.step();
    // The frame of the keystroke sent the new text; nothing in the frames analyses it.
    let job = analyst.last_job();
    assert_eq!(job.generation, harness.state().generation());
    assert!(job.text.to_owned_string().starts_with("G01 X$\nG90"));
    for _ in 0..3 {
        harness.step();
    }
    assert!(
        harness.state().problems().is_empty(),
        "the last results stay"
    );
    assert_eq!(harness.state().analysis_progress(), Some((0, 0)));
    analyst.reply(Reply::Progress {
        generation: job.generation,
        progress: Progress::Running {
            reached: 4000,
            blocks: 10_001,
        },
    });
    harness.step();
    harness.step();
    assert_eq!(harness.state().analysis_progress(), Some((4000, 10_001)));
    harness.get_by_label_contains("4000 / 10001 blocks");
    analyst.reply(Reply::Done(Box::new(analyse(job).0)));
    harness.step();
    let wb = harness.state();
    assert!(wb.analysis_progress().is_none());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.analysis().scene.generation, wb.generation());
}

#[test]
fn the_state_at_cursor_is_asked_of_the_analysis() {
    let mut wb = Workbench::default();
    wb.set_text("G90 G21 G17\nT2 M06\nG00 X10. Y5.\nG01 Z-1. F300.\nM30\n");
    wb.finish_analysis();
    let analyst = Scripted::default();
    wb.set_analyst(Box::new(analyst.clone()));
    let job = analyst.last_job();
    let generation = job.generation;
    let (results, kept) = analyse(job);
    analyst.reply(Reply::Done(Box::new(results)));
    wb.select_line(4);
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 700.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    assert!(
        analyst.0.borrow().0.iter().any(|r| matches!(
            r,
            Request::StateAt { generation: g, line: 4 } if *g == generation
        )),
        "the panel asks for line 4"
    );
    assert_eq!(
        harness
            .query_all_by_label_contains("X10.000 Y5.000")
            .count(),
        0
    );
    analyst.reply(Reply::State {
        generation,
        line: 4,
        state: Some(kept.state_at(4)),
    });
    harness.run();
    // The work and machine positions (no offsets).
    assert_eq!(
        harness
            .query_all_by_label_contains("X10.000 Y5.000")
            .count(),
        2
    );
}

#[test]
fn a_long_program_runs_beside_the_frames_behind_a_progress_bar_keeping_the_old_results() {
    let mut wb = Workbench::default();
    wb.set_text("G01 X$ F100\n");
    wb.finish_analysis();
    let old = wb.problems().to_vec();
    assert!(!old.is_empty());
    let mut harness = harness(wb);
    harness.run();
    let lines = 100_000;
    harness
        .state_mut()
        .set_text(program(lines, "G01 Y$\nM30\n"));
    assert!(harness.state().analysis_progress().is_some());
    assert_eq!(
        harness.state().problems(),
        old.as_slice(),
        "old problems stay"
    );
    let started = Instant::now();
    while harness.state().analysis_progress().is_some() {
        harness.step();
        if harness.state().analysis_progress().is_some() {
            // The frame began with the analysis running: it showed the progress.
            harness.get_by_label_contains("Analysing");
            assert_eq!(harness.state().problems(), old.as_slice());
        }
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "the analysis ends"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    let wb = harness.state();
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(
        codes.contains(&(lines as u32 + 1, "E-SYNTAX-CHAR")),
        "{codes:?}"
    );
    assert!(!codes.contains(&(1, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.stats().blocks, lines + 2);
    harness.step();
    assert!(harness.query_by_label_contains("Analysing").is_none());
}

#[test]
fn a_newer_edit_replaces_an_unfinished_run() {
    let mut wb = Workbench::default();
    wb.set_text(program(300_000, "M30\n"));
    assert!(wb.analysis_progress().is_some());
    wb.set_text("G0 X1\nG01 X$\n");
    wb.finish_analysis();
    assert!(wb.analysis_progress().is_none());
    let codes: Vec<_> = wb.problems().iter().map(|p| (p.line, p.code)).collect();
    assert!(codes.contains(&(2, "E-SYNTAX-CHAR")), "{codes:?}");
    assert_eq!(wb.stats().blocks, 2);
}

#[test]
fn finishing_the_analysis_gives_the_current_texts_results() {
    let mut wb = Workbench::default();
    wb.set_text(program(60_000, "G01 Z$\n"));
    assert!(wb.analysis_progress().is_some());
    wb.finish_analysis();
    assert!(wb.analysis_progress().is_none());
    assert_eq!(wb.stats().blocks, 60_001);
    assert!(wb.problems().iter().any(|p| p.code == "E-SYNTAX-CHAR"));
    assert_eq!(wb.analysis().scene.generation, wb.generation());
}

#[test]
fn the_path_is_simplified_beside_the_frames_at_the_views_level() {
    let Some(render_state) = support::render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the level of detail test");
        return;
    };
    let mut wb = Workbench::default();
    wb.set_text(program(2000, "M30\n"));
    wb.finish_analysis();
    let analyst = Scripted::default();
    wb.set_analyst(Box::new(analyst.clone()));
    let job = analyst.last_job();
    assert_eq!(
        job.lod, None,
        "a first program is framed: its level is not known yet"
    );
    let generation = job.generation;
    let (results, kept) = analyse(job);
    analyst.reply(Reply::Done(Box::new(results)));
    let mut harness = support::drawn_workbench(&render_state, wb, egui::vec2(1200.0, 700.0));
    for _ in 0..4 {
        harness.step();
    }
    // The frames asked for the framed view's level once, and wait for it.
    let asked: Vec<_> = (analyst.0.borrow().0.iter())
        .filter_map(|r| match r {
            Request::Lod { generation, level } => Some((*generation, *level)),
            _ => None,
        })
        .collect();
    let [(asked_generation, level)] = asked[..] else {
        panic!("{asked:?}");
    };
    assert_eq!(asked_generation, generation);
    assert!(level.is_some());
    assert!(harness.state().drawing_pending());
    let simplified = swarf_render::simplify_at(&kept.points, level);
    assert!(simplified.len() < kept.points.len());
    analyst.reply(Reply::Lod {
        generation,
        level,
        kept: Some(std::sync::Arc::new(simplified.clone())),
    });
    harness.run();
    assert!(!harness.state().drawing_pending());
    let lod = harness.state().analysis().scene.lod.clone().unwrap();
    assert_eq!((lod.level, &*lod.kept), (level, &simplified));
    // A keystroke keeps the zoom: its job asks for the level shown, whose points then come
    // with its results.
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .focus();
    harness.run();
    harness
        .get_by_role(egui::accesskit::Role::MultilineTextInput)
        .type_text("G01 X1.\n");
    harness.step();
    let job = analyst.last_job();
    assert!(job.text.to_owned_string().starts_with("G01 X1.\n"));
    assert_eq!(job.lod, Some(level));
    // Text replaced whole is framed anew: its job asks for no level.
    harness.state_mut().set_text(program(2001, "M30\n"));
    assert_eq!(analyst.last_job().lod, None);
}
