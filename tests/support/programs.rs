//! Finding program files for the tests of several crates (included with `#[path]`): the
//! corpus next to the repository, and the programs under a folder.
#![allow(dead_code, reason = "each test uses part of this module")]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

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

/// Runs `check` on every item, spread over the machine's threads: the corpus checks take most
/// of a test run on one. A failing check panics on its thread, which fails the test once all
/// are done; on one thread (or where none can be started) the items are checked in turn.
pub fn check_each<T: Sync>(items: &[T], check: impl Fn(&T) + Sync) {
    let threads = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(items.len());
    if threads <= 1 {
        items.iter().for_each(check);
        return;
    }
    let next = AtomicUsize::new(0);
    let work = || {
        while let Some(item) = items.get(next.fetch_add(1, Ordering::Relaxed)) {
            check(item);
        }
    };
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
}
