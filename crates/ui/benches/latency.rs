//! Keystroke-to-markers latency of the editor: the time from a keystroke in the editor to the
//! diagnostics of the new text being on screen, for a generated 10,000-line program and a
//! 1,000,000-line one (each analysed on the analysis' thread beside the frames, the long one
//! behind a progress bar), and the resident memory the open program takes per line.
//!
//! Every frame is a real egui frame of the whole workbench (editor with its markers, problems,
//! state panel, status bar; no GPU upload, there is no GPU context). The edit is a real one
//! through the editor: a `Text` event typed at the start of the first line (an error in), then
//! Ctrl+Z (the error out again). Both programs are edited in the row editor, which lays out
//! only the rows on screen.
//!
//! Run: `cargo bench -p swarf-ui --bench latency` (add `-- --quick` for fewer repetitions).
//! Prints Markdown tables for docs/performance.md. Memory figures are read from `/proc/self/status`
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

/// One egui frame of the workbench at 1280 × 800 with these input events.
fn frame(ctx: &egui::Context, wb: &mut Workbench, events: Vec<egui::Event>) -> Duration {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 800.0),
        )),
        events,
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
    /// Edit to new diagnostics, per repetition.
    latency: Vec<Duration>,
    frames: usize,
    longest_frame: Duration,
    /// Parsing (the part of the edit's frame that is not spread over frames).
    parse: Duration,
    retained_per_line: Option<f64>,
}

/// Types an error at the start of a `lines`-line program and undoes it, `reps` times in all,
/// and measures each keystroke until its diagnostics are shown.
fn measure(lines: usize, reps: usize) -> Measured {
    let before = memory();
    let text = program(lines);
    let ctx = egui::Context::default();
    let mut wb = Workbench::new(text);
    // The cursor to the start; the editor takes the keyboard.
    wb.go_to_line(1);
    frame(&ctx, &mut wb, Vec::new());
    frame(&ctx, &mut wb, Vec::new());
    let retained_per_line = match (before, memory()) {
        (Some((a, _)), Some((b, _))) => Some(b.saturating_sub(a) as f64 / lines as f64),
        _ => None,
    };
    let mut latency = Vec::new();
    let mut frames = 0;
    let mut longest_frame = Duration::ZERO;
    let mut parse = Duration::ZERO;
    for rep in 0..reps {
        let event = if rep % 2 == 0 {
            egui::Event::Text("G01 X$ ".to_string())
        } else {
            egui::Event::Key {
                key: egui::Key::Z,
                physical_key: None,
                pressed: true,
                repeat: false,
                modifiers: egui::Modifiers::COMMAND,
            }
        };
        let t = Instant::now();
        // The frame of the keystroke: the editor edits the text and sends it to the analysis,
        // which runs beside the frames; then frames until its results are shown.
        let mut first = frame(&ctx, &mut wb, vec![event]);
        frames = 1;
        while wb.analysis_progress().is_some() {
            first = first.max(frame(&ctx, &mut wb, Vec::new()));
            frames += 1;
        }
        latency.push(t.elapsed());
        // The frame after, which drops the results replaced.
        first = first.max(frame(&ctx, &mut wb, Vec::new()));
        longest_frame = longest_frame.max(first);
        assert_eq!(
            wb.problems().iter().any(|p| p.code == "E-SYNTAX-CHAR"),
            rep % 2 == 0
        );
        assert_eq!(wb.text().starts_with("G01 X$ "), rep % 2 == 0);
        let t = Instant::now();
        let _ = swarf_syntax::parse(wb.text(), swarf_syntax::Dialect::Fanuc);
        parse = parse.max(t.elapsed());
    }
    Measured {
        lines,
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

/// The text buffer alone on a `lines`-line program: an insertion in the middle, and the flat
/// copy the analysis reads after it, each the median of `reps`.
fn buffer_costs(lines: usize, reps: usize) -> (Duration, Duration) {
    let mut buffer = swarf_ui::buffer::Buffer::from(program(lines));
    let middle = buffer.len_chars() / 2;
    let mut edits = Vec::new();
    let mut copies = Vec::new();
    for _ in 0..reps {
        let t = Instant::now();
        buffer.replace(middle..middle, "X");
        edits.push(t.elapsed());
        let t = Instant::now();
        assert!(buffer.as_str().len() > lines);
        copies.push(t.elapsed());
        buffer.replace(middle..middle + 1, "");
    }
    edits.sort();
    copies.sort();
    (edits[reps / 2], copies[reps / 2])
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let small = measure(10_000, if quick { 5 } else { 21 });
    let large = measure(1_000_000, if quick { 4 } else { 6 });
    println!(
        "| program | keystroke → diagnostics shown (median) | worst | frames | longest frame | whole parse (not in one frame) | resident memory per line |"
    );
    println!("|---|---|---|---|---|---|---|");
    for m in [small, large] {
        let mut sorted = m.latency.clone();
        sorted.sort();
        let median = sorted[sorted.len() / 2];
        let worst = sorted[sorted.len() - 1];
        println!(
            "| {} lines | {} | {} | {} | {} | {} | {} |",
            m.lines,
            ms(median),
            ms(worst),
            m.frames,
            ms(m.longest_frame),
            ms(m.parse),
            m.retained_per_line
                .map_or("–".to_string(), |b| format!("{b:.0} B")),
        );
    }
    let (edit, copy) = buffer_costs(1_000_000, if quick { 11 } else { 101 });
    println!();
    println!("| 1,000,000 lines | insert a character | flat copy of the text after it |");
    println!("|---|---|---|");
    println!(
        "| buffer | {:.1} µs | {} |",
        edit.as_secs_f64() * 1e6,
        ms(copy)
    );
}
