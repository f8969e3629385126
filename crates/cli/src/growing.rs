//! A program file read a chunk at a time while it is parsed, so that a long program starts
//! running before the end of it is read (the read is no longer a wait before the first piece).

use std::fs::File;
use std::io::Read;

/// Bytes read at a time, and how far ahead of the parse the text is kept.
const CHUNK_BYTES: usize = 64 * 1024;

/// The UTF-8 byte-order mark: a file that starts with it is decoded whole.
const BOM: [u8; 3] = [0xEF, 0xBB, 0xBF];

/// The text of a program as it is read: a file read a chunk at a time, or a text read whole
/// before. Until the file is read to its end the text holds whole lines only (each with its
/// `\n`), so a parse can read every line in it (see `ParseRun::step_growing`).
pub(crate) struct Growing {
    /// The file, until it is read to its end.
    file: Option<File>,
    /// The whole lines read so far, checked to be UTF-8; the whole text once complete.
    pub(crate) text: String,
    /// Bytes read after the last line ending.
    rest: Vec<u8>,
    /// Where a chunk is read (empty until the first read).
    buffer: Vec<u8>,
    /// The file's length when it was opened, or the text's (a reserve, not a limit).
    pub(crate) len: usize,
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
            len: text.len(),
            text,
            rest: Vec::new(),
            buffer: Vec::new(),
        }
    }

    /// A file of about `len` bytes, nothing of it read yet. The room for its text is taken at
    /// the first read, on the thread that reads, after the arrays that thread makes first (the
    /// line index, the first block array): they and the start of the text then share the
    /// first memory that thread writes, which with transparent huge pages is one 2 MB page
    /// mapped rather than two before the first piece.
    pub(crate) fn open(file: File, len: usize) -> Self {
        Growing {
            file: Some(file),
            text: String::new(),
            rest: Vec::new(),
            buffer: Vec::new(),
            len,
        }
    }

    /// Whether the text is all there is (the file is read to its end).
    pub(crate) fn is_complete(&self) -> bool {
        self.file.is_none()
    }

    /// Reads on until the text holds a chunk's bytes past byte `from`, at least one whole line
    /// of them, or is complete.
    pub(crate) fn read_ahead(&mut self, from: usize) -> Result<(), Unread> {
        while self.read_on(from.saturating_add(CHUNK_BYTES))? {}
        Ok(())
    }

    /// Reads one more chunk if the text is shorter than `until` bytes and the file is not read
    /// to its end; whether it read one.
    pub(crate) fn read_on(&mut self, until: usize) -> Result<bool, Unread> {
        if self.is_complete() || self.text.len() >= until {
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

    /// Reads a chunk and adds the lines it ends to the text (at the end of the file, all that
    /// is left).
    fn read_chunk(&mut self) -> Result<(), Unread> {
        let Some(file) = &mut self.file else {
            return Ok(());
        };
        // One call a chunk (`read_to_end` would make several, growing its reads from 8 KB),
        // into a buffer zeroed once rather than before each read.
        if self.buffer.is_empty() {
            self.buffer = vec![0; CHUNK_BYTES];
            // Room for the whole text, or an error where there is none (as `std::fs::read`
            // gives, rather than aborting).
            if self.text.try_reserve_exact(self.len).is_err() {
                return Err(Unread::Failed(std::io::ErrorKind::OutOfMemory.into()));
            }
        }
        let read = loop {
            match file.read(&mut self.buffer) {
                Ok(read) => break read,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(Unread::Failed(e)),
            }
        };
        let chunk = self.buffer.get(..read).unwrap_or_default();
        let (lines, after) = if read == 0 {
            self.file = None;
            (chunk, &[][..])
        } else {
            // The last line ending read: a line never ends inside a character.
            let Some(at) = chunk.iter().rposition(|&b| b == b'\n') else {
                self.rest.extend_from_slice(chunk);
                return Ok(());
            };
            chunk.split_at(at + 1)
        };
        // A line begun in an earlier chunk is finished in `rest`; the chunk's other whole
        // lines go to the text as they are. Until a line is in the text, `rest` and the chunk
        // hold the file from its start.
        let (first, others) = if self.rest.is_empty() {
            (&[][..], lines)
        } else {
            let end = lines
                .iter()
                .position(|&b| b == b'\n')
                .map_or(lines.len(), |at| at + 1);
            lines.split_at(end)
        };
        self.rest.extend_from_slice(first);
        if let Some(text) = plain(&self.rest, self.text.is_empty()) {
            self.text.push_str(text);
            self.rest.clear();
            if let Some(text) = plain(others, self.text.is_empty()) {
                self.text.push_str(text);
                self.rest.extend_from_slice(after);
                return Ok(());
            }
        }
        self.rest.extend_from_slice(others);
        self.rest.extend_from_slice(after);
        Err(self.unread())
    }

    /// Every byte of the file, for a text that is not plain UTF-8.
    fn unread(&mut self) -> Unread {
        let mut bytes = std::mem::take(&mut self.text).into_bytes();
        bytes.append(&mut self.rest);
        if let Some(mut file) = self.file.take() {
            bytes.reserve(self.len.saturating_sub(bytes.len()));
            if let Err(e) = file.read_to_end(&mut bytes) {
                return Unread::Failed(e);
            }
        }
        Unread::Bytes(bytes)
    }
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

    /// `bytes` written to a file and read as it is while it runs: the text after each read
    /// ahead (each ends at a line ending until the file is read), and how it ended.
    fn read(bytes: &[u8]) -> (Vec<String>, Result<String, Option<Vec<u8>>>) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.nc");
        std::fs::write(&path, bytes).unwrap();
        let file = File::open(&path).unwrap();
        let mut growing = Growing::open(file, bytes.len());
        let mut texts = Vec::new();
        let mut from = 0;
        while !growing.is_complete() {
            match growing.read_ahead(from) {
                Ok(()) => {}
                Err(Unread::Bytes(all)) => return (texts, Err(Some(all))),
                Err(Unread::Failed(_)) => return (texts, Err(None)),
            }
            texts.push(growing.text.clone());
            from = growing.text.len();
        }
        (texts, Ok(growing.text))
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
            assert!(text.starts_with(part.as_str()));
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
        let mut gbk = "G1 X1\n".repeat(30_000).into_bytes();
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
    fn a_file_too_long_to_hold_is_an_error_not_an_abort() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.nc");
        std::fs::write(&path, "G1 X1\n").unwrap();
        let file = File::open(&path).unwrap();
        let mut growing = Growing::open(file, usize::MAX);
        let Err(Unread::Failed(error)) = growing.read_ahead(0) else {
            panic!("no room for the text is an error");
        };
        assert_eq!(error.kind(), std::io::ErrorKind::OutOfMemory);
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
        assert_eq!(growing.text.len(), CHUNK_BYTES);
        assert!(growing.read_on(2 * CHUNK_BYTES).ok() == Some(true));
        assert_eq!(growing.text.len(), 2 * CHUNK_BYTES);
        // At the bound: nothing more.
        assert!(growing.read_on(2 * CHUNK_BYTES).ok() == Some(false));
        assert_eq!(growing.text.len(), 2 * CHUNK_BYTES);
        // To the end of the file, and nothing after it.
        while growing.read_on(usize::MAX).ok() == Some(true) {}
        assert!(growing.is_complete());
        assert_eq!(growing.text, text);
        assert!(growing.read_on(usize::MAX).ok() == Some(false));
    }

    #[test]
    fn a_text_read_before_is_complete() {
        let mut growing = Growing::whole("G1 X1\nM30".to_string());
        assert!(growing.is_complete());
        assert!(growing.read_ahead(0).is_ok() && growing.read_to_end().is_ok());
        assert_eq!(growing.text, "G1 X1\nM30");
    }
}
