//! The Swarf application host: the [`swarf_ui::Workbench`] in eframe for the desktop and the web
//! page, with files (dialogs, saving, recovery, settings kept) and the page's JavaScript API.

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
