//! Where the time of `swarf stats` goes: decode, parse, interpret (into a sink that drops the
//! events) and interpret + record (into a [`Toolpath`]), best of several runs each, per file.
//!
//! ```sh
//! cargo run --release -p swarf-toolpath --example stages -- FILE… [--runs N] [--dialect D]
//! ```
#![allow(missing_docs)]

use std::time::{Duration, Instant};

use glam::DVec3;
use swarf_interp::{Canon, Setup, Sink, Source, run};
use swarf_syntax::{Dialect, decode, parse};
use swarf_toolpath::Toolpath;

/// Counts the events and drops them.
struct Count(u64);

impl Sink for Count {
    fn emit(&mut self, _: Source, _: &Canon) {
        self.0 += 1;
    }
}

/// The shortest of `runs` timings of `f`.
fn best<T>(runs: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut fastest = Duration::MAX;
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let out = f();
        fastest = fastest.min(start.elapsed());
        last = Some(out);
    }
    match last {
        Some(out) => (fastest, out),
        None => (fastest, f()),
    }
}

fn main() {
    let mut files = Vec::new();
    let mut runs = 5;
    let mut dialect = Dialect::LinuxCnc;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--runs" => runs = args.next().and_then(|n| n.parse().ok()).unwrap_or(runs),
            "--dialect" => {
                dialect = args.next().and_then(|d| d.parse().ok()).unwrap_or(dialect);
            }
            _ => files.push(a),
        }
    }
    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    for file in files {
        let Ok(bytes) = std::fs::read(&file) else {
            eprintln!("cannot read {file}");
            continue;
        };
        let mb = bytes.len() as f64 / 1e6;
        let (t_decode, decoded) = best(runs, || decode(&bytes));
        let text = decoded.text;
        let (t_parse, program) = best(runs, || parse(&text, dialect));
        let (t_interp, events) = best(runs, || {
            let mut sink = Count(0);
            run(&program, Setup::default(), &mut sink);
            sink.0
        });
        let (t_record, motions) = best(runs, || {
            let setup = Setup::default();
            let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
            path.reserve(program.blocks.len());
            run(&program, setup, &mut path);
            path.len()
        });
        let total = t_decode + t_parse + t_record;
        println!(
            "{file}: {mb:.1} MB, {} blocks, {events} events, {motions} motions",
            program.blocks.len()
        );
        println!(
            "  decode {:.1} ms | parse {:.1} ms | interpret {:.1} ms | interpret + record {:.1} ms | sum {:.1} ms = {:.0} MB/s",
            ms(t_decode),
            ms(t_parse),
            ms(t_interp),
            ms(t_record),
            ms(total),
            mb / total.as_secs_f64()
        );
    }
}
