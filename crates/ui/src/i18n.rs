//! Interface languages: English, Simplified Chinese and Traditional Chinese.
//!
//! Every visible string of the interface is written in English in the code and looked up with
//! [`tr`] (or [`trf`] for one with `{}` placeholders) in one table holding its three forms.
//! The language is per thread (the interface runs on one), set by the workbench each frame.
//! egui's built-in fonts have no CJK glyphs: a Chinese language needs a CJK font added with
//! [`add_cjk_font`] (the web page fetches it, the desktop reads it from the system's fonts).

use std::cell::Cell;
use std::collections::HashMap;
use std::fmt::Display;
use std::sync::{Arc, OnceLock};

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
        match self {
            Lang::En => "en",
            Lang::ZhHans => "zh-Hans",
            Lang::ZhHant => "zh-Hant",
        }
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
        match self {
            Lang::En => "English",
            Lang::ZhHans => "简体中文",
            Lang::ZhHant => "繁體中文",
        }
    }

    /// Whether the language needs a CJK font.
    pub fn needs_cjk_font(self) -> bool {
        self != Lang::En
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
    match index().get(english) {
        Some(&(hans, hant)) => match lang {
            Lang::ZhHans => hans,
            Lang::ZhHant | Lang::En => hant,
        },
        None => english,
    }
}

/// `template` in the current language with its `{}` placeholders replaced by `args` in order.
pub fn trf(template: &'static str, args: &[&dyn Display]) -> String {
    fill(tr(template), args)
}

fn fill(template: &str, args: &[&dyn Display]) -> String {
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

fn index() -> &'static HashMap<&'static str, (&'static str, &'static str)> {
    static INDEX: OnceLock<HashMap<&'static str, (&'static str, &'static str)>> = OnceLock::new();
    INDEX.get_or_init(|| TABLE.iter().map(|&(en, s, t)| (en, (s, t))).collect())
}

/// The name egui knows the CJK font by.
pub const CJK_FONT_NAME: &str = "swarf-cjk";

/// Adds a CJK font (a `.ttf`, `.otf` or `.ttc` file's bytes) to `ctx` as the last fallback of
/// the proportional and monospace families, so Chinese text gets glyphs; `false` when the
/// bytes are no font.
pub fn add_cjk_font(ctx: &egui::Context, bytes: Vec<u8>) -> bool {
    let blob: egui::epaint::text::Blob = Arc::new(bytes);
    let data = egui::FontData::from_blob(blob, 0);
    if data.bytes().len() < 12 || !is_font(data.bytes()) {
        return false;
    }
    ctx.add_font(egui::epaint::text::FontInsert::new(
        CJK_FONT_NAME,
        data,
        vec![
            egui::epaint::text::InsertFontFamily {
                family: egui::FontFamily::Proportional,
                priority: egui::epaint::text::FontPriority::Lowest,
            },
            egui::epaint::text::InsertFontFamily {
                family: egui::FontFamily::Monospace,
                priority: egui::epaint::text::FontPriority::Lowest,
            },
        ],
    ));
    true
}

/// Whether `bytes` start as a TrueType, OpenType or TrueType collection file.
fn is_font(bytes: &[u8]) -> bool {
    matches!(
        bytes.get(..4),
        Some([0, 1, 0, 0] | b"OTTO" | b"ttcf" | b"true")
    )
}

/// Every translated string: (English, Simplified Chinese, Traditional Chinese). `{}` marks
/// where [`trf`] puts its arguments, in the same order in each language.
pub const TABLE: &[(&str, &str, &str)] = &[
    // Menus and the top bar.
    ("File", "文件", "檔案"),
    ("Edit", "编辑", "編輯"),
    ("View", "视图", "檢視"),
    ("Language", "语言", "語言"),
    ("Settings…", "设置…", "設定…"),
    ("Dialect", "方言", "方言"),
    ("Fit view", "适合视图", "符合檢視"),
    ("New", "新建", "新增"),
    ("Open…", "打开…", "開啟…"),
    ("Open recent", "最近打开", "最近開啟"),
    ("Examples", "示例", "範例"),
    ("Save", "保存", "儲存"),
    ("Save as…", "另存为…", "另存新檔…"),
    ("Close tab", "关闭标签页", "關閉分頁"),
    ("Import setup…", "导入设置…", "匯入設定…"),
    ("Export setup…", "导出设置…", "匯出設定…"),
    ("Undo", "撤销", "復原"),
    ("Redo", "重做", "重做"),
    ("Find…", "查找…", "尋找…"),
    ("Replace…", "替换…", "取代…"),
    ("Go to line…", "转到行…", "移至行…"),
    ("Toggle comment", "切换注释", "切換註解"),
    ("Renumber blocks…", "重新编号程序段…", "重新編號單節…"),
    // Tabs and the editor panel.
    ("Program", "程序", "程式"),
    ("New tab", "新建标签页", "新增分頁"),
    ("Close {}", "关闭 {}", "關閉 {}"),
    (
        "{} is open here with unsaved changes",
        "{} 已在此打开且有未保存的更改",
        "{} 已在此開啟且有未儲存的變更",
    ),
    (
        "Recovered unsaved changes of {}",
        "已恢复 {} 的未保存更改",
        "已復原 {} 的未儲存變更",
    ),
    (
        "Recovered unsaved changes of {} tabs: {}",
        "已恢复 {} 个标签页的未保存更改：{}",
        "已復原 {} 個分頁的未儲存變更：{}",
    ),
    ("Could not recover {}", "无法恢复 {}", "無法復原 {}"),
    (
        "Not kept for recovery: {} ({})",
        "未能保留以供恢复：{}（{}）",
        "未能保留以供復原：{}（{}）",
    ),
    (
        "Kept for recovery again: {}",
        "已重新保留以供恢复：{}",
        "已重新保留以供復原：{}",
    ),
    ("Saved {}", "已保存 {}", "已儲存 {}"),
    ("{}, line {}", "{}，第 {} 行", "{}，第 {} 行"),
    (
        "Renumbered {} blocks, {} jump targets",
        "已重新编号 {} 个程序段、{} 个跳转目标",
        "已重新編號 {} 個單節、{} 個跳躍目標",
    ),
    ("Replaced {} matches", "已替换 {} 处", "已取代 {} 處"),
    // Find and replace.
    ("Find", "查找", "尋找"),
    ("regular expression", "正则表达式", "規則運算式"),
    ("text", "文本", "文字"),
    ("Regex", "正则", "規則"),
    ("Match case", "区分大小写", "大小寫須相符"),
    ("Previous", "上一个", "上一個"),
    ("Next", "下一个", "下一個"),
    ("{} matches", "{} 处匹配", "{} 處符合"),
    ("invalid pattern", "无效的模式", "無效的模式"),
    ("Close", "关闭", "關閉"),
    ("Replace", "替换", "取代"),
    ("Replace all", "全部替换", "全部取代"),
    // Dialogs.
    ("Go to line", "转到行", "移至行"),
    ("Line number", "行号", "行號"),
    ("Go", "转到", "移至"),
    ("Renumber blocks", "重新编号程序段", "重新編號單節"),
    ("Start", "起始", "起始"),
    ("Step", "步长", "間隔"),
    ("Number every block", "为每个程序段编号", "為每個單節編號"),
    ("Renumber", "重新编号", "重新編號"),
    ("Settings", "设置", "設定"),
    ("Unsaved changes", "未保存的更改", "未儲存的變更"),
    (
        "{} has changes that are not saved.",
        "{} 有尚未保存的更改。",
        "{} 有尚未儲存的變更。",
    ),
    ("Discard changes", "放弃更改", "捨棄變更"),
    ("Cancel", "取消", "取消"),
    // Status bar, problems, state at cursor.
    ("{} blocks", "{} 个程序段", "{} 個單節"),
    ("{} motions", "{} 个运动", "{} 個運動"),
    (
        "extent {} × {} × {} mm",
        "范围 {} × {} × {} mm",
        "範圍 {} × {} × {} mm",
    ),
    (
        "{} errors, {} warnings",
        "{} 个错误，{} 个警告",
        "{} 個錯誤，{} 個警告",
    ),
    ("line {}", "第 {} 行", "第 {} 行"),
    ("Analysing", "分析中", "分析中"),
    ("{} / {} blocks", "{} / {} 个程序段", "{} / {} 個單節"),
    ("Problems ({})", "问题（{}）", "問題（{}）"),
    ("No problems", "没有问题", "沒有問題"),
    ("Go to this position", "转到此位置", "移至此位置"),
    (
        "Go to this position in {}",
        "转到 {} 中的此位置",
        "移至 {} 中的此位置",
    ),
    ("State at cursor", "光标处状态", "游標處狀態"),
    (
        "Put the cursor on a block.",
        "请将光标放在程序段上。",
        "請將游標放在單節上。",
    ),
    (
        "Line {} does not run.",
        "第 {} 行不会执行。",
        "第 {} 行不會執行。",
    ),
    ("line", "行", "行"),
    ("modes", "模态", "模態"),
    ("work", "工件坐标", "工件座標"),
    ("machine", "机床坐标", "機械座標"),
    ("tool", "刀具", "刀具"),
    ("feed", "进给", "進給"),
    ("spindle", "主轴", "主軸"),
    ("blocks run", "已执行程序段", "已執行單節"),
    // A tab's first analysis, and the dialect its program's codes point to.
    ("Reading… {} %", "读取中… {} %", "讀取中… {} %"),
    ("Analysing… {} %", "分析中… {} %", "分析中… {} %"),
    (
        "This program looks like {} ({} on line {})",
        "此程序看起来属于 {}（{}，第 {} 行）",
        "此程式看起來屬於 {}（{}，第 {} 行）",
    ),
    (
        "This program looks like {}",
        "此程序看起来属于 {}",
        "此程式看起來屬於 {}",
    ),
    ("Switch", "切换", "切換"),
    (
        "Read this tab's program as {}",
        "按 {} 读取此标签页的程序",
        "以 {} 讀取此分頁的程式",
    ),
    // The CJK font.
    (
        "Loading the Chinese font…",
        "正在加载中文字体…",
        "正在載入中文字型…",
    ),
    (
        "No Chinese font found: install fonts-wqy-microhei or fonts-noto-cjk, or set SWARF_CJK_FONT to a font file",
        "未找到中文字体：请安装 fonts-wqy-microhei 或 fonts-noto-cjk，或将 SWARF_CJK_FONT 设为字体文件",
        "未找到中文字型：請安裝 fonts-wqy-microhei 或 fonts-noto-cjk，或將 SWARF_CJK_FONT 設為字型檔",
    ),
    (
        "The Chinese font could not be loaded: {}",
        "无法加载中文字体：{}",
        "無法載入中文字型：{}",
    ),
    // Settings.
    ("Import SETUP.toml…", "导入 SETUP.toml…", "匯入 SETUP.toml…"),
    ("Export SETUP.toml…", "导出 SETUP.toml…", "匯出 SETUP.toml…"),
    ("Reset to defaults", "恢复默认值", "還原預設值"),
    (
        "Values in millimetres; they are kept between runs.",
        "数值单位为毫米；下次运行时保留。",
        "數值單位為公釐；下次執行時保留。",
    ),
    (
        "Offset registers (H length, D radius)",
        "补偿寄存器（H 长度，D 半径）",
        "補正暫存器（H 長度，D 半徑）",
    ),
    ("Work offsets", "工件坐标系", "工件座標系"),
    ("Machine", "机床", "機械"),
    ("No.", "编号", "編號"),
    ("Length", "长度", "長度"),
    ("Length wear", "长度磨损", "長度磨耗"),
    ("Radius", "半径", "半徑"),
    ("Radius wear", "半径磨损", "半徑磨耗"),
    ("Remove", "删除", "刪除"),
    ("Tip (lathe)", "刀尖方向（车床）", "刀尖方向（車床）"),
    (
        "Lathe tool tip direction 1-8 (LinuxCNC's Q): compensation in G18 reports the imaginary tip; 0 a mill, 9 the nose centre",
        "车刀刀尖方向 1–8（LinuxCNC 的 Q）：G18 中的补正报告假想刀尖；0 为铣刀，9 为刀尖圆心",
        "車刀刀尖方向 1–8（LinuxCNC 的 Q）：G18 中的補正報告假想刀尖；0 為銑刀，9 為刀尖圓心",
    ),
    (
        "G41/G42 under a mirror",
        "镜像下的 G41/G42",
        "鏡像下的 G41/G42",
    ),
    ("the dialect's default", "按方言默认", "依方言預設"),
    (
        "swapped by the control (Fanuc)",
        "由控制器对调（Fanuc）",
        "由控制器對調（Fanuc）",
    ),
    (
        "as written (Syntec's example)",
        "按程序所写（新代示例）",
        "依程式所寫（新代範例）",
    ),
    ("Add register", "添加寄存器", "新增暫存器"),
    ("Add offset", "添加坐标系", "新增座標系"),
    ("Add", "添加", "新增"),
    (
        "Rapid rate (mm/min)",
        "快速移动速度（mm/min）",
        "快速移動速度（mm/min）",
    ),
    (
        "Rapid rate per axis X Y Z",
        "各轴快速移动速度 X Y Z",
        "各軸快速移動速度 X Y Z",
    ),
    ("Acceleration (mm/s²)", "加速度（mm/s²）", "加速度（mm/s²）"),
    ("Peck retract (mm)", "啄钻退刀量（mm）", "啄鑽退刀量（mm）"),
    ("Arc tolerance (mm)", "圆弧公差（mm）", "圓弧公差（mm）"),
    (
        "Runaway limit (blocks)",
        "失控上限（程序段）",
        "失控上限（單節）",
    ),
    (
        "Move limit (moves)",
        "运动上限（运动数）",
        "運動上限（運動數）",
    ),
    (
        "Machine travel min / max X Y Z",
        "机床行程 最小 / 最大 X Y Z",
        "機械行程 最小 / 最大 X Y Z",
    ),
    (
        "G76/G87 shift direction",
        "G76/G87 偏移方向",
        "G76/G87 偏移方向",
    ),
    ("Syntec drilling", "新代钻孔", "新代鑽孔"),
    (
        "G81 retracts at F2= (Pr4008 = 1)",
        "G81 以 F2= 退刀（Pr4008 = 1）",
        "G81 以 F2= 退刀（Pr4008 = 1）",
    ),
    (
        "Peck tapping backs out by the peck retract (Pr4001 = 1)",
        "啄式攻牙按啄钻退刀量回退（Pr4001 = 1）",
        "啄式攻牙依啄鑽退刀量回退（Pr4001 = 1）",
    ),
    (
        "Cutter compensation corners",
        "刀具半径补偿拐角",
        "刀具半徑補正轉角",
    ),
    ("as the dialect does", "按方言", "依方言"),
    ("arc (LinuxCNC)", "圆弧（LinuxCNC）", "圓弧（LinuxCNC）"),
    (
        "intersection (Fanuc family)",
        "交点（发那科系列）",
        "交點（發那科系列）",
    ),
    ("Gouges", "过切", "過切"),
    (
        "stop with an alarm (Syntec 3819)",
        "报警停止（新代 3819）",
        "警報停止（新代 3819）",
    ),
    (
        "Integers without a point",
        "不带小数点的整数",
        "不帶小數點的整數",
    ),
    ("as the dialect's manual says", "按方言手册", "依方言手冊"),
    (
        "millimetres (calculator input)",
        "毫米（计算器式输入）",
        "公釐（計算機式輸入）",
    ),
    ("least input increments", "最小输入单位", "最小輸入單位"),
    ("G28 reference point", "G28 参考点", "G28 參考點"),
    ("G30 P2 reference point", "G30 P2 参考点", "G30 P2 參考點"),
    // The backplot.
    ("3D view unavailable", "3D 视图不可用", "3D 檢視無法使用"),
    ("Fit", "适合", "符合"),
    (
        "Fit to extents (double-click)",
        "缩放至全部（双击）",
        "縮放至全部（按兩下）",
    ),
    ("Iso", "等轴", "等角"),
    ("Top", "俯视", "俯視"),
    ("Front", "前视", "前視"),
    ("Right", "右视", "右視"),
    ("Persp", "透视", "透視"),
    (
        "Perspective / orthographic projection",
        "透视 / 正交投影",
        "透視 / 正交投影",
    ),
    ("By tool", "按刀具", "依刀具"),
    (
        "Colour the path by tool instead of by kind of move (T)",
        "按刀具而非运动类型为路径着色（T）",
        "依刀具而非運動類型為路徑著色（T）",
    ),
    ("Contour", "轮廓", "輪廓"),
    (
        "Show the programmed contour beside the tool centre's path under cutter compensation",
        "在刀具半径补偿下，于刀具中心路径旁显示编程轮廓",
        "在刀具半徑補正下，於刀具中心路徑旁顯示程式輪廓",
    ),
    ("Rapids", "快移", "快移"),
    (
        "Show or hide rapid moves",
        "显示或隐藏快速移动",
        "顯示或隱藏快速移動",
    ),
    ("Zoom sel", "缩放选中", "縮放選取"),
    (
        "Zoom to the selected block",
        "缩放至选中的程序段",
        "縮放至選取的單節",
    ),
    ("rapid", "快移", "快移"),
    ("arc", "圆弧", "圓弧"),
    ("plunge", "下刀", "下刀"),
    ("retract", "退刀", "退刀"),
    ("cycle", "循环", "循環"),
    ("compensated", "补偿后", "補正後"),
    ("programmed", "编程", "程式"),
    ("move", "运动", "運動"),
    ("Line {}", "第 {} 行", "第 {} 行"),
    // Playback.
    ("Pause", "暂停", "暫停"),
    ("Pause playback", "暂停播放", "暫停播放"),
    ("Play", "播放", "播放"),
    (
        "Play the program from here (from the start at its end)",
        "从此处播放程序（在末尾时从头开始）",
        "從此處播放程式（在結尾時從頭開始）",
    ),
    ("« Block", "« 程序段", "« 單節"),
    ("Step one block back", "后退一个程序段", "後退一個單節"),
    ("Block »", "程序段 »", "單節 »"),
    ("Step one block forward", "前进一个程序段", "前進一個單節"),
    ("Stop", "停止", "停止"),
    (
        "Stop playback and draw the whole program",
        "停止播放并绘制整个程序",
        "停止播放並繪製整個程式",
    ),
    ("Speed", "速度", "速度"),
    (", line {}", "，第 {} 行", "，第 {} 行"),
    (
        "block {} of {}{}",
        "第 {} / {} 个程序段{}",
        "第 {} / {} 個單節{}",
    ),
    ("Time", "时间", "時間"),
    ("Block", "程序段", "單節"),
    // Editor.
    (
        "{} lines, {} MB: shown read-only (programs up to {} MB are edited here)",
        "{} 行，{} MB：只读显示（最多 {} MB 的程序可在此编辑）",
        "{} 行，{} MB：唯讀顯示（最多 {} MB 的程式可在此編輯）",
    ),
    ("Control alarm: {}", "控制器报警：{}", "控制器警報：{}"),
    (
        "{} is not a code of {}",
        "{} 不是 {} 的代码",
        "{} 不是 {} 的代碼",
    ),
];

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;

    #[test]
    fn every_entry_has_three_forms_with_the_same_placeholders() {
        let mut seen = std::collections::HashSet::new();
        for &(en, hans, hant) in TABLE {
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
            include_str!("workbench.rs"),
            include_str!("settings.rs"),
            include_str!("backplot.rs"),
            include_str!("backplot/playback.rs"),
            include_str!("editor.rs"),
        ];
        let mut looked_up = 0;
        for source in sources {
            for call in ["tr(\"", "trf(\n", "trf(\""] {
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
                        index().contains_key(key),
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
