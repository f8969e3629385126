//! Interface languages: English, Simplified and Traditional Chinese. Every visible string is
//! English in the code, looked up with [`tr`] (or [`trf`], with `{}` placeholders) in a table of
//! its three forms, in the thread's language. Chinese needs a CJK font ([`add_cjk_font`]).

use std::cell::Cell;
use std::collections::HashMap;
use std::fmt::Display;
use std::sync::{Arc, LazyLock};

/// An interface language.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Lang {
    /// English (the strings as written in the code).
    #[default]
    En,
    /// Simplified Chinese.
    ZhHans,
    /// Traditional Chinese.
    ZhHant,
}

impl Lang {
    /// Every language, in the order the menu lists them.
    pub const ALL: [Lang; 3] = [Lang::En, Lang::ZhHans, Lang::ZhHant];

    /// The BCP 47 tag kept in the settings (`en`, `zh-Hans`, `zh-Hant`).
    pub fn code(self) -> &'static str {
        ["en", "zh-Hans", "zh-Hant"][self as usize]
    }

    /// The language of a tag written by [`Lang::code`] (also `zh-CN`, `zh-TW` …).
    pub fn from_code(code: &str) -> Option<Lang> {
        let code = code.trim().to_ascii_lowercase();
        match code.as_str() {
            "en" => Some(Lang::En),
            "zh-hans" | "zh-cn" | "zh-sg" | "zh" => Some(Lang::ZhHans),
            "zh-hant" | "zh-tw" | "zh-hk" | "zh-mo" => Some(Lang::ZhHant),
            _ => None,
        }
    }

    /// The language's name in itself, as the language menu shows it.
    pub fn native_name(self) -> &'static str {
        ["English", "简体中文", "繁體中文"][self as usize]
    }
}

thread_local! {
    static CURRENT: Cell<Lang> = const { Cell::new(Lang::En) };
}

/// Makes `lang` the language [`tr`] answers in on this thread.
pub fn set_current(lang: Lang) {
    CURRENT.with(|c| c.set(lang));
}

/// The language [`tr`] answers in on this thread.
pub fn current() -> Lang {
    CURRENT.with(Cell::get)
}

/// `english` in the current language (itself when the table has no entry for it).
pub fn tr(english: &'static str) -> &'static str {
    tr_in(current(), english)
}

/// `english` in `lang` (itself when the table has no entry for it).
pub fn tr_in(lang: Lang, english: &'static str) -> &'static str {
    if lang == Lang::En {
        return english;
    }
    let (hans, hant) = INDEX.get(english).copied().unwrap_or((english, english));
    if lang == Lang::ZhHans { hans } else { hant }
}

/// `template` in the current language with its `{}` placeholders replaced by `args` in order.
pub fn trf(template: &'static str, args: &[&dyn Display]) -> String {
    let template = tr(template);
    let mut out = String::with_capacity(template.len() + 8 * args.len());
    let mut args = args.iter();
    let mut rest = template;
    while let Some(at) = rest.find("{}") {
        out.push_str(&rest[..at]);
        if let Some(a) = args.next() {
            out.push_str(&a.to_string());
        }
        rest = &rest[at + 2..];
    }
    out.push_str(rest);
    out
}

/// The table's Chinese forms by their English.
static INDEX: LazyLock<HashMap<&str, (&str, &str)>> =
    LazyLock::new(|| table().map(|(en, s, t)| (en, (s, t))).collect());

/// The name egui knows the CJK font by.
pub const CJK_FONT_NAME: &str = "swarf-cjk";

/// Adds a CJK font (a `.ttf`, `.otf` or `.ttc` file's bytes) to `ctx` as the last fallback of
/// both families, so Chinese text gets glyphs; `false` when the bytes are no font.
pub fn add_cjk_font(ctx: &egui::Context, bytes: Vec<u8>) -> bool {
    let blob: egui::epaint::text::Blob = Arc::new(bytes);
    let data = egui::FontData::from_blob(blob, 0);
    // A TrueType, OpenType or TrueType collection file.
    let magic = data.bytes().get(..4);
    let font = matches!(magic, Some([0, 1, 0, 0] | b"OTTO" | b"ttcf" | b"true"));
    if data.bytes().len() < 12 || !font {
        return false;
    }
    use egui::epaint::text::{FontInsert, FontPriority, InsertFontFamily};
    let families = [egui::FontFamily::Proportional, egui::FontFamily::Monospace];
    let last = families.map(|family| InsertFontFamily {
        family,
        priority: FontPriority::Lowest,
    });
    ctx.add_font(FontInsert::new(CJK_FONT_NAME, data, last.to_vec()));
    true
}

/// The translations, a line each: English, Simplified, Traditional Chinese, tab-separated.
const TABLE: &str = include_str!("i18n.tsv");

/// Every entry of the translation table: (English, Simplified Chinese, Traditional Chinese).
pub fn table() -> impl Iterator<Item = (&'static str, &'static str, &'static str)> {
    TABLE
        .lines()
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .filter_map(|l| {
            let mut f = l.split('\t');
            Some((f.next()?, f.next()?, f.next()?))
        })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;

    #[test]
    fn every_entry_has_three_forms_with_the_same_placeholders() {
        let mut seen = std::collections::HashSet::new();
        for line in TABLE
            .lines()
            .filter(|l| !l.is_empty() && !l.starts_with('#'))
        {
            assert_eq!(line.split('\t').count(), 3, "`{line}` is not three forms");
        }
        for (en, hans, hant) in table() {
            assert!(seen.insert(en), "`{en}` is in the table twice");
            for form in [hans, hant] {
                assert!(!form.trim().is_empty(), "`{en}` lacks a translation");
                assert_eq!(
                    form.matches("{}").count(),
                    en.matches("{}").count(),
                    "`{en}` → `{form}`: the placeholders differ"
                );
                assert_ne!(form, en, "`{en}` is not translated");
            }
        }
    }

    #[test]
    fn every_string_the_interface_looks_up_is_in_the_table() {
        let sources = [
            include_str!("workbench/mod.rs"),
            include_str!("workbench/dialogs.rs"),
            include_str!("workbench/edit.rs"),
            include_str!("workbench/find.rs"),
            include_str!("workbench/menus.rs"),
            include_str!("workbench/panels.rs"),
            include_str!("workbench/tabs.rs"),
            include_str!("settings.rs"),
            include_str!("backplot.rs"),
            include_str!("backplot/playback.rs"),
            include_str!("editor.rs"),
        ];
        let mut looked_up = 0;
        for source in sources {
            for call in ["tr(\"", "trf(\n", "trf(\"", "Command(\""] {
                for (at, _) in source.match_indices(call) {
                    let rest = &source[at + call.len()..];
                    let rest = if call == "trf(\n" {
                        let Some(open) = rest.find('"') else { continue };
                        &rest[open + 1..]
                    } else {
                        rest
                    };
                    let Some(end) = rest.find('"') else { continue };
                    let key = &rest[..end];
                    looked_up += 1;
                    assert!(
                        INDEX.contains_key(key),
                        "`{key}` is looked up but has no translations"
                    );
                }
            }
        }
        assert!(looked_up > 100, "only {looked_up} strings found");
    }

    #[test]
    fn lookups_follow_the_current_language_and_fill_placeholders() {
        set_current(Lang::ZhHans);
        assert_eq!(tr("File"), "文件");
        assert_eq!(
            trf("{} errors, {} warnings", &[&2, &0]),
            "2 个错误，0 个警告"
        );
        set_current(Lang::ZhHant);
        assert_eq!(tr("File"), "檔案");
        assert_eq!(tr("not in the table"), "not in the table");
        set_current(Lang::En);
        assert_eq!(trf("{} blocks", &[&12]), "12 blocks");
        for lang in Lang::ALL {
            assert_eq!(Lang::from_code(lang.code()), Some(lang));
        }
        assert_eq!(Lang::from_code("zh-TW"), Some(Lang::ZhHant));
        assert_eq!(Lang::from_code("fr"), None);
    }

    #[test]
    fn only_font_files_are_added() {
        let ctx = egui::Context::default();
        assert!(!add_cjk_font(&ctx, b"<html>not found</html>".to_vec()));
        assert!(!add_cjk_font(&ctx, Vec::new()));
    }
}
