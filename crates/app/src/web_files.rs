//! Files on the web page: an `<input type=file>` picker, dropped files, downloads for saving,
//! and crash recovery in the browser's localStorage.

use std::cell::RefCell;
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

/// A file read by the browser, waiting for the next frame.
type Inbox = Rc<RefCell<Vec<(Purpose, String, Vec<u8>)>>>;

/// Web file state: files read asynchronously, and the autosave bookkeeping.
#[derive(Default)]
pub struct Host {
    /// Recent files (none on the web: the page cannot reopen a file by name).
    pub recent: Vec<String>,
    inbox: Inbox,
    clock: AutosaveClock,
    ctx: Option<egui::Context>,
    /// The CJK font once fetched (or why it was not).
    font: FontSlot,
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
        let Some(session) = Session::from_record(&record) else {
            return false;
        };
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
                    inbox.borrow_mut().push((Purpose::Dropped, name, bytes));
                    if let Some(ctx) = ctx {
                        ctx.request_repaint();
                    }
                }
                Err(e) => log::warn!("cannot read {name}: {e}"),
            }
        });
    }

    /// Hands files the browser has finished reading to the workbench.
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
        for (purpose, name, bytes) in arrived {
            match purpose {
                Purpose::Program => {
                    let decoded = swarf_syntax::decode(&bytes);
                    wb.open_document(&name, decoded.text, decoded.encoding);
                }
                Purpose::Dropped => {
                    let decoded = swarf_syntax::decode(&bytes);
                    wb.open_guarded(&name, decoded.text, decoded.encoding, None);
                }
                Purpose::Setup => {
                    let text = String::from_utf8_lossy(&bytes);
                    match wb.import_setup(&text) {
                        Ok(()) => wb.set_message(format!("Setup read from {name}")),
                        Err(e) => wb.set_message(format!("Cannot import {name}: {e}")),
                    }
                }
            }
        }
    }

    /// Carries out the workbench's file requests: pickers and downloads.
    pub fn handle(&mut self, wb: &mut Workbench, ctx: &egui::Context) {
        self.ctx = Some(ctx.clone());
        for request in wb.take_requests() {
            match request {
                HostRequest::Open | HostRequest::OpenRecent(_) => self.pick_program(),
                HostRequest::ImportSetup => self.pick(Purpose::Setup, ".toml"),
                HostRequest::Save | HostRequest::SaveAs => {
                    let name = wb.document().name.clone();
                    let (bytes, _) = crate::files::encode(wb.text(), wb.document().encoding);
                    match download(&name, &bytes) {
                        Ok(()) => {
                            wb.mark_saved(&name);
                            if wb.any_dirty() {
                                self.write_recovery(wb);
                            } else {
                                clear_recovery();
                            }
                        }
                        Err(e) => wb.set_message(format!("Cannot download {name}: {e:?}")),
                    }
                }
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
    /// [`Host::poll`]. Browsers show it only shortly after a user's action (transient
    /// activation), so the page also calls this straight from the Ctrl+O key event.
    pub fn pick_program(&self) {
        self.pick(Purpose::Program, ".nc,.ngc,.tap,.gcode,.cnc,.txt,.ptp,.mpf");
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
                        inbox.borrow_mut().push((purpose, name, bytes));
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
