//! PNG through the `png` crate: every colour type and depth, expanded to
//! 8-bit RGBA, rows turned bottom-up.

use super::{checked_size, to_rgba, ImageError};
use crate::ir::texture::Image;

pub fn decode(bytes: &[u8]) -> Result<Image, ImageError> {
    let fail = |e: ::png::DecodingError| ImageError(format!("not a readable PNG: {e}"));
    let limits = ::png::Limits {
        bytes: super::MAX_PIXELS * 8,
    };
    let mut decoder = ::png::Decoder::new_with_limits(std::io::Cursor::new(bytes), limits);
    // Palettes and low depths expanded, 16-bit channels cut to 8.
    decoder.set_transformations(::png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(fail)?;
    let (width, height) = (reader.info().width, reader.info().height);
    checked_size(width, height)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| ImageError("the PNG is too large to decode".into()))?;
    let mut buf = vec![0; size];
    let frame = reader.next_frame(&mut buf).map_err(fail)?;
    let channels = frame.color_type.samples();
    let line = frame.line_size;
    let (w, h) = (width as usize, height as usize);
    if line < w * channels || buf.len() < line * h {
        return Err(ImageError(
            "the PNG's rows are shorter than its width".into(),
        ));
    }
    let mut rgba = Vec::with_capacity(w * h * 4);
    // PNG rows run top-down; a texture's bottom-up.
    for row in buf[..line * h].chunks_exact(line).rev() {
        for px in row[..w * channels].chunks_exact(channels) {
            rgba.extend_from_slice(&to_rgba(channels, px));
        }
    }
    Image::new(width, height, rgba).ok_or_else(|| ImageError("the PNG is empty".into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PNG written by the `png` crate's encoder.
    pub(crate) fn encode(w: u32, h: u32, colour: ::png::ColorType, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut enc = ::png::Encoder::new(&mut out, w, h);
        enc.set_color(colour);
        enc.set_depth(::png::BitDepth::Eight);
        let mut writer = enc.write_header().unwrap();
        writer.write_image_data(data).unwrap();
        writer.finish().unwrap();
        out
    }

    #[test]
    fn rgba_and_grey_pngs_decode_bottom_row_first() {
        // Top row red, green; bottom row blue, half-transparent white.
        let data = [
            255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128,
        ];
        let im = decode(&encode(2, 2, ::png::ColorType::Rgba, &data)).unwrap();
        assert_eq!((im.width(), im.height()), (2, 2));
        assert_eq!(im.texel(0, 0), [0, 0, 255, 255]);
        assert_eq!(im.texel(1, 0), [255, 255, 255, 128]);
        assert_eq!(im.texel(0, 1), [255, 0, 0, 255]);
        let grey = decode(&encode(3, 1, ::png::ColorType::Grayscale, &[0, 100, 255])).unwrap();
        assert_eq!(grey.texel(1, 0), [100, 100, 100, 255]);
        let rgb = decode(&encode(1, 1, ::png::ColorType::Rgb, &[1, 2, 3])).unwrap();
        assert_eq!(rgb.texel(0, 0), [1, 2, 3, 255]);
    }

    #[test]
    fn broken_pngs_are_errors_not_panics() {
        let good = encode(2, 1, ::png::ColorType::Rgb, &[1, 2, 3, 4, 5, 6]);
        for cut in [8, 20, 33, good.len() - 13] {
            assert!(decode(&good[..cut]).is_err(), "cut at {cut}");
        }
        let mut bad = good.clone();
        bad[40] ^= 0xff;
        let _ = decode(&bad);
    }
}
