//! The settings window's contents: dialect, offset registers, work offsets, machine
//! parameters, stock and tools — everything `SETUP.toml` holds, edited in place.

use glam::DVec3;
use swarf_interp::{CornerMode, Register, Setup, ShiftDirection};
use swarf_stock::{Shape, StockSetup, Tool};
use swarf_syntax::Dialect;
use toml::{Table, Value};

use crate::i18n::tr;
use crate::workbench::HostRequest;

/// The fixed work offsets always listed (extended ones are added by name).
const STANDARD_OFFSETS: [&str; 6] = ["G54", "G55", "G56", "G57", "G58", "G59"];

/// Shows and edits the settings for `dialect` and `setup` (`new_offset`: the name typed for an
/// extra work offset); an import or export request when one of those buttons was pressed.
pub fn settings_ui(
    ui: &mut egui::Ui,
    dialect: &mut Dialect,
    setup: &mut Setup,
    new_offset: &mut String,
) -> Option<HostRequest> {
    let mut request = None;
    let dialects = Dialect::ALL.map(|d| (d, d.label()));
    let (id, label) = ("swarf-settings-dialect", tr("Dialect"));
    ui.horizontal(|ui| choice(ui, id, label, dialect, &dialects));
    ui.horizontal(|ui| {
        if ui.button(tr("Import SETUP.toml…")).clicked() {
            request = Some(HostRequest::ImportSetup);
        }
        if ui.button(tr("Export SETUP.toml…")).clicked() {
            request = Some(HostRequest::ExportSetup);
        }
        if ui.button(tr("Reset to defaults")).clicked() {
            *setup = Setup::default();
        }
    });
    ui.label(tr("Values in millimetres; they are kept between runs."));
    let registers = tr("Offset registers (H length, D radius)");
    let sections: [(&str, Section); 5] = [
        (registers, |ui, s, _| registers_ui(ui, s)),
        (tr("Work offsets"), work_offsets_ui),
        (tr("Machine"), |ui, s, _| machine_ui(ui, s)),
        (tr("Stock"), |ui, s, _| stock_ui(ui, s)),
        (tr("Tools"), |ui, s, _| tools_ui(ui, s)),
    ];
    for (head, section) in sections {
        egui::CollapsingHeader::new(head)
            .default_open(true)
            .show(ui, |ui| section(ui, setup, new_offset));
    }
    request
}

/// A part of the settings window: draws its fields of the setup (and the new offset's name).
type Section = fn(&mut egui::Ui, &mut Setup, &mut String);

/// A combo box named by the label `label` choosing `value` among `options`, each with its text.
pub(crate) fn choice<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    id: &str,
    label: &str,
    value: &mut T,
    options: &[(T, &str)],
) {
    let label = ui.label(label);
    let shown = options.iter().find(|(o, _)| o == value);
    let shown = shown.map_or("", |(_, text)| *text);
    egui::ComboBox::from_id_salt(id)
        .selected_text(shown)
        .show_ui(ui, |ui| {
            for &(option, text) in options {
                ui.selectable_value(value, option, text);
            }
        })
        .response
        .labelled_by(label.id);
}

/// A grid row: `label`, then `drag` named by it.
pub(crate) fn drag_row(ui: &mut egui::Ui, label: &str, drag: egui::DragValue<'_>) {
    let label = ui.label(label);
    ui.add(drag).labelled_by(label.id);
    ui.end_row();
}

/// Gives `response` an accessible name (for screen readers) where no label widget names it.
fn named(ui: &egui::Ui, response: egui::Response, name: &str) -> egui::Response {
    ui.ctx()
        .accesskit_node_builder(response.id, |node| node.set_label(name));
    response
}

fn length(value: &mut f64) -> egui::DragValue<'_> {
    egui::DragValue::new(value).speed(0.01).max_decimals(4)
}

/// Three length fields named `{name} X`, `{name} Y` and `{name} Z`; whether one changed.
fn xyz(ui: &mut egui::Ui, values: &mut [f64; 3], name: &str) -> bool {
    let mut changed = false;
    for (c, axis) in values.iter_mut().zip(["X", "Y", "Z"]) {
        let response = ui.add(length(c));
        changed |= named(ui, response, &format!("{name} {axis}")).changed();
    }
    changed
}

/// A striped grid `id` of `columns` columns.
fn table(id: &str, columns: usize) -> egui::Grid {
    egui::Grid::new(id).num_columns(columns).striped(true)
}

/// A grid's row of column heads (looked up with `tr`).
fn heads(ui: &mut egui::Ui, heads: &[&'static str]) {
    for head in heads {
        ui.strong(tr(head));
    }
    ui.end_row();
}

/// A × button that removes the row, named `name`; whether it was clicked.
fn remove_button(ui: &mut egui::Ui, name: &str) -> bool {
    let button = ui.small_button("×").on_hover_text(tr("Remove"));
    named(ui, button, name).clicked()
}

fn registers_ui(ui: &mut egui::Ui, setup: &mut Setup) {
    let mut remove = None;
    table("swarf-registers", 7).show(ui, |ui| {
        heads(ui, &["No.", "Length", "Length wear", "Radius", "Radius wear", "Tip (lathe)", ""]);
        for (n, r) in &mut setup.registers {
            ui.label(n.to_string());
            let fields = [
                (&mut r.length, "length"),
                (&mut r.length_wear, "length wear"),
                (&mut r.radius, "radius"),
                (&mut r.radius_wear, "radius wear"),
            ];
            for (value, what) in fields {
                let response = ui.add(length(value));
                named(ui, response, &format!("Register {n} {what}"));
            }
            let drag = egui::DragValue::new(&mut r.orientation).range(0..=9);
            let response = ui.add(drag).on_hover_text(tr(
                "Lathe tool tip direction 1-8 (LinuxCNC's Q): compensation in G18 reports the imaginary tip; 0 a mill, 9 the nose centre",
            ));
            named(ui, response, &format!("Register {n} tool orientation"));
            if remove_button(ui, &format!("Remove register {n}")) {
                remove = Some(*n);
            }
            ui.end_row();
        }
    });
    if let Some(n) = remove {
        setup.registers.remove(&n);
    }
    if ui.button(tr("Add register")).clicked() {
        let next = setup.registers.keys().next_back().map_or(1, |n| n + 1);
        setup.registers.insert(next, Register::default());
    }
}

fn work_offsets_ui(ui: &mut egui::Ui, setup: &mut Setup, new_offset: &mut String) {
    let extended = setup.work_offsets.keys().cloned();
    let extended = extended.filter(|n| !STANDARD_OFFSETS.contains(&n.as_str()));
    let mut names = STANDARD_OFFSETS.map(String::from).to_vec();
    names.extend(extended);
    table("swarf-work-offsets", 4).show(ui, |ui| {
        heads(ui, &["", "X", "Y", "Z"]);
        for name in names {
            let mut v = setup.work_offset(&name).to_array();
            ui.label(&name);
            if xyz(ui, &mut v, &name) {
                setup.work_offsets.insert(name, DVec3::from_array(v));
            }
            ui.end_row();
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label(tr("Add offset"));
        let field = egui::TextEdit::singleline(new_offset).desired_width(90.0);
        ui.add(field.hint_text("G54.1P1")).labelled_by(label.id);
        if ui.button(tr("Add")).clicked() {
            let toml = format!("[work_offsets]\n{:?} = [0, 0, 0]\n", new_offset.trim());
            if let Ok(parsed) = Setup::from_toml(&toml) {
                for name in parsed.work_offsets.into_keys() {
                    setup.work_offsets.entry(name).or_insert(DVec3::ZERO);
                }
                new_offset.clear();
            }
        }
    });
}

fn machine_ui(ui: &mut egui::Ui, setup: &mut Setup) {
    let m = &mut setup.machine;
    egui::Grid::new("swarf-machine")
        .num_columns(2)
        .show(ui, |ui| {
            fn rate(v: &mut f64) -> egui::DragValue<'_> {
                egui::DragValue::new(v).range(1.0..=1_000_000.0).speed(10.0)
            }
            drag_row(ui, tr("Rapid rate (mm/min)"), rate(&mut m.rapid_mm_per_min));
            let mut per_axis = m.rapid_xyz_mm_per_min.is_some();
            let label = tr("Rapid rate per axis X Y Z");
            let per_axis_label = ui.checkbox(&mut per_axis, label).id;
            let mut xyz = m.rapid_xyz_mm_per_min.unwrap_or([m.rapid_mm_per_min; 3]);
            ui.horizontal(|ui| {
                ui.add_enabled_ui(per_axis, |ui| {
                    for v in &mut xyz {
                        ui.add(rate(v)).labelled_by(per_axis_label);
                    }
                });
            });
            m.rapid_xyz_mm_per_min = per_axis.then_some(xyz);
            ui.end_row();
            fn upto(v: &mut f64, max: f64, speed: f64) -> egui::DragValue<'_> {
                egui::DragValue::new(v).range(0.0..=max).speed(speed)
            }
            let acceleration = upto(&mut m.acceleration_mm_per_s2, 100_000.0, 1.0);
            drag_row(ui, tr("Acceleration (mm/s²)"), acceleration);
            let peck = upto(&mut m.peck_retract_mm, 100.0, 0.01);
            drag_row(ui, tr("Peck retract (mm)"), peck);
            let tolerance = upto(&mut m.arc_tolerance_mm, 10.0, 0.001).max_decimals(4);
            drag_row(ui, tr("Arc tolerance (mm)"), tolerance);
            let blocks = egui::DragValue::new(&mut m.max_blocks).range(1..=1_000_000_000_u64);
            drag_row(ui, tr("Runaway limit (blocks)"), blocks);
            let moves = egui::DragValue::new(&mut m.max_motions).range(1..=1_000_000_000_u64);
            drag_row(ui, tr("Move limit (moves)"), moves);
            let mut travel = m.travel_mm.is_some();
            let label = tr("Machine travel min / max X Y Z");
            let travel_label = ui.checkbox(&mut travel, label).id;
            let default = [[-500.0, -400.0, -400.0], [0.0, 0.0, 0.0]];
            let mut bounds = m.travel_mm.unwrap_or(default);
            ui.vertical(|ui| {
                ui.add_enabled_ui(travel, |ui| {
                    for corner in &mut bounds {
                        ui.horizontal(|ui| {
                            for c in corner.iter_mut() {
                                ui.add(length(c)).labelled_by(travel_label);
                            }
                        });
                    }
                });
            });
            m.travel_mm = travel.then_some(bounds);
            ui.end_row();
            let label = tr("G76/G87 shift direction");
            choice(ui, "swarf-shift", label, &mut m.shift_direction, &SHIFTS);
            ui.end_row();
            ui.label(tr("Syntec drilling"));
            ui.vertical(|ui| {
                ui.checkbox(&mut m.fast_drilling, tr("G81 retracts at F2= (Pr4008 = 1)"));
                let text = tr("Peck tapping backs out by the peck retract (Pr4001 = 1)");
                ui.checkbox(&mut m.high_speed_peck_tapping, text);
            });
            ui.end_row();
            let fanuc = tr("intersection (Fanuc family)");
            let corners = [
                (None, tr("as the dialect does")),
                (Some(CornerMode::Arc), tr("arc (LinuxCNC)")),
                (Some(CornerMode::Intersection), fanuc),
            ];
            let label = tr("Cutter compensation corners");
            choice(ui, "swarf-corner", label, &mut m.corner_mode, &corners);
            ui.end_row();
            ui.label(tr("Gouges"));
            ui.checkbox(&mut m.overcut_alarm, tr("stop with an alarm (Syntec 3819)"));
            ui.end_row();
            let sides = [
                (None, tr("the dialect's default")),
                (Some(true), tr("swapped by the control (Fanuc)")),
                (Some(false), tr("as written (Syntec's example)")),
            ];
            let (label, value) = (tr("G41/G42 under a mirror"), &mut m.mirror_swaps_comp_side);
            choice(ui, "swarf-mirror-side", label, value, &sides);
            ui.end_row();
            let inputs = [
                (None, tr("as the dialect's manual says")),
                (Some(true), tr("millimetres (calculator input)")),
                (Some(false), tr("least input increments")),
            ];
            let (label, value) = (tr("Integers without a point"), &mut m.calculator_input);
            choice(ui, "swarf-calculator", label, value, &inputs);
            ui.end_row();
            let names = ["G28 reference point", "G30 P2 reference point"];
            for (i, name) in names.into_iter().enumerate() {
                let label = ui.label(tr(name)).id;
                let mut p = m.reference_points.get(i).copied().unwrap_or_default();
                let mut changed = false;
                ui.horizontal(|ui| {
                    for c in &mut p {
                        changed |= ui.add(length(c)).labelled_by(label).changed();
                    }
                });
                if changed {
                    if m.reference_points.len() <= i {
                        m.reference_points.resize(i + 1, [0.0; 3]);
                    }
                    m.reference_points[i] = p;
                }
                ui.end_row();
            }
        });
}

/// The number `value` holds (a TOML integer too), if it is one.
fn number(value: &Value) -> Option<f64> {
    value.as_float().or(value.as_integer().map(|v| v as f64))
}

/// Three numbers as a TOML array.
fn floats(values: [f64; 3]) -> Value {
    Value::Array(values.into_iter().map(Value::Float).collect())
}

/// A drag value for the number at `key` of `table` (`shown` while the key is unset), named
/// `name`; written back only when changed, so a table as imported stays as written.
fn table_value(ui: &mut egui::Ui, table: &mut Table, key: &str, shown: f64, name: &str) {
    let mut value = table.get(key).and_then(number).unwrap_or(shown);
    let response = ui.add(length(&mut value));
    if named(ui, response, name).changed() {
        table.insert(key.to_string(), Value::Float(value));
    }
}

/// The stock crate's objection to `checked`, in red.
fn refusal<T>(ui: &mut egui::Ui, checked: Result<T, swarf_stock::StockError>) {
    if let Err(e) = checked {
        ui.colored_label(ui.visuals().error_fg_color, e.to_string());
    }
}

/// The stock box (`[stock]`, machine coordinates; without one, one around the feed moves).
fn stock_ui(ui: &mut egui::Ui, setup: &mut Setup) {
    let mut on = setup.stock.is_some();
    ui.checkbox(&mut on, tr("Stock box"));
    if !on {
        setup.stock = None;
        ui.label(tr(
            "Off: a box around the feed moves is assumed, with a note saying so",
        ));
        return;
    }
    let stock = setup.stock.get_or_insert_with(|| {
        Table::from_iter([
            ("min".to_string(), floats([0.0, 0.0, -20.0])),
            ("max".to_string(), floats([100.0, 50.0, 0.0])),
        ])
    });
    let read = |stock: &Table| {
        StockSetup::from_setup(&Setup {
            stock: Some(stock.clone()),
            ..Setup::default()
        })
    };
    egui::Grid::new("swarf-stock")
        .num_columns(4)
        .show(ui, |ui| {
            heads(ui, &["", "X", "Y", "Z"]);
            for (key, head) in [("min", tr("Min")), ("max", tr("Max"))] {
                ui.label(head);
                let numbers = stock.get(key).and_then(Value::as_array);
                let at = |i: usize| numbers.and_then(|a| a.get(i)).and_then(number);
                let mut corner: [f64; 3] = std::array::from_fn(|i| at(i).unwrap_or_default());
                if xyz(ui, &mut corner, &format!("Stock {key}")) {
                    stock.insert(key.to_string(), floats(corner));
                }
                ui.end_row();
            }
            let had = stock.contains_key("cell_mm");
            let mut fixed = had;
            ui.checkbox(&mut fixed, tr("Cell size (mm)"));
            if fixed && !had {
                // Start from the cell the stock crate would choose.
                let auto = read(stock).ok().and_then(|s| s.stock?.grid().ok());
                let auto = auto.map_or(1.0, |(cell, _, _)| cell);
                stock.insert("cell_mm".to_string(), Value::Float(auto));
            }
            if fixed {
                table_value(ui, stock, "cell_mm", 0.0, "Stock cell size");
            } else {
                stock.remove("cell_mm");
                ui.label(tr("auto"));
            }
            ui.end_row();
        });
    refusal(ui, read(stock));
}

/// The shapes a `[tools.N]` table may name, as written there, and as the window shows them.
const SHAPES: [(&str, &str); 5] = [
    ("flat", "flat end mill"),
    ("ball", "ball end mill"),
    ("bull", "bull nose"),
    ("drill", "drill"),
    ("chamfer", "chamfer mill"),
];

/// The tools the stock is cut with (`[tools.N]`), a row each.
fn tools_ui(ui: &mut egui::Ui, setup: &mut Setup) {
    ui.label(tr(
        "A tool not listed cuts as a flat end mill of its register's diameter, or of 10 mm",
    ));
    let mut remove = None;
    let mut renumber = None;
    table("swarf-tools", 7).show(ui, |ui| {
        let (no, diameter, shape) = ("No.", "Diameter", "Shape");
        let (corner, point, flute) = ("Corner radius", "Point angle (°)", "Flute length");
        heads(ui, &[no, diameter, shape, corner, point, flute, ""]);
        for (&n, tool) in &mut setup.tools {
            let mut to = n;
            let response = ui.add(egui::DragValue::new(&mut to));
            if named(ui, response, &format!("Tool {n} number")).changed() {
                renumber = Some((n, to));
            }
            let diameter = Tool::default().diameter;
            let name = format!("Tool {n} diameter");
            table_value(ui, tool, "diameter", diameter, &name);
            let shape = tool.get("shape").and_then(Value::as_str).unwrap_or("flat");
            let shape = shape.to_string();
            let mut chosen = shape.clone();
            let shown = SHAPES.iter().find(|(s, _)| *s == shape);
            let response = egui::ComboBox::from_id_salt(("swarf-tool-shape", n))
                .selected_text(shown.map_or(shape.as_str(), |(_, label)| tr(label)))
                .show_ui(ui, |ui| {
                    for (s, label) in SHAPES {
                        ui.selectable_value(&mut chosen, s.to_string(), tr(label));
                    }
                })
                .response;
            named(ui, response, &format!("Tool {n} shape"));
            if chosen != shape {
                // Each shape's own keys: a bull nose needs its corner, a point its default.
                tool.remove("corner_radius");
                tool.remove("point_angle_deg");
                if chosen == "bull" {
                    let d = tool.get("diameter").and_then(number).unwrap_or(diameter);
                    tool.insert("corner_radius".to_string(), Value::Float(d / 4.0));
                }
                tool.insert("shape".to_string(), Value::String(chosen));
            }
            // The tool as the stock crate reads it, for the defaults it fills in.
            let read = Value::Table(tool.clone()).try_into::<Tool>().ok();
            let (corner, point) = match read.map(|t| t.shape) {
                Some(Shape::Bull { corner_radius }) => (Some(corner_radius), None),
                Some(Shape::Drill { point_angle_deg } | Shape::Chamfer { point_angle_deg }) => {
                    (None, Some(point_angle_deg))
                }
                _ => (None, None),
            };
            for (key, shown, what) in [
                ("corner_radius", corner, "corner radius"),
                ("point_angle_deg", point, "point angle"),
            ] {
                if let Some(shown) = shown {
                    table_value(ui, tool, key, shown, &format!("Tool {n} {what}"));
                } else {
                    ui.label("");
                }
            }
            ui.horizontal(|ui| {
                let had = tool.contains_key("flute_length");
                let mut given = had;
                let response = ui.checkbox(&mut given, "");
                named(ui, response, &format!("Tool {n} flute length given"));
                if given && !had {
                    let d = tool.get("diameter").and_then(number).unwrap_or(diameter);
                    tool.insert("flute_length".to_string(), Value::Float(3.0 * d));
                }
                if given {
                    let name = format!("Tool {n} flute length");
                    table_value(ui, tool, "flute_length", 0.0, &name);
                } else {
                    tool.remove("flute_length");
                }
            });
            if remove_button(ui, &format!("Remove tool {n}")) {
                remove = Some(n);
            }
            ui.end_row();
        }
    });
    if let Some(n) = remove {
        setup.tools.remove(&n);
    }
    if let Some((from, to)) = renumber
        && !setup.tools.contains_key(&to)
        && let Some(tool) = setup.tools.remove(&from)
    {
        setup.tools.insert(to, tool);
    }
    let next = setup.tools.keys().next_back();
    let next = next.map_or(Some(1), |n| n.checked_add(1));
    if ui.button(tr("Add tool")).clicked()
        && let Some(next) = next
    {
        let diameter = Value::Float(Tool::default().diameter);
        let tool = Table::from_iter([
            ("diameter".to_string(), diameter),
            ("shape".to_string(), Value::String("flat".to_string())),
        ]);
        setup.tools.insert(next, tool);
    }
    let tools = Setup {
        tools: setup.tools.clone(),
        ..Setup::default()
    };
    refusal(ui, StockSetup::from_setup(&tools));
}

/// Each shift direction as the setup writes it.
const SHIFTS: [(ShiftDirection, &str); 6] = [
    (ShiftDirection::PlusX, "+X"),
    (ShiftDirection::MinusX, "-X"),
    (ShiftDirection::PlusY, "+Y"),
    (ShiftDirection::MinusY, "-Y"),
    (ShiftDirection::PlusZ, "+Z"),
    (ShiftDirection::MinusZ, "-Z"),
];
