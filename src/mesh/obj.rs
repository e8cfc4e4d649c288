//! Wavefront OBJ and its material library: one group per colour, each
//! vertex with its normal (the same index for both).

use super::Mesh;
use std::fmt::Write;

/// The material name of a colour.
pub(crate) fn material_name(c: (u8, u8, u8)) -> String {
    format!("c{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

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
    // OBJ indices count from 1 over the whole file.
    let mut base = 1u64;
    for p in &mesh.parts {
        let _ = writeln!(s, "usemtl {}", material_name(p.colour));
        for t in &p.triangles {
            let [a, b, c] = t.map(|i| u64::from(i) + base);
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
        }
        base += p.positions.len() as u64;
    }
    s
}

/// The material library of `mesh`: a diffuse colour per part.
pub fn mtl(mesh: &Mesh) -> String {
    let mut s = String::from("# graftal\n");
    for p in &mesh.parts {
        let (r, g, b) = p.colour;
        let f = |x: u8| f64::from(x) / 255.0;
        let _ = writeln!(
            s,
            "newmtl {}\nKa 0 0 0\nKd {:.4} {:.4} {:.4}\nKs 0 0 0\nd 1\nillum 1\n",
            material_name(p.colour),
            f(r),
            f(g),
            f(b)
        );
    }
    s
}
