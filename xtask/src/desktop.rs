//! Desktop smoke test: run the native app under Xvfb, let it save a screenshot, check the PNG.

use std::collections::HashMap;
use std::os::unix::process::CommandExt as _;
use std::path::Path;
use std::process::{Child, Command};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};

use crate::util::{self, command};

/// How long the app may take to start, render and save its screenshot.
const TIMEOUT: Duration = Duration::from_secs(180);

/// Builds `swarf-app` (debug, with the tests), runs `swarf-app --screenshot target/desktop.png` under
/// `xvfb-run -a` and checks that the screenshot shows more than one colour.
pub fn smoke_test() -> Result<()> {
    // The test build (step b's) holds the binary too: built the same way, with the features
    // the workspace's tests unify, nothing is compiled again after it.
    util::build_linted_tests()?;
    let root = util::repo_root();
    let binary = root.join("target").join("debug").join("swarf-app");
    let screenshot = root.join("target").join("desktop.png");
    if screenshot.exists() {
        std::fs::remove_file(&screenshot)
            .with_context(|| format!("removing the old {}", screenshot.display()))?;
    }

    let mut cmd = command("xvfb-run");
    // Xvfb is an X server: keep winit off any Wayland compositor of the caller.
    cmd.env_remove("WAYLAND_DISPLAY")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(&binary)
        .arg("--screenshot")
        .arg(&screenshot)
        // A process group of its own, so a hang can be ended with Xvfb and all.
        .process_group(0);
    println!("$ {}", util::display(&cmd));
    let child = cmd.spawn();
    let child = util::started(&cmd, child)?;
    let status = wait_with_timeout(child, TIMEOUT)?;
    util::check_status(&cmd, status)?;

    check_screenshot(&screenshot)
}

fn wait_with_timeout(mut child: Child, timeout: Duration) -> Result<std::process::ExitStatus> {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait()? {
            return Ok(status);
        }
        if start.elapsed() > timeout {
            let group = format!("-{}", child.id());
            // `kill -- -PGID` ends the app, xvfb-run and its Xvfb together.
            let _ = Command::new("kill").args(["-TERM", "--", &group]).status();
            std::thread::sleep(Duration::from_secs(2));
            let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
            let _ = child.wait();
            bail!(
                "the desktop app did not exit within {} s (killed); it should render a few \
                 frames, save the screenshot and exit 0",
                timeout.as_secs()
            );
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// Checks that `path` is a PNG that is not one flat colour.
pub fn check_screenshot(path: &Path) -> Result<()> {
    let shown = path.display();
    let file = std::fs::File::open(path).with_context(|| {
        format!("the app exited 0 but did not write {shown} (is --screenshot implemented?)")
    })?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = (decoder.read_info()).with_context(|| format!("{shown} is not a PNG"))?;
    let size = (reader.output_buffer_size()).context("PNG dimensions too large")?;
    let mut pixels = vec![0; size];
    let frame = (reader.next_frame(&mut pixels)).with_context(|| format!("decoding {shown}"))?;
    let channels = frame.color_type.samples();
    let data = pixels.get(..frame.buffer_size()).unwrap_or(&pixels);
    let mut counts: HashMap<&[u8], usize> = HashMap::new();
    for pixel in data.chunks_exact(channels) {
        *counts.entry(pixel).or_default() += 1;
    }
    let total: usize = counts.values().sum();
    let dominant = counts.values().copied().max().unwrap_or(0);
    let others = total - dominant;
    let (width, height, colours) = (frame.width, frame.height, counts.len());
    println!(
        "screenshot {shown}: {width}x{height}, {colours} distinct colours, {others} pixels differ from the dominant colour"
    );
    if colours < 2 || others < 100 {
        bail!("the desktop screenshot {shown} is (nearly) a single colour: nothing was drawn");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_png(path: &Path, width: u32, height: u32, pixel: impl Fn(u32, u32) -> [u8; 4]) {
        let mut data = Vec::new();
        for y in 0..height {
            for x in 0..width {
                data.extend_from_slice(&pixel(x, y));
            }
        }
        let file = std::fs::File::create(path).map(std::io::BufWriter::new);
        let Ok(file) = file else {
            return;
        };
        let mut encoder = png::Encoder::new(file, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        if let Ok(mut writer) = encoder.write_header() {
            let _ = writer.write_image_data(&data);
        }
    }

    #[test]
    fn flat_screenshots_fail_and_drawn_ones_pass() {
        let dir = std::env::temp_dir().join(format!("xtask-png-test-{}", std::process::id()));
        let _ = std::fs::create_dir_all(&dir);
        let flat = dir.join("flat.png");
        let drawn = dir.join("drawn.png");
        write_png(&flat, 64, 64, |_, _| [30, 30, 30, 255]);
        write_png(&drawn, 64, 64, |x, y| {
            if x == y || x < 4 {
                [200, 100, 0, 255]
            } else {
                [30, 30, 30, 255]
            }
        });
        assert!(check_screenshot(&flat).is_err());
        assert!(check_screenshot(&drawn).is_ok());
        assert!(check_screenshot(&dir.join("missing.png")).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
