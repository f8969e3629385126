//! `swarf render`: writes a PNG of the toolpath offscreen; checked for size, path colours and
//! against golden images (a pocket, drilling cycles with a G22 zone, a compensated contour, a
//! slot cut out of the stock) with a tolerance. Skips (passing, with a note) when no wgpu adapter is available. Set
//! `SWARF_UPDATE_GOLDEN=1` to rewrite the golden images.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use std::path::{Path, PathBuf};
use support::swarf;

/// A small pocket: rapids, a plunge, straight cuts, a full circle, a retract.
const PROGRAM: &str = "%
O1000 (render test)
G21 G90 G17 G54
G00 X0. Y0. Z5.
G00 X10. Y10.
G01 Z-2. F200.
G01 X60. F600.
G01 Y40.
G01 X10.
G01 Y10.
G02 X35. Y25. R15.
G00 Z5.
G00 X35. Y40.
G01 Z-1. F200.
G03 X35. Y40. I0. J-10. F400.
G00 Z10.
M30
%
";

fn golden_png(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}"))
}

/// Drilling (Syntec): a G81 row under G99, a G83 peck row under G98, and a G22 protected zone
/// below the holes between two columns, seen from above.
const DRILLING: &str = "%
O2000 (golden: cycles and a G22 zone)
G71 G90 G17 G54
G22 X35. I45. Y-5. J50. Z-20. K-50.
G00 X0. Y0. Z20.
G99 G81 X10. Y10. Z-5. R2. F300.
X30.
X50.
G98 G83 X10. Y30. Z-12. R2. Q4. F250.
X30.
X50.
G80
G00 Z20.
M30
%
";

/// Cutter radius compensation (Fanuc): the tool centre's path around a square with a rounded
/// corner, cut on the left of the contour with D1 = 5 mm.
const COMPENSATED: &str = "%
O3000 (golden: G41 around a square)
G21 G90 G17 G54
G00 X-20. Y-20. Z5.
G01 Z-3. F200.
G41 D1 X0. Y0. F500.
G01 Y40.
G01 X30.
G02 X40. Y30. R10.
G01 Y0.
G01 X0.
G40 G01 X-20. Y-20.
G00 Z5.
M30
%
";

/// The setup of [`COMPENSATED`]: D1 is a 5 mm radius.
const COMPENSATED_SETUP: &str = "[registers.1]\nradius = 5.0\n";

struct Png {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

fn read_png(path: &Path) -> Png {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut rgba).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    rgba.truncate(info.buffer_size());
    Png {
        width: info.width,
        height: info.height,
        rgba,
    }
}

/// What a pixel shows, by hue (anti-aliased lines are darker but keep their hue).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Hue {
    Feed,
    Arc,
    Rapid,
}

fn hue(p: &[u8]) -> Option<Hue> {
    // Above the dark background.
    let [r, g, b] = [p[0], p[1], p[2]].map(|c| f32::from(c.saturating_sub(16)));
    if r.max(g).max(b) < 60.0 {
        return None;
    }
    // Ratios of the default colours: feed (80, 200, 255), arc (120, 230, 140), rapid
    // (235, 170, 40).
    if b >= g && g > 0.6 * b && r < 0.5 * b {
        Some(Hue::Feed)
    } else if g > 1.3 * b && g > r {
        Some(Hue::Arc)
    } else if r > g && g > b + 20.0 {
        Some(Hue::Rapid)
    } else {
        None
    }
}

fn count(image: &Png, want: Hue) -> usize {
    image
        .rgba
        .chunks_exact(4)
        .filter(|p| hue(p) == Some(want))
        .count()
}

/// Renders `PROGRAM` with `extra` arguments into a temporary PNG; `None` when there is no
/// GPU adapter (the test then skips).
fn render(dir: &tempfile::TempDir, name: &str, extra: &[&str]) -> Option<(Png, String)> {
    render_program(dir, PROGRAM, name, extra)
}

/// Renders `program` with `extra` arguments into a temporary PNG; `None` when there is no GPU
/// adapter.
fn render_program(
    dir: &tempfile::TempDir,
    program: &str,
    name: &str,
    extra: &[&str],
) -> Option<(Png, String)> {
    let nc = dir.path().join("part.nc");
    std::fs::write(&nc, program).unwrap();
    let png = dir.path().join(name);
    let mut args = vec!["render", nc.to_str().unwrap(), "-o", png.to_str().unwrap()];
    args.extend_from_slice(extra);
    let (code, out, err) = swarf(&args);
    if code == 2 && (err.contains("no GPU adapter") || err.contains("GPU device")) {
        eprintln!("SKIPPED: {err}");
        return None;
    }
    assert_eq!(code, 0, "stdout: {out}\nstderr: {err}");
    assert!(out.contains(name), "{out}");
    Some((read_png(&png), out))
}

#[test]
fn hues_match_the_palette() {
    use swarf_render::{ARC_COLOR, FEED_COLOR, GRID_MAJOR_COLOR, RAPID_COLOR, Z_AXIS_COLOR};
    assert_eq!(hue(&FEED_COLOR), Some(Hue::Feed));
    assert_eq!(hue(&ARC_COLOR), Some(Hue::Arc));
    assert_eq!(hue(&RAPID_COLOR), Some(Hue::Rapid));
    assert_eq!(hue(&Z_AXIS_COLOR), None);
    assert_eq!(hue(&GRID_MAJOR_COLOR), None);
    // Half coverage over the background keeps the hue.
    let half = FEED_COLOR.map(|c| c / 2 + 8);
    assert_eq!(hue(&half), Some(Hue::Feed));
}

#[test]
fn renders_a_png_with_path_colours_in_each_view() {
    let dir = tempfile::tempdir().unwrap();
    for view in ["iso", "top", "front", "right"] {
        let Some((image, out)) = render(
            &dir,
            &format!("{view}.png"),
            &["--view", view, "--size", "320x200"],
        ) else {
            return;
        };
        assert_eq!((image.width, image.height), (320, 200), "{view}");
        assert!(out.contains("320x200"), "{out}");
        let feed = count(&image, Hue::Feed);
        let arc = count(&image, Hue::Arc);
        assert!(feed > 50, "{view}: {feed} feed pixels");
        assert!(arc > 20, "{view}: {arc} arc pixels");
        if view != "front" && view != "right" {
            // Seen from the side, the rapids run along the cuts' edges; from above they show.
            let rapid = count(&image, Hue::Rapid);
            assert!(rapid > 10, "{view}: {rapid} rapid pixels");
        }
    }
    // Perspective and another size also work.
    let Some((image, _)) = render(&dir, "persp.png", &["--perspective", "--size", "100x300"])
    else {
        return;
    };
    assert_eq!((image.width, image.height), (100, 300));
    assert!(count(&image, Hue::Feed) > 20);
}

/// Renders `program` and compares it with `tests/golden/{name}` with a tolerance (or rewrites
/// the golden image when `SWARF_UPDATE_GOLDEN` is set).
fn check_golden(program: &str, name: &str, extra: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["--size", "256x192"];
    args.extend_from_slice(extra);
    let Some((image, _)) = render_program(&dir, program, name, &args) else {
        return;
    };
    let golden = golden_png(name);
    if std::env::var_os("SWARF_UPDATE_GOLDEN").is_some() {
        std::fs::copy(dir.path().join(name), &golden).unwrap();
        eprintln!("updated {}", golden.display());
        return;
    }
    let want = read_png(&golden);
    assert_eq!((image.width, image.height), (want.width, want.height));
    // Rasterisers differ in the last bits of anti-aliasing: count clearly different pixels.
    let differing = image
        .rgba
        .chunks_exact(4)
        .zip(want.rgba.chunks_exact(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 48))
        .count();
    let total = (image.width * image.height) as usize;
    assert!(
        differing * 200 <= total,
        "{differing} of {total} pixels differ from {} (over 0.5 %); \
         rerun with SWARF_UPDATE_GOLDEN=1 if the change is intended",
        golden.display()
    );
}

#[test]
fn iso_view_matches_the_golden_image() {
    check_golden(PROGRAM, "render_iso.png", &[]);
}

#[test]
fn drilling_with_a_stroke_limit_matches_the_golden_image() {
    check_golden(
        DRILLING,
        "render_drilling_top.png",
        &["--view", "top", "--dialect", "syntec"],
    );
}

#[test]
fn a_compensated_contour_matches_the_golden_image() {
    let dir = tempfile::tempdir().unwrap();
    let setup = dir.path().join("setup.toml");
    std::fs::write(&setup, COMPENSATED_SETUP).unwrap();
    check_golden(
        COMPENSATED,
        "render_compensated_top.png",
        &["--view", "top", "--setup", setup.to_str().unwrap()],
    );
}

/// A slot 5 mm deep along Y25 from X20 to X70, a full circle round an island at its end, and
/// a rapid plunge 3 mm into the stock at X30 Y10.
const SLOT: &str = "%
O4000 (golden: a slot cut out of the stock)
G21 G90 G17
T1 M6
G00 Z50.
G00 X20. Y25. Z5.
G01 Z-5. F200.
G01 X70. F600.
G02 X70. Y25. I0. J-12. F400.
G00 Z5.
G00 X30. Y10.
G00 Z-3.
G00 Z50.
M30
%
";

/// The stock of [`SLOT`]: a 100 × 50 × 20 mm block with its top at Z0, and T1 a 10 mm flat end
/// mill.
const SLOT_SETUP: &str =
    "[stock]\nmin = [0, 0, -20]\nmax = [100, 50, 0]\ncell_mm = 0.25\n[tools.1]\ndiameter = 10\n";

#[test]
fn the_cut_stock_matches_the_golden_image() {
    let dir = tempfile::tempdir().unwrap();
    let setup = dir.path().join("setup.toml");
    std::fs::write(&setup, SLOT_SETUP).unwrap();
    let setup = setup.to_str().unwrap();
    check_golden(SLOT, "render_stock_iso.png", &["--stock", "--setup", setup]);

    // Alone: the stock's grey and blue, none of the rapids' amber.
    let Some((image, _)) = render_program(
        &dir,
        SLOT,
        "alone.png",
        &[
            "--stock",
            "--no-path",
            "--setup",
            setup,
            "--size",
            "320x200",
        ],
    ) else {
        return;
    };
    let stock = image
        .rgba
        .chunks_exact(4)
        .filter(|p| p[0] > 60 && p[2] > p[0])
        .count();
    assert!(stock > 5000, "{stock} stock pixels");
    assert_eq!(count(&image, Hue::Rapid), 0);
}

#[test]
fn the_stroke_limit_is_outlined_in_its_colour() {
    let dir = tempfile::tempdir().unwrap();
    let Some((image, _)) = render_program(
        &dir,
        DRILLING,
        "zone.png",
        &["--view", "top", "--dialect", "syntec", "--size", "320x200"],
    ) else {
        return;
    };
    // The zone's outline: red clearly above green and blue (ZONE_COLOR is (255, 90, 70)).
    let red = image
        .rgba
        .chunks_exact(4)
        .filter(|p| p[0] > 120 && f32::from(p[0]) > 1.8 * f32::from(p[1]) && p[1] >= p[2])
        .count();
    assert!(red > 40, "{red} zone pixels");
}

#[test]
fn bad_arguments_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let nc = dir.path().join("part.nc");
    std::fs::write(&nc, PROGRAM).unwrap();
    let nc = nc.to_str().unwrap();
    for args in [
        vec!["render", nc],
        vec!["render", nc, "-o", "x.png", "--view", "bottom"],
        vec!["render", nc, "-o", "x.png", "--size", "0x10"],
        vec!["render", nc, "-o", "x.png", "--size", "big"],
    ] {
        let (code, _, err) = swarf(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
    }
    let (code, _, err) = swarf(&["render", "/nonexistent/part.nc", "-o", "x.png"]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot read"), "{err}");
}
