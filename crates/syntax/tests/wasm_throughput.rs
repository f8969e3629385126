//! The wasm32 parse-throughput figure for docs/performance.md's table: run on demand with
//! `cargo test -p swarf-syntax --release --target wasm32-unknown-unknown --test wasm_throughput -- --include-ignored --nocapture`.
//! It measures and prints; it asserts only that the parse saw every line.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]
#![cfg(target_arch = "wasm32")]

use swarf_syntax::{Dialect, parse};
use wasm_bindgen_test::{console_log, wasm_bindgen_test};

#[path = "../benches/surfacing.rs"]
mod surfacing;

#[wasm_bindgen_test]
#[ignore = "a measurement, run on demand"]
fn parse_throughput_in_wasm() {
    let text = surfacing::surfacing_program(4 << 20);
    let lines = text.lines().count();
    let mut best = f64::MAX;
    for _ in 0..5 {
        let start = js_sys::Date::now();
        let program = parse(&text, Dialect::Fanuc);
        let ms = js_sys::Date::now() - start;
        assert_eq!(program.lines.line_count(), lines + 1);
        best = best.min(ms);
    }
    let mb = text.len() as f64 / 1e6;
    console_log!(
        "wasm32 parse: {mb:.1} MB in {best:.0} ms = {:.0} MB/s",
        mb / (best / 1000.0)
    );
}
