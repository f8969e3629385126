//! Reading and running a long program on two threads (`stats`): a helper thread reads and
//! parses the file a piece at a time while this thread runs the pieces read before.
//!
//! Starting the helper and handing it its job are kept short: this thread keeps to its
//! processor from before the helper is spawned and, until the helper has moved to another one
//! (a new thread starts on its starter's processor, where it would otherwise wait for this
//! thread to sleep), reads the first pieces itself, giving way after each; the helper watches
//! for its job rather than sleeping. Every wait between the two threads watches likewise
//! before it sleeps (see `waits.rs`).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{
    Receiver, Sender, SyncSender, TryRecvError, TrySendError, channel, sync_channel,
};
use std::sync::{Arc, Mutex, PoisonError};

use swarf_interp::{Interpreter, Setup};
use swarf_syntax::{Block, Dialect, ExprNode, ParseRun, Program};
use swarf_toolpath::{Timer, Timings, Toolpath};

use crate::growing::{Feeder, Growing, Unread};
use crate::{FIRST_PIECE_LINES, PIECE_LINES, run_piece};
use crate::{apart, waits};

/// How far ahead of the parse the reader reads the file while it waits for the runner (two
/// chunks): the reads are then not in the parse's way, and the window of the text
/// (`growing.rs`) has room for them.
const IDLE_AHEAD_BYTES: usize = 128 << 10;

/// The reading thread's stack: 1 MiB, far more than the parse needs (its expressions nest 64
/// deep at most) and less than a transparent huge page, so that its first write (the thread's
/// own data sits at the top of its stack) has the system zero one 4 KB page, not 2 MB.
const HELPER_STACK_BYTES: usize = 1 << 20;

/// How many block arrays the reader makes (each a piece long, 256 KB) before it reuses the
/// ones the runner gives back, oldest first: enough that an array has left the runner's
/// processor cache (2 MB of second-level cache a core here) before the reader writes it again.
/// An array the runner has just read is still in that cache, and each of its cache lines the
/// reader then writes first has the other processor's copy invalidated, a wait of the order of
/// a cache miss: with the few arrays that used to go round, the reader's parse took 60–70 %
/// longer than on one thread (`stellabee1.ngc` 8.1 ms against 4.9 ms).
const POOL_ARRAYS: usize = 8;

/// How many pieces read may wait for the runner. With two, each thread often waited for the
/// other in turn (the reader with its queue full and no moves to time, the runner with no piece
/// and the moves being timed by the reader): their speeds vary from piece to piece (a run of
/// arcs is slow to run, a run of short lines slow to read), and a longer queue takes up the
/// difference. Paired runs, two → four: `stellabee1.ngc` 0.977, 0.966 and 0.960, `tiger.nc`
/// 0.969, `la_peinture.gc` 0.981; six was slower than four (1.004, 1.019, 1.010) and three the
/// same. Four in the queue, one being run and one being read leave two of the
/// [`POOL_ARRAYS`] to go round.
const QUEUED_PIECES: usize = 4;

/// A piece as it is handed over: its blocks, the expressions new in it, and the places of the
/// blocks that own memory (see `swarf_syntax::empty_blocks_known`).
type Piece = (Vec<Block>, Vec<ExprNode>, Vec<u32>);

/// What [`run_pieces_beside`] gives besides the interpreter: the reader and the number of
/// blocks read (`None` when the program needs running whole) and the text as read (see
/// [`Growing::into_text`]), or why the file gave no text.
pub(crate) type Beside = Result<(Option<(ParseRun, usize)>, Growing), Unread>;

/// What the reading hands back: the reader and the text as read, or why the file gave no text.
type Read = Result<(ParseRun, Growing), Unread>;

/// The time model, its queue of moves, and the way back for the batches it has taken in:
/// whoever holds it times them.
struct Timing {
    timer: Timer,
    queued: Receiver<Timings>,
    spent: SyncSender<Timings>,
}

impl Timing {
    fn take(&mut self, moves: Timings) {
        self.timer.take(&moves);
        // A full way back (the runner has spares enough, or is done) drops the batch.
        let _ = self.spent.try_send(moves);
    }
}

/// Times the moves of the next piece queued, unless the other thread is timing; whether it
/// did (the caller then looks for its own work again before timing more).
fn time_next(timing: &Mutex<Timing>) -> bool {
    let Ok(mut held) = timing.try_lock() else {
        return false;
    };
    match held.queued.try_recv() {
        Ok(moves) => {
            held.take(moves);
            true
        }
        Err(_) => false,
    }
}

/// What the two threads share: the time model, whether the reader is to stop (the program
/// needs running whole), and how many pieces the runner has taken from the reader (the
/// reader, knowing how many it has sent, sees whether one is waiting for the runner).
struct Shared {
    timing: Mutex<Timing>,
    stop: AtomicBool,
    taken: AtomicUsize,
}

/// The reading of the file: the parse, the text read so far, and how far it has got.
struct Reading {
    reader: ParseRun,
    source: Growing,
    /// Lines in the next piece.
    lines: usize,
    /// How many expressions went with the pieces before.
    sent_exprs: usize,
}

impl Reading {
    fn new(source: Growing, dialect: Dialect) -> Self {
        // Its lines are indexed only where there is something to report (see `stream`).
        let mut reader = ParseRun::growing_unindexed(dialect);
        // Each array is of a whole piece's size, not one that grows.
        let _ = reader.swap_blocks(Vec::with_capacity(PIECE_LINES));
        Reading {
            reader,
            source,
            // The first pieces are short, so that the runner starts soon.
            lines: FIRST_PIECE_LINES,
            sent_exprs: 0,
        }
    }

    /// Reads the next piece, the reading going on into `array` (a spare block array):
    /// the piece and whether it is the last. A file is read a chunk ahead of the parse; one
    /// not plain UTF-8 stops the run.
    fn next_piece(&mut self, array: Vec<Block>) -> Result<(Piece, bool), Unread> {
        self.source.read_ahead(self.reader.offset())?;
        let done = self.reader.step_growing(
            self.source.bytes(),
            self.source.base,
            self.source.is_complete(),
            self.lines,
        );
        self.lines = (self.lines * 4).min(PIECE_LINES);
        let owning = self.reader.take_owning();
        let blocks = self.reader.swap_blocks(array);
        let exprs = &self.reader.program().exprs;
        let new_exprs = exprs.get(self.sent_exprs..).unwrap_or_default().to_vec();
        self.sent_exprs = exprs.len();
        Ok(((blocks, new_exprs, owning), done))
    }

    /// Reads one more chunk of the file while the text is less than [`IDLE_AHEAD_BYTES`] ahead
    /// of the parse; whether it read one.
    fn read_on(&mut self) -> Result<bool, Unread> {
        let until = self.reader.offset().saturating_add(IDLE_AHEAD_BYTES);
        self.source.read_on(until)
    }

    /// The reader and the text. `complete` once every piece is read: the file is then read to
    /// its end (a program that ends at a closing tape mark may end before its file does) and
    /// the reader takes in the rest of the text; not when the run stopped part-way (the
    /// program is then read again whole).
    fn finish(mut self, complete: bool) -> Read {
        if complete {
            self.source.read_to_end()?;
            self.reader.complete(self.source.bytes(), self.source.base);
        }
        Ok((self.reader, self.source))
    }
}

/// The reading thread's ends of the channels, and what it shares with the runner.
struct ReaderEnds {
    shared: Arc<Shared>,
    pieces: SyncSender<Piece>,
    spare: Receiver<Vec<Block>>,
    bell: Receiver<()>,
}

/// The reading thread's job: reads the pieces from `reading` on and hands them over; then,
/// and while it is ahead of the runner, times the moves of the pieces run. The block arrays
/// `made_before` (while the thread waited for the job) are used first.
fn read_pieces(mut reading: Reading, ends: ReaderEnds, mut made_before: Vec<Vec<Block>>) -> Read {
    let ReaderEnds {
        shared,
        pieces,
        spare,
        bell,
    } = ends;
    let Shared {
        timing,
        stop,
        taken,
    } = &*shared;
    // The first page of the end times, which the time model writes on either thread, is
    // mapped here: this thread starts with time to spare (the runner has the pieces it read
    // first to run), the runner with its own arrays' pages to map.
    if let Ok(mut held) = timing.try_lock() {
        held.timer.prefault();
    }
    let mut sent_pieces = 0;
    // The reading's first array is made with it.
    let mut made = 1;
    loop {
        // Each array is of a whole piece's size, not one that grows; the pool is made first,
        // then the arrays the runner has given back go round.
        let array = if made < POOL_ARRAYS {
            made += 1;
            made_before
                .pop()
                .unwrap_or_else(|| Vec::with_capacity(PIECE_LINES))
        } else {
            spare
                .try_recv()
                .unwrap_or_else(|_| Vec::with_capacity(PIECE_LINES))
        };
        let (mut piece, done) = reading.next_piece(array)?;
        let sent = loop {
            if stop.load(Ordering::Relaxed) {
                break false;
            }
            match pieces.try_send(piece) {
                Ok(()) => break true,
                Err(TrySendError::Disconnected(_)) => break false,
                Err(TrySendError::Full(back)) => piece = back,
            }
            // Ahead of the runner: time its moves while waiting, if there are any, else read
            // on in the file (a chunk at a time, up to a huge page ahead, so that the memory
            // the text goes to is mapped while waiting), else wait for the runner to take a
            // piece or queue moves.
            if !time_next(timing) && !reading.read_on()? && waits::recv(&bell).is_err() {
                break pieces.send(piece).is_ok();
            }
        };
        if !sent {
            return reading.finish(false);
        }
        sent_pieces += 1;
        if done {
            break;
        }
        // While the runner has a piece in hand, time its moves first: the timing keeps up
        // with the run, rather than piling up for the end while the runner waits.
        while sent_pieces > taken.load(Ordering::Relaxed) && time_next(timing) {}
    }
    drop(pieces);
    // Every piece is read: time the moves of those still running, until the last.
    let mut held = timing.lock().unwrap_or_else(PoisonError::into_inner);
    while let Ok(more) = waits::recv(&held.queued) {
        held.take(more);
    }
    drop(held);
    reading.finish(true)
}

/// [`crate::run_pieces`] with the reading on the `helper` thread: it hands each piece's blocks
/// (and the expressions new in it) over a short queue while this thread runs the piece before,
/// and gets the block arrays back for reuse. A file `source` is read there too, a chunk ahead of the parse.
/// Returns the interpreter this thread made, with what [`crate::run_pieces`] returns and the
/// whole text, or why the file gave no text.
///
/// Until the helper has moved to a processor of its own (a few tenths of a millisecond after
/// its start here), this thread reads the first pieces itself, giving way after each so that
/// the helper can move; it then hands the reading over and runs the pieces it read first.
///
/// The toolpath's measures and time model (about a quarter of a plain program's work) run on
/// whichever thread would otherwise wait: this thread queues the moves of each piece it has
/// run, and they are measured and timed, in order and a piece's moves at a time, by the
/// reader while this thread has a piece in hand or the queue of pieces is full and once it has
/// read the last, or by this thread while it waits for a piece.
pub(crate) fn run_pieces_beside(
    mut source: Growing,
    again: Option<std::fs::File>,
    dialect: Dialect,
    setup: &Setup,
    toolpath: &mut Toolpath,
    helper: Helper,
) -> (Interpreter, Beside) {
    // The runner reads chunks of the file ahead for the reader while it waits for a piece.
    let mut feeder: Option<Feeder> = again.map(|file| {
        let (feed, feeder) = crate::growing::feed(file, source.len);
        source.fed_by(feed);
        feeder
    });
    let mut reading = Reading::new(source, dialect);
    let first = read_first_pieces(&mut reading, &helper);
    let (first, done) = match first {
        Ok(first) => first,
        Err(unread) => {
            helper.dismiss();
            return (Interpreter::new(setup.clone(), dialect), Err(unread));
        }
    };
    let (moves, queued) = channel::<Timings>();
    let (spent, spent_batches) = sync_channel::<Timings>(4);
    let shared = Arc::new(Shared {
        timing: Mutex::new(Timing {
            timer: toolpath.detach_timer(),
            queued,
            spent,
        }),
        stop: AtomicBool::new(false),
        taken: AtomicUsize::new(0),
    });
    let (pieces, received) = sync_channel::<Piece>(QUEUED_PIECES);
    // Room for the whole pool: no array given back is dropped.
    let (spares, spare) = sync_channel::<Vec<Block>>(POOL_ARRAYS);
    // Rung by the runner when it takes a piece or queues moves: a reader whose queue is full
    // and who has no moves to time waits for it, not for a free place only, so that moves
    // queued meanwhile are timed as they come rather than all after the last piece.
    let (ring, bell) = sync_channel::<()>(1);
    let ends = ReaderEnds {
        shared: Arc::clone(&shared),
        pieces,
        spare,
        bell,
    };
    // The reading goes on on the helper while this thread makes its interpreter and runs the
    // pieces read first; the lines are indexed as they are read, by the reader. A program
    // read to its end already needs no helper: the rest of its reading is done here.
    let reader = if done {
        helper.dismiss();
        drop(ends);
        Reader::Here(reading)
    } else {
        Reader::Beside(helper.run(move |arrays| read_pieces(reading, ends, arrays)))
    };
    let Shared {
        timing,
        stop,
        taken,
    } = &*shared;
    let mut runner = Interpreter::new(setup.clone(), dialect);
    // While the reader reads on, the memory that the moves go to is mapped here: the pieces
    // then run without waiting for it (the reader maps the end times', see `read_pieces`).
    toolpath.prefault();
    // The program as the interpreter sees it: this piece's blocks, every expression so far.
    let mut piece = Program {
        dialect,
        ..Program::default()
    };
    let mut first = first.into_iter();
    let mut blocks = 0;
    let mut ended = false;
    let mut whole = false;
    loop {
        let next = first.next().or_else(|| {
            let next = loop {
                match received.try_recv() {
                    Ok(next) => break Some(next),
                    Err(TryRecvError::Disconnected) => break None,
                    // Ahead of the reader: read a chunk of the file ahead for it, else time the
                    // moves while waiting, if there are any.
                    Err(TryRecvError::Empty) if time_next(timing) => {}
                    Err(TryRecvError::Empty) if feeder.as_mut().is_some_and(Feeder::read_one) => {}
                    Err(TryRecvError::Empty) => break waits::recv(&received).ok(),
                }
            };
            if next.is_some() {
                taken.fetch_add(1, Ordering::Relaxed);
                // A rung bell not yet heard is enough.
                let _ = ring.try_send(());
            }
            next
        });
        let Some((read, exprs, owning)) = next else {
            break;
        };
        piece.blocks = read;
        piece.exprs.extend(exprs);
        blocks += piece.blocks.len();
        if !run_piece(&mut runner, &piece, toolpath, &mut ended) {
            whole = true;
            stop.store(true, Ordering::Relaxed);
            break;
        }
        // Only a reader gone (it panicked, reported at the join) drops them.
        let spare = spent_batches.try_recv().unwrap_or_default();
        let _ = moves.send(toolpath.swap_timings(spare));
        let _ = ring.try_send(());
        // Emptied here, where the blocks were just read, not by the reader (which has more to
        // do); a full queue (the reader is done) just drops the array.
        swarf_syntax::empty_blocks_known(&mut piece.blocks, &owning);
        let _ = spares.try_send(std::mem::take(&mut piece.blocks));
    }
    drop(received);
    drop(moves);
    drop(ring);
    let read = match reader {
        // Every piece was read here.
        Reader::Here(reading) => reading.finish(true),
        Reader::Beside(running) => match running.join() {
            Ok(Some(read)) => read,
            Ok(None) => std::panic::resume_unwind(Box::new(
                "the reading thread ended before it was given the text",
            )),
            Err(panic) => std::panic::resume_unwind(panic),
        },
    };
    let ran = read.map(|(reader, text)| ((!whole).then_some((reader, blocks)), text));
    // The reader is done: the time model takes in the moves still queued and goes back to the
    // path (which gives its stand-in for it).
    let mut held = timing.lock().unwrap_or_else(PoisonError::into_inner);
    while let Ok(moves) = held.queued.try_recv() {
        held.take(moves);
    }
    let timer = std::mem::replace(&mut held.timer, toolpath.detach_timer());
    drop(held);
    toolpath.attach_timer(timer);
    (runner, ran)
}

/// Where the reading of a run on two threads goes on: on the helper, or here where this thread
/// read the whole program before the helper had moved.
enum Reader {
    /// The helper at its job.
    Beside(Running),
    /// The reading, every piece read.
    Here(Reading),
}

/// Reads pieces on this thread, giving way after each, until the helper has moved to its own
/// processor or [`waits::WATCH`] has passed: the pieces and whether the last was the end.
fn read_first_pieces(reading: &mut Reading, helper: &Helper) -> Result<(Vec<Piece>, bool), Unread> {
    let start = std::time::Instant::now();
    let mut first = Vec::new();
    while !helper.moved() && start.elapsed() < waits::WATCH {
        let (piece, done) = reading.next_piece(Vec::with_capacity(PIECE_LINES))?;
        first.push(piece);
        if done {
            return Ok((first, true));
        }
        std::thread::yield_now();
    }
    Ok((first, false))
}

/// The thread that reads a long program's pieces ([`run_pieces_beside`]): started first, so
/// that the file's text is handed only to a thread that could be started, then given its job
/// (or the job runs on a new thread where it is gone).
///
/// The calling thread, which runs the pieces, is kept on the processor it is on and the helper
/// off it until [`Running::join`] ([`apart`]).
pub(crate) struct Helper {
    jobs: Sender<Job>,
    thread: std::thread::JoinHandle<()>,
    apart: apart::Apart,
    /// Set by the thread once it has moved off this thread's processor.
    moved: Arc<AtomicBool>,
}

/// A job for the [`Helper`], given the block arrays the helper made while it waited for it
/// (see [`made_while_waiting`]): it hands its result back itself.
type Job = Box<dyn FnOnce(Vec<Vec<Block>>) + Send>;

/// Waits for the helper's job, making the reader's block arrays meanwhile (each a piece long,
/// its memory touched, up to the pool less the reading's own array): the 2 MB page or two they
/// take is zeroed by the system while the helper has nothing else to do, rather than while it
/// parses the first pieces into them. The job comes as soon as the running thread has seen the
/// helper move; it is looked for between one array and the next.
fn made_while_waiting(job: &Receiver<Job>) -> Option<(Job, Vec<Vec<Block>>)> {
    let mut arrays = Vec::with_capacity(POOL_ARRAYS);
    loop {
        match job.try_recv() {
            Ok(job) => return Some((job, arrays)),
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) if arrays.len() + 1 < POOL_ARRAYS => {
                let mut array: Vec<Block> = Vec::with_capacity(PIECE_LINES);
                // A block every 4 KB: every page of the array is touched, whatever its size.
                for slot in array.spare_capacity_mut().iter_mut().step_by(32) {
                    slot.write(Block::default());
                }
                arrays.push(array);
            }
            Err(TryRecvError::Empty) => return waits::recv(job).ok().map(|job| (job, arrays)),
        }
    }
}

impl Helper {
    /// Starts the thread, which moves to a processor of its own and waits there for its job;
    /// `None` where no thread can be started.
    pub(crate) fn start() -> Option<Helper> {
        let (jobs, job) = channel::<Job>();
        let apart = apart::Apart::new();
        // Kept where it is before the new thread starts, so that the new thread (which takes
        // this one's processors) can only start beside it and then move off.
        apart.stay();
        let away = apart.away();
        let moved = Arc::new(AtomicBool::new(false));
        let gone = Arc::clone(&moved);
        let spawned = std::thread::Builder::new()
            .stack_size(HELPER_STACK_BYTES)
            .spawn(move || {
                away.go();
                gone.store(true, Ordering::Release);
                if let Some((job, arrays)) = made_while_waiting(&job) {
                    job(arrays);
                }
            });
        let Ok(thread) = spawned else {
            apart.release();
            return None;
        };
        // The new thread starts on this thread's processor, the only one it may run on until it
        // moves: this thread gives way to it while it reads the first pieces.
        Some(Helper {
            jobs,
            thread,
            apart,
            moved,
        })
    }

    /// Whether the thread has moved to a processor of its own (and watches for its job).
    fn moved(&self) -> bool {
        self.moved.load(Ordering::Acquire)
    }

    /// Lets the thread go without a job (it ends on its own) and this thread run on any
    /// processor again.
    fn dismiss(self) {
        self.apart.release();
    }

    /// Runs `job` on the thread (on a new one were it gone), with the block arrays made there.
    fn run(self, job: impl FnOnce(Vec<Vec<Block>>) -> Read + Send + 'static) -> Running {
        let (result, results) = sync_channel::<Read>(1);
        let job: Job = Box::new(move |arrays| {
            // Only a runner gone (it panicked) would not take it.
            let _ = result.send(job(arrays));
        });
        let thread = match self.jobs.send(job) {
            Ok(()) => self.thread,
            Err(std::sync::mpsc::SendError(job)) => std::thread::spawn(|| job(Vec::new())),
        };
        Running {
            thread,
            apart: self.apart,
            results,
        }
    }
}

/// The [`Helper`] at its job.
struct Running {
    thread: std::thread::JoinHandle<()>,
    apart: apart::Apart,
    /// Where the job hands its result back.
    results: Receiver<Read>,
}

impl Running {
    /// Lets the calling thread run on any processor again and waits for the job's result: as
    /// soon as the job hands it back, not until its thread has ended (which unmaps the
    /// thread's signal stack, 0.1–0.3 ms later here); the thread is left to end on its own.
    /// A job that panicked gives its panic; `None` where the thread ended without its job.
    fn join(self) -> std::thread::Result<Option<Read>> {
        self.apart.release();
        // The reader is timing the last moves.
        match waits::recv(&self.results) {
            Ok(read) => Ok(Some(read)),
            Err(_) => self.thread.join().map(|()| None),
        }
    }
}
