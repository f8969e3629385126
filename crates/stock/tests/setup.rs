//! A setup's `[stock]` and `[tools.N]` read and checked, and a toolpath cut out of them with
//! its notes and findings as diagnostics at their lines.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Setup, run};
use swarf_stock::{Shape, StockError, StockRun, StockSetup, line_span};
use swarf_syntax::{Dialect, LineIndex, Severity, parse};
use swarf_toolpath::Toolpath;

const STOCK: &str = "[stock]\nmin = [0, 0, -20]\nmax = [100, 50, 0]\n";

/// A slot along Y25 with T1, then a rapid up inside it and out across the block 2 mm below its
/// top (line 7).
const PROGRAM: &str =
    "T1 M6\nG0 Z50.\nG0 X20. Y25. Z5.\nG1 Z-5. F100\nG1 X70.\nG0 Z-2.\nG0 X90. Y10.\nG0 Z50.\n";

fn setup(toml: &str) -> (Setup, StockSetup) {
    let setup = Setup::from_toml(toml).unwrap();
    let stock = StockSetup::from_setup(&setup).unwrap();
    (setup, stock)
}

/// A diagnostic as (line, code, message).
type Found = (u32, &'static str, String);

/// Runs `program` and cuts it out of `toml`'s stock: the run and its diagnostics.
fn cut(program: &str, toml: &str) -> Option<(StockRun, Vec<Found>)> {
    let (setup, stock) = setup(toml);
    let parsed = parse(program, Dialect::Fanuc);
    let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    let diags = run(&parsed, setup, &mut path);
    assert!(diags.is_empty(), "{diags:?}");
    let mut cut = StockRun::new(&path, &stock)?;
    let mut steps = 0;
    while !cut.simulation.step(&path, 2) {
        steps += 1;
    }
    assert!(steps > 1);
    let lines = LineIndex::new(program);
    let diags = cut
        .diagnostics(|line| line_span(&lines, line))
        .into_iter()
        .map(|d| {
            let (line, col) = lines.line_col(program, d.span.start);
            assert_eq!(col, 1);
            let text = &program[d.span.range()];
            assert!(
                text.ends_with('\n') && text.lines().count() == 1,
                "{text:?}"
            );
            let severity = if d.code.starts_with("N-") {
                Severity::Note
            } else {
                Severity::Warning
            };
            assert_eq!(d.severity, severity);
            (line, d.code, d.message)
        })
        .collect();
    Some((cut, diags))
}

#[test]
fn stock_and_tools_are_read_from_the_setup() {
    let (_, stock) = setup(&format!(
        "{STOCK}cell_mm = 0.5\n[tools.2]\ndiameter = 6\nshape = \"ball\"\nflute_length = 10\n"
    ));
    let s = stock.stock.unwrap();
    assert_eq!(
        (s.min, s.max, s.cell_mm),
        ([0.0, 0.0, -20.0], [100.0, 50.0, 0.0], Some(0.5))
    );
    assert_eq!(stock.tools[&2].shape, Shape::Ball);
    assert_eq!(stock.tools[&2].flute_length, Some(10.0));
    assert_eq!(
        StockSetup::from_setup(&Setup::default()).unwrap(),
        StockSetup::default()
    );
}

#[test]
fn a_bad_stock_or_tool_is_refused_naming_its_key() {
    for (toml, key) in [
        ("[stock]\nmin = [0, 0, 0]\nmax = [1e9, 1, 1]\n", "stock.max"),
        (&format!("{STOCK}cell_mm = 0\n"), "stock.cell_mm"),
        ("[tools.3]\ndiameter = 0\n", "tools.3.diameter"),
        (
            "[tools.4]\ndiameter = 6\nshape = \"bull\"\ncorner_radius = 4\n",
            "tools.4.corner_radius",
        ),
    ] {
        let setup = Setup::from_toml(toml).unwrap();
        match StockSetup::from_setup(&setup) {
            Err(StockError::Range { key: k, .. }) => assert_eq!(k, key, "{toml}"),
            other => panic!("{toml}: {other:?}"),
        }
    }
    for (toml, table) in [
        ("[stock]\nmin = [0, 0, 0]\n", "`[stock]`"),
        ("[stock]\nmin = [0, 0]\nmax = [1, 1, 1]\n", "`[stock]`"),
        ("[tools.5]\ndiameter = 6\nlength = 3\n", "`[tools.5]`"),
        ("[tools.6]\ndiameter = 6\nshape = \"bull\"\n", "`[tools.6]`"),
        ("[tools.7]\ndiameter = \"big\"\n", "`[tools.7]`"),
    ] {
        let setup = Setup::from_toml(toml).unwrap();
        let e = StockSetup::from_setup(&setup).unwrap_err();
        assert!(matches!(e, StockError::Table { .. }), "{toml}: {e:?}");
        assert!(e.to_string().starts_with(table), "{toml}: {e}");
    }
    let e = StockSetup::from_setup(
        &Setup::from_toml("[stock]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n").unwrap(),
    );
    assert_eq!(e, Err(StockError::Empty { axis: 'Y' }));
}

#[test]
fn a_rapid_into_the_stock_is_a_warning_at_its_line_with_the_cell_it_meets() {
    let toml = format!("{STOCK}[tools.1]\ndiameter = 10\n");
    let (cut, diags) = cut(PROGRAM, &toml).unwrap();
    assert_eq!(diags.len(), 1, "{diags:?}");
    let (line, code, message) = &diags[0];
    assert_eq!((*line, *code), (7, "W-RAPID-INTO-STOCK"));
    // Moving from (70, 25) towards (90, 10) 2 mm below the top, the tool first meets material
    // at once past the slot's round end, about (74, 22).
    let x: f64 = message
        .split(" at X")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .unwrap()
        .parse()
        .unwrap();
    assert!((73.0..76.0).contains(&x), "{message}");
    assert!(message.ends_with("2.000 mm below its top"), "{message}");
    // The slot (50 × 10 mm plus the round ends, 5 deep) and the rapid's 2 mm deep trench.
    let slot = 5.0 * (50.0 * 10.0 + std::f64::consts::PI * 25.0);
    assert!(
        cut.simulation.field().removed_volume() > slot,
        "{}",
        cut.simulation.field().removed_volume()
    );
    assert_eq!(cut.simulation.findings().len(), 1);
}

#[test]
fn a_feed_past_the_flutes_is_a_shank_cut_warning() {
    let toml = format!("{STOCK}[tools.1]\ndiameter = 10\nflute_length = 3\n");
    let (_, diags) = cut(PROGRAM, &toml).unwrap();
    let codes: Vec<(u32, &str)> = diags.iter().map(|d| (d.0, d.1)).collect();
    assert_eq!(
        codes,
        [
            (4, "W-SHANK-CUT"),
            (5, "W-SHANK-CUT"),
            (7, "W-RAPID-INTO-STOCK")
        ]
    );
    assert!(
        diags[0].2.contains("past the tool's 3.000 mm flutes"),
        "{}",
        diags[0].2
    );
}

#[test]
fn a_tool_without_its_table_is_cut_from_its_register_or_as_10_mm_with_a_note() {
    // Register 1 gives T1 a 4 mm diameter: the slot is narrower than with the 10 mm default.
    let (narrow, diags) = cut(PROGRAM, &format!("{STOCK}[registers.1]\nradius = 2\n")).unwrap();
    assert_eq!((diags[0].0, diags[0].1), (2, "N-TOOL-ASSUMED"));
    assert!(
        diags[0]
            .2
            .ends_with("cut as a 4 mm flat end mill, twice register 1's radius"),
        "{}",
        diags[0].2
    );
    let (wide, diags) = cut(PROGRAM, STOCK).unwrap();
    assert_eq!(
        diags[0].2,
        "T1 has no `[tools.1]` in the setup: cut as a 10 mm flat end mill"
    );
    assert_eq!(narrow.simulation.field().height_at(45.0, 28.5), Some(0.0));
    assert_eq!(wide.simulation.field().height_at(45.0, 28.5), Some(-5.0));
}

#[test]
fn without_a_stock_a_box_around_the_feeds_is_assumed_with_a_note() {
    let toml = "[tools.1]\ndiameter = 10\n";
    let (cut, diags) = cut(PROGRAM, toml).unwrap();
    // The plunge from Z5 is the highest feed's start: the box's top, and the note's line.
    let (line, code, message) = &diags[0];
    assert_eq!((*line, *code), (4, "N-STOCK-ASSUMED"));
    assert!(
        message.contains("X15.000..75.000 Y20.000..30.000 Z-10.000..5.000 mm"),
        "{message}"
    );
    let stock = cut.simulation.field().stock();
    assert_eq!(stock.min, [15.0, 20.0, -10.0]);
    assert_eq!(stock.max, [75.0, 30.0, 5.0]);
    // The rapid at Z-2 crosses the assumed box's corner beyond the slot.
    assert_eq!(diags.len(), 2, "{diags:?}");
    assert_eq!(diags[1].1, "W-RAPID-INTO-STOCK");
    // No feed move: nothing to assume a stock around.
    assert!(cut_none("G0 X10. Y10.\nG0 Z-5.\n"));
}

fn cut_none(program: &str) -> bool {
    let parsed = parse(program, Dialect::Fanuc);
    let mut path = Toolpath::default();
    run(&parsed, Setup::default(), &mut path);
    StockRun::new(&path, &StockSetup::default()).is_none()
}
