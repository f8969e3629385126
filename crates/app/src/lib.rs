//! The Swarf application host: wires the [`swarf_ui::Workbench`] into eframe for the desktop
//! binary and the web page, handles files (dialogs, saving, recovery, settings kept between
//! runs) and exposes the page's JavaScript API.

mod app;
#[cfg(not(target_arch = "wasm32"))]
pub mod desktop;
pub mod files;
#[cfg(target_arch = "wasm32")]
mod web;
#[cfg(target_arch = "wasm32")]
mod web_files;
#[cfg(target_arch = "wasm32")]
mod web_worker;

pub use app::SwarfApp;
