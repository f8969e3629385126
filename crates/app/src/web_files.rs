//! Files on the web page: File System Access pickers where the browser has them (Save writes back
//! to the opened file), else `<input type=file>` and downloads; drops; recovery in IndexedDB.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

use swarf_analysis::ProgramText;
use swarf_ui::{HostRequest, Workbench};

use crate::files::{
    self, Autosave, AutosaveClock, INDEX_KEY, RecoveryBook, RecoveryIndex, Round, TabState,
};

/// The IndexedDB database of the recovery records (made at version 1, with its store).
const DB_NAME: &str = "swarf-recovery";
/// Its object store: the index under [`INDEX_KEY`], each tab's text (UTF-8) under its key.
const STORE: &str = "records";
/// Where the page's CJK font is, relative to the page (`cargo xtask web` puts it there). It is
/// fetched only when a Chinese language is chosen; the service worker keeps it once fetched.
pub const CJK_FONT_URL: &str = "./fonts/wqy-microhei.ttc";
/// Element id of the hidden file input.
const PICKER_ID: &str = "swarf-file-picker";

/// What the browser finished while the app waited: a file read, a save done or refused.
enum Arrival {
    /// The CJK font fetched, or why it was not.
    Font(Result<Vec<u8>, String>),
    /// A program file read, with its handle when it came from the File System Access API.
    File(String, Vec<u8>, Option<Handle>),
    /// A setup file read.
    Setup(String, Vec<u8>),
    /// A program `name` picked that is the file kept under the key (its tab's path).
    Reopened(String, Vec<u8>, String),
    /// The file `name` written (its handle to keep, if new) for the (tab, generation) then.
    Saved(String, Option<Handle>, (usize, u64)),
    /// The save picker refused to open: download `name` instead, for the (tab, generation).
    Download(String, Vec<u8>, (usize, u64)),
    /// Something to tell the user.
    Message(String),
    /// The recovery records read at the start (`None`: no index), or why they could not be.
    Recovered(Result<Option<StoredTabs>, String>),
    /// A round of recovery writes ended, and whether its index is stored (or was already).
    Autosaved(Box<Round>, bool),
}

/// A file's handle in the File System Access API.
type Handle = web_sys::FileSystemFileHandle;

/// The recovery index as stored and read, and the texts of the records it names, by key.
type StoredTabs = (String, RecoveryIndex, HashMap<String, String>);

/// The recovery database.
type Db = web_sys::IdbDatabase;

/// The recovery database once opened.
type DbSlot = Rc<RefCell<Option<Db>>>;

/// What the browser finished, waiting for the next frame, and the context to wake for it.
#[derive(Clone, Default)]
struct Inbox {
    arrivals: Rc<RefCell<Vec<Arrival>>>,
    wake: Rc<RefCell<Option<egui::Context>>>,
}

impl Inbox {
    /// Keeps `arrival` for [`Host::poll`] and asks for a frame.
    fn send(&self, arrival: Arrival) {
        self.arrivals.borrow_mut().push(arrival);
        if let Some(ctx) = self.wake.borrow().as_ref() {
            ctx.request_repaint();
        }
    }

    /// Runs `task` in the browser; what it ends with arrives through [`Host::poll`].
    fn spawn<A: Into<Option<Arrival>>>(&self, task: impl Future<Output = A> + 'static) {
        let inbox = self.clone();
        wasm_bindgen_futures::spawn_local(async move {
            if let Some(arrival) = task.await.into() {
                inbox.send(arrival);
            }
        });
    }
}

/// Web file state: files read asynchronously, the files' handles, the autosave bookkeeping.
#[derive(Default)]
pub struct Host {
    /// Recent files (none on the web: the page cannot reopen a file by name).
    pub recent: Vec<String>,
    inbox: Inbox,
    clock: AutosaveClock,
    /// File handles by the key kept as their tab's document path.
    handles: HashMap<String, Handle>,
    /// Which recovery records are written, and which tabs are not kept.
    book: RecoveryBook,
    /// Whether the recovery records are being read (at the start) or written.
    busy: bool,
    /// The recovery database once opened.
    db: DbSlot,
    /// Whether the records are to be brought up to date once `busy` ends (a save came).
    again: bool,
}

impl Host {
    /// A web host.
    pub fn new() -> Host {
        Host {
            book: RecoveryBook::new(&format!("{:x}", js_sys::Date::now() as u64)),
            ..Host::default()
        }
    }

    /// Starts reading the tabs this browser kept with unsaved changes; they replace the
    /// workbench's when they are in (see [`Host::poll`]), and nothing is written until then.
    pub fn recover(&mut self, _wb: &mut Workbench) {
        self.busy = true;
        let db = self.db.clone();
        self.inbox
            .spawn(async move { Arrival::Recovered(read_recovery(&db).await) });
    }

    /// Shows the recovered tabs: in place of the workbench's, or beside them if changed since.
    fn recovered(&mut self, wb: &mut Workbench, result: Result<Option<StoredTabs>, String>) {
        self.busy = false;
        self.show_recovered(wb, result);
        self.catch_up(wb);
    }

    fn show_recovered(&mut self, wb: &mut Workbench, result: Result<Option<StoredTabs>, String>) {
        let stored = result.inspect_err(|e| log::warn!("cannot read the recovery records: {e}"));
        let Ok(Some((record, index, mut texts))) = stored else {
            return;
        };
        let restored = index.restore(|key| texts.remove(key), |_| None);
        if restored.tabs.is_empty() {
            files::report_lost(wb, &restored.lost);
            return;
        }
        if wb.any_dirty() {
            // Changed before the records were in: the recovered tabs open beside, kept anew.
            self.book.adopt(&[], &[], &record);
            for tab in restored.tabs {
                if tab.dirty {
                    wb.new_tab();
                    wb.recover(&tab.name, tab.text, tab.encoding);
                } else {
                    wb.open_file(&tab.name, tab.text, tab.encoding, None);
                }
            }
        } else {
            wb.restore_tabs(restored.tabs, restored.active);
            let (tabs, _) = TabState::of(wb, false);
            self.book.adopt(&tabs, &restored.records, &record);
            self.clock.settled(wb.generation());
        }
        files::report_lost(wb, &restored.lost);
    }

    /// Reads a file dropped on the page; it opens in a tab when the browser has read it.
    pub fn open_dropped(&mut self, _wb: &mut Workbench, file: &egui::DroppedFileHandle) {
        let file = file.clone();
        self.inbox.spawn(async move {
            let name = file.path().file_name().unwrap_or("dropped.nc".as_ref());
            let name = name.to_string_lossy().into_owned();
            match file.bytes_async().await {
                Ok(bytes) => Some(match files::too_large(bytes.len() as u64) {
                    Some(why) => Arrival::Message(format!("Cannot open {name}: {why}")),
                    None => Arrival::File(name, bytes, None),
                }),
                Err(e) => {
                    log::warn!("cannot read {name}: {e}");
                    None
                }
            }
        });
    }

    /// Hands what the browser has finished (files read, saves done or refused) to `wb`.
    pub fn poll(&mut self, wb: &mut Workbench) {
        let arrived: Vec<_> = self.inbox.arrivals.borrow_mut().drain(..).collect();
        for arrival in arrived {
            match arrival {
                Arrival::Font(Ok(bytes)) => match self.inbox.wake.borrow().as_ref() {
                    Some(ctx) => _ = wb.add_cjk_font(ctx, bytes),
                    None => wb.cjk_font_failed("no context"),
                },
                Arrival::Font(Err(e)) => wb.cjk_font_failed(&e),
                Arrival::File(name, bytes, handle) => {
                    // The bytes become the text (a 256 MiB file is not held twice).
                    let decoded = swarf_syntax::decode_owned(bytes);
                    let key = handle.map(|h| self.keep_handle(&name, h));
                    wb.open_file(&name, decoded.text, decoded.encoding, key);
                }
                Arrival::Reopened(name, bytes, key) => {
                    // The tab that has the file comes back (re-read when nothing is unsaved).
                    let decoded = swarf_syntax::decode_owned(bytes);
                    wb.open_file(&name, decoded.text, decoded.encoding, Some(key));
                }
                Arrival::Setup(name, bytes) => {
                    let text = String::from_utf8_lossy(&bytes);
                    match wb.import_setup(&text) {
                        Ok(()) => wb.set_message(format!("Setup read from {name}")),
                        Err(e) => wb.set_message(format!("Cannot import {name}: {e}")),
                    }
                }
                Arrival::Saved(name, handle, (tab, generation)) => {
                    if wb.active_tab() == tab && wb.generation() == generation {
                        if let Some(handle) = handle {
                            wb.set_path(Some(self.keep_handle(&name, handle)));
                        }
                        wb.mark_saved(&name);
                        self.write_recovery(wb);
                    } else {
                        wb.set_message(format!(
                            "Saved {name} as it was when saving began; later changes are not in it"
                        ));
                    }
                }
                Arrival::Download(name, bytes, (tab, generation)) => {
                    if wb.active_tab() == tab && wb.generation() == generation {
                        self.download_program(wb, &name, &bytes);
                    } else if let Err(e) = download(&name, &bytes) {
                        wb.set_message(format!("Cannot download {name}: {e:?}"));
                    }
                }
                Arrival::Message(message) => wb.set_message(message),
                Arrival::Recovered(result) => self.recovered(wb, result),
                Arrival::Autosaved(round, stored) => self.autosaved(wb, *round, stored),
            }
        }
    }

    /// Keeps a file handle under a new key, which becomes its tab's document path.
    fn keep_handle(&mut self, name: &str, handle: Handle) -> String {
        // Handles are never dropped: their count numbers the keys.
        let key = format!("{name} (browser file {})", self.handles.len() + 1);
        self.handles.insert(key.clone(), handle);
        key
    }

    /// Catches up with a save made while the records were being read or written.
    fn catch_up(&mut self, wb: &mut Workbench) {
        if std::mem::take(&mut self.again) {
            self.write_recovery(wb);
        }
    }

    /// Saves the active tab's program as a download named `name`.
    fn download_program(&mut self, wb: &mut Workbench, name: &str, bytes: &[u8]) {
        match download(name, bytes) {
            Ok(()) => {
                wb.mark_saved(name);
                self.write_recovery(wb);
            }
            Err(e) => wb.set_message(format!("Cannot download {name}: {e:?}")),
        }
    }

    /// Saves the active tab: to its file handle when it has one, else as [`Host::save_as`].
    fn save(&mut self, wb: &mut Workbench) {
        let key = wb.document().path.as_deref().unwrap_or_default();
        match self.handles.get(key).cloned() {
            // The tab keeps its handle (and key).
            Some(handle) => {
                let at = (wb.active_tab(), wb.generation());
                self.inbox.spawn(save_to(handle, encoded(wb), at, false));
            }
            None => self.save_as(wb),
        }
    }

    /// Writes the active tab to a file the save picker asks for (without one, a download).
    fn save_as(&mut self, wb: &mut Workbench) {
        let name = wb.document().name.clone();
        let bytes = encoded(wb);
        let Some(picker) = window_function("showSaveFilePicker") else {
            self.download_program(wb, &name, &bytes);
            return;
        };
        let options = js_object(&[("suggestedName", JsValue::from_str(&name))]);
        let (tab, generation) = (wb.active_tab(), wb.generation());
        self.inbox.spawn(async move {
            let handle = match call_picker(&picker, &options).await {
                Ok(handle) => handle.unchecked_into::<Handle>(),
                Err(e) => {
                    return match js_error_name(&e).as_str() {
                        // Cancelled: nothing to say.
                        "AbortError" => None,
                        // Refused without a user action just before: download instead.
                        "SecurityError" | "NotAllowedError" => {
                            Some(Arrival::Download(name, bytes, (tab, generation)))
                        }
                        _ => Some(failed(&format!("Cannot save {name}"), &e)),
                    };
                }
            };
            Some(save_to(handle, bytes, (tab, generation), true).await)
        });
    }

    /// Carries out the workbench's file requests: pickers and downloads.
    pub fn handle(&mut self, wb: &mut Workbench, ctx: &egui::Context) {
        *self.inbox.wake.borrow_mut() = Some(ctx.clone());
        for request in wb.take_requests() {
            match request {
                HostRequest::Open | HostRequest::OpenRecent(_) => self.pick_program(),
                HostRequest::ImportSetup => self.pick(".toml", Arrival::Setup),
                HostRequest::Save => self.save(wb),
                HostRequest::SaveAs => self.save_as(wb),
                HostRequest::ExportSetup => {
                    let result = wb.setup_toml().and_then(|t| {
                        download("SETUP.toml", t.as_bytes()).map_err(|e| format!("{e:?}"))
                    });
                    if let Err(e) = result {
                        wb.set_message(format!("Cannot export the setup: {e}"));
                    }
                }
                HostRequest::LoadCjkFont => self.inbox.spawn(async {
                    let result = fetch_bytes(CJK_FONT_URL).await;
                    if let Err(e) = &result {
                        log::warn!("cannot load {CJK_FONT_URL}: {e}");
                    }
                    Arrival::Font(result)
                }),
                HostRequest::Quit => {}
            }
        }
    }

    /// Opens the browser's picker for a program (the File System Access API's, keeping the
    /// handle for Save, where the browser has it); the file arrives through [`Host::poll`]. A
    /// picker opens only just after a user's action, so Ctrl+O's key event calls this too.
    pub fn pick_program(&self) {
        let extensions = files::PROGRAM_EXTENSIONS.map(|e| format!(".{e}"));
        let Some(picker) = window_function("showOpenFilePicker") else {
            self.pick(&extensions.join(","), |name, bytes| {
                Arrival::File(name, bytes, None)
            });
            return;
        };
        let extensions = js_sys::Array::from_iter(extensions.iter().map(JsValue::from));
        let accept = js_object(&[("text/plain", extensions.into())]);
        let program_type = js_object(&[
            ("description", JsValue::from_str("G-code programs")),
            ("accept", accept.into()),
        ]);
        let options = js_object(&[("types", js_sys::Array::of1(&program_type).into())]);
        let known = self.handles.clone();
        self.inbox.spawn(async move {
            let picked = match call_picker(&picker, &options).await {
                Ok(picked) => picked,
                Err(e) if js_error_name(&e) == "AbortError" => return None,
                Err(e) => return Some(failed("Cannot open a file", &e)),
            };
            let first = js_sys::Array::from(&picked).get(0);
            if !first.is_object() {
                return None;
            }
            let handle = first.unchecked_into::<Handle>();
            let name = handle.name();
            let bytes = match read_handle(&handle).await {
                Ok(bytes) => bytes,
                Err(e) => return Some(failed(&format!("Cannot read {name}"), &e)),
            };
            for (key, other) in known {
                if same_entry(&handle, &other).await {
                    return Some(Arrival::Reopened(name, bytes, key));
                }
            }
            Some(Arrival::File(name, bytes, Some(handle)))
        });
    }

    /// Opens the browser's file picker; the file chosen arrives as `arrival` in [`Host::poll`].
    fn pick(&self, accept: &str, arrival: fn(String, Vec<u8>) -> Arrival) {
        let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
            return;
        };
        let input = doc.create_element("input").ok();
        let Some(input) = input.and_then(|e| e.dyn_into::<web_sys::HtmlInputElement>().ok()) else {
            return;
        };
        input.set_type("file");
        input.set_accept(accept);
        let inbox = self.inbox.clone();
        let target = input.clone();
        let on_change = Closure::once_into_js(move |_event: web_sys::Event| {
            let Some(file) = target.files().and_then(|f| f.get(0)) else {
                return;
            };
            inbox.spawn(async move {
                let name = file.name();
                if let Some(why) = files::too_large(file.size() as u64) {
                    return Some(Arrival::Message(format!("Cannot open {name}: {why}")));
                }
                match JsFuture::from(file.array_buffer()).await {
                    Ok(buffer) => {
                        let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
                        Some(arrival(name, bytes))
                    }
                    Err(e) => {
                        log::warn!("cannot read {name}: {e:?}");
                        None
                    }
                }
            });
        });
        input.set_onchange(Some(on_change.unchecked_ref()));
        // Attached (hidden) till the next Open: some browsers open no picker for a detached one.
        if let Some(previous) = doc.get_element_by_id(PICKER_ID) {
            previous.remove();
        }
        input.set_id(PICKER_ID);
        let _ = input.set_attribute("style", "display: none");
        if let Some(body) = doc.body() {
            let _ = body.append_child(&input);
        }
        input.click();
    }

    /// Keeps unsaved changes in IndexedDB a moment after they are made, and removes the records
    /// once nothing is unsaved (later while they are being read or written).
    pub fn autosave(&mut self, wb: &mut Workbench, now: f64) {
        if self.busy {
            return;
        }
        match self.clock.step(wb.generation(), wb.any_dirty(), now) {
            Autosave::Wait => {}
            Autosave::Clear => self.clear_recovery(),
            Autosave::Write => self.write_recovery(wb),
        }
    }

    /// Starts a round of recovery writes when any tab has unsaved changes: a record for each
    /// tab whose text changed (the page cannot read a file again), each in a transaction of its
    /// own so one past the quota spares the others, then the index; [`Host::poll`] takes the end.
    pub fn write_recovery(&mut self, wb: &mut Workbench) {
        if self.busy {
            self.again = true;
            return;
        }
        self.clock.restart();
        if !wb.any_dirty() {
            self.clear_recovery();
            return;
        }
        let (tabs, active) = TabState::of(wb, false);
        let writes = self.book.plan(&tabs);
        // The texts are shared, not copied: they are copied out piece by piece below.
        let texts: Vec<ProgramText> = writes
            .iter()
            .map(|w| wb.tab_source(w.tab).unwrap_or_else(|| String::new().into()))
            .collect();
        let book = self.book.clone();
        let db = self.db.clone();
        self.busy = true;
        self.inbox.spawn(async move {
            let opened = open_db(&db).await;
            let mut results = Vec::with_capacity(writes.len());
            for (write, text) in writes.iter().zip(&texts) {
                let value = text_blob(text).await.map_err(dom_error);
                let stored = match value {
                    Ok(blob) => put(&opened, &write.key, &blob).await,
                    Err(why) => Err(why),
                };
                results.push(stored);
            }
            let mut round = book.compose(&tabs, active, &writes, &results);
            let stored = !round.changed
                || put(&opened, INDEX_KEY, &JsValue::from_str(&round.record))
                    .await
                    .map_err(|e| round.failed = RecoveryBook::all_failed(&tabs, &e))
                    .is_ok();
            Arrival::Autosaved(Box::new(round), stored)
        });
    }

    /// Ends a round of recovery writes: removes stale records, says which tabs are not kept.
    fn autosaved(&mut self, wb: &mut Workbench, round: Round, stored: bool) {
        self.busy = false;
        let (tabs, _) = TabState::of(wb, false);
        if let Some(message) = self.book.report(&round.failed, &tabs) {
            wb.set_message(message);
        }
        self.book.commit(round, stored);
        let stale = self.book.take_stale();
        if !stale.is_empty() {
            self.remove(Some(stale));
        }
        self.catch_up(wb);
    }

    /// Removes every recovery record: nothing is unsaved.
    fn clear_recovery(&mut self) {
        self.clock.restart();
        let stored = self.book.holds_records();
        self.book.cleared();
        if stored {
            self.remove(None);
        }
    }

    /// Removes the records `keys`, or every record and the index when `None`, in the background.
    fn remove(&self, keys: Option<Vec<String>>) {
        let db = self.db.clone();
        wasm_bindgen_futures::spawn_local(async move {
            if let Err(e) = delete(&db, keys.as_deref()).await {
                log::warn!("cannot remove recovery records: {e}");
            }
        });
    }
}

/// Writes `bytes` to `handle`'s file for the (tab, generation) `at`, keeping it when `keep`.
async fn save_to(handle: Handle, bytes: Vec<u8>, at: (usize, u64), keep: bool) -> Arrival {
    let name = handle.name();
    match write_file(&handle, &bytes).await {
        Ok(()) => Arrival::Saved(name, keep.then_some(handle), at),
        Err(e) => failed(&format!("Cannot save {name}"), &e),
    }
}

/// Opens the recovery database once (kept in `slot`), upgrading it if it lacks its store.
async fn open_db(slot: &DbSlot) -> Result<Db, String> {
    if let Some(db) = slot.borrow().as_ref() {
        return Ok(db.clone());
    }
    let mut db = open_version(None).await?;
    if !db.object_store_names().contains(STORE) {
        let next = db.version() as u32 + 1;
        db.close();
        db = open_version(Some(next)).await?;
    }
    *slot.borrow_mut() = Some(db.clone());
    Ok(db)
}

/// Opens the recovery database at `version` (`None`: as it is), making its store on upgrade.
async fn open_version(version: Option<u32>) -> Result<Db, String> {
    let factory = web_sys::window()
        .ok_or("no window")?
        .indexed_db()
        .map_err(dom_error)?
        .ok_or("this browser has no IndexedDB")?;
    let request = match version {
        Some(version) => factory.open_with_u32(DB_NAME, version),
        None => factory.open(DB_NAME),
    }
    .map_err(dom_error)?;
    let opening = request.clone();
    let upgrade = Closure::<dyn FnMut(web_sys::Event)>::new(move |_event: web_sys::Event| {
        if let Ok(db) = opening.result() {
            let db = db.unchecked_into::<Db>();
            if !db.object_store_names().contains(STORE)
                && let Err(e) = db.create_object_store(STORE)
            {
                log::warn!("cannot make the recovery store: {}", dom_error(e));
            }
        }
    });
    request.set_onupgradeneeded(Some(upgrade.as_ref().unchecked_ref()));
    let opened = request_done(&request).await;
    request.set_onupgradeneeded(None);
    drop(upgrade);
    Ok(opened?.unchecked_into::<Db>())
}

/// The result of an IndexedDB request once it succeeded, or its error.
async fn request_done(request: &web_sys::IdbRequest) -> Result<JsValue, String> {
    let promise = js_sys::Promise::new(&mut |resolve, reject| {
        request.set_onsuccess(Some(&resolve));
        request.set_onerror(Some(&reject));
    });
    let done = JsFuture::from(promise).await;
    request.set_onsuccess(None);
    request.set_onerror(None);
    if done.is_ok() {
        return request.result().map_err(dom_error);
    }
    let error = request.error().ok().flatten();
    Err(error.map_or_else(|| "the request failed".into(), |e| dom_error(e.into())))
}

/// Makes the changes `issue` asks of the store in a transaction of its own, committed when
/// this returns Ok (aborted when a change cannot be asked; its error, a quota exceeded say).
async fn write(
    db: &Db,
    issue: impl FnOnce(&web_sys::IdbObjectStore) -> Result<(), JsValue>,
) -> Result<(), String> {
    let tx = db
        .transaction_with_str_and_mode(STORE, web_sys::IdbTransactionMode::Readwrite)
        .map_err(dom_error)?;
    if let Err(e) = tx.object_store(STORE).and_then(|store| issue(&store)) {
        let _ = tx.abort();
        return Err(dom_error(e));
    }
    let promise = js_sys::Promise::new(&mut |resolve, reject| {
        tx.set_oncomplete(Some(&resolve));
        tx.set_onerror(Some(&reject));
        tx.set_onabort(Some(&reject));
    });
    if JsFuture::from(promise).await.is_ok() {
        return Ok(());
    }
    let why = tx.error().map(|e| dom_error(e.into()));
    Err(why.unwrap_or_else(|| "the transaction was aborted".into()))
}

/// The most bytes of a text copied out of the app in one task when it is kept for recovery.
const RECOVERY_PIECE_BYTES: usize = 1 << 20;

/// `text` as UTF-8 in a `Blob`, copied [`RECOVERY_PIECE_BYTES`] at a time, each piece in a task
/// of its own, so that keeping a long program never holds up a frame (a blob of blobs copies
/// none of their bytes, and the database keeps a blob without copying it in the page).
async fn text_blob(text: &ProgramText) -> Result<web_sys::Blob, JsValue> {
    let pieces = js_sys::Array::new();
    let mut chunks = text.chunks().map(str::as_bytes);
    let mut rest: &[u8] = &[];
    let mut left = text.len();
    while left > 0 {
        let len = left.min(RECOVERY_PIECE_BYTES);
        left -= len;
        let array = js_sys::Uint8Array::new_with_length(u32::try_from(len).unwrap_or(u32::MAX));
        crate::web_worker::copy_chunks(&array, &mut rest, &mut chunks);
        let blob = web_sys::Blob::new_with_u8_array_sequence(&js_sys::Array::of1(&array))?;
        pieces.push(&blob);
        next_task().await;
    }
    web_sys::Blob::new_with_blob_sequence(&pieces)
}

/// Waits for a task of its own (after the frames and events already due).
async fn next_task() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        let window = web_sys::window();
        let later = window.map(|w| w.set_timeout_with_callback(&resolve));
        if !matches!(later, Some(Ok(_))) {
            let _ = resolve.call0(&JsValue::NULL);
        }
    });
    let _ = JsFuture::from(promise).await;
}

/// Stores `value` under `key` in the database `opened`, in a transaction of its own.
async fn put(opened: &Result<Db, String>, key: &str, value: &JsValue) -> Result<(), String> {
    let db = opened.as_ref().map_err(String::clone)?;
    let key = JsValue::from_str(key);
    write(db, |store| store.put_with_key(value, &key).map(|_| ())).await
}

/// Removes the records `keys`, or every record and the index when `None`.
async fn delete(slot: &DbSlot, keys: Option<&[String]>) -> Result<(), String> {
    let db = open_db(slot).await?;
    write(&db, |store| match keys {
        Some(keys) => keys
            .iter()
            .try_for_each(|key| store.delete(&JsValue::from_str(key)).map(|_| ())),
        None => store.clear().map(|_| ()),
    })
    .await
}

/// Reads the recovery index (`None`: none stored) and the records it names that can be read,
/// and removes those it does not name (left over from a round whose index was not stored).
async fn read_recovery(slot: &DbSlot) -> Result<Option<StoredTabs>, String> {
    let db = open_db(slot).await?;
    let store = |db: &Db| {
        db.transaction_with_str(STORE)
            .and_then(|tx| tx.object_store(STORE))
            .map_err(dom_error)
    };
    let index = store(&db)?.get(&INDEX_KEY.into()).map_err(dom_error)?;
    let record = request_done(&index).await?.as_string();
    let index = record.as_deref().and_then(RecoveryIndex::from_record);
    let keys = index.iter().flat_map(RecoveryIndex::keys);
    let named: Vec<String> = keys.map(str::to_string).collect();
    // Every request in one transaction, made before the first is awaited.
    let records = store(&db)?;
    let request = |key: &String| Some((key.clone(), records.get(&key.into()).ok()?));
    let requests: Vec<_> = named.iter().filter_map(request).collect();
    // Each request's result is taken as it comes, before anything else is awaited.
    let mut values = Vec::with_capacity(requests.len());
    for (key, request) in requests {
        values.push((key, request_done(&request).await.ok()));
    }
    let mut texts = HashMap::new();
    for (key, value) in values {
        let bytes = match value.map(JsCast::dyn_into::<web_sys::Blob>) {
            Some(Ok(blob)) => JsFuture::from(blob.array_buffer()).await.ok(),
            // Records kept as a byte array by an earlier version.
            Some(Err(value)) => Some(value),
            None => None,
        };
        let array = bytes.and_then(|v| match v.dyn_into::<js_sys::ArrayBuffer>() {
            Ok(buffer) => Some(js_sys::Uint8Array::new(&buffer)),
            Err(v) => v.dyn_into::<js_sys::Uint8Array>().ok(),
        });
        match array.map(|a| String::from_utf8(a.to_vec())) {
            Some(Ok(text)) => _ = texts.insert(key, text),
            _ => log::warn!("the recovery record {key} cannot be read"),
        }
    }
    let all = request_done(&store(&db)?.get_all_keys().map_err(dom_error)?).await?;
    let left_over: Vec<String> = js_sys::Array::from(&all)
        .iter()
        .filter_map(|k| k.as_string())
        .filter(|k| k != INDEX_KEY && !named.contains(k))
        .collect();
    if !left_over.is_empty()
        && let Err(e) = delete(slot, Some(&left_over)).await
    {
        log::warn!("cannot remove left-over recovery records: {e}");
    }
    let stored = record.zip(index);
    Ok(stored.map(|(record, index)| (record, index, texts)))
}

/// A DOM exception (or any JavaScript error) as `Name: message` for the status bar.
fn dom_error(error: JsValue) -> String {
    let name = js_error_name(&error);
    let message = js_error(&error);
    if name.is_empty() || message.starts_with(&name) {
        message
    } else {
        format!("{name}: {message}")
    }
}

/// The body of `url`, fetched.
async fn fetch_bytes(url: &str) -> Result<Vec<u8>, String> {
    let window = web_sys::window().ok_or("no window")?;
    let response = JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|e| format!("{e:?}"))?
        .dyn_into::<web_sys::Response>()
        .map_err(|_| "no response".to_string())?;
    if !response.ok() {
        return Err(format!("HTTP {}", response.status()));
    }
    let buffer = response.array_buffer().map_err(|e| format!("{e:?}"))?;
    let buffer = JsFuture::from(buffer).await.map_err(|e| format!("{e:?}"))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// The active tab's program in its file's encoding (or UTF-8 if that cannot hold it).
fn encoded(wb: &Workbench) -> Vec<u8> {
    crate::files::encode(wb.text(), wb.document().encoding).0
}

/// A JavaScript object with `entries` as its properties.
fn js_object(entries: &[(&str, JsValue)]) -> js_sys::Object {
    let object = js_sys::Object::new();
    for (key, value) in entries {
        let _ = js_sys::Reflect::set(&object, &JsValue::from_str(key), value);
    }
    object
}

/// `window[name]` when the browser has it (the File System Access API: Chromium only).
fn window_function(name: &str) -> Option<js_sys::Function> {
    let window = web_sys::window()?;
    let value = js_sys::Reflect::get(&window, &name.into()).ok()?;
    value.dyn_into().ok()
}

/// Calls a picker of the File System Access API with `options` and waits for its answer.
async fn call_picker(
    picker: &js_sys::Function,
    options: &js_sys::Object,
) -> Result<JsValue, JsValue> {
    let window = web_sys::window().ok_or_else(|| JsValue::from_str("no window"))?;
    let promise = picker
        .call1(&window, options)?
        .dyn_into::<js_sys::Promise>()
        .map_err(|_| JsValue::from_str("the picker returned no promise"))?;
    JsFuture::from(promise).await
}

/// The bytes of the file behind `handle`.
async fn read_handle(handle: &Handle) -> Result<Vec<u8>, JsValue> {
    let file = JsFuture::from(handle.get_file())
        .await?
        .unchecked_into::<web_sys::File>();
    if let Some(why) = files::too_large(file.size() as u64) {
        return Err(JsValue::from_str(&why));
    }
    let buffer = JsFuture::from(file.array_buffer()).await?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// Whether two handles are the same file (false when the browser cannot tell).
async fn same_entry(a: &Handle, b: &Handle) -> bool {
    let same = JsFuture::from(a.is_same_entry(b)).await.ok();
    same.is_some_and(|same| same.as_bool() == Some(true))
}

/// Replaces the content of `handle`'s file with `bytes` (swapped in on close).
async fn write_file(handle: &Handle, bytes: &[u8]) -> Result<(), JsValue> {
    let stream = JsFuture::from(handle.create_writable())
        .await?
        .unchecked_into::<web_sys::FileSystemWritableFileStream>();
    // A copy owned by JavaScript: the write completes after this call returns.
    let data = js_sys::Uint8Array::from(bytes);
    JsFuture::from(stream.write_with_js_u8_array(&data)?).await?;
    JsFuture::from(stream.close()).await?;
    Ok(())
}

/// The `name` of a JavaScript error (`AbortError` …), empty for anything else.
fn js_error_name(error: &JsValue) -> String {
    let name = js_sys::Reflect::get(error, &"name".into()).ok();
    name.and_then(|n| n.as_string()).unwrap_or_default()
}

/// The status bar's `what: error`.
fn failed(what: &str, error: &JsValue) -> Arrival {
    Arrival::Message(format!("{what}: {}", js_error(error)))
}

/// A JavaScript error as a line for the status bar.
fn js_error(error: &JsValue) -> String {
    let message = js_sys::Reflect::get(error, &JsValue::from_str("message")).ok();
    match message.and_then(|m| m.as_string()) {
        Some(m) if !m.is_empty() => m,
        _ => error.as_string().unwrap_or_else(|| format!("{error:?}")),
    }
}

/// Offers `bytes` as a download named `name`.
fn download(name: &str, bytes: &[u8]) -> Result<(), JsValue> {
    let doc = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| JsValue::from_str("no document"))?;
    let parts = js_sys::Array::new();
    parts.push(&js_sys::Uint8Array::from(bytes));
    let options = web_sys::BlobPropertyBag::new();
    options.set_type("application/octet-stream");
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)?;
    let anchor = doc
        .create_element("a")?
        .dyn_into::<web_sys::HtmlAnchorElement>()
        .map_err(|_| JsValue::from_str("no anchor"))?;
    anchor.set_href(&url);
    anchor.set_download(name);
    anchor.click();
    web_sys::Url::revoke_object_url(&url)?;
    Ok(())
}
