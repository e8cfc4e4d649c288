//! The view file's textures (`texture:` lines, and the texture file a
//! `surface:` line may end with): their images read from the object's
//! folder and decoded. An image that is missing or cannot be decoded is a
//! warning at its view line, and what it would texture is drawn without
//! it (cpfg says so and draws untextured too); its number is kept, so the
//! `@Tx(n)` that follow still name the textures the author meant.

use super::{push_side_file, view, Beside};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::texture::Texture;
use crate::ir::System;
use std::sync::Arc;

impl Beside<'_> {
    /// Reads the view's textures into the look.
    pub(super) fn add_textures(&self, sys: &mut System, v: &view::View, diags: &mut Diagnostics) {
        let mut found = Diagnostics::default();
        for r in &v.textures {
            let image = self.image(&r.file, &r.line, &mut found);
            textures_of(sys).push(Texture {
                filter: r.filter,
                mode: r.mode,
                per_surface: r.per_surface,
                ratio: r.ratio,
                ..Texture::new(r.file.clone(), image)
            });
        }
        if let Some((path, text)) = &v.source {
            push_side_file(diags, &found, path, text);
        }
    }

    /// The texture a `surface:` line names, as one more texture of the
    /// look (cpfg's defaults, mapped across the whole surface); its
    /// number among the look's textures, counted from 0.
    pub(super) fn surface_texture(
        &self,
        sys: &mut System,
        r: &view::SurfaceRef,
        found: &mut Diagnostics,
    ) -> Option<u16> {
        let file = r.texture.as_ref()?;
        let image = self.image(file, &r.line, found);
        let index = u16::try_from(textures_of(sys).len()).ok()?;
        textures_of(sys).push(Texture {
            per_surface: true,
            ..Texture::new(file.clone(), image)
        });
        Some(index)
    }
}

/// The look's textures (a cpfg look is always lit; one that is not gets
/// the default lighting, which draws nothing differently).
fn textures_of(sys: &mut System) -> &mut Vec<Texture> {
    &mut sys
        .look
        .lighting
        .get_or_insert_with(Default::default)
        .textures
}

impl Beside<'_> {
    /// The decoded image `file`, or a warning at `line` saying why not.
    fn image(
        &self,
        file: &str,
        line: &crate::ir::Span,
        found: &mut Diagnostics,
    ) -> Option<Arc<crate::ir::texture::Image>> {
        let why = match self.read_bytes(file) {
            None if self.is_missing(file) || self.dir.is_none() => {
                "is not in the object's folder".to_string()
            }
            None => "cannot be read from the object's folder".to_string(),
            Some(bytes) => match crate::decode::decode(&bytes) {
                Ok(image) => return Some(Arc::new(image)),
                Err(e) => format!("cannot be decoded: {e}"),
            },
        };
        found.push(
            Diagnostic::at(
                codes::CPFG_TEXTURE_IMAGE,
                line.clone(),
                format!("the texture image `{file}` {why}: what it textures is drawn without it"),
            )
            .with_label("named here")
            .with_help(format!(
                "put `{file}` (a PNG or SGI .rgb image) in the object's folder"
            )),
        );
        None
    }
}
