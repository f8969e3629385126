//! Build tasks, `cargo xtask <command>`: `web [--dev] [--no-opt]` builds the page into
//! `target/web/`, `serve [--port 8080] [--no-build] [--dir DIR] [--dev]` serves it,
//! `test [--quick]` runs every test, `wasm-tools` installs the wasm32 tests' tools.

mod desktop;
mod serve;
mod test;
mod tools;
mod util;
mod web;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};

const USAGE: &str = "\
Swarf build tasks

USAGE:
    cargo xtask <COMMAND> [OPTIONS]

COMMANDS:
    web     Build the web page into target/web/
              --dev         debug build of the wasm (faster to build, slower to run, no
                            wasm-opt)
              --no-opt      leave out wasm-opt -Oz (npm's binaryen, installed when missing)
    serve   Build the web page and serve it on http://127.0.0.1:PORT/, each file
            compressed (.br, .gz beside it) when the browser accepts it
              --port PORT   port to listen on (default 8080; 0 picks a free one)
              --no-build    serve the site as it is
              --dir DIR     serve DIR instead of target/web/ (with --no-build)
              --dev, --no-opt  as for `web`
    test    Install what the tests need, then run every check and test
              --quick       skip the browser and desktop steps
              --only STEPS  run only these steps, e.g. `--only g` or `--only a,b,e`
                            (a fmt, b clippy, c clippy wasm32, d tests, e wasm tests in
                            Node, f wasm tests in Chromium, g architecture, k cargo deny,
                            h desktop, j fuzzing, i web build + browser end-to-end test)
    wasm-tools
            Install what the wasm32 tests need where it is missing: the wasm32 target and
            wasm-bindgen-cli (the benchmark script runs its wasm32 test with them)
    help    Show this message
";

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // One line with the whole cause chain and no backtrace (even with RUST_BACKTRACE
            // set): the closing lines of `cargo xtask test` belong to the last test runner.
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some((command, rest)) = args.split_first() else {
        print!("{USAGE}");
        return Ok(());
    };
    let mut opts = Options::parse(rest)?;
    match command.as_str() {
        "web" => {
            opts.reject_unused(&["--dev", "--no-opt"])?;
            web::build(opts.dev, opts.no_opt)?;
        }
        "serve" => {
            opts.reject_unused(&["--dev", "--no-opt", "--port", "--no-build", "--dir"])?;
            if opts.dir.is_some() && !opts.no_build {
                bail!("--dir serves a site as it is; add --no-build");
            }
            if !opts.no_build {
                web::build(opts.dev, opts.no_opt)?;
            }
            let dir = opts.dir.take().map_or_else(web::site_dir, PathBuf::from);
            serve::serve(&dir, opts.port.take().unwrap_or(8080))?;
        }
        "test" => {
            opts.reject_unused(&["--quick", "--only"])?;
            test::run_all(opts.quick, opts.only.as_deref())?;
        }
        "wasm-tools" => {
            opts.reject_unused(&[])?;
            tools::ensure_wasm_target()?;
            tools::ensure_wasm_bindgen()?;
        }
        "help" | "--help" | "-h" => print!("{USAGE}"),
        other => bail!("unknown command `{other}`\n\n{USAGE}"),
    }
    Ok(())
}

/// Command-line options shared by all commands; each command accepts a subset.
#[derive(Debug, Default)]
struct Options {
    dev: bool,
    no_opt: bool,
    no_build: bool,
    quick: bool,
    port: Option<u16>,
    only: Option<String>,
    dir: Option<String>,
    seen: Vec<String>,
}

impl Options {
    fn parse(args: &[String]) -> Result<Self> {
        let mut opts = Options::default();
        let mut iter = args.iter();
        while let Some(arg) = iter.next() {
            let (flag, inline_value) = match arg.split_once('=') {
                Some((flag, value)) => (flag, Some(value.to_owned())),
                None => (arg.as_str(), None),
            };
            // The option's value: after `=` or the next argument.
            let mut value =
                |example: &str| match inline_value.clone().or_else(|| iter.next().cloned()) {
                    Some(value) => Ok(value),
                    None => Err(anyhow::anyhow!("{flag} needs {example}")),
                };
            match flag {
                "--dev" => opts.dev = true,
                "--no-opt" => opts.no_opt = true,
                "--no-build" => opts.no_build = true,
                "--quick" => opts.quick = true,
                "--only" => opts.only = Some(value("step letters, e.g. --only a,g")?),
                "--dir" => opts.dir = Some(value("a folder, e.g. --dir target/web")?),
                "--port" => {
                    let value = value("a value, e.g. --port 8080")?;
                    let port = value
                        .parse::<u16>()
                        .map_err(|e| anyhow::anyhow!("invalid port `{value}`: {e}"))?;
                    opts.port = Some(port);
                }
                _ => bail!("unknown option `{flag}`\n\n{USAGE}"),
            }
            if inline_value.is_some() && !matches!(flag, "--port" | "--only" | "--dir") {
                bail!("option `{flag}` takes no value");
            }
            opts.seen.push(flag.to_owned());
        }
        Ok(opts)
    }

    fn reject_unused(&self, allowed: &[&str]) -> Result<()> {
        for flag in &self.seen {
            if !allowed.contains(&flag.as_str()) {
                bail!("option `{flag}` does not apply to this command\n\n{USAGE}");
            }
        }
        Ok(())
    }
}
