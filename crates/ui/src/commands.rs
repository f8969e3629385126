//! Editor commands as pure text transformations: find, replace, lines, comments, renumbering.

use std::ops::{Range, RangeInclusive};

use swarf_syntax::Dialect;

/// How a find or replace pattern is matched.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FindOptions {
    /// The pattern is a regular expression (`regex` crate syntax) rather than literal text.
    pub regex: bool,
    /// Letters must match in case (G-code is case-insensitive, so the default is not to).
    pub match_case: bool,
}

/// A compiled find pattern.
#[derive(Debug, Clone)]
pub struct Finder {
    re: regex::Regex,
}

impl Finder {
    /// Compiles `pattern`; the error is the regex parser's message, for showing beside the field.
    pub fn new(pattern: &str, options: FindOptions) -> Result<Finder, String> {
        let source = if options.regex {
            pattern.to_string()
        } else {
            regex::escape(pattern)
        };
        regex::RegexBuilder::new(&source)
            .case_insensitive(!options.match_case)
            .multi_line(true)
            .size_limit(1 << 22)
            .build()
            .map(|re| Finder { re })
            .map_err(|e| e.to_string())
    }

    /// Byte ranges of every non-empty match in `text`, in order.
    pub fn find_all(&self, text: &str) -> Vec<Range<usize>> {
        let found = self.re.find_iter(text).filter(|m| !m.is_empty());
        found.map(|m| m.range()).collect()
    }

    /// The first non-empty match starting at or after byte `from`, wrapping to the start.
    pub fn next(&self, text: &str, from: usize) -> Option<Range<usize>> {
        let all = self.find_all(text);
        let found = all.iter().find(|r| r.start >= from);
        found.or_else(|| all.first()).cloned()
    }

    /// The last non-empty match ending at or before byte `before`, wrapping to the end.
    pub fn previous(&self, text: &str, before: usize) -> Option<Range<usize>> {
        let all = self.find_all(text);
        let found = all.iter().rev().find(|r| r.end <= before);
        found.or_else(|| all.last()).cloned()
    }

    /// `text` with every match replaced (`$1`, `${name}` in regex mode), and how many.
    pub fn replace_all(
        &self,
        text: &str,
        replacement: &str,
        options: FindOptions,
    ) -> (String, usize) {
        let count = self.find_all(text).len();
        if count == 0 {
            return (text.to_string(), 0);
        }
        let out = if options.regex {
            self.re.replace_all(text, replacement)
        } else {
            self.re.replace_all(text, regex::NoExpand(replacement))
        };
        (out.into_owned(), count)
    }

    /// The replacement for the match at exactly `range` (groups expanded); `None` if none.
    pub fn replacement_at(
        &self,
        text: &str,
        range: Range<usize>,
        replacement: &str,
        options: FindOptions,
    ) -> Option<String> {
        let mut all = self.re.captures_iter(text);
        let caps = all.find(|c| c.get(0).is_some_and(|m| m.range() == range))?;
        if options.regex {
            let mut out = String::new();
            caps.expand(replacement, &mut out);
            Some(out)
        } else {
            Some(replacement.to_string())
        }
    }
}

/// Converts a character index into a byte offset of `text` (clamped to its end).
pub fn byte_of_char(text: &str, chars: usize) -> usize {
    let at = text.char_indices().nth(chars);
    at.map_or(text.len(), |(b, _)| b)
}

/// Converts sorted, non-overlapping byte ranges into character ranges in one pass over `text`.
pub fn char_ranges(text: &str, bytes: &[Range<usize>]) -> Vec<Range<usize>> {
    let (mut at, mut chars) = (0, 0);
    let mut advance = |to: usize| {
        let to = to.min(text.len());
        if to > at {
            chars += text.get(at..to).map_or(0, |t| t.chars().count());
            at = to;
        }
        chars
    };
    let ranges = bytes.iter().map(|r| advance(r.start)..advance(r.end));
    ranges.collect()
}

/// Converts a byte offset into a character index of `text` (clamped to its end).
pub fn char_of_byte(text: &str, byte: usize) -> usize {
    text[..text.floor_char_boundary(byte)].chars().count()
}

/// The byte offset where 1-based `line` starts (the end of the text past the last line).
pub fn line_start(text: &str, line: u32) -> usize {
    if line <= 1 {
        return 0;
    }
    let start = line_starts(text).nth(line as usize - 2);
    start.unwrap_or(text.len())
}

/// Where the lines after the first start: after each `\n`, `\r\n` or lone `\r` (as parsed).
fn line_starts(text: &str) -> impl Iterator<Item = usize> + '_ {
    let bytes = text.as_bytes();
    memchr::memchr2_iter(b'\n', b'\r', bytes).filter_map(move |i| {
        // The `\r` of a `\r\n` ends no line of its own.
        (!(bytes[i] == b'\r' && bytes.get(i + 1) == Some(&b'\n'))).then_some(i + 1)
    })
}

/// The 1-based line holding byte `byte`.
pub fn line_of_byte(text: &str, byte: usize) -> u32 {
    let end = byte.min(text.len());
    let newlines = line_starts(text).take_while(|&start| start <= end).count();
    u32::try_from(newlines).unwrap_or(u32::MAX - 1) + 1
}

/// Number of lines of `text` (a final newline ends the last line rather than starting one, but
/// an empty text still has one line).
pub fn line_count(text: &str) -> u32 {
    let n = line_starts(text).count() + usize::from(!text.ends_with(['\n', '\r']));
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Comments out the 1-based lines `lines` (inclusive) in the dialect's form (`G01 X1 (cut)` →
/// `(G01 X1) (cut)`, or `; ` for LinuxCNC) or, when every non-blank one is commented, uncomments.
pub fn toggle_comment(text: &str, lines: RangeInclusive<u32>, dialect: Dialect) -> String {
    let semicolon = dialect.semicolon_is_comment();
    // The lines to change: selected and not blank.
    let chosen = |(i, l): &(usize, &str)| lines.contains(&(*i as u32 + 1)) && !l.trim().is_empty();
    let mark = if semicolon { ';' } else { '(' };
    let commented = |l: &str| l.trim_start().starts_with(mark);
    let uncomment_all = (text.split('\n').enumerate().filter(chosen)).all(|(_, l)| commented(l));
    let out: Vec<String> = (text.split('\n').enumerate())
        .map(|(i, line)| {
            let chosen = chosen(&(i, line));
            if chosen && uncomment_all {
                uncomment_line(line, semicolon)
            } else if chosen && !commented(line) {
                comment_line(line, semicolon)
            } else {
                line.to_string()
            }
        })
        .collect();
    out.join("\n")
}

fn comment_line(line: &str, semicolon: bool) -> String {
    let body = line.strip_suffix('\r').unwrap_or(line);
    let cr = if body.len() < line.len() { "\r" } else { "" };
    let indent_len = body.len() - body.trim_start().len();
    let (indent, rest) = body.split_at(indent_len);
    if semicolon {
        return format!("{indent}; {rest}{cr}");
    }
    // Each piece of code between comments is wrapped (Fanuc comments do not nest).
    let mut out = String::from(indent);
    let mut rest = rest;
    while !rest.is_empty() {
        // A comment, or the code up to the next one.
        let end = match rest.find('(') {
            Some(0) => rest.find(')').map_or(rest.len(), |j| j + 1),
            found => found.unwrap_or(rest.len()),
        };
        let (piece, after) = rest.split_at(end);
        let code = piece.trim_end();
        if piece.starts_with('(') || code.trim().is_empty() {
            out.push_str(piece);
        } else {
            out.push_str(&format!("({code}){}", &piece[code.len()..]));
        }
        rest = after;
    }
    out.push_str(cr);
    out
}

fn uncomment_line(line: &str, semicolon: bool) -> String {
    let indent_len = line.len() - line.trim_start().len();
    let (indent, rest) = line.split_at(indent_len);
    if semicolon {
        let rest = rest.strip_prefix(';').unwrap_or(rest);
        let rest = rest.strip_prefix(' ').unwrap_or(rest);
        return format!("{indent}{rest}");
    }
    // Unwrap the first comment: `(G01 X1) (cut)` → `G01 X1 (cut)`.
    let Some(inner) = rest.strip_prefix('(') else {
        return line.to_string();
    };
    match inner.find(')') {
        Some(j) => format!("{indent}{}{}", &inner[..j], &inner[j + 1..]),
        None => format!("{indent}{inner}"),
    }
}

/// How [`renumber`] numbers blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenumberOptions {
    /// The first N number.
    pub start: u32,
    /// The increment between blocks.
    pub step: u32,
    /// Number every block, not only those that already have an N number.
    pub all_blocks: bool,
}

impl Default for RenumberOptions {
    fn default() -> Self {
        RenumberOptions {
            start: 10,
            step: 10,
            all_blocks: false,
        }
    }
}

/// The outcome of [`renumber`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Renumbered {
    /// The renumbered text.
    pub text: String,
    /// Blocks that got a new or changed N number.
    pub numbered: usize,
    /// `GOTO n` and `M99 Pn` targets rewritten to the new numbers.
    pub targets: usize,
}

/// Renumbers N words `start`, `start + step`, … in text order (every block's with `all_blocks`;
/// blank, comment, `%` and `O…`/`:…` lines are no blocks); `GOTO n` and `M99 Pn` targets follow.
pub fn renumber(text: &str, options: RenumberOptions, dialect: Dialect) -> Renumbered {
    let step = options.step.max(1);
    let mut next = options.start;
    let mut map = std::collections::HashMap::new();
    let mut numbered = 0;
    let mut lines: Vec<String> = Vec::new();
    for line in text.split('\n') {
        let Some(at) = block_start(line, dialect) else {
            lines.push(line.to_string());
            continue;
        };
        let (head, body) = line.split_at(at);
        // The rest of the block, and what starting it needs no space after the new number.
        let (rest, spaced): (&str, &[char]) = match n_word(body) {
            Some((len, old)) => {
                if let Some(old) = old {
                    map.entry(old).or_insert(next);
                }
                (&body[len..], &[' ', '\t'])
            }
            None if options.all_blocks => (body, &[' ', '\t', '\r']),
            None => {
                lines.push(line.to_string());
                continue;
            }
        };
        let joined = rest.is_empty() || rest.starts_with(spaced);
        let sep = if joined { "" } else { " " };
        lines.push(format!("{head}N{next}{sep}{rest}"));
        numbered += 1;
        next = next.saturating_add(step);
    }
    let mut targets = 0;
    for line in &mut lines {
        if let Some((new, n)) = retarget(line, &map, dialect) {
            *line = new;
            targets += n;
        }
    }
    Renumbered {
        text: lines.join("\n"),
        numbered,
        targets,
    }
}

/// Where the block's words start on `line` (past indentation and `/`, `/1`–`/9`); `None`: none.
fn block_start(line: &str, dialect: Dialect) -> Option<usize> {
    let bytes = line.as_bytes();
    let skip_space = |i: usize| i + bytes[i..].iter().take_while(|b| b" \t".contains(b)).count();
    let mut i = skip_space(0);
    if bytes.get(i) == Some(&b'/') {
        i += 1 + usize::from(bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        i = skip_space(i);
    }
    let first = *bytes.get(i)?;
    let no_block = match first {
        b'\r' | b'%' | b'(' | b':' | b';' => true,
        b'/' if dialect == Dialect::Syntec => bytes.get(i + 1) == Some(&b'/'),
        b'O' | b'o' => {
            // `O1234` program numbers and LinuxCNC `o100 sub` lines; not `OR`-less macros.
            bytes
                .get(i + 1)
                .is_some_and(|b| b.is_ascii_digit() || *b == b'<')
        }
        _ => false,
    };
    (!no_block).then_some(i)
}

/// The length of an `N` word at the start of `body` and its integer value, if it has one.
fn n_word(body: &str) -> Option<(usize, Option<u64>)> {
    let bytes = body.as_bytes();
    if !matches!(bytes.first(), Some(b'N' | b'n')) {
        return None;
    }
    let digits = digits_after(bytes, 1);
    (!digits.is_empty()).then(|| (digits.end, body[digits].parse().ok()))
}

/// The digits after `from` in `bytes`, past any spaces (empty where there are none).
fn digits_after(bytes: &[u8], from: usize) -> Range<usize> {
    let rest = |at: usize| bytes.get(at..).unwrap_or_default().iter();
    let start = from + rest(from).take_while(|b| **b == b' ').count();
    start..start + rest(start).take_while(|b| b.is_ascii_digit()).count()
}

/// Rewrites literal `GOTO n` and `M99 Pn` targets of one line through `map` (old → new).
fn retarget(
    line: &str,
    map: &std::collections::HashMap<u64, u32>,
    dialect: Dialect,
) -> Option<(String, usize)> {
    if map.is_empty() || dialect == Dialect::LinuxCnc {
        return None;
    }
    let upper = line.to_ascii_uppercase();
    let code_end = upper.find('(').unwrap_or(upper.len());
    let mut edits: Vec<(Range<usize>, u32)> = Vec::new();
    let mut target_after = |key_end: usize| {
        let digits = digits_after(upper.as_bytes(), key_end);
        if !digits.is_empty() && digits.end <= code_end {
            let old: Option<u64> = upper[digits.clone()].parse().ok();
            if let Some(new) = old.and_then(|o| map.get(&o)) {
                edits.push((digits, *new));
            }
        }
    };
    for (at, _) in upper[..code_end].match_indices("GOTO") {
        target_after(at + 4);
    }
    let has_m99 = upper[..code_end]
        .match_indices('M')
        .any(|(at, _)| upper[at + 1..].trim_start_matches('0').starts_with("99"));
    if has_m99 {
        for (at, _) in upper[..code_end].match_indices('P') {
            target_after(at + 1);
        }
    }
    if edits.is_empty() {
        return None;
    }
    let mut out = line.to_string();
    let count = edits.len();
    edits.sort_by_key(|(r, _)| std::cmp::Reverse(r.start));
    for (range, new) in edits {
        out.replace_range(range, &new.to_string());
    }
    Some((out, count))
}

/// One completion offered for a partly typed code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Completion {
    /// The code as it is inserted (`G01`, `G54.1`).
    pub code: String,
    /// Its one-line meaning in the dialect.
    pub name: &'static str,
}

/// The G or M word being typed just before byte `cursor`: its byte range and text (`G8`), when
/// the cursor follows a letter G/M and digits at the start of a word.
pub fn completion_prefix(text: &str, cursor: usize) -> Option<(Range<usize>, String)> {
    let cursor = cursor.min(text.len());
    let bytes = text.as_bytes();
    let mut i = cursor;
    while i > 0 && (bytes[i - 1].is_ascii_digit() || bytes[i - 1] == b'.') {
        i -= 1;
    }
    let letter_at = i.checked_sub(1)?;
    let letter = bytes[letter_at].to_ascii_uppercase();
    if letter != b'G' && letter != b'M' {
        return None;
    }
    // The letter starts a word: not the middle of `GOTO`, `MOD` or a name.
    if letter_at > 0 && bytes[letter_at - 1].is_ascii_alphabetic() {
        return None;
    }
    if bytes.get(cursor).is_some_and(u8::is_ascii_alphanumeric) {
        return None;
    }
    // Not inside a comment on this line.
    let line_start = text[..letter_at].rfind('\n').map_or(0, |j| j + 1);
    let before = &text[line_start..letter_at];
    if before.rfind('(') > before.rfind(')') || before.contains(';') {
        return None;
    }
    Some((
        letter_at..cursor,
        text[letter_at..cursor].to_ascii_uppercase(),
    ))
}

/// The codes of `dialect` that `prefix` (`G`, `G8`, `M0`, `G54.`) can start, at most `limit`.
/// Digits match with or without the leading zero: `G1` offers `G01` and `G10`–`G19`.
pub fn completions(dialect: Dialect, prefix: &str, limit: usize) -> Vec<Completion> {
    let prefix = prefix.to_ascii_uppercase();
    let Some(letter) = prefix.bytes().next() else {
        return Vec::new();
    };
    let typed = &prefix[1..];
    swarf_syntax::codes::codes_of(dialect)
        .filter(|def| def.code.letter == letter)
        .filter(|def| {
            let padded = def.code.to_string();
            let plain = padded[1..].trim_start_matches('0');
            padded[1..].starts_with(typed) || plain.starts_with(typed.trim_start_matches('0'))
        })
        .take(limit)
        .map(|def| Completion {
            code: def.code.to_string(),
            name: def.name,
        })
        .collect()
}

/// The alarm a control manual names in a diagnostic message (`COR-006`, `alarm 12`), if any.
pub fn alarm_in(message: &str) -> Option<&str> {
    if let Some(at) = message.find("COR-") {
        let digits = message[at + 4..].find(|c: char| !c.is_ascii_digit());
        let end = digits.map_or(message.len(), |j| at + 4 + j);
        return (end > at + 4).then(|| &message[at..end]);
    }
    let lower = message.to_ascii_lowercase();
    let at = lower.find("alarm ")?;
    let start = at + 6;
    let end = message[start..]
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '.'))
        .map_or(message.len(), |j| start + j);
    let name = message[start..end].trim_end_matches('.');
    name.bytes()
        .any(|b| b.is_ascii_digit())
        .then(|| &message[at..start + name.len()])
}
