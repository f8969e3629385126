//! The wasm32 figure of the peer benchmark (`scripts/bench-peers.sh`): parse + interpret +
//! record of the generated 1M-line surfacing program in Node, run on demand with
//! `cargo test -p swarf-toolpath --release --target wasm32-unknown-unknown --test wasm_throughput -- --include-ignored --nocapture`.
//! It measures and prints; it asserts only that every move was recorded.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]
#![cfg(target_arch = "wasm32")]

use glam::DVec3;
use swarf_interp::{Setup, run};
use swarf_syntax::{Dialect, parse};
use swarf_toolpath::Toolpath;
use wasm_bindgen_test::{console_log, wasm_bindgen_test};

#[path = "../../syntax/benches/surfacing.rs"]
mod surfacing;

#[wasm_bindgen_test]
#[ignore = "a measurement, run on demand"]
fn stats_throughput_in_wasm() {
    let text = surfacing::surfacing_program(1_000_000 * 37);
    let lines = text.lines().count();
    let mut best = f64::MAX;
    for _ in 0..3 {
        let start = js_sys::Date::now();
        let program = parse(&text, Dialect::Fanuc);
        let mut path = Toolpath::for_machine(DVec3::ZERO, &Setup::default().machine);
        path.reserve(program.blocks.len());
        run(&program, Setup::default(), &mut path);
        let ms = js_sys::Date::now() - start;
        // Every G01 line of the generator is one move.
        assert!(
            path.len() + 10 >= lines - 10,
            "{} moves, {lines} lines",
            path.len()
        );
        best = best.min(ms);
    }
    let mb = text.len() as f64 / 1e6;
    console_log!(
        "wasm32 stats: {lines} lines, {mb:.1} MB in {best:.0} ms = {:.0} MB/s",
        mb / (best / 1000.0)
    );
}
