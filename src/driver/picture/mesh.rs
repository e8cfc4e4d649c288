//! Meshes: OBJ (with its material library), PLY and glTF, from shared
//! subtrees where a glTF can place them, else from the interpreted word.

use super::{DrawError, Method, Picture, Progress, Request, SideFile, Stage};
use crate::driver::derive::derive_values;
use crate::driver::interpret::{add_fixed, check_moves_up_front, interpret};
use crate::eval::tree::MAX_TREE_DEPTH;
use crate::ir::System;
use crate::mesh::{MeshFormat, Scene};
use crate::turtle::instanced::Instanced;

/// The mesh of the system in `format`: for glTF from its shared subtrees
/// when [`Instanced`] can (one mesh per repeated subtree), else from the
/// derived word's geometry (with an STL file's layout when the request
/// asks for one). An OBJ names its material library
/// [`Request::material_library`], returned as a side file.
pub(super) fn draw(
    sys: &System,
    format: MeshFormat,
    req: &Request,
    progress: &mut dyn Progress,
) -> Result<Picture, DrawError> {
    let opts = &req.run;
    let steps = opts.derive_options(sys).steps;
    // A scene beside the word is drawn from the stored geometry.
    let instanced = format == MeshFormat::Glb && sys.look.scene.is_empty();
    let shared = (instanced && steps <= MAX_TREE_DEPTH)
        .then(|| Instanced::new(sys).filter(|i| i.fits(steps)))
        .flatten()
        .and_then(|mut inst| crate::mesh::instanced::scene(sys, &mut inst, steps));
    let method = match shared {
        Some(_) => Method::InstancedMesh,
        None => Method::Mesh,
    };
    let scene = match shared {
        Some(s) => s,
        None => {
            check_moves_up_front(sys, opts)?;
            let (word, values) = derive_values(sys, opts, |k, n| progress.derived(k, steps, n))?;
            let mut g = interpret(sys, &word, &values, opts, false)?;
            add_fixed(sys, &mut g, req.layout);
            let lighting = sys.look.lighting.as_ref();
            let mut meshing = |done, total| progress.advanced(Stage::Meshing, done, total);
            Scene::single(crate::mesh::of_geometry(&g, lighting, &mut meshing))
        }
    };
    let stats = scene.stats();
    let (bytes, side_files) = match format {
        MeshFormat::Glb => (crate::mesh::glb(&scene), Vec::new()),
        MeshFormat::Obj => {
            let mesh = scene.flattened();
            let library = &req.material_library;
            let mtl = SideFile {
                name: library.clone(),
                bytes: crate::mesh::mtl(&mesh, library).into_bytes(),
            };
            // The textures' images beside the library that names them.
            let images = crate::mesh::texture::image_files(&mesh, library)
                .into_iter()
                .map(|(name, bytes)| SideFile { name, bytes });
            let obj = crate::mesh::obj(&mesh, library);
            (
                obj.into_bytes(),
                std::iter::once(mtl).chain(images).collect(),
            )
        }
        MeshFormat::Ply => (
            crate::mesh::ply(&scene.flattened()).into_bytes(),
            Vec::new(),
        ),
    };
    Ok(Picture {
        bytes,
        side_files,
        method,
        warnings: Vec::new(),
        mesh: Some(stats),
    })
}
