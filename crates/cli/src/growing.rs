//! A program file read a chunk at a time while it is parsed, so that a long program starts
//! running before the end of it is read (the read is no longer a wait before the first piece),
//! through a window: the lines parsed are let go of, so the text of a long file is never held
//! whole (its memory, a fresh page zeroed by the system for every 2 MB of text, and the copy
//! into it are saved) and the window's bytes are still in the processor's cache when they are
//! parsed.

use std::fs::File;
use std::io::{Read, Seek};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

/// Bytes read at a time, and how far ahead of the parse the text is kept.
const CHUNK_BYTES: usize = 64 * 1024;

/// The room the window of a file's text takes: the lines parsed are let go of when the next
/// chunk would not fit in it (a line longer than that is read whole all the same). The lines
/// not yet parsed move to its start then, a fraction of what was read since the last time.
const WINDOW_BYTES: usize = 512 * 1024;

/// The UTF-8 byte-order mark: a file that starts with it is decoded whole.
const BOM: [u8; 3] = [0xEF, 0xBB, 0xBF];

/// The text of a program as it is read: a file read a chunk at a time, or a text read whole
/// before. Until the file is read to its end the text holds whole lines only (each with its
/// `\n`), so a parse can read every line in it (see `ParseRun::step_growing`).
pub(crate) struct Growing {
    /// The file, until it is read to its end.
    file: Option<File>,
    /// The file read to its end, kept to be read again from its start where its whole text
    /// is wanted after the window let go of some of it ([`Growing::into_text`]).
    read: Option<File>,
    /// A text read before, whole.
    text: String,
    /// A file's window: its bytes from `base` on, the chunks read straight into it (zeroed
    /// once, when made). Whole lines checked to be UTF-8 up to `lines`, then the start of the
    /// next line up to `filled`.
    window: Vec<u8>,
    lines: usize,
    filled: usize,
    /// Where the window starts in the file: the bytes before it are parsed and let go of.
    pub(crate) base: usize,
    /// The offset of the first byte still wanted (the next line to parse): the window keeps
    /// the text from here on.
    wanted: usize,
    /// The file's length when it was opened, or the text's (a reserve, not a limit).
    pub(crate) len: usize,
    /// The next chunk of the file to read (chunk `k` is its bytes from `k * CHUNK_BYTES`),
    /// and where the file's handle reads next.
    next_chunk: usize,
    at: usize,
    /// Chunks read ahead by another thread, if any ([`feed`]).
    feed: Option<Feed>,
}

/// Why a file read while it ran gives no text.
pub(crate) enum Unread {
    /// It is not plain UTF-8 (or it starts with a byte-order mark): all its bytes, to be
    /// decoded whole.
    Bytes(Vec<u8>),
    /// It could not be read.
    Failed(std::io::Error),
}

impl Growing {
    /// A text read before: complete.
    pub(crate) fn whole(text: String) -> Self {
        Growing {
            file: None,
            read: None,
            len: text.len(),
            text,
            window: Vec::new(),
            lines: 0,
            filled: 0,
            base: 0,
            wanted: 0,
            next_chunk: 0,
            at: 0,
            feed: None,
        }
    }

    /// A file of about `len` bytes, nothing of it read yet. The room for its window is taken
    /// at the first read, on the thread that reads, after the arrays that thread makes first
    /// (the line index, the first block array): they and the window then share the first
    /// memory that thread writes, which with transparent huge pages is one 2 MB page mapped
    /// rather than two before the first piece.
    pub(crate) fn open(file: File, len: usize) -> Self {
        Growing {
            file: Some(file),
            read: None,
            text: String::new(),
            window: Vec::new(),
            lines: 0,
            filled: 0,
            base: 0,
            wanted: 0,
            len,
            next_chunk: 0,
            at: 0,
            feed: None,
        }
    }

    /// Takes the chunks another thread reads ahead ([`feed`]) where it has them, and reads
    /// the others itself.
    pub(crate) fn fed_by(&mut self, feed: Feed) {
        self.feed = Some(feed);
    }

    /// The whole lines read so far, from byte `base` of the file on (UTF-8); the whole text
    /// of a text read before.
    pub(crate) fn bytes(&self) -> &[u8] {
        if self.window.is_empty() {
            self.text.as_bytes()
        } else {
            self.window.get(..self.lines).unwrap_or_default()
        }
    }

    /// Whether this is a file read as it runs (not a text read before).
    pub(crate) fn is_file(&self) -> bool {
        self.file.is_some() || self.read.is_some()
    }

    /// Whether the text is all there is (the file is read to its end).
    pub(crate) fn is_complete(&self) -> bool {
        self.file.is_none()
    }

    /// Where the whole lines read so far end in the file.
    fn end(&self) -> usize {
        self.base + self.bytes().len()
    }

    /// Reads on until the text holds a chunk's bytes past byte `from` (the next line to
    /// parse: the lines before it may be let go of), at least one whole line of them, or is
    /// complete.
    pub(crate) fn read_ahead(&mut self, from: usize) -> Result<(), Unread> {
        self.wanted = self.wanted.max(from);
        while self.read_on(from.saturating_add(CHUNK_BYTES))? {}
        Ok(())
    }

    /// Reads one more chunk if the text ends before byte `until` and the file is not read to
    /// its end; whether it read one.
    pub(crate) fn read_on(&mut self, until: usize) -> Result<bool, Unread> {
        if self.is_complete() || self.end() >= until {
            return Ok(false);
        }
        self.read_chunk()?;
        Ok(true)
    }

    /// Reads the rest of the file.
    pub(crate) fn read_to_end(&mut self) -> Result<(), Unread> {
        while self.read_on(usize::MAX)? {}
        Ok(())
    }

    /// Reads a chunk into the window and checks the lines it ends (at the end of the file,
    /// all that is left).
    fn read_chunk(&mut self) -> Result<(), Unread> {
        if self.file.is_none() {
            return Ok(());
        }
        self.make_room()?;
        let Some(file) = &mut self.file else {
            return Ok(());
        };
        let from = self.filled;
        let room = self
            .window
            .get_mut(from..from + CHUNK_BYTES)
            .unwrap_or_default();
        let chunk = self.next_chunk;
        self.next_chunk += 1;
        let read = match self.feed.as_ref().and_then(|feed| feed.take(chunk)) {
            // Read by the other thread.
            Some(Ok(bytes)) => {
                let read = bytes.len().min(room.len());
                room.get_mut(..read)
                    .unwrap_or_default()
                    .copy_from_slice(bytes.get(..read).unwrap_or_default());
                if let Some(feed) = &self.feed {
                    feed.give_back(bytes);
                }
                read
            }
            Some(Err(e)) => return Err(Unread::Failed(e)),
            None => read_chunk_at(file, &mut self.at, chunk, room).map_err(Unread::Failed)?,
        };
        self.filled += read;
        let lines_end = if read == 0 {
            self.read = self.file.take();
            self.filled
        } else {
            // The last line ending read: a line never ends inside a character.
            let chunk = self.window.get(from..self.filled).unwrap_or_default();
            match chunk.iter().rposition(|&b| b == b'\n') {
                Some(at) => from + at + 1,
                None => return Ok(()),
            }
        };
        let first = self.base + self.lines == 0;
        let lines = self.window.get(self.lines..lines_end).unwrap_or_default();
        if plain(lines, first).is_none() {
            return Err(self.unread());
        }
        self.lines = lines_end;
        Ok(())
    }

    /// Room for a chunk at the end of the window: made at the first read, then by letting go
    /// of the lines parsed when the window is full (the rest moves to its start), and by
    /// growing it where a line is longer than it. An error where there is no memory for it
    /// (as `std::fs::read` gives, rather than aborting).
    fn make_room(&mut self) -> Result<(), Unread> {
        if self.window.len() >= self.filled + CHUNK_BYTES {
            return Ok(());
        }
        if !self.window.is_empty() {
            let parsed = self.wanted.saturating_sub(self.base).min(self.lines);
            self.window.copy_within(parsed..self.filled, 0);
            self.base += parsed;
            self.lines -= parsed;
            self.filled -= parsed;
        }
        let wanted = (self.filled + CHUNK_BYTES).max(self.len.clamp(CHUNK_BYTES, WINDOW_BYTES));
        if self.window.len() < wanted {
            if self
                .window
                .try_reserve_exact(wanted - self.window.len())
                .is_err()
            {
                return Err(Unread::Failed(std::io::ErrorKind::OutOfMemory.into()));
            }
            self.window.resize(wanted, 0);
        }
        Ok(())
    }

    /// Every byte of the file: those the window holds, with the rest of the file where it
    /// let go of none, else the file read again from its start. The file is read no more.
    fn all_bytes(&mut self) -> std::io::Result<Vec<u8>> {
        let at_end = self.is_complete();
        let file = self.file.take().or_else(|| self.read.take());
        // The window let go of the file's start, or the handle is not where the window ends
        // (chunks were read elsewhere): it is read again.
        if self.base > 0 || (!at_end && self.feed.is_some()) {
            return file.map_or_else(|| Err(std::io::ErrorKind::UnexpectedEof.into()), read_again);
        }
        let mut bytes = std::mem::take(&mut self.window);
        bytes.truncate(self.filled);
        if let (Some(mut file), false) = (file, at_end) {
            bytes.reserve(self.len.saturating_sub(bytes.len()));
            file.read_to_end(&mut bytes)?;
        }
        Ok(bytes)
    }

    /// Every byte of the file, for a text that is not plain UTF-8.
    fn unread(&mut self) -> Unread {
        match self.all_bytes() {
            Ok(bytes) => Unread::Bytes(bytes),
            Err(e) => Unread::Failed(e),
        }
    }

    /// Whether this is a text read before, held whole.
    pub(crate) fn held_whole(&self) -> bool {
        self.window.is_empty() && self.file.is_none() && self.read.is_none()
    }

    /// The whole text: a text read before, or a file's read to its end and held whole, else
    /// the file read again from its start (a file that is no longer plain UTF-8 gives its
    /// bytes, to be decoded).
    pub(crate) fn into_text(mut self) -> Result<String, Unread> {
        if self.held_whole() {
            return Ok(self.text);
        }
        match String::from_utf8(self.all_bytes().map_err(Unread::Failed)?) {
            Ok(text) if !text.as_bytes().starts_with(&BOM) => Ok(text),
            Ok(text) => Err(Unread::Bytes(text.into_bytes())),
            Err(e) => Err(Unread::Bytes(e.into_bytes())),
        }
    }
}

/// Reads chunk `k` of `file` into `room`, a chunk long: how many bytes it holds (fewer at the
/// end of the file). `at` is where the handle reads next, kept so that a handle reading chunk
/// after chunk is not moved; unknown (`usize::MAX`) after an error.
fn read_chunk_at(
    file: &mut File,
    at: &mut usize,
    k: usize,
    room: &mut [u8],
) -> std::io::Result<usize> {
    let offset = k * CHUNK_BYTES;
    let moved = *at != offset;
    *at = usize::MAX;
    if moved {
        file.seek(std::io::SeekFrom::Start(offset as u64))?;
    }
    let read = read_full(file, room)?;
    *at = offset + read;
    Ok(read)
}

/// Reads into `room` until it is full or the file ends; how many bytes were read.
fn read_full(file: &mut File, room: &mut [u8]) -> std::io::Result<usize> {
    let mut read = 0;
    while let Some(rest) = room.get_mut(read..).filter(|rest| !rest.is_empty()) {
        match file.read(rest) {
            Ok(0) => break,
            Ok(n) => read += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(read)
}

/// How many chunks the other thread reads ahead of the reading at most.
const FED_AHEAD: usize = 4;

/// What the reading and the thread that reads chunks for it share: how many chunks are
/// claimed (each is read by the one that claims it), and how many the reading has taken.
struct Chunks {
    claimed: AtomicUsize,
    taken: AtomicUsize,
}

/// The reading's end of a [`feed`]: the chunks the other thread read, in order, and the way
/// back for their buffers.
pub(crate) struct Feed {
    shared: Arc<Chunks>,
    chunks: Receiver<std::io::Result<Vec<u8>>>,
    spare: SyncSender<Vec<u8>>,
}

impl Feed {
    /// Chunk `k`, the next the reading needs: `None` when it is for the reading to read (it
    /// is claimed for it now), else the chunk the other thread read (it is waited for: the
    /// other thread claims a chunk as it starts reading it).
    fn take(&self, k: usize) -> Option<std::io::Result<Vec<u8>>> {
        let shared = &self.shared;
        let mine = shared
            .claimed
            .compare_exchange(k, k + 1, Ordering::AcqRel, Ordering::Acquire)
            .is_ok();
        shared.taken.store(k + 1, Ordering::Release);
        if mine {
            return None;
        }
        Some(
            crate::waits::recv(&self.chunks)
                .unwrap_or_else(|_| Err(std::io::ErrorKind::BrokenPipe.into())),
        )
    }

    fn give_back(&self, bytes: Vec<u8>) {
        let _ = self.spare.try_send(bytes);
    }
}

/// The other thread's end of a [`feed`]: its own handle on the file, and where it reads.
pub(crate) struct Feeder {
    file: File,
    at: usize,
    /// Chunks in the file.
    count: usize,
    shared: Arc<Chunks>,
    chunks: SyncSender<std::io::Result<Vec<u8>>>,
    spare: Receiver<Vec<u8>>,
}

impl Feeder {
    /// Reads the next chunk the reading has not claimed, if it is not too far ahead of it:
    /// whether it read one.
    pub(crate) fn read_one(&mut self) -> bool {
        let shared = &self.shared;
        let k = shared.claimed.load(Ordering::Acquire);
        if k >= self.count || k >= shared.taken.load(Ordering::Acquire) + FED_AHEAD {
            return false;
        }
        if shared
            .claimed
            .compare_exchange(k, k + 1, Ordering::AcqRel, Ordering::Acquire)
            .is_err()
        {
            return false;
        }
        let mut bytes = self.spare.try_recv().unwrap_or_default();
        bytes.resize(CHUNK_BYTES, 0);
        let result = read_chunk_at(&mut self.file, &mut self.at, k, &mut bytes).map(|read| {
            bytes.truncate(read);
            bytes
        });
        // Never full: at most `FED_AHEAD` chunks are ahead of the reading.
        let _ = self.chunks.send(result);
        true
    }
}

/// Chunks of a file `len` bytes long read ahead for a [`Growing`] (`Growing::fed_by`) by
/// another thread, from `file`, a second handle on it (`Feeder::read_one`, while that thread
/// would otherwise wait): the reading then spends its time on the parse rather than in the
/// system's copy of the file. Each chunk is read by whichever claims it first.
pub(crate) fn feed(file: File, len: usize) -> (Feed, Feeder) {
    let shared = Arc::new(Chunks {
        claimed: AtomicUsize::new(0),
        taken: AtomicUsize::new(0),
    });
    let (chunks_in, chunks) = sync_channel(FED_AHEAD + 1);
    let (spare, spares) = sync_channel(FED_AHEAD + 1);
    (
        Feed {
            shared: Arc::clone(&shared),
            chunks,
            spare,
        },
        Feeder {
            file,
            at: 0,
            count: len.div_ceil(CHUNK_BYTES),
            shared,
            chunks: chunks_in,
            spare: spares,
        },
    )
}

/// Every byte of `file`, read from its start.
fn read_again(mut file: File) -> std::io::Result<Vec<u8>> {
    file.rewind()?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// `bytes` as text when they are UTF-8, and where they start the text (`first`), do not start
/// with a byte-order mark.
fn plain(bytes: &[u8], first: bool) -> Option<&str> {
    std::str::from_utf8(bytes)
        .ok()
        .filter(|text| !(first && text.as_bytes().starts_with(&BOM)))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// `bytes` written to a file and read as it is while it runs, each read ahead from where
    /// the last ended (as a parse that has read every line before would): the text each read
    /// ahead adds (each ends at a line ending until the file is read), and how it ended (the
    /// text put together from them, which the window gives back whole too).
    fn read(bytes: &[u8]) -> (Vec<String>, Result<String, Option<Vec<u8>>>) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.nc");
        std::fs::write(&path, bytes).unwrap();
        let file = File::open(&path).unwrap();
        let mut growing = Growing::open(file, bytes.len());
        let mut parts = Vec::new();
        let mut whole = String::new();
        while !growing.is_complete() {
            match growing.read_ahead(whole.len()) {
                Ok(()) => {}
                Err(Unread::Bytes(all)) => return (parts, Err(Some(all))),
                Err(Unread::Failed(_)) => return (parts, Err(None)),
            }
            // The window keeps the text from where the parse is on.
            assert!(growing.base <= whole.len());
            let added = &growing.bytes()[whole.len() - growing.base..];
            let added = String::from_utf8(added.to_vec()).unwrap();
            whole.push_str(&added);
            parts.push(added);
        }
        match growing.into_text() {
            Ok(again) => assert_eq!(again, whole),
            Err(_) => panic!("the whole text is given back"),
        }
        (parts, Ok(whole))
    }

    #[test]
    fn a_file_is_read_in_whole_lines_to_its_end() {
        let mut text = String::new();
        for i in 0..20_000 {
            text.push_str(&format!("N{i} G1 X{i}.5 (é, 加工)\n"));
        }
        text.push_str("M30");
        let (parts, whole) = read(text.as_bytes());
        assert!(parts.len() > 3, "{} reads", parts.len());
        for part in &parts[..parts.len() - 1] {
            assert!(part.ends_with('\n'));
        }
        assert_eq!(whole.ok(), Some(text));
    }

    #[test]
    fn a_line_longer_than_a_chunk_is_read_whole() {
        let long = format!("G1 X1 ({})\nG0 Z5\n", "x".repeat(3 * CHUNK_BYTES));
        let (parts, whole) = read(long.as_bytes());
        assert!(parts[0].len() > 3 * CHUNK_BYTES);
        assert_eq!(whole.ok(), Some(long));
    }

    #[test]
    fn a_file_not_plain_utf8_is_given_back_whole() {
        // GB18030 in a comment far into the file, a byte-order mark, UTF-16.
        // The first far enough in that the window has let go of the file's start.
        let mut gbk = "G1 X1\n".repeat(150_000).into_bytes();
        gbk.extend_from_slice(b"(\xBC\xD3\xB9\xA4)\nM30\n");
        let mut bom = BOM.to_vec();
        bom.extend_from_slice("G1 X1\n".repeat(30_000).as_bytes());
        let utf16: Vec<u8> = "G1 X1\n"
            .repeat(100)
            .encode_utf16()
            .flat_map(u16::to_le_bytes)
            .collect();
        for bytes in [gbk, bom, [&[0xFF, 0xFE][..], &utf16].concat()] {
            let (_, whole) = read(&bytes);
            assert_eq!(whole.err(), Some(Some(bytes)));
        }
    }

    #[test]
    fn bytes_not_utf8_are_found_wherever_the_chunks_cut() {
        // A bad byte in a line cut by the end of a chunk, in the line that finishes it, and in
        // a line after it; a zero-width no-break space starting a later line is text.
        for at in [
            CHUNK_BYTES - 3,
            CHUNK_BYTES,
            CHUNK_BYTES + 2,
            CHUNK_BYTES + 40,
        ] {
            let mut bytes = "G1 X1.5\n".repeat(3 * CHUNK_BYTES / 8).into_bytes();
            bytes[at] = 0xB9;
            let (_, whole) = read(&bytes);
            assert_eq!(whole.err(), Some(Some(bytes)), "{at}");
        }
        let text = format!("{}\u{feff}G0 Z5\n", "G1 X1.5\n".repeat(CHUNK_BYTES / 8));
        assert_eq!(read(text.as_bytes()).1.ok(), Some(text));
    }

    #[test]
    fn a_long_file_is_read_through_a_window_and_can_be_read_again_whole() {
        let mut text = String::new();
        for i in 0..200_000 {
            text.push_str(&format!("G1 X{i}.25 Y-{i}.5\n"));
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.nc");
        std::fs::write(&path, &text).unwrap();
        // A length far over any memory is only a reserve.
        let mut growing = Growing::open(File::open(&path).unwrap(), usize::MAX);
        let mut most = 0;
        while !growing.is_complete() {
            assert!(growing.read_ahead(growing.end()).is_ok());
            most = most.max(growing.bytes().len());
            // What it holds is the file's, from where it starts.
            assert!(text.as_bytes()[growing.base..].starts_with(growing.bytes()));
        }
        assert!(most <= WINDOW_BYTES + CHUNK_BYTES, "{most} bytes held");
        assert!(growing.base > text.len() - WINDOW_BYTES);
        assert!(!growing.held_whole());
        match growing.into_text() {
            Ok(again) => assert_eq!(again, text),
            Err(_) => panic!("the whole text is read again"),
        }
    }

    #[test]
    fn reading_on_takes_a_chunk_at_a_time_up_to_its_bound() {
        let text = "G1 X1.5\n".repeat(4 * CHUNK_BYTES / 8);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.nc");
        std::fs::write(&path, &text).unwrap();
        let mut growing = Growing::open(File::open(&path).unwrap(), text.len());
        // Short of the bound: a chunk a call, each read in whole lines.
        assert!(growing.read_on(2 * CHUNK_BYTES).ok() == Some(true));
        assert_eq!(growing.bytes().len(), CHUNK_BYTES);
        assert!(growing.read_on(2 * CHUNK_BYTES).ok() == Some(true));
        assert_eq!(growing.bytes().len(), 2 * CHUNK_BYTES);
        // At the bound: nothing more.
        assert!(growing.read_on(2 * CHUNK_BYTES).ok() == Some(false));
        assert_eq!(growing.bytes().len(), 2 * CHUNK_BYTES);
        // To the end of the file, and nothing after it.
        while growing.read_on(usize::MAX).ok() == Some(true) {}
        assert!(growing.is_complete());
        assert_eq!(growing.bytes(), text.as_bytes());
        assert!(growing.read_on(usize::MAX).ok() == Some(false));
    }

    /// A file read with chunks read ahead by another thread (each chunk by whichever claims
    /// it first) gives the same text, in whole lines, as one read alone; and one that is not
    /// plain UTF-8 still gives back all its bytes.
    #[test]
    fn chunks_read_ahead_by_another_thread_make_the_same_text() {
        let mut text = String::new();
        for i in 0..60_000 {
            text.push_str(&format!("N{i} G1 X{i}.5 Y-2.25 (é)\n"));
        }
        let mut bad = text.clone().into_bytes();
        let at = bad.len() - 1000;
        bad[at] = 0xB9;
        for (bytes, good) in [(text.as_bytes(), true), (&bad[..], false)] {
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("p.nc");
            std::fs::write(&path, bytes).unwrap();
            let mut growing = Growing::open(File::open(&path).unwrap(), bytes.len());
            let (feed, mut feeder) = feed(File::open(&path).unwrap(), bytes.len());
            growing.fed_by(feed);
            // The first two chunks are read there for certain, the rest as the threads go.
            assert!(feeder.read_one() && feeder.read_one());
            let done = Arc::new(std::sync::atomic::AtomicBool::new(false));
            let stop = Arc::clone(&done);
            let other = std::thread::spawn(move || {
                let mut read = 0;
                while !stop.load(Ordering::Acquire) {
                    if feeder.read_one() {
                        read += 1;
                    } else {
                        std::thread::yield_now();
                    }
                }
                read
            });
            let mut whole = String::new();
            let outcome = loop {
                if growing.is_complete() {
                    break Ok(());
                }
                if let Err(e) = growing.read_ahead(whole.len()) {
                    break Err(e);
                }
                let added = &growing.bytes()[whole.len() - growing.base..];
                assert!(added.is_empty() || added.ends_with(b"\n") || growing.is_complete());
                whole.push_str(std::str::from_utf8(added).unwrap());
                // The parse takes its time: the other thread reads on meanwhile.
                std::thread::sleep(std::time::Duration::from_micros(50));
            };
            done.store(true, Ordering::Release);
            let read_there = other.join().unwrap();
            match outcome {
                Ok(()) => {
                    assert!(good);
                    assert_eq!(whole, text);
                    assert!(read_there <= bytes.len().div_ceil(CHUNK_BYTES));
                }
                Err(Unread::Bytes(all)) => {
                    assert!(!good);
                    assert_eq!(all, bytes);
                }
                Err(Unread::Failed(e)) => panic!("{e}"),
            }
        }
    }

    #[test]
    fn a_text_read_before_is_complete() {
        let mut growing = Growing::whole("G1 X1\nM30".to_string());
        assert!(growing.is_complete());
        assert!(growing.read_ahead(0).is_ok() && growing.read_to_end().is_ok());
        assert_eq!(growing.bytes(), b"G1 X1\nM30");
    }
}
