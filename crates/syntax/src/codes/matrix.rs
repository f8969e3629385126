//! The feature table of the README: every code group with the codes each dialect has in it,
//! generated from [`CODES`](super::CODES) so the documentation cannot drift from the code.

use crate::Dialect;

use super::{Code, Group, codes_of, is_fanuc_reading};

/// A Markdown table: one row per code group (in table order), one column per dialect, each cell
/// the dialect's codes of that group (runs of three or more whole codes as `G80–G89`; codes read
/// as on Fanuc because the manual leaves them out marked `*`).
pub fn markdown_table() -> String {
    let mut groups: Vec<Group> = Vec::new();
    for def in super::CODES {
        if !groups.contains(&def.group) {
            groups.push(def.group);
        }
    }
    let mut out = String::from("| group |");
    for d in Dialect::ALL {
        out.push_str(&format!(" {} |", d.name()));
    }
    out.push_str("\n|---|");
    out.push_str(&"---|".repeat(Dialect::ALL.len()));
    out.push('\n');
    for group in groups {
        out.push_str(&format!("| {} |", group.name()));
        for dialect in Dialect::ALL {
            let codes: Vec<(Code, bool)> = codes_of(dialect)
                .filter(|d| d.group == group)
                .map(|d| (d.code, is_fanuc_reading(dialect, d)))
                .collect();
            let cell = compress(&codes);
            out.push_str(&format!(" {} |", if cell.is_empty() { "—" } else { &cell }));
        }
        out.push('\n');
    }
    out
}

/// `G80 G81 … G89` as `G80–G89`: runs of three or more consecutive whole codes of one kind
/// (own or Fanuc reading) joined; the rest listed.
fn compress(codes: &[(Code, bool)]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < codes.len() {
        let (first, star) = codes[i];
        let mut j = i;
        while j + 1 < codes.len()
            && first.tenths % 10 == 0
            && codes[j + 1].1 == star
            && codes[j + 1].0.letter == first.letter
            && codes[j + 1].0.tenths == codes[j].0.tenths + 10
        {
            j += 1;
        }
        let mark = if star { "*" } else { "" };
        if j - i >= 2 {
            parts.push(format!("{first}–{}{mark}", codes[j].0));
            i = j + 1;
        } else {
            parts.push(format!("{first}{mark}"));
            i += 1;
        }
    }
    parts.join(" ")
}
