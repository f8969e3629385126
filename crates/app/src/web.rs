//! The web entry point and the page's JavaScript API (`window.swarf` is built on it in
//! `web/swarf.js`).

use serde_json::{Value, json};
use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;

use crate::SwarfApp;

/// Handle to the running app, returned by [`start`]; its methods back `window.swarf`.
#[wasm_bindgen]
pub struct SwarfApi {
    runner: eframe::WebRunner,
}

/// Starts Swarf on the canvas with id `canvas_id`; resolves once the app is created.
#[wasm_bindgen]
pub async fn start(canvas_id: String) -> Result<SwarfApi, JsValue> {
    let _ = eframe::WebLogger::init(log::LevelFilter::Info);
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| JsValue::from_str("no document"))?;
    let canvas = document
        .get_element_by_id(&canvas_id)
        .ok_or_else(|| JsValue::from_str(&format!("no element with id `{canvas_id}`")))?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| JsValue::from_str(&format!("`{canvas_id}` is not a canvas")))?;
    let runner = eframe::WebRunner::new();
    let app: eframe::AppCreator<'static> = Box::new(|cc| Ok(Box::new(SwarfApp::new(cc))));
    let options = eframe::WebOptions::default();
    runner.start(canvas, options, app).await?;
    install_open_shortcut(&runner)?;
    Ok(SwarfApi { runner })
}

/// Ctrl+O (Cmd+O) opens the file picker inside the key event itself: browsers show a picker
/// only during the user's action, and the app's frame that would otherwise handle the key may
/// come too late on a busy machine. The file opens in a tab of its own.
fn install_open_shortcut(runner: &eframe::WebRunner) -> Result<(), JsValue> {
    let window = web_sys::window().ok_or_else(|| JsValue::from_str("no window"))?;
    let runner = runner.clone();
    let on_key =
        Closure::<dyn FnMut(web_sys::KeyboardEvent)>::new(move |event: web_sys::KeyboardEvent| {
            let shortcut = (event.ctrl_key() || event.meta_key())
                && !event.shift_key()
                && !event.alt_key()
                && event.key().eq_ignore_ascii_case("o");
            if !shortcut {
                return;
            }
            if let Some(app) = runner.app_mut::<SwarfApp>() {
                event.prevent_default();
                event.stop_immediate_propagation();
                app.host.pick_program();
            }
        });
    let listener = on_key.as_ref().unchecked_ref();
    window.add_event_listener_with_callback_and_bool("keydown", listener, true)?;
    // The listener lives as long as the page.
    on_key.forget();
    Ok(())
}

fn to_js(value: &Value) -> Result<JsValue, JsValue> {
    js_sys::JSON::parse(&value.to_string())
}

#[wasm_bindgen]
impl SwarfApi {
    fn with_app<R>(&self, f: impl FnOnce(&mut SwarfApp) -> R) -> Result<R, JsValue> {
        if let Some(mut app) = self.runner.app_mut::<SwarfApp>() {
            return Ok(f(&mut app));
        }
        let panic = self.runner.panic_summary().map(|p| p.message());
        let why = panic.as_deref().unwrap_or("Swarf is not running");
        Err(JsValue::from_str(why))
    }

    /// What `f` makes of the app, as a JavaScript value.
    fn json(&self, f: impl FnOnce(&mut SwarfApp) -> Value) -> Result<JsValue, JsValue> {
        to_js(&self.with_app(f)?)
    }

    /// Replaces the program text; diagnostics and the backplot follow once its analysis, in
    /// the page's worker, is finished (see [`SwarfApi::idle`]).
    pub fn set_text(&self, text: String) -> Result<(), JsValue> {
        self.with_app(|app| app.edit(|wb| wb.set_text(text)))
    }

    /// Opens `text` as the program file `name` in a tab (a fresh undo history, nothing
    /// unsaved); the other API calls act on the active tab.
    pub fn open(&self, name: String, text: String) -> Result<(), JsValue> {
        self.with_app(|app| {
            app.edit(|wb| wb.open_document(&name, text, swarf_syntax::Encoding::Utf8));
        })
    }

    /// Selects the whole of 1-based `line` in the editor (clamped to the program) and scrolls
    /// to it.
    pub fn select(&self, line: u32) -> Result<(), JsValue> {
        self.with_app(|app| app.edit(|wb| wb.select_line(line)))
    }

    /// `{start, end, text, start_line, end_line}`: the editor's selection in characters, the
    /// selected text and the 1-based lines it covers.
    pub fn selection(&self) -> Result<JsValue, JsValue> {
        self.json(|app| {
            let wb = &app.workbench;
            let range = wb.selection();
            let lines = wb.selected_lines();
            json!({
                "start": range.start, "end": range.end, "text": wb.selected_text(),
                "start_line": lines.start(), "end_line": lines.end(),
            })
        })
    }

    /// `[x, y]`: where the machine point `[x, y, z]` (mm, the frame of `stats().bounds`) was
    /// drawn in the backplot at the last frame, in CSS pixels from the canvas's top left;
    /// `undefined` when it was not (no geometry yet, or behind the eye).
    pub fn project(&self, x: f64, y: f64, z: f64) -> Result<Option<Vec<f64>>, JsValue> {
        self.with_app(|app| app.project(glam::DVec3::new(x, y, z)).map(|p| p.to_vec()))
    }

    /// The machine setup programs run with, as a `SETUP.toml` text.
    pub fn setup(&self) -> Result<String, JsValue> {
        self.with_app(|app| app.workbench.setup_toml())?
            .map_err(|e| js_sys::Error::new(&e).into())
    }

    /// Replaces the machine setup with the `SETUP.toml` text `toml` and re-analyses; throws an
    /// `Error` saying why, the setup unchanged, when the text is not a setup the CLI takes.
    pub fn set_setup(&self, toml: String) -> Result<(), JsValue> {
        self.with_app(|app| app.workbench.import_setup(&toml))?
            .map_err(|e| js_sys::Error::new(&e).into())
    }

    /// The program text.
    pub fn get_text(&self) -> Result<String, JsValue> {
        self.with_app(|app| app.workbench.text().to_string())
    }

    /// `[{line, col, severity, code, message}]`: the problems the page shows now, those of the
    /// last finished analysis (of an earlier text while a new one runs; see
    /// [`SwarfApi::idle`]).
    pub fn diagnostics(&self) -> Result<JsValue, JsValue> {
        self.json(|app| {
            let problems = app.workbench.problems().iter().map(|p| {
                json!({
                    "line": p.line, "col": p.col, "severity": p.severity.as_str(),
                    "code": p.code, "message": p.message,
                })
            });
            Value::Array(problems.collect())
        })
    }

    /// `{blocks, motions, bounds: {min, max} | null, estimated_secs, drawn_points, drawing,
    /// wasm_bytes: {page, worker}}`: the last finished analysis's numbers ([`SwarfApi::idle`]), the
    /// points drawn, whether the picture is incomplete, and the wasm memories in bytes.
    pub fn stats(&self) -> Result<JsValue, JsValue> {
        let (s, drawn, drawing) = self.with_app(|app| {
            let wb = &app.workbench;
            (wb.stats(), wb.drawn_points(), wb.drawing_pending())
        })?;
        let bounds = s
            .bounds
            .map(|(min, max)| json!({"min": min.to_array(), "max": max.to_array()}));
        let memory = wasm_bindgen::memory().dyn_into::<js_sys::WebAssembly::Memory>();
        let buffer = memory.map(|m| m.buffer().unchecked_into::<js_sys::ArrayBuffer>());
        let page = buffer.map_or(0.0, |b| f64::from(b.byte_length()));
        to_js(&json!({
            "blocks": s.blocks, "motions": s.motions, "bounds": bounds,
            "estimated_secs": s.estimated_secs, "drawn_points": drawn,
            "drawing": drawing,
            "wasm_bytes": {"page": page, "worker": crate::web_worker::memory_bytes()},
        }))
    }

    /// A Promise that resolves once the analysis of the current text is finished and a frame
    /// showing it painted, so `diagnostics()` and `stats()` describe it (nothing hurries it).
    pub fn idle(&self) -> Result<js_sys::Promise, JsValue> {
        let mut resolver = None;
        let promise = js_sys::Promise::new(&mut |resolve, _reject| resolver = Some(resolve));
        let resolve = resolver.ok_or_else(|| JsValue::from_str("the Promise gave no resolver"))?;
        self.with_app(|app| {
            app.when_idle(move || {
                // Resolving a Promise cannot fail; its handlers run once the frame is over.
                let _ = resolve.call0(&JsValue::UNDEFINED);
            });
        })?;
        Ok(promise)
    }

    /// `[x, y, width, height]`: where the named widget (`editor`, `backplot`, `find_field`,
    /// `find_next`, `problem_first`, `tab 2` …; see `Workbench::widget_rect`) was drawn at the
    /// last frame, in CSS pixels from the canvas's top left; `undefined` when it was not drawn.
    pub fn widget(&self, name: String) -> Result<Option<Vec<f64>>, JsValue> {
        self.with_app(|app| app.widget_rect(&name).map(|r| r.to_vec()))
    }

    /// Switches the interface language to the tag `code` (`en`, `zh-Hans`, `zh-Hant`); a
    /// Chinese one fetches the CJK font the first time. False for an unknown tag.
    pub fn set_language(&self, code: String) -> Result<bool, JsValue> {
        let Some(lang) = swarf_ui::i18n::Lang::from_code(&code) else {
            return Ok(false);
        };
        self.with_app(|app| app.edit(|wb| wb.set_language(lang)))?;
        Ok(true)
    }

    /// `{language, cjk_font}`: the interface language's tag and whether the CJK font is in.
    pub fn language(&self) -> Result<JsValue, JsValue> {
        self.json(|app| {
            json!({
                "language": app.workbench.language().code(),
                "cjk_font": app.workbench.has_cjk_font(),
            })
        })
    }

    /// `{tabs: [{name, unsaved}], active}`: the open tabs in order and the active one's index.
    pub fn tabs(&self) -> Result<JsValue, JsValue> {
        self.json(|app| {
            let wb = &app.workbench;
            let tab = |d: &&swarf_ui::Document| json!({"name": d.name, "unsaved": d.is_unsaved()});
            let tabs: Vec<Value> = wb.tab_documents().iter().map(tab).collect();
            json!({"tabs": tabs, "active": wb.active_tab()})
        })
    }

    /// The status bar's message (a command's result, an error, what was recovered), if any.
    pub fn status(&self) -> Result<Option<String>, JsValue> {
        self.with_app(|app| app.workbench.message().map(str::to_string))
    }

    /// Frames painted so far (the page waits for the first one before it is ready).
    pub fn frames(&self) -> Result<f64, JsValue> {
        self.with_app(|app| app.frames as f64)
    }
}
