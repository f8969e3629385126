//! Parses a file many times (for profiling): `cargo run --release -p swarf-syntax --example parse_file FILE [DIALECT]`.

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        eprintln!("usage: parse_file FILE [DIALECT]");
        return;
    };
    let dialect = args
        .next()
        .and_then(|d| d.parse().ok())
        .unwrap_or(swarf_syntax::Dialect::LinuxCnc);
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("cannot read {path}");
        return;
    };
    let text = swarf_syntax::decode(&bytes).text;
    let start = std::time::Instant::now();
    let mut blocks = 0;
    for _ in 0..10 {
        blocks += swarf_syntax::parse(&text, dialect).blocks.len();
    }
    let secs = start.elapsed().as_secs_f64() / 10.0;
    println!(
        "{} blocks, {:.1} MB/s",
        blocks / 10,
        text.len() as f64 / 1e6 / secs
    );
}
