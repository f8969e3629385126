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
        let Some(line) = self.tab.cursor_line else {
            ui.label(tr("Put the cursor on a block."));
            return;
        };
        // Asked of the analysis, which holds the program; the last answer stays till the next.
        let key = (self.analysis.scene.generation, line);
        if self.own_analysis
            && self.state_cache.as_ref().map(|(k, _)| *k) != Some(key)
            && self.state_asked != Some(key)
        {
            self.state_asked = Some(key);
            let generation = key.0;
            self.ask(Request::StateAt { generation, line });
        }
        let Some(((_, line), state)) = &self.state_cache else {
            return;
        };
        let Some(s) = state else {
            ui.label(trf("Line {} does not run.", &[&line]));
            return;
        };
        let mm = |v: glam::DVec3| format!("X{:.3} Y{:.3} Z{:.3}", v.x, v.y, v.z);
        // The modal codes wrap within the panel's width (first, before what scrolls).
        ui.label(tr("modes"));
        ui.add(egui::Label::new(s.codes.join(" ")).wrap());
        let tool = match s.length_offset {
            Some((h, v)) => format!("T{} H{h} ({v:+.3} mm)", s.tool),
            None => format!("T{}", s.tool),
        };
        // (name, value, whether it is a position, shown in monospace)
        let rows = [
            (tr("line"), line.to_string(), false),
            (tr("work"), mm(s.work), true),
            (tr("machine"), mm(s.machine), true),
            (s.work_offset_name.as_str(), mm(s.work_offset), true),
            (tr("tool"), tool, false),
            (tr("feed"), format!("F{}", s.feed), false),
            (tr("spindle"), format!("S{}", s.spindle_rpm), false),
            (tr("blocks run"), s.executed.to_string(), false),
        ];
        egui::Grid::new("swarf-state-grid")
            .num_columns(2)
            .show(ui, |ui| {
                for (name, value, position) in rows {
                    ui.label(name);
                    let value = egui::RichText::new(value);
                    ui.label(if position { value.monospace() } else { value });
                    ui.end_row();
                }
            });
    }

    pub(super) fn status_bar(&self, ui: &mut egui::Ui) {
        let s = self.stats();
        ui.horizontal(|ui| {
            ui.label(trf("{} blocks", &[&s.blocks]));
            ui.separator();
            ui.label(trf("{} motions", &[&s.motions]));
            ui.separator();
            if let Some((min, max)) = s.bounds {
                let [x, y, z] = (max - min).to_array().map(|v| format!("{v:.2}"));
                ui.label(trf("extent {} × {} × {} mm", &[&x, &y, &z]));
                ui.separator();
            }
            ui.label(format!("≈ {}", format_duration(s.estimated_secs)));
            ui.separator();
            let errors = self.analysis.count(Severity::Error);
            let warnings = self.analysis.count(Severity::Warning);
            let color = if errors > 0 {
                severity_color(Severity::Error)
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(color, trf("{} errors, {} warnings", &[&errors, &warnings]));
            if let Some(line) = self.tab.cursor_line {
                ui.separator();
                ui.label(trf("line {}", &[&line]));
            }
            ui.separator();
            ui.label(self.tab.document.encoding.name());
            let progress = self.pending.map(|progress| match progress {
                Progress::Reading { read, bytes } => {
                    let mb = |b: usize| format!("{:.1}", b as f64 / 1e6);
                    let text = trf("{} / {} MB read", &[&mb(read), &mb(bytes)]);
                    (read as f32 / bytes.max(1) as f32, text)
                }
                Progress::Running { reached, blocks } => {
                    let text = trf("{} / {} blocks", &[&reached, &blocks]);
                    let fraction = reached as f32 / blocks as f32;
                    (if blocks == 0 { 1.0 } else { fraction }, text)
                }
            });
            if let Some((fraction, text)) = progress {
                ui.separator();
                ui.label(tr("Analysing"));
                let bar = egui::ProgressBar::new(fraction).desired_width(180.0);
                ui.add(bar.text(text));
            }
            if let Some(message) = &self.message {
                ui.separator();
                ui.label(message);
            }
        });
    }

    /// "Reading… N %" over the empty view of a tab whose first analysis is still running.
    pub(super) fn loading_overlay(&self, ui: &mut egui::Ui, view: egui::Rect) {
        let Some(progress) = self.pending.filter(|_| !self.own_analysis) else {
            return;
        };
        let percent = |done: usize, total: usize| {
            let (done, total) = (done as u64, total.max(1) as u64);
            done.min(total) * 100 / total
        };
        let text = match progress {
            Progress::Reading { read, bytes } => trf("Reading… {} %", &[&percent(read, bytes)]),
            Progress::Running { reached, blocks } => {
                trf("Analysing… {} %", &[&percent(reached, blocks)])
            }
        };
        let at = egui::Rect::from_center_size(view.center(), egui::vec2(260.0, 40.0));
        let text = egui::RichText::new(text).heading().weak();
        ui.put(at, egui::Label::new(text));
    }

    /// The offer to read the active tab's program in the dialect its codes point to, over the
    /// problems: "This program looks like Syntec 900M (G71 on line 3)" and a Switch button.
    fn dialect_notice(&mut self, ui: &mut egui::Ui) {
        let Some(to) = self.suggested_dialect() else {
            return;
        };
        let text = match self.analysis.hint.as_ref().and_then(|h| h.first.as_ref()) {
            Some((what, line)) => trf(
                "This program looks like {} ({} on line {})",
                &[&to.label(), what, line],
            ),
            None => trf("This program looks like {}", &[&to.label()]),
        };
        let switch = ui.horizontal(|ui| {
            ui.colored_label(severity_color(Severity::Warning), text);
            let hint = trf("Read this tab's program as {}", &[&to.label()]);
            ui.button(tr("Switch")).on_hover_text(hint).clicked()
        });
        if switch.inner {
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
                // Only the rows on screen are laid out; the program's own problems come first.
                let mut clicked = None;
                for i in rows {
                    let (file, p, hover) = if let Some(p) = self.analysis.problems.get(i) {
                        (String::new(), p, tr("Go to this position").to_string())
                    } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                        let hover = trf("Go to this position in {}", &[&l.file]);
                        (format!("{}:", l.file), &l.problem, hover)
                    } else {
                        continue;
                    };
                    let text = format!(
                        "{file}{}:{}  {}[{}]  {}",
                        p.line, p.col, p.severity, p.code, p.message
                    );
                    let label = egui::RichText::new(text)
                        .monospace()
                        .color(severity_color(p.severity));
                    let row = ui.add(egui::Label::new(label).sense(egui::Sense::click()));
                    if i == 0 {
                        self.keep_rect(ui, "problem_first", &row);
                    }
                    if row.on_hover_text(hover).clicked() {
                        clicked = Some(i);
                    }
                }
                let Some(i) = clicked else { return };
                if let Some(p) = self.analysis.problems.get(i) {
                    self.select_chars(p.chars.clone());
                } else if let Some(l) = self.analysis.elsewhere.get(i - own) {
                    let (file, chars) = (l.file.clone(), l.problem.chars.clone());
                    if let Some(tab) =
                        (0..self.tabs.len()).find(|&t| self.tab_document(t).name == file)
                    {
                        self.switch_tab(tab);
                        self.select_chars(chars);
                    }
                }
            });
    }
}

/// `1 h 02 min`, `3 min 04 s` or `12.5 s`.
pub fn format_duration(secs: f64) -> String {
    let secs = secs.max(0.0);
    let (hours, minutes) = ((secs / 3600.0).floor(), ((secs % 3600.0) / 60.0).floor());
    if secs >= 3600.0 {
        format!("{hours:.0} h {minutes:02.0} min")
    } else if secs >= 60.0 {
        format!("{minutes:.0} min {:02.0} s", (secs % 60.0).floor())
    } else {
        format!("{secs:.1} s")
    }
}
