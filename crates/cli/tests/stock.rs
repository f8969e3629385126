//! The stock on the command line: `check` warns of rapids into it and shank cuts at their
//! lines, `stats` reports the material removed, and a bad `[stock]` or `[tools.N]` is a usage
//! error naming its key. (`render --stock` is checked against a golden image in render.rs.)
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::swarf;

/// A slot 5 mm deep along Y25 from X20 to X70 (lines 7–8), then a rapid plunge 3 mm into the
/// stock at X30 Y10 (line 11).
const SLOT: &str = "%
O4000 (a slot, then a rapid into the stock)
G21 G90 G17
T1 M6
G00 Z50.
G00 X20. Y25. Z5.
G01 Z-5. F200.
G01 X70. F600.
G00 Z5.
G00 X30. Y10.
G00 Z-3.
G00 Z50.
M30
%
";

/// A 100 × 50 × 20 mm block with its top at Z0 in 0.25 mm cells, and T1 a 10 mm flat end mill
/// with 6 mm flutes.
const SETUP: &str = "[stock]
min = [0, 0, -20]
max = [100, 50, 0]
cell_mm = 0.25

[tools.1]
diameter = 10
flute_length = 6
";

/// The slot program and `setup` written to a temporary folder: (folder, program, setup).
fn files(setup: &str) -> (tempfile::TempDir, String, String) {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("slot.nc");
    std::fs::write(&nc, SLOT).unwrap();
    let toml = dir.path().join("setup.toml");
    std::fs::write(&toml, setup).unwrap();
    let [nc, toml] = [nc, toml].map(|p| p.to_str().unwrap().to_string());
    (dir, nc, toml)
}

#[test]
fn check_warns_of_a_rapid_into_the_stock_at_its_line() {
    let (_dir, nc, setup) = files(SETUP);
    let (code, out, err) = swarf(&["check", &nc, "--setup", &setup]);
    assert_eq!(code, 0, "warnings leave the status at 0: {err}");
    assert!(out.is_empty());
    assert_eq!(
        err,
        format!(
            "{nc}:11:1: warning[W-RAPID-INTO-STOCK]: a rapid move into the stock: the tool meets \
             material at X29.125 Y5.125, 3.000 mm below its top\n"
        )
    );

    // With flutes shorter than the slot is deep, the plunge and the cut rub the shank.
    let (_dir, nc, setup) = files(&SETUP.replace("flute_length = 6", "flute_length = 4"));
    let (code, _, err) = swarf(&["check", &nc, "--setup", &setup]);
    assert_eq!(code, 0);
    let codes: Vec<&str> = err
        .lines()
        .map(|l| l.split(": ").nth(1).unwrap_or(l))
        .collect();
    assert_eq!(
        codes,
        [
            "warning[W-SHANK-CUT]",
            "warning[W-SHANK-CUT]",
            "warning[W-RAPID-INTO-STOCK]"
        ],
        "{err}"
    );
    assert!(err.starts_with(&format!("{nc}:7:1: ")), "{err}");
    assert!(err.contains("past the tool's 4.000 mm flutes"), "{err}");
}

#[test]
fn without_a_stock_check_cuts_none_unless_asked() {
    let (_dir, nc, _) = files(SETUP);
    let (code, _, err) = swarf(&["check", &nc]);
    assert_eq!((code, err.as_str()), (0, ""));
    // Asked: a box round the feed moves, below the plunge's start at Z5, cut by a 10 mm tool;
    // the rapid plunge at Y10 lies outside it.
    let (code, _, err) = swarf(&["check", &nc, "--stock"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 2, "{err}");
    assert_eq!(
        lines[0],
        format!(
            "{nc}:5:1: note[N-TOOL-ASSUMED]: T1 has no `[tools.1]` in the setup: cut as a 10 mm \
             flat end mill"
        )
    );
    assert!(
        lines[1].starts_with(&format!(
            "{nc}:7:1: note[N-STOCK-ASSUMED]: no `[stock]` in the setup: the stock is taken as \
             X15.000..75.000 Y20.000..30.000 Z-10.000..5.000 mm"
        )),
        "{}",
        lines[1]
    );
}

#[test]
fn stats_reports_the_material_removed_and_the_rapids_into_the_stock() {
    let (_dir, nc, setup) = files(SETUP);
    let (code, out, err) = swarf(&["stats", &nc, "--setup", &setup, "--json"]);
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    let stock = &report["stock"];
    // The slot (50 × 10 mm and its round ends, 5 deep) and the plunge (10 mm across, 3 deep).
    let expected = 5.0 * (500.0 + 25.0 * std::f64::consts::PI) + 3.0 * 25.0 * std::f64::consts::PI;
    let removed = stock["removed_mm3"].as_f64().unwrap();
    assert!(
        (removed - expected).abs() < expected * 0.01,
        "{removed} mm³, expected {expected}"
    );
    assert_eq!(stock["rapids_into_stock"], 1);
    assert_eq!(stock["shank_cuts"], 0);
    assert_eq!(report["diagnostics"]["warnings"], 1);

    let (_, out, _) = swarf(&["stats", &nc, "--setup", &setup]);
    let line = out.lines().find(|l| l.starts_with("stock ")).unwrap();
    assert!(
        line.ends_with("mm³ removed, 1 rapids into it, 0 shank cuts"),
        "{line}"
    );

    // No stock, none asked for: none reported.
    let (_, out, _) = swarf(&["stats", &nc, "--json"]);
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(report["stock"].is_null(), "{out}");
}

#[test]
fn a_bad_stock_or_tool_is_a_usage_error_naming_its_key() {
    for (setup, want) in [
        (
            SETUP.replace("cell_mm = 0.25", "cell_mm = 0"),
            "`stock.cell_mm` must be from",
        ),
        (
            SETUP.replace("diameter = 10", "diameter = -1"),
            "`tools.1.diameter` must be from 0.001 to 1000 (it is -1)",
        ),
        (
            SETUP.replace("flute_length = 6", "flutes = 6"),
            "`[tools.1]`: unknown field `flutes`",
        ),
    ] {
        let (_dir, nc, setup) = files(&setup);
        for command in ["check", "stats", "canon"] {
            let (code, _, err) = swarf(&[command, &nc, "--setup", &setup]);
            assert_eq!(code, 2, "{command}: {err}");
            assert!(
                err.contains("invalid setup") && err.contains(want),
                "{command}: {err}"
            );
        }
    }
}
