//! Byte offsets of graftal's spans and the protocol's positions: a line
//! and a column counted in UTF-16 code units (LSP 3.17's default, the only
//! encoding every client knows).

use crate::source::SourceFile;
use lsp_types::{Position, Range};

/// The protocol position of byte offset `offset` of `file`.
pub fn position(file: &SourceFile, offset: usize) -> Position {
    let text = &file.text;
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let line = file.line_index(offset);
    let start = file.line_range(line).start.min(offset);
    let before = &text[start..offset];
    // An ASCII prefix (the common case) is one unit a byte.
    let column = if before.is_ascii() {
        before.len()
    } else {
        before.encode_utf16().count()
    };
    Position::new(line as u32, column as u32)
}

/// The protocol range of byte span `span` of `file`.
pub fn range(file: &SourceFile, span: &std::ops::Range<usize>) -> Range {
    Range::new(position(file, span.start), position(file, span.end))
}

/// The byte offset of protocol position `pos` in `file`: a column past the
/// line's end is its end, a line past the file's end is the file's end.
pub fn offset(file: &SourceFile, pos: Position) -> usize {
    let line = pos.line as usize;
    if line >= file.line_count() {
        return file.text.len();
    }
    let bytes = file.line_range(line);
    let mut units = 0usize;
    for (i, c) in file.text[bytes.clone()].char_indices() {
        if units >= pos.character as usize {
            return bytes.start + i;
        }
        units += c.len_utf16();
    }
    bytes.end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_utf16_units_and_round_trip() {
        // `é` is one unit, `𝄞` two (a surrogate pair), each several bytes.
        let file = SourceFile::new("a.l", "# é𝄞\nF -> x\n");
        let x = file.text.find('x').unwrap();
        assert_eq!(position(&file, x), Position::new(1, 5));
        let after = file.text.find('\n').unwrap();
        assert_eq!(position(&file, after), Position::new(0, 5));
        assert_eq!(offset(&file, Position::new(0, 5)), after);
        assert_eq!(offset(&file, Position::new(1, 5)), x);
        assert_eq!(offset(&file, Position::new(1, 99)), x + 1);
        assert_eq!(offset(&file, Position::new(9, 0)), file.text.len());
    }
}
