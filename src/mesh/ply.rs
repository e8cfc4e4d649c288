//! PLY (ASCII): vertices with normals and colours, triangles.

use super::Mesh;
use std::fmt::Write;

/// The PLY text of `mesh`; each vertex carries its part's colour (a
/// material's diffuse colour).
pub fn ply(mesh: &Mesh) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "ply\nformat ascii 1.0\ncomment graftal\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        mesh.vertices(),
        mesh.triangles()
    );
    for p in &mesh.parts {
        let (r, g, b) = p.finish.colour;
        for (v, n) in p.positions.iter().zip(&p.normals) {
            let _ = writeln!(
                s,
                "{} {} {} {} {} {} {r} {g} {b}",
                v[0] as f32, v[1] as f32, v[2] as f32, n[0] as f32, n[1] as f32, n[2] as f32
            );
        }
    }
    let mut base = 0u64;
    for p in &mesh.parts {
        for t in &p.triangles {
            let [a, b, c] = t.map(|i| u64::from(i) + base);
            let _ = writeln!(s, "3 {a} {b} {c}");
        }
        base += p.positions.len() as u64;
    }
    s
}
