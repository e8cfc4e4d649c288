//! SGI images (`.rgb`, `.sgi`, `.bw`): a 512-byte big-endian header, then
//! each channel's rows from the bottom up, stored verbatim or run-length
//! encoded (a table of each row's offset and length first). 1 to 4
//! channels (grey, grey and alpha, RGB, RGBA) of 1 or 2 bytes; 2-byte
//! values keep their high byte. Every read is bounds-checked: a file that
//! is cut short or whose tables point outside it is an error.

use super::{checked_size, to_rgba, ImageError};
use crate::ir::texture::Image;

/// The first two bytes of every SGI image.
pub const MAGIC: u16 = 474;
const HEADER: usize = 512;

struct Header {
    rle: bool,
    bytes_per_value: usize,
    width: usize,
    height: usize,
    channels: usize,
}

fn be16(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes([*b.get(at)?, *b.get(at + 1)?]))
}

fn be32(b: &[u8], at: usize) -> Option<u32> {
    let s = b.get(at..at + 4)?;
    Some(u32::from_be_bytes([s[0], s[1], s[2], s[3]]))
}

fn err(msg: impl Into<String>) -> ImageError {
    ImageError(format!("not a readable SGI image: {}", msg.into()))
}

fn header(b: &[u8]) -> Result<Header, ImageError> {
    if b.len() < HEADER || be16(b, 0) != Some(MAGIC) {
        return Err(err("shorter than its 512-byte header"));
    }
    let (storage, bpc) = (b[2], b[3]);
    let (dimension, x, y, z) = (be16(b, 4), be16(b, 6), be16(b, 8), be16(b, 10));
    let [Some(dimension), Some(x), Some(y), Some(z)] = [dimension, x, y, z] else {
        return Err(err("its header is cut short"));
    };
    if storage > 1 || !(1..=2).contains(&bpc) {
        return Err(err(format!(
            "storage {storage} with {bpc} bytes a value is not SGI's"
        )));
    }
    // One-dimensional images have one row, two-dimensional ones one channel.
    let (height, channels) = match dimension {
        1 => (1, 1),
        2 => (y, 1),
        3 => (y, z),
        d => return Err(err(format!("{d} dimensions"))),
    };
    if !(1..=4).contains(&channels) {
        return Err(err(format!("{channels} channels (1 to 4 are images)")));
    }
    checked_size(u32::from(x), u32::from(height))?;
    Ok(Header {
        rle: storage == 1,
        bytes_per_value: usize::from(bpc),
        width: usize::from(x),
        height: usize::from(height),
        channels: usize::from(channels),
    })
}

/// Decodes an SGI image, bottom row first.
pub fn decode(b: &[u8]) -> Result<Image, ImageError> {
    let h = header(b)?;
    // planes[c][y * width + x]
    let mut planes = vec![vec![0u8; h.width * h.height]; h.channels];
    for (c, plane) in planes.iter_mut().enumerate() {
        for (y, row) in plane.chunks_exact_mut(h.width).enumerate() {
            let index = c * h.height + y;
            if h.rle {
                rle_row(b, &h, index, row)?;
            } else {
                verbatim_row(b, &h, index, row)?;
            }
        }
    }
    let mut rgba = Vec::with_capacity(h.width * h.height * 4);
    let mut px = [0u8; 4];
    for i in 0..h.width * h.height {
        for (c, plane) in planes.iter().enumerate() {
            px[c] = plane[i];
        }
        rgba.extend_from_slice(&to_rgba(h.channels, &px[..h.channels]));
    }
    Image::new(h.width as u32, h.height as u32, rgba).ok_or_else(|| err("empty"))
}

/// The value at `at` (the high byte of a 2-byte value).
fn value(b: &[u8], at: usize) -> Option<u8> {
    b.get(at).copied()
}

fn verbatim_row(b: &[u8], h: &Header, index: usize, row: &mut [u8]) -> Result<(), ImageError> {
    let start = HEADER + index * h.width * h.bytes_per_value;
    for (x, out) in row.iter_mut().enumerate() {
        *out = value(b, start + x * h.bytes_per_value)
            .ok_or_else(|| err("its pixels stop before the last row"))?;
    }
    Ok(())
}

/// One run-length encoded row: counts with the high bit set copy that many
/// values, without it repeat the next value that many times; 0 ends.
fn rle_row(b: &[u8], h: &Header, index: usize, row: &mut [u8]) -> Result<(), ImageError> {
    let rows = h.height * h.channels;
    let start = be32(b, HEADER + index * 4);
    let length = be32(b, HEADER + (rows + index) * 4);
    let (Some(start), Some(length)) = (start, length) else {
        return Err(err("its table of rows is cut short"));
    };
    let (start, length) = (start as usize, length as usize);
    let end = start.saturating_add(length).min(b.len());
    let bpv = h.bytes_per_value;
    let short = || err(format!("row {index} runs past the end of its data"));
    let (mut at, mut x) = (start, 0);
    while at < end {
        let count_at = at + bpv - 1;
        let count = value(b, count_at).ok_or_else(short)?;
        at += bpv;
        let n = usize::from(count & 0x7f);
        if n == 0 {
            break;
        }
        let run = row
            .get_mut(x..x + n)
            .ok_or_else(|| err(format!("row {index} is too long")))?;
        if count & 0x80 != 0 {
            for out in run.iter_mut() {
                *out = value(b, at).filter(|_| at < end).ok_or_else(short)?;
                at += bpv;
            }
        } else {
            let v = value(b, at).filter(|_| at < end).ok_or_else(short)?;
            run.fill(v);
            at += bpv;
        }
        x += n;
    }
    if x < row.len() {
        return Err(err(format!(
            "row {index} has {x} of its {} pixels",
            row.len()
        )));
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// An SGI header: `rle`, 1 byte a value, 3 dimensions.
    fn head(rle: bool, w: u16, h: u16, channels: u16) -> Vec<u8> {
        let mut b = vec![0u8; HEADER];
        b[0..2].copy_from_slice(&MAGIC.to_be_bytes());
        b[2] = u8::from(rle);
        b[3] = 1;
        b[4..6].copy_from_slice(&3u16.to_be_bytes());
        b[6..8].copy_from_slice(&w.to_be_bytes());
        b[8..10].copy_from_slice(&h.to_be_bytes());
        b[10..12].copy_from_slice(&channels.to_be_bytes());
        b
    }

    /// A verbatim RGB image of 2 × 2: planes of rows, bottom row first.
    pub(crate) fn verbatim() -> Vec<u8> {
        let mut b = head(false, 2, 2, 3);
        b.extend_from_slice(&[10, 11, 12, 13]); // red: bottom row, top row
        b.extend_from_slice(&[20, 21, 22, 23]); // green
        b.extend_from_slice(&[30, 31, 32, 33]); // blue
        b
    }

    /// The same picture run-length encoded: each row once a run of two
    /// literal values.
    fn rle() -> Vec<u8> {
        let mut b = head(true, 2, 2, 3);
        let rows: Vec<[u8; 2]> = vec![[10, 11], [12, 13], [20, 21], [22, 23], [30, 31], [32, 33]];
        let data_at = HEADER + rows.len() * 8;
        let mut data = Vec::new();
        let mut starts = Vec::new();
        for r in &rows {
            starts.push((data_at + data.len()) as u32);
            // One literal run of two, then the end.
            data.extend_from_slice(&[0x82, r[0], r[1], 0]);
        }
        for s in &starts {
            b.extend_from_slice(&s.to_be_bytes());
        }
        for _ in &starts {
            b.extend_from_slice(&4u32.to_be_bytes());
        }
        b.extend_from_slice(&data);
        b
    }

    #[test]
    fn verbatim_and_run_length_images_decode_alike() {
        for bytes in [verbatim(), rle()] {
            let im = decode(&bytes).unwrap();
            assert_eq!((im.width(), im.height()), (2, 2));
            assert_eq!(im.texel(0, 0), [10, 20, 30, 255]);
            assert_eq!(im.texel(1, 0), [11, 21, 31, 255]);
            assert_eq!(im.texel(0, 1), [12, 22, 32, 255]);
        }
    }

    #[test]
    fn repeated_runs_and_grey_alpha_images() {
        // 3 × 1, two channels (grey, alpha): grey repeated, alpha literal.
        let mut b = head(true, 3, 1, 2);
        let data_at = (HEADER + 16) as u32;
        for s in [data_at, data_at + 3] {
            b.extend_from_slice(&s.to_be_bytes());
        }
        for l in [3u32, 5] {
            b.extend_from_slice(&l.to_be_bytes());
        }
        b.extend_from_slice(&[0x03, 77, 0]); // grey: 77 three times
        b.extend_from_slice(&[0x83, 1, 2, 3, 0]); // alpha: 1, 2, 3
        let im = decode(&b).unwrap();
        assert_eq!(im.texel(2, 0), [77, 77, 77, 3]);
    }

    #[test]
    fn broken_files_are_errors_not_panics() {
        let good = rle();
        for cut in [0, 5, HEADER, HEADER + 10, good.len() - 3] {
            assert!(decode(&good[..cut]).is_err(), "cut at {cut}");
        }
        // A row whose start points far outside the file.
        let mut far = good.clone();
        far[HEADER..HEADER + 4].copy_from_slice(&u32::MAX.to_be_bytes());
        assert!(decode(&far).is_err());
        // A run longer than its row.
        let mut long = good.clone();
        let at = HEADER + 48;
        long[at] = 0x85;
        assert!(decode(&long).is_err());
        // Five channels, a wrong storage byte, and sizes too large.
        assert!(decode(&head(false, 1, 1, 5)).is_err());
        let mut storage = verbatim();
        storage[2] = 7;
        assert!(decode(&storage).is_err());
        assert!(decode(&head(false, 65535, 65535, 3)).is_err());
        let cut = verbatim();
        assert!(decode(&cut[..cut.len() - 1]).is_err());
    }

    proptest::proptest! {
        #[test]
        fn never_panics(tail in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..200),
                        w in 0u16..6, h in 0u16..6, c in 0u16..6, rle in proptest::prelude::any::<bool>()) {
            let mut b = head(rle, w, h, c);
            b.extend_from_slice(&tail);
            let _ = decode(&b);
        }
    }
}
