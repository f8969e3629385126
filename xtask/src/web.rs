//! `cargo xtask web`: builds the wasm app and assembles the static site in `target/web/`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::tools::{self, WASM_TARGET};
use crate::util::{self, cargo, command, run};

/// The package that holds the wasm entry point.
const APP_PACKAGE: &str = "swarf-app";
/// Its library's file name stem (`swarf_app.wasm`).
const APP_LIB: &str = "swarf_app";

/// Options of the web build.
#[derive(Debug, Clone, Copy, Default)]
pub struct WebOptions {
    /// Debug build (faster to compile) instead of release.
    pub dev: bool,
    /// Run `wasm-opt -Oz` when an npm-installed binaryen is present.
    pub opt: bool,
}

/// The folder the site is assembled in.
pub fn site_dir() -> PathBuf {
    util::target_dir().join("web")
}

/// Builds the web page: wasm build, wasm-bindgen, optional wasm-opt, then copies the static
/// files next to the generated ones in `target/web/`.
pub fn build(options: WebOptions) -> Result<()> {
    tools::ensure_wasm_target()?;
    tools::ensure_wasm_bindgen()?;

    let profile = if options.dev { "debug" } else { "release" };
    let mut build = cargo();
    build.args(["build", "-p", APP_PACKAGE, "--lib", "--target", WASM_TARGET]);
    if !options.dev {
        build.arg("--release");
    }
    run(&mut build)?;

    let wasm = util::target_dir()
        .join(WASM_TARGET)
        .join(profile)
        .join(format!("{APP_LIB}.wasm"));
    if !wasm.exists() {
        bail!(
            "the build did not produce {}; is `{APP_PACKAGE}` a cdylib?",
            wasm.display()
        );
    }

    let site = site_dir();
    if site.exists() {
        std::fs::remove_dir_all(&site).with_context(|| format!("removing {}", site.display()))?;
    }
    std::fs::create_dir_all(&site).with_context(|| format!("creating {}", site.display()))?;

    let mut bindgen = command("wasm-bindgen");
    bindgen
        .args([
            "--target",
            "web",
            "--no-typescript",
            "--out-name",
            APP_LIB,
            "--out-dir",
        ])
        .arg(&site)
        .arg(&wasm);
    run(&mut bindgen)?;

    let bg_wasm = site.join(format!("{APP_LIB}_bg.wasm"));
    if options.opt {
        optimize(&bg_wasm)?;
    }

    copy_static_files(&site)?;
    copy_cjk_font(&site)?;

    let size = std::fs::metadata(&bg_wasm)
        .with_context(|| format!("wasm-bindgen did not write {}", bg_wasm.display()))?
        .len();
    println!("web build ({profile}) is in {}", site.display());
    println!(
        "wasm size: {:.2} MiB ({size} bytes) {}",
        size as f64 / (1024.0 * 1024.0),
        bg_wasm.display()
    );
    Ok(())
}

/// Copies `index.html`, the files of `web/` and the `assets/` folder into the site.
fn copy_static_files(site: &Path) -> Result<()> {
    let root = util::repo_root();
    let index = root.join("index.html");
    std::fs::copy(&index, site.join("index.html"))
        .with_context(|| format!("copying {}", index.display()))?;
    let web = root.join("web");
    if web.is_dir() {
        util::copy_dir(&web, site)?;
    }
    let assets = root.join("assets");
    if assets.is_dir() {
        util::copy_dir(&assets, &site.join("assets"))?;
    }
    Ok(())
}

/// Copies the CJK font (and its copyright file) into `fonts/` of the site; the page fetches it
/// only when a Chinese interface language is chosen. Without apt the page is built without
/// it (and says so when Chinese is chosen).
fn copy_cjk_font(site: &Path) -> Result<()> {
    if let Err(e) = tools::ensure_cjk_font() {
        println!("warning: no CJK font for the page ({e:#}); Chinese will show no glyphs");
        return Ok(());
    }
    let fonts = site.join("fonts");
    std::fs::create_dir_all(&fonts).with_context(|| format!("creating {}", fonts.display()))?;
    std::fs::copy(tools::CJK_FONT, fonts.join("wqy-microhei.ttc"))
        .with_context(|| format!("copying {}", tools::CJK_FONT))?;
    if Path::new(tools::CJK_FONT_COPYRIGHT).exists() {
        std::fs::copy(
            tools::CJK_FONT_COPYRIGHT,
            fonts.join("wqy-microhei.copyright.txt"),
        )
        .with_context(|| format!("copying {}", tools::CJK_FONT_COPYRIGHT))?;
    }
    Ok(())
}

/// Runs `wasm-opt -Oz` from an npm-installed binaryen. Debian's `/usr/bin/wasm-opt` is too old
/// for the wasm features rustc emits and corrupts the output, so it is never used.
fn optimize(wasm: &Path) -> Result<()> {
    let root = util::repo_root();
    let candidates = [
        root.join("tests/e2e/node_modules/.bin/wasm-opt"),
        root.join("node_modules/.bin/wasm-opt"),
    ];
    let Some(wasm_opt) = candidates.iter().find(|path| path.exists()) else {
        println!(
            "--opt: no npm-installed binaryen found (looked for {}); skipping wasm-opt. \
             Install it with `npm install --no-save binaryen` in the repository root \
             (node_modules/ is ignored by git).",
            candidates
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        return Ok(());
    };
    let before = std::fs::metadata(wasm)?.len();
    let optimized = wasm.with_extension("opt.wasm");
    let mut cmd = std::process::Command::new(wasm_opt);
    cmd.current_dir(&root)
        .arg("-Oz")
        // The features rustc enables by default for wasm32-unknown-unknown.
        .args([
            "--enable-bulk-memory",
            "--enable-sign-ext",
            "--enable-mutable-globals",
            "--enable-nontrapping-float-to-int",
            "--enable-reference-types",
            "--enable-multivalue",
        ])
        .arg(wasm)
        .arg("-o")
        .arg(&optimized);
    run(&mut cmd)?;
    std::fs::rename(&optimized, wasm)?;
    let after = std::fs::metadata(wasm)?.len();
    println!("wasm-opt: {before} -> {after} bytes");
    Ok(())
}
