//! Writes a generated 3D surfacing program of about `LINES` lines (default one million) to
//! standard output, for the peer benchmark: `cargo run --release -p swarf-syntax --example
//! surfacing -- 1000000 > surfacing.nc`.

#[path = "../benches/surfacing.rs"]
mod surfacing;

use std::io::Write;

fn main() {
    let lines: usize = std::env::args()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(1_000_000);
    // The generator's lines are about 37 bytes.
    let text = surfacing::surfacing_program(lines.saturating_mul(37));
    if std::io::stdout().write_all(text.as_bytes()).is_err() {
        eprintln!("surfacing: cannot write the program");
    }
}
