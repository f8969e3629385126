//! The Stock view: its button in the backplot has the analysis cut the stock, which is drawn as
//! a lit surface with the rapid into it marked, its findings join the problems list, hovering
//! it tells its height, and during playback the stock is the one cut up to the current block.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

mod support;
use support::render_state;

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use glam::DVec3;
use swarf_ui::Workbench;
use swarf_ui::backplot::RAPID_INTO_STOCK_COLOR;

/// A slot 2 mm deep from the top at Z0 along X and up Y (a 10 mm tool assumed), then a rapid
/// down into the material beside it (line 7).
const PROGRAM: &str =
    "G90 G21 G17\nG1 Z-2. F300.\nG1 X40.\nG1 Y20.\nG0 Z5.\nG0 X10. Y10.\nG0 Z-1.\nM30\n";

fn harness(render_state: &egui_wgpu::RenderState) -> Harness<'static, Workbench> {
    support::drawn_workbench(
        render_state,
        Workbench::new(PROGRAM.to_string()),
        egui::vec2(1200.0, 700.0),
    )
}

/// Frames until `done` holds of the workbench (the analysis' thread answers meanwhile).
fn until(harness: &mut Harness<'_, Workbench>, what: &str, done: impl Fn(&Workbench) -> bool) {
    let start = Instant::now();
    while !done(harness.state()) {
        let wb = harness.state();
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "never: {what}; {:?} {:?} {} {:?} {:?}",
            wb.widget_rect("backplot"),
            wb.backplot().stock_button_rect(),
            wb.analysis().scene.generation,
            wb.problems(),
            wb.analysis().scene.stock
        );
        std::thread::sleep(Duration::from_millis(5));
        harness.step();
    }
    harness.step();
}

/// The codes of the problems listed, with their lines.
fn problems(wb: &Workbench) -> Vec<(u32, &'static str)> {
    wb.problems().iter().map(|p| (p.line, p.code)).collect()
}

/// Pixels of the view within 12 of `want` in each channel.
fn pixels(harness: &mut Harness<'_, Workbench>, want: [u8; 3]) -> usize {
    let view = harness.state().widget_rect("backplot").unwrap();
    let ppp = harness.ctx.pixels_per_point();
    let image = harness.render().expect("render");
    let (x0, y0) = ((view.min.x * ppp) as u32, (view.min.y * ppp) as u32);
    let (x1, y1) = ((view.max.x * ppp) as u32, (view.max.y * ppp) as u32);
    (y0..y1.min(image.height()))
        .flat_map(|y| (x0..x1.min(image.width())).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let p = image.get_pixel(x, y).0;
            p.iter().zip(want).all(|(a, b)| a.abs_diff(b) <= 12)
        })
        .count()
}

/// The uncut top of the stock as the view shades it (lit from above, sRGB).
const TOP: [u8; 3] = [154, 156, 163];

#[test]
fn the_stock_button_cuts_draws_and_reports_the_stock() {
    let Some(render_state) = render_state() else {
        eprintln!("SKIPPED: no wgpu adapter available for the stock view test");
        return;
    };
    let mut harness = harness(&render_state);
    harness.run();
    // The stock's Path button is there only while the stock is drawn.
    assert!(harness.query_by_label("Path").is_none());
    assert!(problems(harness.state()).is_empty());
    let before = pixels(&mut harness, TOP);

    // A real click on the view's Stock button: the cut is asked for and comes back.
    harness.get_by_label("Stock").click();
    until(&mut harness, "the rapid into the stock listed", |wb| {
        problems(wb).contains(&(7, "W-RAPID-INTO-STOCK"))
    });
    assert!(harness.query_by_label("Path").is_some());
    assert_eq!(
        problems(harness.state()),
        [
            (2, "N-TOOL-ASSUMED"),
            (2, "N-STOCK-ASSUMED"),
            (7, "W-RAPID-INTO-STOCK")
        ]
    );
    let cut = harness.state().analysis().scene.stock.clone().unwrap();
    assert!(cut.whole && cut.field.is_some());
    assert_eq!(cut.rapids.len(), 1);
    harness.run();
    let top = pixels(&mut harness, TOP);
    assert!(
        top > before + 2000,
        "the stock's top: {before} → {top} pixels"
    );
    let c = RAPID_INTO_STOCK_COLOR;
    let red = pixels(&mut harness, [c.r(), c.g(), c.b()]);
    assert!(
        red > 20,
        "the rapid into the stock is not marked: {red} pixels"
    );

    // Fit frames the whole block, the corners of its top included.
    harness.get_by_label("Fit").click();
    harness.run();
    let wb = harness.state();
    let (field, origin) = (cut.field.as_ref().unwrap(), wb.analysis().scene.origin);
    let view = wb.widget_rect("backplot").unwrap();
    let (nx, ny) = field.size;
    for (i, j) in [(0, 0), (nx, 0), (0, ny), (nx, ny)] {
        let corner = DVec3::new(i as f64, j as f64, 0.0) * field.cell_mm + field.min;
        let at = wb
            .backplot()
            .screen_pos((corner.with_z(field.top) - origin).as_vec3());
        assert!(
            at.is_some_and(|p| view.contains(p)),
            "{corner} at {at:?}, not in {view:?}"
        );
    }

    // Hovering the uncut top tells its height.
    let wb = harness.state();
    let origin = wb.analysis().scene.origin;
    let over = DVec3::new(20.0, 14.0, 0.0) - origin;
    let at = wb.backplot().screen_pos(over.as_vec3()).unwrap();
    harness.hover_at(at);
    harness.run();
    let label = harness.get_by_label_contains("Stock X");
    let text = format!("{label:?}");
    assert!(text.contains("Z0.000"), "{text}");

    // Playback one block on: the stock as cut by the plunge alone.
    harness.get_by_label("Block »").click();
    until(&mut harness, "the stock cut up to the first block", |wb| {
        wb.analysis()
            .scene
            .stock
            .as_ref()
            .is_some_and(|c| c.upto == 1 && c.field.is_some())
    });
    let wb = harness.state();
    let cut = wb.analysis().scene.stock.clone().unwrap();
    let field = cut.field.as_ref().unwrap();
    assert!((field.height_at(0.0, 0.0).unwrap() + 2.0).abs() < 1e-3);
    assert_eq!(field.height_at(20.0, 0.0), Some(0.0));
    // The problems stay those of the whole cut.
    assert_eq!(problems(wb).len(), 3);

    // Off: nothing more is asked, the surface goes.
    harness.get_by_label("Stop").click();
    harness.get_by_label("Stock").click();
    harness.run();
    assert!(harness.query_by_label("Path").is_none());
    let off = pixels(&mut harness, TOP);
    assert!(
        off < before + 100,
        "the stock's top still drawn: {off} pixels"
    );
}
