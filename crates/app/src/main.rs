//! Swarf desktop: the G-code editor and backplot in a native window. `swarf-app [FILE]...
//! [--screenshot OUT.png]`; `--screenshot` saves a PNG of the window and exits (smoke test).

#[cfg(not(target_arch = "wasm32"))]
fn main() -> anyhow::Result<()> {
    native::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use std::path::PathBuf;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};

    use anyhow::{Context as _, bail};
    use swarf_app::SwarfApp;

    /// Frames drawn before the screenshot is taken, so layout and the backplot have settled.
    const SCREENSHOT_AFTER_FRAMES: u64 = 8;

    /// Swarf's G-code editor and backplot in a window.
    #[derive(clap::Parser)]
    #[command(name = "swarf-app", version)]
    struct Args {
        /// Programs to open, each in a tab of its own.
        files: Vec<PathBuf>,
        /// Renders a few frames, saves the window as this PNG and exits.
        #[arg(long, value_name = "OUT.png")]
        screenshot: Option<PathBuf>,
    }

    pub fn main() -> anyhow::Result<()> {
        let Args { files, screenshot } = clap::Parser::parse();
        for p in &files {
            std::fs::metadata(p).with_context(|| format!("cannot read {}", p.display()))?;
        }
        let ok = Arc::new(AtomicBool::new(screenshot.is_none()));
        let options = eframe::NativeOptions {
            viewport: egui::ViewportBuilder::default()
                .with_title("Swarf — G-code editor and backplot")
                .with_inner_size([1280.0, 800.0]),
            ..Default::default()
        };
        let ok_in_app = ok.clone();
        eframe::run_native(
            swarf_app::desktop::APP_ID,
            options,
            Box::new(move |cc| {
                let mut app = SwarfApp::new(cc);
                for path in files {
                    // Each in a tab of its own beside what the last run left unsaved.
                    app.host.open_path(&mut app.workbench, &path);
                }
                if let Some(out) = screenshot {
                    // The picture shows the program's analysis, however long it takes.
                    app.workbench.finish_analysis();
                    install_screenshot(&mut app, out, ok_in_app);
                }
                Ok(Box::new(app))
            }),
        )
        .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))?;
        if !ok.load(Ordering::SeqCst) {
            bail!("the screenshot was not saved");
        }
        Ok(())
    }

    /// Takes a screenshot after a few frames, saves it and closes the window.
    fn install_screenshot(app: &mut SwarfApp, out: PathBuf, ok: Arc<AtomicBool>) {
        app.set_after_frame(move |ctx, frames| {
            if frames == SCREENSHOT_AFTER_FRAMES {
                let ctx2 = ctx.clone();
                let out = out.clone();
                let ok = ok.clone();
                ctx.request_screenshot(move |image| {
                    let [w, h] = image.size;
                    let pixels = image.pixels.iter();
                    let rgba: Vec<u8> = pixels.flat_map(egui::Color32::to_array).collect();
                    let wh = u32::try_from(w).ok().zip(u32::try_from(h).ok());
                    let img = wh.and_then(|(w, h)| image::RgbaImage::from_raw(w, h, rgba));
                    let saved = img.map(|img| img.save(&out));
                    match saved {
                        Some(Ok(())) => {
                            eprintln!("saved {w}x{h} screenshot to {}", out.display());
                            ok.store(true, Ordering::SeqCst);
                        }
                        Some(Err(e)) => eprintln!("cannot save {}: {e}", out.display()),
                        None => eprintln!("screenshot has an invalid size {w}x{h}"),
                    }
                    ctx2.send_viewport_cmd(egui::ViewportCommand::Close);
                    ctx2.request_repaint();
                });
            }
            if frames < SCREENSHOT_AFTER_FRAMES + 2 {
                ctx.request_repaint();
            }
            if frames > SCREENSHOT_AFTER_FRAMES + 600 {
                eprintln!("no screenshot arrived; giving up");
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        });
    }
}
