//! Files on the desktop: native dialogs (rfd), atomic writes in the file's own encoding, recent
//! files, and crash recovery in the platform data folder (a file per tab to keep, an index).

use std::path::{Path, PathBuf};

use swarf_ui::{HostRequest, Workbench};

use crate::files::{self, Autosave, AutosaveClock, RecoveryBook, RecoveryIndex, TabState};

/// The file at `path`, refused past [`swarf_syntax::MAX_FILE_BYTES`] (and read no further).
fn read_bounded(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read as _;
    let file = std::fs::File::open(path)?;
    let refuse = |len: u64| files::too_large(len).map(std::io::Error::other);
    refuse(file.metadata()?.len()).map_or(Ok(()), Err)?;
    let mut bytes = Vec::new();
    file.take(swarf_syntax::MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)?;
    refuse(bytes.len() as u64).map_or(Ok(bytes), Err)
}

/// The recovery folder inside the data folder.
const RECOVERY_FOLDER: &str = "recovery";

/// The application id: names the data folder (`~/.local/share/swarf` on Linux).
pub const APP_ID: &str = "Swarf";

/// Desktop file state: the open file's path, the recent files and where recovery goes.
#[derive(Debug, Default)]
pub struct Host {
    /// Recent files, newest first (full paths).
    pub recent: Vec<String>,
    /// The folder of the recovery records, in the data folder (none when the platform has none).
    recovery: Option<PathBuf>,
    /// When the recovery records are written or removed.
    clock: AutosaveClock,
    /// Which recovery records are written, and which tabs are not kept.
    book: RecoveryBook,
    /// Set once the user chose to quit, so the close is no longer held back.
    pub quitting: bool,
}

impl Host {
    /// A host whose recovery records are in the platform's data folder for Swarf.
    pub fn new() -> Host {
        Host::with_data_folder(eframe::storage_dir(APP_ID))
    }

    /// A host whose recovery records are in the folder `recovery` of `data` (none without one).
    pub fn with_data_folder(data: impl Into<Option<PathBuf>>) -> Host {
        let run = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        Host {
            recovery: data.into().map(|d| d.join(RECOVERY_FOLDER)),
            book: RecoveryBook::new(&format!("{run:x}{:x}", std::process::id())),
            ..Host::default()
        }
    }

    /// Shows the tabs a previous run left with unsaved changes (the other files read again from
    /// disk); the status bar names the tabs recovered and any whose changes could not be read.
    pub fn recover(&mut self, wb: &mut Workbench) -> bool {
        let Some(dir) = self.recovery.clone() else {
            return false;
        };
        let stored = std::fs::read_to_string(dir.join(files::INDEX_KEY)).ok();
        let Some((index, record)) =
            stored.and_then(|r| RecoveryIndex::from_record(&r).map(|index| (index, r)))
        else {
            return false;
        };
        let restored = index.restore(
            |key| std::fs::read_to_string(dir.join(record_file(key))).ok(),
            |path| {
                let decoded = swarf_syntax::decode(&std::fs::read(path).ok()?);
                Some((decoded.text, decoded.encoding))
            },
        );
        // Records the index does not name are left over from a write never named.
        let named: Vec<String> = index.keys().map(record_file).collect();
        remove_records(&dir, |name| !named.iter().any(|n| n == name));
        let any = !restored.tabs.is_empty();
        if any {
            wb.restore_tabs(restored.tabs, restored.active);
            let (tabs, _) = TabState::of(wb, true);
            self.book.adopt(&tabs, &restored.records, &record);
            self.clock.settled(wb.generation());
        }
        files::report_lost(wb, &restored.lost);
        any
    }

    /// Opens the program file at `path`.
    pub fn open_path(&mut self, wb: &mut Workbench, path: &Path) {
        match read_bounded(path) {
            Ok(bytes) => {
                let (decoded, at) = (swarf_syntax::decode(&bytes), path.display().to_string());
                wb.open_file(&file_name(path), decoded.text, decoded.encoding, Some(at));
                files::push_recent(&mut self.recent, path.display().to_string());
                wb.set_recent(self.recent.clone());
            }
            Err(e) => wb.set_message(format!("Cannot open {}: {e}", path.display())),
        }
    }

    /// Opens a file dropped on the window in a tab.
    pub fn open_dropped(&mut self, wb: &mut Workbench, file: &egui::DroppedFileHandle) {
        self.open_path(wb, file.path());
    }

    /// Carries out the workbench's file requests; stops at one the user cancels.
    pub fn handle(&mut self, wb: &mut Workbench, ctx: &egui::Context) {
        for request in wb.take_requests() {
            if !self.handle_one(wb, ctx, request) {
                break;
            }
        }
    }

    /// Carries out one request; false when the user cancelled its dialog.
    fn handle_one(
        &mut self,
        wb: &mut Workbench,
        ctx: &egui::Context,
        request: HostRequest,
    ) -> bool {
        let setup_dialog = || rfd::FileDialog::new().add_filter("Setup", &["toml"]);
        match request {
            HostRequest::Open => {
                let dialog = rfd::FileDialog::new()
                    .add_filter("G-code programs", &files::PROGRAM_EXTENSIONS)
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
                let Some(path) = setup_dialog().pick_file() else {
                    return false;
                };
                let result = read_bounded(&path)
                    .map_err(|e| e.to_string())
                    .and_then(|bytes| wb.import_setup(&String::from_utf8_lossy(&bytes)));
                wb.set_message(match result {
                    Ok(()) => format!("Setup read from {}", path.display()),
                    Err(e) => format!("Cannot import {}: {e}", path.display()),
                });
            }
            HostRequest::ExportSetup => {
                let Some(path) = setup_dialog().set_file_name("SETUP.toml").save_file() else {
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
                Some(bytes) => _ = wb.add_cjk_font(ctx, bytes),
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
            .add_filter("G-code programs", &files::PROGRAM_EXTENSIONS);
        let path = wb.document().path.as_ref();
        if let Some(dir) = path.and_then(|p| Path::new(p).parent()) {
            dialog = dialog.set_directory(dir);
        }
        let path = dialog.save_file();
        path.is_some_and(|path| self.save_to(wb, &path))
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
                self.write_recovery(wb);
                true
            }
            Err(e) => {
                wb.set_message(format!("Cannot save {}: {e}", path.display()));
                false
            }
        }
    }

    /// Keeps unsaved changes in the recovery folder a moment after an edit; empties it after.
    pub fn autosave(&mut self, wb: &mut Workbench, now: f64) {
        match self.clock.step(wb.generation(), wb.any_dirty(), now) {
            Autosave::Wait => {}
            Autosave::Clear => self.clear_recovery(),
            Autosave::Write => self.write_recovery(wb),
        }
    }

    /// Brings the recovery folder up to date now (also on exit): a file for each tab to keep
    /// whose text changed, then the index, then the files it no longer names go (all of them
    /// with nothing unsaved). A tab not written is named in the status bar and tried again.
    pub fn write_recovery(&mut self, wb: &mut Workbench) {
        self.clock.restart();
        if !wb.any_dirty() {
            self.clear_recovery();
            return;
        }
        // Quitting with the changes discarded: nothing to recover.
        if self.quitting {
            return;
        }
        let (tabs, active) = TabState::of(wb, true);
        let Some(dir) = self.recovery.clone() else {
            let failed = RecoveryBook::all_failed(&tabs, "no data folder");
            if let Some(message) = self.book.report(&failed, &tabs) {
                wb.set_message(message);
            }
            return;
        };
        let made = std::fs::create_dir_all(&dir).map_err(|e| e.to_string());
        let writes = self.book.plan(&tabs);
        let results: Vec<Result<(), String>> = writes
            .iter()
            .map(|w| {
                made.clone()?;
                let text = wb.tab_text(w.tab).unwrap_or_default();
                atomic_write(&dir.join(record_file(&w.key)), text.as_bytes())
                    .map_err(|e| e.to_string())
            })
            .collect();
        let mut round = self.book.compose(&tabs, active, &writes, &results);
        let stored = !round.changed
            || atomic_write(&dir.join(files::INDEX_KEY), round.record.as_bytes())
                .map_err(|e| round.failed = RecoveryBook::all_failed(&tabs, &e.to_string()))
                .is_ok();
        if let Some(message) = self.book.report(&round.failed, &tabs) {
            wb.set_message(message);
        }
        self.book.commit(round, stored);
        let stale = self.book.take_stale();
        let stale: Vec<String> = stale.iter().map(|k| record_file(k)).collect();
        remove_records(&dir, |name| stale.iter().any(|s| s == name));
    }

    /// Empties the recovery folder: nothing is unsaved.
    fn clear_recovery(&mut self) {
        self.clock.restart();
        self.book.cleared();
        if let Some(dir) = &self.recovery {
            let index = dir.join(files::INDEX_KEY);
            if index.exists()
                && let Err(e) = std::fs::remove_file(&index)
            {
                log::warn!("cannot remove the recovery index {}: {e}", index.display());
            }
            remove_records(dir, |_| true);
        }
    }
}

/// The file of the recovery record `key` in the recovery folder.
fn record_file(key: &str) -> String {
    format!("{key}.nc")
}

/// Removes the tab records (`{key}.nc`, nothing else) in `dir` whose file names `remove` picks.
fn remove_records(dir: &Path, remove: impl Fn(&str) -> bool) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_record = name.strip_suffix(".nc").is_some_and(files::is_record_key);
        if is_record
            && remove(&name)
            && let Err(e) = std::fs::remove_file(entry.path())
        {
            log::warn!("cannot remove the recovery record {name}: {e}");
        }
    }
}

/// Environment variable naming a CJK font file to use for the Chinese interface languages.
pub const CJK_FONT_VARIABLE: &str = "SWARF_CJK_FONT";

/// Where Linux, Windows and macOS keep CJK fonts egui can read, in the order they are tried.
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

/// The bytes of the CJK font [`CJK_FONT_VARIABLE`] names, else of the system's first readable.
pub fn find_cjk_font() -> Option<Vec<u8>> {
    let named = std::env::var_os(CJK_FONT_VARIABLE).map(PathBuf::from);
    named
        .into_iter()
        .chain(CJK_FONT_FILES.iter().map(PathBuf::from))
        .find_map(|p| std::fs::read(p).ok())
}

/// The last component of `path` for titles and the status bar.
fn file_name(path: &Path) -> String {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    name.unwrap_or_else(|| path.display().to_string())
}

/// Writes `bytes` to `path` through a temporary file and a rename, so a crash never leaves a
/// half-written program; the file keeps its permissions, and a symbolic link its target.
pub fn atomic_write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write as _;
    let resolved = std::fs::canonicalize(path).ok();
    let path = resolved.as_deref().unwrap_or(path);
    let permissions = std::fs::metadata(path).ok().map(|m| m.permissions());
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
    let dir = dir.unwrap_or(Path::new("."));
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
