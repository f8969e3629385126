//! `cargo xtask web`: builds the wasm app and assembles the static site in `target/web/`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::tools::{self, WASM_TARGET};
use crate::util::{self, cargo, command, run};

/// The package that holds the wasm entry point.
const APP_PACKAGE: &str = "swarf-app";
/// Its library's file name stem (`swarf_app.wasm`).
const APP_LIB: &str = "swarf_app";
/// The package of the analysis' web worker (its own module, loaded by `web/worker.js`).
const WORKER_PACKAGE: &str = "swarf-worker";
/// Its library's file name stem (`swarf_worker.wasm`).
const WORKER_LIB: &str = "swarf_worker";

/// Wasm SIMD for the page's build (every browser with WebGL2 or WebGPU has it): without it egui's
/// text rasteriser (`fearless_simd`) compiles as scalar code, a fifth of the module.
const WEB_RUSTFLAGS: &str =
    r#"target.wasm32-unknown-unknown.rustflags=["-Ctarget-feature=+simd128"]"#;

/// Extensions of the site's files written beside them compressed (`.br`, `.gz`), which
/// `cargo xtask serve` sends to browsers that accept them.
const COMPRESSED: &[&str] = &["wasm", "js", "css", "html"];

/// The folder the site is assembled in.
pub fn site_dir() -> PathBuf {
    util::target_dir().join("web")
}

/// Builds the web page: wasm build (the `web` profile of `Cargo.toml`, or a debug build with
/// `dev`), wasm-bindgen, wasm-opt (unless `dev` or `no_opt`), then copies the static files next
/// to the generated ones in `target/web/` and writes the compressed copies.
pub fn build(dev: bool, no_opt: bool) -> Result<()> {
    tools::ensure_wasm_target()?;
    tools::ensure_wasm_bindgen()?;
    let wasm_opt = (!(dev || no_opt)).then(tools::ensure_wasm_opt);
    let wasm_opt = wasm_opt
        .transpose()
        .context("wasm-opt is needed (or pass --no-opt)")?;

    let profile = if dev { "debug" } else { "web" };
    let mut build = cargo();
    build.args(["build", "-p", APP_PACKAGE, "-p", WORKER_PACKAGE, "--lib"]);
    build.args(["--target", WASM_TARGET]);
    if !dev {
        build.args(["--profile", profile, "--config", WEB_RUSTFLAGS]);
    }
    run(&mut build)?;

    let wasm = util::target_dir().join(WASM_TARGET).join(profile);
    let wasm = wasm.join(format!("{APP_LIB}.wasm"));
    if !wasm.exists() {
        let shown = wasm.display();
        bail!("the build did not produce {shown}; is `{APP_PACKAGE}` a cdylib?");
    }

    let site = site_dir();
    if site.exists() {
        std::fs::remove_dir_all(&site).with_context(|| format!("removing {}", site.display()))?;
    }
    std::fs::create_dir_all(&site).with_context(|| format!("creating {}", site.display()))?;

    let opt = wasm_opt.as_deref();
    bindgen(&wasm, "web", APP_LIB, &site, opt)?;
    // The worker's module, for a classic worker script (`importScripts`), which every browser
    // the page runs in starts.
    let worker = wasm.with_file_name(format!("{WORKER_LIB}.wasm"));
    bindgen(&worker, "no-modules", WORKER_LIB, &site, opt)?;

    copy_static_files(&site)?;
    copy_cjk_font(&site)?;
    compress(&site)?;

    println!("web build ({profile}) is in {}", site.display());
    let bg_wasm = site.join(format!("{APP_LIB}_bg.wasm"));
    for suffix in ["", ".br", ".gz"] {
        let size = std::fs::metadata(with_suffix(&bg_wasm, suffix))
            .with_context(|| format!("{} was not written", bg_wasm.display()))?
            .len();
        println!("wasm{suffix}: {:.2} MB ({size} bytes)", size as f64 / 1e6);
    }
    Ok(())
}

/// Runs wasm-bindgen for `target` on `wasm`, writing `NAME.js` and `NAME_bg.wasm` into `site`,
/// then wasm-opt `opt` on the latter.
fn bindgen(wasm: &Path, target: &str, name: &str, site: &Path, opt: Option<&Path>) -> Result<()> {
    let mut bindgen = command("wasm-bindgen");
    bindgen
        .args(["--target", target, "--no-typescript"])
        .args(["--out-name", name, "--out-dir"])
        .arg(site)
        .arg(wasm);
    run(&mut bindgen)?;
    match opt {
        Some(wasm_opt) => optimize(wasm_opt, &site.join(format!("{name}_bg.wasm"))),
        None => Ok(()),
    }
}

/// Copies `index.html`, the files of `web/` and the `assets/` folder into the site.
fn copy_static_files(site: &Path) -> Result<()> {
    let root = util::repo_root();
    let index = root.join("index.html");
    util::copy(&index, &site.join("index.html"))?;
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

/// Copies the CJK font and its copyright file into the site's `fonts/`, fetched only for a
/// Chinese interface; without apt the page is built without it (and says so).
fn copy_cjk_font(site: &Path) -> Result<()> {
    if let Err(e) = tools::ensure_cjk_font() {
        println!("warning: no CJK font for the page ({e:#}); Chinese will show no glyphs");
        return Ok(());
    }
    let fonts = site.join("fonts");
    std::fs::create_dir_all(&fonts).with_context(|| format!("creating {}", fonts.display()))?;
    util::copy(Path::new(tools::CJK_FONT), &fonts.join("wqy-microhei.ttc"))?;
    let copyright = Path::new(tools::CJK_FONT_COPYRIGHT);
    if copyright.exists() {
        util::copy(copyright, &fonts.join("wqy-microhei.copyright.txt"))?;
    }
    Ok(())
}

/// Runs `wasm-opt -Oz` (npm's binaryen), without inlining, on the wasm in place.
fn optimize(wasm_opt: &Path, wasm: &Path) -> Result<()> {
    let before = std::fs::metadata(wasm)?.len();
    let optimized = wasm.with_extension("opt.wasm");
    let mut cmd = std::process::Command::new(wasm_opt);
    cmd.current_dir(util::repo_root())
        // No inlining (before `-Oz`, to hold for its passes): on top of rustc's it makes the
        // brotli copy larger and the page slower to start.
        .args(["--no-inline=*", "-Oz"])
        // The features rustc enables by default for wasm32-unknown-unknown, and SIMD.
        .args([
            "--enable-bulk-memory",
            "--enable-sign-ext",
            "--enable-mutable-globals",
            "--enable-nontrapping-float-to-int",
            "--enable-reference-types",
            "--enable-multivalue",
            "--enable-simd",
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

/// Writes `NAME.br` (brotli, quality 11) and `NAME.gz` (gzip, level 9) beside each file of the
/// site's top folder whose extension is in [`COMPRESSED`].
fn compress(site: &Path) -> Result<()> {
    let entries = std::fs::read_dir(site).with_context(|| format!("reading {}", site.display()))?;
    let listed = |path: &PathBuf| {
        (path.extension().and_then(|e| e.to_str())).is_some_and(|e| COMPRESSED.contains(&e))
    };
    let files = entries.flatten().map(|entry| entry.path());
    let files: Vec<PathBuf> = files
        .filter(|path| path.is_file() && listed(path))
        .collect();
    // One thread a file: the wasm takes most of the time, the others finish beside it.
    std::thread::scope(|scope| {
        let jobs: Vec<_> = files
            .iter()
            .map(|file| scope.spawn(move || compress_file(file)))
            .collect();
        jobs.into_iter().try_for_each(|job| {
            job.join()
                .map_err(|_| anyhow::anyhow!("a compression thread stopped unexpectedly"))?
        })
    })
}

/// `path` with `suffix` added to its file name (`a.wasm` and `.br` make `a.wasm.br`).
pub fn with_suffix(path: &Path, suffix: &str) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(suffix);
    PathBuf::from(name)
}

fn compress_file(file: &Path) -> Result<()> {
    use std::io::Write as _;
    let data = std::fs::read(file).with_context(|| format!("reading {}", file.display()))?;
    let mut gzip = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gzip.write_all(&data)?;
    let gz = with_suffix(file, ".gz");
    std::fs::write(&gz, gzip.finish()?).with_context(|| format!("writing {}", gz.display()))?;

    let mut brotli = Vec::new();
    let params = brotli::enc::BrotliEncoderParams {
        quality: 11,
        lgwin: 24,
        ..Default::default()
    };
    brotli::BrotliCompress(&mut data.as_slice(), &mut brotli, &params)?;
    let br = with_suffix(file, ".br");
    std::fs::write(&br, brotli).with_context(|| format!("writing {}", br.display()))?;
    Ok(())
}
