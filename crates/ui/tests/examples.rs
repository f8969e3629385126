//! The built-in examples: one or more per dialect, each runs without an error or a warning, and
//! the File menu opens them in their dialect.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _};
use swarf_syntax::{Dialect, Severity};
use swarf_ui::Workbench;
use swarf_ui::examples::EXAMPLES;

#[test]
fn every_example_interprets_cleanly_in_its_dialect() {
    for ex in EXAMPLES {
        let job = swarf_analysis::Job {
            generation: 1,
            text: ex.text.to_string().into(),
            dialect: ex.dialect,
            setup: swarf_interp::Setup::default(),
            others: None,
            lod: None,
        };
        let analysis = swarf_analysis::analyse(job).0;
        let bad: Vec<_> = analysis
            .problems
            .iter()
            .filter(|p| p.severity >= Severity::Warning)
            .collect();
        assert!(bad.is_empty(), "{}: {bad:#?}", ex.name);
        assert!(analysis.stats.motions >= 5, "{} draws too little", ex.name);
    }
    for d in Dialect::ALL {
        assert!(
            EXAMPLES.iter().any(|e| e.dialect == d),
            "no example for {d:?}"
        );
    }
}

/// A workbench with the menu's example `entry` opened (File → Examples) and analysed.
fn open_example(entry: &str) -> Harness<'static, Workbench> {
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), Workbench::default());
    harness.run();
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Examples").click();
    harness.run();
    harness.get_by_label(entry).click();
    harness.run();
    harness.state_mut().finish_analysis();
    harness
}

#[test]
fn the_examples_menu_opens_a_program_in_its_dialect() {
    let harness = open_example("linuxcnc-engrave-sub.ngc  (LinuxCNC)");
    let wb = harness.state();
    assert_eq!(wb.dialect(), Dialect::LinuxCnc);
    assert_eq!(wb.document().name, "linuxcnc-engrave-sub.ngc");
    assert!(wb.text().contains("o100 sub"));
    assert!(!wb.document().is_unsaved());
    assert!(wb.problems().iter().all(|p| p.severity < Severity::Warning));
}

#[test]
fn the_syntec_example_opens_in_syntec_in_its_own_tab() {
    let mut harness = open_example("syntec-bolt-circle.nc  (Syntec 900M)");
    let wb = harness.state();
    assert_eq!(wb.document().name, "syntec-bolt-circle.nc");
    assert_eq!(wb.dialect(), Dialect::Syntec);
    assert!(
        wb.problems().iter().all(|p| p.code != "E-CODE-DIALECT"),
        "{:?}",
        wb.problems()
    );
    assert_eq!(wb.suggested_dialect(), None);
    assert_eq!(
        harness
            .get_by_label("Dialect")
            .accesskit_node()
            .value()
            .as_deref(),
        Some("Syntec 900M")
    );
    // The tab it came from and the tabs opened next keep their dialect.
    let wb = harness.state_mut();
    assert_eq!(wb.tab_dialect(0), Some(Dialect::Fanuc));
    assert_eq!(wb.default_dialect(), Dialect::Fanuc);
    wb.new_tab();
    assert_eq!(wb.dialect(), Dialect::Fanuc);
}

#[test]
fn every_example_read_in_another_dialect_is_offered_its_own_or_none() {
    // An example whose codes another dialect lacks is offered back to its own dialect (or to
    // one that reads it as cleanly), never to a worse one.
    let mut offers = Vec::new();
    for ex in EXAMPLES {
        for d in Dialect::ALL {
            let mut wb = Workbench::default();
            wb.open_document(ex.name, ex.text, swarf_syntax::Encoding::Utf8);
            assert_eq!(wb.dialect(), ex.dialect);
            wb.set_tab_dialect(wb.active_tab(), d);
            wb.finish_analysis();
            let Some(offered) = wb.suggested_dialect() else {
                continue;
            };
            assert_ne!(offered, d);
            let here = wb
                .problems()
                .iter()
                .filter(|p| p.severity == Severity::Error)
                .count();
            wb.set_dialect(offered);
            wb.finish_analysis();
            let there = wb
                .problems()
                .iter()
                .filter(|p| p.severity == Severity::Error)
                .count();
            assert!(
                there < here,
                "{} in {d:?}: {offered:?} has {there} errors, not fewer than {here}",
                ex.name
            );
            offers.push((ex.name, d, offered));
        }
    }
    // The Syntec and LinuxCNC examples are told apart from every other dialect.
    for ex in EXAMPLES
        .iter()
        .filter(|e| matches!(e.dialect, Dialect::Syntec | Dialect::LinuxCnc))
    {
        for d in Dialect::ALL.into_iter().filter(|&d| d != ex.dialect) {
            assert!(
                offers.contains(&(ex.name, d, ex.dialect)),
                "{} in {d:?} is not offered {:?}: {offers:?}",
                ex.name,
                ex.dialect
            );
        }
    }
}

#[test]
fn an_example_opened_as_a_file_opens_in_its_dialect_and_its_copy_is_offered_it() {
    let syntec = EXAMPLES
        .iter()
        .find(|e| e.dialect == Dialect::Syntec)
        .unwrap();
    // `assets/examples/syntec-bolt-circle.nc` opened from the disk, in a Fanuc workbench.
    let mut wb = Workbench::default();
    wb.open_file(
        syntec.name,
        syntec.text.to_string(),
        swarf_syntax::Encoding::Utf8,
        Some("/work/assets/examples/syntec-bolt-circle.nc".into()),
    );
    assert_eq!(wb.dialect(), Dialect::Syntec);
    wb.finish_analysis();
    assert!(wb.analysis_ready());
    assert!(wb.problems().iter().all(|p| p.code != "E-CODE-DIALECT"));
    assert_eq!(wb.default_dialect(), Dialect::Fanuc);
    // A changed copy opens in the default dialect, with the offer of Syntec.
    let copy = syntec.text.replace("Z-12.", "Z-15.");
    wb.open_file(
        "flange.nc",
        copy,
        swarf_syntax::Encoding::Utf8,
        Some("/work/flange.nc".into()),
    );
    assert_eq!(wb.dialect(), Dialect::Fanuc);
    wb.finish_analysis();
    assert!(wb.problems().iter().any(|p| p.code == "E-CODE-DIALECT"));
    assert_eq!(wb.suggested_dialect(), Some(Dialect::Syntec));
}
