//! The stock cut beside the UI: asked for after an analysis, it comes back as heights with the
//! rapids into it and its diagnostics located; a later segment continues the cut, an earlier
//! one starts it again, a new job stops it, and it reads back from the worker's bytes.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_analysis::{Analyst, Job, ProgramText, Reply, Request, Service, StockCut, Thread, wire};
use swarf_interp::Setup;
use swarf_syntax::Dialect;

/// A slot cut 2 mm deep from the top at Z0 along X and up Y, then a rapid down into the
/// material beside it (line 7).
const PROGRAM: &str =
    "G90 G21 G17\nG1 Z-2. F300.\nG1 X40.\nG1 Y20.\nG0 Z5.\nG0 X10. Y10.\nG0 Z-1.\nM30\n";

fn job(generation: u64, setup: Setup) -> Job {
    Job {
        generation,
        text: ProgramText::from(PROGRAM.to_string()),
        dialect: Dialect::Fanuc,
        setup,
        others: None,
        lod: None,
    }
}

/// Steps `service` until it is idle, returning the stock replies in order.
fn cuts(service: &mut Service) -> Vec<StockCut> {
    let mut out = Vec::new();
    while let Some(reply) = service.step() {
        if let Reply::Stock(cut) = reply {
            out.push(*cut);
        }
    }
    out
}

#[test]
fn the_whole_cut_comes_with_its_heights_rapids_and_problems() {
    let mut thread = Thread::spawn(|_| {}).unwrap();
    thread.send(Request::Analyse(Box::new(job(4, Setup::default()))));
    assert!(matches!(thread.wait_reply(), Some(Reply::Done(_))));
    thread.send(Request::Stock {
        generation: 4,
        upto: usize::MAX,
    });
    let cut = loop {
        match thread.wait_reply().expect("a reply") {
            Reply::Stock(cut) if cut.finished() => break cut,
            Reply::Stock(_) => {}
            other => panic!("{other:?}"),
        }
    };
    assert_eq!(
        (cut.generation, cut.upto, cut.done, cut.whole),
        (4, 6, 6, true)
    );
    assert_eq!(cut.error, None);
    let field = cut.field.as_ref().expect("heights");
    assert_eq!(field.heights.len(), field.size.0 * field.size.1);
    assert_eq!(field.top, 0.0);
    // The slot's floor, and the material beside it where the rapid went down.
    let floor = field.height_at(20.0, 0.0).unwrap();
    assert!((floor + 2.0).abs() < 1e-3, "{floor}");
    let plunged = field.height_at(10.0, 10.0).unwrap();
    assert!((plunged + 1.0).abs() < 1e-3, "{plunged}");
    assert!(field.height_at(1e6, 0.0).is_none());
    assert_eq!(cut.rapids.len(), 1);
    assert_eq!(cut.rapids[0].0, 5, "the rapid down is the sixth segment");
    let codes: Vec<_> = cut.problems.iter().map(|p| (p.line, p.code)).collect();
    assert_eq!(
        codes,
        [
            (2, "N-TOOL-ASSUMED"),
            (2, "N-STOCK-ASSUMED"),
            (7, "W-RAPID-INTO-STOCK"),
        ]
    );
    let rapid = &cut.problems[2];
    assert_eq!((rapid.col, &PROGRAM[rapid.chars.clone()]), (1, "G0 Z-1.\n"));
}

#[test]
fn a_later_segment_continues_the_cut_an_earlier_one_starts_again() {
    let mut service = Service::default();
    service.handle(Request::Analyse(Box::new(job(1, Setup::default()))));
    while !matches!(service.step(), Some(Reply::Done(_))) {}
    assert!(!service.is_busy());

    // Up to the plunge: a hole at X0 Y0, nothing found yet, no problems before the whole cut.
    assert!(
        service
            .handle(Request::Stock {
                generation: 1,
                upto: 1
            })
            .is_none()
    );
    let part = cuts(&mut service);
    let last = part.last().unwrap();
    assert_eq!((last.done, last.whole), (1, false));
    assert!(last.problems.is_empty() && last.rapids.is_empty());
    let field = last.field.as_ref().unwrap();
    assert!((field.height_at(0.0, 0.0).unwrap() + 2.0).abs() < 1e-3);
    assert_eq!(field.height_at(20.0, 0.0), Some(0.0));

    // On to the end: the cut goes on from there and gives what a whole cut gives.
    service.handle(Request::Stock {
        generation: 1,
        upto: 100,
    });
    let on = cuts(&mut service).pop().unwrap();
    let mut fresh = Service::default();
    fresh.handle(Request::Analyse(Box::new(job(1, Setup::default()))));
    while !matches!(fresh.step(), Some(Reply::Done(_))) {}
    fresh.handle(Request::Stock {
        generation: 1,
        upto: 100,
    });
    assert_eq!(Some(&on), cuts(&mut fresh).last());
    assert_eq!(on.problems.len(), 3);

    // Back to the start: started again, nothing cut.
    service.handle(Request::Stock {
        generation: 1,
        upto: 0,
    });
    let back = cuts(&mut service).pop().unwrap();
    let field = back.field.unwrap();
    assert!(field.heights.iter().all(|&h| h == 0.0));
    assert!(!service.is_busy());

    // A new job stops the cut; the old analysis is no longer there to cut.
    service.handle(Request::Stock {
        generation: 1,
        upto: 100,
    });
    service.handle(Request::Analyse(Box::new(job(2, Setup::default()))));
    let mut replies = Vec::new();
    while let Some(reply) = service.step() {
        replies.push(reply);
    }
    assert!(
        matches!(replies.as_slice(), [Reply::Done(_)]),
        "{replies:?}"
    );
    let Some(Reply::Stock(gone)) = service.handle(Request::Stock {
        generation: 1,
        upto: 5,
    }) else {
        panic!("an answer at once");
    };
    assert!(gone.finished() && gone.field.is_none() && gone.error.is_some());
}

#[test]
fn a_stock_the_setup_gets_wrong_is_named() {
    let setup = Setup::from_toml("[stock]\nmin = [0, 0, 0]\nmax = [10, 10, -5]\n").unwrap();
    let mut service = Service::default();
    service.handle(Request::Analyse(Box::new(job(3, setup))));
    while !matches!(service.step(), Some(Reply::Done(_))) {}
    let Some(Reply::Stock(cut)) = service.handle(Request::Stock {
        generation: 3,
        upto: 9,
    }) else {
        panic!("an answer at once");
    };
    let error = cut.error.unwrap();
    assert!(error.contains("stock.max"), "{error}");
}

#[test]
fn a_cut_and_its_request_read_back_from_bytes() {
    let mut service = Service::default();
    service.handle(Request::Analyse(Box::new(job(6, Setup::default()))));
    while !matches!(service.step(), Some(Reply::Done(_))) {}
    service.handle(Request::Stock {
        generation: 6,
        upto: 99,
    });
    let cut = cuts(&mut service).pop().unwrap();
    for reply in [
        Reply::Stock(Box::new(cut)),
        Reply::Stock(Box::new(StockCut {
            generation: 6,
            upto: 9,
            done: 2,
            ..StockCut::default()
        })),
    ] {
        let (head, arrays) = wire::reply_parts(&reply);
        let sizes: Vec<usize> = arrays.iter().map(|a| a.len()).collect();
        let back = wire::reply_from(&head, &sizes, |i, bytes| bytes.copy_from_slice(arrays[i]));
        assert_eq!(back, Some(reply));
        // Heights that do not fill the grid do not read.
        if let Some(size) = sizes.first() {
            assert!(wire::reply_from(&head, &[size - 4], |_, _| {}).is_none());
        }
    }
    let (head, texts) = wire::request_parts(
        &Request::Stock {
            generation: 6,
            upto: 12,
        },
        &mut Vec::new(),
    );
    assert!(texts.is_empty());
    assert!(matches!(
        wire::request_from(&head, Vec::new(), &mut Vec::new()),
        Some(Request::Stock {
            generation: 6,
            upto: 12
        })
    ));
}
