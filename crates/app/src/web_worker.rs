//! The page's analysis in a web worker (`web/worker.js` running crates/worker), or in the page's
//! frames if it fails. Requests about a large program wait for a frame that paints nothing, so on
//! two cores without a GPU the worker never makes painting late.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;

use js_sys::{Array, ArrayBuffer, Uint8Array};
use swarf_analysis::{Analyst, Inline, Job, ProgramText, Reply, Request, wire};
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

/// The script the worker runs, beside the page's own.
const WORKER_SCRIPT: &str = "./worker.js";

thread_local! {
    /// The size of the worker's wasm memory, as it last said (bytes).
    static WORKER_MEMORY: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

/// The size of the worker's wasm memory in bytes, as it last said with a reply.
pub fn memory_bytes() -> f64 {
    WORKER_MEMORY.get()
}

/// Programs of more than this many bytes hold their requests back until the page paints nothing
/// (about 30,000 lines: a run of the worker on one takes longer than a frame).
const HOLD_BYTES: usize = 1 << 20;

/// The most animation frames a held request waits through for one in which the page paints
/// nothing (while the view is orbited or played back, say).
const HOLD_FRAMES: u32 = 8;

/// The page's side of its messages to the worker: requests held back for a frame in which the
/// page paints nothing (in the order they were made), and the open files the worker keeps.
#[derive(Default)]
struct Held {
    requests: Vec<Request>,
    /// The app's frame count at the last look, and how many looks there have been.
    frame: u64,
    looks: u32,
    /// Whether a look is scheduled.
    scheduled: bool,
    /// Schedules the look after the next animation frame.
    on_frame: Option<js_sys::Function>,
    /// The revisions of the other open files the worker holds from the last job posted.
    files: Vec<u64>,
}

/// What the worker's events leave for the next frame.
#[derive(Default)]
struct Inbox {
    replies: VecDeque<Reply>,
    failed: bool,
}

/// The analysis in a web worker (an [`Analyst`] for [`swarf_ui::Workbench::example`]).
pub struct WorkerAnalyst {
    worker: web_sys::Worker,
    inbox: Rc<RefCell<Inbox>>,
    held: Rc<RefCell<Held>>,
    /// Whether the last program sent is large enough to hold requests back ([`HOLD_BYTES`]).
    large: bool,
    ctx: egui::Context,
    /// The worker's handlers, which live as long as it does.
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::ErrorEvent)>,
    /// At an animation frame, and after it, the look at whether the page painted ([`look`]).
    _on_frame: Closure<dyn FnMut()>,
    _after_frame: Closure<dyn FnMut()>,
    /// The last job sent: run here should the worker fail before it answers.
    last_job: Option<Job>,
    /// The level of detail last asked and not yet answered: asked here should the worker fail.
    last_lod: Option<Request>,
    /// The analysis in the frames, once the worker has failed.
    fallback: Option<Inline>,
}

impl WorkerAnalyst {
    /// Starts the worker; each reply it posts asks `ctx` for a frame.
    pub fn start(ctx: &egui::Context) -> Result<Self, JsValue> {
        let worker = web_sys::Worker::new(WORKER_SCRIPT)?;
        let inbox = Rc::new(RefCell::new(Inbox::default()));
        let on_message = {
            let (inbox, ctx) = (Rc::clone(&inbox), ctx.clone());
            Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |event: web_sys::MessageEvent| {
                if let Some(bytes) = event.data().as_f64() {
                    WORKER_MEMORY.set(bytes);
                    return;
                }
                match read_reply(&event.data()) {
                    Some(reply) => {
                        let progress = reply.is_progress();
                        ctx.request_repaint_after(swarf_ui::reply_frame(progress));
                        inbox.borrow_mut().replies.push_back(reply);
                    }
                    None => log::warn!("the analysis worker sent a message that does not read"),
                }
            })
        };
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        let on_error = {
            let (inbox, ctx) = (Rc::clone(&inbox), ctx.clone());
            Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(move |event: web_sys::ErrorEvent| {
                let why = event.message();
                log::error!("the analysis worker failed ({why}); it goes on in the page");
                inbox.borrow_mut().failed = true;
                ctx.request_repaint();
            })
        };
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        let held = Rc::new(RefCell::new(Held::default()));
        // The look runs in a task after the animation frame's (where the app paints and the
        // browser then draws), so it sees whether that frame painted.
        let after_frame = {
            let (held, inbox) = (Rc::clone(&held), Rc::clone(&inbox));
            let (worker, ctx) = (worker.clone(), ctx.clone());
            Closure::<dyn FnMut()>::new(move || look(&held, &inbox, &worker, &ctx))
        };
        let on_frame = {
            let after: js_sys::Function = after_frame.as_ref().clone().unchecked_into();
            Closure::<dyn FnMut()>::new(move || {
                if let Some(window) = web_sys::window() {
                    let _ = window.set_timeout_with_callback(&after);
                }
            })
        };
        held.borrow_mut().on_frame = Some(on_frame.as_ref().clone().unchecked_into());
        Ok(WorkerAnalyst {
            worker,
            inbox,
            held,
            large: false,
            ctx: ctx.clone(),
            _on_message: on_message,
            _on_error: on_error,
            _on_frame: on_frame,
            _after_frame: after_frame,
            last_job: None,
            last_lod: None,
            fallback: None,
        })
    }

    /// Leaves the worker for the frames, starting with the last job sent.
    fn fail(&mut self) {
        self.worker.terminate();
        self.held.borrow_mut().requests.clear();
        let mut inline = Inline::default();
        if let Some(job) = self.last_job.take() {
            // A job is answered later, from the frames.
            let _ = inline.send(Request::Analyse(Box::new(job)));
        }
        if let Some(lod) = self.last_lod.take()
            && let Some(reply) = inline.send(lod)
        {
            // Answered at once: taken with the replies that came before.
            self.inbox.borrow_mut().replies.push_back(reply);
        }
        self.fallback = Some(inline);
    }
}

impl Drop for WorkerAnalyst {
    fn drop(&mut self) {
        self.worker.terminate();
    }
}

impl Analyst for WorkerAnalyst {
    fn send(&mut self, request: Request) -> Option<Reply> {
        match &request {
            Request::Analyse(job) => {
                self.last_job = Some(job.as_ref().clone());
                self.large = job.text.len() > HOLD_BYTES;
            }
            Request::Lod { .. } => self.last_lod = Some(request.clone()),
            Request::StateAt { .. } | Request::Stock { .. } => {}
        }
        if let Some(inline) = &mut self.fallback {
            return inline.send(request);
        }
        let mut held = self.held.borrow_mut();
        if self.large || !held.requests.is_empty() {
            // A job not sent yet is replaced by a newer one.
            if matches!(request, Request::Analyse(_)) {
                held.requests.retain(|r| !matches!(r, Request::Analyse(_)));
            }
            held.requests.push(request);
            if !held.scheduled {
                held.looks = 0;
                held.frame = self.ctx.cumulative_frame_nr();
                held.scheduled = request_frame(held.on_frame.as_ref());
                if !held.scheduled {
                    // No frame to wait for: sent at once.
                    drop(held);
                    look(&self.held, &self.inbox, &self.worker, &self.ctx);
                }
            }
            return None;
        }
        drop(held);
        if let Err(error) = post(&self.worker, &request, &self.held) {
            log::error!("the analysis worker takes no message ({error:?}); it goes on in the page");
            self.fail();
        }
        None
    }

    fn try_reply(&mut self) -> Option<Reply> {
        if self.fallback.is_none() && self.inbox.borrow().failed {
            self.fail();
        }
        // Replies that came before a failure are taken first.
        let reply = self.inbox.borrow_mut().replies.pop_front();
        let reply = reply.or_else(|| self.fallback.as_mut()?.try_reply());
        if matches!(reply, Some(Reply::Lod { .. })) {
            self.last_lod = None;
        }
        reply
    }

    /// The page's main thread cannot wait: the reply that has come, if any.
    fn wait_reply(&mut self) -> Option<Reply> {
        self.try_reply()
    }
}

/// After an animation frame: sends the held requests when the app painted nothing since the
/// last look (or they have waited [`HOLD_FRAMES`]), or else looks again after the next frame.
fn look(
    held: &RefCell<Held>,
    inbox: &RefCell<Inbox>,
    worker: &web_sys::Worker,
    ctx: &egui::Context,
) {
    let frame = ctx.cumulative_frame_nr();
    let mut waiting = held.borrow_mut();
    waiting.looks += 1;
    if frame != waiting.frame
        && waiting.looks < HOLD_FRAMES
        && request_frame(waiting.on_frame.as_ref())
    {
        waiting.frame = frame;
        return;
    }
    waiting.scheduled = false;
    let requests = std::mem::take(&mut waiting.requests);
    drop(waiting);
    for request in &requests {
        if inbox.borrow().failed {
            return;
        }
        if let Err(error) = post(worker, request, held) {
            log::error!("the analysis worker takes no message ({error:?}); it goes on in the page");
            inbox.borrow_mut().failed = true;
            ctx.request_repaint();
        }
    }
}

/// Asks the browser to call `callback` at its next animation frame; whether it will.
fn request_frame(callback: Option<&js_sys::Function>) -> bool {
    let window = web_sys::window();
    window
        .zip(callback)
        .is_some_and(|(window, callback)| window.request_animation_frame(callback).is_ok())
}

/// Posts `request` to the worker, its texts as UTF-8 in buffers it takes over (the other files'
/// only where changed since the last job `held` records).
fn post(worker: &web_sys::Worker, request: &Request, held: &RefCell<Held>) -> Result<(), JsValue> {
    let (head, texts) = wire::request_parts(request, &mut held.borrow_mut().files);
    let message: Array = std::iter::once(Uint8Array::from(head.as_slice()).buffer())
        .chain(texts.into_iter().map(text_buffer))
        .collect();
    worker.post_message_with_transfer(&message, &message)
}

/// A text as UTF-8 in a new `ArrayBuffer`, its pieces copied straight into place.
fn text_buffer(text: &ProgramText) -> ArrayBuffer {
    let array = Uint8Array::new_with_length(u32::try_from(text.len()).unwrap_or(u32::MAX));
    copy_chunks(&array, &mut &[][..], &mut text.chunks().map(str::as_bytes));
    array.buffer()
}

/// Fills `array` with the next bytes of a text in pieces: what is left of the piece before
/// (`rest`), then `chunks`, whose last piece's rest is left in `rest` for the next array.
pub(crate) fn copy_chunks<'a>(
    array: &Uint8Array,
    rest: &mut &'a [u8],
    chunks: &mut impl Iterator<Item = &'a [u8]>,
) {
    let len = array.length();
    let mut at = 0u32;
    while at < len {
        if rest.is_empty() {
            let Some(chunk) = chunks.next() else { break };
            *rest = chunk;
        }
        let room = usize::try_from(len - at).unwrap_or(usize::MAX);
        let (head, tail) = rest.split_at(rest.len().min(room));
        let end = at + u32::try_from(head.len()).unwrap_or(len - at);
        array.subarray(at, end).copy_from(head);
        (*rest, at) = (tail, end);
    }
}

/// A reply of the worker (`[head, ...arrays]`), its arrays copied straight into place.
fn read_reply(data: &JsValue) -> Option<Reply> {
    let message = data.dyn_ref::<Array>()?;
    let buffers = message
        .iter()
        .map(|part| part.dyn_into::<ArrayBuffer>().ok())
        .collect::<Option<Vec<_>>>()?;
    let (head, arrays) = buffers.split_first()?;
    let head = Uint8Array::new(head).to_vec();
    let sizes: Vec<usize> = arrays.iter().map(|a| a.byte_length() as usize).collect();
    wire::reply_from(&head, &sizes, |i, bytes| {
        if let Some(array) = arrays.get(i) {
            Uint8Array::new(array).copy_to(bytes);
        }
    })
}
