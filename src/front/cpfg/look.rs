//! What a cpfg picture looks like besides its L-system: the colour maps
//! (`-m file.map`, `-m1`/`-m2` for indices 0–255 and 256–511) or the
//! materials (`-M file.mat`) named on the object's `cpfg` command line in
//! its `specifications` file (manual §1.2.2), and the view file's camera,
//! lights and rendering switches, as the IR's [`Look`].
//!
//! Formats (vlab's palette and medit editors write them):
//! - `.map`: 256 RGB byte triples, 768 bytes;
//! - `.mat`: records of 15 bytes: the colour index, transparency, then
//!   ambient, diffuse, emission and specular RGB, then the shininess; each
//!   byte scaled to 0..=1 (the shininess to 0..=128).
//!
//! The background is colour index 0: the map's first colour, or the
//! emission of material 0 (manual §8.1.10, "background color … use
//! instead").

use super::view::{self, View};
use crate::ir::look::{Camera, Lighting, LineStyle, Look, Material, Shading};
use crate::ir::Rgb;

/// A `.map` file's size: 256 RGB triples.
const MAP_BYTES: usize = 768;
/// A `.mat` record's size.
const MATERIAL_BYTES: usize = 15;

/// The colour files of an object's `cpfg` command line.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ColourFiles {
    /// Colour maps and the block of 256 indices each fills (`-m`, `-m1`:
    /// 0; `-m2`: 1; …).
    pub maps: Vec<(usize, String)>,
    /// The material file (`-M`).
    pub materials: Option<String>,
}

/// The colour files of the `cpfg` line of `spec` (a `specifications`
/// file) that names `l_name`; else of its first `cpfg` line.
pub fn colour_files(spec: &str, l_name: &str) -> ColourFiles {
    let lines: Vec<Vec<&str>> = spec
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| w.first() == Some(&"cpfg"))
        .collect();
    let Some(words) = lines.iter().find(|w| w.contains(&l_name)).or(lines.first()) else {
        return ColourFiles::default();
    };
    let mut files = ColourFiles::default();
    for pair in words.windows(2) {
        let (flag, file) = (pair[0], pair[1].to_string());
        if flag == "-M" {
            files.materials = Some(file);
        } else if let Some(n) = flag.strip_prefix("-m") {
            match n.parse::<usize>() {
                Ok(k) if (1..=4).contains(&k) => files.maps.push((k - 1, file)),
                _ if n.is_empty() => files.maps.push((0, file)),
                _ => {}
            }
        }
    }
    files
}

/// The 256 colours of a `.map` file.
pub fn read_map(bytes: &[u8]) -> Result<Vec<Rgb>, String> {
    if bytes.len() != MAP_BYTES {
        return Err(format!(
            "a colour map has {MAP_BYTES} bytes (256 RGB triples), this file {}",
            bytes.len()
        ));
    }
    Ok(bytes.chunks(3).map(|c| Rgb(c[0], c[1], c[2])).collect())
}

/// The materials of a `.mat` file, by colour index.
pub fn read_materials(bytes: &[u8]) -> Result<Vec<Option<Material>>, String> {
    if bytes.is_empty() || bytes.len() % MATERIAL_BYTES != 0 {
        return Err(format!(
            "a material file is made of {MATERIAL_BYTES}-byte records, this file has {} bytes",
            bytes.len()
        ));
    }
    let mut out = vec![None; 256];
    for r in bytes.chunks(MATERIAL_BYTES) {
        let unit = |k: usize| [r[k], r[k + 1], r[k + 2]].map(|b| b as f32 / 255.0);
        out[r[0] as usize] = Some(Material {
            transparency: r[1] as f32 / 255.0,
            ambient: unit(2),
            diffuse: unit(5),
            emission: unit(8),
            specular: unit(11),
            shininess: r[14] as f32 / 255.0 * 128.0,
        });
    }
    Ok(out)
}

/// A material's colour when drawn unlit (cpfg's `filled` mode draws the
/// diffuse colour).
pub fn flat_colour(m: &Material) -> Rgb {
    let c = m.diffuse.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
    Rgb(c[0], c[1], c[2])
}

/// The material OpenGL gives an index the file leaves out.
pub const DEFAULT_MATERIAL: Material = Material {
    ambient: [0.2, 0.2, 0.2],
    diffuse: [0.8, 0.8, 0.8],
    specular: [0.0, 0.0, 0.0],
    emission: [0.0, 0.0, 0.0],
    shininess: 0.0,
    transparency: 0.0,
};

/// The look of a picture of the view `v`, drawn with `palette` (colour-map
/// mode) or `materials` (material mode, when not empty).
pub fn look(v: &View, palette: &[Rgb], materials: &[Option<Material>]) -> Look {
    let background = match materials.first() {
        Some(Some(m)) => {
            let c = m
                .emission
                .map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
            Rgb(c[0], c[1], c[2])
        }
        Some(None) => Rgb(0, 0, 0),
        None => palette.first().copied().unwrap_or(Rgb(0, 0, 0)),
    };
    Look {
        scene: Vec::new(),
        background: Some(background),
        lighting: Some(lighting(v, materials)),
        camera: Some(camera(v)),
    }
}

fn lighting(v: &View, materials: &[Option<Material>]) -> Lighting {
    let shading = match v.render_mode {
        view::RenderMode::Filled | view::RenderMode::Fast => Shading::Filled,
        view::RenderMode::Wireframe => Shading::Wireframe,
        view::RenderMode::Flat => Shading::Flat,
        view::RenderMode::Interpolated | view::RenderMode::Shaded | view::RenderMode::Shadows => {
            Shading::Smooth
        }
    };
    let line_style = match v.line_style {
        view::LineStyle::Pixel | view::LineStyle::Wireframe => LineStyle::Pixel,
        view::LineStyle::Polygon => LineStyle::Polygon,
        view::LineStyle::Cylinder => LineStyle::Cylinder,
    };
    let lights = if !materials.is_empty() && !v.lights.is_empty() {
        v.lights.clone()
    } else if materials.is_empty() {
        vec![crate::ir::look::Light {
            vector: v.light_direction,
            directional: true,
            ..Default::default()
        }]
    } else {
        vec![crate::ir::look::Light::default()]
    };
    Lighting {
        shading,
        line_style,
        tapered: v.tapered_lines,
        lights,
        materials: materials.to_vec(),
        index_shift: v.diffuse_reflection,
        surface_ambient: v.surface_ambient,
        surface_diffuse: v.surface_diffuse,
        shadows: v.render_mode == view::RenderMode::Shadows,
        textures: Vec::new(),
    }
}

/// The camera of the view file: from the viewpoint towards the view
/// reference point, the picture turned by the twist (tenths of a degree,
/// manual §8.1.2).
fn camera(v: &View) -> Camera {
    let perspective = (v.projection == view::Projection::Perspective).then_some(v.viewing_angle);
    // A perspective zooms by moving the eye: cpfg's SetView puts it at
    // vrp + (viewpoint − vrp) / scale factor.
    let zoom = match perspective {
        Some(_) if v.scale_factor > 0.0 && v.scale_factor.is_finite() => v.scale_factor,
        _ => 1.0,
    };
    let (vp, vrp) = (v.viewpoint, v.view_reference_point);
    let eye = [0, 1, 2].map(|k| vrp[k] + (vp[k] - vrp[k]) / zoom);
    Camera::aimed(eye, v.view_reference_point, v.twist / 10.0, perspective)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_line_names_maps_and_materials() {
        let spec = "model:\n\tgenerate:\n\t\tcpfg -m1 a.map -m2 b.map2 x.l x.v\n\t\tcpfg -M m.mat y.l y.v y.a\n";
        let x = colour_files(spec, "x.l");
        assert_eq!(x.maps, vec![(0, "a.map".into()), (1, "b.map2".into())]);
        assert_eq!(x.materials, None);
        let y = colour_files(spec, "y.l");
        assert!(y.maps.is_empty());
        assert_eq!(y.materials.as_deref(), Some("m.mat"));
        // An .l no line names: the first line's files.
        assert_eq!(colour_files(spec, "z.l"), x);
        assert_eq!(colour_files("", "x.l"), ColourFiles::default());
    }

    #[test]
    fn maps_are_768_bytes() {
        let mut bytes = vec![0u8; 768];
        bytes[3..6].copy_from_slice(&[10, 20, 30]);
        let map = read_map(&bytes).unwrap();
        assert_eq!(map.len(), 256);
        assert_eq!(map[1], Rgb(10, 20, 30));
        assert!(read_map(&bytes[..767]).is_err());
    }

    #[test]
    fn material_records_by_index() {
        let rec = [3, 0, 0, 0, 0, 255, 0, 0, 0, 0, 51, 255, 255, 255, 255];
        let mats = read_materials(&rec).unwrap();
        let m = mats[3].unwrap();
        assert_eq!(m.diffuse, [1.0, 0.0, 0.0]);
        assert_eq!(m.emission, [0.0, 0.0, 0.2]);
        assert_eq!(m.shininess, 128.0);
        assert!(mats[0].is_none());
        assert_eq!(flat_colour(&m), Rgb(255, 0, 0));
        assert!(read_materials(&rec[..14]).is_err());
        assert!(read_materials(&[]).is_err());
    }

    #[test]
    fn background_is_index_zero() {
        let v = View::default();
        let palette = vec![Rgb(1, 2, 3), Rgb(9, 9, 9)];
        assert_eq!(look(&v, &palette, &[]).background, Some(Rgb(1, 2, 3)));
        let mut mats = vec![None; 2];
        mats[0] = Some(Material {
            emission: [1.0, 0.0, 0.0],
            ..DEFAULT_MATERIAL
        });
        assert_eq!(look(&v, &palette, &mats).background, Some(Rgb(255, 0, 0)));
    }

    #[test]
    fn camera_looks_at_the_reference_point() {
        let mut v = View {
            viewpoint: [0.0, 0.0, 5.0],
            ..View::default()
        };
        let cam = camera(&v);
        assert_eq!(cam.up, [0.0, 1.0, 0.0]);
        assert_eq!(cam.perspective, None);
        // 900 tenths of a degree: a quarter turn, clockwise on the screen
        // (cpfg's up becomes -x, so world +y points right).
        v.twist = 900.0;
        let up = camera(&v).up;
        assert!(up[1].abs() < 1e-9 && (up[0] + 1.0).abs() < 1e-9, "{up:?}");
        // Looking straight down y.
        v.viewpoint = [0.0, 10.0, 0.0];
        v.twist = 0.0;
        let up = camera(&v).up;
        assert!(up[1].abs() < 1e-9 && (up[2].abs() - 1.0).abs() < 1e-9);
    }
}
