//! Growth animations: the pictures of steps up to N as the frames of an
//! animated GIF ([`gif`](::gif)) or APNG (the `png` crate's animation
//! control). Every frame is fitted as the last one is
//! ([`super::RenderOptions::framing`]), so the plant grows in place rather
//! than shrinking to fit. The frames are drawn by the caller (the driver
//! derives and draws each step as a still picture) and encoded here one by
//! one, so that only one frame is held at a time.

use crate::turtle::{Disc, Geometry, Origins, Polygon, Segment, Sink};
use std::io::Write;

/// The most frames an animation has: more is not an animation anyone
/// watches, and each costs a derivation.
pub const MAX_FRAMES: u64 = 1000;

/// The most pixels encoded in all: frames × width × height (about ten
/// seconds of encoding).
pub const MAX_PIXELS: u64 = 1 << 30;

/// The most frames an outline's growth is replayed in (fewer when fewer
/// stems grow).
pub const GROWTH_FRAMES: u64 = 60;

/// What of `g` appeared before `before` stems had grown: its parts whose
/// module (`g.origins`) appeared earlier (`appeared`, per module of the
/// word). Parts of no known module (a layout) are kept.
pub fn grown_part(g: &Geometry, appeared: &[u32], before: u32) -> Geometry {
    let mut part = Part {
        kept: Geometry {
            world_widths: g.world_widths,
            max_depth: g.max_depth,
            ..Geometry::default()
        },
        origins: &g.origins,
        seen: [0; 3],
        shown: &|origin| appeared.get(origin).is_none_or(|&a| a < before),
    };
    // Replayed, so that the part keeps the order the whole was drawn in.
    g.replay(&mut part);
    part.kept
}

/// What [`grown_part`] keeps of a replayed drawing.
struct Part<'a> {
    kept: Geometry,
    origins: &'a Origins,
    /// Segments, polygons and discs seen so far.
    seen: [usize; 3],
    shown: &'a dyn Fn(usize) -> bool,
}

impl Part<'_> {
    /// Whether the next thing of `kind` (0 segment, 1 polygon, 2 disc) with
    /// origins `of` is kept.
    fn keeps(&mut self, kind: usize, of: &[usize]) -> bool {
        let i = self.seen[kind];
        self.seen[kind] += 1;
        (self.shown)(of.get(i).copied().unwrap_or(usize::MAX))
    }
}

impl Sink for Part<'_> {
    fn segment(&mut self, s: Segment) {
        let origins = self.origins;
        if self.keeps(0, &origins.segments) {
            self.kept.segment(s);
        }
    }
    fn polygon(&mut self, p: Polygon) {
        let origins = self.origins;
        if self.keeps(1, &origins.polygons) {
            self.kept.polygon(p);
        }
    }
    fn disc(&mut self, d: Disc) {
        let origins = self.origins;
        if self.keeps(2, &origins.discs) {
            self.kept.disc(d);
        }
    }
}

/// The container of an animation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Container {
    Gif,
    /// Animated PNG.
    Apng,
}

impl Container {
    /// Every container. An output's extension is looked up here, so the
    /// help that lists them ([`crate::driver::picture::Target::all`])
    /// names every one that can be written.
    pub const ALL: [Container; 2] = [Container::Gif, Container::Apng];

    /// The extension of a file of it: an animated PNG is a `.png`.
    pub fn extension(self) -> &'static str {
        match self {
            Container::Gif => "gif",
            Container::Apng => "png",
        }
    }

    /// The container an output path names by its extension (`.gif`, `.png`),
    /// else the one `to` names (`gif`, `png`, `apng`).
    pub fn choose(path: Option<&str>, to: Option<&str>) -> Option<Container> {
        let by_ext = path
            .and_then(|p| std::path::Path::new(p).extension())
            .and_then(|e| e.to_str());
        let name = to.or(by_ext)?;
        if name.eq_ignore_ascii_case("apng") {
            return Some(Container::Apng);
        }
        Container::ALL
            .into_iter()
            .find(|c| c.extension().eq_ignore_ascii_case(name))
    }
}

/// How an animation is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Animation {
    pub container: Container,
    pub width: u32,
    pub height: u32,
    /// Frames per second (1..=100).
    pub fps: u32,
    pub frames: u64,
}

impl Animation {
    /// Why this animation is refused before anything is drawn: too many
    /// frames or pixels, a GIF over 65535 pixels wide, no frame rate.
    pub fn refusal(&self) -> Option<String> {
        let pixels = self.frames * u64::from(self.width) * u64::from(self.height);
        if self.frames == 0 || self.frames > MAX_FRAMES {
            Some(format!(
                "an animation has 1..={MAX_FRAMES} frames, not {}",
                self.frames
            ))
        } else if pixels > MAX_PIXELS {
            Some(format!(
                "{} frames of {}x{} are {pixels} pixels, more than an animation encodes ({MAX_PIXELS})",
                self.frames, self.width, self.height
            ))
        } else if !(1..=100).contains(&self.fps) {
            Some(format!("`--fps {}`: 1..=100 frames per second", self.fps))
        } else {
            None
        }
    }

    /// The delay between frames as a GIF states it, in hundredths of a
    /// second.
    pub fn gif_delay(&self) -> u16 {
        (100 / self.fps.max(1)).max(1) as u16
    }
}

/// A frame: `width × height` RGBA pixels, not premultiplied.
pub struct Frame {
    pub rgba: Vec<u8>,
}

impl Frame {
    /// The pixels of a PNG picture (what a still `render` writes).
    pub fn from_png(bytes: &[u8]) -> Result<Frame, String> {
        let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
        let size = reader
            .output_buffer_size()
            .ok_or("the frame is too large")?;
        let mut buf = vec![0; size];
        let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
        buf.truncate(info.buffer_size());
        let rgba = match info.color_type {
            png::ColorType::Rgba => buf,
            png::ColorType::Rgb => buf
                .chunks_exact(3)
                .flat_map(|p| [p[0], p[1], p[2], 255])
                .collect(),
            png::ColorType::GrayscaleAlpha => buf
                .chunks_exact(2)
                .flat_map(|p| [p[0], p[0], p[0], p[1]])
                .collect(),
            png::ColorType::Grayscale => buf.iter().flat_map(|&g| [g, g, g, 255]).collect(),
            png::ColorType::Indexed => return Err("an indexed frame".into()),
        };
        Ok(Frame { rgba })
    }
}

/// Encodes `anim.frames` frames, each asked of `frame(k)` when it is
/// written (so one is held at a time), into `out`; `progress(k, n)` after
/// each.
pub fn encode<W: Write>(
    anim: &Animation,
    out: W,
    frame: &mut dyn FnMut(u64) -> Result<Frame, String>,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<(), String> {
    if let Some(why) = anim.refusal() {
        return Err(why);
    }
    let expected = anim.width as usize * anim.height as usize * 4;
    let mut next = |k: u64| -> Result<Frame, String> {
        let f = frame(k)?;
        if f.rgba.len() != expected {
            return Err(format!("frame {k} is not {}x{}", anim.width, anim.height));
        }
        Ok(f)
    };
    match anim.container {
        Container::Gif => encode_gif(anim, out, &mut next, progress),
        Container::Apng => encode_apng(anim, out, &mut next, progress),
    }
}

fn encode_gif<W: Write>(
    anim: &Animation,
    out: W,
    next: &mut dyn FnMut(u64) -> Result<Frame, String>,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<(), String> {
    let (w, h) = (
        u16::try_from(anim.width).map_err(|_| "a GIF is at most 65535 pixels wide")?,
        u16::try_from(anim.height).map_err(|_| "a GIF is at most 65535 pixels high")?,
    );
    let mut enc = gif::Encoder::new(out, w, h, &[]).map_err(|e| e.to_string())?;
    enc.set_repeat(gif::Repeat::Infinite)
        .map_err(|e| e.to_string())?;
    for k in 0..anim.frames {
        let mut f = next(k)?;
        // Exact colours when a frame has at most 256 (a flat drawing),
        // else NeuQuant at its usual speed.
        let mut g = gif::Frame::from_rgba_speed(w, h, &mut f.rgba, 10);
        g.delay = anim.gif_delay();
        enc.write_frame(&g).map_err(|e| e.to_string())?;
        progress(k + 1, anim.frames);
    }
    Ok(())
}

fn encode_apng<W: Write>(
    anim: &Animation,
    out: W,
    next: &mut dyn FnMut(u64) -> Result<Frame, String>,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<(), String> {
    let frames = u32::try_from(anim.frames).map_err(|_| "too many frames")?;
    let mut enc = png::Encoder::new(out, anim.width, anim.height);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    let err = |e: png::EncodingError| e.to_string();
    enc.set_animated(frames, 0).map_err(err)?;
    enc.set_frame_delay(1, anim.fps as u16).map_err(err)?;
    let mut writer = enc.write_header().map_err(err)?;
    for k in 0..anim.frames {
        let f = next(k)?;
        writer.write_image_data(&f.rgba).map_err(err)?;
        progress(k + 1, anim.frames);
    }
    writer.finish().map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_container_comes_from_the_extension_or_to() {
        assert_eq!(Container::choose(Some("a.gif"), None), Some(Container::Gif));
        assert_eq!(
            Container::choose(Some("a.PNG"), None),
            Some(Container::Apng)
        );
        assert_eq!(Container::choose(None, Some("gif")), Some(Container::Gif));
        assert_eq!(Container::choose(Some("a.svg"), None), None);
    }

    #[test]
    fn too_many_frames_or_pixels_are_refused() {
        let anim = |frames, side| Animation {
            container: Container::Gif,
            width: side,
            height: side,
            fps: 10,
            frames,
        };
        assert!(anim(10, 64).refusal().is_none());
        assert!(anim(MAX_FRAMES + 1, 8).refusal().is_some());
        assert!(anim(100, 8192).refusal().is_some());
        assert!(anim(0, 8).refusal().is_some());
    }
}
