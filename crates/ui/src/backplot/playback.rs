//! Playback of a scene, at a chosen speed or a block at a time, and its bar under the backplot.
//! A block is a run of consecutive segments of one source line (a block a loop runs twice is
//! stepped twice; one that moves nothing is no stop of its own).

use std::sync::Arc;

use glam::Vec3;
use swarf_render::PathPoint;

use super::Scene;
use crate::format_duration;
use crate::i18n::{tr, trf};

/// The playback speeds offered, as multiples of real time.
pub const PLAYBACK_SPEEDS: [f64; 7] = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0];

/// Room left beside the two sliders for their labels, in points.
const SLIDER_LABELS_POINTS: f32 = 100.0;

/// Two times closer than this (seconds) are the same position.
const SAME_TIME: f64 = 1e-9;

/// Where playback is and how it runs.
#[derive(Clone, Debug)]
pub struct Playback {
    /// Seconds from the program start; `None` while playback is off.
    time: Option<f64>,
    /// The block last stepped or slid to, at that time: blocks that take no time share an
    /// end time with their neighbour, and this keeps stepping through them one by one.
    pinned: Option<(f64, usize)>,
    playing: bool,
    speed: f64,
    /// First segment of each block, for the scene generation it was built for.
    blocks: Option<(u64, Arc<Vec<usize>>)>,
    /// The scene generation last seen (an edit pauses playback).
    generation: Option<u64>,
    /// The current block's source line as last reported.
    line: Option<u32>,
    /// A line reached by playback and not yet taken by [`Self::take_line`].
    moved_line: Option<u32>,
}

/// A playback button: enabled, its label, its hover text and what a click does.
type Button<'a> = (bool, &'a str, &'a str, fn(&mut Playback, &Scene));

impl Default for Playback {
    /// Playback off, at real-time speed.
    fn default() -> Self {
        Self {
            time: None,
            pinned: None,
            playing: false,
            speed: 1.0,
            blocks: None,
            generation: None,
            line: None,
            moved_line: None,
        }
    }
}

impl Playback {
    /// Seconds from the program start, `None` while playback is off.
    pub fn time(&self) -> Option<f64> {
        self.time
    }

    /// Speed as a multiple of real time.
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// Sets the speed (a positive multiple of real time; anything else is ignored).
    pub fn set_speed(&mut self, speed: f64) {
        if speed.is_finite() && speed > 0.0 {
            self.speed = speed;
        }
    }

    /// Plays from the current position, or from the start when off or at the end.
    pub fn play(&mut self, scene: &Scene) {
        self.sync(scene);
        let total = scene.total_secs();
        if self.time.is_none_or(|t| t >= total - SAME_TIME) {
            self.set_time(0.0);
        }
        self.playing = true;
    }

    /// Stops playing, keeping the position.
    pub fn pause(&mut self) {
        self.playing = false;
    }

    /// Turns playback off: the whole path is drawn as executed again.
    pub fn stop(&mut self) {
        (self.time, self.pinned, self.line, self.moved_line) = (None, None, None, None);
        self.playing = false;
    }

    /// Moves to `t` seconds from the start (clamped to the program).
    pub fn seek(&mut self, scene: &Scene, t: f64) {
        self.sync(scene);
        let t = if t.is_finite() { t } else { 0.0 };
        self.set_time(t.clamp(0.0, scene.total_secs()));
        self.report(scene);
    }

    /// Moves to the end of block `block` (0-based, clamped), as if it had just run.
    pub fn seek_block(&mut self, scene: &Scene, block: usize) {
        self.sync(scene);
        let blocks = self.blocks(scene);
        let Some(last) = blocks.len().checked_sub(1) else {
            return;
        };
        let block = block.min(last);
        let t = block_end(scene, &blocks, block);
        self.set_time(t);
        self.pinned = Some((t, block));
        self.report(scene);
    }

    /// Pauses and moves to the end of the next block (the end of the current one when it is
    /// under way; the first block when playback was off).
    pub fn step_forward(&mut self, scene: &Scene) {
        self.sync(scene);
        self.playing = false;
        let blocks = self.blocks(scene);
        let (Some(t), Some(block)) = (self.time, self.current_block(scene)) else {
            self.seek_block(scene, 0);
            return;
        };
        let done = t >= block_end(scene, &blocks, block) - SAME_TIME;
        self.seek_block(scene, block + usize::from(done));
    }

    /// Pauses and moves to the end of the previous block (the start of the program from the
    /// first block; the end of the last block but one when playback was off).
    pub fn step_back(&mut self, scene: &Scene) {
        self.sync(scene);
        self.playing = false;
        let count = self.blocks(scene).len();
        let target = match self.time {
            None => count.checked_sub(2),
            Some(_) => self.current_block(scene).and_then(|b| b.checked_sub(1)),
        };
        match target {
            Some(block) => self.seek_block(scene, block),
            None => self.seek(scene, 0.0),
        }
    }

    /// Advances by `dt` seconds of real time while playing (stopping at the end).
    pub fn advance(&mut self, scene: &Scene, dt: f64) {
        self.sync(scene);
        if !self.playing {
            return;
        }
        let total = scene.total_secs();
        let dt = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        let t = self.time.unwrap_or(0.0) + dt * self.speed;
        self.playing = t < total;
        self.set_time(t.min(total));
        self.report(scene);
    }

    /// Number of blocks of `scene` that move the tool.
    pub fn block_count(&mut self, scene: &Scene) -> usize {
        scene
            .block_count
            .unwrap_or_else(|| self.blocks(scene).len())
    }

    /// The segment under way (or just finished), `None` while off.
    pub fn current_segment(&self, scene: &Scene) -> Option<usize> {
        let t = self.time?;
        match (self.pinned, &self.blocks) {
            (Some((at, block)), Some((generation, blocks)))
                if at == t && *generation == scene.generation =>
            {
                last_segment(scene, blocks, block)
            }
            _ => scene.segment_at(t),
        }
    }

    /// The block under way (or just finished), 0-based, `None` while off.
    pub fn current_block(&mut self, scene: &Scene) -> Option<usize> {
        let segment = self.current_segment(scene)?;
        let begun = self
            .blocks(scene)
            .partition_point(|&start| start <= segment);
        begun.checked_sub(1)
    }

    /// The source line of the block under way, `None` while off.
    pub fn current_line(&self, scene: &Scene) -> Option<u32> {
        scene.lines.get(self.current_segment(scene)?).copied()
    }

    /// How many segments are drawn as executed, `None` while off (everything is).
    pub fn executed(&self, scene: &Scene) -> Option<usize> {
        let t = self.time?;
        let finished = scene.finished_at(t);
        // A block stepped to counts as run even when it takes no time.
        Some(match self.current_segment(scene) {
            Some(segment) if self.pinned.is_some() => finished.max(segment + 1),
            _ => finished,
        })
    }

    /// Where the tool is, in the scene's frame, `None` while off.
    pub fn position(&self, scene: &Scene) -> Option<Vec3> {
        let t = self.time?;
        if let Some(segment) = self.current_segment(scene)
            && self.pinned.is_some()
        {
            return scene.points.get(segment + 1).map(PathPoint::position);
        }
        scene.position_at(t)
    }

    /// The source line playback moved to since the last call (the editor follows it).
    pub fn take_line(&mut self) -> Option<u32> {
        self.moved_line.take()
    }

    /// The bar of controls (buttons, speed, sliders), which advances the position while playing.
    pub fn ui(&mut self, ui: &mut egui::Ui, scene: &Scene) {
        self.sync(scene);
        if self.playing {
            let dt = f64::from(ui.input(|i| i.stable_dt));
            self.advance(scene, dt);
            ui.ctx().request_repaint();
        }
        let total = scene.total_secs();
        let count = self.block_count(scene);
        let has_path = count > 0;
        ui.horizontal(|ui| {
            let play = "Play the program from here (from the start at its end)";
            let (label, hint) = match self.playing {
                true => ("Pause", "Pause playback"),
                false => ("Play", play),
            };
            let (back, forward) = (tr("Step one block back"), tr("Step one block forward"));
            let stop_hint = tr("Stop playback and draw the whole program");
            let buttons: [Button<'_>; 4] = [
                (has_path, tr(label), tr(hint), |p, scene| {
                    if p.playing { p.pause() } else { p.play(scene) }
                }),
                (has_path, tr("« Block"), back, Self::step_back),
                (has_path, tr("Block »"), forward, Self::step_forward),
                (self.time.is_some(), tr("Stop"), stop_hint, |p, _| p.stop()),
            ];
            for (enabled, label, hint, run) in buttons {
                let button = ui.add_enabled(enabled, egui::Button::new(label));
                if button.on_hover_text(hint).clicked() {
                    run(self, scene);
                }
            }
            let speed_label = ui.label(tr("Speed"));
            let mut speed = self.speed;
            egui::ComboBox::from_id_salt("swarf-playback-speed")
                .selected_text(format!("×{speed}"))
                .width(56.0)
                .show_ui(ui, |ui| {
                    for s in PLAYBACK_SPEEDS {
                        ui.selectable_value(&mut speed, s, format!("×{s}"));
                    }
                })
                .response
                .labelled_by(speed_label.id);
            self.set_speed(speed);
            ui.separator();
            let now = format_duration(self.time.unwrap_or(total));
            ui.label(format!("{now} / {}", format_duration(total)));
            ui.separator();
            let current = self.current_block(scene).map_or(count, |b| b + 1);
            let line = self.current_line(scene);
            let line = line.map_or(String::new(), |l| trf(", line {}", &[&l]));
            ui.label(trf("block {} of {}{}", &[&current, &count, &line]));
        });
        ui.horizontal(|ui| {
            // The two sliders share the row.
            ui.spacing_mut().slider_width =
                ((ui.available_width() - SLIDER_LABELS_POINTS) / 2.0).max(40.0);
            let time_label = ui.label(tr("Time"));
            let mut t = self.time.unwrap_or(total);
            let slider = egui::Slider::new(&mut t, 0.0..=total.max(SAME_TIME)).show_value(false);
            let slider = ui.add_enabled(has_path, slider).labelled_by(time_label.id);
            if slider.changed() {
                self.seek(scene, t);
            }
            ui.separator();
            let block_label = ui.label(tr("Block"));
            let current = self.current_block(scene).map_or(count, |b| b + 1);
            let mut block = current;
            let slider = egui::Slider::new(&mut block, 1..=count.max(1)).show_value(false);
            let slider = ui.add_enabled(has_path, slider).labelled_by(block_label.id);
            if slider.changed() && block != current {
                self.seek_block(scene, block.saturating_sub(1));
            }
        });
    }

    /// Notices a new scene: the position is kept within it, and an edit pauses playback.
    fn sync(&mut self, scene: &Scene) {
        if self.generation == Some(scene.generation) {
            return;
        }
        self.playing &= self.generation.is_none();
        self.generation = Some(scene.generation);
        self.pinned = None;
        self.time = self.time.map(|t| t.min(scene.total_secs()));
    }

    fn set_time(&mut self, t: f64) {
        self.time = Some(t);
        self.pinned = None;
    }

    /// Queues the current line for [`Self::take_line`] when it changed.
    fn report(&mut self, scene: &Scene) {
        let line = self.current_line(scene);
        if line.is_some() && line != self.line {
            self.moved_line = line;
        }
        self.line = line;
    }

    /// The first segment of each block (cached per scene generation).
    fn blocks(&mut self, scene: &Scene) -> Arc<Vec<usize>> {
        if let Some((generation, blocks)) = &self.blocks
            && *generation == scene.generation
        {
            return Arc::clone(blocks);
        }
        let lines = &scene.lines[..scene.lines.len().min(scene.segment_count())];
        let blocks = Arc::new(swarf_analysis::block_starts(lines).collect::<Vec<_>>());
        self.blocks = Some((scene.generation, Arc::clone(&blocks)));
        blocks
    }
}

/// The last segment of block `block`, given the first segment of each block.
fn last_segment(scene: &Scene, blocks: &[usize], block: usize) -> Option<usize> {
    let next = blocks.get(block + 1).copied();
    next.unwrap_or(scene.segment_count()).checked_sub(1)
}

/// When block `block` ends: the end of its last segment.
fn block_end(scene: &Scene, blocks: &[usize], block: usize) -> f64 {
    last_segment(scene, blocks, block)
        .and_then(|last| scene.segment_span(last))
        .map_or(0.0, |(_, end)| end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_render::{Kind, PathPoint};

    /// Five segments on lines 1, 2, 2, 3, 4 (one second each: no timeline).
    fn scene() -> Scene {
        let points = (0..6)
            .map(|i| PathPoint::new(Vec3::new(i as f32, 0.0, 0.0), Kind::Feed))
            .collect();
        Scene {
            generation: 1,
            points: Arc::new(points),
            lines: Arc::new(vec![1, 2, 2, 3, 4]),
            ..Scene::default()
        }
    }

    #[test]
    fn steps_through_blocks_and_back() {
        let scene = scene();
        let mut p = Playback::default();
        assert_eq!(p.block_count(&scene), 4);
        assert_eq!(p.executed(&scene), None);
        p.step_forward(&scene);
        assert_eq!(p.current_block(&scene), Some(0));
        assert_eq!(p.take_line(), Some(1));
        p.step_forward(&scene);
        assert_eq!((p.time(), p.current_line(&scene)), (Some(3.0), Some(2)));
        assert_eq!(p.executed(&scene), Some(3));
        assert_eq!(p.take_line(), Some(2));
        assert_eq!(p.take_line(), None);
        p.step_back(&scene);
        assert_eq!(p.current_line(&scene), Some(1));
        p.step_back(&scene);
        assert_eq!((p.time(), p.current_block(&scene)), (Some(0.0), Some(0)));
        // Half-way through line 2's second segment, stepping forward finishes the block.
        p.seek(&scene, 2.5);
        assert_eq!(p.current_line(&scene), Some(2));
        assert_eq!(p.position(&scene), Some(Vec3::new(2.5, 0.0, 0.0)));
        p.step_forward(&scene);
        assert_eq!(p.time(), Some(3.0));
        // Off, stepping back lands on the last block but one.
        p.stop();
        p.step_back(&scene);
        assert_eq!(p.current_line(&scene), Some(3));
    }

    #[test]
    fn the_analysis_block_count_is_shown_without_a_pass_over_the_lines() {
        let scene = Scene {
            block_count: Some(4),
            ..scene()
        };
        let mut p = Playback::default();
        assert_eq!(p.block_count(&scene), 4);
        assert!(
            p.blocks.is_none(),
            "the block starts were listed to count them"
        );
        p.step_forward(&scene);
        assert_eq!(p.current_block(&scene), Some(0));
    }

    #[test]
    fn the_analysis_counts_the_blocks_playback_steps_through() {
        let program = swarf_syntax::parse(
            "G0 X0 Y0 Z5.\nG1 Z0 F100\nG2 X10. I5.\nG1 Y10.\nY10.\nG81 X20. R2. Z-5.\nX30.\nG80\n",
            swarf_syntax::Dialect::Fanuc,
        );
        let mut path = swarf_toolpath::Toolpath::default();
        swarf_interp::run(&program, swarf_interp::Setup::default(), &mut path);
        let scene = crate::analysis::scene_of(&path, &swarf_interp::Setup::default(), 1);
        let counted = Playback::default().blocks(&Scene {
            block_count: None,
            ..scene.clone()
        });
        assert_eq!(scene.block_count, Some(counted.len()));
        assert!(counted.len() >= 6, "{counted:?}");
    }

    #[test]
    fn plays_at_speed_and_stops_at_the_end() {
        let scene = scene();
        let mut p = Playback::default();
        p.set_speed(2.0);
        p.play(&scene);
        p.advance(&scene, 0.75);
        assert_eq!(p.time(), Some(1.5));
        assert_eq!(p.current_line(&scene), Some(2));
        assert_eq!(p.executed(&scene), Some(1));
        p.advance(&scene, 10.0);
        assert_eq!(p.time(), Some(5.0));
        assert!(!p.playing);
        // Play at the end starts over; an edit (new generation) pauses.
        p.play(&scene);
        assert_eq!(p.time(), Some(0.0));
        let edited = Scene {
            generation: 2,
            ..scene
        };
        p.advance(&edited, 1.0);
        assert!(!p.playing);
        assert_eq!(p.time(), Some(0.0));
    }
}
