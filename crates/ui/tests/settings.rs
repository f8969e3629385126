//! The settings window: offset registers, work offsets and machine parameters edit the setup
//! programs run with, and the setup goes out and in as SETUP.toml.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use swarf_ui::{HostRequest, Workbench};

#[test]
fn the_settings_window_edits_the_setup_and_re_runs_the_program() {
    let mut wb = Workbench::default();
    wb.open_document(
        "t.nc",
        "G90 G21 G55\nG00 X0 Y0 Z0\nM30\n",
        swarf_syntax::Encoding::Utf8,
    );
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("Settings…").click();
    harness.run();
    harness.get_by_label("Offset registers (H length, D radius)");
    harness.get_by_label("Add register").click();
    harness.run();
    assert_eq!(harness.state().setup().registers.len(), 1);
    // An extended work offset by name.
    let field = harness.get_by_role_and_label(Role::TextInput, "Add offset");
    field.focus();
    field.type_text("g54.1 p3");
    harness.run();
    harness.get_by_label("Add").click();
    harness.run();
    assert!(harness.state().setup().work_offsets.contains_key("G54.1P3"));
    harness.get_by_label("G54.1P3");
    // Import moves G55, and the program's rapid follows it.
    let before = harness.state().analysis().scene.generation;
    harness
        .state_mut()
        .import_setup("[work_offsets]\nG55 = [100, 50, -20]\n")
        .unwrap();
    harness.run();
    harness.state_mut().finish_analysis();
    assert!(harness.state().analysis().scene.generation > before);
    let bounds = harness.state().stats().bounds.unwrap();
    assert_eq!(bounds.1.x, 100.0);
    // Export asks the host, with the setup as SETUP.toml.
    harness.get_by_label("Export SETUP.toml…").click();
    harness.run();
    assert_eq!(
        harness.state_mut().take_requests(),
        [HostRequest::ExportSetup]
    );
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("G55 = [100.0, 50.0, -20.0]"), "{toml}");
    assert!(
        harness
            .state_mut()
            .import_setup("[work_offsets]\nG60 = [0, 0, 0]\n")
            .is_err()
    );
    assert!(harness.state().setup().work_offsets.contains_key("G55"));
}

#[test]
fn the_machine_travel_and_drilling_parameters_are_settings_too() {
    let wb = Workbench::default();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 1400.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("Settings…").click();
    harness.run();
    assert!(harness.state().setup().machine.travel_mm.is_none());
    harness
        .get_by_role_and_label(Role::CheckBox, "Machine travel min / max X Y Z")
        .click();
    harness.run();
    assert!(harness.state().setup().machine.travel_mm.is_some());
    // The drilling and compensation parameters are there too.
    harness.get_by_label("G81 retracts at F2= (Pr4008 = 1)");
    harness.get_by_label("Peck tapping backs out by the peck retract (Pr4001 = 1)");
    harness.get_by_label("stop with an alarm (Syntec 3819)");
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("travel_mm"), "{toml}");
    // Whether a mirror swaps G41/G42: the dialect's default until chosen.
    assert_eq!(harness.state().setup().machine.mirror_swaps_comp_side, None);
    harness.get_by_role_and_label(Role::ComboBox, "G41/G42 under a mirror");
    harness
        .state_mut()
        .import_setup("[machine]\nmirror_swaps_comp_side = false\n")
        .unwrap();
    harness.run();
    assert_eq!(
        harness.state().setup().machine.mirror_swaps_comp_side,
        Some(false)
    );
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("mirror_swaps_comp_side = false"), "{toml}");
}

#[test]
fn a_register_holds_a_lathe_tool_orientation() {
    let mut wb = Workbench::default();
    wb.import_setup("[registers.2]\nradius = 0.4\norientation = 3\n")
        .unwrap();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("Settings…").click();
    harness.run();
    harness.get_by_label("Register 2 tool orientation");
    assert_eq!(harness.state().setup().registers[&2].orientation, 3);
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("orientation = 3"), "{toml}");
}
