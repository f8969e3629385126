//! `cargo xtask test`: installs what the tests need, then runs every check and test in order,
//! stopping at the first failure. The browser end-to-end test runs last, so the run's closing
//! lines are the summary of Node's test runner.

use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};

use crate::tools::{self, WASM_TARGET};
use crate::util::{self, cargo, command, header, run};
use crate::{desktop, web};

/// Crates that are compiled and tested for wasm32 (the core has no UI and no GPU).
const WASM_TEST_CRATES: &[&str] = &[
    "swarf-syntax",
    "swarf-interp",
    "swarf-toolpath",
    "swarf-stock",
];

/// Crates that must compile for wasm32 without warnings.
const WASM_CLIPPY_CRATES: &[&str] = &[
    "swarf-syntax",
    "swarf-interp",
    "swarf-toolpath",
    "swarf-stock",
    "swarf-render",
    "swarf-ui",
    "swarf-app",
];

/// The dependency rules of ARCHITECTURE.md: package → crates its normal dependency tree (for
/// every target) must not contain. A rule also forbids the crate's family (`egui` forbids
/// `egui-wgpu`, `egui_kittest`, …).
const FORBIDDEN_DEPENDENCIES: &[(&str, &[&str])] = &[
    // `swarf render` draws offscreen with swarf-render (wgpu), but never through a UI toolkit.
    ("swarf-cli", &["egui", "eframe", "winit"]),
    ("swarf-syntax", &["egui", "eframe", "wgpu", "winit"]),
    ("swarf-interp", &["egui", "eframe", "wgpu", "winit"]),
    ("swarf-toolpath", &["egui", "eframe", "wgpu", "winit"]),
    ("swarf-stock", &["egui", "eframe", "wgpu", "winit"]),
    // The stock is drawn from its heights: the renderer never needs the stock crate.
    ("swarf-render", &["egui", "swarf-interp", "swarf-stock"]),
    // The analysis runs on a thread or in the page's worker: it never reaches the UI toolkit.
    ("swarf-analysis", &["egui", "eframe", "winit"]),
    ("swarf-worker", &["egui", "eframe", "winit"]),
];

/// How long each fuzz target runs in the test run.
const FUZZ_SECONDS: u32 = 20;

/// The cargo-fuzz targets, and the file name extensions of their seeds.
const FUZZ_TARGETS: [(&str, &[&str]); 5] = [
    ("parse", &["nc", "ngc"]),
    ("pieces", &["nc", "ngc"]),
    ("interpret", &["nc", "ngc"]),
    ("linked", &["nc", "ngc"]),
    ("setup", &["toml"]),
];

/// Runs the cargo-fuzz targets briefly, seeded with the repository's programs (setups for the
/// setup target), keeping the corpus and any crash under `target/`.
fn fuzz() -> Result<()> {
    tools::ensure_cargo_tool("fuzz", "cargo-fuzz", "0.13.2", &[])?;
    let root = util::repo_root();
    for (target, seeds) in FUZZ_TARGETS {
        let corpus = root.join("target/fuzz-corpus").join(target);
        let artifacts = root.join("target/fuzz-artifacts").join(target);
        std::fs::create_dir_all(&corpus)?;
        std::fs::create_dir_all(&artifacts)?;
        for dir in ["assets/examples", "tests/golden"] {
            for entry in std::fs::read_dir(root.join(dir))?.flatten() {
                let path = entry.path();
                let seed = (path.extension()).is_some_and(|e| seeds.iter().any(|s| e == *s));
                if seed && let Some(name) = path.file_name() {
                    std::fs::copy(&path, corpus.join(name))?;
                }
            }
        }
        let mut cmd = cargo();
        cmd.current_dir(&root)
            // cargo-fuzz passes unstable compiler flags (sanitizer coverage); the toolchain is
            // stable, so they are enabled for this build only.
            .env("RUSTC_BOOTSTRAP", "1")
            .args(["fuzz", "run", "--target-dir"])
            .arg(root.join("target/fuzz"))
            .arg(target)
            .arg(&corpus)
            .arg("--")
            .arg(format!("-max_total_time={FUZZ_SECONDS}"))
            .arg("-rss_limit_mb=2048")
            .arg(format!("-artifact_prefix={}/", artifacts.display()));
        run(&mut cmd)?;
    }
    Ok(())
}

/// Path of the webdriver capabilities used by `wasm-bindgen-test-runner` in the browser step.
const WEBDRIVER_JSON: &str = "webdriver.json";

/// Chromium and its driver from Debian's `chromium` and `chromium-driver` packages.
const CHROMIUM: &str = "/usr/bin/chromium";
const CHROMEDRIVER: &str = "/usr/bin/chromedriver";

struct Step {
    id: char,
    title: String,
    action: Box<dyn Fn() -> Result<()>>,
}

impl Step {
    fn new(id: char, title: impl Into<String>, action: impl Fn() -> Result<()> + 'static) -> Self {
        Self {
            id,
            title: title.into(),
            action: Box::new(action),
        }
    }
}

/// Runs every test step. `quick` skips the steps that need a browser or a display; `only`
/// (step letters such as `"a,g"`) picks steps.
pub fn run_all(quick: bool, only: Option<&str>) -> Result<()> {
    let started = Instant::now();
    let mut steps = steps(quick);
    if let Some(only) = only {
        let letters = only.chars().filter(char::is_ascii_alphabetic);
        let wanted: Vec<char> = letters.map(|c| c.to_ascii_lowercase()).collect();
        if let Some(unknown) = wanted.iter().find(|c| !steps.iter().any(|s| s.id == **c)) {
            bail!(
                "--only: there is no step `{unknown}` (steps: a to k; f, h, i and j not with --quick)"
            );
        }
        steps.retain(|step| wanted.contains(&step.id));
    }
    let needs = |ids: &str| steps.iter().any(|step| ids.contains(step.id));

    header("setup: tools the tests need");
    if needs("fhi") {
        tools::ensure_apt_packages()?;
    }
    if needs("cefi") {
        tools::ensure_wasm_target()?;
    }
    if needs("efi") {
        tools::ensure_wasm_bindgen()?;
    }
    if needs("i") {
        tools::ensure_node_modules()?;
    }
    println!("all tools present");

    let count = steps.len();
    for (index, step) in steps.iter().enumerate() {
        let number = index + 1;
        header(&format!("[{number}/{count}] {}. {}", step.id, step.title));
        let step_started = Instant::now();
        (step.action)().with_context(|| format!("step {}. `{}` failed", step.id, step.title))?;
        if number < count {
            println!(
                "-- {}. passed in {:.0} s (total {:.0} s)",
                step.id,
                step_started.elapsed().as_secs_f64(),
                started.elapsed().as_secs_f64()
            );
        }
    }
    if quick {
        println!("\nquick test run passed (browser and desktop steps skipped)");
    }
    Ok(())
}

fn steps(quick: bool) -> Vec<Step> {
    let clippy_crates = package_args(WASM_CLIPPY_CRATES).join(" ");
    let test_crates = package_args(WASM_TEST_CRATES).join(" ");
    let steps = vec![
        Step::new('a', "format: cargo fmt --all -- --check", || {
            run(cargo().args(["fmt", "--all", "--", "--check"]))
        }),
        Step::new(
            'b',
            "lint and build (native): cargo test --workspace --all-targets --no-run, the workspace's crates compiled by clippy-driver with -D warnings (the lints of cargo clippy --workspace --all-targets -- -D warnings)",
            util::build_linted_tests,
        ),
        Step::new(
            'c',
            format!(
                "lint (wasm32): cargo clippy --target {WASM_TARGET} {clippy_crates} -- -D warnings"
            ),
            || {
                let mut cmd = cargo();
                cmd.args(["clippy", "--target", WASM_TARGET])
                    .args(package_args(WASM_CLIPPY_CRATES))
                    .args(["--", "-D", "warnings"]);
                run(&mut cmd)
            },
        ),
        Step::new(
            'd',
            "native tests: cargo test --workspace (as built by step b)",
            || run(&mut util::linted_cargo_test()?),
        ),
        Step::new(
            'e',
            format!("wasm tests in Node: cargo test --target {WASM_TARGET} {test_crates}"),
            || run(&mut wasm_test_command(false)),
        ),
        Step::new(
            'f',
            format!(
                "wasm tests in headless Chromium: WASM_BINDGEN_USE_BROWSER=1 cargo test --target {WASM_TARGET} {test_crates}"
            ),
            || run(&mut wasm_test_command(true)),
        ),
        Step::new(
            'g',
            "architecture: forbidden dependencies (cargo tree -e normal --target all)",
            check_architecture,
        ),
        Step::new(
            'k',
            "dependencies: cargo deny check bans licenses sources (deny.toml)",
            || {
                // Without default features: they fetch advisories, and the check runs offline.
                let options = ["--no-default-features"];
                tools::ensure_cargo_tool("deny", "cargo-deny", "0.18.9", &options)?;
                // `--offline` reads every platform's crates from the local registry: fetch them
                // first (quick when they are there) so a fresh machine has them.
                run(cargo().args(["fetch"]))?;
                run(cargo().args(["deny", "--offline", "check", "bans", "licenses", "sources"]))
            },
        ),
        Step::new(
            'h',
            "desktop smoke test: swarf-app --screenshot under xvfb-run",
            desktop::smoke_test,
        ),
        Step::new(
            'j',
            format!(
                "fuzzing: cargo fuzz run parse / pieces / interpret / linked / setup, {FUZZ_SECONDS} s each (seeds: the examples and golden programs and setups)"
            ),
            fuzz,
        ),
        Step::new(
            'i',
            "web build (release) and browser end-to-end tests (WebGL2, WebGPU): xvfb-run -a node --test tests/e2e/",
            || {
                web::build(false, false)?;
                header("i. xvfb-run -a node --test tests/e2e/");
                run(&mut node_test_command())
            },
        ),
    ];
    // The browser, desktop and fuzzing steps are not quick.
    let slow = |step: &Step| quick && "fhji".contains(step.id);
    steps.into_iter().filter(|step| !slow(step)).collect()
}

fn package_args(packages: &[&str]) -> Vec<String> {
    (packages.iter())
        .flat_map(|p| ["-p".to_owned(), (*p).to_owned()])
        .collect()
}

/// `cargo test` for the core crates on wasm32 through `wasm-bindgen-test-runner`: in Node, or
/// with `browser` in headless Chromium (`$CHROMEDRIVER`, `$WASM_BINDGEN_TEST_WEBDRIVER_JSON`).
fn wasm_test_command(browser: bool) -> Command {
    let mut cmd = cargo();
    cmd.args(["test", "--target", WASM_TARGET])
        .args(package_args(WASM_TEST_CRATES));
    // Start from a clean slate: a mode variable left in the caller's environment would
    // silently move the Node run into a browser or the other way round.
    for var in [
        "WASM_BINDGEN_USE_BROWSER",
        "WASM_BINDGEN_USE_NODE_EXPERIMENTAL",
        "WASM_BINDGEN_USE_DENO",
        "WASM_BINDGEN_USE_DEDICATED_WORKER",
        "WASM_BINDGEN_USE_SHARED_WORKER",
        "WASM_BINDGEN_USE_SERVICE_WORKER",
        "WASM_BINDGEN_TEST_ONLY_NODE",
        "WASM_BINDGEN_TEST_ONLY_WEB",
        "NO_HEADLESS",
        "GECKODRIVER",
        "GECKODRIVER_REMOTE",
        "CHROMEDRIVER_REMOTE",
        "SAFARIDRIVER",
        "SAFARIDRIVER_REMOTE",
    ] {
        cmd.env_remove(var);
    }
    // Debug wasm on a busy 2-core machine is slow; the default limit is 20 s per suite.
    cmd.env("WASM_BINDGEN_TEST_TIMEOUT", "600");
    if browser {
        cmd.env("WASM_BINDGEN_USE_BROWSER", "1")
            .env("CHROMEDRIVER", CHROMEDRIVER)
            .env("WASM_BINDGEN_TEST_DRIVER_TIMEOUT", "60")
            .env(
                "WASM_BINDGEN_TEST_WEBDRIVER_JSON",
                util::repo_root().join(WEBDRIVER_JSON),
            );
    }
    cmd
}

/// `node --test tests/e2e/` under `xvfb-run -a`: the WebGPU test needs headed Chromium (it skips
/// without a `DISPLAY`); `xvfb-run` keeps node's status and prints nothing, so its summary is last.
fn node_test_command() -> Command {
    let mut cmd = command("xvfb-run");
    // Xvfb is an X server: keep Chromium off any Wayland compositor of the caller.
    cmd.env_remove("WAYLAND_DISPLAY")
        .args(["-a", "node", "--test", "tests/e2e/"])
        .env("SWARF_CHROMIUM", CHROMIUM)
        .env("SWARF_WEB_DIR", web::site_dir());
    // The tests serve the page with this program itself rather than through cargo, unless a
    // build during the run replaced it (then cargo runs the new one).
    if let Some(xtask) = std::env::current_exe().ok().filter(|p| p.exists()) {
        cmd.env("SWARF_XTASK", xtask);
    }
    cmd
}

/// Checks [`FORBIDDEN_DEPENDENCIES`] with `cargo tree`.
fn check_architecture() -> Result<()> {
    let mut violations = Vec::new();
    for (package, forbidden) in FORBIDDEN_DEPENDENCIES {
        let mut cmd = cargo();
        cmd.args([
            "tree", "-e", "normal", "--target", "all", "--prefix", "none", "--format", "{p}", "-p",
            package,
        ]);
        let tree = util::output(&mut cmd)?;
        let names: std::collections::BTreeSet<&str> = (tree.lines())
            .filter_map(|line| line.split_whitespace().next())
            .collect();
        let ruled_out = |name: &&str| forbidden.iter().any(|f| in_family(name, f));
        let bad: Vec<&str> = (names.iter().copied()).filter(ruled_out).collect();
        let verdict = if bad.is_empty() {
            "ok".to_owned()
        } else {
            format!("FORBIDDEN: {}", bad.join(", "))
        };
        let (count, rules) = (names.len(), forbidden.join(", "));
        println!(
            "{package:<15} {count:>3} crates in its tree; must not contain {rules:<32} {verdict}"
        );
        if let Some(first) = bad.first() {
            let list = bad.join(", ");
            violations.push(format!(
                "{package} depends on {list} (see `cargo tree -e normal --target all -p {package} -i {first}`)"
            ));
        }
    }
    let broken = violations.join("\n  ");
    if violations.is_empty() {
        Ok(())
    } else {
        bail!("dependency rules of ARCHITECTURE.md broken:\n  {broken}")
    }
}

/// `name` is `family` or a crate of that family (`egui-wgpu`, `egui_kittest`, `wgpu-core`).
fn in_family(name: &str, family: &str) -> bool {
    name == family || (name.strip_prefix(family)).is_some_and(|rest| rest.starts_with(['-', '_']))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crate_families() {
        assert!(in_family("egui", "egui"));
        assert!(in_family("egui-wgpu", "egui"));
        assert!(in_family("egui_kittest", "egui"));
        assert!(in_family("wgpu-core", "wgpu"));
        assert!(!in_family("eguix", "egui"));
        assert!(!in_family("swarf-interpolate", "swarf-interp"));
        assert!(in_family("swarf-interp", "swarf-interp"));
    }
}
