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
    let names: String = Dialect::ALL.map(|d| format!(" {} |", d.name())).concat();
    let rule = "---|".repeat(Dialect::ALL.len());
    let mut out = format!("| group |{names}\n|---|{rule}\n");
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
    let next = |(a, star): &(Code, bool), (b, next_star): &(Code, bool)| {
        star == next_star && a.letter == b.letter && a.tenths % 10 == 0 && b.tenths == a.tenths + 10
    };
    for run in codes.chunk_by(next) {
        let mark = if run[0].1 { "*" } else { "" };
        match run {
            [(first, _), _, .., (last, _)] => parts.push(format!("{first}–{last}{mark}")),
            _ => parts.extend(run.iter().map(|(c, _)| format!("{c}{mark}"))),
        }
    }
    parts.join(" ")
}
