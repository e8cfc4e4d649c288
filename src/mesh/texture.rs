//! The images of a mesh's textures as files: PNG, top row first, as OBJ
//! readers (through `map_Kd`) and glTF (`image/png`) take them. The
//! decoded image is written rather than the source's file, so that an SGI
//! `.rgb` texture reaches readers that know only PNG.

use crate::ir::texture::Image;

/// The PNG bytes of `image`; `None` if encoding fails.
pub fn png(image: &Image) -> Option<Vec<u8>> {
    let (w, h) = (image.width(), image.height());
    let row = w as usize * 4;
    // The image keeps its bottom row first; PNG wants the top one.
    let mut top_first = Vec::with_capacity(image.rgba().len());
    for r in image.rgba().chunks_exact(row).rev() {
        top_first.extend_from_slice(r);
    }
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, w, h);
    encoder.set_color(::png::ColorType::Rgba);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().ok()?;
    writer.write_image_data(&top_first).ok()?;
    writer.finish().ok()?;
    Some(out)
}

/// The file an OBJ's material library names for texture `t` (counted
/// from 0): the library's name without `.mtl`, then `_t` and the
/// texture's number from 1, `.png`.
pub fn image_file(library: &str, t: u16) -> String {
    let stem = library.strip_suffix(".mtl").unwrap_or(library);
    format!("{stem}_t{}.png", u32::from(t) + 1)
}

/// The image files of the textures `mesh`'s parts wear: (file name, PNG
/// bytes), each once, named by [`image_file`].
pub fn image_files(mesh: &super::Mesh, library: &str) -> Vec<(String, Vec<u8>)> {
    let mut used: Vec<u16> = mesh.parts.iter().filter_map(|p| p.finish.texture).collect();
    used.sort_unstable();
    used.dedup();
    used.into_iter()
        .filter_map(|t| {
            let image = mesh.textures.get(usize::from(t))?.image.as_ref()?;
            Some((image_file(library, t), png(image)?))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_are_written_top_row_first_and_named_after_the_library() {
        // Bottom row red, top row blue.
        let rgba = vec![255, 0, 0, 255, 0, 0, 255, 255];
        let im = Image::new(1, 2, rgba).unwrap();
        let back = crate::decode::decode(&png(&im).unwrap()).unwrap();
        assert_eq!(back, im);
        assert_eq!(image_file("plant.mtl", 0), "plant_t1.png");
    }
}
