//! Stock simulation speed: a generated program of a million segments cut out of a
//! 200 × 200 × 30 mm block on the default 1024 × 1024 grid, once with a Ø6 tool of each shape.
//! The program surfaces a wavy part in back-and-forth rows of 0.2 mm chords, clears rings of
//! arcs at three depths and pecks a grid of holes.
//!
//! Run: `cargo bench -p swarf-stock --bench sweep` (add `-- --quick` for one run each, a word
//! to run only the shapes whose name has it, `--segments N` for a shorter program).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::time::{Duration, Instant};

use glam::DVec3;
use swarf_interp::{Sink, Source};
use swarf_stock::{Shape, Simulation, Stock, Tool};
use swarf_toolpath::Toolpath;

/// Chord length of the generated paths, mm (what a CAM system's arc and surface output has).
const CHORD: f64 = 0.2;

const STOCK: Stock = Stock {
    min: [0.0, 0.0, -30.0],
    max: [200.0, 200.0, 0.0],
    cell_mm: None,
};

/// The program, `segments` long: 70 % surfacing, 25 % rings, 5 % holes.
fn program(segments: usize) -> Toolpath {
    let mut path = Toolpath::new(DVec3::new(0.0, 0.0, 10.0), 10_000.0);
    path.reserve(segments);
    let mut line = 0;
    let mut go = |path: &mut Toolpath, rapid: bool, p: DVec3| {
        if path.len() >= segments {
            return;
        }
        line += 1;
        let source = Source { block: line, line };
        let feed = if rapid { 0.0 } else { 3000.0 };
        path.straight(source, rapid, p.x, p.y, p.z, feed);
    };
    // Surfacing: rows along X 0.4 mm apart over a wavy surface, 2 to 6 mm deep.
    let surface = |x: f64, y: f64| -4.0 + 2.0 * (x / 15.0).sin() * (y / 20.0).cos();
    let per_row = (200.0 / CHORD) as usize;
    let mut row = 0;
    while path.len() < segments * 7 / 10 {
        let y = (f64::from(row) * 0.4) % 200.0;
        for k in 0..=per_row {
            let k = if row % 2 == 0 { k } else { per_row - k };
            let x = k as f64 * CHORD;
            go(&mut path, false, DVec3::new(x, y, surface(x, y)));
        }
        row += 1;
    }
    // Up from where the tool is, then across at 10 mm above the block.
    let retract = |path: &Toolpath| path.ends().last().map_or(DVec3::ZERO, |p| p.with_z(10.0));
    // Rings: circles of 5 to 60 mm radius about the block's centre, 1 mm apart, each entered
    // from the one inside it, at 8, 9 and 10 mm deep.
    let up = retract(&path);
    go(&mut path, true, up);
    go(&mut path, true, DVec3::new(100.0, 100.0, 10.0));
    let mut depth = 8.0;
    while path.len() < segments * 95 / 100 {
        go(&mut path, false, DVec3::new(105.0, 100.0, -depth));
        let mut radius = 5.0;
        while radius <= 60.0 && path.len() < segments * 95 / 100 {
            let chords = (TAU * radius / CHORD).ceil();
            for k in 0..=chords as usize {
                let a = TAU * k as f64 / chords;
                let p = DVec3::new(100.0 + radius * a.cos(), 100.0 + radius * a.sin(), -depth);
                go(&mut path, false, p);
            }
            radius += 1.0;
        }
        let up = retract(&path);
        go(&mut path, true, up);
        go(&mut path, true, DVec3::new(100.0, 100.0, 10.0));
        depth = if depth >= 10.0 { 8.0 } else { depth + 1.0 };
    }
    // Holes: a 5 mm grid, each pecked 12 mm deep in three steps from 1 mm above the part.
    let mut hole = 0;
    while path.len() < segments {
        let (x, y) = (
            2.5 + f64::from(hole % 39) * 5.0,
            2.5 + f64::from(hole / 39 % 39) * 5.0,
        );
        go(&mut path, true, DVec3::new(x, y, 3.0));
        for peck in [4.0, 8.0, 12.0] {
            go(&mut path, false, DVec3::new(x, y, 1.0 - peck));
            go(&mut path, true, DVec3::new(x, y, 3.0));
        }
        hole += 1;
    }
    path
}

/// The time this thread has spent on a CPU (Linux), which a busy machine does not inflate.
fn cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(Duration::from_nanos(
        stat.split_whitespace().next()?.parse().ok()?,
    ))
}

/// Wall and CPU time of the whole simulation, the volume it removed and its findings.
fn run(path: &Toolpath, tool: Tool) -> (Duration, Option<Duration>, f64, usize) {
    let mut sim = Simulation::new(&STOCK, BTreeMap::from([(0, tool)])).unwrap();
    let (start, cpu) = (Instant::now(), cpu_time());
    // As the editor would: a bounded number of segments a frame.
    while !sim.step(path, 20_000) {}
    let cpu = cpu.and_then(|before| Some(cpu_time()? - before));
    (
        start.elapsed(),
        cpu,
        sim.field().removed_volume(),
        sim.findings().len(),
    )
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let runs = if quick { 1 } else { 3 };
    let segments = args
        .iter()
        .position(|a| a == "--segments")
        .and_then(|i| args.get(i + 1)?.parse().ok())
        .unwrap_or(1_000_000);
    let filter = args
        .iter()
        .find(|a| !a.starts_with('-') && a.parse::<usize>().is_err());
    let tool = |shape| Tool {
        diameter: 6.0,
        shape,
        flute_length: None,
    };
    let cases = [
        ("flat", tool(Shape::Flat)),
        ("ball", tool(Shape::Ball)),
        ("bull, r1", tool(Shape::Bull { corner_radius: 1.0 })),
        (
            "drill, 118°",
            tool(Shape::Drill {
                point_angle_deg: 118.0,
            }),
        ),
        (
            "chamfer, 90°",
            tool(Shape::Chamfer {
                point_angle_deg: 90.0,
            }),
        ),
        (
            "flat, 25 mm flutes (checked)",
            Tool {
                flute_length: Some(25.0),
                ..tool(Shape::Flat)
            },
        ),
    ];
    let path = program(segments);
    println!("| Ø6 tool | segments | wall | CPU | removed mm³ | findings |");
    println!("|---|---|---|---|---|---|");
    for (name, tool) in cases {
        if filter.is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let results: Vec<_> = (0..runs).map(|_| run(&path, tool)).collect();
        let ms = |d: Duration| format!("{:.0} ms", d.as_secs_f64() * 1000.0);
        let wall = results.iter().map(|r| r.0).min().unwrap();
        let cpu = results
            .iter()
            .filter_map(|r| r.1)
            .min()
            .map_or("?".into(), ms);
        let (_, _, volume, findings) = results[0];
        println!(
            "| {name} | {} | {} | {cpu} | {volume:.0} | {findings} |",
            path.len(),
            ms(wall)
        );
    }
}
