//! Files on the web page: the File System Access API's pickers where the browser has them
//! (Open keeps the file's handle, Save writes back to it), otherwise an `<input type=file>`
//! picker and downloads for saving; dropped files; crash recovery in the browser's
//! localStorage.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

use swarf_ui::{HostRequest, Workbench};

use crate::files::{Autosave, AutosaveClock, Session};

/// localStorage key of the open tabs while any has unsaved changes.
const RECOVERY_KEY: &str = "swarf.recovery";
/// Where the page's CJK font is, relative to the page (`cargo xtask web` puts it there). It is
/// fetched only when a Chinese language is chosen; the service worker keeps it once fetched.
pub const CJK_FONT_URL: &str = "./fonts/wqy-microhei.ttc";
/// Element id of the hidden file input.
const PICKER_ID: &str = "swarf-file-picker";

/// What a picked file is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Purpose {
    Program,
    Dropped,
    Setup,
}

/// The CJK font once fetched (or why it was not), waiting for the next frame.
type FontSlot = Rc<RefCell<Option<Result<Vec<u8>, String>>>>;

/// What the browser finished while the app waited: a file read, a save done or refused.
enum Arrival {
    /// A file read for `Purpose`, with its handle when it came from the File System Access API.
    File(
        Purpose,
        String,
        Vec<u8>,
        Option<web_sys::FileSystemFileHandle>,
    ),
    /// A program picked with the File System Access API that is the file kept under `key`.
    Reopened {
        name: String,
        bytes: Vec<u8>,
        key: String,
    },
    /// A save that was written (to `handle` when there is one), for the tab that was active
    /// at `generation`.
    Saved {
        name: String,
        handle: Option<web_sys::FileSystemFileHandle>,
        tab: usize,
        generation: u64,
    },
    /// The save picker refused to open (no user action just before): download instead, for
    /// the tab that was active at `generation`.
    Download {
        name: String,
        bytes: Vec<u8>,
        tab: usize,
        generation: u64,
    },
    /// Something to tell the user.
    Message(String),
}

/// What the browser finished, waiting for the next frame.
type Inbox = Rc<RefCell<Vec<Arrival>>>;

/// Web file state: files read asynchronously, the handles of files opened or saved through
/// the File System Access API, and the autosave bookkeeping.
#[derive(Default)]
pub struct Host {
    /// Recent files (none on the web: the page cannot reopen a file by name).
    pub recent: Vec<String>,
    inbox: Inbox,
    clock: AutosaveClock,
    ctx: Option<egui::Context>,
    /// The CJK font once fetched (or why it was not).
    font: FontSlot,
    /// File handles by the key kept as their tab's document path.
    handles: HashMap<String, web_sys::FileSystemFileHandle>,
    /// Handles given out so far, for unique keys.
    handle_count: u64,
}

fn local_storage() -> Option<web_sys::Storage> {
    web_sys::window().and_then(|w| w.local_storage().ok().flatten())
}

/// Sets the page's title (the document name and whether it has unsaved changes).
pub fn set_document_title(title: &str) {
    if let Some(doc) = web_sys::window().and_then(|w| w.document()) {
        doc.set_title(title);
    }
}

impl Host {
    /// A web host.
    pub fn new() -> Host {
        Host::default()
    }

    /// Shows the tabs left with unsaved changes in this browser, if there are.
    pub fn recover(&mut self, wb: &mut Workbench) -> bool {
        let Some(record) = local_storage().and_then(|s| s.get_item(RECOVERY_KEY).ok().flatten())
        else {
            return false;
        };
        let Some(mut session) = Session::from_record(&record) else {
            return false;
        };
        // File handles do not outlive the page: the recovered tabs are saved anew.
        for tab in &mut session.tabs {
            tab.path = None;
        }
        wb.restore_tabs(session.tabs, session.active);
        self.clock.settled(wb.generation());
        true
    }

    /// Reads a file dropped on the page; it opens in a tab when the browser has read it.
    pub fn open_dropped(&mut self, _wb: &mut Workbench, file: &egui::DroppedFileHandle) {
        let file = file.clone();
        let inbox = self.inbox.clone();
        let ctx = self.ctx.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let name = file.path().file_name().map_or_else(
                || "dropped.nc".to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            match file.bytes_async().await {
                Ok(bytes) => {
                    inbox
                        .borrow_mut()
                        .push(Arrival::File(Purpose::Dropped, name, bytes, None));
                    if let Some(ctx) = ctx {
                        ctx.request_repaint();
                    }
                }
                Err(e) => log::warn!("cannot read {name}: {e}"),
            }
        });
    }

    /// Hands what the browser has finished (files read, saves written or refused) to the
    /// workbench.
    pub fn poll(&mut self, wb: &mut Workbench) {
        let font = self.font.borrow_mut().take();
        match (font, &self.ctx) {
            (Some(Ok(bytes)), Some(ctx)) => {
                wb.add_cjk_font(ctx, bytes);
            }
            (Some(Ok(_)), None) => wb.cjk_font_failed("no context"),
            (Some(Err(e)), _) => wb.cjk_font_failed(&e),
            (None, _) => {}
        }
        let arrived: Vec<_> = self.inbox.borrow_mut().drain(..).collect();
        for arrival in arrived {
            match arrival {
                Arrival::File(Purpose::Program, name, bytes, handle) => {
                    let decoded = swarf_syntax::decode(&bytes);
                    let key = handle.map(|h| self.keep_handle(&name, h));
                    wb.open_file(&name, decoded.text, decoded.encoding, key);
                }
                Arrival::Reopened { name, bytes, key } => {
                    // The tab that has the file comes back (re-read when nothing is unsaved).
                    let decoded = swarf_syntax::decode(&bytes);
                    wb.open_file(&name, decoded.text, decoded.encoding, Some(key));
                }
                Arrival::File(Purpose::Dropped, name, bytes, _) => {
                    let decoded = swarf_syntax::decode(&bytes);
                    wb.open_guarded(&name, decoded.text, decoded.encoding, None);
                }
                Arrival::File(Purpose::Setup, name, bytes, _) => {
                    let text = String::from_utf8_lossy(&bytes);
                    match wb.import_setup(&text) {
                        Ok(()) => wb.set_message(format!("Setup read from {name}")),
                        Err(e) => wb.set_message(format!("Cannot import {name}: {e}")),
                    }
                }
                Arrival::Saved {
                    name,
                    handle,
                    tab,
                    generation,
                } => {
                    if wb.active_tab() == tab && wb.generation() == generation {
                        if let Some(handle) = handle {
                            let key = self.keep_handle(&name, handle);
                            wb.set_path(Some(key));
                        }
                        wb.mark_saved(&name);
                        self.after_save(wb);
                    } else {
                        wb.set_message(format!(
                            "Saved {name} as it was when saving began; later changes are not in it"
                        ));
                    }
                }
                Arrival::Download {
                    name,
                    bytes,
                    tab,
                    generation,
                } => {
                    if wb.active_tab() == tab && wb.generation() == generation {
                        self.download_program(wb, &name, &bytes);
                    } else if let Err(e) = download(&name, &bytes) {
                        wb.set_message(format!("Cannot download {name}: {e:?}"));
                    }
                }
                Arrival::Message(message) => wb.set_message(message),
            }
        }
    }

    /// Keeps a file handle under a new key, which becomes its tab's document path.
    fn keep_handle(&mut self, name: &str, handle: web_sys::FileSystemFileHandle) -> String {
        self.handle_count += 1;
        let key = format!("{name} (browser file {})", self.handle_count);
        self.handles.insert(key.clone(), handle);
        key
    }

    /// The recovery copy after a save: kept while another tab has unsaved changes.
    fn after_save(&mut self, wb: &Workbench) {
        if wb.any_dirty() {
            self.write_recovery(wb);
        } else {
            clear_recovery();
        }
    }

    /// Saves the active tab's program as a download named `name`.
    fn download_program(&mut self, wb: &mut Workbench, name: &str, bytes: &[u8]) {
        match download(name, bytes) {
            Ok(()) => {
                wb.mark_saved(name);
                self.after_save(wb);
            }
            Err(e) => wb.set_message(format!("Cannot download {name}: {e:?}")),
        }
    }

    /// Saves the active tab: to its file handle when it has one, else as [`Host::save_as`].
    fn save(&mut self, wb: &mut Workbench) {
        let handle = wb
            .document()
            .path
            .as_ref()
            .and_then(|key| self.handles.get(key))
            .cloned();
        match handle {
            Some(handle) => {
                let name = handle.name();
                let bytes = encoded(wb);
                let (tab, generation) = (wb.active_tab(), wb.generation());
                self.spawn(async move {
                    match write_file(&handle, &bytes).await {
                        // The tab keeps its handle (and key).
                        Ok(()) => Arrival::Saved {
                            name,
                            handle: None,
                            tab,
                            generation,
                        },
                        Err(e) => Arrival::Message(format!("Cannot save {name}: {}", js_error(&e))),
                    }
                });
            }
            None => self.save_as(wb),
        }
    }

    /// Asks for a file with the browser's save picker and writes the active tab there; where
    /// the browser has no such picker, downloads the program.
    fn save_as(&mut self, wb: &mut Workbench) {
        let name = wb.document().name.clone();
        let bytes = encoded(wb);
        let Some(picker) = window_function("showSaveFilePicker") else {
            self.download_program(wb, &name, &bytes);
            return;
        };
        let options = js_sys::Object::new();
        let _ = js_sys::Reflect::set(
            &options,
            &JsValue::from_str("suggestedName"),
            &JsValue::from_str(&name),
        );
        let (tab, generation) = (wb.active_tab(), wb.generation());
        self.spawn(async move {
            let handle = match call_picker(&picker, &options).await {
                Ok(handle) => handle.unchecked_into::<web_sys::FileSystemFileHandle>(),
                Err(e) => {
                    return match js_error_name(&e).as_str() {
                        // Cancelled: nothing to say.
                        "AbortError" => None,
                        // Refused without a user action just before: download instead.
                        "SecurityError" | "NotAllowedError" => Some(Arrival::Download {
                            name,
                            bytes,
                            tab,
                            generation,
                        }),
                        _ => Some(Arrival::Message(format!(
                            "Cannot save {name}: {}",
                            js_error(&e)
                        ))),
                    };
                }
            };
            let name = handle.name();
            Some(match write_file(&handle, &bytes).await {
                Ok(()) => Arrival::Saved {
                    name,
                    handle: Some(handle),
                    tab,
                    generation,
                },
                Err(e) => Arrival::Message(format!("Cannot save {name}: {}", js_error(&e))),
            })
        });
    }

    /// Runs `task` in the browser; what it ends with arrives through [`Host::poll`].
    fn spawn<A>(&self, task: impl std::future::Future<Output = A> + 'static)
    where
        A: Into<Option<Arrival>>,
    {
        let inbox = self.inbox.clone();
        let ctx = self.ctx.clone();
        wasm_bindgen_futures::spawn_local(async move {
            if let Some(arrival) = task.await.into() {
                inbox.borrow_mut().push(arrival);
                if let Some(ctx) = ctx {
                    ctx.request_repaint();
                }
            }
        });
    }

    /// Carries out the workbench's file requests: pickers and downloads.
    pub fn handle(&mut self, wb: &mut Workbench, ctx: &egui::Context) {
        self.ctx = Some(ctx.clone());
        for request in wb.take_requests() {
            match request {
                HostRequest::Open | HostRequest::OpenRecent(_) => self.pick_program(),
                HostRequest::ImportSetup => self.pick(Purpose::Setup, ".toml"),
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
                HostRequest::LoadCjkFont => self.fetch_cjk_font(),
                HostRequest::Quit => {}
            }
        }
    }

    /// Fetches the CJK font; it is handed to the workbench by [`Host::poll`].
    fn fetch_cjk_font(&self) {
        let slot = self.font.clone();
        let ctx = self.ctx.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let result = fetch_bytes(CJK_FONT_URL).await;
            if let Err(e) = &result {
                log::warn!("cannot load {CJK_FONT_URL}: {e}");
            }
            *slot.borrow_mut() = Some(result);
            if let Some(ctx) = ctx {
                ctx.request_repaint();
            }
        });
    }

    /// Opens the browser's file picker for a program; the chosen file arrives through
    /// [`Host::poll`]. Where the browser has the File System Access API its picker is used and
    /// the file's handle kept, so Save writes back to the file. Browsers show a picker only
    /// shortly after a user's action (transient activation), so the page also calls this
    /// straight from the Ctrl+O key event.
    pub fn pick_program(&self) {
        let Some(picker) = window_function("showOpenFilePicker") else {
            self.pick(Purpose::Program, &PROGRAM_EXTENSIONS.join(","));
            return;
        };
        let options = js_sys::Object::new();
        let accept = js_sys::Object::new();
        let extensions: js_sys::Array = PROGRAM_EXTENSIONS
            .iter()
            .map(|e| JsValue::from_str(e))
            .collect();
        let _ = js_sys::Reflect::set(&accept, &JsValue::from_str("text/plain"), &extensions);
        let program_type = js_sys::Object::new();
        let _ = js_sys::Reflect::set(
            &program_type,
            &JsValue::from_str("description"),
            &JsValue::from_str("G-code programs"),
        );
        let _ = js_sys::Reflect::set(&program_type, &JsValue::from_str("accept"), &accept);
        let _ = js_sys::Reflect::set(
            &options,
            &JsValue::from_str("types"),
            &js_sys::Array::of1(&program_type),
        );
        let known: Vec<_> = self
            .handles
            .iter()
            .map(|(key, handle)| (key.clone(), handle.clone()))
            .collect();
        self.spawn(async move {
            let picked = match call_picker(&picker, &options).await {
                Ok(picked) => picked,
                Err(e) if js_error_name(&e) == "AbortError" => return None,
                Err(e) => {
                    return Some(Arrival::Message(format!(
                        "Cannot open a file: {}",
                        js_error(&e)
                    )));
                }
            };
            let first = js_sys::Array::from(&picked).get(0);
            if !first.is_object() {
                return None;
            }
            let handle = first.unchecked_into::<web_sys::FileSystemFileHandle>();
            let name = handle.name();
            let bytes = match read_handle(&handle).await {
                Ok(bytes) => bytes,
                Err(e) => {
                    return Some(Arrival::Message(format!(
                        "Cannot read {name}: {}",
                        js_error(&e)
                    )));
                }
            };
            for (key, other) in known {
                if same_entry(&handle, &other).await {
                    return Some(Arrival::Reopened { name, bytes, key });
                }
            }
            Some(Arrival::File(Purpose::Program, name, bytes, Some(handle)))
        });
    }

    /// Opens the browser's file picker; the chosen file arrives through [`Host::poll`].
    fn pick(&self, purpose: Purpose, accept: &str) {
        let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
            return;
        };
        let Some(input) = doc
            .create_element("input")
            .ok()
            .and_then(|e| e.dyn_into::<web_sys::HtmlInputElement>().ok())
        else {
            return;
        };
        input.set_type("file");
        input.set_accept(accept);
        let inbox = self.inbox.clone();
        let ctx = self.ctx.clone();
        let target = input.clone();
        let on_change = Closure::once_into_js(move |_event: web_sys::Event| {
            let Some(file) = target.files().and_then(|f| f.get(0)) else {
                return;
            };
            wasm_bindgen_futures::spawn_local(async move {
                let name = file.name();
                match wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await {
                    Ok(buffer) => {
                        let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
                        inbox
                            .borrow_mut()
                            .push(Arrival::File(purpose, name, bytes, None));
                        if let Some(ctx) = ctx {
                            ctx.request_repaint();
                        }
                    }
                    Err(e) => log::warn!("cannot read {name}: {e:?}"),
                }
            });
        });
        input.set_onchange(Some(on_change.unchecked_ref()));
        // Attached (hidden) while it is in use: some browsers open no picker for a detached
        // input. The next Open replaces it.
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

    /// Keeps unsaved changes in localStorage a moment after they are made.
    pub fn autosave(&mut self, wb: &Workbench, now: f64) {
        match self.clock.step(wb.generation(), wb.any_dirty(), now) {
            Autosave::Wait => {}
            Autosave::Clear => clear_recovery(),
            Autosave::Write => self.write_recovery(wb),
        }
    }

    /// Writes the open tabs to localStorage now, when any has unsaved changes.
    pub fn write_recovery(&mut self, wb: &Workbench) {
        self.clock.restart();
        if !wb.any_dirty() {
            return;
        }
        let record = Session::of(wb);
        if let Some(storage) = local_storage()
            && let Err(e) = storage.set_item(RECOVERY_KEY, &record.to_record())
        {
            log::warn!("cannot keep the unsaved program in localStorage: {e:?}");
        }
    }
}

fn clear_recovery() {
    if let Some(storage) = local_storage() {
        let _ = storage.remove_item(RECOVERY_KEY);
    }
}

/// The body of `url`, fetched.
async fn fetch_bytes(url: &str) -> Result<Vec<u8>, String> {
    let window = web_sys::window().ok_or("no window")?;
    let response = wasm_bindgen_futures::JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|e| format!("{e:?}"))?
        .dyn_into::<web_sys::Response>()
        .map_err(|_| "no response".to_string())?;
    if !response.ok() {
        return Err(format!("HTTP {}", response.status()));
    }
    let buffer = response.array_buffer().map_err(|e| format!("{e:?}"))?;
    let buffer = wasm_bindgen_futures::JsFuture::from(buffer)
        .await
        .map_err(|e| format!("{e:?}"))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// The extensions the open picker offers for programs.
const PROGRAM_EXTENSIONS: [&str; 8] = [
    ".nc", ".ngc", ".tap", ".gcode", ".cnc", ".txt", ".ptp", ".mpf",
];

/// The active tab's program in its file's encoding (as UTF-8 when an edit added a character
/// the encoding cannot hold).
fn encoded(wb: &Workbench) -> Vec<u8> {
    crate::files::encode(wb.text(), wb.document().encoding).0
}

/// `window[name]` when the browser has such a function (the File System Access API's pickers
/// exist in Chromium-based browsers only).
fn window_function(name: &str) -> Option<js_sys::Function> {
    let window = web_sys::window()?;
    js_sys::Reflect::get(&window, &JsValue::from_str(name))
        .ok()?
        .dyn_into::<js_sys::Function>()
        .ok()
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
    wasm_bindgen_futures::JsFuture::from(promise).await
}

/// The bytes of the file behind `handle`.
async fn read_handle(handle: &web_sys::FileSystemFileHandle) -> Result<Vec<u8>, JsValue> {
    let file = wasm_bindgen_futures::JsFuture::from(handle.get_file())
        .await?
        .unchecked_into::<web_sys::File>();
    let buffer = wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// Whether two handles are the same file (false when the browser cannot tell).
async fn same_entry(a: &web_sys::FileSystemFileHandle, b: &web_sys::FileSystemFileHandle) -> bool {
    wasm_bindgen_futures::JsFuture::from(a.is_same_entry(b))
        .await
        .ok()
        .and_then(|same| same.as_bool())
        .unwrap_or(false)
}

/// Replaces the content of the file behind `handle` with `bytes` (the browser writes a
/// temporary file and swaps it in on close).
async fn write_file(handle: &web_sys::FileSystemFileHandle, bytes: &[u8]) -> Result<(), JsValue> {
    let stream = wasm_bindgen_futures::JsFuture::from(handle.create_writable())
        .await?
        .unchecked_into::<web_sys::FileSystemWritableFileStream>();
    // A copy owned by JavaScript: the write completes after this call returns.
    let data = js_sys::Uint8Array::from(bytes);
    wasm_bindgen_futures::JsFuture::from(stream.write_with_js_u8_array(&data)?).await?;
    wasm_bindgen_futures::JsFuture::from(stream.close()).await?;
    Ok(())
}

/// The `name` of a JavaScript error (`AbortError` …), empty for anything else.
fn js_error_name(error: &JsValue) -> String {
    js_sys::Reflect::get(error, &JsValue::from_str("name"))
        .ok()
        .and_then(|n| n.as_string())
        .unwrap_or_default()
}

/// A JavaScript error as a line for the status bar.
fn js_error(error: &JsValue) -> String {
    let message = js_sys::Reflect::get(error, &JsValue::from_str("message"))
        .ok()
        .and_then(|m| m.as_string());
    match message {
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
