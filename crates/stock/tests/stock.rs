//! Material removal against closed-form volumes, the sweep against its definition, the checks
//! on rapids and shanks, and the setup keys.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use std::collections::BTreeMap;
use std::f64::consts::PI;

use glam::DVec3;
use swarf_interp::{Setup, run};
use swarf_stock::{Finding, HeightField, Shape, Simulation, Stock, StockError, Tool};
use swarf_syntax::{Dialect, parse};
use swarf_toolpath::Toolpath;

/// 100 × 50 × 20 mm with its top at Z0: the default grid is 1024 × 512 cells.
const STOCK: Stock = Stock {
    min: [0.0, 0.0, -20.0],
    max: [100.0, 50.0, 0.0],
    cell_mm: None,
};

fn tool(diameter: f64, shape: Shape) -> Tool {
    Tool {
        diameter,
        shape,
        flute_length: None,
    }
}

fn toolpath(program: &str) -> Toolpath {
    let program = parse(program, Dialect::Fanuc);
    let mut path = Toolpath::new(DVec3::new(0.0, 0.0, 50.0), 10_000.0);
    let diags = run(&program, Setup::default(), &mut path);
    assert!(diags.is_empty(), "{diags:?}");
    path
}

/// Cuts `program` with tool 1 out of [`STOCK`], in steps of 100 segments.
fn simulate(program: &str, tool1: Tool) -> Simulation {
    let path = toolpath(program);
    let mut sim = Simulation::new(&STOCK, BTreeMap::from([(1, tool1)])).unwrap();
    let mut steps = 0;
    while !sim.step(&path, 100) {
        steps += 1;
        assert!(steps < 100_000);
    }
    sim
}

fn assert_volume(sim: &Simulation, expected: f64) {
    let volume = sim.field().removed_volume();
    let error = (volume - expected).abs() / expected;
    assert!(
        error < 0.005,
        "removed {volume:.2} mm³, expected {expected:.2} ({:.3} %)",
        error * 100.0
    );
}

#[test]
fn default_grid_is_about_1024_on_the_longer_side() {
    let field = HeightField::new(&STOCK).unwrap();
    assert_eq!(field.size(), (1024, 512));
    assert!((field.cell_mm() - 100.0 / 1024.0).abs() < 1e-12);
    assert!(field.heights().iter().all(|&h| h == 0.0));
    assert_eq!(field.removed_volume(), 0.0);
    assert_eq!(field.height_at(50.0, 25.0), Some(0.0));
    assert_eq!(field.height_at(-1.0, 25.0), None);
    assert_eq!(
        field.cell_center(0, 511),
        [50.0 / 1024.0, 50.0 - 50.0 / 1024.0]
    );
}

#[test]
fn flat_end_mill_slot() {
    let sim = simulate(
        "T1 M6\nG0 X20. Y25. Z5.\nG1 Z-5. F100\nG1 X70.\nG0 X20.\nG0 Z5.\n",
        tool(10.0, Shape::Flat),
    );
    // L·D·d plus the two half-discs at the ends.
    assert_volume(&sim, 50.0 * 10.0 * 5.0 + PI * 25.0 * 5.0);
    // The rapid back along the slot's floor runs where the same tool has just cut.
    assert_eq!(sim.findings(), []);
    let field = sim.field();
    assert!((field.height_at(45.0, 25.0).unwrap() + 5.0).abs() < 1e-6);
    assert!((field.height_at(45.0, 29.9).unwrap() + 5.0).abs() < 1e-6);
    assert_eq!(field.height_at(45.0, 30.2), Some(0.0));
}

#[test]
fn ball_end_groove() {
    let sim = simulate(
        "T1 M6\nG0 X20. Y25. Z5.\nG1 Z-5. F100\nG1 X70.\nG0 Z5.\n",
        tool(10.0, Shape::Ball),
    );
    // A half-cylinder along L, and a quarter ball at each end.
    assert_volume(&sim, 50.0 * PI * 25.0 / 2.0 + 2.0 / 3.0 * PI * 125.0);
    let field = sim.field();
    let r = 3.0_f64;
    let expected = -5.0 + 5.0 - (25.0 - r * r).sqrt();
    let [x, y] = field.cell_center(461, 256);
    let h = field.height_at(x, y).unwrap();
    let exact = -5.0 + 5.0 - (25.0 - (y - 25.0).powi(2)).sqrt();
    assert!((h - exact).abs() < 1e-4, "{h} {exact}");
    assert!(field.height_at(45.0, 25.0 + r).unwrap() - expected < 0.05);
    assert_eq!(sim.findings(), []);
}

#[test]
fn drilled_hole_with_its_point() {
    let sim = simulate(
        "T1 M6\nG0 X50. Y25. Z20.\nG99 G81 X50. Y25. R2. Z-15. F100\nG80\nG0 Z20.\n",
        tool(
            10.0,
            Shape::Drill {
                point_angle_deg: 118.0,
            },
        ),
    );
    let point = 5.0 / (59.0_f64).to_radians().tan();
    // The cylinder down to the point's top, and the cone of the point.
    assert_volume(&sim, PI * 25.0 * (15.0 - point) + PI * 25.0 * point / 3.0);
    // The rapid retract from the bottom runs up the hole the drill has just made.
    assert_eq!(sim.findings(), []);
}

#[test]
fn circular_pocket_with_a_helical_entry() {
    // A helix of 2.5 mm radius down to 5 mm in four turns, a clean-up turn, then rings at 7,
    // 11 and 15 mm: a Ø10 flat mill clears a Ø40 cylinder 5 deep.
    let program = "T1 M6\nG0 X52.5 Y25. Z5.\nG1 Z0 F500\n\
        G3 X52.5 Y25. Z-1.25 I-2.5 J0\nG3 X52.5 Y25. Z-2.5 I-2.5 J0\n\
        G3 X52.5 Y25. Z-3.75 I-2.5 J0\nG3 X52.5 Y25. Z-5. I-2.5 J0\n\
        G3 X52.5 Y25. I-2.5 J0\n\
        G1 X57.\nG3 X57. Y25. I-7. J0\nG1 X61.\nG3 X61. Y25. I-11. J0\n\
        G1 X65.\nG3 X65. Y25. I-15. J0\nG0 Z5.\nM30\n";
    let sim = simulate(program, tool(10.0, Shape::Flat));
    assert_volume(&sim, PI * 400.0 * 5.0);
    assert_eq!(sim.findings(), []);
    let field = sim.field();
    assert!((field.height_at(50.0, 25.0).unwrap() + 5.0).abs() < 1e-6);
    assert!((field.height_at(50.0, 44.8).unwrap() + 5.0).abs() < 1e-6);
    assert_eq!(field.height_at(50.0, 45.2), Some(0.0));
}

#[test]
fn a_rapid_through_the_stock_is_found_and_still_cuts() {
    let sim = simulate(
        "T1 M6\nG0 X-10. Y25. Z20.\nG0 Z-2.\nG0 X110.\nG0 Z20.\n",
        tool(10.0, Shape::Flat),
    );
    let [finding] = sim.findings() else {
        panic!("{:?}", sim.findings());
    };
    let Finding::RapidIntoStock {
        segment,
        line,
        cell_xy,
        depth,
    } = *finding
    else {
        panic!("{finding:?}");
    };
    assert_eq!((segment, line), (2, 4));
    // The tool meets the stock's near face first, in front of its centre.
    assert!(
        cell_xy[0] < 0.1 && (cell_xy[1] - 25.0).abs() < 0.1,
        "{cell_xy:?}"
    );
    assert!((depth - 2.0).abs() < 1e-4, "{depth}");
    assert_volume(&sim, 100.0 * 10.0 * 2.0);
}

#[test]
fn a_rapid_above_the_stock_or_beside_it_is_not() {
    let sim = simulate(
        "T1 M6\nG0 X-10. Y25. Z0.5\nG0 X110.\nG0 Y56.\nG0 Z-5.\nG0 X-10.\nG0 Z20.\n",
        tool(10.0, Shape::Ball),
    );
    assert_eq!(sim.findings(), []);
    assert_eq!(sim.field().removed_volume(), 0.0);
}

#[test]
fn a_rapid_plunge_into_the_stock_is_found() {
    let sim = simulate(
        "T1 M6\nG0 X30. Y20. Z20.\nG0 Z-3.\nG0 Z20.\n",
        tool(
            6.0,
            Shape::Chamfer {
                point_angle_deg: 90.0,
            },
        ),
    );
    let [Finding::RapidIntoStock { line, depth, .. }] = sim.findings() else {
        panic!("{:?}", sim.findings());
    };
    assert_eq!(*line, 3);
    // The first cell the point meets is the one under the tip, 3 mm deep.
    assert!((depth - 3.0).abs() < 0.2, "{depth}");
}

#[test]
fn a_feed_deeper_than_the_flutes_is_a_shank_cut() {
    let short = Tool {
        flute_length: Some(3.0),
        ..tool(8.0, Shape::Flat)
    };
    let program =
        |z: f64| format!("T1 M6\nG0 X20. Y25. Z5.\nG1 Z{z:.1} F100\nG1 X70.\nG1 Y30.\nG0 Z5.\n");
    assert_eq!(simulate(&program(-2.5), short).findings(), []);
    let sim = simulate(&program(-5.0), short);
    // The plunge, the slot and the step aside each bury the tool 5 mm in fresh material.
    let lines: Vec<u32> = sim.findings().iter().map(Finding::line).collect();
    assert_eq!(lines, [3, 4, 5]);
    let Finding::ShankCut {
        depth,
        flute_length,
        ..
    } = sim.findings()[1]
    else {
        panic!("{:?}", sim.findings());
    };
    assert!((depth - 5.0).abs() < 1e-4 && flute_length == 3.0, "{depth}");
}

/// The lowest point of the tool's end over `(x, y)` as its tip moves from `a` to `b`, by
/// sampling the move finely; `None` if the tool does not come within 95 % of its radius.
fn sampled_low(a: DVec3, b: DVec3, tool: &Tool, x: f64, y: f64) -> Option<f64> {
    let radius = tool.diameter / 2.0;
    let lift = |r: f64| match tool.shape {
        Shape::Flat => 0.0,
        Shape::Ball => radius - (radius * radius - r * r).sqrt(),
        Shape::Bull { corner_radius: c } => {
            let out = (r - (radius - c)).max(0.0);
            c - (c * c - out * out).sqrt()
        }
        Shape::Drill { point_angle_deg } | Shape::Chamfer { point_angle_deg } => {
            r / (point_angle_deg.to_radians() / 2.0).tan()
        }
    };
    let n = 20_000;
    let mut low = None::<f64>;
    let mut near = false;
    for k in 0..=n {
        let p = a.lerp(b, f64::from(k) / f64::from(n));
        let r = (x - p.x).hypot(y - p.y);
        near |= r <= 0.95 * radius;
        if r <= radius {
            let z = p.z + lift(r);
            low = Some(low.map_or(z, |l| l.min(z)));
        }
    }
    near.then_some(low?)
}

#[test]
fn every_profile_cuts_to_the_lowest_point_its_end_reaches() {
    let stock = Stock {
        min: [0.0, 0.0, -20.0],
        max: [20.0, 20.0, 0.0],
        cell_mm: Some(0.25),
    };
    let tools = [
        tool(6.0, Shape::Flat),
        tool(6.0, Shape::Ball),
        tool(6.0, Shape::Bull { corner_radius: 1.0 }),
        tool(
            6.0,
            Shape::Drill {
                point_angle_deg: 118.0,
            },
        ),
        tool(
            6.0,
            Shape::Chamfer {
                point_angle_deg: 60.0,
            },
        ),
    ];
    let moves = [
        (DVec3::new(4.0, 5.0, -1.0), DVec3::new(16.0, 13.0, -4.0)),
        (DVec3::new(15.0, 4.0, -6.0), DVec3::new(6.0, 15.0, -0.5)),
        (DVec3::new(10.0, 10.0, -1.0), DVec3::new(10.3, 10.1, -7.0)),
        (DVec3::new(3.0, 17.0, -2.0), DVec3::new(17.0, 17.0, -2.0)),
        (DVec3::new(8.0, 8.0, 0.0), DVec3::new(8.0, 8.0, -5.0)),
    ];
    for tool in &tools {
        for &(a, b) in &moves {
            let mut field = HeightField::new(&stock).unwrap();
            field.cut(a, b, tool);
            let (nx, ny) = field.size();
            let mut compared = 0;
            for j in (0..ny).step_by(3) {
                for i in (0..nx).step_by(3) {
                    let [x, y] = field.cell_center(i, j);
                    let h = f64::from(field.heights()[j * nx + i]);
                    match sampled_low(a, b, tool, x, y) {
                        Some(low) => {
                            compared += 1;
                            let want = low.min(0.0);
                            assert!(
                                (h - want).abs() < 2e-3,
                                "{tool:?} {a} → {b} at ({x}, {y}): {h} not {want}"
                            );
                        }
                        None if (x - a.x).hypot(y - a.y) > 3.1
                            && (x - b.x).hypot(y - b.y) > 3.1 =>
                        {
                            // Well away from both ends: only the band along the move is cut.
                        }
                        None => {}
                    }
                }
            }
            assert!(compared > 20, "{tool:?} {a} → {b}");
        }
    }
}

#[test]
fn cuts_stop_at_the_stock_bottom_and_odd_input_is_harmless() {
    let mut field = HeightField::new(&STOCK).unwrap();
    let flat = tool(10.0, Shape::Flat);
    field.cut(
        DVec3::new(50.0, 25.0, 5.0),
        DVec3::new(50.0, 25.0, -40.0),
        &flat,
    );
    assert_eq!(field.height_at(50.0, 25.0), Some(-20.0));
    assert!((field.removed_volume() - PI * 25.0 * 20.0).abs() / (PI * 25.0 * 20.0) < 0.005);
    let before = field.heights().to_vec();
    field.cut(
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(1.0, 1.0, -1.0),
        &flat,
    );
    field.cut(DVec3::splat(1e300), DVec3::splat(-1e300), &flat);
    field.cut(
        DVec3::new(500.0, 500.0, -5.0),
        DVec3::new(600.0, 500.0, -5.0),
        &flat,
    );
    field.cut(DVec3::ZERO, DVec3::ONE, &tool(f64::NAN, Shape::Ball));
    assert_eq!(field.heights(), before);
}

#[test]
fn stock_and_tools_read_from_setup_keys() {
    #[derive(serde::Deserialize)]
    struct File {
        stock: Stock,
        tools: BTreeMap<u32, Tool>,
    }
    let file: File = toml::from_str(
        "[stock]\nmin = [0, 0, -20]\nmax = [100, 50, 0]\ncell_mm = 0.2\n\
         [tools.1]\ndiameter = 10\n\
         [tools.2]\ndiameter = 6\nshape = \"bull\"\ncorner_radius = 1\nflute_length = 12\n\
         [tools.3]\ndiameter = 8.5\nshape = \"drill\"\n\
         [tools.4]\ndiameter = 12\nshape = \"chamfer\"\npoint_angle_deg = 60\n",
    )
    .unwrap();
    assert_eq!(file.stock.cell_mm, Some(0.2));
    assert_eq!(file.stock.grid().unwrap(), (0.2, 500, 250));
    assert_eq!(file.tools[&1], tool(10.0, Shape::Flat));
    assert_eq!(
        file.tools[&2],
        Tool {
            flute_length: Some(12.0),
            ..tool(6.0, Shape::Bull { corner_radius: 1.0 })
        }
    );
    assert_eq!(
        file.tools[&3].shape,
        Shape::Drill {
            point_angle_deg: 118.0
        }
    );
    assert_eq!(
        file.tools[&4].shape,
        Shape::Chamfer {
            point_angle_deg: 60.0
        }
    );
    assert!(Simulation::new(&file.stock, file.tools).is_ok());

    for bad in [
        "diameter = 6\nshape = \"bull\"",
        "diameter = 6\ncorner_radius = 1",
        "diameter = 6\nshape = \"ball\"\npoint_angle_deg = 90",
        "diameter = 6\nshape = \"conical\"",
        "diameter = 6\nlength = 3",
    ] {
        assert!(toml::from_str::<Tool>(bad).is_err(), "{bad}");
    }
}

#[test]
fn values_out_of_range_are_refused_naming_the_key_and_the_range() {
    fn range<T: std::fmt::Debug>(result: Result<T, StockError>) -> (String, f64, f64) {
        match result {
            Err(StockError::Range { key, min, max, .. }) => (key, min, max),
            other => panic!("{other:?}"),
        }
    }
    let fine = |cell_mm| Stock { cell_mm, ..STOCK };
    assert_eq!(
        range(fine(Some(0.001)).grid()),
        ("stock.cell_mm".into(), 100.0 / 4096.0, 100.0)
    );
    assert_eq!(fine(Some(100.0 / 4096.0)).grid().unwrap().1, 4096);
    let tiny = Stock {
        min: [0.0; 3],
        max: [10.0, 10.0, 1.0],
        cell_mm: Some(0.001),
    };
    assert_eq!(range(tiny.grid()).1, 0.005);
    assert_eq!(range(fine(Some(f64::NAN)).grid()).0, "stock.cell_mm");
    let far = Stock {
        min: [f64::NAN, 0.0, 0.0],
        ..STOCK
    };
    assert_eq!(range(far.grid()).0, "stock.min");
    let flat = Stock {
        max: [100.0, 50.0, -20.0],
        ..STOCK
    };
    assert_eq!(flat.grid(), Err(StockError::Empty { axis: 'Z' }));

    let check = |tool: Tool| tool.validate(7);
    assert_eq!(
        range(check(tool(0.0, Shape::Flat))),
        ("tools.7.diameter".into(), 0.001, 1000.0)
    );
    assert_eq!(
        range(check(tool(f64::NAN, Shape::Ball))).0,
        "tools.7.diameter"
    );
    let (key, _, max) = range(check(tool(6.0, Shape::Bull { corner_radius: 3.5 })));
    assert_eq!((key.as_str(), max), ("tools.7.corner_radius", 3.0));
    let (key, min, max) = range(check(tool(
        6.0,
        Shape::Drill {
            point_angle_deg: 180.0,
        },
    )));
    assert_eq!(
        (key.as_str(), min, max),
        ("tools.7.point_angle_deg", 1.0, 179.0)
    );
    let no_flutes = Tool {
        flute_length: Some(-1.0),
        ..Tool::default()
    };
    assert_eq!(range(check(no_flutes)).0, "tools.7.flute_length");
    let message = Simulation::new(&STOCK, BTreeMap::from([(7, no_flutes)]))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("`tools.7.flute_length` must be from 0.001"),
        "{message}"
    );
}

#[cfg(not(target_arch = "wasm32"))]
mod properties {
    use super::*;
    use proptest::prelude::*;
    use swarf_interp::{Sink, Source};

    fn shape() -> impl Strategy<Value = Shape> {
        prop_oneof![
            Just(Shape::Flat),
            Just(Shape::Ball),
            // A share of the radius, made a length by `bounded`.
            (0.0..1.0f64).prop_map(|corner_radius| Shape::Bull { corner_radius }),
            (20.0..170.0f64).prop_map(|point_angle_deg| Shape::Drill { point_angle_deg }),
            (20.0..170.0f64).prop_map(|point_angle_deg| Shape::Chamfer { point_angle_deg }),
        ]
    }

    /// A tool of `diameter`, a bull nose's corner taken as a share of its radius.
    fn bounded(diameter: f64, shape: Shape) -> Tool {
        let shape = match shape {
            Shape::Bull { corner_radius } => Shape::Bull {
                corner_radius: corner_radius * diameter / 2.0,
            },
            other => other,
        };
        tool(diameter, shape)
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (-5.0..25.0f64, -5.0..25.0f64, -25.0..3.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    /// A short move of a chain: level, gently sloped, steep, a plunge or none at all.
    fn step() -> impl Strategy<Value = DVec3> {
        prop_oneof![
            (-0.4..0.4f64, -0.4..0.4f64).prop_map(|(x, y)| DVec3::new(x, y, 0.0)),
            (-0.4..0.4f64, -0.4..0.4f64, -0.1..0.1f64).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            (-3.0..3.0f64).prop_map(|z| DVec3::new(0.0, 0.0, z)),
            Just(DVec3::ZERO),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn heights_never_rise_and_the_volume_never_shrinks(
            diameter in 0.5..6.0f64,
            shape in shape(),
            points in proptest::collection::vec(point(), 2..12),
        ) {
            let tool = bounded(diameter, shape);
            let stock = Stock { min: [0.0, 0.0, -20.0], max: [20.0, 15.0, 0.0], cell_mm: Some(0.2) };
            let mut field = HeightField::new(&stock).unwrap();
            for pair in points.windows(2) {
                let (before, volume) = (field.heights().to_vec(), field.removed_volume());
                field.cut(pair[0], pair[1], &tool);
                for (new, old) in field.heights().iter().zip(&before) {
                    prop_assert!(new <= old && *new >= -20.0);
                }
                prop_assert!(field.removed_volume() >= volume);
            }
        }

        /// The simulation skips the cells behind a move's start that the move before it left
        /// at the tool's shape; the result is the same as cutting every move whole.
        #[test]
        fn a_simulation_cuts_as_every_move_cut_whole(
            diameter in 0.5..6.0f64,
            shape in shape(),
            points in proptest::collection::vec(point(), 2..12),
        ) {
            let tool = bounded(diameter, shape);
            let stock = Stock { min: [0.0, 0.0, -20.0], max: [20.0, 15.0, 0.0], cell_mm: Some(0.2) };
            let mut path = Toolpath::new(points[0], 10_000.0);
            for (line, p) in (1..).zip(&points[1..]) {
                path.straight(Source { block: line, line }, false, p.x, p.y, p.z, 1000.0);
            }
            let mut sim = Simulation::new(&stock, BTreeMap::from([(0, tool)])).unwrap();
            prop_assert!(sim.step(&path, 100));
            let mut field = HeightField::new(&stock).unwrap();
            for (i, &to) in path.ends().iter().enumerate() {
                field.cut(path.segment_start(i), to, &tool);
            }
            for (a, b) in sim.field().heights().iter().zip(field.heights()) {
                prop_assert!((a - b).abs() < 1e-3, "{a} {b}");
            }
        }

        /// In a chain of short moves each leaves to its neighbours the cells about their
        /// joints where they come lower (but where a rapid or a shank check looks at the
        /// material); however the steps split the chain, the result is the same as cutting
        /// every move whole.
        #[test]
        fn a_chain_of_short_moves_cuts_as_every_move_cut_whole(
            diameter in 0.5..6.0f64,
            shape in shape(),
            start in point(),
            moves in proptest::collection::vec((step(), 0..8u8), 1..40),
            per_step in 1..30usize,
            flutes in proptest::option::of(0.5..5.0f64),
        ) {
            let tool = Tool { flute_length: flutes, ..bounded(diameter, shape) };
            let stock = Stock { min: [0.0, 0.0, -20.0], max: [20.0, 15.0, 0.0], cell_mm: Some(0.2) };
            let mut path = Toolpath::new(start, 10_000.0);
            let mut p = start;
            for (line, (step, kind)) in (1..).zip(&moves) {
                p += *step;
                path.straight(Source { block: line, line }, *kind == 0, p.x, p.y, p.z, 1000.0);
            }
            let mut sim = Simulation::new(&stock, BTreeMap::from([(0, tool)])).unwrap();
            while !sim.step(&path, per_step) {}
            let mut field = HeightField::new(&stock).unwrap();
            for (i, &to) in path.ends().iter().enumerate() {
                field.cut(path.segment_start(i), to, &tool);
            }
            for (a, b) in sim.field().heights().iter().zip(field.heights()) {
                prop_assert!((a - b).abs() < 1e-3, "{a} {b}");
            }
        }
    }
}
