//! Files on the desktop: native open and save dialogs (rfd), atomic writes in the file's own
//! encoding, recent files, and a recovery file in the platform data folder.

use std::path::{Path, PathBuf};

use swarf_ui::{HostRequest, Workbench};

use crate::files::{self, Autosave, AutosaveClock, Session};

/// The application id: names the data folder (`~/.local/share/swarf` on Linux).
pub const APP_ID: &str = "Swarf";

/// File name extensions offered in the program dialogs.
const PROGRAM_EXTENSIONS: &[&str] = &["nc", "ngc", "tap", "gcode", "cnc", "txt", "ptp", "mpf"];

/// Desktop file state: the open file's path, the recent files and where recovery goes.
#[derive(Debug, Default)]
pub struct Host {
    /// Recent files, newest first (full paths).
    pub recent: Vec<String>,
    /// The recovery file (none when the platform has no data folder).
    recovery: Option<PathBuf>,
    /// When the recovery file is written or removed.
    clock: AutosaveClock,
    /// Set once the user chose to quit, so the close is no longer held back.
    pub quitting: bool,
}

impl Host {
    /// A host whose recovery file is in the platform's data folder for Swarf.
    pub fn new() -> Host {
        Host {
            recovery: eframe::storage_dir(APP_ID).map(|d| d.join("recovery.nc")),
            ..Host::default()
        }
    }

    /// A host with its recovery file at `path` (tests).
    pub fn with_recovery_file(path: PathBuf) -> Host {
        Host {
            recovery: Some(path),
            ..Host::default()
        }
    }

    /// Shows the tabs a previous run left with unsaved changes, if it did: unsaved texts as
    /// changes still to save, the other files read again from disk where they still are.
    pub fn recover(&mut self, wb: &mut Workbench) -> bool {
        let Some(record) = self
            .recovery
            .as_ref()
            .and_then(|p| std::fs::read_to_string(p).ok())
        else {
            return false;
        };
        let Some(mut session) = Session::from_record(&record) else {
            return false;
        };
        for tab in session.tabs.iter_mut().filter(|t| !t.dirty) {
            if let Some(bytes) = tab.path.as_ref().and_then(|p| std::fs::read(p).ok()) {
                let decoded = swarf_syntax::decode(&bytes);
                tab.text = decoded.text;
                tab.encoding = decoded.encoding;
            }
        }
        wb.restore_tabs(session.tabs, session.active);
        self.clock.settled(wb.generation());
        true
    }

    /// Opens the program file at `path`.
    pub fn open_path(&mut self, wb: &mut Workbench, path: &Path) {
        match std::fs::read(path) {
            Ok(bytes) => {
                let decoded = swarf_syntax::decode(&bytes);
                wb.open_file(
                    &file_name(path),
                    decoded.text,
                    decoded.encoding,
                    Some(path.display().to_string()),
                );
                files::push_recent(&mut self.recent, path.display().to_string());
                wb.set_recent(self.recent.clone());
            }
            Err(e) => wb.set_message(format!("Cannot open {}: {e}", path.display())),
        }
    }

    /// Reads a dropped file and opens it in a tab.
    pub fn open_dropped(&mut self, wb: &mut Workbench, file: &egui::DroppedFileHandle) {
        let path = file.path().to_path_buf();
        match file.bytes() {
            Ok(bytes) => {
                let decoded = swarf_syntax::decode(&bytes);
                let full = path.display().to_string();
                files::push_recent(&mut self.recent, full.clone());
                wb.set_recent(self.recent.clone());
                wb.open_guarded(
                    &file_name(&path),
                    decoded.text,
                    decoded.encoding,
                    Some(full),
                );
            }
            Err(e) => wb.set_message(format!("Cannot open {}: {e}", path.display())),
        }
    }

    /// Nothing arrives later on the desktop (dialogs answer at once); the web host reads picked
    /// files here.
    pub fn poll(&mut self, _wb: &mut Workbench) {}

    /// Carries out the workbench's file requests; stops at one the user cancels.
    pub fn handle(&mut self, wb: &mut Workbench, ctx: &egui::Context) {
        for request in wb.take_requests() {
            if !self.handle_one(wb, ctx, request) {
                break;
            }
        }
    }

    fn handle_one(
        &mut self,
        wb: &mut Workbench,
        ctx: &egui::Context,
        request: HostRequest,
    ) -> bool {
        match request {
            HostRequest::Open => {
                let dialog = rfd::FileDialog::new()
                    .add_filter("G-code programs", PROGRAM_EXTENSIONS)
                    .add_filter("All files", &["*"]);
                match dialog.pick_file() {
                    Some(path) => self.open_path(wb, &path),
                    None => return false,
                }
            }
            HostRequest::OpenRecent(name) => {
                if !Path::new(&name).exists() {
                    // Gone since: say so and forget it.
                    self.recent.retain(|r| *r != name);
                    wb.set_recent(self.recent.clone());
                }
                self.open_path(wb, Path::new(&name));
            }
            HostRequest::Save => match wb.document().path.clone() {
                Some(path) => return self.save_to(wb, Path::new(&path)),
                None => return self.save_as(wb),
            },
            HostRequest::SaveAs => return self.save_as(wb),
            HostRequest::ImportSetup => {
                let Some(path) = rfd::FileDialog::new()
                    .add_filter("Setup", &["toml"])
                    .pick_file()
                else {
                    return false;
                };
                let result = std::fs::read_to_string(&path)
                    .map_err(|e| e.to_string())
                    .and_then(|text| wb.import_setup(&text));
                wb.set_message(match result {
                    Ok(()) => format!("Setup read from {}", path.display()),
                    Err(e) => format!("Cannot import {}: {e}", path.display()),
                });
            }
            HostRequest::ExportSetup => {
                let Some(path) = rfd::FileDialog::new()
                    .set_file_name("SETUP.toml")
                    .add_filter("Setup", &["toml"])
                    .save_file()
                else {
                    return false;
                };
                let result = wb
                    .setup_toml()
                    .and_then(|t| atomic_write(&path, t.as_bytes()).map_err(|e| e.to_string()));
                wb.set_message(match result {
                    Ok(()) => format!("Setup written to {}", path.display()),
                    Err(e) => format!("Cannot write {}: {e}", path.display()),
                });
            }
            HostRequest::LoadCjkFont => match find_cjk_font() {
                Some(bytes) => {
                    wb.add_cjk_font(ctx, bytes);
                }
                None => wb.cjk_font_missing(),
            },
            HostRequest::Quit => {
                self.quitting = true;
                self.clear_recovery();
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        true
    }

    fn save_as(&mut self, wb: &mut Workbench) -> bool {
        let mut dialog = rfd::FileDialog::new()
            .set_file_name(&wb.document().name)
            .add_filter("G-code programs", PROGRAM_EXTENSIONS);
        if let Some(dir) = wb
            .document()
            .path
            .as_ref()
            .and_then(|p| Path::new(p).parent())
        {
            dialog = dialog.set_directory(dir);
        }
        match dialog.save_file() {
            Some(path) => self.save_to(wb, &path),
            None => false,
        }
    }

    /// Writes the program to `path` in its encoding (atomically); false when it failed.
    pub fn save_to(&mut self, wb: &mut Workbench, path: &Path) -> bool {
        let (bytes, used) = files::encode(wb.text(), wb.document().encoding);
        match atomic_write(path, &bytes) {
            Ok(()) => {
                files::push_recent(&mut self.recent, path.display().to_string());
                wb.set_recent(self.recent.clone());
                wb.set_path(Some(path.display().to_string()));
                if used == wb.document().encoding {
                    wb.mark_saved(&file_name(path));
                } else {
                    let text = wb.text().to_string();
                    wb.reload_document(&file_name(path), text, used);
                    wb.set_message(format!(
                        "Saved as UTF-8: the text has characters {} cannot hold",
                        wb.document().encoding.name()
                    ));
                }
                self.sync_recovery(wb);
                true
            }
            Err(e) => {
                wb.set_message(format!("Cannot save {}: {e}", path.display()));
                false
            }
        }
    }

    /// Writes unsaved changes to the recovery file a moment after they are made, and removes
    /// it once nothing is unsaved.
    pub fn autosave(&mut self, wb: &Workbench, now: f64) {
        match self.clock.step(wb.generation(), wb.any_dirty(), now) {
            Autosave::Wait => {}
            Autosave::Clear => self.clear_recovery(),
            Autosave::Write => self.write_recovery(wb),
        }
    }

    /// Writes the recovery file now when a tab has unsaved changes, removes it otherwise.
    fn sync_recovery(&mut self, wb: &Workbench) {
        if wb.any_dirty() {
            self.write_recovery(wb);
        } else {
            self.clear_recovery();
        }
    }

    /// Writes the recovery file (every tab) now, also on exit with unsaved changes.
    pub fn write_recovery(&mut self, wb: &Workbench) {
        self.clock.restart();
        let Some(file) = &self.recovery else {
            return;
        };
        // Quitting with the changes discarded (or saved): nothing to recover.
        if !wb.any_dirty() || self.quitting {
            return;
        }
        let record = Session::of(wb);
        if let Some(dir) = file.parent() {
            let _ = std::fs::create_dir_all(dir);
        }
        if let Err(e) = atomic_write(file, record.to_record().as_bytes()) {
            log::warn!("cannot write the recovery file {}: {e}", file.display());
        }
    }

    fn clear_recovery(&mut self) {
        self.clock.restart();
        if let Some(file) = &self.recovery
            && file.exists()
            && let Err(e) = std::fs::remove_file(file)
        {
            log::warn!("cannot remove the recovery file {}: {e}", file.display());
        }
    }
}

/// Environment variable naming a CJK font file to use for the Chinese interface languages.
pub const CJK_FONT_VARIABLE: &str = "SWARF_CJK_FONT";

/// Where the systems keep CJK fonts egui can read (TrueType or OpenType, collections too), in
/// the order they are tried: WenQuanYi Micro Hei and Noto Sans CJK on Linux, Microsoft YaHei
/// and JhengHei on Windows, PingFang and Heiti on macOS.
const CJK_FONT_FILES: &[&str] = &[
    "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc",
    "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/google-noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/wenquanyi/wqy-microhei/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/droid/DroidSansFallbackFull.ttf",
    "C:\\Windows\\Fonts\\msyh.ttc",
    "C:\\Windows\\Fonts\\msjh.ttc",
    "C:\\Windows\\Fonts\\simsun.ttc",
    "/System/Library/Fonts/PingFang.ttc",
    "/System/Library/Fonts/STHeiti Medium.ttc",
    "/System/Library/Fonts/Hiragino Sans GB.ttc",
    "/Library/Fonts/Arial Unicode.ttf",
];

/// The bytes of a CJK font: the file named by [`CJK_FONT_VARIABLE`], else the first of the
/// system's that can be read.
pub fn find_cjk_font() -> Option<Vec<u8>> {
    let named = std::env::var_os(CJK_FONT_VARIABLE).map(PathBuf::from);
    named
        .into_iter()
        .chain(CJK_FONT_FILES.iter().map(PathBuf::from))
        .find_map(|p| std::fs::read(p).ok())
}

/// The last component of `path` for titles and the status bar.
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so a
/// crash or a full disk never leaves a half-written program in place of the old one. A file
/// that exists keeps its permissions, and a symbolic link keeps pointing at the file written.
pub fn atomic_write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write as _;
    let resolved = std::fs::canonicalize(path).ok();
    let path = resolved.as_deref().unwrap_or(path);
    let permissions = std::fs::metadata(path).ok().map(|m| m.permissions());
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".{}.tmp", std::process::id()));
    let tmp = dir.join(tmp_name);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        if let Some(p) = permissions {
            std::fs::set_permissions(&tmp, p)?;
        }
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
