//! Finding program files for the tests of several crates (included with `#[path]`): the
//! corpus next to the repository, and the programs under a folder.

use std::path::{Path, PathBuf};

/// The extensions of program files.
const PROGRAMS: [&str; 5] = ["ngc", "nc", "gcode", "gc", "tap"];

/// `../shared/corpus` when it is there (a note says so when it is not, and the caller skips).
pub fn corpus() -> Option<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if root.is_dir() {
        Some(root)
    } else {
        eprintln!(
            "note: {} is not there; the corpus is not checked",
            root.display()
        );
        None
    }
}

/// Every program file under `dir`, in path order.
pub fn programs_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    collect(dir, &mut out);
    out
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(&path, out);
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| PROGRAMS.contains(&e))
        {
            out.push(path);
        }
    }
}
