//! The whole editing surface: editor, problems list and backplot, wired to the pipeline.

use swarf_interp::Setup;
use swarf_syntax::{Dialect, Severity};

use crate::analysis::{Analysis, Problem, Stats};
use crate::backplot::Backplot;
use crate::editor::{CodeEditor, severity_color};

/// The example program the editor starts with.
pub const EXAMPLE_PROGRAM: &str = include_str!("../../../assets/examples/pocket.nc");

/// Editor, problems and backplot over one program text; re-analyses on every edit.
pub struct Workbench {
    text: String,
    dialect: Dialect,
    setup: Setup,
    generation: u64,
    analysis: Analysis,
    editor: CodeEditor,
    backplot: Backplot,
    cursor_line: Option<u32>,
    /// The cursor line last sent to the backplot as its selection.
    synced_line: Option<u32>,
    /// The state shown for ((generation, line)), recomputed only when either changes.
    state_cache: Option<((u64, u32), Option<swarf_interp::BlockState>)>,
}

impl Default for Workbench {
    fn default() -> Self {
        Workbench::new(EXAMPLE_PROGRAM.to_string())
    }
}

impl Workbench {
    /// A workbench showing `text`, read as Fanuc with a default setup.
    pub fn new(text: String) -> Self {
        let setup = Setup::default();
        let dialect = Dialect::default();
        let analysis = Analysis::run(&text, dialect, &setup, 1);
        Workbench {
            text,
            dialect,
            setup,
            generation: 1,
            analysis,
            editor: CodeEditor::default(),
            backplot: Backplot::new(),
            cursor_line: None,
            synced_line: None,
            state_cache: None,
        }
    }

    /// The program text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Replaces the text and re-analyses it.
    pub fn set_text(&mut self, text: impl Into<String>) {
        self.text = text.into();
        self.reanalyse();
        self.backplot.fit();
    }

    /// The dialect programs are read as.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Changes the dialect and re-analyses.
    pub fn set_dialect(&mut self, dialect: Dialect) {
        if dialect != self.dialect {
            self.dialect = dialect;
            self.reanalyse();
        }
    }

    /// The latest analysis.
    pub fn analysis(&self) -> &Analysis {
        &self.analysis
    }

    /// Diagnostics of the current text, sorted by position.
    pub fn problems(&self) -> &[Problem] {
        &self.analysis.problems
    }

    /// Summary numbers of the current text.
    pub fn stats(&self) -> Stats {
        self.analysis.stats()
    }

    fn reanalyse(&mut self) {
        self.generation += 1;
        self.analysis = Analysis::run(&self.text, self.dialect, &self.setup, self.generation);
    }

    /// Shows the workbench filling `ui`.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        egui::Panel::top("swarf-top").show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("swarf-status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::bottom("swarf-problems")
            .resizable(true)
            .default_size(140.0)
            .show(ui, |ui| self.problems_list(ui));
        egui::Panel::right("swarf-state")
            .resizable(true)
            .default_size(200.0)
            .show(ui, |ui| self.state_view(ui));
        egui::Panel::left("swarf-editor")
            .resizable(true)
            .default_size(460.0)
            .show(ui, |ui| {
                let title = ui.strong("Program");
                let out = self.editor.show(
                    ui,
                    title.id,
                    &mut self.text,
                    self.dialect,
                    &self.analysis.problems,
                );
                if out.changed {
                    self.reanalyse();
                }
                if out.cursor_line.is_some() {
                    self.cursor_line = out.cursor_line;
                }
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                // The editor's block is highlighted in the backplot (set only when the cursor
                // moves, so a click in the backplot is not undone) …
                if self.cursor_line != self.synced_line {
                    self.backplot.set_selected_line(self.cursor_line);
                    self.synced_line = self.cursor_line;
                }
                egui::Panel::bottom("swarf-playback").show(ui, |ui| {
                    self.backplot.playback_bar(ui, &self.analysis.scene)
                });
                self.backplot.show(ui, &self.analysis.scene);
                // … a click on a segment moves the editor to its block, and so does playback
                // (the backplot highlights the block itself).
                let played = self.backplot.take_playback_line();
                if let Some(line) = self.backplot.take_picked_line().or(played) {
                    self.jump_to_line(line);
                }
            });
    }

    /// The machine state just before the block on 1-based `line` first runs (modal codes,
    /// position, offsets, tool, feed, speed); `None` when no block there runs.
    pub fn state_at_line(&self, line: u32) -> Option<swarf_interp::BlockState> {
        let program = &self.analysis.program;
        let row = line.checked_sub(1)?;
        let block = program.blocks.iter().position(|b| b.line == row)?;
        self.analysis.states.at(program, block)
    }

    /// The "state at cursor" panel.
    fn state_view(&mut self, ui: &mut egui::Ui) {
        ui.strong("State at cursor");
        let Some(line) = self.cursor_line else {
            ui.label("Put the cursor on a block.");
            return;
        };
        let key = (self.generation, line);
        if self.state_cache.as_ref().map(|(k, _)| *k) != Some(key) {
            self.state_cache = Some((key, self.state_at_line(line)));
        }
        let Some((_, state)) = &self.state_cache else {
            return;
        };
        let Some(s) = state else {
            ui.label(format!("Line {line} does not run."));
            return;
        };
        let mm = |v: glam::DVec3| format!("X{:.3} Y{:.3} Z{:.3}", v.x, v.y, v.z);
        egui::Grid::new("swarf-state-grid")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label("line");
                ui.label(line.to_string());
                ui.end_row();
                ui.label("modes");
                ui.label(s.codes.join(" "));
                ui.end_row();
                ui.label("work");
                ui.monospace(mm(s.work));
                ui.end_row();
                ui.label("machine");
                ui.monospace(mm(s.machine));
                ui.end_row();
                ui.label(&s.work_offset_name);
                ui.monospace(mm(s.work_offset));
                ui.end_row();
                ui.label("tool");
                ui.label(match s.length_offset {
                    Some((h, v)) => format!("T{} H{h} ({v:+.3} mm)", s.tool),
                    None => format!("T{}", s.tool),
                });
                ui.end_row();
                ui.label("feed");
                ui.label(format!("F{}", s.feed));
                ui.end_row();
                ui.label("spindle");
                ui.label(format!("S{}", s.spindle_rpm));
                ui.end_row();
                ui.label("blocks run");
                ui.label(s.executed.to_string());
                ui.end_row();
            });
    }

    /// The backplot (camera, selection, playback).
    pub fn backplot(&self) -> &Backplot {
        &self.backplot
    }

    /// The 1-based line of the editor's cursor, as last reported or moved there.
    pub fn cursor_line(&self) -> Option<u32> {
        self.cursor_line
    }

    /// Puts the editor's cursor at the start of 1-based `line`.
    fn jump_to_line(&mut self, line: u32) {
        let lines = &self.analysis.program.lines;
        let start = lines.line_start(line.saturating_sub(1) as usize) as usize;
        let start = start.min(self.text.len());
        let chars = self.text.get(..start).map_or(0, |t| t.chars().count());
        self.editor.jump_to(chars..chars);
        self.cursor_line = Some(line);
        self.synced_line = Some(line);
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.strong("Swarf");
            ui.separator();
            let label = ui.label("Dialect");
            let mut dialect = self.dialect;
            egui::ComboBox::from_id_salt("swarf-dialect")
                .selected_text(dialect.label())
                .show_ui(ui, |ui| {
                    for d in Dialect::ALL {
                        ui.selectable_value(&mut dialect, d, d.label());
                    }
                })
                .response
                .labelled_by(label.id);
            self.set_dialect(dialect);
            ui.separator();
            if ui.button("Fit view").clicked() {
                self.backplot.fit();
            }
        });
    }

    fn status_bar(&self, ui: &mut egui::Ui) {
        let s = self.stats();
        ui.horizontal(|ui| {
            ui.label(format!("{} blocks", s.blocks));
            ui.separator();
            ui.label(format!("{} motions", s.motions));
            ui.separator();
            if let Some((min, max)) = s.bounds {
                let size = max - min;
                ui.label(format!(
                    "extent {:.2} × {:.2} × {:.2} mm",
                    size.x, size.y, size.z
                ));
                ui.separator();
            }
            ui.label(format!("≈ {}", format_duration(s.estimated_secs)));
            ui.separator();
            let errors = self.analysis.count(Severity::Error);
            let warnings = self.analysis.count(Severity::Warning);
            ui.colored_label(
                if errors > 0 {
                    severity_color(Severity::Error)
                } else {
                    ui.visuals().text_color()
                },
                format!("{errors} errors, {warnings} warnings"),
            );
            if let Some(line) = self.cursor_line {
                ui.separator();
                ui.label(format!("line {line}"));
            }
        });
    }

    fn problems_list(&mut self, ui: &mut egui::Ui) {
        ui.strong(format!("Problems ({})", self.analysis.problems.len()));
        egui::ScrollArea::vertical()
            .id_salt("swarf-problems-scroll")
            .auto_shrink([false, false])
            .show(ui, |ui| {
                let mut jump = None;
                for p in &self.analysis.problems {
                    let text = format!(
                        "{}:{}  {}[{}]  {}",
                        p.line, p.col, p.severity, p.code, p.message
                    );
                    let label = egui::RichText::new(text)
                        .monospace()
                        .color(severity_color(p.severity));
                    if ui
                        .add(egui::Label::new(label).sense(egui::Sense::click()))
                        .on_hover_text("Go to this position")
                        .clicked()
                    {
                        jump = Some(p.chars.clone());
                    }
                }
                if let Some(chars) = jump {
                    self.editor.jump_to(chars);
                }
            });
    }
}

/// `1 h 02 min`, `3 min 04 s` or `12.5 s`.
pub fn format_duration(secs: f64) -> String {
    let secs = secs.max(0.0);
    if secs >= 3600.0 {
        format!(
            "{:.0} h {:02.0} min",
            (secs / 3600.0).floor(),
            ((secs % 3600.0) / 60.0).floor()
        )
    } else if secs >= 60.0 {
        format!(
            "{:.0} min {:02.0} s",
            (secs / 60.0).floor(),
            (secs % 60.0).floor()
        )
    } else {
        format!("{secs:.1} s")
    }
}
