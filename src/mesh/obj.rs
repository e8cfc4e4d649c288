//! Wavefront OBJ and its material library: one group per material, each
//! vertex with its normal (the same index for both). A textured part's
//! vertices have texture coordinates (`vt`, OpenGL's, v up from the
//! image's bottom row) and its material names the texture's image
//! (`map_Kd`), written as PNG beside the library ([`super::texture`]).
//! OBJ's `map_Kd` multiplies the diffuse colour: cpfg's modulate mode;
//! decal and blend textures are written as modulated too.

use super::{Finish, Mesh};
use crate::ir::look::Material;
use std::fmt::Write;

/// The OBJ text of `mesh`, naming `mtl_file` (beside it) as its material
/// library.
pub fn obj(mesh: &Mesh, mtl_file: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# graftal\nmtllib {mtl_file}\no graftal");
    for p in &mesh.parts {
        for v in &p.positions {
            let _ = writeln!(s, "v {} {} {}", v[0] as f32, v[1] as f32, v[2] as f32);
        }
    }
    for p in &mesh.parts {
        for n in &p.normals {
            let _ = writeln!(s, "vn {} {} {}", n[0] as f32, n[1] as f32, n[2] as f32);
        }
    }
    for p in mesh.parts.iter().filter(|p| textured(p)) {
        for uv in &p.uvs {
            let _ = writeln!(s, "vt {} {}", uv[0] as f32, uv[1] as f32);
        }
    }
    // OBJ indices count from 1 over the whole file; texture coordinates
    // are counted apart.
    let (mut base, mut uv_base) = (1u64, 1u64);
    for p in &mesh.parts {
        let _ = writeln!(s, "usemtl {}", p.finish.name());
        let with_uvs = textured(p);
        for t in &p.triangles {
            let [a, b, c] = t.map(|i| u64::from(i) + base);
            if with_uvs {
                let [ta, tb, tc] = t.map(|i| u64::from(i) + uv_base);
                let _ = writeln!(s, "f {a}/{ta}/{a} {b}/{tb}/{b} {c}/{tc}/{c}");
            } else {
                let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
            }
        }
        base += p.positions.len() as u64;
        if with_uvs {
            uv_base += p.uvs.len() as u64;
        }
    }
    s
}

/// Whether a part's vertices carry texture coordinates.
fn textured(p: &super::Part) -> bool {
    p.finish.texture.is_some() && p.uvs.len() == p.positions.len()
}

/// The material library `library` of `mesh`: a lit look's materials as
/// they are, else a diffuse colour per part; a textured part's material
/// names its image ([`super::texture::image_file`]).
pub fn mtl(mesh: &Mesh, library: &str) -> String {
    let mut s = String::from("# graftal\n");
    for p in &mesh.parts {
        match p.finish.material {
            Some((_, m)) => lit(&mut s, &p.finish, &m),
            None => plain(&mut s, &p.finish),
        }
        let image = p.finish.texture.filter(|&t| {
            let t = mesh.textures.get(usize::from(t));
            textured(p) && t.is_some_and(|t| t.image.is_some())
        });
        if let Some(t) = image {
            // The material's block ends with a blank line: the map goes
            // before it.
            s.pop();
            let _ = writeln!(s, "map_Kd {}\n", super::texture::image_file(library, t));
        }
    }
    s
}

fn plain(s: &mut String, f: &Finish) {
    let (r, g, b) = f.colour;
    let c = |x: u8| f64::from(x) / 255.0;
    let _ = writeln!(
        s,
        "newmtl {}\nKa 0 0 0\nKd {:.4} {:.4} {:.4}\nKs 0 0 0\nd 1\nillum 1\n",
        f.name(),
        c(r),
        c(g),
        c(b)
    );
}

/// A cpfg material: OpenGL's ambient, diffuse, specular and emission as
/// `Ka`, `Kd`, `Ks`, `Ke`. Its shininess (`GL_SHININESS`, 0..=128) is the
/// exponent of the same Phong highlight that `Ns` (0..=1000) is, so `Ns`
/// takes it unchanged. `d` is the opacity, 1 − transparency; `illum 2`
/// (highlights on) when the material has a specular colour.
fn lit(s: &mut String, f: &Finish, m: &Material) {
    let rgb = |c: [f32; 3]| format!("{:.4} {:.4} {:.4}", c[0], c[1], c[2]);
    let shiny = m.specular.iter().any(|&x| x > 0.0);
    let _ = writeln!(
        s,
        "newmtl {}\nKa {}\nKd {}\nKs {}\nKe {}\nNs {:.4}\nd {:.4}\nillum {}\n",
        f.name(),
        rgb(m.ambient),
        rgb(m.diffuse),
        rgb(m.specular),
        rgb(m.emission),
        m.shininess.clamp(0.0, 128.0),
        1.0 - m.transparency.clamp(0.0, 1.0),
        if shiny { 2 } else { 1 }
    );
}
