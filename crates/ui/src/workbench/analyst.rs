//! The round trip to the analysis: sending each change, taking its replies, asking the state.

use std::sync::{Arc, OnceLock};

use swarf_analysis::{Analyst, Job, OpenFile, ProgramText, Progress, Reply, Request};
use swarf_syntax::Dialect;

use super::Workbench;
use crate::analysis::{Analysis, Problem, Stats};

/// How soon after a reply of the analysis the frame that shows it comes: an answer at once,
/// `progress` twice a second. Without a GPU a frame of the whole window takes a core for tens
/// of milliseconds, taken from the analysis on a machine of two cores.
pub fn reply_frame(progress: bool) -> std::time::Duration {
    std::time::Duration::from_millis(if progress { 500 } else { 2 })
}

impl Workbench {
    /// Has `analyst` (the web page's worker) run the analysis from now on, from the current text.
    pub fn set_analyst(&mut self, analyst: Box<dyn Analyst>) {
        self.analyst = analyst;
        self.sent.clear();
        self.state_asked = None;
        self.reanalyse();
    }

    /// The dialect offered for the active tab's program: one whose codes, by the code tables,
    /// leave strictly fewer errors than its own dialect (see the notice over the problems).
    pub fn suggested_dialect(&self) -> Option<Dialect> {
        let hint = self.analysis.hint.as_ref();
        let hint = hint.filter(|h| h.from == self.tab.dialect && self.own_analysis);
        hint.map(|h| h.to)
    }

    /// Whether the analysis shown is the active tab's own; false while the first analysis of
    /// a tab just opened is still running (an empty view, problems and counts are shown).
    pub fn analysis_ready(&self) -> bool {
        self.own_analysis
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
        self.analysis.stats
    }

    /// Points of the path the backplot draws at the level of detail the analysis last sent
    /// (`None` before one came).
    pub fn drawn_points(&self) -> Option<usize> {
        let lod = self.analysis.scene.lod.as_ref();
        lod.filter(|_| self.analysis.scene.lod_from_analysis)
            .map(|l| l.kept.len())
    }

    /// Sends the current text to the analysis (replacing an unfinished run there).
    pub(super) fn reanalyse(&mut self) {
        self.generation += 1;
        // The texts are shared, not copied: a keystroke costs no copy of them.
        let active = self.active;
        let others = self.tabs.iter().enumerate().filter(|(i, _)| *i != active);
        let others = others.map(|(_, t)| OpenFile {
            name: t.document.name.clone(),
            revision: t.document.revision,
            text: t.text.program_text(),
        });
        let text = self.tab.text.program_text();
        self.ask(Request::Analyse(Box::new(Job {
            generation: self.generation,
            text: text.clone(),
            dialect: self.tab.dialect,
            setup: self.setup.clone(),
            others: Some(others.collect()),
            lod: self.backplot.lod_for_job(&self.analysis.scene),
        })));
        self.sent.push_back((self.generation, text));
        self.pending = Some(Progress::Reading { read: 0, bytes: 0 });
    }

    /// Sends a request to the analysis, taking an answer given at once.
    pub(super) fn ask(&mut self, request: Request) {
        if let Some(reply) = self.analyst.send(request) {
            self.receive(reply);
        }
    }

    /// Takes the replies the analysis has sent since the last look; whether any came.
    pub fn take_replies(&mut self) -> bool {
        let mut any = false;
        while let Some(reply) = self.analyst.try_reply() {
            self.receive(reply);
            any = true;
        }
        any
    }

    /// Takes one reply: progress, a finished analysis (shown unless a newer one is), a state.
    fn receive(&mut self, reply: Reply) {
        match reply {
            Reply::Progress {
                generation,
                progress,
            } => {
                if generation == self.generation && self.pending.is_some() {
                    self.pending = Some(progress);
                }
            }
            Reply::Done(results) => {
                let generation = results.generation;
                // The jobs sent before this one were replaced.
                while self.sent.pop_front_if(|(g, _)| *g < generation).is_some() {}
                let sent = self.sent.pop_front_if(|(g, _)| *g == generation);
                let newer = !self.own_analysis || generation > self.analysis.scene.generation;
                if let Some((_, text)) = sent
                    && generation >= self.floor
                    && newer
                {
                    self.analysis = Analysis::of(*results, &text);
                    // The analysis simplifies the path for the view, beside the frames.
                    self.analysis.scene.lod_from_analysis = true;
                    self.own_analysis = true;
                    if generation == self.generation {
                        self.pending = None;
                    }
                }
            }
            Reply::State {
                generation,
                line,
                state,
            } => {
                // `None`: that analysis is no longer held; the next one shown is asked again.
                if let Some(state) = state
                    && self.state_asked == Some((generation, line))
                {
                    self.state_cache = Some(((generation, line), state));
                    self.state_asked = None;
                }
            }
            Reply::Stock(cut) => self.analysis.take_stock(*cut),
            Reply::Lod {
                generation,
                level,
                kept,
            } => {
                let scene = &mut self.analysis.scene;
                if generation == scene.generation && scene.lod_from_analysis {
                    // An analysis no longer held leaves it to this side, once.
                    let lod = match kept {
                        Some(kept) => swarf_analysis::Lod { level, kept },
                        None => swarf_analysis::Lod::of(&scene.points, level),
                    };
                    scene.lod = Some(lod);
                }
            }
        }
    }

    /// Progress of the current text's analysis while it runs, as (different blocks run, blocks
    /// in the program); (0, 0) while the text is read.
    pub fn analysis_progress(&self) -> Option<(usize, usize)> {
        self.pending.map(|p| match p {
            Progress::Running { reached, blocks } => (reached, blocks),
            Progress::Reading { .. } => (0, 0),
        })
    }

    /// Whether the backplot's picture is not complete on screen yet (it waits for the
    /// analysis to simplify the path for its view, or draws it over several frames).
    pub fn drawing_pending(&self) -> bool {
        self.backplot.drawing_pending(&self.analysis.scene)
    }

    /// Waits for the analysis of the current text and shows it (a web page cannot wait).
    pub fn finish_analysis(&mut self) {
        self.take_replies();
        while self.pending.is_some() {
            match self.analyst.wait_reply() {
                Some(reply) => self.receive(reply),
                None => return,
            }
        }
    }

    /// A number bumped by every change of the text, dialect or setup (see the scene's).
    pub fn generation(&self) -> u64 {
        self.generation
    }
}

/// What a tab shows before its first analysis is done: no path, no problems, no counts.
pub(super) fn no_analysis() -> Analysis {
    let empty = ProgramText::from(String::new());
    Analysis::of(swarf_analysis::Results::default(), &empty)
}

/// The analysis beside the UI: a thread repainting `waker`'s context, else the frames themselves.
pub(super) fn default_analyst(waker: &Arc<OnceLock<egui::Context>>) -> Box<dyn Analyst> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let waker = Arc::clone(waker);
        let wake = move |progress| {
            if let Some(ctx) = waker.get() {
                ctx.request_repaint_after(reply_frame(progress));
            }
        };
        if let Ok(thread) = swarf_analysis::Thread::spawn(wake) {
            return Box::new(thread);
        }
    }
    let _ = waker;
    Box::new(swarf_analysis::Inline::default())
}
