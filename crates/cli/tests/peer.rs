//! Peer agreement with LinuxCNC's reference interpreter `rs274` on the shared corpus programs
//! Swarf already runs completely. Skipped when `../shared` is absent or rs274 cannot be set up.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// Programs (relative to `shared/corpus/programs`) whose every motion must match rs274.
const AGREEING: &[&str] = &[
    "cncjs/arc-xy-plane.nc",
    "cncjs/arc-yz-plane.nc",
    "cncjs/arc-zx-plane.nc",
    "cncjs/circle.nc",
    "cncjs/one-inch-circle.nc",
];

fn shared() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared")
}

#[test]
fn canon_agrees_with_linuxcnc_rs274() {
    let tools = shared().join("tools/rs274");
    if !tools.join("setup.sh").is_file() {
        eprintln!("skipped: {} is not present", tools.display());
        return;
    }
    let setup = Command::new("bash").arg(tools.join("setup.sh")).output();
    match setup {
        Ok(out) if out.status.success() => {}
        other => {
            eprintln!("skipped: rs274 could not be set up: {other:?}");
            return;
        }
    }
    let dir = tempfile::tempdir().unwrap();
    for rel in AGREEING {
        let program = shared().join("corpus/programs").join(rel);
        let reference = Command::new("bash")
            .arg(tools.join("oracle.sh"))
            .arg(&program)
            .output()
            .unwrap();
        // rs274 exits non-zero at the end of some programs; what counts is its canonical output.
        let text = String::from_utf8_lossy(&reference.stdout);
        assert!(
            text.contains("STRAIGHT_") || text.contains("ARC_FEED"),
            "rs274 printed no motion for {rel}"
        );
        let ref_path = dir.path().join("ref.canon");
        std::fs::write(&ref_path, &reference.stdout).unwrap();

        let mut ours = Vec::new();
        let mut err = Vec::new();
        let code = swarf_cli::run(
            [
                "swarf",
                "canon",
                program.to_str().unwrap(),
                "--dialect",
                "linuxcnc",
            ],
            &mut ours,
            &mut err,
        );
        assert_eq!(code, 0, "{rel}: {}", String::from_utf8_lossy(&err));
        let ours_path = dir.path().join("ours.jsonl");
        std::fs::write(&ours_path, &ours).unwrap();

        let compare = Command::new("python3")
            .arg(tools.join("compare.py"))
            .arg(&ours_path)
            .arg(&ref_path)
            .output()
            .unwrap();
        assert!(
            compare.status.success(),
            "{rel} differs from rs274:\n{}",
            String::from_utf8_lossy(&compare.stdout)
        );
    }
}
