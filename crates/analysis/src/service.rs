//! The analysis as a service beside the UI: the UI sends [`Request`]s and takes [`Reply`]s as
//! they come, from a thread ([`Thread`]), a web worker (the page's host) or, where neither
//! exists, in its own frames ([`Inline`]). All of them run the same [`Service`].

use std::sync::{Arc, Mutex};

use swarf_interp::BlockState;

use crate::run::{Job, Kept, PendingAnalysis, Progress, Results};
use crate::stock::{StockCut, StockJob};

/// Blocks' worth of work (see [`PendingAnalysis::step`]) between two looks at the requests: a
/// few milliseconds, so that a newer edit replaces a running analysis at once.
pub const PIECE: usize = 20_000;

/// What the UI asks of the analysis.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub enum Request {
    /// The machine state before the block on 1-based `line` of the program analysed in
    /// `generation`.
    StateAt {
        /// The analysis asked about.
        generation: u64,
        /// 1-based line.
        line: u32,
    },
    /// The stock cut by the toolpath of the analysis of `generation`, up to segment `upto`
    /// (the whole toolpath, or playback's position): answered by [`Reply::Stock`]s, its
    /// progress and then the cut. A later `upto` continues the cut; a new job stops it.
    Stock {
        /// The analysis whose toolpath is cut.
        generation: u64,
        /// Segments to cut.
        upto: usize,
    },
    /// The points the backplot draws of the analysis of `generation` at a zoom's level of
    /// detail (see [`swarf_render::simplify_at`]): simplified here, beside the frames.
    Lod {
        /// The analysis whose path is drawn.
        generation: u64,
        /// The level.
        level: crate::LodLevel,
    },
    /// Analyse a program, dropping any unfinished analysis. Sent apart (see [`crate::wire`]),
    /// and last: serde numbers the variants it reads without it.
    #[serde(skip)]
    Analyse(Box<Job>),
}

/// What the analysis answers.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Reply {
    /// How far the analysis of `generation` has got.
    Progress {
        /// The analysis.
        generation: u64,
        /// How far it has got.
        progress: Progress,
    },
    /// A finished analysis.
    Done(Box<Results>),
    /// The answer to [`Request::StateAt`]: `None` when that analysis is no longer held (a
    /// newer one finished), `Some(None)` when no block on the line runs.
    State {
        /// The analysis asked about.
        generation: u64,
        /// 1-based line.
        line: u32,
        /// The state.
        state: Option<Option<BlockState>>,
    },
    /// The stock asked for by [`Request::Stock`]: its progress (no heights yet), then the cut.
    Stock(Box<StockCut>),
    /// The answer to [`Request::Lod`].
    Lod {
        /// The analysis asked about.
        generation: u64,
        /// The level asked for.
        level: crate::LodLevel,
        /// The indices of the points kept, ascending; `None` when that analysis is no longer
        /// held (the asker simplifies its own copy). Sent beside the head (see
        /// [`crate::wire`]).
        #[serde(skip)]
        kept: Option<Arc<Vec<u32>>>,
    },
}

impl Reply {
    /// Whether it only tells how far work has got (the UI need not show it at once).
    pub fn is_progress(&self) -> bool {
        match self {
            Reply::Progress { .. } => true,
            Reply::Stock(cut) => !cut.finished(),
            Reply::Done(_) | Reply::State { .. } | Reply::Lod { .. } => false,
        }
    }
}

/// What the last finished analysis keeps, shared with whoever answers questions about it.
pub type Held = Arc<Mutex<Option<Kept>>>;

/// `f` of what `held` keeps of the analysis of `generation`, while it is held.
pub(crate) fn with_kept<T>(held: &Held, generation: u64, f: impl FnOnce(&Kept) -> T) -> Option<T> {
    let kept = held.lock().ok()?;
    kept.as_ref().filter(|k| k.generation == generation).map(f)
}

/// The answer to [`Request::StateAt`] from what `held` keeps.
fn state_of(held: &Held, generation: u64, line: u32) -> Reply {
    let state = with_kept(held, generation, |k| k.state_at(line));
    Reply::State {
        generation,
        line,
        state,
    }
}

/// The analysis side's state: the analysis under way, what the last finished one keeps, and
/// the stock cut from it.
#[derive(Debug, Default)]
pub struct Service {
    pending: Option<PendingAnalysis>,
    held: Held,
    stock: Option<StockJob>,
}

impl Service {
    /// Takes a request: a job replaces the analysis under way (answered later, by
    /// [`step`](Service::step)); a question is answered now.
    pub fn handle(&mut self, request: Request) -> Option<Reply> {
        match request {
            Request::Analyse(job) => {
                self.pending = Some(PendingAnalysis::start(*job));
                self.stock = None;
                None
            }
            Request::Stock { generation, upto } => {
                if (self.stock.as_mut()).is_some_and(|job| job.extend(generation, upto)) {
                    return None;
                }
                let started = StockJob::start(&self.held, generation, upto);
                let error = started.as_ref().err().cloned();
                self.stock = started.ok();
                let mut cut = StockCut::default();
                (cut.generation, cut.upto, cut.done, cut.error) =
                    (generation, upto, upto, Some(error?));
                Some(Reply::Stock(Box::new(cut)))
            }
            Request::StateAt { generation, line } => Some(state_of(&self.held, generation, line)),
            Request::Lod { generation, level } => {
                // Simplified outside the lock, which a thread's caller takes for a state.
                let points = with_kept(&self.held, generation, |k| Arc::clone(&k.points));
                let kept = points.map(|p| crate::Lod::of(&p, level).kept);
                Some(Reply::Lod {
                    generation,
                    level,
                    kept,
                })
            }
        }
    }

    /// Whether an analysis or a cut of the stock is under way.
    pub fn is_busy(&self) -> bool {
        self.pending.is_some() || self.stock.as_ref().is_some_and(|job| job.due)
    }

    /// Runs a [`PIECE`] of the analysis under way: its progress, or its results once it is
    /// finished (then it answers questions until the next one finishes); else a piece of the
    /// stock's cut; `None` when idle.
    pub fn step(&mut self) -> Option<Reply> {
        let Some(pending) = self.pending.as_mut() else {
            let job = self.stock.as_mut().filter(|job| job.due)?;
            return Some(Reply::Stock(Box::new(job.step(&self.held))));
        };
        if !pending.step(PIECE) {
            return Some(Reply::Progress {
                generation: pending.generation(),
                progress: pending.progress(),
            });
        }
        let pending = self.pending.take()?;
        // The program kept before is freed first (two long ones need not be held at once), and
        // outside the lock.
        let old = self.held.lock().ok().and_then(|mut held| held.take());
        drop(old);
        let (results, kept) = pending.finish();
        if let Ok(mut held) = self.held.lock() {
            *held = Some(kept);
        }
        Some(Reply::Done(Box::new(results)))
    }
}

/// Where the UI sends its requests and takes the replies (a thread, a worker, or its own
/// frames).
pub trait Analyst {
    /// Sends a request; an answer given at once comes back (a question about the finished
    /// analysis, where it is held on the caller's side of the thread).
    fn send(&mut self, request: Request) -> Option<Reply>;
    /// The next reply, if one has come.
    fn try_reply(&mut self) -> Option<Reply>;
    /// Waits for the next reply; `None` when none will come or this host cannot wait (a web
    /// page's main thread).
    fn wait_reply(&mut self) -> Option<Reply>;
}

/// The analysis run in the caller's own time: a job (or a cut of the stock) runs whole when
/// its reply is first asked for (for a host with neither threads nor a worker).
#[derive(Debug, Default)]
pub struct Inline {
    service: Service,
}

impl Analyst for Inline {
    fn send(&mut self, request: Request) -> Option<Reply> {
        self.service.handle(request)
    }

    fn try_reply(&mut self) -> Option<Reply> {
        std::iter::from_fn(|| self.service.step()).find(|reply| !reply.is_progress())
    }

    fn wait_reply(&mut self) -> Option<Reply> {
        self.try_reply()
    }
}

/// The analysis on its own thread: a newer job replaces one under way between pieces, questions
/// are answered from what it keeps, and a waker is called with every reply. Ends when dropped.
#[cfg(not(target_arch = "wasm32"))]
#[derive(Debug)]
pub struct Thread {
    requests: std::sync::mpsc::Sender<Request>,
    replies: std::sync::mpsc::Receiver<Reply>,
    held: Held,
}

#[cfg(not(target_arch = "wasm32"))]
impl Thread {
    /// Starts the thread; `wake` is called after each reply is sent, with whether it was only
    /// progress.
    pub fn spawn(wake: impl Fn(bool) + Send + 'static) -> std::io::Result<Self> {
        let (requests, requests_in) = std::sync::mpsc::channel();
        let (replies_out, replies) = std::sync::mpsc::channel();
        let service = Service::default();
        let held = Arc::clone(&service.held);
        std::thread::Builder::new()
            .name("swarf-analysis".into())
            .spawn(move || serve(service, &requests_in, &replies_out, &wake))?;
        Ok(Thread {
            requests,
            replies,
            held,
        })
    }
}

/// The thread's loop: every request that has come, then a piece of the analysis under way (or a
/// wait for the next request when there is none).
#[cfg(not(target_arch = "wasm32"))]
fn serve(
    mut service: Service,
    requests: &std::sync::mpsc::Receiver<Request>,
    replies: &std::sync::mpsc::Sender<Reply>,
    wake: &dyn Fn(bool),
) {
    use std::sync::mpsc::TryRecvError;
    loop {
        let request = if service.is_busy() {
            match requests.try_recv() {
                Err(TryRecvError::Disconnected) => return,
                request => request.ok(),
            }
        } else {
            let Ok(request) = requests.recv() else {
                return;
            };
            Some(request)
        };
        let reply = match request {
            Some(request) => service.handle(request),
            None => service.step(),
        };
        if let Some(reply) = reply {
            let progress = reply.is_progress();
            if replies.send(reply).is_err() {
                return;
            }
            wake(progress);
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl Analyst for Thread {
    fn send(&mut self, request: Request) -> Option<Reply> {
        if let Request::StateAt { generation, line } = request {
            return Some(state_of(&self.held, generation, line));
        }
        // A thread that ended (it never panics) leaves nothing to send to.
        let _ = self.requests.send(request);
        None
    }

    fn try_reply(&mut self) -> Option<Reply> {
        self.replies.try_recv().ok()
    }

    fn wait_reply(&mut self) -> Option<Reply> {
        self.replies.recv().ok()
    }
}
