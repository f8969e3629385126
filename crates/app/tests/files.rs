//! Desktop files: open and save in the file's encoding (byte for byte), atomic writes, crash
//! recovery, and settings kept between runs.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};

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
    let mut host = Host::with_data_folder(dir.join("data"));
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &path);
    assert_eq!(wb.document().encoding, Encoding::Gb18030);
    assert_eq!(wb.document().name, "零件.nc");
    assert_eq!(wb.document().path, Some(path.display().to_string()));
    assert!(!wb.document().is_unsaved());
    assert!(host.save_to(&mut wb, &path));
    assert_eq!(std::fs::read(&path).unwrap(), original);
    wb.set_text("(銑削 平面)\nG01 X20. F200\n");
    assert!(wb.document().is_unsaved());
    assert!(host.save_to(&mut wb, &path));
    assert!(!wb.document().is_unsaved());
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
    let mut host = Host::with_data_folder(dir.join("data"));
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

/// The files in the recovery folder: the index and the tabs' records, sorted.
fn recovery_files(data: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(data.join("recovery"))
        .map(|entries| {
            entries
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// The tabs' record files in the recovery folder.
fn records(data: &Path) -> Vec<String> {
    recovery_files(data)
        .into_iter()
        .filter(|n| n.starts_with("tab-"))
        .collect()
}

#[test]
fn unsaved_edits_are_recovered_after_a_crash_and_cleared_by_saving() {
    let dir = scratch("recovery");
    let data = dir.join("data");
    let path = dir.join("part.nc");
    std::fs::write(&path, "G0 X1\n").unwrap();
    let mut host = Host::with_data_folder(data.clone());
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &path);
    wb.set_text("G0 X1\nG1 X5 F100\n");
    host.autosave(&mut wb, 10.0);
    assert!(
        recovery_files(&data).is_empty(),
        "written only after a moment"
    );
    host.autosave(&mut wb, 11.5);
    // The example tab (no file to read it again from) and the edited one, and the index.
    assert_eq!(records(&data).len(), 2, "{:?}", recovery_files(&data));
    assert!(recovery_files(&data).contains(&"index".to_string()));
    assert_eq!(wb.message(), None, "a kept change says nothing");
    // The next run (the process died without saving) gets the text back, and says so.
    let mut host2 = Host::with_data_folder(data.clone());
    let mut wb2 = Workbench::default();
    assert!(host2.recover(&mut wb2));
    assert_eq!(wb2.tab_documents().len(), 2);
    assert_eq!(wb2.text(), "G0 X1\nG1 X5 F100\n");
    assert!(wb2.document().is_unsaved());
    assert_eq!(wb2.document().name, "part.nc");
    assert_eq!(wb2.document().path, Some(path.display().to_string()));
    assert_eq!(wb2.message(), Some("Recovered unsaved changes of part.nc"));
    assert!(host2.save_to(&mut wb2, &path));
    assert!(
        recovery_files(&data).is_empty(),
        "{:?}",
        recovery_files(&data)
    );
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "G0 X1\nG1 X5 F100\n"
    );
    let mut fresh = Workbench::default();
    assert!(!Host::with_data_folder(data).recover(&mut fresh));
    assert_eq!(fresh.message(), None, "nothing recovered, nothing said");
}

#[test]
fn every_tab_comes_back_after_a_crash_with_clean_files_read_again() {
    let dir = scratch("tabs");
    let data = dir.join("data");
    let a = dir.join("a.nc");
    let sub = dir.join("O1234.nc");
    std::fs::write(&a, "G0 X1\n").unwrap();
    std::fs::write(&sub, "O1234\nG1 X5. F100\nM99\n").unwrap();
    let mut host = Host::with_data_folder(data.clone());
    let mut wb = Workbench::default();
    host.open_path(&mut wb, &sub);
    host.open_path(&mut wb, &a);
    wb.set_text("G0 X1\nM98 P1234\nM30\n");
    wb.set_tab_dialect(2, Dialect::Syntec);
    host.autosave(&mut wb, 1.0);
    host.autosave(&mut wb, 2.5);
    // The example and a.nc have records; O1234.nc is read again from its file.
    assert_eq!(records(&data).len(), 2, "{:?}", recovery_files(&data));
    // Saving another tab keeps the records: a.nc still has changes.
    wb.switch_tab(1);
    assert!(host.save_to(&mut wb, &sub));
    assert_eq!(records(&data).len(), 2, "{:?}", recovery_files(&data));
    // The sub changed on disk since: the clean tab is read again.
    std::fs::write(&sub, "O1234\nG1 X7. F100\nM99\n").unwrap();
    let mut next = Workbench::default();
    assert!(Host::with_data_folder(data.clone()).recover(&mut next));
    let names: Vec<_> = next
        .tab_documents()
        .iter()
        .map(|d| d.name.clone())
        .collect();
    assert_eq!(names, ["pocket.nc", "O1234.nc", "a.nc"]);
    // The tab active when the index was written is active again.
    assert_eq!(next.document().name, "O1234.nc");
    assert_eq!(next.text(), "O1234\nG1 X7. F100\nM99\n");
    assert!(!next.document().is_unsaved());
    // Each tab keeps its dialect.
    assert_eq!(next.tab_dialect(2), Some(Dialect::Syntec));
    assert_eq!(next.tab_dialect(1), Some(Dialect::default()));
    next.switch_tab(2);
    assert_eq!(next.document().name, "a.nc");
    assert_eq!(next.text(), "G0 X1\nM98 P1234\nM30\n");
    assert!(next.document().is_unsaved());
    next.finish_analysis();
    // The call reaches the sub's tab: its move ends at X7.
    let bounds = next.stats().bounds.unwrap();
    assert!((bounds.1.x - 7.0).abs() < 1e-9, "{bounds:?}");
    // Saving the last changed tab removes the records.
    assert!(Host::with_data_folder(data.clone()).save_to(&mut next, &a));
    assert!(
        recovery_files(&data).is_empty(),
        "{:?}",
        recovery_files(&data)
    );
}

#[test]
fn only_the_tab_that_changed_is_written_again_and_closed_tabs_lose_their_record() {
    let dir = scratch("changed");
    let data = dir.join("data");
    let mut host = Host::with_data_folder(data.clone());
    let mut wb = Workbench::default();
    wb.open_document("big.nc", "G0 X1\n".repeat(10_000), Encoding::Utf8);
    wb.open_document("small.nc", "G0 X2\n", Encoding::Utf8);
    wb.set_text("G0 X2\nG1 X3 F100\n");
    host.autosave(&mut wb, 1.0);
    host.autosave(&mut wb, 2.5);
    let first = records(&data);
    assert_eq!(first.len(), 3, "{first:?}");
    let big_file = |data: &Path| {
        records(data)
            .into_iter()
            .find(|n| {
                std::fs::metadata(data.join("recovery").join(n))
                    .unwrap()
                    .len()
                    == 60_000
            })
            .unwrap()
    };
    let big = big_file(&data);
    // The big tab's record is left alone when the small one changes.
    let stamp = |data: &Path, name: &str| {
        std::fs::metadata(data.join("recovery").join(name))
            .unwrap()
            .modified()
            .unwrap()
    };
    let written = stamp(&data, &big);
    std::thread::sleep(std::time::Duration::from_millis(20));
    wb.set_text("G0 X2\nG1 X4 F100\n");
    host.autosave(&mut wb, 3.0);
    host.autosave(&mut wb, 4.5);
    let second = records(&data);
    assert_eq!(second.len(), 3, "{second:?}");
    assert_eq!(big_file(&data), big);
    assert_eq!(stamp(&data, &big), written);
    let new: Vec<_> = second.iter().filter(|n| !first.contains(n)).collect();
    assert_eq!(
        new.len(),
        1,
        "only the small tab's record is new: {first:?} {second:?}"
    );
    assert_eq!(
        std::fs::read_to_string(data.join("recovery").join(new[0])).unwrap(),
        "G0 X2\nG1 X4 F100\n"
    );
    // Switching tabs writes the index alone.
    wb.switch_tab(1);
    host.autosave(&mut wb, 5.0);
    host.autosave(&mut wb, 6.5);
    assert_eq!(records(&data), second);
    // Closing the big tab removes its record.
    wb.close_tab(1);
    host.autosave(&mut wb, 7.0);
    host.autosave(&mut wb, 8.5);
    assert_eq!(records(&data).len(), 2);
    assert!(!records(&data).contains(&big));
    let mut next = Workbench::default();
    assert!(Host::with_data_folder(data).recover(&mut next));
    let names: Vec<_> = next
        .tab_documents()
        .iter()
        .map(|d| d.name.clone())
        .collect();
    assert_eq!(names, ["pocket.nc", "small.nc"]);
    assert_eq!(next.text(), "G0 X2\nG1 X4 F100\n");
}

#[test]
fn a_tab_that_cannot_be_kept_is_named_and_tried_again_at_the_next_change() {
    let dir = scratch("failing");
    let data = dir.join("data");
    std::fs::create_dir_all(&data).unwrap();
    // A file where the recovery folder should be: nothing can be written there.
    std::fs::write(data.join("recovery"), "in the way").unwrap();
    let mut host = Host::with_data_folder(data.clone());
    let mut wb = Workbench::default();
    wb.open_document("small.nc", "G0 X2\n", Encoding::Utf8);
    wb.set_text("G0 X2\nG1 X3 F100\n");
    host.autosave(&mut wb, 1.0);
    host.autosave(&mut wb, 2.5);
    let message = wb.message().unwrap_or_default().to_string();
    assert!(
        message.starts_with("Not kept for recovery: pocket.nc, small.nc ("),
        "{message}"
    );
    // Without a change nothing is tried again; the next change is.
    std::fs::remove_file(data.join("recovery")).unwrap();
    host.autosave(&mut wb, 3.0);
    assert!(recovery_files(&data).is_empty());
    wb.set_text("G0 X2\nG1 X4 F100\n");
    host.autosave(&mut wb, 4.0);
    host.autosave(&mut wb, 5.5);
    assert_eq!(records(&data).len(), 2);
    assert_eq!(
        wb.message(),
        Some("Kept for recovery again: pocket.nc, small.nc")
    );
    let mut next = Workbench::default();
    assert!(Host::with_data_folder(data).recover(&mut next));
    assert_eq!(next.text(), "G0 X2\nG1 X4 F100\n");
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
    assert_eq!(other.setup(), &swarf_interp::Setup::default());
    // A stock the settings window shows refused comes back, to be mended there.
    let refused = "[stock]\nmin = [0, 0, 0]\nmax = [-10, 10, 10]\n";
    assert!(other.import_setup(refused).is_err());
    eframe::Storage::set_string(&mut storage, files::KEY_SETUP, refused.to_string());
    files::restore_settings(&storage, &mut other);
    assert!(other.setup().stock.is_some());
}
