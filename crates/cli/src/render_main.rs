//! `swarf-render`: `swarf render` for a statically linked `swarf` (the release build on x86-64
//! Linux), which cannot load the system's Vulkan driver and runs this program from its own folder
//! instead (`swarf_cli::RENDER_HELPER`). It takes the arguments that follow `render`.

fn main() {
    let args = std::env::args_os().skip(1);
    let args = ["swarf".into(), "render".into()].into_iter().chain(args);
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let code = swarf_cli::run(args, &mut stdout.lock(), &mut stderr.lock());
    std::process::exit(code);
}
