//! `swarf`: check, run and measure G-code programs from the command line.

/// On Linux the memory comes from jemalloc with transparent huge pages (configured when it is
/// built, see `.cargo/config.toml`): recording a long program writes tens of megabytes of fresh
/// memory, and a first touch of each 4 KB page costs more than reading the program does.
#[cfg(target_os = "linux")]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    // A statically linked build (the release build on x86-64 Linux, `cargo xtask pgo`) cannot
    // load the Vulkan driver: `swarf render` runs in `swarf-render`, beside it.
    #[cfg(all(target_os = "linux", target_feature = "crt-static"))]
    if let Some(code) = swarf_cli::render_elsewhere(&args, &mut std::io::stderr().lock()) {
        std::process::exit(code);
    }
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let code = swarf_cli::run(args, &mut stdout.lock(), &mut stderr.lock());
    std::process::exit(code);
}
