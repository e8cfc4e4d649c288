//! Image files decoded into [`Image`]s for textures: PNG (through the
//! `png` crate) and SGI `.rgb` (the format of cpfg's older textures, read
//! here: no kept crate reads it). Decoding never panics: a file that is
//! cut short, lies about its sizes or is too large is an [`ImageError`]
//! saying what is wrong with it.

mod png;
mod sgi;

use crate::ir::texture::Image;
use std::fmt;

/// The most pixels a decoded image may have (4096 × 4096): textures are
/// small, and a header that claims more is refused before anything is
/// allocated.
pub const MAX_PIXELS: usize = 4096 * 4096;

/// Why an image file could not be decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImageError(pub String);

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// The image formats read, by how a file begins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Png,
    Sgi,
}

impl Format {
    /// The format of `bytes`, from its signature.
    pub fn sniff(bytes: &[u8]) -> Option<Format> {
        if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            Some(Format::Png)
        } else if bytes.starts_with(&sgi::MAGIC.to_be_bytes()) {
            Some(Format::Sgi)
        } else {
            None
        }
    }
}

/// Decodes a PNG or SGI image (told apart by their signatures), rows
/// bottom-up as textures keep them.
pub fn decode(bytes: &[u8]) -> Result<Image, ImageError> {
    match Format::sniff(bytes) {
        Some(Format::Png) => png::decode(bytes),
        Some(Format::Sgi) => sgi::decode(bytes),
        None => Err(ImageError(
            "neither a PNG nor an SGI (.rgb) image: its first bytes are not either signature"
                .into(),
        )),
    }
}

/// Checks a header's sizes before anything is allocated.
fn checked_size(width: u32, height: u32) -> Result<usize, ImageError> {
    let pixels = (width as usize).saturating_mul(height as usize);
    if width == 0 || height == 0 {
        return Err(ImageError(format!(
            "the image is {width} × {height} pixels: empty"
        )));
    }
    if pixels > MAX_PIXELS {
        return Err(ImageError(format!(
            "the image is {width} × {height} pixels, more than the {MAX_PIXELS} a texture may have"
        )));
    }
    Ok(pixels)
}

/// RGBA from `channels` values a pixel (grey, grey and alpha, RGB, RGBA).
fn to_rgba(channels: usize, px: &[u8]) -> [u8; 4] {
    match (channels, px) {
        (1, &[g, ..]) => [g, g, g, 255],
        (2, &[g, a, ..]) => [g, g, g, a],
        (3, &[r, g, b, ..]) => [r, g, b, 255],
        (_, &[r, g, b, a, ..]) => [r, g, b, a],
        _ => [0, 0, 0, 255],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_and_empty_files_are_errors() {
        assert!(decode(b"").is_err());
        assert!(decode(b"GIF89a").unwrap_err().0.contains("signature"));
        assert!(checked_size(0, 5).is_err());
        assert!(checked_size(65535, 65535).is_err());
        assert_eq!(checked_size(4, 2), Ok(8));
    }
}
