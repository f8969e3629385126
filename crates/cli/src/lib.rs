//! The `swarf` command line: `check`, `canon` and `stats` over G-code files, and `explain`.
//!
//! Everything is in this library so it can be tested in-process; `main.rs` only forwards the
//! process arguments and exit status.

mod apart;
mod beside;
mod explain;
mod growing;
mod render;
mod waits;

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use beside::{Helper, run_pieces_beside};
use clap::{Parser, Subcommand};
use growing::{Growing, Unread};
pub use render::{RENDER_HELPER, render_elsewhere, render_helper};
use serde_json::json;
use swarf_interp::{Canon, Setup, Sink, Source};
use swarf_syntax::{
    Decoded, Diagnostic, Dialect, LineIndex, LinkedSource, Missing, Program, Severity,
    decode_owned, parse,
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
    /// Explain a G/M code (G83, G54.1, M98) or an address letter (Q) as each control reads it.
    Explain {
        /// The code or address; omit with --list.
        what: Option<String>,
        /// Only this dialect (default: every dialect that has it).
        #[arg(long, value_parser = parse_dialect)]
        dialect: Option<Dialect>,
        /// List every code of the dialect (fanuc unless --dialect is given).
        #[arg(long)]
        list: bool,
        /// Print the Markdown table of every code group per dialect (the README's feature table).
        #[arg(long)]
        table: bool,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

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
    /// of running it piece by piece as it is read (the figures are the same).
    #[arg(long)]
    whole: bool,
    /// Read and run on this thread only (by default, on a machine with two cores or more, a
    /// long program is read on a second thread while the part read before runs; the
    /// figures are the same).
    #[arg(long)]
    one_thread: bool,
}

/// The command line of `swarf stats …` alone: `stats` is read with only its own arguments
/// built, where [`Cli`] builds every subcommand's (with their help texts), about 0.2 ms of a
/// run that may take a few milliseconds. It reads, and reports errors, as [`Cli`] does.
#[derive(Parser, Debug)]
#[command(name = "swarf")]
struct StatsCli {
    #[command(subcommand)]
    command: StatsCommand,
}

#[derive(Subcommand, Debug)]
enum StatsCommand {
    #[command(about = STATS_ABOUT)]
    Stats(StatsArgs),
}

/// The command line parsed; `Err` with the exit status once clap has printed its message
/// (help, version or a usage error).
fn parse_args(
    args: Vec<OsString>,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<Command, i32> {
    if let Some(stats) = plain_stats(&args) {
        return Ok(Command::Stats(stats));
    }
    let parsed = if args.get(1).is_some_and(|arg| arg == "stats") {
        StatsCli::try_parse_from(args).map(|cli| match cli.command {
            StatsCommand::Stats(args) => Command::Stats(args),
        })
    } else {
        Cli::try_parse_from(args).map(|cli| cli.command)
    };
    parsed.map_err(|e| {
        let text = e.render().to_string();
        if e.use_stderr() {
            let _ = err.write_all(text.as_bytes());
            EXIT_USAGE
        } else {
            let _ = out.write_all(text.as_bytes());
            EXIT_OK
        }
    })
}

/// `swarf stats FILE` with any of its options each given once, read without clap: the
/// command line a benchmark or a script repeats, where building clap's parser of even the one
/// subcommand takes about 0.25 ms of a run that may take a few milliseconds. `None` for any
/// other command line (help, version, an option given twice or misspelt, a value that does
/// not parse, `--`, a lone `-`, a second file …): clap reads it, and reports its errors. What
/// this reads, clap reads the same (a test holds the two together).
fn plain_stats(args: &[OsString]) -> Option<StatsArgs> {
    let (_, rest) = args.split_first()?;
    let (command, rest) = rest.split_first()?;
    if command != "stats" {
        return None;
    }
    let mut file = None;
    let (mut dialect, mut setup) = (None, None);
    let (mut json, mut whole, mut one_thread) = (false, false, false);
    let mut words = rest.iter();
    while let Some(word) = words.next() {
        let text = word.to_str();
        let (name, inline) = match text.and_then(|t| t.split_once('=')) {
            Some((name, value)) if name.starts_with("--") => (Some(name), Some(value)),
            _ => (text, None),
        };
        // A value: after `=`, or the next word unless it looks like an option; not empty.
        let mut value = || {
            match inline {
                Some(value) => Some(OsString::from(value)),
                None => words
                    .next()
                    .filter(|v| !v.as_encoded_bytes().starts_with(b"-"))
                    .cloned(),
            }
            .filter(|v| !v.is_empty())
        };
        let flag =
            |set: &mut bool| (!std::mem::replace(set, true) && inline.is_none()).then_some(());
        match name {
            Some("--json") => flag(&mut json)?,
            Some("--whole") => flag(&mut whole)?,
            Some("--one-thread") => flag(&mut one_thread)?,
            Some("--dialect") if dialect.is_none() => {
                let value = value()?;
                dialect = Some(parse_dialect(value.to_str()?).ok()?);
            }
            Some("--setup") if setup.is_none() => setup = Some(PathBuf::from(value()?)),
            _ if file.is_none()
                && !word.is_empty()
                && !word.as_encoded_bytes().starts_with(b"-") =>
            {
                file = Some(PathBuf::from(word));
            }
            _ => return None,
        }
    }
    Some(StatsArgs {
        file: file?,
        opts: RunOptions {
            dialect: dialect.unwrap_or(Dialect::Fanuc),
            setup,
        },
        json,
        whole,
        one_thread,
    })
}

fn parse_dialect(s: &str) -> Result<Dialect, String> {
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
        Command::Check { files, opts } => check(&files, &opts, err),
        Command::Canon { file, opts } => canon(&file, &opts, out, err),
        Command::Stats(args) => stats(&args, out, err),
        Command::Render(args) => render::render(&args, out, err),
        Command::Explain {
            what,
            dialect,
            list,
            table,
            json,
        } => {
            if table {
                write!(out, "{}", swarf_syntax::codes::markdown_table())
                    .map(|()| EXIT_OK)
                    .map_err(anyhow::Error::from)
            } else {
                explain::explain(what.as_deref(), dialect, list, json, out, err)
            }
        }
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
    /// The text, for the diagnostics' lines and columns: empty for a long program run as its
    /// file was read (`stream`) where there is nothing to report.
    text: String,
    program: Program,
    /// Decoding and parsing diagnostics.
    diagnostics: Vec<Diagnostic>,
    /// The files linked for the program's calls, in the order of `program.linked`.
    linked: Vec<LinkedSource>,
}

/// Most files linked to one program (a bound on runaway chains of calls).
const MAX_LINKED: usize = 64;

/// The files in `dir` that may hold a called program (see [`Missing::file_names`]).
fn candidates(dir: &Path, missing: &Missing) -> Vec<PathBuf> {
    missing
        .file_names()
        .iter()
        .map(|name| dir.join(name))
        .collect()
}

/// Links the programs the program calls and does not hold from files beside it, until nothing
/// more can be found; returns the linked files' texts.
fn link_external(
    program: &mut Program,
    path: &Path,
    main_len: usize,
    dialect: Dialect,
) -> Vec<LinkedSource> {
    let dir = path.parent().unwrap_or(Path::new("."));
    program.link_calls(main_len, dialect, MAX_LINKED, |missing| {
        let file = candidates(dir, missing)
            .into_iter()
            .find(|c| c.is_file() && c.as_path() != path)?;
        let bytes = std::fs::read(&file).ok()?;
        Some((file.display().to_string(), decode_owned(bytes).text))
    })
}

/// The setup named by `--setup`, or the default one.
fn read_setup(opts: &RunOptions) -> anyhow::Result<Setup> {
    let Some(p) = &opts.setup else {
        return Ok(Setup::default());
    };
    let text = std::fs::read_to_string(p)
        .map_err(|e| anyhow::anyhow!("cannot read setup {}: {e}", p.display()))?;
    Setup::from_toml(&text).map_err(|e| anyhow::anyhow!("invalid setup {}: {e}", p.display()))
}

fn load(path: &Path, opts: &RunOptions) -> anyhow::Result<Loaded> {
    Ok(load_decoded(path, read_decoded(path)?, opts))
}

/// Reads and decodes a program file.
fn read_decoded(path: &Path) -> anyhow::Result<Decoded> {
    let bytes =
        std::fs::read(path).map_err(|e| anyhow::anyhow!("cannot read {}: {e}", path.display()))?;
    Ok(decode_owned(bytes))
}

/// Parses a decoded program file and links the programs it calls from files beside it.
fn load_decoded(path: &Path, decoded: Decoded, opts: &RunOptions) -> Loaded {
    load_text(path, decoded.text, decoded.diagnostics, opts)
}

/// [`load_decoded`] for a text and its decoding diagnostics.
fn load_text(path: &Path, text: String, decoding: Vec<Diagnostic>, opts: &RunOptions) -> Loaded {
    let mut program = parse(&text, opts.dialect);
    let linked = link_external(&mut program, path, text.len(), opts.dialect);
    Loaded::new(path, decoding, text, program, linked)
}

/// The reading diagnostics and the run's, in one list sorted by position.
fn merged(mut reading: Vec<Diagnostic>, run: Vec<Diagnostic>) -> Vec<Diagnostic> {
    reading.extend(run);
    reading.sort_by_key(|d| (d.span.start, d.span.end));
    reading
}

/// Lines read and run at a time when a program runs piece by piece: a piece's blocks (256 KB)
/// stay in a processor's second-level cache, and the two threads of a long run hand over a
/// piece about every 60 µs (2,048 lines gave the corpus files 2–7 % more than 1,024).
const PIECE_LINES: usize = 2048;

/// Lines in the first piece read on a second thread (the pieces after grow fourfold up to
/// [`PIECE_LINES`]): the runner waits for it.
const FIRST_PIECE_LINES: usize = 128;

/// A text up to this long (about a piece's lines) is read and run on one thread.
const PIECE_BYTES: usize = PIECE_LINES * 24;

/// How many processors this process may run on. On Linux this is the affinity mask, one
/// system call: `std::thread::available_parallelism` also reads the cgroup's processor quota,
/// which takes a tenth of a millisecond of files (`/proc/self/mountinfo` among them), a
/// noticeable part of a short run. A quota below two processors only makes the two threads
/// share one.
fn cores() -> usize {
    #[cfg(target_os = "linux")]
    if let Ok(set) = rustix::thread::sched_getaffinity(None) {
        return set.count() as usize;
    }
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
}

/// Sets aside, before a long program runs, address space for its toolpath and pieces in one
/// mapping. On Linux jemalloc maps a request of 8 MiB or more in a mapping whose length is a
/// multiple of 2 MiB, which the kernel places at a 2 MiB boundary, so all of it can be backed
/// by transparent huge pages; the run's arrays are carved from it once it is freed here,
/// instead of from mappings of odd sizes that are mostly backed by 4 KiB pages, each a page
/// fault (several hundred for a 1 MB program). Nothing is written, so none of it is touched
/// before the arrays fill.
fn set_aside_memory(file_len: u64) {
    /// The transparent huge page size on x86-64 and most AArch64 Linux systems.
    const HUGE_PAGE: usize = 2 << 20;
    // Four bytes a byte: the toolpath (37 bytes a move, about a move every sixteen bytes),
    // the line index, and the reading's window and block arrays with the pieces in flight.
    // Bounded: this is only a hint.
    let bytes = usize::try_from(file_len)
        .unwrap_or(usize::MAX)
        .min(1 << 30)
        .saturating_mul(4)
        .max(8 << 20)
        .next_multiple_of(HUGE_PAGE);
    let mut room: Vec<u8> = Vec::new();
    if room.try_reserve_exact(bytes).is_ok() {
        // Kept from being optimised away with the allocation it frees.
        drop(std::hint::black_box(room));
    }
}

/// How a program read and run piece by piece came out.
enum Outcome {
    /// It ran to its end.
    Ran(Box<Streamed>),
    /// It needs all its blocks at once (it jumps, loops or calls): its text and decoding
    /// diagnostics, to be run whole (the path may hold part of its moves).
    Whole(String, Vec<Diagnostic>),
}

/// A program read and run piece by piece into a toolpath.
struct Streamed {
    /// The file, its program without blocks (none is kept) and its reading diagnostics.
    loaded: Loaded,
    /// How many blocks the program has.
    blocks: usize,
    /// Every diagnostic, sorted by position.
    diagnostics: Vec<Diagnostic>,
}

/// Reads and runs the program piece by piece as it is parsed, keeping none of its blocks, for
/// a program that runs straight through (no jumps, loops or calls): the memory and the first
/// touches of it that the parsed blocks of a long program would take are saved. A file
/// `source` is read a chunk at a time as it is parsed, through a window. `beside` lets a
/// program of several pieces be read on a second thread while the pieces before run (the
/// figures are the same); the thread starts after the toolpath's arrays are reserved, so that its
/// stack is not mapped between them and the memory set aside for them (see
/// [`set_aside_memory`]). `decoding` holds the diagnostics of a text decoded before. An
/// error when the file is not plain UTF-8 (its bytes, to be decoded and run again;
/// `toolpath` may then hold part of its moves) or cannot be read.
fn stream(
    path: &Path,
    mut source: Growing,
    decoding: Vec<Diagnostic>,
    opts: &RunOptions,
    setup: &Setup,
    toolpath: &mut Toolpath,
    beside: bool,
) -> Result<Outcome, Unread> {
    // About a move a line, and a line is rarely under sixteen bytes: the part of the reserve
    // that no move fills is never touched.
    toolpath.reserve(source.len / 16);
    let helper = (beside && source.len > PIECE_BYTES)
        .then(Helper::start)
        .flatten();
    let (mut interp, ran, source) = if let Some(helper) = helper {
        // A second handle on the file, for the runner to read chunks ahead on.
        let again = source
            .is_file()
            .then(|| std::fs::File::open(path).ok())
            .flatten();
        let (interp, read) =
            run_pieces_beside(source, again, opts.dialect, setup, toolpath, helper);
        let (ran, source) = read?;
        (interp, ran, source)
    } else {
        let mut interp = swarf_interp::Interpreter::new(setup.clone(), opts.dialect);
        let ran = run_pieces(&mut source, opts.dialect, &mut interp, toolpath)?;
        (interp, ran, source)
    };
    let Some((reader, blocks)) = ran else {
        return Ok(Outcome::Whole(source.into_text()?, decoding));
    };
    interp.finish_pieces(toolpath);
    let mut program = reader.finish();
    let run = interp.take_diagnostics();
    // The text is wanted to report diagnostics: a file read through a window, which let go of
    // the lines it parsed, is read again for them (and only then).
    let reported = !(decoding.is_empty() && program.diagnostics.is_empty() && run.is_empty());
    let text = if reported || source.held_whole() {
        source.into_text()?
    } else {
        String::new()
    };
    // The reading indexed no lines (four bytes a line of fresh memory, of no use to a
    // program with nothing to report): they are indexed for the report.
    if reported {
        program.lines = LineIndex::new(&text);
    }
    let mut loaded = Loaded::new(path, decoding, text, program, Vec::new());
    let diagnostics = loaded.all_diagnostics(run);
    Ok(Outcome::Ran(Box::new(Streamed {
        loaded,
        blocks,
        diagnostics,
    })))
}

/// Runs one piece unless the program has ended (`ended` then set); `false` when the program
/// needs running whole.
fn run_piece(
    interp: &mut swarf_interp::Interpreter,
    piece: &Program,
    toolpath: &mut Toolpath,
    ended: &mut bool,
) -> bool {
    if !*ended {
        match interp.run_piece(piece, toolpath) {
            swarf_interp::Piece::Ran => {}
            swarf_interp::Piece::Ended => *ended = true,
            swarf_interp::Piece::NeedsWhole => return false,
        }
    }
    true
}

/// Reads and runs `source` piece by piece on this thread (a file a chunk ahead of the parse,
/// through its window): the reader and the number of blocks read, or `None` when the program
/// needs running whole; why the file gave no text.
fn run_pieces(
    source: &mut Growing,
    dialect: swarf_syntax::Dialect,
    interp: &mut swarf_interp::Interpreter,
    toolpath: &mut Toolpath,
) -> Result<Option<(swarf_syntax::ParseRun, usize)>, Unread> {
    // The lines are indexed only where there is something to report (see `stream`).
    let mut reader = swarf_syntax::ParseRun::growing_unindexed(dialect);
    let mut blocks = 0;
    let mut ended = false;
    loop {
        source.read_ahead(reader.offset())?;
        let done = reader.step_growing(
            source.bytes(),
            source.base,
            source.is_complete(),
            PIECE_LINES,
        );
        blocks += reader.program().blocks.len();
        if !run_piece(interp, reader.program(), toolpath, &mut ended) {
            return Ok(None);
        }
        reader.clear_blocks();
        if done {
            // A program that ends at a closing tape mark may end before its file does.
            source.read_to_end()?;
            reader.complete(source.bytes(), source.base);
            return Ok(Some((reader, blocks)));
        }
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

    /// Interprets the program into `sink`; returns the run's diagnostics (see
    /// [`Loaded::all_diagnostics`]).
    fn interpret(&self, setup: &Setup, sink: &mut dyn Sink) -> Vec<Diagnostic> {
        swarf_interp::run(&self.program, setup.clone(), sink)
    }

    /// The reading diagnostics (moved out) and the run's `run`, sorted by position.
    fn all_diagnostics(&mut self, run: Vec<Diagnostic>) -> Vec<Diagnostic> {
        merged(std::mem::take(&mut self.diagnostics), run)
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

fn check(files: &[PathBuf], opts: &RunOptions, err: &mut dyn Write) -> anyhow::Result<i32> {
    let setup = read_setup(opts)?;
    let mut status = EXIT_OK;
    for file in files {
        let mut loaded = match load(file, opts) {
            Ok(l) => l,
            Err(e) => {
                writeln!(err, "swarf: {e:#}")?;
                status = EXIT_USAGE;
                continue;
            }
        };
        let run = loaded.interpret(&setup, &mut NullSink);
        let diags = loaded.all_diagnostics(run);
        let s = loaded.print(&diags, err)?;
        if status == EXIT_OK {
            status = s;
        }
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
    /// The program: an event from a file linked to it names that file, with its line there.
    program: &'a Program,
}

impl Sink for JsonLines<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        let mut value = event.to_json(source);
        let line0 = source.line.saturating_sub(1);
        if let Some(file) = self
            .program
            .linked_at_line(line0)
            .and_then(|i| self.program.linked.get(i))
        {
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
    let setup = read_setup(opts)?;
    let mut loaded = load(file, opts)?;
    let mut buffered = std::io::BufWriter::new(out);
    let mut sink = JsonLines {
        program: &loaded.program,
        out: &mut buffered,
        error: None,
    };
    let run = loaded.interpret(&setup, &mut sink);
    if let Some(e) = sink.error {
        return Err(anyhow::anyhow!("cannot write output: {e}"));
    }
    buffered.flush()?;
    let diags = loaded.all_diagnostics(run);
    Ok(loaded.print(&diags, err)?)
}

fn stats(args: &StatsArgs, out: &mut dyn Write, err: &mut dyn Write) -> anyhow::Result<i32> {
    let StatsArgs {
        ref file,
        ref opts,
        json: as_json,
        whole,
        one_thread,
    } = *args;
    let setup = read_setup(opts)?;
    // The length of a program longer than a piece, read piece by piece.
    let long_file = (!whole)
        .then(|| std::fs::metadata(file).ok())
        .flatten()
        .map(|m| m.len())
        .filter(|&len| len > PIECE_BYTES as u64);
    if let Some(len) = long_file {
        set_aside_memory(len);
    }
    // A long program's file is read a chunk at a time as it is parsed, through a window (see
    // `growing.rs`). A second thread only pays where it has a core of its own and the program
    // is longer than a piece; it reads and parses while the part read before runs.
    let two_threads = long_file.is_some() && !one_thread && cores() >= 2;
    let cannot_read = |e: std::io::Error| anyhow::anyhow!("cannot read {}: {e}", file.display());
    let started = Instant::now();
    let mut path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
    let outcome = if whole {
        let decoded = read_decoded(file)?;
        Outcome::Whole(decoded.text, decoded.diagnostics)
    } else {
        let (mut source, mut decoding) = if let Some(len) = long_file {
            let opened = std::fs::File::open(file).map_err(cannot_read)?;
            let len = usize::try_from(len).unwrap_or(usize::MAX);
            (Growing::open(opened, len), Vec::new())
        } else {
            let decoded = read_decoded(file)?;
            (Growing::whole(decoded.text), decoded.diagnostics)
        };
        // Run again, once, when the file turns out not to be plain UTF-8: decoded whole
        // (a text read whole is not read again).
        loop {
            match stream(file, source, decoding, opts, &setup, &mut path, two_threads) {
                Ok(outcome) => break outcome,
                Err(Unread::Bytes(bytes)) => {
                    path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
                    let decoded = decode_owned(bytes);
                    (source, decoding) = (Growing::whole(decoded.text), decoded.diagnostics);
                }
                Err(Unread::Failed(e)) => return Err(cannot_read(e)),
            }
        }
    };
    let (loaded, blocks, diags) = match outcome {
        Outcome::Ran(s) => (s.loaded, s.blocks, s.diagnostics),
        Outcome::Whole(text, decoding) => {
            // Run whole: it jumps, loops or calls.
            path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
            let mut loaded = load_text(file, text, decoding, opts);
            path.reserve(loaded.program.blocks.len());
            let run = loaded.interpret(&setup, &mut path);
            let diags = loaded.all_diagnostics(run);
            let blocks = loaded.program.blocks.len();
            (loaded, blocks, diags)
        }
    };
    let interp_ms = started.elapsed().as_secs_f64() * 1000.0;
    let errors = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    let warnings = diags
        .iter()
        .filter(|d| d.severity == Severity::Warning)
        .count();
    let bounds = path
        .bounds()
        .map(|b| json!({"min": b.min.to_array(), "max": b.max.to_array()}));
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
        "diagnostics": {"errors": errors, "warnings": warnings, "total": diags.len()},
        "interpretation_ms": interp_ms,
    });
    // One write for the report rather than one a line.
    let mut out = std::io::BufWriter::new(out);
    if as_json {
        writeln!(out, "{report:#}")?;
    } else {
        writeln!(out, "file            {}", loaded.path)?;
        writeln!(out, "dialect         {}", opts.dialect.name())?;
        writeln!(out, "blocks          {blocks}")?;
        writeln!(out, "motions         {}", path.len())?;
        match path.bounds() {
            Some(b) => writeln!(
                out,
                "bounds          X {:.3}..{:.3}  Y {:.3}..{:.3}  Z {:.3}..{:.3} mm",
                b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z
            )?,
            None => writeln!(out, "bounds          (no motion)")?,
        }
        writeln!(out, "rapid length    {:.3} mm", path.rapid_length_mm())?;
        writeln!(out, "feed length     {:.3} mm", path.feed_length_mm())?;
        writeln!(
            out,
            "estimated time  {}",
            format_secs(path.estimated_secs())
        )?;
        let tools: Vec<String> = path.tools().iter().map(|t| format!("T{t}")).collect();
        writeln!(
            out,
            "tools           {}",
            if tools.is_empty() {
                "(none)".to_string()
            } else {
                tools.join(" ")
            }
        )?;
        let holes: Vec<String> = path
            .holes_per_tool()
            .iter()
            .map(|(tool, n)| format!("T{tool}: {n}"))
            .collect();
        if !holes.is_empty() {
            writeln!(
                out,
                "holes           {} ({})",
                path.holes().len(),
                holes.join(", ")
            )?;
        }
        writeln!(out, "diagnostics     {errors} errors, {warnings} warnings")?;
        writeln!(out, "interpretation  {interp_ms:.1} ms")?;
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

    /// `swarf stats …` reads the same with the `stats` subcommand alone as with every
    /// subcommand: the same arguments, and the same help and errors.
    #[test]
    fn the_stats_command_line_reads_as_the_whole_one_does() {
        let cases: [&[&str]; 9] = [
            &["stats", "p.nc"],
            &[
                "stats",
                "p.nc",
                "--dialect",
                "linuxcnc",
                "--one-thread",
                "--json",
            ],
            &[
                "stats",
                "--whole",
                "p.nc",
                "--setup",
                "s.toml",
                "--dialect=syntec",
            ],
            &["stats", "--help"],
            &["stats"],
            &["stats", "p.nc", "--bogus"],
            &["stats", "p.nc", "--dialect", "haas"],
            &["stats", "--version"],
            &["stats", "a.nc", "b.nc"],
        ];
        for case in cases {
            let args = std::iter::once("swarf").chain(case.iter().copied());
            let whole = Cli::try_parse_from(args.clone())
                .map(|cli| format!("{:?}", cli.command))
                .map_err(|e| (e.kind(), e.render().to_string()));
            let alone = StatsCli::try_parse_from(args)
                .map(|cli| match cli.command {
                    StatsCommand::Stats(args) => format!("{:?}", Command::Stats(args)),
                })
                .map_err(|e| (e.kind(), e.render().to_string()));
            assert_eq!(alone, whole, "{case:?}");
        }
    }

    /// Every `swarf stats` command line that the reader without clap takes, clap reads the
    /// same: all the command lines of up to four words from a set of files, options, values
    /// and mistakes; and it takes the plain ones.
    #[test]
    fn the_plain_stats_reader_reads_as_clap_does() {
        let words = [
            "p.nc",
            "q.nc",
            "--json",
            "--whole",
            "--one-thread",
            "--dialect",
            "linuxcnc",
            "haas",
            "--dialect=syntec",
            "--setup",
            "--setup=",
            "--setup=s.toml",
            "--dialect=",
            "-",
            "--",
            "--json=1",
            "-x",
            "",
        ];
        let command_line = |line: &[&str]| -> Vec<OsString> {
            ["swarf", "stats"]
                .iter()
                .chain(line)
                .map(OsString::from)
                .collect()
        };
        let mut lines: Vec<Vec<&str>> = vec![Vec::new()];
        let mut taken = 0;
        for _ in 0..4 {
            let longer: Vec<Vec<&str>> = lines
                .iter()
                .filter(|line| line.len() == lines.last().map_or(0, Vec::len))
                .flat_map(|line| {
                    words.iter().map(move |word| {
                        let mut line = line.clone();
                        line.push(word);
                        line
                    })
                })
                .collect();
            lines.extend(longer);
        }
        for line in &lines {
            let args = command_line(line);
            if let Some(plain) = plain_stats(&args) {
                taken += 1;
                let clap = StatsCli::try_parse_from(&args)
                    .map(|cli| match cli.command {
                        StatsCommand::Stats(args) => format!("{args:?}"),
                    })
                    .map_err(|e| e.render().to_string());
                assert_eq!(Ok(format!("{plain:?}")), clap, "{line:?}");
            }
        }
        // The plain lines are taken, in any order.
        for line in [
            &["p.nc"][..],
            &["p.nc", "--dialect", "linuxcnc"],
            &["--one-thread", "p.nc", "--dialect=syntec", "--json"],
            &["p.nc", "--setup", "s.toml", "--whole"],
        ] {
            assert!(plain_stats(&command_line(line)).is_some(), "{line:?}");
        }
        assert!(taken > 1000, "{taken} command lines taken");
    }

    /// Whether `text` runs piece by piece, from a text read before and from a file read as it
    /// runs (the two agree).
    fn streams(text: &str) -> bool {
        let opts = RunOptions {
            dialect: Dialect::Fanuc,
            setup: None,
        };
        let setup = Setup::default();
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("t.nc");
        std::fs::write(&file, text).unwrap();
        // A text read before, and a file read as it runs on two threads and on one.
        let sources = [
            (Growing::whole(text.to_string()), true),
            (
                Growing::open(std::fs::File::open(&file).unwrap(), text.len()),
                true,
            ),
            (
                Growing::open(std::fs::File::open(&file).unwrap(), text.len()),
                false,
            ),
        ];
        let mut ran = Vec::new();
        for (source, beside) in sources {
            let mut path = Toolpath::for_machine(glam::DVec3::ZERO, &setup.machine);
            let outcome = stream(&file, source, Vec::new(), &opts, &setup, &mut path, beside);
            ran.push(match outcome {
                Ok(Outcome::Ran(streamed)) => {
                    // A text read through a window is read again only to report diagnostics.
                    if streamed.loaded.text.is_empty() {
                        assert!(streamed.diagnostics.is_empty());
                    } else {
                        assert_eq!(streamed.loaded.text, text);
                    }
                    true
                }
                // A program that needs running whole gets its whole text back.
                Ok(Outcome::Whole(back, _)) => {
                    assert_eq!(back, text);
                    false
                }
                Err(_) => panic!("a UTF-8 text is read"),
            });
        }
        assert!(ran.iter().all(|&r| r == ran[0]));
        ran[0]
    }

    /// A program longer than the window its file is read through (`growing.rs`), so that its
    /// start is let go of before its end is read: its diagnostics are reported where they
    /// are, from its text read again, and one that needs running whole gets its whole text.
    #[test]
    fn a_long_file_read_through_a_window_reports_where_its_diagnostics_are() {
        let mut long = String::from("G90 G21 G1 F500.\n");
        for i in 0..120_000 {
            long.push_str(&format!("X{i}.5 Y1.\n"));
        }
        assert!(streams(&long));
        let broken = format!("{long}G1 X1. @ Y2.\nM30\n");
        assert!(streams(&broken));
        assert!(!streams(&format!(
            "{long}M98 P2000\nM30\nO2000\nX1.\nM99\n"
        )));
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("t.nc");
        std::fs::write(&file, &broken).unwrap();
        let args = StatsArgs {
            file: file.clone(),
            opts: RunOptions {
                dialect: Dialect::Fanuc,
                setup: None,
            },
            json: false,
            whole: false,
            one_thread: false,
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

    #[test]
    fn straight_programs_stream_and_jumping_ones_do_not() {
        let mut long = String::from("O1000\nG90 G21 G1 F500.\n#1=2.\n");
        for i in 0..20_000 {
            long.push_str(&format!("X{i}. Y#1\n"));
        }
        assert!(streams(&long));
        assert!(streams("G0 X1.\nG81 X2. R1. Z-1. F50.\nG80\nM30\n"));
        assert!(!streams(&format!(
            "{long}M98 P2000\nM30\nO2000\nX1.\nM99\n"
        )));
        assert!(!streams("#1=0\nWHILE [#1 LT 3] DO1\n#1=#1+1\nEND1\nM30\n"));
        assert!(!streams("N1 G0 X1.\nGOTO 1\n"));
        assert!(!streams("G65 P9000 A1.\nM30\n"));
        assert!(!streams("O1\nX1.\nM30\nO2\nX2.\nM99\n"));
    }
}
