//! Peer agreement with LinuxCNC's reference interpreter `rs274` on the shared corpus programs
//! Swarf already runs completely. Skipped when `../shared` is absent or rs274 cannot be set up.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Programs (relative to `shared/corpus`) whose every motion must match rs274, with rs274's tool
/// table as the setup's offset registers (lathe tool orientations included) and the position a
/// tool change re-reads taken as a machine's (`scripts/rs274-machine-canon.py`). The others of
/// `scripts/peer-compare.sh` differ for the reasons the agreement section of docs/interpreter.md
/// gives (rs274 stops at a block Swarf refuses and goes on from; rs274's printed rounding makes
/// moves to one machine point under rotated offsets look like several). Of `ccomp/`, `early-exit` runs in a
/// full LinuxCNC, not rs274: the interpreter's compensation tests cover it.
const AGREEING: &[&str] = &[
    "linuxcnc-tests/interp/g10/g10-l1-l10/test.ngc",
    "linuxcnc-tests/interp/g10/g10-l2-while-active/test.ngc",
    "linuxcnc-tests/interp/g10/g10-l20-while-active/test.ngc",
    "linuxcnc-tests/interp/g10/g10-with-g92/test.ngc",
    "linuxcnc-tests/interp/g52/g52-g92-interaction/g52-g92-interaction.ngc",
    "linuxcnc-tests/interp/g52/g92-offset-persistence/g92_offsets.ngc",
    "linuxcnc-tests/interp/rotation/abs-pts/test.ngc",
    "linuxcnc-tests/interp/unit-conversion/test.ngc",
    "linuxcnc-tests/interp/machine-coord-params/test.ngc",
    "linuxcnc-tests/interp/sequence-number/test.ngc",
    "linuxcnc-tests/interp/g81/g17/g98/g17-g98-g81.ngc",
    "linuxcnc-tests/interp/g81/g17/g99/g17-g99-g81.ngc",
    "linuxcnc-tests/interp/g81/g18/g98/g18-g98-g81.ngc",
    "linuxcnc-tests/interp/g81/g18/g99/g18-g99-g81.ngc",
    "linuxcnc-tests/interp/g81/g19/g98/g19-g98-g81.ngc",
    "linuxcnc-tests/interp/g81/g19/g99/g19-g99-g81.ngc",
    "linuxcnc-tests/interp/g84/g17/g98/g17-g98-g84.ngc",
    "linuxcnc-tests/interp/g84/g17/g99/g17-g99-g84.ngc",
    "linuxcnc-tests/interp/g84/g18/g98/g18-g98-g84.ngc",
    "linuxcnc-tests/interp/g84/g18/g99/g18-g99-g84.ngc",
    "linuxcnc-tests/interp/g84/g19/g98/g19-g98-g84.ngc",
    "linuxcnc-tests/interp/g84/g19/g99/g19-g99-g84.ngc",
    "programs/nist/example3.gcode",
    "linuxcnc-tests/interp/m98m99/01-basics/test.ngc",
    "linuxcnc-tests/interp/m98m99/02-variables/test.ngc",
    "linuxcnc-tests/interp/m98m99/03-error-M98-no-P-word/test.ngc",
    "linuxcnc-tests/interp/m98m99/04-M98-but-no-sub/test.ngc",
    "linuxcnc-tests/interp/m98m99/05-M98-loops/test.ngc",
    "linuxcnc-tests/interp/m98m99/07-nested-subs/test.ngc",
    "linuxcnc-tests/interp/m98m99/08-sub-follows-main/test.ngc",
    "linuxcnc-tests/interp/m98m99/09-disable-fanuc-subs/test-fanuc.ngc",
    "linuxcnc-tests/interp/m98m99/09-disable-fanuc-subs/test-rs274ngc.ngc",
    "linuxcnc-tests/interp/m98m99/10-M98-P001/test.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-end-main-with-eof.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-no-m30-before-osub.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-illegal-sub-after-percent.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-legal-end-main-with-m02.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-legal-end-main-with-m2.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-legal-end-main-with-m30.ngc",
    "linuxcnc-tests/interp/m98m99/11-main-program-oword/test-legal-end-main-with-percent.ngc",
    "linuxcnc-tests/interp/m98m99/12-M99-endless-main-program/test.ngc",
    "linuxcnc-tests/interp/m98m99/13-named-program/test-named.ngc",
    "linuxcnc-tests/interp/m98m99/13-named-program/test-numbered.ngc",
    "linuxcnc-tests/interp/m98m99/14-o-expression-call/test.ngc",
    "programs/cncjs/arc-no-plane.nc",
    "programs/cncjs/arc-xy-plane.nc",
    "programs/cncjs/arc-yz-plane.nc",
    "programs/cncjs/arc-zx-plane.nc",
    "programs/cncjs/circle.nc",
    "programs/cncjs/coordinate.nc",
    "programs/cncjs/dwell.nc",
    "programs/cncjs/feedrate.nc",
    "programs/cncjs/g92offset.nc",
    "programs/cncjs/helical-thread-milling.nc",
    "programs/cncjs/linear.nc",
    "programs/cncjs/motion.nc",
    "programs/cncjs/one-inch-circle.nc",
    "programs/cncjs/t2laser.nc",
    "programs/cncjs/units.nc",
    "programs/nist/example1.gcode",
    "programs/camotics/cameo.nc",
    "programs/camotics/tiger.nc",
    "programs/camotics/la_peinture.gc",
    "programs/linuxcnc/3D_Chips.ngc",
    "programs/linuxcnc/stellabee1.ngc",
    "linuxcnc-tests/ccomp/lathe-comp/test.ngc",
    "linuxcnc-tests/ccomp/mill-g90g91g92/test.ngc",
    "linuxcnc-tests/ccomp/mill-line-arc-entry/test.ngc",
    "linuxcnc-tests/ccomp/mill-zchanges/test.ngc",
    "linuxcnc-tests/interp/inside-corners/test.ngc",
    "linuxcnc-tests/interp/cam-nisley/cam.ngc",
    "linuxcnc-tests/interp/crazy-paths/test.ngc",
    "linuxcnc-tests/interp/inverse-time-with-comp/inverse.ngc",
    "programs/autodesk/test.fanuc.nc",
];

/// A LinuxCNC tool table (`T3 P3 Z0.5 D0.25 Q2`) as a setup: tool N's Z is register N's length,
/// half its diameter D the radius (in inches as standalone rs274 reads them) and Q its lathe
/// tool orientation.
fn table_setup(table: &str) -> String {
    let mut out = String::from("units = \"inch\"\n");
    for line in table.lines() {
        let line = line.split(';').next().unwrap_or("");
        let word = |letter: char| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(letter).and_then(|v| v.parse::<f64>().ok()))
        };
        let Some(t) = word('T') else { continue };
        out.push_str(&format!("[registers.{}]\n", t as u32));
        if let Some(z) = word('Z') {
            out.push_str(&format!("length = {z:?}\n"));
        }
        if let Some(d) = word('D') {
            out.push_str(&format!("radius = {:?}\n", d / 2.0));
        }
        if let Some(q) = word('Q').filter(|q| *q > 0.0) {
            out.push_str(&format!("orientation = {}\n", q as u8));
        }
    }
    out
}

fn shared() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared")
}

#[test]
fn tool_tables_become_registers() {
    let setup = table_setup(
        "T1 P1 Z0.511 D0.125 ;1/8 end mill\nT4 P4 Z0.7 D1.0 ;\nT7 P7 Z0.0 X0.0 D0.1 I-30.0 J30.0 Q7;\n",
    );
    let setup = swarf_interp::Setup::from_toml(&setup).unwrap();
    assert!((setup.registers[&1].radius - 0.0625 * 25.4).abs() < 1e-9);
    assert!((setup.registers[&1].length - 0.511 * 25.4).abs() < 1e-9);
    assert!((setup.registers[&4].radius - 12.7).abs() < 1e-9);
    assert_eq!(setup.registers[&4].orientation, 0);
    assert_eq!(setup.registers[&7].orientation, 7);
}

/// Held by a test while it runs rs274: one rs274 at a time (two at once, or one while its
/// setup unpacks it, can give no output).
static RS274: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The folder of rs274 and its comparator, once rs274 is set up; `None` (the tests are
/// skipped) without `../shared` or where rs274 cannot be set up.
fn rs274_tools() -> Option<PathBuf> {
    let tools = shared().join("tools/rs274");
    if !tools.join("setup.sh").is_file() {
        eprintln!("skipped: {} is not present", tools.display());
        return None;
    }
    let setup = Command::new("bash").arg(tools.join("setup.sh")).output();
    match setup {
        Ok(out) if out.status.success() => Some(tools),
        other => {
            eprintln!("skipped: rs274 could not be set up: {other:?}");
            None
        }
    }
}

/// Short programs for behaviours compared with rs274 one by one (each in a folder of its own,
/// with the tool table named, in inches as standalone rs274 reads it): absolute arc centres in
/// the three planes, a tool length offset changed without a move, the `\r\r\n` line ends of
/// some Windows tools, G10 L10/L11, and the blocks LinuxCNC stops at (motions agree up to
/// them).
const SNIPPETS: &[(&str, &str, &str)] = &[
    (
        "g90-1-xy",
        "G21 G17 G90 G90.1\nG0 X10 Y0\nG3 X0 Y10 I5 J5 F100\nG91.1\nG2 X10 Y0 I5 J-5\nM2\n",
        "",
    ),
    (
        "g90-1-xz",
        "G21 G18 G90.1\nG0 X10 Z0\nG3 X0 Z10 I5 K5 F100\nM2\n",
        "",
    ),
    (
        "g90-1-yz",
        "G21 G19 G90.1\nG0 Y10 Z0\nG3 Y0 Z10 J5 K5 F100\nG91.1 G2 Y10 Z0 J5 K-5\nM2\n",
        "",
    ),
    (
        "g90-1-offsets",
        "G21 G90.1\nG10 L2 P1 X100 Y100\nG92 X1 Y1\nG0 X10 Y0\nG91 G3 X-10 Y10 I5 J5 F100\nM2\n",
        "",
    ),
    (
        "g43-no-h",
        "G21 G90\nT1 M6\nG43\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
        "",
    ),
    (
        "g43-spindle-tool",
        "G21 G90\nT1 M6\nT2\nG43\nG0 X10 Y10\nG0 Z5\nG49\nG0 X0\nM2\n",
        "",
    ),
    ("cr-cr-lf", "G21 G90\r\r\nG0 X1 Y2\r\r\nM2\r\r\n", ""),
    (
        "g10-l10-l11",
        "G21 G90\nG10 L2 P9 Z-27\nG10 L2 P1 Z-3\nG54\nT1 M6\nG53 G0 Z-30\nG10 L11 P1 Z0\nG43\n\
         G0 X1\nG0 Z2\nG10 L10 P2 Z5\nT2 M6\nG43\nG0 X2\nG49\nG0 X3\nM2\n",
        "T1 P1 Z0.5 D0.125 ;\nT2 P2 Z0.1 D0.0625 ;\n",
    ),
    (
        "k-on-g17-arc",
        "G21\nG0 X1\nG17 G2 X1 Y1 I1 K1 F100\nM2\n",
        "",
    ),
    (
        "p-on-g73",
        "G21\nG0 Z5\nG73 X1 Y1 Z-1 R1 Q0.5 P1 F100\nM2\n",
        "",
    ),
    ("t-not-in-table", "G21\nG0 X1\nT8 M6\nG0 X2\nM2\n", ""),
    (
        "d-not-in-table",
        "G21\nT1 M6\nG0 X1\nG41 D8 G1 X2 F100\nG40 G0 X5\nM2\n",
        "",
    ),
    ("h-not-in-table", "G21\nG0 X1\nG43 H8\nG0 X2\nM2\n", ""),
];

#[test]
fn snippets_agree_with_linuxcnc_rs274() {
    let _one = RS274
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let Some(tools) = rs274_tools() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (name, text, table) in SNIPPETS {
        let folder = dir.path().join(name);
        std::fs::create_dir(&folder).unwrap();
        let program = folder.join("test.ngc");
        std::fs::write(&program, text).unwrap();
        if !table.is_empty() {
            std::fs::write(folder.join("test.tbl"), table).unwrap();
        }
        let work = folder.join("work");
        std::fs::create_dir(&work).unwrap();
        if let Err(diff) = agree(&tools, &work, &program) {
            panic!("{name} differs from rs274:\n{diff}");
        }
    }
}

#[test]
fn canon_agrees_with_linuxcnc_rs274() {
    let _one = RS274
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let Some(tools) = rs274_tools() else {
        return;
    };
    // One program at a time: rs274 runs in the program's folder, and two of one folder at
    // once can give one of them no output.
    let dir = tempfile::tempdir().unwrap();
    for rel in AGREEING {
        let program = shared().join("corpus").join(rel);
        if let Err(diff) = agree(&tools, dir.path(), &program) {
            panic!("{rel} differs from rs274:\n{diff}");
        }
    }
}

/// Runs `program` through rs274 (with its folder's tool table, else the default one) and
/// through `swarf canon` with the same table as the setup; compares the motions.
fn agree(tools: &Path, dir: &Path, program: &Path) -> Result<(), String> {
    // The folder's tool table, when it has one (LinuxCNC's tests ship theirs).
    let table = std::fs::read_dir(program.parent().unwrap())
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|x| x == "tbl"));
    let mut oracle = Command::new("bash");
    oracle.arg(tools.join("oracle.sh")).arg(program);
    if let Some(table) = &table {
        oracle.arg(table);
    }
    let table = table.unwrap_or_else(|| tools.join("default.tbl"));
    let setup_path = dir.join("setup.toml");
    std::fs::write(
        &setup_path,
        table_setup(&std::fs::read_to_string(&table).unwrap()),
    )
    .unwrap();
    let reference = oracle.output().unwrap();
    // rs274 exits non-zero at the end of some programs; what counts is its canonical output,
    // with the position a tool change re-reads from its stand-in canon layer as a machine's
    // (scripts/rs274-machine-canon.py says why).
    let machine = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/rs274-machine-canon.py"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    machine
        .stdin
        .as_ref()
        .unwrap()
        .write_all(&reference.stdout)
        .unwrap();
    let machine = machine.wait_with_output().unwrap();
    assert!(machine.status.success());
    let ref_path = dir.join("ref.canon");
    std::fs::write(&ref_path, &machine.stdout).unwrap();

    let mut ours = Vec::new();
    let mut err = Vec::new();
    let code = swarf_cli::run(
        [
            "swarf",
            "canon",
            program.to_str().unwrap(),
            "--dialect",
            "linuxcnc",
            "--setup",
            setup_path.to_str().unwrap(),
        ],
        &mut ours,
        &mut err,
    );
    // Programs with errors still agree on the motions before them.
    assert!(
        code <= 1,
        "{}: {}",
        program.display(),
        String::from_utf8_lossy(&err)
    );
    let ours_path = dir.join("ours.jsonl");
    std::fs::write(&ours_path, &ours).unwrap();

    let compare = Command::new("python3")
        .arg(tools.join("compare.py"))
        .arg(&ours_path)
        .arg(&ref_path)
        .output()
        .unwrap();
    if compare.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&compare.stdout).into_owned())
    }
}
