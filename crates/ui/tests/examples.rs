//! The built-in examples: one or more per dialect, each runs without an error or a warning, and
//! the File menu opens them in their dialect.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_syntax::{Dialect, Severity};
use swarf_ui::examples::EXAMPLES;
use swarf_ui::{Analysis, Workbench};

#[test]
fn every_example_interprets_cleanly_in_its_dialect() {
    for ex in EXAMPLES {
        let analysis = Analysis::run(ex.text, ex.dialect, &swarf_interp::Setup::default(), 1);
        let bad: Vec<_> = analysis
            .problems
            .iter()
            .filter(|p| p.severity >= Severity::Warning)
            .collect();
        assert!(bad.is_empty(), "{}: {bad:#?}", ex.name);
        assert!(
            analysis.stats().motions >= 5,
            "{} draws too little",
            ex.name
        );
    }
    for d in Dialect::ALL {
        assert!(
            EXAMPLES.iter().any(|e| e.dialect == d),
            "no example for {d:?}"
        );
    }
}

#[test]
fn the_examples_menu_opens_a_program_in_its_dialect() {
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), Workbench::default());
    harness.run();
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Examples").click();
    harness.run();
    harness
        .get_by_label("linuxcnc-engrave-sub.ngc  (LinuxCNC)")
        .click();
    harness.run();
    let wb = harness.state();
    assert_eq!(wb.dialect(), Dialect::LinuxCnc);
    assert_eq!(wb.document().name, "linuxcnc-engrave-sub.ngc");
    assert!(wb.text().contains("o100 sub"));
    assert!(!wb.is_dirty());
    assert!(wb.problems().iter().all(|p| p.severity < Severity::Warning));
}
