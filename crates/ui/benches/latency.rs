//! Keystroke-to-markers latency of the editor: the time from an edit of the program to the
//! diagnostics of the new text being on screen, for a generated 10,000-line program (ready in
//! the frame of the edit) and a 1,000,000-line one (run over frames behind a progress bar), and
//! the resident memory the analysed program takes per line.
//!
//! For the 10,000-line program each frame is a real egui frame of the whole workbench (editor
//! with its markers, problems, state panel, status bar; no GPU upload, there is no GPU context).
//! For the 1,000,000-line program only the analysis is measured (the edit's parse and one
//! budget of blocks per frame until done), since laying out a million-line text in egui's
//! text editor takes far longer than the analysis and is not what is measured here.
//!
//! Run: `cargo bench -p swarf-ui --bench latency` (add `-- --quick` for fewer repetitions).
//! Prints a Markdown table for the README. Memory figures are read from `/proc/self/status`
//! (Linux only; elsewhere they are left out).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::time::{Duration, Instant};

use swarf_ui::Workbench;

/// A program of `lines` lines: straight feeds over a grid, an arc every 50 lines, a tool
/// change and a canned cycle here and there, the kind of text CAM posts.
fn program(lines: usize) -> String {
    let mut text = String::with_capacity(lines * 24);
    text.push_str("G90 G21 G17 G54\nT1 M06\nS8000 M03\nG00 X0. Y0. Z5.\n");
    let mut n = 4;
    while n < lines - 1 {
        let i = n as f64;
        let line = if n % 50 == 0 {
            format!(
                "G02 X{:.3} Y{:.3} I2. J0.\n",
                (i * 0.37) % 200.0,
                (i * 0.11) % 150.0
            )
        } else if n % 997 == 0 {
            "G81 X10. Y10. Z-3. R2. F200.\nG80\n".to_string()
        } else {
            format!(
                "G01 X{:.3} Y{:.3} Z{:.3} F1200.\n",
                (i * 0.37) % 200.0,
                (i * 0.11) % 150.0,
                -((i * 0.013) % 5.0)
            )
        };
        n += line.matches('\n').count();
        text.push_str(&line);
    }
    text.push_str("M30\n");
    text
}

/// One egui frame of the workbench at 1280 × 800.
fn frame(ctx: &egui::Context, wb: &mut Workbench) -> Duration {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 800.0),
        )),
        ..Default::default()
    };
    let t = Instant::now();
    let _ = ctx.run_ui(input, |ui| wb.ui(ui));
    t.elapsed()
}

/// Resident set size and its peak, bytes (Linux).
fn memory() -> Option<(u64, u64)> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let field = |name: &str| -> Option<u64> {
        let line = status.lines().find(|l| l.starts_with(name))?;
        let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kb * 1024)
    };
    Some((field("VmRSS:")?, field("VmHWM:")?))
}

struct Measured {
    lines: usize,
    ui: bool,
    /// Edit to new diagnostics, per repetition.
    latency: Vec<Duration>,
    frames: usize,
    longest_frame: Duration,
    /// Parsing (the part of the edit's frame that is not spread over frames).
    parse: Duration,
    retained_per_line: Option<f64>,
}

/// Edits the first line of a `lines`-line program `reps` times (alternating an error in and
/// out) and measures each edit until its diagnostics are shown.
fn measure(lines: usize, reps: usize, ui: bool) -> Measured {
    let before = memory();
    let text = program(lines);
    let ctx = egui::Context::default();
    let mut wb = Workbench::new(text.clone());
    if ui {
        frame(&ctx, &mut wb);
        frame(&ctx, &mut wb);
    }
    let retained_per_line = match (before, memory()) {
        (Some((a, _)), Some((b, _))) => Some(b.saturating_sub(a) as f64 / lines as f64),
        _ => None,
    };
    let mut latency = Vec::new();
    let mut frames = 0;
    let mut longest_frame = Duration::ZERO;
    let mut parse = Duration::ZERO;
    for rep in 0..reps {
        let edited = if rep % 2 == 0 {
            format!("G01 X$ {text}")
        } else {
            text.clone()
        };
        let t = Instant::now();
        // The edit as the editor makes it: the text changes, the analysis starts and runs
        // this frame's budget, then the frame is drawn.
        wb.set_text(edited);
        let edit = t.elapsed();
        let mut first = if ui {
            edit + frame(&ctx, &mut wb)
        } else {
            edit
        };
        frames = 1;
        while wb.analysis_progress().is_some() {
            let f = if ui {
                frame(&ctx, &mut wb)
            } else {
                let t = Instant::now();
                wb.run_frame_budget();
                t.elapsed()
            };
            first = first.max(f);
            frames += 1;
        }
        latency.push(t.elapsed());
        longest_frame = longest_frame.max(first);
        assert_eq!(
            wb.problems().iter().any(|p| p.code == "E-SYNTAX-CHAR"),
            rep % 2 == 0
        );
        let t = Instant::now();
        let _ = swarf_syntax::parse(wb.text(), swarf_syntax::Dialect::Fanuc);
        parse = parse.max(t.elapsed());
    }
    Measured {
        lines,
        ui,
        latency,
        frames,
        longest_frame,
        parse,
        retained_per_line,
    }
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let small = measure(10_000, if quick { 5 } else { 21 }, true);
    let large = measure(1_000_000, if quick { 2 } else { 5 }, false);
    println!(
        "| program | edit → diagnostics shown (median) | worst | frames | longest frame | of which parsing | resident memory per line |"
    );
    println!("|---|---|---|---|---|---|---|");
    for m in [small, large] {
        let mut sorted = m.latency.clone();
        sorted.sort();
        let median = sorted[sorted.len() / 2];
        let worst = sorted[sorted.len() - 1];
        println!(
            "| {} lines{} | {} | {} | {} | {} | {} | {} |",
            m.lines,
            if m.ui {
                ", whole frames"
            } else {
                ", analysis only"
            },
            ms(median),
            ms(worst),
            m.frames,
            ms(m.longest_frame),
            ms(m.parse),
            m.retained_per_line
                .map_or("–".to_string(), |b| format!("{b:.0} B")),
        );
    }
}
