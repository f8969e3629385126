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

#[test]
fn the_stock_box_and_the_tools_are_settings_checked_as_the_cli_checks_them() {
    let wb = Workbench::default();
    // A grid's new row takes a few frames to settle its column widths.
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 1400.0))
        .with_max_steps(12)
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("Settings…").click();
    harness.run();
    // Off: no `[stock]`, a box is assumed.
    assert!(harness.state().setup().stock.is_none());
    harness.get_by_label("Off: a box around the feed moves is assumed, with a note saying so");
    harness
        .get_by_role_and_label(Role::CheckBox, "Stock box")
        .click_accesskit();
    harness.run();
    harness
        .get_by_label("Stock max X")
        .set_value_accesskit(80.0);
    harness.run();
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("[stock]"), "{toml}");
    assert!(toml.contains("max = [80.0, 50.0, 0.0]"), "{toml}");
    assert!(!toml.contains("cell_mm"), "{toml}");
    harness.get_by_label("auto");
    // A fixed cell starts at the one the stock crate would choose: the longer side / 1024.
    harness
        .get_by_role_and_label(Role::CheckBox, "Cell size (mm)")
        .click_accesskit();
    harness.run();
    let stock = harness.state().setup().stock.clone().unwrap();
    assert_eq!(stock["cell_mm"].as_float(), Some(80.0 / 1024.0));

    // A tool row writes `[tools.N]`, keys as the stock crate reads them.
    assert!(harness.state().setup().tools.is_empty());
    harness.get_by_label("Add tool").click_accesskit();
    harness.run();
    harness
        .get_by_label("Tool 1 diameter")
        .set_value_accesskit(6.0);
    harness.run();
    let toml = harness.state().setup_toml().unwrap();
    assert!(toml.contains("[tools.1]"), "{toml}");
    assert!(toml.contains("diameter = 6.0"), "{toml}");
    assert!(toml.contains("shape = \"flat\""), "{toml}");
    let checked = swarf_stock::StockSetup::from_setup(harness.state().setup()).unwrap();
    assert_eq!(checked.tools[&1].diameter, 6.0);
    assert_eq!(checked.stock.unwrap().max, [80.0, 50.0, 0.0]);
    // A bull nose takes a corner radius; one past half the diameter is refused in red.
    harness.get_by_label("Tool 1 shape").click_accesskit();
    harness.run();
    harness.get_by_label("bull nose").click_accesskit();
    harness.run();
    let tool = harness.state().setup().tools[&1].clone();
    assert_eq!(tool["shape"].as_str(), Some("bull"));
    assert_eq!(tool["corner_radius"].as_float(), Some(1.5));
    harness
        .get_by_label("Tool 1 corner radius")
        .set_value_accesskit(5.0);
    harness.run();
    harness.get_by_label("`tools.1.corner_radius` must be from 0 to 3 (it is 5)");
    // So is a stock whose max lies below its min.
    harness
        .get_by_label("Stock max X")
        .set_value_accesskit(-5.0);
    harness.run();
    harness.get_by_label("`stock.max` must be above `stock.min` in X");
    // Renumbered, the tool keeps its keys; removed, it is gone.
    harness
        .get_by_label("Tool 1 number")
        .set_value_accesskit(4.0);
    harness.run();
    assert_eq!(
        harness.state().setup().tools[&4]["shape"].as_str(),
        Some("bull")
    );
    harness.get_by_label("Remove tool 4").click_accesskit();
    harness.run();
    assert!(harness.state().setup().tools.is_empty());
    // Off again: no `[stock]`.
    harness
        .get_by_role_and_label(Role::CheckBox, "Stock box")
        .click_accesskit();
    harness.run();
    assert!(harness.state().setup().stock.is_none());
}

#[test]
fn an_import_the_stock_crate_refuses_changes_nothing() {
    let mut wb = Workbench::default();
    wb.import_setup("[stock]\nmin = [0, 0, -10]\nmax = [50, 50, 0]\n[tools.2]\ndiameter = 4.0\n")
        .unwrap();
    let before = wb.setup().clone();
    for bad in [
        "[tools.2]\ndiameter = -1.0\n",
        "[tools.2]\ndiameter = 4.0\nshape = \"bull\"\n",
        "[stock]\nmin = [0, 0, 0]\nmax = [10, 10, 0]\n",
        "[stock]\nmin = [0, 0, 0]\nmax = [10, 10, 1]\nsize = 3\n",
    ] {
        let e = wb.import_setup(bad).unwrap_err();
        assert!(e.starts_with("SETUP.toml: "), "{bad}: {e}");
        assert_eq!(wb.setup(), &before, "{bad}");
    }
}
