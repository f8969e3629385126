//! The diagnostic registry and the sources agree: every code literal in `crates/*/src` is
//! registered, every registered code is given somewhere, and each `Diagnostic::error`,
//! `warning` or `note` with a literal code has the code's registered severity.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use swarf_syntax::{DIAGNOSTICS, DiagnosticDef, Severity};

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `(file, text)` of every source file of every crate but the registry itself.
fn sources() -> Vec<(String, String)> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for krate in std::fs::read_dir(&crates).unwrap() {
        let src = krate.unwrap().path().join("src");
        if src.is_dir() {
            rust_files(&src, &mut files);
        }
    }
    assert!(files.len() > 20, "only {} source files found", files.len());
    files
        .into_iter()
        .filter(|f| !f.ends_with("diagnostic/registry.rs"))
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap();
            (f.strip_prefix(&crates).unwrap().display().to_string(), text)
        })
        .collect()
}

/// Whether `s` has the shape of a diagnostic code: `E-`, `W-` or `N-` and dash-separated runs
/// of capitals and digits.
fn is_code(s: &str) -> bool {
    let Some(rest) = s
        .strip_prefix("E-")
        .or_else(|| s.strip_prefix("W-"))
        .or_else(|| s.strip_prefix("N-"))
    else {
        return false;
    };
    rest.split('-').all(|part| {
        !part.is_empty()
            && part
                .bytes()
                .all(|b| b.is_ascii_uppercase() || b.is_ascii_digit())
    })
}

/// `text` with comments and the insides of string and char literals blanked (so that only
/// code is left to match brackets in), and the byte ranges of its string literals' contents.
fn lex(text: &str) -> (Vec<u8>, Vec<(usize, usize)>) {
    let bytes = text.as_bytes();
    let mut code = bytes.to_vec();
    let mut strings = Vec::new();
    let blank = |code: &mut Vec<u8>, from: usize, to: usize| code[from..to].fill(b' ');
    let mut i = 0;
    while i < bytes.len() {
        let rest = &bytes[i..];
        let after_ident = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if rest.starts_with(b"//") {
            let end = rest
                .iter()
                .position(|&b| b == b'\n')
                .map_or(bytes.len(), |n| i + n);
            blank(&mut code, i, end);
            i = end;
        } else if rest.starts_with(b"/*") {
            let end = text[i + 2..]
                .find("*/")
                .map_or(bytes.len(), |n| i + 2 + n + 2);
            blank(&mut code, i, end);
            i = end;
        } else if rest[0] == b'r'
            && !after_ident
            && rest[1..].iter().find(|&&b| b != b'#') == Some(&b'"')
        {
            let hashes = rest[1..].iter().take_while(|&&b| b == b'#').count();
            let open = i + 1 + hashes + 1;
            let close = format!("\"{}", "#".repeat(hashes));
            let end = text[open..].find(&close).map_or(bytes.len(), |n| open + n);
            strings.push((open, end));
            blank(&mut code, open, end);
            i = (end + close.len()).min(bytes.len());
        } else if rest[0] == b'"' {
            let open = i + 1;
            let mut end = open;
            while end < bytes.len() && bytes[end] != b'"' {
                end += if bytes[end] == b'\\' { 2 } else { 1 };
            }
            let end = end.min(bytes.len());
            strings.push((open, end));
            blank(&mut code, open, end);
            i = end + 1;
        } else if rest[0] == b'\'' {
            // A char literal, or else a lifetime or a label.
            let len = char_literal_len(&text[i..]);
            if let Some(len) = len {
                blank(&mut code, i + 1, i + len - 1);
                i += len;
            } else {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    (code, strings)
}

/// The length of the char literal `text` starts with (`'x'`, `'\''`, `'\u{..}'`), if it
/// starts with one.
fn char_literal_len(text: &str) -> Option<usize> {
    let bytes = text.as_bytes();
    if bytes.get(1) == Some(&b'\\') {
        let close = bytes.get(3..)?.iter().position(|&b| b == b'\'')?;
        return Some(close + 4);
    }
    let n = text.get(1..)?.chars().next()?.len_utf8();
    (bytes.get(1 + n) == Some(&b'\'')).then_some(n + 2)
}

/// A file's code literals with their offsets, and its bracket-matching view (see [`lex`]).
fn code_literals(text: &str) -> (Vec<(usize, &str)>, Vec<u8>) {
    let (code, strings) = lex(text);
    let codes = strings
        .into_iter()
        .map(|(a, b)| (a, &text[a..b]))
        .filter(|(_, s)| is_code(s))
        .collect();
    (codes, code)
}

/// The offset of the `)` that closes the argument list opening just before `open`.
fn call_end(code: &[u8], open: usize) -> usize {
    let mut depth = 1;
    for (i, &b) in code.iter().enumerate().skip(open) {
        match b {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    return i;
                }
            }
            _ => {}
        }
    }
    code.len()
}

#[test]
fn every_code_in_the_sources_is_registered_and_every_registered_code_is_used() {
    let mut used = BTreeSet::new();
    let mut unregistered = Vec::new();
    for (file, text) in sources() {
        for (_, code) in code_literals(&text).0 {
            used.insert(code.to_string());
            if DiagnosticDef::lookup(code).is_none() {
                unregistered.push(format!("{file}: {code}"));
            }
        }
    }
    assert!(
        unregistered.is_empty(),
        "codes missing from crates/syntax/src/diagnostic/registry.rs:\n{}",
        unregistered.join("\n")
    );
    let unused: Vec<&str> = DIAGNOSTICS
        .iter()
        .map(|d| d.code)
        .filter(|c| !used.contains(*c))
        .collect();
    assert!(unused.is_empty(), "registered but never given: {unused:?}");
}

#[test]
fn each_constructor_gives_its_codes_registered_severity() {
    let mut checked = 0;
    let mut wrong = Vec::new();
    for (file, text) in sources() {
        let (codes, code) = code_literals(&text);
        for (name, severity) in [
            ("Diagnostic::error(", Severity::Error),
            ("Diagnostic::warning(", Severity::Warning),
            ("Diagnostic::note(", Severity::Note),
            // The interpreter's `State` reports through these, the code second as well.
            ("st.error(", Severity::Error),
            ("st.fail(", Severity::Error),
            ("st.warning(", Severity::Warning),
            ("st.note(", Severity::Note),
        ] {
            for (at, _) in text.match_indices(name) {
                let open = at + name.len();
                let args = open..call_end(&code, open);
                // The code is the second argument; a code held in a variable is checked by
                // the constructor's debug assertion instead.
                let Some(&(_, code)) = codes.iter().find(|(at, _)| args.contains(at)) else {
                    continue;
                };
                checked += 1;
                let registered = DiagnosticDef::lookup(code).map(|d| d.severity);
                if registered != Some(severity) {
                    wrong.push(format!("{file}: {name}{code}) is {registered:?}"));
                }
            }
        }
    }
    assert!(
        checked > 100,
        "only {checked} constructor calls with a literal code found"
    );
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_scanner_reads_literals_and_calls() {
    let text = r##"// "E-NOT"
Diagnostic::error(f(')', "(", '"', x), "E-A-1", format!("a \" {}", y)); "W-B" r#"N-C"#
fn f<'a>(s: &'a str) -> char { '\'' } /* "E-NOT" */ "e-d" "N-""##;
    let (codes, code) = code_literals(text);
    let codes: Vec<&str> = codes.into_iter().map(|(_, c)| c).collect();
    assert_eq!(codes, ["E-A-1", "W-B", "N-C"]);
    let open = text.find('(').unwrap() + 1;
    assert!(text[call_end(&code, open)..].starts_with("); \"W-B\""));
}
