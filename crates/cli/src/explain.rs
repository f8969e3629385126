//! `swarf explain`: what a code, an address or a diagnostic code means, from the language
//! crate's tables.

use std::io::Write;

use anyhow::Result;
use serde_json::json;
use swarf_syntax::codes::{self, AddressDef, CodeDef, Documented, Modality};
use swarf_syntax::{Code, DIAGNOSTICS, DiagnosticDef, Dialect};

use crate::{EXIT_ERRORS, EXIT_OK, EXIT_USAGE};

/// Arguments of `swarf explain`.
#[derive(clap::Args, Debug)]
pub(crate) struct ExplainArgs {
    /// The code, address or diagnostic code; omit with --list, --table or --diagnostics.
    what: Option<String>,
    /// Only this dialect (default: every dialect that has it).
    #[arg(long, value_parser = crate::parse_dialect)]
    dialect: Option<Dialect>,
    /// List every code of the dialect (fanuc unless --dialect is given).
    #[arg(long)]
    list: bool,
    /// List every diagnostic code with its severity and meaning.
    #[arg(long)]
    diagnostics: bool,
    /// Print the Markdown table of every code group per dialect (the README's feature table),
    /// or with --diagnostics of every diagnostic code (docs/interpreter.md's).
    #[arg(long)]
    table: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Explains `what` (a code such as `G83`, an address such as `Q`, a diagnostic such as
/// `E-ARC-RADIUS`) for `dialect` or all; `list`, `diagnostics` and `table` print lists or tables.
pub(crate) fn explain(args: &ExplainArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32> {
    let (dialect, list, json) = (args.dialect, args.list, args.json);
    if args.diagnostics {
        return diagnostics(args.table, json, out);
    }
    if args.table {
        write!(out, "{}", codes::markdown_table())?;
        return Ok(EXIT_OK);
    }
    let (code, defs): (_, Vec<&CodeDef>) = if list {
        (None, codes::codes_of(dialect.unwrap_or_default()).collect())
    } else {
        let Some(what) = &args.what else {
            writeln!(
                err,
                "swarf explain: name a code (G83, M98), an address letter (Q) or a diagnostic code (E-ARC-RADIUS), or pass --list or --diagnostics"
            )?;
            return Ok(EXIT_USAGE);
        };
        let trimmed = what.trim();
        if trimmed.as_bytes().get(1) == Some(&b'-') {
            return diagnostic(&trimmed.to_ascii_uppercase(), json, out, err);
        }
        if trimmed.len() == 1 && trimmed.as_bytes()[0].is_ascii_alphabetic() {
            return address(trimmed.as_bytes()[0], dialect, json, out);
        }
        let Some(code) = Code::parse(trimmed) else {
            writeln!(
                err,
                "swarf explain: `{what}` is not a G or M code (such as G83, G54.1, M98), an address letter or a diagnostic code"
            )?;
            return Ok(EXIT_USAGE);
        };
        match dialect {
            Some(d) => (Some(code), codes::lookup(d, code).into_iter().collect()),
            None => (Some(code), codes::meanings(code).collect()),
        }
    };
    if json {
        let items: Vec<_> = defs.iter().map(|d| def_json(d)).collect();
        writeln!(out, "{}", serde_json::to_string_pretty(&items)?)?;
    } else if list {
        for d in &defs {
            writeln!(out, "{:<8} {:<40} {}", d.code.to_string(), d.name, d.format)?;
        }
    } else {
        for d in &defs {
            print_def(d, out)?;
        }
    }
    if let Some(code) = code
        && defs.is_empty()
    {
        let others: Vec<String> = codes::meanings(code)
            .map(|d| format!("{} on {}", d.name, d.dialects.labels()))
            .collect();
        let name = dialect.map_or("any supported control", Dialect::label);
        let also = if others.is_empty() {
            String::new()
        } else {
            format!("; it is {}", others.join("; "))
        };
        writeln!(err, "{code} is not a code of {name}{also}")?;
        return Ok(EXIT_ERRORS);
    }
    Ok(EXIT_OK)
}

/// Explains one diagnostic code: its severity and meaning.
fn diagnostic(code: &str, json: bool, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32> {
    let Some(d) = DiagnosticDef::lookup(code) else {
        writeln!(
            err,
            "{code} is not a diagnostic code (`swarf explain --diagnostics` lists them)"
        )?;
        return Ok(EXIT_ERRORS);
    };
    if json {
        let items = [diagnostic_json(d)];
        writeln!(out, "{}", serde_json::to_string_pretty(&items)?)?;
    } else {
        writeln!(out, "{} — {}\n  {}", d.code, d.severity, d.summary)?;
    }
    Ok(EXIT_OK)
}

/// Lists every diagnostic code: as text, as JSON, or with `table` as the Markdown table of
/// docs/interpreter.md.
fn diagnostics(table: bool, json: bool, out: &mut dyn Write) -> Result<i32> {
    if table {
        writeln!(out, "| code | severity | meaning |\n|---|---|---|")?;
        for d in DIAGNOSTICS {
            let summary = d.summary.replace('|', "\\|");
            writeln!(out, "| `{}` | {} | {summary} |", d.code, d.severity)?;
        }
    } else if json {
        let items: Vec<_> = DIAGNOSTICS.iter().map(diagnostic_json).collect();
        writeln!(out, "{}", serde_json::to_string_pretty(&items)?)?;
    } else {
        let width = DIAGNOSTICS.iter().map(|d| d.code.len()).max().unwrap_or(0);
        for d in DIAGNOSTICS {
            let severity = d.severity.as_str();
            writeln!(out, "{:<width$}  {severity:<7}  {}", d.code, d.summary)?;
        }
    }
    Ok(EXIT_OK)
}

fn diagnostic_json(d: &DiagnosticDef) -> serde_json::Value {
    json!({
        "code": d.code,
        "severity": d.severity.as_str(),
        "summary": d.summary,
    })
}

fn print_def(d: &CodeDef, out: &mut dyn Write) -> Result<()> {
    writeln!(out, "{} — {}", d.code, d.name)?;
    writeln!(out, "  dialects:  {}", d.dialects.labels())?;
    writeln!(out, "  format:    {}", d.format)?;
    let words: Vec<String> = d.words.chars().map(String::from).collect();
    writeln!(out, "  words:     {}", words.join(" "))?;
    let (group, modal) = (d.group.name(), d.modality.name());
    writeln!(out, "  group:     {group}, {modal}")?;
    if !d.power_on.is_empty() {
        writeln!(out, "  power-on:  {}", d.power_on.labels())?;
    }
    match d.documented {
        Documented::Full => {}
        Documented::ListOnly => writeln!(
            out,
            "  note:      only listed in the manual; no format is documented"
        )?,
        Documented::Mentioned => writeln!(out, "  note:      only mentioned in the manual")?,
    }
    writeln!(out, "  {}", d.summary)?;
    if !d.section.is_empty() {
        writeln!(out, "  reference: §{}", d.section)?;
    }
    writeln!(out)?;
    Ok(())
}

fn def_json(d: &CodeDef) -> serde_json::Value {
    json!({
        "code": d.code.to_string(),
        "name": d.name,
        "dialects": d.dialects.iter().map(Dialect::name).collect::<Vec<_>>(),
        "format": d.format,
        "words": d.words,
        "group": d.group.name(),
        "modal": d.modality == Modality::Modal,
        "power_on": d.power_on.iter().map(Dialect::name).collect::<Vec<_>>(),
        "documented": d.documented.name(),
        "summary": d.summary,
        "section": d.section,
    })
}

fn address(letter: u8, dialect: Option<Dialect>, json: bool, out: &mut dyn Write) -> Result<i32> {
    let dialects = dialect.map_or(Dialect::ALL.to_vec(), |d| vec![d]);
    let mut seen = Vec::new();
    for a in dialects.into_iter().flat_map(|d| codes::address(d, letter)) {
        if !seen.contains(&a) {
            seen.push(a);
        }
    }
    if json {
        let item = |a: &&AddressDef| {
            json!({
                "address": char::from(a.letter).to_string(),
                "dialects": a.dialects.iter().map(Dialect::name).collect::<Vec<_>>(),
                "meaning": a.meaning,
            })
        };
        let items: Vec<_> = seen.iter().map(item).collect();
        writeln!(out, "{}", serde_json::to_string_pretty(&items)?)?;
    } else {
        for a in &seen {
            writeln!(
                out,
                "{} ({}): {}",
                char::from(a.letter),
                a.dialects.labels(),
                a.meaning
            )?;
        }
    }
    Ok(if seen.is_empty() {
        EXIT_ERRORS
    } else {
        EXIT_OK
    })
}
