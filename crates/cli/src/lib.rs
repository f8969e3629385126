//! The `swarf` command line: `check`, `canon` and `stats` over G-code files, and `explain`. It is
//! a library to be tested in-process; `main.rs` only forwards the arguments and exit status.

mod explain;
mod render;

use std::ffi::OsString;
use std::io::{BufRead as _, Read as _, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Parser, Subcommand};
use serde_json::json;
use swarf_interp::{Canon, Setup, Sink, Source};
use swarf_stock::{Finding, StockRun, StockSetup};
use swarf_syntax::{
    Decoded, Diagnostic, Dialect, LineIndex, LineSource, LinkedFile, LinkedSource, Lookup,
    MAX_FILE_BYTES, Program, Severity, Span, decode_owned, parse,
};
use swarf_toolpath::Toolpath;

/// Exit status: no error diagnostics.
pub const EXIT_OK: i32 = 0;
/// Exit status: the program has at least one error.
pub const EXIT_ERRORS: i32 = 1;
/// Exit status: bad usage or an I/O problem.
pub const EXIT_USAGE: i32 = 2;

#[derive(Parser, Debug)]
#[command(
    name = "swarf",
    version,
    about = "Check, run and measure G-code programs the way the selected CNC control would"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args, Debug)]
struct RunOptions {
    /// Controller dialect: fanuc, syntec, lnc, kt, gsk or linuxcnc.
    #[arg(long, default_value = "fanuc", value_parser = parse_dialect)]
    dialect: Dialect,
    /// Machine setup (offset registers, work offsets, machine parameters) as TOML.
    #[arg(long, value_name = "SETUP.toml")]
    setup: Option<PathBuf>,
    /// The largest program, setup or called file read, in MiB: a larger one is refused.
    #[arg(long, value_name = "MB", default_value_t = MAX_FILE_BYTES >> 20)]
    max_file_mb: u64,
}

impl RunOptions {
    /// The largest file read, in bytes.
    fn max_file_bytes(&self) -> u64 {
        self.max_file_mb.saturating_mul(1 << 20)
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse and interpret programs; print one line per diagnostic.
    Check {
        /// Program files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        #[command(flatten)]
        opts: RunOptions,
        #[arg(long, help = STOCK_HELP)]
        stock: bool,
    },
    /// Print the canonical motion stream as JSON Lines.
    Canon {
        /// Program file.
        file: PathBuf,
        #[command(flatten)]
        opts: RunOptions,
    },
    #[command(about = STATS_ABOUT)]
    Stats(StatsArgs),
    /// Draw the toolpath to a PNG image offscreen (no display needed).
    Render(render::RenderArgs),
    /// Explain a G/M code (G83, G54.1, M98) or an address letter (Q) as each control reads it,
    /// or a diagnostic code (E-ARC-RADIUS).
    Explain(explain::ExplainArgs),
}

/// What `--stock` does, in the help of each command that has it.
const STOCK_HELP: &str = "Cut the stock and check for rapids into it and shank cuts even when \
                          the setup has no [stock] (a box around the feed moves is assumed)";

/// What `swarf stats` does, in its help and the command list.
const STATS_ABOUT: &str = "Print statistics: blocks, motions, bounds, lengths, time, tools";

#[derive(clap::Args, Debug)]
struct StatsArgs {
    /// Program file.
    file: PathBuf,
    #[command(flatten)]
    opts: RunOptions,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Hold the whole parsed program in memory while it runs, as the editor does, instead
    /// of running it piece by piece as it is parsed (the figures are the same).
    #[arg(long)]
    whole: bool,
    #[arg(long, help = STOCK_HELP)]
    stock: bool,
}

/// The command line parsed; `Err` with the exit status once clap has printed its message
/// (help, version or a usage error).
fn parse_args(
    args: Vec<OsString>,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<Command, i32> {
    Cli::try_parse_from(args)
        .map(|cli| cli.command)
        .map_err(|e| {
            let to: &mut dyn Write = if e.use_stderr() { err } else { out };
            let _ = to.write_all(e.render().to_string().as_bytes());
            if e.use_stderr() { EXIT_USAGE } else { EXIT_OK }
        })
}

pub(crate) fn parse_dialect(s: &str) -> Result<Dialect, String> {
    s.parse::<Dialect>().map_err(|e| e.to_string())
}

/// Runs the CLI with `args` (including the program name), writing to `out` and `err`;
/// returns the exit status.
pub fn run<I, T>(args: I, out: &mut dyn Write, err: &mut dyn Write) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let command = match parse_args(args.into_iter().map(Into::into).collect(), out, err) {
        Ok(command) => command,
        Err(code) => return code,
    };
    let result = match command {
        Command::Check { files, opts, stock } => check(&files, &opts, stock, err),
        Command::Canon { file, opts } => canon(&file, &opts, out, err),
        Command::Stats(args) => stats(&args, out, err),
        Command::Render(args) => render::render(&args, out, err),
        Command::Explain(args) => explain::explain(&args, out, err),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            let _ = writeln!(err, "swarf: {e:#}");
            EXIT_USAGE
        }
    }
}

/// A program file read, decoded and parsed.
struct Loaded {
    path: String,
    /// The text, for the diagnostics' lines and columns.
    text: String,
    program: Program,
    /// Decoding and parsing diagnostics.
    diagnostics: Vec<Diagnostic>,
    /// The files linked for the program's calls, in the order of `program.linked`.
    linked: Vec<LinkedSource>,
}

/// Most files linked to one program (a bound on runaway chains of calls).
const MAX_LINKED: usize = 64;

/// Links the programs `program` calls and lacks from files beside it; returns texts and warnings.
/// A file that cannot be read (a folder, over `max` bytes) is named in the call's error; one that
/// changed while read gets `W-FILE-CHANGED`.
fn link_external(
    program: &mut Program,
    path: &Path,
    main_len: usize,
    dialect: Dialect,
    max: u64,
) -> (Vec<LinkedSource>, Vec<Diagnostic>) {
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut changed = Vec::new();
    let linked = program.link_calls(main_len, dialect, MAX_LINKED, |missing| {
        // The files beside it that may hold a called program.
        let paths: Vec<PathBuf> = (missing.file_names().iter())
            .map(|name| dir.join(name))
            .filter(|c| c != path)
            .collect();
        // A file first; else something else of a candidate's name (a folder) is named.
        let Some(file) = paths.iter().find(|c| c.is_file()) else {
            return paths.iter().find(|c| c.exists()).map_or(Lookup::None, |c| {
                Lookup::Refused(format!("{} is not a file", c.display()))
            });
        };
        match read_file(file, max) {
            Ok((bytes, same)) => {
                let name = file.display().to_string();
                if !same {
                    changed.push(name.clone());
                }
                Lookup::Found(name, decode_owned(bytes).text)
            }
            Err(why) => Lookup::Refused(why),
        }
    });
    let linked_file = |name: &String| program.linked.iter().find(|l| l.name == *name);
    let found = changed.iter().filter_map(linked_file);
    let at = |l: &LinkedFile| Span::new(l.first_byte as usize, l.first_byte as usize);
    let warnings = found.map(|l| changed_warning(&l.name, at(l))).collect();
    (linked, warnings)
}

/// The warning that file `name` changed while it was read, at `span`.
fn changed_warning(name: impl std::fmt::Display, span: Span) -> Diagnostic {
    let message =
        format!("{name} changed while it was read: what was read may be part old, part new");
    Diagnostic::warning(span, "W-FILE-CHANGED", message)
}

/// The bytes of the file at `path`, refused past `max` bytes before more is read (a file that
/// grows, or a device that never ends, is read no further than `max` + 1 bytes), and whether
/// the file stayed the same while it was read (its length and time of change).
fn read_file(path: &Path, max: u64) -> Result<(Vec<u8>, bool), String> {
    let shown = path.display();
    let cannot = |e: std::io::Error| format!("cannot read {shown}: {e}");
    let mib = max >> 20;
    let too_large = || format!("{shown} is larger than {mib} MiB, the most read (--max-file-mb)");
    let mut file = std::fs::File::open(path).map_err(cannot)?;
    let before = file.metadata().map_err(cannot)?;
    if before.is_dir() {
        return Err(format!("{shown} is a folder, not a file"));
    }
    if before.len() > max {
        return Err(too_large());
    }
    let mut bytes = Vec::with_capacity(usize::try_from(before.len()).unwrap_or(0));
    let mut limited = (&mut file).take(max.saturating_add(1));
    limited.read_to_end(&mut bytes).map_err(cannot)?;
    if bytes.len() as u64 > max {
        return Err(too_large());
    }
    let same =
        !before.is_file() || (bytes.len() as u64 == before.len() && unchanged(path, &before));
    Ok((bytes, same))
}

/// Whether the file at `path` still has `before`'s length and time of change.
fn unchanged(path: &Path, before: &std::fs::Metadata) -> bool {
    let same = |m: std::fs::Metadata| {
        (m.len(), m.modified().ok()) == (before.len(), before.modified().ok())
    };
    std::fs::metadata(path).is_ok_and(same)
}

/// The setup named by `--setup`, or the default one, with its stock and tools; a setup that
/// changed while it was read gets `W-FILE-CHANGED` on `err`.
fn read_setup(opts: &RunOptions, err: &mut dyn Write) -> anyhow::Result<(Setup, StockSetup)> {
    let Some(p) = &opts.setup else {
        return Ok((Setup::default(), StockSetup::default()));
    };
    let (bytes, same) =
        read_file(p, opts.max_file_bytes()).map_err(|e| anyhow::anyhow!("setup: {e}"))?;
    if !same {
        let (path, w) = (p.display(), changed_warning(p.display(), Span::default()));
        writeln!(err, "{path}: {}[{}]: {}", w.severity, w.code, w.message)?;
    }
    let text = String::from_utf8(bytes)
        .map_err(|e| anyhow::anyhow!("cannot read setup {}: {e}", p.display()))?;
    let invalid = |e: &dyn std::fmt::Display| anyhow::anyhow!("invalid setup {}: {e}", p.display());
    let setup = Setup::from_toml(&text).map_err(|e| invalid(&e))?;
    let stock = StockSetup::from_setup(&setup).map_err(|e| invalid(&e))?;
    Ok((setup, stock))
}

/// Cuts `path` out of the stock when the setup has `[stock]` or `asked` (`--stock`): the cut
/// and its diagnostics at their places in `loaded`.
fn cut_stock(
    path: &Toolpath,
    stock: &StockSetup,
    asked: bool,
    loaded: &Loaded,
) -> Option<(StockRun, Vec<Diagnostic>)> {
    if !asked && stock.stock.is_none() {
        return None;
    }
    let mut cut = StockRun::new(path, stock)?;
    cut.simulation.step(path, usize::MAX);
    let diags = cut.diagnostics(|line| loaded.line_span(line));
    Some((cut, diags))
}

fn load(path: &Path, opts: &RunOptions) -> anyhow::Result<Loaded> {
    Ok(load_decoded(path, read_decoded(path, opts)?, opts))
}

/// Reads and decodes a program file (at most `--max-file-mb`); one that changed while it was
/// read gets `W-FILE-CHANGED` among its decoding diagnostics.
fn read_decoded(path: &Path, opts: &RunOptions) -> anyhow::Result<Decoded> {
    let (bytes, same) = read_file(path, opts.max_file_bytes()).map_err(anyhow::Error::msg)?;
    let mut decoded = decode_owned(bytes);
    if !same {
        (decoded.diagnostics).push(changed_warning(path.display(), Span::default()));
    }
    Ok(decoded)
}

/// Parses a decoded program file and links the programs it calls from files beside it.
fn load_decoded(path: &Path, mut decoded: Decoded, opts: &RunOptions) -> Loaded {
    let mut program = parse(&decoded.text, opts.dialect);
    let (len, max) = (decoded.text.len(), opts.max_file_bytes());
    let (linked, warnings) = link_external(&mut program, path, len, opts.dialect, max);
    decoded.diagnostics.extend(warnings);
    Loaded::new(path, decoded.diagnostics, decoded.text, program, linked)
}

/// The reading diagnostics and the run's, in one list sorted by position.
fn merged(mut reading: Vec<Diagnostic>, run: Vec<Diagnostic>) -> Vec<Diagnostic> {
    reading.extend(run);
    reading.sort_by_key(|d| (d.span.start, d.span.end));
    reading
}

/// Lines parsed and run at a time when `stats` runs a straight program piece by piece: the
/// parsed blocks of a long program are never held all at once.
const PIECE_LINES: usize = 2048;

/// Parses and runs a straight-through `source` into `sink` piece by piece, dropping blocks once
/// run; `None` if it jumps, loops or calls (`sink` then has the run's first events).
fn run_pieces(
    source: &mut dyn LineSource,
    dialect: Dialect,
    setup: &Setup,
    sink: &mut dyn Sink,
) -> Option<(Program, usize, Vec<Diagnostic>)> {
    let mut reader = swarf_syntax::ParseRun::new(dialect);
    let mut interp = swarf_interp::Interpreter::new(setup.clone(), dialect);
    let mut blocks = 0;
    let mut ended = false;
    loop {
        let done = reader.step_from(source, PIECE_LINES);
        blocks += reader.program().blocks.len();
        if !ended {
            match interp.run_piece(reader.program(), sink) {
                swarf_interp::Piece::Ran => {}
                swarf_interp::Piece::Ended => ended = true,
                swarf_interp::Piece::NeedsWhole => return None,
            }
        }
        reader.clear_blocks();
        if done {
            break;
        }
    }
    interp.finish_pieces(sink);
    Some((reader.finish(), blocks, interp.take_diagnostics()))
}

/// A program file read (see [`read_run`]).
enum Read {
    /// Run piece by piece to its end: the program (without its blocks), how many blocks it
    /// had, and every diagnostic, sorted.
    Ran(Loaded, usize, Vec<Diagnostic>),
    /// Parsed whole, not run: it jumps, loops or calls (or the whole program was asked for).
    Whole(Loaded),
}

/// Runs a decoded file into `sink` piece by piece if it runs straight through; else parses it
/// whole, with its called files, for the caller to run (`sink` then has the first events).
fn read_run(
    file: &Path,
    decoded: Decoded,
    opts: &RunOptions,
    setup: &Setup,
    whole: bool,
    sink: &mut dyn Sink,
) -> Read {
    let pieces = (!whole)
        .then(|| run_pieces(&mut decoded.text.as_str(), opts.dialect, setup, sink))
        .flatten();
    match pieces {
        Some((program, blocks, run)) => {
            let mut loaded =
                Loaded::new(file, decoded.diagnostics, decoded.text, program, Vec::new());
            let diags = loaded.all_diagnostics(run);
            Read::Ran(loaded, blocks, diags)
        }
        None => Read::Whole(load_decoded(file, decoded, opts)),
    }
}

/// Runs a plain UTF-8 file into `sink` as it reads it ([`FileLines`]), or parses it whole if it
/// jumps, loops or calls; `None` if it is not plain UTF-8 (`sink` then has the first events).
fn stream_run(
    file: &Path,
    opts: &RunOptions,
    setup: &Setup,
    sink: &mut dyn Sink,
) -> anyhow::Result<Option<Read>> {
    let Some(mut lines) = FileLines::open(file, opts.max_file_bytes()) else {
        return Ok(None);
    };
    let ran = run_pieces(&mut lines, opts.dialect, setup, sink);
    if lines.failed {
        return Ok(None);
    }
    let Some((program, blocks, run)) = ran else {
        return Ok(Some(Read::Whole(load(file, opts)?)));
    };
    let changed =
        (!unchanged(file, &lines.opened)).then(|| changed_warning(file.display(), Span::default()));
    let decoding = changed.into_iter().collect();
    let mut loaded = Loaded::new(file, decoding, String::new(), program, Vec::new());
    let diags = loaded.all_diagnostics(run);
    // The text is read again only for the lines and columns of the diagnostics.
    if !diags.is_empty() {
        loaded.text = read_decoded(file, opts)?.text;
    }
    Ok(Some(Read::Ran(loaded, blocks, diags)))
}

/// A program file read a piece at a time as it is parsed: the text held is the piece last read,
/// which ends at a line end (or the file's end).
struct FileLines {
    reader: std::io::BufReader<std::fs::File>,
    /// The file's metadata when it was opened.
    opened: std::fs::Metadata,
    /// The piece last read, from byte `at` on.
    text: String,
    at: usize,
    /// Whether the file is to be read whole instead: it is not plain UTF-8 (or opens with a
    /// byte-order mark), grew, or could not be read.
    failed: bool,
}

impl FileLines {
    fn open(path: &Path, max: u64) -> Option<Self> {
        let file = std::fs::File::open(path).ok()?;
        let fits = |m: &std::fs::Metadata| m.is_file() && m.len() <= max;
        let meta = file.metadata().ok().filter(fits)?;
        Some(FileLines {
            reader: std::io::BufReader::new(file),
            opened: meta,
            text: String::new(),
            at: 0,
            failed: false,
        })
    }
}

impl LineSource for FileLines {
    fn len(&self) -> usize {
        usize::try_from(self.opened.len()).unwrap_or(usize::MAX)
    }

    fn line(&mut self, start: usize, end: usize) -> &str {
        if self.at + self.text.len() < end {
            self.failed |= self.reader.read_to_string(&mut self.text).is_err();
        }
        let (from, to) = (start.saturating_sub(self.at), end.saturating_sub(self.at));
        (self.text.get(from..to.min(self.text.len()))).unwrap_or_default()
    }

    fn rest(&mut self, start: usize) -> &str {
        // The lines are asked for in order: past the piece held, the next 64 KiB are read, and
        // the rest of their last line.
        if start >= self.at + self.text.len() && !self.failed {
            self.at += self.text.len();
            // The last piece's buffer is read into again.
            let mut bytes = std::mem::take(&mut self.text).into_bytes();
            bytes.clear();
            let piece = (&mut self.reader).take(64 << 10).read_to_end(&mut bytes);
            let line = self.reader.read_until(b'\n', &mut bytes);
            match (piece, line, String::from_utf8(bytes)) {
                (Ok(_), Ok(_), Ok(text)) => self.text = text,
                _ => self.failed = true,
            }
            let bom = self.at == 0 && self.text.starts_with('\u{feff}');
            self.failed |= bom || self.at + self.text.len() > self.len();
        }
        let from = start.saturating_sub(self.at);
        self.text.get(from..).unwrap_or_default()
    }
}

impl Loaded {
    /// A program read from `path`, with its reading diagnostics: the decoding ones, then the
    /// parser's.
    fn new(
        path: &Path,
        decoding: Vec<Diagnostic>,
        text: String,
        mut program: Program,
        linked: Vec<LinkedSource>,
    ) -> Self {
        // Moved, not copied: a broken file may have millions.
        let mut diagnostics = decoding;
        diagnostics.append(&mut program.diagnostics);
        Loaded {
            path: path.display().to_string(),
            text,
            program,
            diagnostics,
            linked,
        }
    }

    /// The reading diagnostics (moved out) and the run's `run`, sorted by position.
    fn all_diagnostics(&mut self, run: Vec<Diagnostic>) -> Vec<Diagnostic> {
        merged(std::mem::take(&mut self.diagnostics), run)
    }

    /// The span of 1-based `line` of the program, in a linked file's text when it is one of
    /// theirs.
    fn line_span(&self, line: u32) -> Span {
        let line0 = line.saturating_sub(1);
        let linked = self
            .program
            .linked_at_line(line0)
            .and_then(|i| Some((self.program.linked.get(i)?, self.linked.get(i)?)));
        match linked {
            Some((at, l)) => {
                let span = swarf_stock::line_span(&l.lines, line0 - at.first_line + 1);
                let first = at.first_byte as usize;
                Span::new(first + span.start as usize, first + span.end as usize)
            }
            None => swarf_stock::line_span(&self.program.lines, line),
        }
    }

    fn print(&self, diags: &[Diagnostic], err: &mut dyn Write) -> std::io::Result<i32> {
        let index: &LineIndex = &self.program.lines;
        let mut cols = index.cursor(&self.text);
        let mut status = EXIT_OK;
        // Standard error writes at once what it is given: a program with millions of
        // diagnostics would make a system call of each.
        let mut err = std::io::BufWriter::with_capacity(64 << 10, err);
        for d in diags {
            // A diagnostic in a linked file is reported at its place in that file.
            let linked = self
                .program
                .linked_at_offset(d.span.start)
                .and_then(|i| Some((self.program.linked.get(i)?, self.linked.get(i)?)));
            let (path, (line, col)) = match linked {
                Some((at, l)) => (
                    l.name.as_str(),
                    l.lines.line_col(&l.text, d.span.start - at.first_byte),
                ),
                None => (self.path.as_str(), cols.line_col(d.span.start)),
            };
            writeln!(
                err,
                "{path}:{line}:{col}: {}[{}]: {}",
                d.severity, d.code, d.message
            )?;
            if d.severity == Severity::Error {
                status = EXIT_ERRORS;
            }
        }
        err.flush()?;
        Ok(status)
    }
}

fn check(
    files: &[PathBuf],
    opts: &RunOptions,
    cut: bool,
    err: &mut dyn Write,
) -> anyhow::Result<i32> {
    let (setup, stock) = read_setup(opts, err)?;
    let mut status = EXIT_OK;
    for file in files {
        let decoded = match read_decoded(file, opts) {
            Ok(d) => d,
            Err(e) => {
                writeln!(err, "swarf: {e:#}")?;
                status = EXIT_USAGE;
                continue;
            }
        };
        // Only the diagnostics are wanted: no toolpath is kept unless the stock is cut.
        let cuts = cut || stock.stock.is_some();
        let mut path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
        let mut null = NullSink;
        let sink: &mut dyn Sink = if cuts { &mut path } else { &mut null };
        let (loaded, mut diags) = match read_run(file, decoded, opts, &setup, false, sink) {
            Read::Ran(loaded, _, diags) => (loaded, diags),
            Read::Whole(mut loaded) => {
                path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
                let sink: &mut dyn Sink = if cuts { &mut path } else { &mut null };
                let run = swarf_interp::run(&loaded.program, setup.clone(), sink);
                let diags = loaded.all_diagnostics(run);
                (loaded, diags)
            }
        };
        if let Some((_, more)) = cut_stock(&path, &stock, cut, &loaded) {
            diags = merged(diags, more);
        }
        // The worst status of all: a usage error, then errors in a program.
        status = status.max(loaded.print(&diags, err)?);
    }
    Ok(status)
}

struct NullSink;

impl Sink for NullSink {
    fn emit(&mut self, _: Source, _: &Canon) {}
}

/// Writes each event as one JSON line; remembers the first write error and stops writing.
struct JsonLines<'a> {
    out: &'a mut dyn Write,
    error: Option<std::io::Error>,
    /// The program, when it has others linked to it: an event from a linked file names that
    /// file, with its line there.
    program: Option<&'a Program>,
    /// Events written, and how many of the first events to leave out (written already by a
    /// run that was tried piece by piece: a whole run repeats them).
    written: u64,
    skip: u64,
}

impl<'a> JsonLines<'a> {
    fn new(out: &'a mut dyn Write, program: Option<&'a Program>, skip: u64) -> Self {
        let (error, written) = (None, 0);
        JsonLines {
            out,
            error,
            program,
            written,
            skip,
        }
    }
}

impl Sink for JsonLines<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        if self.skip > 0 {
            self.skip -= 1;
            return;
        }
        self.written += 1;
        let mut value = event.to_json(source);
        let line0 = source.line.saturating_sub(1);
        if let Some(file) = (self.program).and_then(|p| p.linked.get(p.linked_at_line(line0)?)) {
            value["file"] = json!(file.name);
            value["line"] = json!(line0 - file.first_line + 1);
        }
        if self.error.is_none()
            && let Err(e) = writeln!(self.out, "{value}")
        {
            self.error = Some(e);
        }
    }
}

fn canon(
    file: &Path,
    opts: &RunOptions,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> anyhow::Result<i32> {
    let (setup, _) = read_setup(opts, err)?;
    let decoded = read_decoded(file, opts)?;
    let mut buffered = std::io::BufWriter::new(out);
    let mut pieces = JsonLines::new(&mut buffered, None, 0);
    let read = read_run(file, decoded, opts, &setup, false, &mut pieces);
    let (written, mut error) = (pieces.written, pieces.error.take());
    let (loaded, diags) = match read {
        Read::Ran(loaded, _, diags) => (loaded, diags),
        Read::Whole(mut loaded) => {
            // The whole run makes the same first events as the run tried piece by piece.
            let mut sink = JsonLines::new(&mut buffered, Some(&loaded.program), written);
            let run = swarf_interp::run(&loaded.program, setup.clone(), &mut sink);
            error = error.or(sink.error);
            let diags = loaded.all_diagnostics(run);
            (loaded, diags)
        }
    };
    if let Some(e) = error {
        return Err(anyhow::anyhow!("cannot write output: {e}"));
    }
    buffered.flush()?;
    Ok(loaded.print(&diags, err)?)
}

fn stats(args: &StatsArgs, out: &mut dyn Write, err: &mut dyn Write) -> anyhow::Result<i32> {
    let StatsArgs {
        ref file,
        ref opts,
        json: as_json,
        whole,
        stock: cut,
    } = *args;
    let (setup, stock) = read_setup(opts, err)?;
    let started = Instant::now();
    // The report takes only the path's measures: its segments are kept only to cut the stock,
    // with room made for `moves` of them.
    let keep = cut || stock.stock.is_some();
    let new_path = |moves: usize| {
        if keep {
            let mut path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
            path.reserve(moves);
            path
        } else {
            Toolpath::measuring(glam::DVec3::ZERO, &setup.machine)
        }
    };
    // About a move a line, and a line is rarely under sixteen bytes.
    let len = std::fs::metadata(file).map_or(0, |m| m.len() as usize);
    let mut path = new_path(len / 16);
    let streamed = (!whole).then(|| stream_run(file, opts, &setup, &mut path));
    let read = if let Some(read) = streamed.transpose()?.flatten() {
        read
    } else {
        path = new_path(len / 16);
        let decoded = read_decoded(file, opts)?;
        read_run(file, decoded, opts, &setup, whole, &mut path)
    };
    let (loaded, blocks, mut diags) = match read {
        Read::Ran(loaded, blocks, diags) => (loaded, blocks, diags),
        Read::Whole(mut loaded) => {
            path = new_path(loaded.program.blocks.len());
            let run = swarf_interp::run(&loaded.program, setup.clone(), &mut path);
            let diags = loaded.all_diagnostics(run);
            let blocks = loaded.program.blocks.len();
            (loaded, blocks, diags)
        }
    };
    let interp_ms = started.elapsed().as_secs_f64() * 1000.0;
    // The material removed, the rapids into the stock and the shank cuts.
    let mut cut_figures = None;
    if let Some((cut, more)) = cut_stock(&path, &stock, cut, &loaded) {
        diags = merged(diags, more);
        let (findings, field) = (cut.simulation.findings(), cut.simulation.field());
        let rapid = |f: &&Finding| matches!(f, Finding::RapidIntoStock { .. });
        let rapids = findings.iter().filter(rapid).count();
        let (removed, shanks) = (field.removed_volume(), findings.len() - rapids);
        cut_figures = Some((removed, rapids, shanks));
    }
    let count = |s: Severity| diags.iter().filter(|d| d.severity == s).count();
    let (errors, warnings) = (count(Severity::Error), count(Severity::Warning));
    let bounds = (path.bounds()).map(|b| json!({"min": b.min.to_array(), "max": b.max.to_array()}));
    let report = json!({
        "file": loaded.path,
        "dialect": opts.dialect.name(),
        "blocks": blocks,
        "motions": path.len(),
        "bounds": bounds,
        "rapid_mm": path.rapid_length_mm(),
        "feed_mm": path.feed_length_mm(),
        "estimated_secs": path.estimated_secs(),
        "tools": path.tools(),
        "holes": path.holes().len(),
        "holes_per_tool": path
            .holes_per_tool()
            .iter()
            .map(|(tool, n)| json!({"tool": tool, "holes": n}))
            .collect::<Vec<_>>(),
        "stock": cut_figures.map(|(removed, rapids, shanks)| json!({
            "removed_mm3": removed,
            "rapids_into_stock": rapids,
            "shank_cuts": shanks,
        })),
        "diagnostics": {"errors": errors, "warnings": warnings, "total": diags.len()},
        "interpretation_ms": interp_ms,
    });
    // One write for the report rather than one a line.
    let mut out = std::io::BufWriter::new(out);
    if as_json {
        writeln!(out, "{report:#}")?;
    } else {
        let mut row = |label: &str, value: String| writeln!(out, "{label:<16}{value}");
        row("file", loaded.path.clone())?;
        row("dialect", opts.dialect.name().to_string())?;
        row("blocks", blocks.to_string())?;
        row("motions", path.len().to_string())?;
        let bounds = path.bounds().map_or("(no motion)".into(), |b| {
            let ([x0, y0, z0], [x1, y1, z1]) = (b.min.to_array(), b.max.to_array());
            format!("X {x0:.3}..{x1:.3}  Y {y0:.3}..{y1:.3}  Z {z0:.3}..{z1:.3} mm")
        });
        row("bounds", bounds)?;
        row("rapid length", format!("{:.3} mm", path.rapid_length_mm()))?;
        row("feed length", format!("{:.3} mm", path.feed_length_mm()))?;
        row("estimated time", format_secs(path.estimated_secs()))?;
        let tools: Vec<String> = path.tools().iter().map(|t| format!("T{t}")).collect();
        let none = tools.is_empty().then(|| "(none)".to_string());
        row("tools", none.unwrap_or_else(|| tools.join(" ")))?;
        let holes: Vec<String> = (path.holes_per_tool().iter())
            .map(|(tool, n)| format!("T{tool}: {n}"))
            .collect();
        if !holes.is_empty() {
            let n = path.holes().len();
            row("holes", format!("{n} ({})", holes.join(", ")))?;
        }
        if let Some((removed, rapids, shanks)) = cut_figures {
            let cut =
                format!("{removed:.3} mm³ removed, {rapids} rapids into it, {shanks} shank cuts");
            row("stock", cut)?;
        }
        let counts = format!("{errors} errors, {warnings} warnings");
        row("diagnostics", counts)?;
        row("interpretation", format!("{interp_ms:.1} ms"))?;
    }
    out.flush()?;
    Ok(loaded.print(&diags, err)?)
}

/// `h:mm:ss.s` for a duration in seconds.
fn format_secs(secs: f64) -> String {
    let total = secs.max(0.0);
    let h = (total / 3600.0).floor();
    let m = ((total - h * 3600.0) / 60.0).floor();
    let s = total - h * 3600.0 - m * 60.0;
    format!("{h:.0}:{m:02.0}:{s:04.1}")
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// Whether `text` runs piece by piece; when it does, its toolpath is the whole run's.
    fn runs_in_pieces(text: &str) -> bool {
        let setup = Setup::default();
        let mut pieces = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
        let Some((_, blocks, _)) = run_pieces(&mut { text }, Dialect::Fanuc, &setup, &mut pieces)
        else {
            return false;
        };
        let program = parse(text, Dialect::Fanuc);
        assert_eq!(blocks, program.blocks.len());
        let mut whole = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
        swarf_interp::run(&program, setup, &mut whole);
        assert_eq!(pieces.len(), whole.len());
        assert_eq!(pieces.bounds(), whole.bounds());
        assert_eq!(pieces.feed_length_mm(), whole.feed_length_mm());
        true
    }

    #[test]
    fn straight_programs_run_in_pieces_and_jumping_ones_do_not() {
        let mut long = String::from("O1000\nG90 G21 G1 F500.\n#1=2.\n");
        for i in 0..20_000 {
            long.push_str(&format!("X{i}. Y#1\n"));
        }
        assert!(runs_in_pieces(&long));
        assert!(runs_in_pieces("G0 X1.\nG81 X2. R1. Z-1. F50.\nG80\nM30\n"));
        assert!(!runs_in_pieces(&format!(
            "{long}M98 P2000\nM30\nO2000\nX1.\nM99\n"
        )));
        assert!(!runs_in_pieces(
            "#1=0\nWHILE [#1 LT 3] DO1\n#1=#1+1\nEND1\nM30\n"
        ));
        assert!(!runs_in_pieces("N1 G0 X1.\nGOTO 1\n"));
        assert!(!runs_in_pieces("G65 P9000 A1.\nM30\n"));
        assert!(!runs_in_pieces("O1\nX1.\nM30\nO2\nX2.\nM99\n"));
    }

    /// A file read a piece at a time as it runs reports as the file read whole does, whatever
    /// its line ends and wherever the pieces cut it; one that is not plain UTF-8 is read whole.
    #[test]
    fn a_file_read_in_pieces_reports_as_the_whole_file() {
        let dir = tempfile::tempdir().unwrap();
        let half = "G1 X1.5 Y2 F100\r\nX2\rY3 @\n".repeat(3000);
        let body = format!("%\n{half}%\n{half}G1 X$");
        let bom = [b"\xef\xbb\xbf".as_slice(), body.as_bytes()].concat();
        let latin = [body.as_bytes(), b"(\xe9)\n"].concat();
        for (name, bytes) in [("a.nc", body.as_bytes()), ("b.nc", &bom), ("c.nc", &latin)] {
            let file = dir.path().join(name);
            std::fs::write(&file, bytes).unwrap();
            let report = |whole| {
                let opts = RunOptions {
                    dialect: Dialect::Fanuc,
                    setup: None,
                    max_file_mb: 256,
                };
                let (file, json, stock) = (file.clone(), false, false);
                let args = StatsArgs {
                    file,
                    opts,
                    json,
                    whole,
                    stock,
                };
                let (mut out, mut err) = (Vec::new(), Vec::new());
                let status = stats(&args, &mut out, &mut err).unwrap();
                let out = String::from_utf8(out).unwrap();
                let out: Vec<_> = out.lines().filter(|l| !l.starts_with("interp")).collect();
                (status, out.join("\n"), String::from_utf8(err).unwrap())
            };
            let (pieces, whole) = (report(false), report(true));
            assert_eq!(pieces, whole, "{name}");
            assert!(pieces.2.lines().count() > 3000, "{name}");
            assert!(pieces.2.contains("N-AFTER-TAPE-END"), "{name}");
        }
    }

    /// A long program run in pieces reports its diagnostics at their lines.
    #[test]
    fn a_long_program_run_in_pieces_reports_where_its_diagnostics_are() {
        let mut long = String::from("G90 G21 G1 F500.\n");
        for i in 0..120_000 {
            long.push_str(&format!("X{i}.5 Y1.\n"));
        }
        let broken = format!("{long}G1 X1. @ Y2.\nM30\n");
        assert!(runs_in_pieces(&broken));
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("t.nc");
        std::fs::write(&file, &broken).unwrap();
        let args = StatsArgs {
            file: file.clone(),
            opts: RunOptions {
                dialect: Dialect::Fanuc,
                setup: None,
                max_file_mb: 256,
            },
            json: false,
            whole: false,
            stock: false,
        };
        let (mut out, mut err) = (Vec::new(), Vec::new());
        assert_eq!(stats(&args, &mut out, &mut err).unwrap(), EXIT_ERRORS);
        let err = String::from_utf8(err).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("{}:120002:8: error", file.display())),
            "{err}"
        );
    }
}
