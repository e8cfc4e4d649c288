//! Source files: their text, their name, and line/column look-up.

use std::io::Read as _;
use std::ops::Range;
use std::path::Path;

/// The largest source file read (8 MiB): L-system files are a few KB, and
/// reading keeps per-character spans (about 150 bytes per input byte).
pub const MAX_SOURCE_BYTES: usize = 8 << 20;

/// Characters are counted in blocks of this many bytes, so a column on a
/// line of megabytes is found without counting the whole line each time.
const CHAR_BLOCK: usize = 4096;

/// The part of a file looked at to tell text from other files.
const SNIFF_BYTES: usize = 8 << 10;

/// One source text with the name diagnostics show for it.
#[derive(Clone, Debug)]
pub struct SourceFile {
    pub name: String,
    pub text: String,
    line_starts: Vec<usize>,
    /// Characters before each [`CHAR_BLOCK`] boundary; empty for ASCII text
    /// (a byte is a character).
    block_chars: Vec<usize>,
    /// Set when the file was larger than [`MAX_SOURCE_BYTES`] and not read.
    oversize: Option<Oversize>,
}

/// A file larger than [`MAX_SOURCE_BYTES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Oversize {
    /// Its size in bytes, when known (not for pipes and devices, which are
    /// read no further than the limit).
    pub size: Option<u64>,
}

/// Why a file is not taken for text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NotText {
    /// It holds a NUL byte (at this byte offset).
    Nul(usize),
    /// This share (in percent) of its first characters are neither
    /// printable nor white space (control characters, invalid UTF-8).
    Unprintable(usize),
}

impl SourceFile {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Self {
        let text = text.into();
        // LF, CR LF and a lone CR each end a line, as in the lexer.
        let bytes = text.as_bytes();
        let mut line_starts = vec![0];
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')) {
                line_starts.push(i + 1);
            }
        }
        let mut block_chars = Vec::new();
        if !text.is_ascii() {
            // One count per block boundary, the end included.
            block_chars.push(0);
            for block in bytes.chunks(CHAR_BLOCK) {
                let before = block_chars[block_chars.len() - 1];
                block_chars.push(before + count_chars(block));
            }
        }
        let oversize = (text.len() > MAX_SOURCE_BYTES).then_some(Oversize {
            size: Some(text.len() as u64),
        });
        SourceFile {
            name: name.into(),
            text,
            line_starts,
            block_chars,
            oversize,
        }
    }

    /// Reads a file from disk: at most [`MAX_SOURCE_BYTES`], whatever kind
    /// of file it is (a device or a pipe may never end). A larger file is
    /// not kept: its text is empty and [`SourceFile::oversize`] says so.
    pub fn read(path: &Path) -> std::io::Result<Self> {
        let file = std::fs::File::open(path)?;
        let mut bytes = Vec::new();
        // One byte more than the limit tells a file of exactly the limit
        // from a larger one.
        file.take(MAX_SOURCE_BYTES as u64 + 1)
            .read_to_end(&mut bytes)?;
        let name = path.display().to_string();
        if bytes.len() > MAX_SOURCE_BYTES {
            let size = std::fs::metadata(path)
                .ok()
                .filter(|m| m.is_file())
                .map(|m| m.len());
            let mut f = SourceFile::new(name, String::new());
            f.oversize = Some(Oversize { size });
            return Ok(f);
        }
        let text = match String::from_utf8(bytes) {
            Ok(t) => t,
            Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
        };
        Ok(SourceFile::new(name, text))
    }

    /// Set when the file is larger than [`MAX_SOURCE_BYTES`] (and, when read
    /// from disk, was not read).
    pub fn oversize(&self) -> Option<Oversize> {
        self.oversize
    }

    /// Whether the text is not text at all: any NUL, or more than a tenth
    /// of the first 8 KiB neither printable nor white space (control
    /// characters, and the replacement characters that stand for invalid
    /// UTF-8). Such a file is reported once instead of byte by byte.
    pub fn not_text(&self) -> Option<NotText> {
        if let Some(at) = self.text.bytes().position(|b| b == 0) {
            return Some(NotText::Nul(at));
        }
        let mut end = SNIFF_BYTES.min(self.text.len());
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let (mut chars, mut unprintable) = (0usize, 0usize);
        for c in self.text[..end].chars() {
            chars += 1;
            if (c.is_control() && !c.is_whitespace()) || c == char::REPLACEMENT_CHARACTER {
                unprintable += 1;
            }
        }
        (unprintable * 10 > chars).then(|| NotText::Unprintable(unprintable * 100 / chars))
    }

    /// 1-based line and column (in characters) of byte offset `offset`.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = floor_char_boundary(&self.text, offset.min(self.text.len()));
        let line = self.line_index(offset);
        let start = self.line_starts[line];
        (line + 1, self.chars_between(start, offset) + 1)
    }

    /// The 0-based line that byte offset `offset` is on (an offset past the
    /// end is on the last line).
    pub fn line_index(&self, offset: usize) -> usize {
        let offset = offset.min(self.text.len());
        match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        }
    }

    /// How many lines the text has (an empty text, or a text ending with a
    /// line break, has an empty last line).
    pub fn line_count(&self) -> usize {
        self.line_starts.len()
    }

    /// The bytes of 0-based line `line`, without its line break.
    pub fn line_range(&self, line: usize) -> Range<usize> {
        let start = self.line_starts[line];
        let next = self
            .line_starts
            .get(line + 1)
            .copied()
            .unwrap_or(self.text.len());
        let content = self.text[start..next].trim_end_matches(['\n', '\r']);
        start..start + content.len()
    }

    /// How many characters the text has between byte offsets `from` and
    /// `to` (both on character boundaries), in time bounded by
    /// [`CHAR_BLOCK`] however far apart they are.
    pub fn chars_between(&self, from: usize, to: usize) -> usize {
        self.chars_before(to) - self.chars_before(from)
    }

    fn chars_before(&self, offset: usize) -> usize {
        if self.block_chars.is_empty() {
            return offset;
        }
        let block = offset / CHAR_BLOCK;
        let start = block * CHAR_BLOCK;
        self.block_chars[block] + count_chars(&self.text.as_bytes()[start..offset])
    }

    /// The notation of this file by its extension.
    pub fn extension(&self) -> Option<&str> {
        Path::new(&self.name).extension().and_then(|e| e.to_str())
    }
}

/// The characters that begin in `bytes` of UTF-8 (every byte that is not a
/// continuation byte).
fn count_chars(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| (b as i8) >= -0x40).count()
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_is_one_based_and_counts_characters() {
        let f = SourceFile::new("x.l", "ab\r\ncé d\nlast");
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(1), (1, 2));
        assert_eq!(f.line_col(4), (2, 1));
        // 'd' comes after 'c', 'é' (2 bytes) and ' '
        assert_eq!(f.line_col(8), (2, 4));
        assert_eq!(f.line_col(10), (3, 1));
        assert_eq!(f.line_col(999), (3, 5));
        let mac = SourceFile::new("m.l", "ab\rcd\r\nef");
        assert_eq!(mac.line_col(3), (2, 1));
        assert_eq!(mac.line_col(7), (3, 1));
    }

    #[test]
    fn columns_on_a_long_line_of_many_byte_characters_count_characters() {
        // Past several blocks, on block boundaries and in between.
        let text = format!("x\n{}ab", "é".repeat(5000));
        let f = SourceFile::new("l.l", text.clone());
        let a = text.len() - 2;
        assert_eq!(f.line_col(a), (2, 5001));
        assert_eq!(f.line_col(2 + 2 * 2048), (2, 2049));
        assert_eq!(f.line_col(text.len()), (2, 5003));
        // The middle of a character is the character.
        assert_eq!(f.line_col(3), (2, 1));
        assert_eq!(f.chars_between(0, text.len()), text.chars().count());
        // A text whose length is a multiple of the block.
        let exact = SourceFile::new("e.l", "é".repeat(CHAR_BLOCK));
        assert_eq!(exact.line_col(exact.text.len()), (1, CHAR_BLOCK + 1));
    }

    #[test]
    fn line_ranges_leave_out_line_breaks() {
        let f = SourceFile::new("x.l", "ab\r\ncd\ref\n");
        assert_eq!(f.line_count(), 4);
        assert_eq!(f.line_range(0), 0..2);
        assert_eq!(f.line_range(1), 4..6);
        assert_eq!(f.line_range(2), 7..9);
        assert_eq!(f.line_range(3), 10..10);
        assert_eq!(f.line_index(5), 1);
        assert_eq!(f.line_index(99), 3);
    }

    #[test]
    fn text_with_nul_or_mostly_control_characters_is_not_text() {
        let plain = SourceFile::new("p.l", "axiom: F\n\tF --> F+F\r\n");
        assert_eq!(plain.not_text(), None);
        let nul = SourceFile::new("n.l", "axiom: F\0");
        assert_eq!(nul.not_text(), Some(NotText::Nul(8)));
        // A few invalid bytes (a Latin-1 comment) are text; many are not.
        let latin = String::from_utf8_lossy(b"/* Fran\xe7ois */ axiom: F").into_owned();
        assert_eq!(SourceFile::new("l.l", latin).not_text(), None);
        let noise = "\u{1}\u{2}F\u{fffd}".repeat(100);
        assert_eq!(
            SourceFile::new("r.l", noise).not_text(),
            Some(NotText::Unprintable(75))
        );
    }

    #[test]
    fn reading_stops_past_the_limit_and_says_the_size() {
        let dir = std::env::temp_dir().join(format!("graftal-source-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let exact = dir.join("exact.l");
        std::fs::write(&exact, "F".repeat(MAX_SOURCE_BYTES)).unwrap();
        let f = SourceFile::read(&exact).unwrap();
        assert_eq!((f.text.len(), f.oversize()), (MAX_SOURCE_BYTES, None));
        let big = dir.join("big.l");
        std::fs::write(&big, "F".repeat(MAX_SOURCE_BYTES + 10)).unwrap();
        let f = SourceFile::read(&big).unwrap();
        assert!(f.text.is_empty());
        assert_eq!(
            f.oversize(),
            Some(Oversize {
                size: Some(MAX_SOURCE_BYTES as u64 + 10)
            })
        );
        let bytes = dir.join("latin.l");
        std::fs::write(&bytes, b"axiom: F \xff").unwrap();
        assert_eq!(SourceFile::read(&bytes).unwrap().text, "axiom: F \u{fffd}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
