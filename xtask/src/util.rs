//! Helpers: repository paths, finding programs, running commands.

use std::ffi::{OsStr, OsString};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};

use anyhow::{Context, Result, bail};

/// The repository root (the parent of the `xtask` crate).
pub fn repo_root() -> PathBuf {
    let manifest_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    (manifest_dir.parent()).map_or_else(|| manifest_dir.to_path_buf(), Path::to_path_buf)
}

/// Cargo's target folder: `CARGO_TARGET_DIR` (relative to the repository root) or `target/`.
pub fn target_dir() -> PathBuf {
    // An absolute folder replaces the root when joined.
    repo_root().join(std::env::var_os("CARGO_TARGET_DIR").unwrap_or_else(|| "target".into()))
}

/// `PATH` with `cargo install`'s folder (`$CARGO_HOME/bin`, default `~/.cargo/bin`) in front
/// when it is missing, so freshly installed tools are found.
pub fn search_path() -> OsString {
    let current = std::env::var_os("PATH").unwrap_or_default();
    let mut dirs: Vec<PathBuf> = std::env::split_paths(&current).collect();
    let bin = std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cargo")))
        .map(|home| home.join("bin"));
    if let Some(bin) = bin
        && !dirs.contains(&bin)
    {
        dirs.insert(0, bin);
    }
    std::env::join_paths(dirs).unwrap_or(current)
}

/// Finds an executable in [`search_path`].
pub fn which(program: &str) -> Option<PathBuf> {
    std::env::split_paths(&search_path())
        .map(|dir| dir.join(program))
        .find(|candidate| is_executable(candidate))
}

fn is_executable(path: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt as _;
    path.metadata()
        .is_ok_and(|meta| meta.is_file() && meta.permissions().mode() & 0o111 != 0)
}

/// A command for `program` (looked up in [`search_path`]), run in the repository root, with
/// that `PATH` in its environment, and a private `XDG_RUNTIME_DIR` when the caller has none.
pub fn command(program: &str) -> Command {
    let resolved = which(program).unwrap_or_else(|| PathBuf::from(program));
    let mut cmd = Command::new(resolved);
    cmd.current_dir(repo_root()).env("PATH", search_path());
    if let Some(dir) = fallback_runtime_dir() {
        cmd.env("XDG_RUNTIME_DIR", dir);
    }
    cmd
}

/// `target/xdg-runtime` (mode 0700) when `XDG_RUNTIME_DIR` is unset or unusable (root,
/// containers): Mesa and winit complain on every start without one.
fn fallback_runtime_dir() -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt as _;
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|dir| Path::new(&dir).is_dir()) {
        return None;
    }
    let dir = repo_root().join("target").join("xdg-runtime");
    std::fs::create_dir_all(&dir).ok()?;
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700)).ok()?;
    Some(dir)
}

/// A `cargo` command (the rustup proxy, so `rust-toolchain.toml` is honoured).
pub fn cargo() -> Command {
    command("cargo")
}

/// `cargo test --workspace` with the workspace's crates compiled by clippy-driver with `-D
/// warnings`: one build lints them as `cargo clippy --workspace --all-targets -- -D warnings`
/// would and tests them, so the dependencies are compiled once.
pub fn linted_cargo_test() -> Result<Command> {
    let driver = sysroot()?.join("bin").join("clippy-driver");
    if !is_executable(&driver) {
        bail!(
            "{} is missing: the toolchain's clippy component is needed (`rustup component add clippy`)",
            driver.display()
        );
    }
    let mut cmd = cargo();
    cmd.args(["test", "--workspace"])
        .env("RUSTC_WORKSPACE_WRAPPER", driver)
        // clippy-driver's own arguments, each ended by this separator (as cargo-clippy passes
        // them).
        .env(
            "CLIPPY_ARGS",
            "-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__",
        );
    Ok(cmd)
}

/// The test build of step b and of the desktop smoke test (which runs its `swarf-app`):
/// [`linted_cargo_test`] with `--all-targets --no-run`, so the two stay the same build.
pub fn build_linted_tests() -> Result<()> {
    run(linted_cargo_test()?.args(["--all-targets", "--no-run"]))
}

/// The sysroot of the toolchain `rust-toolchain.toml` pins (`rustc --print sysroot`).
pub fn sysroot() -> Result<PathBuf> {
    let sysroot = output(command("rustc").args(["--print", "sysroot"]))?;
    Ok(PathBuf::from(sysroot.trim()))
}

/// Renders a command the way one would type it, with the variables it sets in front (but
/// `PATH` and `XDG_RUNTIME_DIR`, which [`command`] sets for every command).
pub fn display(cmd: &Command) -> String {
    let program = cmd.get_program();
    let name = Path::new(program).file_name().unwrap_or(program);
    let name = name.to_string_lossy().into_owned();
    let mut parts: Vec<String> = cmd
        .get_envs()
        .filter(|(key, _)| *key != "PATH" && *key != "XDG_RUNTIME_DIR")
        .filter_map(|(key, value)| {
            value.map(|value| format!("{}={}", key.to_string_lossy(), quote(value)))
        })
        .collect();
    parts.push(name);
    parts.extend(cmd.get_args().map(quote));
    parts.join(" ")
}

fn quote(arg: &OsStr) -> String {
    let s = arg.to_string_lossy();
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_=./:,+@%".contains(c))
    {
        s.into_owned()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

/// Runs a command to completion, echoing it first; fails on a non-zero exit.
pub fn run(cmd: &mut Command) -> Result<()> {
    println!("$ {}", display(cmd));
    let status = cmd.status();
    check_status(cmd, started(cmd, status)?)
}

/// `result` of starting `cmd`, its error naming the command.
pub fn started<T>(cmd: &Command, result: std::io::Result<T>) -> Result<T> {
    result.with_context(|| format!("could not start `{}`", display(cmd)))
}

/// Fails with a readable message when `status` is not success.
pub fn check_status(cmd: &Command, status: ExitStatus) -> Result<()> {
    if status.success() {
        Ok(())
    } else {
        bail!("`{}` failed ({status})", display(cmd))
    }
}

/// Runs a command and returns its standard output (standard error goes to the terminal).
pub fn output(cmd: &mut Command) -> Result<String> {
    let out = cmd.stderr(std::process::Stdio::inherit()).output();
    let out = started(cmd, out)?;
    check_status(cmd, out.status)?;
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Prints a step header that stands out in a long log.
pub fn header(title: &str) {
    let bar = "=".repeat(78);
    println!("\n{bar}\n== {title}\n{bar}");
}

/// Copies the file `from` to `to`.
pub fn copy(from: &Path, to: &Path) -> Result<()> {
    let context = || format!("copying {} to {}", from.display(), to.display());
    std::fs::copy(from, to).map(drop).with_context(context)
}

/// Copies a directory tree (files and sub-directories; links are followed).
pub fn copy_dir(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    for entry in std::fs::read_dir(from).with_context(|| format!("reading {}", from.display()))? {
        let entry = entry?;
        let src = entry.path();
        let dst = to.join(entry.file_name());
        if src.is_dir() {
            copy_dir(&src, &dst)?;
        } else {
            copy(&src, &dst)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_command_is_shown_with_the_variables_it_sets() {
        let mut cmd = command("cargo");
        cmd.args(["test", "--workspace"])
            .env(
                "CLIPPY_ARGS",
                "-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__",
            )
            .env("SOME_DIR", "/a b")
            .env_remove("GONE");
        assert_eq!(
            display(&cmd),
            "CLIPPY_ARGS=-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__ SOME_DIR='/a b' cargo test --workspace"
        );
    }
}
