//! Stock simulation speed: a million segments cut out of a 200 × 200 × 30 mm block on the
//! default 1024 × 1024 grid, for a roughing and a finishing program.
//!
//! Run: `cargo bench -p swarf-stock --bench sweep` (add `-- --quick` for one run each).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use glam::DVec3;
use swarf_interp::{Sink, Source};
use swarf_stock::{Shape, Simulation, Stock, Tool};
use swarf_toolpath::Toolpath;

const SEGMENTS: usize = 1_000_000;

/// Chord length of the generated paths, mm (what a CAM system's arc and surface output has).
const CHORD: f64 = 0.2;

const STOCK: Stock = Stock {
    min: [0.0, 0.0, -30.0],
    max: [200.0, 200.0, 0.0],
    cell_mm: None,
};

/// Pocket roughing: levels 1 mm apart, each an inward spiral of 4 mm stepover about the
/// block's centre from a 95 mm radius, left by a rapid up and over to the next level's start.
fn roughing() -> Toolpath {
    let mut path = Toolpath::new(DVec3::new(195.0, 100.0, 5.0), 10_000.0);
    path.reserve(SEGMENTS);
    let mut level = 0.0;
    while path.len() < SEGMENTS {
        level -= 1.0;
        let line = |n: u32| Source {
            block: n,
            line: n + 1,
        };
        path.straight(line(0), true, 195.0, 100.0, 5.0, 0.0);
        path.straight(line(1), true, 195.0, 100.0, level + 1.0, 0.0);
        path.straight(line(2), false, 195.0, 100.0, level, 500.0);
        let mut theta: f64 = 0.0;
        loop {
            let r = 95.0 - 4.0 * theta / std::f64::consts::TAU;
            if r <= 0.0 || path.len() >= SEGMENTS {
                break;
            }
            let (x, y) = (100.0 + r * theta.cos(), 100.0 + r * theta.sin());
            path.straight(line(3), false, x, y, level, 2000.0);
            theta += CHORD / r.max(CHORD);
        }
    }
    path
}

/// Surface finishing: back-and-forth rows 0.2 mm apart along X over a wavy surface.
fn finishing() -> Toolpath {
    let surface = |x: f64, y: f64| -10.0 + 3.0 * (x / 15.0).sin() * (y / 20.0).cos();
    let mut path = Toolpath::new(DVec3::new(0.0, 0.0, 5.0), 10_000.0);
    path.reserve(SEGMENTS);
    let per_row = (200.0 / CHORD) as usize;
    let mut row = 0u32;
    while path.len() < SEGMENTS {
        let y = (f64::from(row) * 0.2) % 200.0;
        for k in 0..=per_row {
            let k = if row.is_multiple_of(2) {
                k
            } else {
                per_row - k
            };
            let x = k as f64 * CHORD;
            let source = Source {
                block: row,
                line: row + 1,
            };
            path.straight(source, false, x, y, surface(x, y), 3000.0);
            if path.len() >= SEGMENTS {
                break;
            }
        }
        row += 1;
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
    let runs = if args.iter().any(|a| a == "--quick") {
        1
    } else {
        3
    };
    let filter = args.iter().find(|a| !a.starts_with('-'));
    let flat = Tool {
        diameter: 10.0,
        shape: Shape::Flat,
        flute_length: None,
    };
    let cases = [
        ("roughing, Ø10 flat", roughing as fn() -> Toolpath, flat),
        (
            "roughing, Ø10 flat, 25 mm flutes",
            roughing,
            Tool {
                flute_length: Some(25.0),
                ..flat
            },
        ),
        (
            "finishing, Ø6 ball",
            finishing,
            Tool {
                diameter: 6.0,
                shape: Shape::Ball,
                flute_length: None,
            },
        ),
        (
            "finishing, Ø6 bull r1",
            finishing,
            Tool {
                diameter: 6.0,
                shape: Shape::Bull { corner_radius: 1.0 },
                flute_length: None,
            },
        ),
        (
            "finishing, Ø6 90° chamfer",
            finishing,
            Tool {
                diameter: 6.0,
                shape: Shape::Chamfer {
                    point_angle_deg: 90.0,
                },
                flute_length: None,
            },
        ),
    ];
    let cell = 200.0 / 1024.0;
    println!("| case | segments | cells a segment | wall | CPU | removed mm³ | findings |");
    println!("|---|---|---|---|---|---|---|");
    for (name, path, tool) in cases {
        if filter.is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let path = path();
        let radius = tool.diameter / 2.0 / cell;
        let cells = std::f64::consts::PI * radius * radius + 2.0 * radius * CHORD / cell;
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
            "| {name} | {} | {cells:.0} | {} | {cpu} | {volume:.0} | {findings} |",
            path.len(),
            ms(wall)
        );
    }
}
