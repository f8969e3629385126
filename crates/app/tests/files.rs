//! Desktop files: open and save in the file's encoding (byte for byte), atomic writes, crash
//! recovery, and settings kept between runs.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::collections::HashMap;
use std::path::PathBuf;

use egui_kittest::kittest::Queryable as _;
use swarf_app::desktop::{Host, atomic_write};
use swarf_app::files;
use swarf_syntax::{Dialect, Encoding};
use swarf_ui::Workbench;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-app-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_gb18030_program_is_saved_back_byte_for_byte_and_edits_keep_the_encoding() {
    let dir = scratch("gb");
    let path = dir.join("零件.nc");
    let original = encoding_rs::GB18030
        .encode("(銑削 平面)\nG01 X10. F200\n")
        .0
        .to_vec();
    std::fs::write(&path, &original).unwrap();
    let mut host = Host::with_recovery_file(dir.join("recovery.nc"));
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &path);
    assert_eq!(wb.document().encoding, Encoding::Gb18030);
    assert_eq!(wb.document().name, "零件.nc");
    assert_eq!(wb.document().path, Some(path.display().to_string()));
    assert!(!wb.is_dirty());
    assert!(host.save_to(&mut wb, &path));
    assert_eq!(std::fs::read(&path).unwrap(), original);
    wb.set_text("(銑削 平面)\nG01 X20. F200\n");
    assert!(wb.is_dirty());
    assert!(host.save_to(&mut wb, &path));
    assert!(!wb.is_dirty());
    let saved = std::fs::read(&path).unwrap();
    let decoded = swarf_syntax::decode(&saved);
    assert_eq!(decoded.encoding, Encoding::Gb18030);
    assert_eq!(decoded.text, "(銑削 平面)\nG01 X20. F200\n");
    assert_eq!(host.recent, [path.display().to_string()]);
    // No temporary file is left beside it.
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
}

#[test]
fn atomic_write_replaces_the_file_and_fails_cleanly() {
    let dir = scratch("atomic");
    let path = dir.join("a.nc");
    atomic_write(&path, b"G0 X1\n").unwrap();
    atomic_write(&path, b"G0 X2\n").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"G0 X2\n");
    assert!(atomic_write(&dir.join("missing").join("b.nc"), b"x").is_err());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

#[cfg(unix)]
#[test]
fn atomic_write_keeps_permissions_and_symbolic_links() {
    use std::os::unix::fs::PermissionsExt as _;
    let dir = scratch("links");
    let real = dir.join("real.nc");
    std::fs::write(&real, "G0 X1\n").unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
    let link = dir.join("link.nc");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    atomic_write(&link, b"G0 X2\n").unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&real).unwrap(), b"G0 X2\n");
    let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640);
}

#[test]
fn a_recent_file_that_is_gone_is_reported_and_forgotten() {
    let dir = scratch("gone");
    let path = dir.join("gone.nc");
    std::fs::write(&path, "G0 X1\n").unwrap();
    let mut host = Host::with_recovery_file(dir.join("recovery.nc"));
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &path);
    std::fs::remove_file(&path).unwrap();
    wb.open_document("other.nc", "G0 X5\n", Encoding::Utf8);
    wb.set_recent(host.recent.clone());
    // The File menu's entry asks the host to open it.
    let ctx = egui::Context::default();
    let mut harness = egui_kittest::Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Open recent").click();
    harness.run();
    harness.get_by_label(&path.display().to_string()).click();
    harness.run();
    let mut wb = harness.into_state();
    host.handle(&mut wb, &ctx);
    assert!(host.recent.is_empty(), "{:?}", host.recent);
    assert_eq!(wb.text(), "G0 X5\n");
}

#[test]
fn unsaved_edits_are_recovered_after_a_crash_and_cleared_by_saving() {
    let dir = scratch("recovery");
    let recovery = dir.join("data").join("recovery.nc");
    let path = dir.join("part.nc");
    std::fs::write(&path, "G0 X1\n").unwrap();
    let mut host = Host::with_recovery_file(recovery.clone());
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &path);
    wb.set_text("G0 X1\nG1 X5 F100\n");
    host.autosave(&wb, 10.0);
    assert!(!recovery.exists(), "written only after a moment");
    host.autosave(&wb, 11.5);
    assert!(recovery.exists());
    // The next run (the process died without saving) gets the text back.
    let mut host2 = Host::with_recovery_file(recovery.clone());
    let mut wb2 = Workbench::default();
    assert!(host2.recover(&mut wb2));
    assert_eq!(wb2.text(), "G0 X1\nG1 X5 F100\n");
    assert!(wb2.is_dirty());
    assert_eq!(wb2.document().name, "part.nc");
    assert_eq!(wb2.document().path, Some(path.display().to_string()));
    assert!(host2.save_to(&mut wb2, &path));
    assert!(!recovery.exists());
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "G0 X1\nG1 X5 F100\n"
    );
    assert!(!Host::with_recovery_file(recovery).recover(&mut Workbench::default()));
}

#[test]
fn every_tab_comes_back_after_a_crash_with_clean_files_read_again() {
    let dir = scratch("tabs");
    let recovery = dir.join("recovery.nc");
    let a = dir.join("a.nc");
    let sub = dir.join("O1234.nc");
    std::fs::write(&a, "G0 X1\n").unwrap();
    std::fs::write(&sub, "O1234\nG1 X5. F100\nM99\n").unwrap();
    let mut host = Host::with_recovery_file(recovery.clone());
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &sub);
    host.open_path(&mut wb, &a);
    wb.set_text("G0 X1\nM98 P1234\nM30\n");
    host.autosave(&wb, 1.0);
    host.autosave(&wb, 2.5);
    assert!(recovery.exists());
    // Saving another tab keeps the record: a.nc still has changes.
    wb.switch_tab(1);
    assert!(host.save_to(&mut wb, &sub));
    assert!(recovery.exists());
    // The sub changed on disk since: the clean tab is read again.
    std::fs::write(&sub, "O1234\nG1 X7. F100\nM99\n").unwrap();
    let mut next = Workbench::default();
    assert!(Host::with_recovery_file(recovery.clone()).recover(&mut next));
    assert_eq!(next.tab_count(), 3);
    // The tab active when the record was written is active again.
    assert_eq!(next.document().name, "O1234.nc");
    assert_eq!(next.text(), "O1234\nG1 X7. F100\nM99\n");
    assert!(!next.is_dirty());
    next.switch_tab(2);
    assert_eq!(next.document().name, "a.nc");
    assert_eq!(next.text(), "G0 X1\nM98 P1234\nM30\n");
    assert!(next.is_dirty());
    next.finish_analysis();
    // The call reaches the sub's tab: its move ends at X7.
    let bounds = next.stats().bounds.unwrap();
    assert!((bounds.1.x - 7.0).abs() < 1e-9, "{bounds:?}");
    // Saving the last changed tab removes the record.
    assert!(Host::with_recovery_file(recovery.clone()).save_to(&mut next, &a));
    assert!(!recovery.exists());
}

#[derive(Default)]
struct MemoryStorage(HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_string(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

#[test]
fn dialect_setup_and_recent_files_are_kept_between_runs() {
    let mut wb = Workbench::default();
    wb.set_dialect(Dialect::Syntec);
    wb.set_language(swarf_ui::i18n::Lang::ZhHant);
    wb.import_setup("[registers.2]\nlength = 75.5\n[work_offsets]\nG55 = [10, 20, -30]\n")
        .unwrap();
    let mut storage = MemoryStorage::default();
    files::store_settings(
        &mut storage,
        &wb,
        &["/a.nc".to_string(), "/b.nc".to_string()],
    );
    let mut next = Workbench::default();
    let recent = files::restore_settings(&storage, &mut next);
    assert_eq!(next.dialect(), Dialect::Syntec);
    assert_eq!(next.language(), swarf_ui::i18n::Lang::ZhHant);
    // The Chinese language asks the host for its font at once.
    assert_eq!(next.take_requests(), [swarf_ui::HostRequest::LoadCjkFont]);
    assert_eq!(next.setup(), wb.setup());
    assert_eq!(recent, ["/a.nc", "/b.nc"]);
    // A broken value is skipped, not fatal.
    eframe::Storage::set_string(&mut storage, files::KEY_SETUP, "nonsense = [".to_string());
    let mut other = Workbench::default();
    files::restore_settings(&storage, &mut other);
    // The setup type is the interpreter's, which this crate reaches only through the ui.
    #[allow(clippy::default_trait_access)]
    let default = Default::default();
    assert_eq!(other.setup(), &default);
}
