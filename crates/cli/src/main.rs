//! `swarf`: check, run and measure G-code programs from the command line.

fn main() {
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let code = swarf_cli::run(std::env::args_os(), &mut stdout.lock(), &mut stderr.lock());
    std::process::exit(code);
}
