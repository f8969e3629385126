//! Interface languages: the View menu switches them live, the Chinese ones ask for the CJK
//! font once, and no English string of the table is left on screen in Chinese.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable as _, by};
use swarf_ui::i18n::{self, Lang};
use swarf_ui::{HostRequest, Workbench};

/// Where Debian's fonts-wqy-microhei puts its font (the web build copies it from there).
const SYSTEM_CJK_FONT: &str = "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc";

fn harness(wb: Workbench) -> Harness<'static, Workbench> {
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .build_ui_state(|ui, wb: &mut Workbench| wb.ui(ui), wb);
    harness.run();
    harness
}

fn labels(harness: &Harness<'static, Workbench>) -> Vec<String> {
    harness
        .query_all(by().include_labels().predicate(|_| true))
        .filter_map(|n| n.accesskit_node().label())
        .collect()
}

#[test]
fn the_view_menu_switches_the_language_and_asks_for_the_font_once() {
    let mut harness = harness(Workbench::default());
    // Until the font is in, Chinese shows boxes, as the app does while it loads.
    harness
        .ctx
        .set_missing_glyph_policy(egui::MissingGlyphPolicy::Tofu);
    harness.get_by_label("View").click();
    harness.run();
    harness.get_by_label("Language").click();
    harness.run();
    harness.get_by_label("简体中文").click();
    harness.run();
    assert_eq!(harness.state().language(), Lang::ZhHans);
    assert_eq!(
        harness.state_mut().take_requests(),
        [HostRequest::LoadCjkFont]
    );
    harness.run();
    harness.get_by_label("文件");
    harness.get_by_label("编辑");
    assert!(harness.query_by_label("File").is_none());
    harness.get_by_label_contains("正在加载中文字体");
    // Bytes that are no font are refused with a message; asking again asks the host again.
    let ctx = harness.ctx.clone();
    assert!(
        !harness
            .state_mut()
            .add_cjk_font(&ctx, b"404 Not Found".to_vec())
    );
    assert!(!harness.state().has_cjk_font());
    harness.state_mut().set_language(Lang::ZhHant);
    assert_eq!(
        harness.state_mut().take_requests(),
        [HostRequest::LoadCjkFont]
    );
    harness.run();
    harness.get_by_label("檔案");
    // A real font, where the system has one.
    if let Ok(bytes) = std::fs::read(SYSTEM_CJK_FONT) {
        assert!(harness.state_mut().add_cjk_font(&ctx, bytes));
        assert!(harness.state().has_cjk_font());
        // From now on a character without a glyph fails the test.
        harness
            .ctx
            .set_missing_glyph_policy(egui::MissingGlyphPolicy::Panic);
        harness.run();
        // The glyphs of the labels now come from the font: 檔 is laid out as a real glyph.
        let found = harness
            .ctx
            .fonts_mut(|f| f.has_glyphs(&egui::FontId::proportional(14.0), "檔案编辑"));
        assert!(found, "the CJK font gives no glyphs");
        harness.state_mut().set_language(Lang::ZhHans);
        assert!(harness.state_mut().take_requests().is_empty());
    }
    // Back to English.
    harness.state_mut().set_language(Lang::En);
    harness.run();
    harness.get_by_label("File");
    assert_eq!(i18n::current(), Lang::En);
}

#[test]
fn nothing_on_screen_stays_english_in_chinese() {
    let mut wb = Workbench::default();
    wb.set_text("G90 G21\nG0 X0 Y0 Z5\nG1 X10 Y$ F100\nM30\n");
    wb.finish_analysis();
    let mut harness = harness(wb);
    // With the system's CJK font every character must have a glyph; without one, boxes.
    match std::fs::read(SYSTEM_CJK_FONT) {
        Ok(bytes) => {
            let ctx = harness.ctx.clone();
            assert!(harness.state_mut().add_cjk_font(&ctx, bytes));
        }
        Err(_) => harness
            .ctx
            .set_missing_glyph_policy(egui::MissingGlyphPolicy::Tofu),
    }
    for lang in [Lang::ZhHans, Lang::ZhHant] {
        harness.state_mut().set_language(lang);
        harness.run();
        // The settings window and the find bar too.
        harness.get_by_label(i18n::tr_in(lang, "Settings…")).click();
        harness.run();
        harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::H);
        harness.run();
        let shown = labels(&harness);
        let english: Vec<&str> = i18n::table().map(|(en, _, _)| en).collect();
        let left: Vec<&String> = shown
            .iter()
            .filter(|l| english.contains(&l.as_str()))
            .collect();
        assert!(left.is_empty(), "{lang:?}: still English: {left:?}");
        // The status bar and the problems header are translated.
        let header = i18n::tr_in(lang, "Problems ({})")
            .replace("{})", "")
            .replace("{}）", "");
        harness.get_by_label_contains(&header);
        harness.get_by_label_contains(&i18n::trf("{} blocks", &[&4]));
        let _ = harness.state_mut().take_requests();
    }
}
