//! The Swarf application host: wires the [`swarf_ui::Workbench`] into eframe for the desktop
//! binary and the web page, and exposes the page's JavaScript API.

mod app;
#[cfg(target_arch = "wasm32")]
mod web;

pub use app::SwarfApp;
