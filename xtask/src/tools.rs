//! Installs the tools the build and the tests need. Every check is idempotent and fast when
//! the tool is already there, so the commands can run on a fresh CI machine.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail};

use crate::util::{self, cargo, command, output, run};

/// The wasm-bindgen version that must match the `wasm-bindgen` crate in `Cargo.lock`.
pub const WASM_BINDGEN_VERSION: &str = "0.2.130";

/// The wasm target used for the web build and the wasm tests.
pub const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// Makes sure the wasm32 target of the pinned toolchain is installed.
pub fn ensure_wasm_target() -> Result<()> {
    let installed =
        output(command("rustup").args(["target", "list", "--installed"])).unwrap_or_default();
    if installed.lines().any(|line| line.trim() == WASM_TARGET) {
        return Ok(());
    }
    run(command("rustup").args(["target", "add", WASM_TARGET]))
}

fn tool_version(program: &str) -> Option<String> {
    version_of(Command::new(util::which(program)?).arg("--version"))
}

/// What `cmd` (a `--version` query) prints, trimmed, when it succeeds.
fn version_of(cmd: &mut Command) -> Option<String> {
    let out = cmd.output().ok().filter(|o| o.status.success())?;
    Some(String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

/// Makes sure `wasm-bindgen` and `wasm-bindgen-test-runner` are exactly
/// [`WASM_BINDGEN_VERSION`], installing `wasm-bindgen-cli` with cargo otherwise.
pub fn ensure_wasm_bindgen() -> Result<()> {
    let wanted = format!("wasm-bindgen {WASM_BINDGEN_VERSION}");
    let bindgen = tool_version("wasm-bindgen");
    let runner = format!("wasm-bindgen-test-runner {WASM_BINDGEN_VERSION}");
    if bindgen.as_ref() == Some(&wanted) && tool_version("wasm-bindgen-test-runner") == Some(runner)
    {
        return Ok(());
    }
    println!(
        "wasm-bindgen-cli {WASM_BINDGEN_VERSION} is needed (found: {}); installing it (takes a few minutes)",
        bindgen.as_deref().unwrap_or("none")
    );
    let version = format!("={WASM_BINDGEN_VERSION}");
    run(cargo().args(["install", "wasm-bindgen-cli", "--version", &version]))?;
    match tool_version("wasm-bindgen") {
        Some(v) if v == wanted => Ok(()),
        found => bail!(
            "after installing, `wasm-bindgen --version` says {found:?}, expected `{wanted}`; \
             is another wasm-bindgen earlier in PATH?"
        ),
    }
}

/// Installs the crate `package` at exactly `version` (with `options` for `cargo install`)
/// unless `cargo SUB --version` already reports it.
pub fn ensure_cargo_tool(sub: &str, package: &str, version: &str, options: &[&str]) -> Result<()> {
    let found = version_of(cargo().args([sub, "--version"]));
    if found.as_deref() == Some(&format!("{package} {version}")) {
        return Ok(());
    }
    println!("{package} {version} is needed; installing it (takes a few minutes)");
    let (mut cmd, version) = (cargo(), format!("={version}"));
    cmd.args(["install", package, "--locked", "--version", &version]);
    run(cmd.args(options))
}

/// Debian packages for the browser tests (Chromium, chromedriver) and the desktop smoke test
/// (Xvfb, Mesa's lavapipe Vulkan driver, the X11 libraries winit loads).
const APT_PACKAGES: &[&str] = &[
    "chromium",
    "chromium-driver",
    "xvfb",
    "xauth",
    "mesa-vulkan-drivers",
    "libvulkan1",
    "libxkbcommon-x11-0",
    "libxcursor1",
    "libxrandr2",
    "libxi6",
    "libx11-xcb1",
];

/// Folders the shared libraries of [`APT_PACKAGES`] are looked for in.
const LIB_DIRS: [&str; 6] = [
    "/usr/lib/x86_64-linux-gnu",
    "/lib/x86_64-linux-gnu",
    "/usr/lib/aarch64-linux-gnu",
    "/lib/aarch64-linux-gnu",
    "/usr/lib64",
    "/usr/lib",
];

/// Installs Chromium, chromedriver, Xvfb and Mesa's Vulkan drivers with apt, but only when one
/// of them is missing (`apt-get update` is slow).
pub fn ensure_apt_packages() -> Result<()> {
    let exists = |path: &str| Path::new(path).exists();
    let library = |name: &str| LIB_DIRS.iter().any(|dir| exists(&format!("{dir}/{name}")));
    let icd_dirs = ["/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"];
    let entries = icd_dirs
        .iter()
        .flat_map(std::fs::read_dir)
        .flatten()
        .flatten();
    let mut names = entries.map(|entry| entry.file_name().to_string_lossy().into_owned());
    let lavapipe = names.any(|name| name.starts_with("lvp_icd") && name.ends_with(".json"));
    let present = [
        (exists("/usr/bin/chromium"), "chromium"),
        (exists("/usr/bin/chromedriver"), "chromium-driver"),
        (util::which("xvfb-run").is_some(), "xvfb"),
        (util::which("xauth").is_some(), "xauth"),
        (lavapipe, "mesa-vulkan-drivers"),
        (library("libvulkan.so.1"), "libvulkan1"),
        (library("libxkbcommon-x11.so.0"), "libxkbcommon-x11-0"),
    ];
    let missing: Vec<&str> = present.iter().filter(|p| !p.0).map(|p| p.1).collect();
    if missing.is_empty() {
        return Ok(());
    }
    println!("missing system packages: {}", missing.join(", "));
    apt_install(APT_PACKAGES)
}

/// `apt-get update` then `apt-get install -y packages` (through sudo when not root).
fn apt_install(packages: &[&str]) -> Result<()> {
    let list = packages.join(" ");
    if util::which("apt-get").is_none() {
        bail!("apt-get is not available; install by hand: {list}");
    }
    let sudo = if is_root() {
        None
    } else if util::which("sudo").is_some() {
        Some("sudo")
    } else {
        bail!("not root and no sudo: install by hand with `apt-get install {list}`");
    };
    let apt = |args: &[&str]| {
        let mut cmd = command(sudo.unwrap_or("apt-get"));
        cmd.args(sudo.map(|_| "apt-get"))
            .env("DEBIAN_FRONTEND", "noninteractive")
            .args(args);
        run(&mut cmd)
    };
    apt(&["update"])?;
    apt(&[&["install", "-y"][..], packages].concat())
}

/// The CJK font the page offers for Chinese: WenQuanYi Micro Hei from Debian's
/// `fonts-wqy-microhei` (Apache 2.0 or GPLv3 with the font exception).
pub const CJK_FONT: &str = "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc";
/// The font package's copyright file.
pub const CJK_FONT_COPYRIGHT: &str = "/usr/share/doc/fonts-wqy-microhei/copyright";

/// Installs `fonts-wqy-microhei` with apt when [`CJK_FONT`] is missing.
pub fn ensure_cjk_font() -> Result<()> {
    if Path::new(CJK_FONT).exists() {
        return Ok(());
    }
    println!("missing system package: fonts-wqy-microhei");
    apt_install(&["fonts-wqy-microhei"])
}

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|out| String::from_utf8_lossy(&out.stdout).trim() == "0")
}

/// The npm packages of `tests/e2e/package.json`: the browser tests' and binaryen's `wasm-opt`.
const NPM_PACKAGES: &[&str] = &["playwright-core", "pngjs", "binaryen"];

/// Installs the npm packages and returns npm binaryen's `wasm-opt`. Debian's binaryen is too
/// old for the wasm features rustc emits and corrupts the module, so it is never used.
pub fn ensure_wasm_opt() -> Result<PathBuf> {
    ensure_node_modules()?;
    Ok(e2e_dir().join("node_modules").join(".bin").join("wasm-opt"))
}

fn e2e_dir() -> PathBuf {
    util::repo_root().join("tests").join("e2e")
}

/// Makes sure `node` (20 or newer) and `npm` exist and that `tests/e2e/node_modules`
/// holds the packages locked in `tests/e2e/package-lock.json`.
pub fn ensure_node_modules() -> Result<()> {
    let node_major = tool_version("node").and_then(|v| {
        v.trim_start_matches('v')
            .split('.')
            .next()?
            .parse::<u32>()
            .ok()
    });
    match node_major {
        Some(major) if major >= 20 => {}
        Some(major) => bail!(
            "node {major} is too old for the browser end-to-end test (playwright-core needs \
             node 20 or newer); install a newer node from nodejs.org or NodeSource"
        ),
        None => bail!(
            "node (20 or newer) and npm are needed for wasm-opt and the browser end-to-end test; install \
             them (Debian 12's own nodejs is too old: use NodeSource or nodejs.org)"
        ),
    }
    if util::which("npm").is_none() {
        bail!("npm is needed for the browser end-to-end test's packages; install it with node");
    }
    let e2e = e2e_dir();
    let modules = e2e.join("node_modules");
    let complete =
        (NPM_PACKAGES.iter()).all(|name| modules.join(name).join("package.json").exists());
    if complete {
        return Ok(());
    }
    let verb = if e2e.join("package-lock.json").exists() {
        "ci"
    } else {
        "install"
    };
    let mut npm = command("npm");
    npm.current_dir(&e2e)
        .args([verb, "--no-audit", "--no-fund"])
        .env("PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD", "1");
    run(&mut npm).context("installing the end-to-end test's npm packages")
}
