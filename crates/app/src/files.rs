//! What the desktop and the web host share about files: the recent list, the recovery record
//! and saving in the file's own encoding.

use swarf_syntax::{Dialect, Encoding};
use swarf_ui::i18n::Lang;
use swarf_ui::{TabRecord, Workbench};

/// Most recent files remembered.
pub const RECENT_MAX: usize = 10;

/// Storage key of the recent files (newline-separated paths).
pub const KEY_RECENT: &str = "swarf.recent";
/// Storage key of the dialect name.
pub const KEY_DIALECT: &str = "swarf.dialect";
/// Storage key of the machine setup, as `SETUP.toml` text.
pub const KEY_SETUP: &str = "swarf.setup";
/// Storage key of the interface language (`en`, `zh-Hans`, `zh-Hant`).
pub const KEY_LANGUAGE: &str = "swarf.language";

/// Puts `item` first in `list`, without duplicates, keeping at most [`RECENT_MAX`].
pub fn push_recent(list: &mut Vec<String>, item: String) {
    list.retain(|p| *p != item);
    list.insert(0, item);
    list.truncate(RECENT_MAX);
}

/// Keeps the dialect, the machine setup (as `SETUP.toml`), the interface language and the
/// recent files in `storage`.
pub fn store_settings(storage: &mut dyn eframe::Storage, wb: &Workbench, recent: &[String]) {
    storage.set_string(KEY_DIALECT, wb.dialect().name().to_string());
    storage.set_string(KEY_LANGUAGE, wb.language().code().to_string());
    match wb.setup_toml() {
        Ok(toml) => storage.set_string(KEY_SETUP, toml),
        Err(e) => log::warn!("cannot keep the setup: {e}"),
    }
    storage.set_string(KEY_RECENT, recent.join("\n"));
}

/// Restores what [`store_settings`] kept into `wb`; returns the recent files. Anything
/// unreadable is skipped with a warning in the log.
pub fn restore_settings(storage: &dyn eframe::Storage, wb: &mut Workbench) -> Vec<String> {
    if let Some(dialect) = storage
        .get_string(KEY_DIALECT)
        .and_then(|d| d.parse::<Dialect>().ok())
    {
        wb.set_dialect(dialect);
    }
    if let Some(lang) = storage
        .get_string(KEY_LANGUAGE)
        .and_then(|l| Lang::from_code(&l))
    {
        wb.set_language(lang);
    }
    if let Some(setup) = storage.get_string(KEY_SETUP)
        && let Err(e) = wb.import_setup(&setup)
    {
        log::warn!("the saved setup is not readable: {e}");
    }
    let recent: Vec<String> = storage
        .get_string(KEY_RECENT)
        .map(|r| {
            r.lines()
                .filter(|l| !l.is_empty())
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default();
    wb.set_recent(recent.clone());
    recent
}

/// `text` encoded as `encoding` when that gives the same text back, else as UTF-8 (a character
/// the file's encoding cannot hold must not be lost); the encoding actually used comes with it.
pub fn encode(text: &str, encoding: Encoding) -> (Vec<u8>, Encoding) {
    let bytes = encoding.encode(text);
    let back = swarf_syntax::decode(&bytes);
    if back.text == text && back.encoding == encoding {
        (bytes, encoding)
    } else {
        (text.as_bytes().to_vec(), Encoding::Utf8)
    }
}

/// Seconds an edit waits before it is written to the recovery copy.
pub const AUTOSAVE_DELAY: f64 = 1.0;

/// When the recovery copy of unsaved changes is written or cleared, the same on the desktop
/// (a file) and the web (localStorage): a moment after an edit, once per text generation.
#[derive(Debug, Default, Clone, Copy)]
pub struct AutosaveClock {
    /// The text generation last written (or cleared).
    autosaved: u64,
    /// When the text was first seen changed since the last autosave (egui time).
    changed_at: Option<f64>,
}

/// What the recovery copy needs now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Autosave {
    /// Nothing (no change, or the edit is too recent).
    Wait,
    /// Remove it: nothing is unsaved.
    Clear,
    /// Write it.
    Write,
}

impl AutosaveClock {
    /// What to do for text `generation` (`dirty`: it has unsaved changes) at time `now`.
    pub fn step(&mut self, generation: u64, dirty: bool, now: f64) -> Autosave {
        if generation == self.autosaved {
            return Autosave::Wait;
        }
        if !dirty {
            self.autosaved = generation;
            return Autosave::Clear;
        }
        let since = *self.changed_at.get_or_insert(now);
        if now - since < AUTOSAVE_DELAY {
            return Autosave::Wait;
        }
        self.autosaved = generation;
        Autosave::Write
    }

    /// Generation `generation` is already safe (e.g. just recovered).
    pub fn settled(&mut self, generation: u64) {
        self.autosaved = generation;
    }

    /// The copy was written or removed: the next edit waits its delay again.
    pub fn restart(&mut self) {
        self.changed_at = None;
    }
}

/// An unsaved program kept for crash recovery: which file it belongs to and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recovery {
    /// The document's name.
    pub name: String,
    /// Its file's full path on the desktop (empty when it was never saved, and on the web).
    pub path: String,
    /// The file's encoding.
    pub encoding: Encoding,
    /// The unsaved text.
    pub text: String,
}

const MAGIC: &str = "swarf-recovery 1";

impl Recovery {
    /// The record as one string: a header line (tab-separated) and the text.
    pub fn to_record(&self) -> String {
        let clean = |s: &str| s.replace(['\t', '\n', '\r'], " ");
        format!(
            "{MAGIC}\t{}\t{}\t{}\n{}",
            encoding_name(self.encoding),
            clean(&self.name),
            clean(&self.path),
            self.text
        )
    }

    /// Reads a record written by [`Recovery::to_record`]; `None` for anything else.
    pub fn from_record(record: &str) -> Option<Recovery> {
        let (head, text) = record.split_once('\n')?;
        let mut fields = head.split('\t');
        if fields.next()? != MAGIC {
            return None;
        }
        let encoding = encoding_of(fields.next()?)?;
        let name = fields.next()?.to_string();
        let path = fields.next().unwrap_or_default().to_string();
        Some(Recovery {
            name,
            path,
            encoding,
            text: text.to_string(),
        })
    }
}

const SESSION_MAGIC: &str = "swarf-recovery 2";

/// Every open tab kept for crash recovery (written while any has unsaved changes): each tab's
/// file and text, and which one is active.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Session {
    /// The tabs, in order.
    pub tabs: Vec<TabRecord>,
    /// The index of the active tab.
    pub active: usize,
}

impl Session {
    /// The workbench's tabs.
    pub fn of(wb: &Workbench) -> Session {
        let (tabs, active) = wb.tab_records();
        Session { tabs, active }
    }

    /// The record as one string: a header line, then for each tab a tab-separated line
    /// (encoding, name, path, 1 when unsaved, length of the text in bytes) and the text.
    pub fn to_record(&self) -> String {
        let clean = |s: &str| s.replace(['\t', '\n', '\r'], " ");
        let mut out = format!("{SESSION_MAGIC}\t{}\t{}\n", self.tabs.len(), self.active);
        for t in &self.tabs {
            out.push_str(&format!(
                "{}\t{}\t{}\t{}\t{}\n",
                encoding_name(t.encoding),
                clean(&t.name),
                clean(t.path.as_deref().unwrap_or_default()),
                u8::from(t.dirty),
                t.text.len()
            ));
            out.push_str(&t.text);
            out.push('\n');
        }
        out
    }

    /// Reads a record written by [`Session::to_record`], or a single unsaved program written
    /// by [`Recovery::to_record`]; `None` for anything else.
    pub fn from_record(record: &str) -> Option<Session> {
        if let Some(r) = Recovery::from_record(record) {
            return Some(Session {
                tabs: vec![TabRecord {
                    name: r.name,
                    path: (!r.path.is_empty()).then_some(r.path),
                    encoding: r.encoding,
                    text: r.text,
                    dirty: true,
                }],
                active: 0,
            });
        }
        let (head, mut rest) = record.split_once('\n')?;
        let mut fields = head.split('\t');
        if fields.next()? != SESSION_MAGIC {
            return None;
        }
        let count: usize = fields.next()?.parse().ok()?;
        let active: usize = fields.next()?.parse().ok()?;
        let mut tabs = Vec::new();
        for _ in 0..count {
            let (line, after) = rest.split_once('\n')?;
            let mut f = line.split('\t');
            let encoding = encoding_of(f.next()?)?;
            let name = f.next()?.to_string();
            let path = f.next()?.to_string();
            let dirty = f.next()? == "1";
            let len: usize = f.next()?.parse().ok()?;
            let text = after.get(..len)?.to_string();
            rest = after.get(len..)?.strip_prefix('\n')?;
            tabs.push(TabRecord {
                name,
                path: (!path.is_empty()).then_some(path),
                encoding,
                text,
                dirty,
            });
        }
        (!tabs.is_empty() && active < tabs.len()).then_some(Session { tabs, active })
    }
}

fn encoding_name(e: Encoding) -> &'static str {
    match e {
        Encoding::Utf8 => "utf8",
        Encoding::Utf8Bom => "utf8bom",
        Encoding::Gb18030 => "gb18030",
        Encoding::Big5 => "big5",
    }
}

fn encoding_of(name: &str) -> Option<Encoding> {
    Some(match name {
        "utf8" => Encoding::Utf8,
        "utf8bom" => Encoding::Utf8Bom,
        "gb18030" => Encoding::Gb18030,
        "big5" => Encoding::Big5,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn recent_files_are_newest_first_without_duplicates() {
        let mut list = Vec::new();
        for i in 0..12 {
            push_recent(&mut list, format!("/p/{i}.nc"));
        }
        push_recent(&mut list, "/p/5.nc".to_string());
        assert_eq!(list.len(), RECENT_MAX);
        assert_eq!(list[0], "/p/5.nc");
        assert_eq!(list.iter().filter(|p| *p == "/p/5.nc").count(), 1);
    }

    #[test]
    fn saving_keeps_the_encoding_unless_a_character_would_be_lost() {
        let text = "(銑削) G01 X1.\n";
        let (bytes, enc) = encode(text, Encoding::Gb18030);
        assert_eq!(enc, Encoding::Gb18030);
        assert_eq!(swarf_syntax::decode(&bytes).text, text);
        let (bytes, enc) = encode("(é) G0\n", Encoding::Utf8Bom);
        assert_eq!(
            (enc, &bytes[..3]),
            (Encoding::Utf8Bom, &[0xEF, 0xBB, 0xBF][..])
        );
        // Big5 has no `€`: the file becomes UTF-8 rather than lose it.
        let (bytes, enc) = encode("(€) G0\n", Encoding::Big5);
        assert_eq!(enc, Encoding::Utf8);
        assert_eq!(bytes, "(€) G0\n".as_bytes());
    }

    #[test]
    fn recovery_records_read_back() {
        let r = Recovery {
            name: "part.nc".into(),
            path: "/home/me/part.nc".into(),
            encoding: Encoding::Big5,
            text: "G0 X1\n\tG1 X2\n".into(),
        };
        assert_eq!(Recovery::from_record(&r.to_record()), Some(r));
        assert_eq!(Recovery::from_record("G0 X1\n"), None);
        assert_eq!(Recovery::from_record(""), None);
    }

    #[test]
    fn sessions_read_back_and_old_records_are_one_unsaved_tab() {
        let tab = |name: &str, text: &str, dirty: bool| TabRecord {
            name: name.into(),
            path: dirty.then(|| format!("/home/me/{name}")),
            encoding: Encoding::Utf8,
            text: text.into(),
            dirty,
        };
        let s = Session {
            tabs: vec![
                tab("a.nc", "G0 X1\n\nM30\n", false),
                tab("O1234.nc", "O1234\n\tG1 X2 (多)\nM99", true),
                tab("untitled.nc", "", false),
            ],
            active: 1,
        };
        assert_eq!(Session::from_record(&s.to_record()), Some(s.clone()));
        // Cut short or out of range: nothing.
        let record = s.to_record();
        assert_eq!(Session::from_record(&record[..record.len() - 20]), None);
        assert_eq!(
            Session::from_record(&record.replacen("\t3\t1\n", "\t3\t7\n", 1)),
            None
        );
        let old = Recovery {
            name: "part.nc".into(),
            path: String::new(),
            encoding: Encoding::Big5,
            text: "G0 X1\n".into(),
        };
        let read = Session::from_record(&old.to_record()).unwrap();
        assert_eq!(read.active, 0);
        assert_eq!(read.tabs.len(), 1);
        assert!(read.tabs[0].dirty);
        assert_eq!(read.tabs[0].path, None);
        assert_eq!(read.tabs[0].text, "G0 X1\n");
    }
}
