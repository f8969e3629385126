//! `swarf`: check, run and measure G-code programs from the command line.

/// On Linux the memory comes from jemalloc with transparent huge pages (configured when it is
/// built, see `.cargo/config.toml`): recording a long program writes tens of megabytes of fresh
/// memory, and a first touch of each 4 KB page costs more than reading the program does.
#[cfg(target_os = "linux")]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() {
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let code = swarf_cli::run(std::env::args_os(), &mut stdout.lock(), &mut stderr.lock());
    std::process::exit(code);
}
