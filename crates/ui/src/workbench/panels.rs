//! The panels around the editor and the view: state at cursor, problems, status bar.

use swarf_analysis::{Progress, Request};
use swarf_syntax::Severity;

use super::Workbench;
use crate::editor::severity_color;
use crate::i18n::{tr, trf};

impl Workbench {
    /// The "state at cursor" panel.
    pub(super) fn state_view(&mut self, ui: &mut egui::Ui) {
        ui.strong(tr("State at cursor"));
        let Some(line) = self.cursor_line else {
            ui.label(tr("Put the cursor on a block."));
            return;
        };
        // Asked of the analysis, which holds the program (answered at once where it is kept
        // on this side of the thread); the last answer stays until the next one comes.
        let key = (self.analysis.scene.generation, line);
        if self.own_analysis
            && self.state_cache.as_ref().map(|(k, _)| *k) != Some(key)
            && self.state_asked != Some(key)
        {
            self.state_asked = Some(key);
            self.ask(Request::StateAt {
                generation: key.0,
                line,
            });
        }
        let Some(((_, line), state)) = &self.state_cache else {
            return;
        };
        let line = *line;
        let Some(s) = state else {
            ui.label(trf("Line {} does not run.", &[&line]));
            return;
        };
        let mm = |v: glam::DVec3| format!("X{:.3} Y{:.3} Z{:.3}", v.x, v.y, v.z);
        // The modal codes, many on some lines, wrap within the panel's width (first, before
        // anything wider than the panel that scrolls).
        ui.label(tr("modes"));
        ui.add(egui::Label::new(s.codes.join(" ")).wrap());
        egui::Grid::new("swarf-state-grid")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label(tr("line"));
                ui.label(line.to_string());
                ui.end_row();
                ui.label(tr("work"));
                ui.monospace(mm(s.work));
                ui.end_row();
                ui.label(tr("machine"));
                ui.monospace(mm(s.machine));
                ui.end_row();
                ui.label(&s.work_offset_name);
                ui.monospace(mm(s.work_offset));
                ui.end_row();
                ui.label(tr("tool"));
                ui.label(match s.length_offset {
                    Some((h, v)) => format!("T{} H{h} ({v:+.3} mm)", s.tool),
                    None => format!("T{}", s.tool),
                });
                ui.end_row();
                ui.label(tr("feed"));
                ui.label(format!("F{}", s.feed));
                ui.end_row();
                ui.label(tr("spindle"));
                ui.label(format!("S{}", s.spindle_rpm));
                ui.end_row();
                ui.label(tr("blocks run"));
                ui.label(s.executed.to_string());
                ui.end_row();
            });
    }

    /// The problems of the active tab's program and of the files it called.
    pub(super) fn problem_count(&self) -> usize {
        self.analysis.problems.len() + self.analysis.elsewhere.len()
    }

    pub(super) fn status_bar(&self, ui: &mut egui::Ui) {
        let s = self.stats();
        ui.horizontal(|ui| {
            ui.label(trf("{} blocks", &[&s.blocks]));
            ui.separator();
            ui.label(trf("{} motions", &[&s.motions]));
            ui.separator();
            if let Some((min, max)) = s.bounds {
                let size = max - min;
                ui.label(trf(
                    "extent {} × {} × {} mm",
                    &[
                        &format!("{:.2}", size.x),
                        &format!("{:.2}", size.y),
                        &format!("{:.2}", size.z),
                    ],
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
                trf("{} errors, {} warnings", &[&errors, &warnings]),
            );
            if let Some(line) = self.cursor_line {
                ui.separator();
                ui.label(trf("line {}", &[&line]));
            }
            ui.separator();
            ui.label(self.document.encoding.name());
            if let Some(Progress::Reading { read, lines }) = self.pending {
                ui.separator();
                ui.label("Analysing");
                ui.add(
                    egui::ProgressBar::new(read as f32 / lines.max(1) as f32)
                        .desired_width(180.0)
                        .text(format!("{read} / {lines} lines read")),
                );
            } else if let Some((done, total)) = self.analysis_progress() {
                ui.separator();
                ui.label(tr("Analysing"));
                let fraction = if total == 0 {
                    1.0
                } else {
                    done as f32 / total as f32
                };
                ui.add(
                    egui::ProgressBar::new(fraction)
                        .desired_width(180.0)
                        .text(trf("{} / {} blocks", &[&done, &total])),
                );
            }
            if let Some(message) = &self.message {
                ui.separator();
                ui.label(message);
            }
        });
    }

    /// "Reading… N %" over the empty view of a tab whose first analysis is still running.
    pub(super) fn loading_overlay(&self, ui: &mut egui::Ui, view: egui::Rect) {
        if self.own_analysis {
            return;
        }
        let Some(progress) = self.pending else {
            return;
        };
        let percent = |done: usize, total: usize| {
            let (done, total) = (done as u64, total.max(1) as u64);
            done.min(total) * 100 / total
        };
        let text = match progress {
            Progress::Reading { read, lines } => trf("Reading… {} %", &[&percent(read, lines)]),
            Progress::Running { reached, blocks } => {
                trf("Analysing… {} %", &[&percent(reached, blocks)])
            }
        };
        let at = egui::Rect::from_center_size(view.center(), egui::vec2(260.0, 40.0));
        ui.put(
            at,
            egui::Label::new(egui::RichText::new(text).heading().weak()),
        );
    }

    /// The offer to read the active tab's program in the dialect its codes point to, over the
    /// problems: "This program looks like Syntec 900M (G71 on line 3)" and a Switch button.
    fn dialect_notice(&mut self, ui: &mut egui::Ui) {
        let Some(to) = self.suggested_dialect() else {
            return;
        };
        let first = self.analysis.hint.as_ref().and_then(|h| h.first.clone());
        let mut switch = false;
        ui.horizontal(|ui| {
            let text = match &first {
                Some((what, line)) => trf(
                    "This program looks like {} ({} on line {})",
                    &[&to.label(), what, line],
                ),
                None => trf("This program looks like {}", &[&to.label()]),
            };
            ui.colored_label(severity_color(Severity::Warning), text);
            switch = ui
                .button(tr("Switch"))
                .on_hover_text(trf("Read this tab's program as {}", &[&to.label()]))
                .clicked();
        });
        if switch {
            self.set_tab_dialect(self.active, to);
        }
    }

    pub(super) fn problems_list(&mut self, ui: &mut egui::Ui) {
        self.dialect_notice(ui);
        let own = self.analysis.problems.len();
        let total = own + self.analysis.elsewhere.len();
        if total == 0 {
            ui.label(tr("No problems"));
            return;
        }
        ui.strong(trf("Problems ({})", &[&total]));
        let row_height = ui.text_style_height(&egui::TextStyle::Monospace);
        egui::ScrollArea::vertical()
            .id_salt("swarf-problems-scroll")
            .auto_shrink([false, false])
            .show_rows(ui, row_height, total, |ui, rows| {
                // Only the rows on screen are laid out: a program can have many thousands. The
                // program's own problems come first, then those in the other tabs it called.
                let mut jump = None;
                let mut jump_elsewhere = None;
                for i in rows {
                    let (text, severity, hover) = if let Some(p) = self.analysis.problems.get(i) {
                        (
                            format!(
                                "{}:{}  {}[{}]  {}",
                                p.line, p.col, p.severity, p.code, p.message
                            ),
                            p.severity,
                            tr("Go to this position").to_string(),
                        )
                    } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                        let p = &l.problem;
                        (
                            format!(
                                "{}:{}:{}  {}[{}]  {}",
                                l.file, p.line, p.col, p.severity, p.code, p.message
                            ),
                            p.severity,
                            trf("Go to this position in {}", &[&l.file]),
                        )
                    } else {
                        continue;
                    };
                    let label = egui::RichText::new(text)
                        .monospace()
                        .color(severity_color(severity));
                    let row = ui.add(egui::Label::new(label).sense(egui::Sense::click()));
                    if i == 0 {
                        self.widgets
                            .insert("problem_first".into(), row.rect.intersect(ui.clip_rect()));
                    }
                    if row.on_hover_text(hover).clicked() {
                        if let Some(p) = self.analysis.problems.get(i) {
                            jump = Some(p.chars.clone());
                        } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                            jump_elsewhere = Some((l.file.clone(), l.problem.chars.clone()));
                        }
                    }
                }
                if let Some(chars) = jump {
                    self.select_chars(chars);
                }
                if let Some((file, chars)) = jump_elsewhere
                    && let Some(i) =
                        (0..self.tabs.len()).find(|&i| self.tab_document(i).name == file)
                {
                    self.switch_tab(i);
                    self.select_chars(chars);
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
