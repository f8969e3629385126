//! `cargo xtask pgo`: the `swarf` command line built with profile-guided optimisation, into
//! `target/pgo/release/swarf`.
//!
//! Three steps in a target folder of their own (`target/pgo`, whose dependencies are built the
//! first time and reused after): the workspace's crates are built instrumented; the
//! instrumented `swarf stats` runs a generated CAM-style finishing program (straight moves with
//! and without their G word, arcs by radius and by centre in two planes, feed changes, sequence
//! numbers: about 160 000 lines, in two dialects, on one thread and on two) and the example
//! programs in `assets/examples`; and the workspace's crates are built again with the profile
//! those runs wrote (merged by `llvm-profdata` from rustup's `llvm-tools` component, installed
//! when missing). The training programs are not the benchmark's.
//!
//! The dependencies are built as usual: the flags reach the workspace's crates only, through
//! this program as cargo's `RUSTC_WORKSPACE_WRAPPER` ([`wrap`]). Cargo does not see them, so
//! each build first cleans those crates from the folder, and the result is checked to write no
//! profile of its own.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};

use anyhow::{Context, Result, bail};

use crate::tools;
use crate::util::{self, cargo, command, output, run};

/// The variable that carries the extra `rustc` flags (separated by `\x1f`) to the wrapper, and
/// whose presence makes this program act as one.
const WRAP_FLAGS: &str = "SWARF_PGO_RUSTC_FLAGS";

/// The variable that carries `rustc` flags (separated by `\x1f`) for the `swarf` binary's own
/// crate only, on top of [`WRAP_FLAGS`].
const BIN_FLAGS: &str = "SWARF_PGO_BIN_FLAGS";

/// The flags that link the `swarf` binary statically, where the C library allows it (x86-64
/// Linux): with no dynamic loader to map and bind the C, maths and unwinding libraries at every
/// start, a run begins about 0.6 ms sooner here, a tenth of a short program's run. Only the
/// binary's own crate takes them (`-C target-feature=+crt-static` is read where it is linked;
/// a fixed address, as `crates/cli/build.rs` links it, needs the static relocation model), so
/// the dependencies are built as usual. The `render` command, which loads the Vulkan driver,
/// runs in `swarf-render` beside it (`swarf_cli::RENDER_HELPER`), built for the machine's own
/// target.
const STATIC_FLAGS: &[&str] = if cfg!(all(
    target_os = "linux",
    target_env = "gnu",
    target_arch = "x86_64"
)) {
    &["-Ctarget-feature=+crt-static", "-Crelocation-model=static"]
} else {
    &[]
};

/// The workspace's packages that the `swarf` binary is built from: cleaned before each build,
/// so that cargo builds them again with the wrapper's flags.
const PACKAGES: [&str; 5] = [
    "swarf-syntax",
    "swarf-interp",
    "swarf-toolpath",
    "swarf-render",
    "swarf-cli",
];

/// Runs as cargo's `RUSTC_WORKSPACE_WRAPPER` when [`WRAP_FLAGS`] is set: `rustc` (the first
/// argument) with the rest of the arguments and those flags, and its exit status. `None` when
/// this program is not called as the wrapper.
pub fn wrap() -> Option<ExitCode> {
    let flags = std::env::var(WRAP_FLAGS).ok()?;
    let mut args = std::env::args_os().skip(1);
    let rustc = args.next()?;
    let args: Vec<_> = args.collect();
    // The `swarf` binary's crate (the library is `swarf_cli`).
    let bin = args
        .windows(2)
        .any(|pair| pair[0] == "--crate-name" && pair[1] == "swarf");
    let bin_flags = if bin {
        std::env::var(BIN_FLAGS).unwrap_or_default()
    } else {
        String::new()
    };
    let status = Command::new(rustc)
        .args(args)
        .args(split_flags(&flags))
        .args(split_flags(&bin_flags))
        .status();
    Some(match status {
        Ok(status) => ExitCode::from(u8::try_from(status.code().unwrap_or(1)).unwrap_or(1)),
        Err(error) => {
            eprintln!("error: could not run rustc: {error}");
            ExitCode::FAILURE
        }
    })
}

/// The flags in a variable of [`WRAP_FLAGS`]'s form.
fn split_flags(flags: &str) -> impl Iterator<Item = &str> {
    flags.split('\x1f').filter(|flag| !flag.is_empty())
}

/// The target the `swarf` binary is built for: on x86-64 Linux musl's C library where it can
/// be installed ([`tools::ensure_musl`]), else the machine's own (`None`). A static glibc
/// binary starts by asking the processor about its caches, dozens of `cpuid` instructions,
/// each a trip to the hypervisor in a virtual machine (6 µs each here, half a millisecond a
/// start); musl asks nothing, and a run of `swarf stats` on a short program is a tenth
/// shorter.
fn swarf_target() -> Option<&'static str> {
    if !cfg!(all(
        target_os = "linux",
        target_env = "gnu",
        target_arch = "x86_64"
    )) {
        return None;
    }
    match tools::ensure_musl() {
        Ok(()) => Some(tools::MUSL_TARGET),
        Err(error) => {
            eprintln!(
                "pgo: {} cannot be built here ({error:#}); swarf is linked with glibc",
                tools::MUSL_TARGET
            );
            None
        }
    }
}

/// Builds `target/pgo/release/swarf` (see the module's documentation) and returns its path.
pub fn build() -> Result<PathBuf> {
    let profdata = llvm_profdata()?;
    let target = swarf_target();
    let dir = util::target_dir().join("pgo");
    let swarf = dir.join("release").join("swarf");
    let profiles = dir.join("profiles");
    if profiles.exists() {
        std::fs::remove_dir_all(&profiles)
            .with_context(|| format!("could not empty {}", profiles.display()))?;
    }
    std::fs::create_dir_all(&profiles)
        .with_context(|| format!("could not make {}", profiles.display()))?;

    util::header("pgo: the instrumented build");
    build_with(
        &dir,
        &format!("-Cprofile-generate={}", profiles.display()),
        STATIC_FLAGS,
        target,
    )?;
    util::header("pgo: training runs");
    train(&swarf, &dir)?;
    let merged = dir.join("swarf.profdata");
    run(Command::new(&profdata)
        .arg("merge")
        .arg("-o")
        .arg(&merged)
        .arg(&profiles))?;
    util::header("pgo: the optimised build");
    build_with(
        &dir,
        &format!("-Cprofile-use={}", merged.display()),
        STATIC_FLAGS,
        target,
    )?;
    check_not_instrumented(&swarf, &dir)?;
    check_render_helper(&swarf)?;
    println!("pgo: {}", swarf.display());
    Ok(swarf)
}

/// Builds the `swarf` binary and its render helper in `dir` with `flag` given to the
/// workspace's crates and `bin_flags` to the `swarf` binary's own: `swarf` for `target` where
/// one is given (and copied to `dir/release`, beside the helper), the helper for the machine.
fn build_with(dir: &Path, flag: &str, bin_flags: &[&str], target: Option<&str>) -> Result<()> {
    // The machine's own folder (the helper, and `swarf` where it has no other target), then
    // `target`'s.
    for target in std::iter::once(None).chain(target.map(Some)) {
        let mut clean = cargo();
        clean
            .args(["clean", "--release", "--quiet"])
            .env("CARGO_TARGET_DIR", dir);
        if let Some(target) = target {
            clean.args(["--target", target]);
        }
        for package in PACKAGES {
            clean.args(["-p", package]);
        }
        run(&mut clean)?;
    }
    let wrapper = std::env::current_exe().context("where is this program?")?;
    let build = |bins: &[&str], target: Option<&str>| -> Result<()> {
        let mut cmd = cargo();
        cmd.args(["build", "--release", "-p", "swarf-cli"]);
        for bin in bins {
            cmd.args(["--bin", bin]);
        }
        if let Some(target) = target {
            cmd.args(["--target", target]);
        }
        run(cmd
            .env("CARGO_TARGET_DIR", dir)
            .env("RUSTC_WORKSPACE_WRAPPER", &wrapper)
            .env(WRAP_FLAGS, flag)
            .env(BIN_FLAGS, bin_flags.join("\x1f")))
    };
    let Some(target) = target else {
        return build(&["swarf", "swarf-render"], None);
    };
    build(&["swarf"], Some(target))?;
    build(&["swarf-render"], None)?;
    let built = dir.join(target).join("release").join("swarf");
    let swarf = dir.join("release").join("swarf");
    // Removed first: cargo's copy there may be a hard link to its own.
    if swarf.exists() {
        std::fs::remove_file(&swarf)
            .with_context(|| format!("could not remove {}", swarf.display()))?;
    }
    std::fs::copy(&built, &swarf)
        .with_context(|| format!("could not copy {} to {}", built.display(), swarf.display()))?;
    Ok(())
}

/// Runs the instrumented `swarf` over the training programs (their profiles go where the
/// build told them to).
fn train(swarf: &Path, dir: &Path) -> Result<()> {
    let program = dir.join("finishing.nc");
    std::fs::write(&program, finishing_program())
        .with_context(|| format!("could not write {}", program.display()))?;
    let mut runs: Vec<(PathBuf, &str, bool)> = Vec::new();
    for dialect in ["linuxcnc", "fanuc"] {
        runs.push((program.clone(), dialect, false));
        runs.push((program.clone(), dialect, true));
    }
    let examples = util::repo_root().join("assets").join("examples");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&examples)
        .with_context(|| format!("could not list {}", examples.display()))?
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| path.extension().is_some_and(|ext| ext == "nc"))
        .collect();
    files.sort();
    for file in files {
        let name = file
            .file_name()
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_default();
        let dialect = ["syntec", "lnc", "kt", "gsk", "linuxcnc"]
            .into_iter()
            .find(|d| name.starts_with(&format!("{d}-")))
            .unwrap_or("fanuc");
        runs.push((file, dialect, false));
    }
    for (file, dialect, one_thread) in runs {
        let mut cmd = Command::new(swarf);
        cmd.arg("stats")
            .arg(&file)
            .args(["--dialect", dialect])
            .stdout(Stdio::null())
            .stderr(Stdio::null());
        if one_thread {
            cmd.arg("--one-thread");
        }
        println!("$ {}", util::display(&cmd));
        let status = cmd
            .status()
            .with_context(|| format!("could not start {}", swarf.display()))?;
        // 1: the program has errors, which is a finished run too.
        if !matches!(status.code(), Some(0 | 1)) {
            bail!("`{}` failed ({status})", util::display(&cmd));
        }
    }
    Ok(())
}

/// Fails when `swarf` still writes a profile (a workspace crate of its was left instrumented,
/// e.g. one missing from [`PACKAGES`]).
fn check_not_instrumented(swarf: &Path, dir: &Path) -> Result<()> {
    let probe = dir.join("probe.profraw");
    let _ = std::fs::remove_file(&probe);
    let status = Command::new(swarf)
        .arg("--version")
        .env("LLVM_PROFILE_FILE", &probe)
        .stdout(Stdio::null())
        .status()
        .with_context(|| format!("could not start {}", swarf.display()))?;
    if !status.success() {
        bail!("{} --version failed ({status})", swarf.display());
    }
    if probe.exists() {
        bail!(
            "{} still writes a profile: a crate of the workspace that it is built from is missing from the list in xtask/src/pgo.rs",
            swarf.display()
        );
    }
    Ok(())
}

/// Fails when `swarf render` does not reach the renderer: a statically linked `swarf` hands
/// it to `swarf-render` beside it, whose help this asks for (no GPU needed).
fn check_render_helper(swarf: &Path) -> Result<()> {
    let mut cmd = Command::new(swarf);
    cmd.args(["render", "--help"]);
    // `output` names the command when it cannot start or fails.
    let help = output(&mut cmd)?;
    if !help.contains("Usage: swarf render") {
        bail!("`{}` printed no render usage:\n{help}", util::display(&cmd));
    }
    Ok(())
}

/// `llvm-profdata` of the pinned toolchain, from rustup's `llvm-tools` component (added when
/// missing).
fn llvm_profdata() -> Result<PathBuf> {
    let find = || -> Option<PathBuf> {
        let sysroot = util::sysroot().ok()?;
        let version = output(command("rustc").arg("-vV")).ok()?;
        let host = version
            .lines()
            .find_map(|line| line.strip_prefix("host: "))?;
        let path = sysroot
            .join("lib")
            .join("rustlib")
            .join(host.trim())
            .join("bin")
            .join("llvm-profdata");
        path.is_file().then_some(path)
    };
    if let Some(path) = find() {
        return Ok(path);
    }
    run(command("rustup").args(["component", "add", "llvm-tools"]))?;
    find().context("rustup's llvm-tools component has no llvm-profdata")
}

/// The training program: a 3D finishing job of the kind CAM systems write, in millimetres.
/// Sixty passes along X at rising Y, each a plunge and 2 500 moves over a wavy surface: most
/// are modal `X… Z…` lines, the rest `G1 X Y Z` lines, XY moves, G18 arcs by radius and G17
/// arcs by centre (each followed by `G1`), and numbered blocks that change the feed. The
/// numbers come from a fixed xorshift sequence, so the program is the same every time.
fn finishing_program() -> String {
    use std::fmt::Write as _;
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut random = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut out = String::with_capacity(6 << 20);
    out.push_str(
        "%\n(FINISHING)\nG21 G17 G40 G49 G80 G90 G94\nT1 M6\nS12000 M3\nG0 X0. Y0. Z5.\nF800.\n",
    );
    let mut sequence = 0;
    for pass in 0..60 {
        let y = f64::from(pass) * 0.5;
        let _ = writeln!(
            out,
            "(PASS {pass})\nG0 X0. Y{y:.4} Z2.\nG1 Z-0.5 F300.\nF1200."
        );
        let mut x = 0.0_f64;
        for _ in 0..2500 {
            let pick = random();
            let from = x;
            x += 0.05 + random() * 0.3;
            let z = -0.5 - 0.3 * (x * 0.1 + f64::from(pass)).sin();
            let _ = if pick < 0.6 {
                writeln!(out, " X{x:.4} Z{z:.4}")
            } else if pick < 0.75 {
                writeln!(out, "G1 X{x:.3} Y{y:.4} Z{z:.3}")
            } else if pick < 0.83 {
                writeln!(out, "X{x:.4} Y{y:.4}")
            } else if pick < 0.88 {
                writeln!(out, "G18 G3 X{x:.4} Z{z:.4} R2.\nG17 G1")
            } else if pick < 0.92 {
                let i = (x - from) / 2.0;
                writeln!(out, "G2 X{x:.4} Y{y:.4} I{i:.4} J-1.\nG1")
            } else if pick < 0.96 {
                sequence += 10;
                let feed = 900 + (random() * 600.0) as u32;
                writeln!(out, "N{sequence} G1 X{x:.3} Z{z:.3} F{feed}")
            } else {
                writeln!(out, "G1 X{x:.4} Y{y:.4} Z{z:.4}")
            };
        }
        out.push_str("G0 Z5.\n");
    }
    out.push_str("M5\nM30\n%\n");
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    /// The training program is the same every time, of the size documented, and its arcs
    /// close (a G2 by centre ends on its circle).
    #[test]
    fn the_training_program_is_fixed_and_sized() {
        let program = finishing_program();
        assert_eq!(program, finishing_program());
        let lines = program.lines().count();
        assert!((150_000..175_000).contains(&lines), "{lines} lines");
        assert!(program.contains("G18 G3 X"));
        let arc = program.lines().find(|l| l.starts_with("G2 X")).unwrap();
        let i: f64 = arc
            .split_whitespace()
            .find_map(|w| w.strip_prefix('I'))
            .unwrap()
            .parse()
            .unwrap();
        assert!(i > 0.0 && i < 0.2, "{arc}");
    }
}
