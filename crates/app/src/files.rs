//! What the desktop and the web host share about files: the recent list, the crash-recovery
//! records (one per tab, and an index) and saving in the file's own encoding.

use std::collections::{HashMap, HashSet};

use swarf_interp::Setup;
use swarf_syntax::{Dialect, Encoding};
use swarf_ui::i18n::{Lang, trf};
use swarf_ui::{TabRecord, Workbench};

/// File name extensions the open dialogs offer for programs.
pub const PROGRAM_EXTENSIONS: [&str; 8] = ["nc", "ngc", "tap", "gcode", "cnc", "txt", "ptp", "mpf"];

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

/// Why a file of `len` bytes is not opened: past [`swarf_syntax::MAX_FILE_BYTES`].
pub fn too_large(len: u64) -> Option<String> {
    let (max, size) = (swarf_syntax::MAX_FILE_BYTES >> 20, len.div_ceil(1 << 20));
    let why = || format!("it is {size} MiB; Swarf opens files up to {max} MiB");
    (len > swarf_syntax::MAX_FILE_BYTES).then(why)
}

/// Puts `item` first in `list`, without duplicates, keeping at most [`RECENT_MAX`].
pub fn push_recent(list: &mut Vec<String>, item: String) {
    list.retain(|p| *p != item);
    list.insert(0, item);
    list.truncate(RECENT_MAX);
}

/// Keeps the default dialect, the setup (`SETUP.toml`), the language and recent files.
pub fn store_settings(storage: &mut dyn eframe::Storage, wb: &Workbench, recent: &[String]) {
    storage.set_string(KEY_DIALECT, wb.default_dialect().name().to_string());
    storage.set_string(KEY_LANGUAGE, wb.language().code().to_string());
    match wb.setup_toml() {
        Ok(toml) => storage.set_string(KEY_SETUP, toml),
        Err(e) => log::warn!("cannot keep the setup: {e}"),
    }
    storage.set_string(KEY_RECENT, recent.join("\n"));
}

/// Restores what [`store_settings`] kept (skipping what is unreadable); the recent files.
pub fn restore_settings(storage: &dyn eframe::Storage, wb: &mut Workbench) -> Vec<String> {
    let dialect = storage.get_string(KEY_DIALECT);
    if let Some(dialect) = dialect.and_then(|d| d.parse::<Dialect>().ok()) {
        wb.set_dialect(dialect);
    }
    let lang = storage.get_string(KEY_LANGUAGE);
    if let Some(lang) = lang.and_then(|l| Lang::from_code(&l)) {
        wb.set_language(lang);
    }
    // Read as the settings window left it: a stock or tool it shows refused stays to be mended.
    if let Some(setup) = storage.get_string(KEY_SETUP) {
        match Setup::from_toml(&setup) {
            Ok(setup) => wb.set_setup(setup),
            Err(e) => log::warn!("the saved setup is not readable: {e}"),
        }
    }
    let stored = storage.get_string(KEY_RECENT).unwrap_or_default();
    let lines = stored.lines().filter(|l| !l.is_empty());
    let recent: Vec<String> = lines.map(str::to_string).collect();
    wb.set_recent(recent.clone());
    recent
}

/// `text` in `encoding` when that gives the same text back, else in UTF-8; and the one used.
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

/// When the recovery copy is written or cleared: a moment after an edit, once a generation.
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

/// Header of the recovery index record.
const INDEX_MAGIC: &str = "swarf-recovery 3";

/// The key of the recovery index among the recovery records.
pub const INDEX_KEY: &str = "index";

/// Whether `key` can name a tab's record (`tab-`, letters, digits, `-`): never a path elsewhere.
pub fn is_record_key(key: &str) -> bool {
    key.len() <= 64
        && key.strip_prefix("tab-").is_some_and(|rest| {
            !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-')
        })
}

/// One tab in the recovery index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IndexEntry {
    /// The document's name.
    pub name: String,
    /// Its file, where the host can read it again after a restart (the desktop's full path).
    pub path: Option<String>,
    /// The file's encoding.
    pub encoding: Encoding,
    /// Whether the text had changes that were not saved.
    pub dirty: bool,
    /// The key of the record of the tab's text; `None`: read from its file, or not kept.
    pub record: Option<String>,
    /// The tab's dialect; `None` in an index that names none.
    pub dialect: Option<Dialect>,
}

/// The record listing the open tabs in order, the active one, and the record of each one's text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecoveryIndex {
    /// The tabs, in order.
    pub tabs: Vec<IndexEntry>,
    /// The index of the active tab.
    pub active: usize,
}

/// Tabs read back from the recovery records, ready for [`Workbench::restore_tabs`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Restored {
    /// The tabs, in order.
    pub tabs: Vec<TabRecord>,
    /// The record each tab's text came from (`None`: read from its file).
    pub records: Vec<Option<String>>,
    /// The index of the active tab.
    pub active: usize,
    /// Names of the tabs with unsaved changes that could not be read back.
    pub lost: Vec<String>,
}

impl RecoveryIndex {
    /// The index as one string: a header line (tab-separated: magic, count, active), then a
    /// line per tab (encoding, 1 when unsaved, record key or nothing, name, path, dialect).
    pub fn to_record(&self) -> String {
        let clean = |s: &str| s.replace(['\t', '\n', '\r'], " ");
        let mut out = format!("{INDEX_MAGIC}\t{}\t{}\n", self.tabs.len(), self.active);
        for t in &self.tabs {
            out.push_str(&format!(
                "{}\t{}\t{}\t{}\t{}\t{}\n",
                encoding_name(t.encoding),
                u8::from(t.dirty),
                t.record.as_deref().unwrap_or_default(),
                clean(&t.name),
                clean(t.path.as_deref().unwrap_or_default()),
                t.dialect.map(Dialect::name).unwrap_or_default(),
            ));
        }
        out
    }

    /// Reads an index [`RecoveryIndex::to_record`] wrote (a key [`is_record_key`] refuses: none).
    pub fn from_record(record: &str) -> Option<RecoveryIndex> {
        let mut lines = record.lines();
        let mut head = lines.next()?.split('\t');
        if head.next()? != INDEX_MAGIC {
            return None;
        }
        let count: usize = head.next()?.parse().ok()?;
        let active: usize = head.next()?.parse().ok()?;
        let mut tabs = Vec::new();
        for line in lines.by_ref().take(count) {
            let mut f = line.split('\t');
            let encoding = encoding_of(f.next()?)?;
            let dirty = f.next()? == "1";
            let record = Some(f.next()?).filter(|k| is_record_key(k));
            let name = f.next()?.to_string();
            let path = f.next()?;
            let dialect = f.next().and_then(|d| d.parse().ok());
            tabs.push(IndexEntry {
                name,
                path: (!path.is_empty()).then(|| path.to_string()),
                encoding,
                dirty,
                record: record.map(str::to_string),
                dialect,
            });
        }
        (tabs.len() == count && active < count).then_some(RecoveryIndex { tabs, active })
    }

    /// The keys of the records the index names.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.tabs.iter().filter_map(|t| t.record.as_deref())
    }

    /// The tabs to restore: an unsaved one from its record (else named in `lost`, from its file),
    /// a saved one from its file where `read_file` can read it, else its record; or left out.
    pub fn restore(
        &self,
        mut read_record: impl FnMut(&str) -> Option<String>,
        mut read_file: impl FnMut(&str) -> Option<(String, Encoding)>,
    ) -> Restored {
        let mut out = Restored::default();
        for (i, entry) in self.tabs.iter().enumerate() {
            if i == self.active {
                out.active = out.tabs.len();
            }
            let mut record = || {
                let text = read_record(entry.record.as_deref()?)?;
                Some((text, entry.encoding, entry.dirty, entry.record.clone()))
            };
            let mut file = || {
                let (text, encoding) = read_file(entry.path.as_deref()?)?;
                Some((text, encoding, false, None))
            };
            let found = if entry.dirty {
                record().or_else(|| {
                    out.lost.push(entry.name.clone());
                    file()
                })
            } else {
                file().or_else(record)
            };
            if let Some((text, encoding, dirty, key)) = found {
                out.tabs.push(TabRecord {
                    name: entry.name.clone(),
                    path: entry.path.clone(),
                    encoding,
                    text,
                    dirty,
                    dialect: entry.dialect,
                });
                out.records.push(key);
            }
        }
        out.active = out.active.min(out.tabs.len().saturating_sub(1));
        out
    }
}

/// An open tab as the recovery records see it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TabState {
    /// The document's id ([`swarf_ui::Document::id`]).
    pub id: u64,
    /// The revision of its text ([`swarf_ui::Document::revision`]).
    pub revision: u64,
    /// The tab as the index lists it, no record chosen yet.
    pub entry: IndexEntry,
}

impl TabState {
    /// The workbench's tabs and the active one; `with_paths`: whether a path can be read again.
    pub fn of(wb: &Workbench, with_paths: bool) -> (Vec<TabState>, usize) {
        let docs = wb.tab_documents().into_iter().enumerate();
        let tabs = docs.map(|(i, d)| TabState {
            id: d.id(),
            revision: d.revision(),
            entry: IndexEntry {
                name: d.name.clone(),
                path: if with_paths { d.path.clone() } else { None },
                encoding: d.encoding,
                dirty: d.is_unsaved(),
                record: None,
                dialect: Some(wb.tab_dialect(i).unwrap_or_default()),
            },
        });
        (tabs.collect(), wb.active_tab())
    }

    /// Whether the tab's text needs a record: it is unsaved, or has no file to read again.
    pub fn needs_record(&self) -> bool {
        self.entry.dirty || self.entry.path.is_none()
    }
}

/// A tab's text to write as a record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecordWrite {
    /// The tab's position.
    pub tab: usize,
    /// The key to write it under (new: a record is never overwritten).
    pub key: String,
}

/// What a round of recovery writes comes to: the index to store once the records are written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Round {
    /// The index.
    pub index: RecoveryIndex,
    /// The index as a record ([`RecoveryIndex::to_record`]).
    pub record: String,
    /// Whether it differs from the index stored.
    pub changed: bool,
    /// The tabs whose current text is not kept, with why.
    pub failed: Vec<(String, String)>,
    /// Document id → (revision, key) of the record the index names for it.
    kept: HashMap<u64, (u64, String)>,
    /// The keys of the records written (or tried) in the round.
    written: Vec<String>,
}

/// What this host knows the recovery records hold: which a round writes, which may go.
#[derive(Debug, Clone, Default)]
pub struct RecoveryBook {
    /// Starts every key this host makes, unique to the run.
    prefix: String,
    /// Document id → (revision, key) of the record the stored index names for it.
    kept: HashMap<u64, (u64, String)>,
    /// The index record stored, when one is.
    stored: Option<String>,
    /// Names of the tabs last reported as not kept.
    failing: Vec<String>,
    /// The records this host wrote or read and has not removed yet.
    owned: HashSet<String>,
}

impl RecoveryBook {
    /// A book for a run whose keys start with `run`'s letters and digits (a time stamp, say).
    pub fn new(run: &str) -> RecoveryBook {
        let run = run.chars().filter(char::is_ascii_alphanumeric);
        let run: String = run.take(24).collect();
        RecoveryBook {
            prefix: format!("tab-{run}"),
            ..RecoveryBook::default()
        }
    }

    /// The records to write for `tabs`: of those that need one, whose text changed since.
    pub fn plan(&self, tabs: &[TabState]) -> Vec<RecordWrite> {
        let kept = |t: &TabState| self.kept.get(&t.id).map(|(rev, _)| *rev);
        let due = tabs.iter().enumerate();
        let due = due.filter(|(_, t)| t.needs_record() && kept(t) != Some(t.revision));
        let key = |t: &TabState| format!("{}-{}", self.prefix, t.revision);
        due.map(|(tab, t)| RecordWrite { tab, key: key(t) })
            .collect()
    }

    /// The index once `writes` ([`RecoveryBook::plan`] of `tabs`) ended with `results`: a tab
    /// whose write failed keeps an earlier record if any, and is named in [`Round::failed`].
    pub fn compose(
        &self,
        tabs: &[TabState],
        active: usize,
        writes: &[RecordWrite],
        results: &[Result<(), String>],
    ) -> Round {
        let mut kept = HashMap::new();
        let mut failed = Vec::new();
        let mut entries = Vec::with_capacity(tabs.len());
        for (i, t) in tabs.iter().enumerate() {
            let earlier = self.kept.get(&t.id);
            let write = writes.iter().position(|w| w.tab == i);
            let record = match write {
                _ if !t.needs_record() => None,
                None => earlier.cloned(),
                Some(w) => match results.get(w) {
                    Some(Ok(())) => Some((t.revision, writes[w].key.clone())),
                    result => {
                        let why = result.and_then(|r| r.clone().err());
                        let why = why.unwrap_or_else(|| "not written".to_string());
                        failed.push((t.entry.name.clone(), why));
                        earlier.cloned()
                    }
                },
            };
            entries.push(IndexEntry {
                record: record.as_ref().map(|(_, key)| key.clone()),
                ..t.entry.clone()
            });
            if let Some(record) = record {
                kept.insert(t.id, record);
            }
        }
        let index = RecoveryIndex {
            tabs: entries,
            active: active.min(tabs.len().saturating_sub(1)),
        };
        let record = index.to_record();
        Round {
            changed: self.stored.as_deref() != Some(record.as_str()),
            index,
            record,
            failed,
            kept,
            written: writes.iter().map(|w| w.key.clone()).collect(),
        }
    }

    /// The tabs that need a record, with `why` (none is kept when the index is not stored).
    pub fn all_failed(tabs: &[TabState], why: &str) -> Vec<(String, String)> {
        let due = tabs.iter().filter(|t| t.needs_record());
        due.map(|t| (t.entry.name.clone(), why.to_string()))
            .collect()
    }

    /// Ends a round: when its index is `stored` its records are kept, else those written are stale.
    pub fn commit(&mut self, round: Round, stored: bool) {
        self.owned.extend(round.written);
        if stored {
            self.kept = round.kept;
            self.stored = Some(round.record);
        }
    }

    /// Whether the stored index names the record `key`.
    pub fn keeps(&self, key: &str) -> bool {
        self.kept.values().any(|(_, k)| k == key)
    }

    /// The records of this host the stored index no longer names, to remove (each once).
    pub fn take_stale(&mut self) -> Vec<String> {
        let owned = self.owned.iter().cloned();
        let mut stale: Vec<String> = owned.filter(|key| !self.keeps(key)).collect();
        for key in &stale {
            self.owned.remove(key);
        }
        stale.sort_unstable();
        stale
    }

    /// Whether this host stored an index (and records) that are not yet removed.
    pub fn holds_records(&self) -> bool {
        self.stored.is_some()
    }

    /// Every record and the index were removed.
    pub fn cleared(&mut self) {
        self.kept.clear();
        self.owned.clear();
        self.stored = None;
        self.failing.clear();
    }

    /// The restored `tabs` came from `records` named by the stored `index`: not written again till
    /// they change; the records `index` names are this host's, to remove once none names them.
    pub fn adopt(&mut self, tabs: &[TabState], records: &[Option<String>], index: &str) {
        self.kept = tabs
            .iter()
            .zip(records)
            .filter_map(|(t, key)| Some((t.id, (t.revision, key.clone()?))))
            .collect();
        if let Some(stored) = RecoveryIndex::from_record(index) {
            self.owned.extend(stored.keys().map(str::to_string));
        }
        self.stored = Some(index.to_string());
    }

    /// The status bar's message after a round: the tabs `failed` and why, or those kept again.
    pub fn report(&mut self, failed: &[(String, String)], tabs: &[TabState]) -> Option<String> {
        if let Some((_, why)) = failed.first() {
            let names: Vec<String> = failed.iter().map(|(name, _)| name.clone()).collect();
            let message = trf("Not kept for recovery: {} ({})", &[&names.join(", "), why]);
            self.failing = names;
            return Some(message);
        }
        let open = |n: &str| tabs.iter().any(|t| t.entry.name == n && t.needs_record());
        let failing = self.failing.iter().map(String::as_str);
        let again: Vec<&str> = failing.filter(|name| open(name)).collect();
        let message =
            (!again.is_empty()).then(|| trf("Kept for recovery again: {}", &[&again.join(", ")]));
        self.failing.clear();
        message
    }
}

/// Adds to the status bar's message the tabs whose unsaved changes could not be read back.
pub fn report_lost(wb: &mut Workbench, lost: &[String]) {
    if lost.is_empty() {
        return;
    }
    let line = trf("Could not recover {}", &[&lost.join(", ")]);
    let message = wb.message().map(|m| format!("{m}; {line}"));
    wb.set_message(message.unwrap_or(line));
}

/// An encoding's name in the recovery index: its [`Encoding::name`] in lower case, letters and
/// digits only (`utf8bom`, `gb18030`).
fn encoding_name(e: Encoding) -> String {
    let name = e.name().chars().filter(char::is_ascii_alphanumeric);
    name.map(|c| c.to_ascii_lowercase()).collect()
}

fn encoding_of(name: &str) -> Option<Encoding> {
    Encoding::ALL
        .into_iter()
        .find(|&e| encoding_name(e) == name)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn encodings_keep_their_names_in_the_index() {
        let names: Vec<String> = Encoding::ALL.into_iter().map(encoding_name).collect();
        let kept = [
            "utf8", "utf8bom", "gb18030", "big5", "utf16le", "utf16be", "utf32le", "utf32be",
        ];
        assert_eq!(names, kept);
        for e in Encoding::ALL {
            assert_eq!(encoding_of(&encoding_name(e)), Some(e));
        }
    }

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

    fn state(id: u64, revision: u64, name: &str, path: Option<&str>, dirty: bool) -> TabState {
        TabState {
            id,
            revision,
            entry: IndexEntry {
                name: name.into(),
                path: path.map(str::to_string),
                encoding: Encoding::Utf8,
                dirty,
                record: None,
                dialect: Some(Dialect::Fanuc),
            },
        }
    }

    /// Runs a round in which every write ends with `result(key)`; returns the round's index
    /// and the keys written.
    fn round(
        book: &mut RecoveryBook,
        tabs: &[TabState],
        active: usize,
        result: impl Fn(&str) -> Result<(), String>,
    ) -> (Round, Vec<String>) {
        let writes = book.plan(tabs);
        let results: Vec<_> = writes.iter().map(|w| result(&w.key)).collect();
        let round = book.compose(tabs, active, &writes, &results);
        (round, writes.into_iter().map(|w| w.key).collect())
    }

    #[test]
    fn indexes_read_back_and_damaged_ones_are_refused() {
        let index = RecoveryIndex {
            tabs: vec![
                IndexEntry {
                    name: "a\tb.nc".into(),
                    path: Some("/home/me/a b.nc".into()),
                    encoding: Encoding::Gb18030,
                    dirty: true,
                    record: Some("tab-1a2b-7".into()),
                    dialect: Some(Dialect::Syntec),
                },
                IndexEntry {
                    name: "O1234.nc".into(),
                    path: None,
                    encoding: Encoding::Utf8,
                    dirty: false,
                    record: None,
                    dialect: None,
                },
            ],
            active: 1,
        };
        let record = index.to_record();
        let back = RecoveryIndex::from_record(&record).unwrap();
        // A tab in a name would split the line: it is kept as a space.
        assert_eq!(back.tabs[0].name, "a b.nc");
        assert_eq!(back.tabs[1], index.tabs[1]);
        assert_eq!(back.tabs[0].record.as_deref(), Some("tab-1a2b-7"));
        assert_eq!(back.tabs[0].dialect, Some(Dialect::Syntec));
        assert_eq!(back.active, 1);
        // An index line that names no dialect reads as none.
        let plain = "swarf-recovery 3\t1\t0\nutf8\t0\t\ta.nc\t\n";
        assert_eq!(
            RecoveryIndex::from_record(plain).unwrap().tabs[0].dialect,
            None
        );
        assert_eq!(back.keys().collect::<Vec<_>>(), ["tab-1a2b-7"]);
        // Cut short, out of range or of another kind: nothing.
        assert_eq!(
            RecoveryIndex::from_record(&record[..record.len() - 12]),
            None
        );
        assert_eq!(
            RecoveryIndex::from_record(&record.replacen("\t2\t1\n", "\t2\t2\n", 1)),
            None
        );
        assert_eq!(RecoveryIndex::from_record("swarf-recovery 2\t1\t0\n"), None);
        // A key that could name a file elsewhere is no record.
        let evil = record.replace("tab-1a2b-7", "../../etc/passwd");
        assert_eq!(
            RecoveryIndex::from_record(&evil).unwrap().tabs[0].record,
            None
        );
        for key in ["index", "tab-", "tab-a/b", "tab-a.nc", "x-1", ""] {
            assert!(!is_record_key(key), "{key}");
        }
        assert!(is_record_key("tab-19af-12"));
    }

    #[test]
    fn only_tabs_whose_text_changed_are_written_and_the_rest_is_removed() {
        let mut book = RecoveryBook::new("run/1");
        let mut tabs = vec![
            state(1, 10, "big.nc", None, false),
            state(2, 20, "part.nc", Some("/p/part.nc"), false),
            state(3, 30, "small.nc", Some("/p/small.nc"), true),
        ];
        // The clean tab with a file needs no record; the others do.
        let (first, keys) = round(&mut book, &tabs, 2, |_| Ok(()));
        assert_eq!(keys, ["tab-run1-10", "tab-run1-30"]);
        assert!(first.failed.is_empty() && first.changed);
        let records: Vec<_> = first.index.tabs.iter().map(|t| t.record.clone()).collect();
        assert_eq!(
            records,
            [Some("tab-run1-10".into()), None, Some("tab-run1-30".into())]
        );
        book.commit(first, true);
        assert!(book.take_stale().is_empty());
        // Nothing changed: nothing to write, the same index.
        let (same, keys) = round(&mut book, &tabs, 2, |_| Ok(()));
        assert!(keys.is_empty() && !same.changed);
        book.commit(same, true);
        // The small tab changed: its record alone is written, the earlier one goes.
        tabs[2].revision = 31;
        let (next, keys) = round(&mut book, &tabs, 2, |_| Ok(()));
        assert_eq!(keys, ["tab-run1-31"]);
        book.commit(next, true);
        assert_eq!(book.take_stale(), ["tab-run1-30"]);
        // Saved to its file: no record any more. Closed: neither.
        tabs[2].entry.dirty = false;
        tabs.remove(0);
        let (saved, keys) = round(&mut book, &tabs, 1, |_| Ok(()));
        assert!(keys.is_empty());
        assert_eq!(saved.index.keys().count(), 0);
        book.commit(saved, true);
        assert_eq!(book.take_stale(), ["tab-run1-10", "tab-run1-31"]);
        assert!(book.holds_records());
        book.cleared();
        assert!(!book.holds_records());
    }

    #[test]
    fn a_write_that_fails_is_named_keeps_the_earlier_text_and_is_tried_again() {
        let mut book = RecoveryBook::new("r");
        let mut tabs = vec![
            state(1, 10, "big.nc", None, false),
            state(2, 20, "small.nc", None, true),
        ];
        let (first, _) = round(&mut book, &tabs, 1, |_| Ok(()));
        book.commit(first, true);
        // The big tab changed and is now too big to keep; the small one changed too.
        tabs[0].revision = 11;
        tabs[1].revision = 21;
        let quota = |key: &str| {
            if key.ends_with("-11") {
                Err("QuotaExceededError".to_string())
            } else {
                Ok(())
            }
        };
        let (second, keys) = round(&mut book, &tabs, 1, quota);
        assert_eq!(keys, ["tab-r-11", "tab-r-21"]);
        assert_eq!(
            second.failed,
            [("big.nc".to_string(), "QuotaExceededError".to_string())]
        );
        // The big tab keeps its earlier record, the small one has its new one.
        let records: Vec<_> = second.index.keys().collect();
        assert_eq!(records, ["tab-r-10", "tab-r-21"]);
        let failed = second.failed.clone();
        book.commit(second, true);
        assert_eq!(book.take_stale(), ["tab-r-11", "tab-r-20"]);
        assert_eq!(
            book.report(&failed, &tabs).as_deref(),
            Some("Not kept for recovery: big.nc (QuotaExceededError)")
        );
        // Tried again at the next round, and said so once it is kept.
        let (third, keys) = round(&mut book, &tabs, 1, |_| Ok(()));
        assert_eq!(keys, ["tab-r-11"]);
        let failed = third.failed.clone();
        book.commit(third, true);
        assert_eq!(
            book.report(&failed, &tabs).as_deref(),
            Some("Kept for recovery again: big.nc")
        );
        assert_eq!(book.report(&[], &tabs), None);
    }

    #[test]
    fn an_index_that_could_not_be_stored_leaves_the_earlier_one_in_force() {
        let mut book = RecoveryBook::new("r");
        let mut tabs = vec![state(1, 10, "a.nc", None, true)];
        let (first, _) = round(&mut book, &tabs, 0, |_| Ok(()));
        book.commit(first, true);
        tabs[0].revision = 11;
        let (second, _) = round(&mut book, &tabs, 0, |_| Ok(()));
        assert_eq!(
            RecoveryBook::all_failed(&tabs, "disk full"),
            [("a.nc".to_string(), "disk full".to_string())]
        );
        book.commit(second, false);
        // The record written for the index that was not stored goes; the earlier one stays.
        assert_eq!(book.take_stale(), ["tab-r-11"]);
        assert!(book.keeps("tab-r-10"));
        // And the text is written again at the next round.
        let (_, keys) = round(&mut book, &tabs, 0, |_| Ok(()));
        assert_eq!(keys, ["tab-r-11"]);
    }

    #[test]
    fn restoring_reads_records_and_files_and_names_what_is_lost() {
        let entry =
            |name: &str, path: Option<&str>, dirty: bool, record: Option<&str>| IndexEntry {
                name: name.into(),
                path: path.map(str::to_string),
                encoding: Encoding::Utf8,
                dirty,
                record: record.map(str::to_string),
                dialect: Some(Dialect::Lnc),
            };
        let index = RecoveryIndex {
            tabs: vec![
                entry("gone.nc", Some("/gone.nc"), false, None),
                entry("lost.nc", None, true, Some("tab-x-1")),
                entry("file.nc", Some("/file.nc"), false, None),
                entry("edited.nc", Some("/edited.nc"), true, Some("tab-x-2")),
                entry("example.nc", None, false, Some("tab-x-3")),
            ],
            active: 3,
        };
        let records = HashMap::from([
            ("tab-x-2".to_string(), "G0 X2 (edited)\n".to_string()),
            ("tab-x-3".to_string(), "G0 X3\n".to_string()),
        ]);
        let files = HashMap::from([
            ("/file.nc".to_string(), "G0 X1\n".to_string()),
            ("/edited.nc".to_string(), "G0 X2\n".to_string()),
        ]);
        let restored = index.restore(
            |key| records.get(key).cloned(),
            |path| files.get(path).map(|t| (t.clone(), Encoding::Big5)),
        );
        let got: Vec<_> = restored
            .tabs
            .iter()
            .map(|t| (t.name.as_str(), t.text.as_str(), t.dirty))
            .collect();
        assert_eq!(
            got,
            [
                ("file.nc", "G0 X1\n", false),
                ("edited.nc", "G0 X2 (edited)\n", true),
                ("example.nc", "G0 X3\n", false),
            ]
        );
        // Read from the file: its encoding is the file's.
        assert_eq!(restored.tabs[0].encoding, Encoding::Big5);
        assert_eq!(
            restored.records,
            [
                None,
                Some("tab-x-2".to_string()),
                Some("tab-x-3".to_string())
            ]
        );
        assert_eq!(restored.active, 1);
        assert_eq!(restored.lost, ["lost.nc"]);
    }

    #[test]
    fn recovered_tabs_are_not_written_again_until_they_change() {
        let mut wb = Workbench::default();
        wb.open_document("a.nc", "G0 X1\n", Encoding::Utf8);
        wb.set_text("G0 X2\n");
        let (tabs, active) = TabState::of(&wb, false);
        let mut book = RecoveryBook::new("one");
        let (first, _) = round(&mut book, &tabs, active, |_| Ok(()));
        let (record, index) = (first.record.clone(), first.index.clone());
        book.commit(first, true);
        // The next run reads them back.
        let restored = index.restore(
            |key| {
                let i = index
                    .tabs
                    .iter()
                    .position(|t| t.record.as_deref() == Some(key))?;
                wb.tab_text(i)
            },
            |_| None,
        );
        let mut next = Workbench::default();
        next.restore_tabs(restored.tabs, restored.active);
        assert_eq!(next.message(), Some("Recovered unsaved changes of a.nc"));
        let (tabs, active) = TabState::of(&next, false);
        let mut book = RecoveryBook::new("two");
        book.adopt(&tabs, &restored.records, &record);
        let (again, keys) = round(&mut book, &tabs, active, |_| Ok(()));
        assert!(keys.is_empty(), "{keys:?}");
        assert!(!again.changed);
        // An edit writes that tab alone.
        next.set_text("G0 X3\n");
        let (tabs, active) = TabState::of(&next, false);
        let (_, keys) = round(&mut book, &tabs, active, |_| Ok(()));
        assert_eq!(keys.len(), 1);
        assert!(keys[0].starts_with("tab-two-"), "{keys:?}");
    }
}
