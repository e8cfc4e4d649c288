//! The items of docs/gft.md §9 (`background`, `camera`, `lighting`,
//! `light`, `material`, `surface`, `contour`), `function` and `tropism`:
//! fixed fields, each introduced by its label, read from a keyword's
//! arguments.

use super::{err, Cx};
use crate::diagnostics::codes;
use crate::front::gft::ast::{Arg, Keyword};
use crate::ir::look::{
    Camera, Contour, ContourRole, Light, Lighting, LineStyle, Material, Shading, Tropism,
    TropismKind,
};
use crate::ir::program::Function;
use crate::ir::texture::{Filter, Image, Texture, TextureMode};
use crate::ir::{ElasticityChange, QueryKind, Rgb, Span, SurfaceMesh, TurtleOp};

/// One argument after joining what is written without space between:
/// a word (`line-style`, `~l`), a number (`-0.5`), a colour or a
/// parenthesised list of numbers `(x, y, z)`.
#[derive(Clone, Debug)]
pub(super) enum Val {
    Word(String, Span),
    Num(String, Span),
    Colour(Rgb, Span),
    Tuple(Vec<String>, Span),
}

impl Val {
    pub(super) fn span(&self) -> &Span {
        match self {
            Val::Word(_, s) | Val::Num(_, s) | Val::Colour(_, s) | Val::Tuple(_, s) => s,
        }
    }
}

/// `#rrggbb` as a colour.
pub(super) fn rgb(text: &str) -> Option<Rgb> {
    let hex = text.strip_prefix('#').filter(|h| h.len() == 6)?;
    let h = |i: usize| u8::from_str_radix(hex.get(i..i + 2)?, 16).ok();
    Some(Rgb(h(0)?, h(2)?, h(4)?))
}

fn run_val(text: String, span: Span) -> Val {
    if let Some(c) = rgb(&text) {
        return Val::Colour(c, span);
    }
    if text.parse::<f64>().is_ok() {
        return Val::Num(text, span);
    }
    Val::Word(text, span)
}

/// The arguments as [`Val`]s (a `(` without its `)` takes the rest).
pub(super) fn vals(args: &[Arg]) -> Vec<Val> {
    let mut out = Vec::new();
    let mut run: Option<(String, Span)> = None;
    let mut i = 0;
    while i < args.len() {
        let a = &args[i];
        if a.text() == "(" {
            if let Some((t, s)) = run.take() {
                out.push(run_val(t, s));
            }
            let close = (i..args.len())
                .find(|&k| args[k].text() == ")")
                .unwrap_or(args.len());
            let inner: String = args[i + 1..close].iter().map(Arg::text).collect();
            let end = args.get(close).unwrap_or(&args[args.len() - 1]).span().end;
            let parts = inner.split(',').map(str::to_string).collect();
            out.push(Val::Tuple(parts, a.span().start..end));
            i = close + 1;
            continue;
        }
        match &mut run {
            Some((t, s)) if s.end == a.span().start => {
                t.push_str(a.text());
                s.end = a.span().end;
            }
            _ => {
                if let Some((t, s)) = run.take() {
                    out.push(run_val(t, s));
                }
                run = Some((a.text().to_string(), a.span().clone()));
            }
        }
        i += 1;
    }
    if let Some((t, s)) = run {
        out.push(run_val(t, s));
    }
    out
}

/// Reads a line's labelled fields, reporting the first field that is
/// missing or malformed once (E0903).
pub(super) struct Fields<'k> {
    vals: Vec<Val>,
    line: &'k Span,
    /// The first problem: where, and what was expected.
    pub(super) problem: Option<(Span, String)>,
}

impl<'k> Fields<'k> {
    pub(super) fn new(k: &'k Keyword) -> Self {
        Fields {
            vals: vals(&k.args),
            line: &k.line,
            problem: None,
        }
    }

    fn fail<T>(&mut self, at: Option<&Val>, what: String) -> Option<T> {
        if self.problem.is_none() {
            let span = at.map_or(self.line.clone(), |v| v.span().clone());
            self.problem = Some((span, what));
        }
        None
    }

    /// The value right after the word `label` (or the first value when
    /// `label` is empty).
    fn after(&self, label: &str) -> Option<(usize, &Val)> {
        if label.is_empty() {
            return self.vals.first().map(|v| (0, v));
        }
        let k = self
            .vals
            .iter()
            .position(|v| matches!(v, Val::Word(w, _) if w == label))?;
        self.vals.get(k + 1).map(|v| (k + 1, v))
    }

    /// The second value after the word `label` (`broadness 8 1`).
    pub(super) fn second<T: std::str::FromStr>(&mut self, label: &str) -> Option<T> {
        let k = self.after(label).map(|x| x.0 + 1);
        match k.and_then(|k| self.vals.get(k)).cloned() {
            Some(Val::Num(t, s)) => match t.parse() {
                Ok(v) => Some(v),
                Err(_) => self.fail(
                    Some(&Val::Num(t, s)),
                    format!("two numbers after `{label}`"),
                ),
            },
            v => self.fail(v.as_ref(), format!("two numbers after `{label}`")),
        }
    }

    /// The third value after the word `label` (`grid 32 32 32`).
    pub(super) fn third<T: std::str::FromStr>(&mut self, label: &str) -> Option<T> {
        let k = self.after(label).map(|x| x.0 + 2);
        match k.and_then(|k| self.vals.get(k)).cloned() {
            Some(Val::Num(t, s)) => match t.parse() {
                Ok(v) => Some(v),
                Err(_) => self.fail(
                    Some(&Val::Num(t, s)),
                    format!("three numbers after `{label}`"),
                ),
            },
            v => self.fail(v.as_ref(), format!("three numbers after `{label}`")),
        }
    }

    /// `(x, y)` after `label`, as `[x, y, 0]`.
    pub(super) fn pair_or_triple(&mut self, label: &str) -> Option<[f64; 3]> {
        let v = self.after(label).map(|x| x.1.clone());
        if let Some(Val::Tuple(parts, _)) = &v {
            let n: Option<Vec<f64>> = parts.iter().map(|p| p.trim().parse().ok()).collect();
            if let Some(&[a, b]) = n.as_deref() {
                return Some([a, b, 0.0]);
            }
        }
        self.fail(v.as_ref(), format!("`(x, y)` after `{label}`"))
    }

    /// Fails at the value after `label`, expecting `what`.
    pub(super) fn fail_at<T>(&mut self, label: &str, what: &str) -> Option<T> {
        let v = self.after(label).map(|x| x.1.clone());
        self.fail(v.as_ref(), what.to_string())
    }

    /// The whole line's span.
    pub(super) fn line(&self) -> &Span {
        self.line
    }

    /// Whether the word `w` is present.
    pub(super) fn has(&self, w: &str) -> bool {
        self.vals
            .iter()
            .any(|v| matches!(v, Val::Word(x, _) if x == w))
    }

    pub(super) fn number<T: std::str::FromStr>(&mut self, label: &str) -> Option<T> {
        match self.after(label) {
            Some((_, Val::Num(t, _))) => match t.parse() {
                Ok(v) => Some(v),
                Err(_) => {
                    let v = self.after(label).map(|x| x.1.clone());
                    self.fail(v.as_ref(), format!("a number after `{label}`"))
                }
            },
            v => {
                let v = v.map(|x| x.1.clone());
                self.fail(v.as_ref(), format!("a number after `{label}`"))
            }
        }
    }

    pub(super) fn word(&mut self, label: &str, choices: &[&str]) -> Option<String> {
        match self.after(label) {
            Some((_, Val::Word(w, _))) if choices.is_empty() || choices.contains(&w.as_str()) => {
                Some(w.clone())
            }
            v => {
                let v = v.map(|x| x.1.clone());
                let what = if choices.is_empty() {
                    "a name".to_string()
                } else {
                    choices.join(" or ")
                };
                self.fail(v.as_ref(), what)
            }
        }
    }

    pub(super) fn colour(&mut self, label: &str) -> Option<Rgb> {
        match self.after(label) {
            Some((_, Val::Colour(c, _))) => Some(*c),
            v => {
                let v = v.map(|x| x.1.clone());
                self.fail(v.as_ref(), "a colour `#rrggbb`".into())
            }
        }
    }

    /// `(x, y, z)` after `label`, each parsed as `T` (f32 fields parse as
    /// f32, docs/gft-emitter-notes.md).
    pub(super) fn triple<T: std::str::FromStr + Copy>(&mut self, label: &str) -> Option<[T; 3]> {
        let v = self.after(label).map(|x| x.1.clone());
        if let Some(Val::Tuple(parts, _)) = &v {
            let n: Option<Vec<T>> = parts.iter().map(|p| p.parse().ok()).collect();
            if let Some([a, b, c]) = n.as_deref() {
                return Some([*a, *b, *c]);
            }
        }
        self.fail(v.as_ref(), format!("`(x, y, z)` after `{label}`"))
    }

    /// Every value, in order (the points of a surface or contour line).
    pub(super) fn all(&self) -> &[Val] {
        &self.vals
    }
}

impl Cx<'_> {
    /// Reports a malformed item: `shape` is what the line should look like.
    pub(super) fn malformed(&mut self, f: Fields<'_>, k: &Keyword, shape: &str) -> Option<()> {
        let (span, what) = f.problem?;
        self.diags.push(err(
            codes::GFT_BAD_VALUE,
            &span,
            format!("malformed `{}`", k.name),
            &format!("expected {what}"),
            &format!("write `{shape}`"),
        ));
        Some(())
    }

    /// The look, function and tropism items; false when `k` is none of them.
    pub(super) fn look_item(&mut self, k: &Keyword) -> bool {
        match k.name.as_str() {
            "background" => self.background(k),
            "camera" => self.camera(k),
            "lighting" => self.lighting(k),
            "light" => self.light(k),
            "material" => self.material(k),
            "texture" => self.texture(k),
            "contour" => self.contour(k),
            "backdrop" => self.backdrop(k),
            "function" => self.function(k),
            "tropism" => self.tropism(k),
            // Read before the symbols' operations, which name surfaces.
            "surface" => {}
            _ => return false,
        }
        true
    }

    fn background(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        if let Some(c) = f.colour("") {
            self.sys.look.background = Some(c);
        }
        self.malformed(f, k, "background #000000");
    }

    fn camera(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let (eye, target, up) = (f.triple("eye"), f.triple("target"), f.triple("up"));
        let perspective = if f.has("perspective") {
            f.number("perspective")
        } else {
            None
        };
        if let (Some(eye), Some(target), Some(up)) = (eye, target, up) {
            self.sys.look.camera = Some(Camera {
                eye,
                target,
                up,
                perspective,
            });
        }
        self.malformed(
            f,
            k,
            "camera eye (0, 0, 10) target (0, 0, 0) up (0, 1, 0) [perspective 45]",
        );
    }

    fn lighting_mut(&mut self) -> &mut Lighting {
        self.sys.look.lighting.get_or_insert_with(|| Lighting {
            lights: Vec::new(),
            ..Lighting::default()
        })
    }

    fn lighting(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let shading = f.word("", &["filled", "wireframe", "flat", "smooth"]);
        let style = f.word("line-style", &["pixel", "polygon", "cylinder"]);
        let tapered = f.has("tapered");
        let shadows = f.has("shadows");
        let shift = f.number("index-shift");
        let ambient = f.number("surface-ambient");
        let diffuse = f.number("surface-diffuse");
        if let (Some(s), Some(ls), Some(shift), Some(a), Some(d)) =
            (shading, style, shift, ambient, diffuse)
        {
            let l = self.lighting_mut();
            l.shading = match s.as_str() {
                "filled" => Shading::Filled,
                "wireframe" => Shading::Wireframe,
                "flat" => Shading::Flat,
                _ => Shading::Smooth,
            };
            l.line_style = match ls.as_str() {
                "pixel" => LineStyle::Pixel,
                "polygon" => LineStyle::Polygon,
                _ => LineStyle::Cylinder,
            };
            (l.tapered, l.shadows, l.index_shift) = (tapered, shadows, shift);
            (l.surface_ambient, l.surface_diffuse) = (a, d);
        }
        self.malformed(f, k, "lighting flat line-style cylinder [tapered] [shadows] index-shift 10 surface-ambient 0.15 surface-diffuse 0.75");
    }

    fn light(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let vector = f.triple("");
        let kind = match f.all().get(1).cloned() {
            Some(Val::Word(w, _)) if w == "directional" || w == "point" => Some(w),
            v => f.fail(v.as_ref(), "directional or point".into()),
        };
        let (a, d, s) = (
            f.triple("ambient"),
            f.triple("diffuse"),
            f.triple("specular"),
        );
        if let (Some(vector), Some(kind), Some(ambient), Some(diffuse), Some(specular)) =
            (vector, kind, a, d, s)
        {
            self.lighting_mut().lights.push(Light {
                vector,
                directional: kind == "directional",
                ambient,
                diffuse,
                specular,
            });
        }
        self.malformed(f, k, "light (0, 0, 1) directional|point ambient (1, 1, 1) diffuse (1, 1, 1) specular (1, 1, 1)");
    }

    fn material(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let index: Option<u16> = f.number("");
        // `material N` alone: slot N holds no material (the list's length).
        if let (Some(i), 1) = (index, f.all().len()) {
            let ms = &mut self.lighting_mut().materials;
            if ms.len() <= usize::from(i) {
                ms.resize(usize::from(i) + 1, None);
            }
            return;
        }
        let (a, d) = (f.triple("ambient"), f.triple("diffuse"));
        let (s, e) = (f.triple("specular"), f.triple("emission"));
        let (shininess, transparency) = (f.number("shininess"), f.number("transparency"));
        if let (Some(i), Some(a), Some(d), Some(s), Some(e), Some(sh), Some(t)) =
            (index, a, d, s, e, shininess, transparency)
        {
            let ms = &mut self.lighting_mut().materials;
            let i = usize::from(i);
            if ms.len() <= i {
                ms.resize(i + 1, None);
            }
            ms[i] = Some(Material {
                ambient: a,
                diffuse: d,
                specular: s,
                emission: e,
                shininess: sh,
                transparency: t,
            });
        }
        self.malformed(f, k, "material 3 ambient (…) diffuse (…) specular (…) emission (…) shininess 20 transparency 0");
    }

    /// The points of a block's lines, in order; `None` when one is not
    /// `(x, y, z)` (reported).
    fn block_points(&mut self, k: &Keyword) -> Option<Vec<[f64; 3]>> {
        let mut points = Vec::new();
        for v in vals(&k.lines()) {
            let p = match &v {
                Val::Tuple(parts, _) => {
                    let n: Option<Vec<f64>> = parts.iter().map(|p| p.parse().ok()).collect();
                    n.and_then(|n| <[f64; 3]>::try_from(n).ok())
                }
                _ => None,
            };
            match p {
                Some(p) => points.push(p),
                None => {
                    self.diags.push(err(
                        codes::GFT_BAD_VALUE,
                        v.span(),
                        format!("not a point of `{}`", k.name),
                        "not `(x, y, z)`",
                        "write each point as `(x, y, z)`",
                    ));
                    return None;
                }
            }
        }
        Some(points)
    }

    /// `backdrop #rrggbb INDEX { points }`: a polygon of the look's scene.
    fn backdrop(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let colour = f.colour("");
        let index = f.second::<u16>("");
        let points = self.block_points(k);
        if let (Some(colour), Some(index), Some(points)) = (colour, index, points) {
            if points.len() < 3 {
                self.diags.push(err(
                    codes::GFT_BAD_VALUE,
                    &k.line,
                    "a backdrop polygon has three points or more",
                    "fewer than three points",
                    "write its corners as `(x, y, z)`",
                ));
                return;
            }
            self.sys.look.scene.push(crate::ir::look::ScenePolygon {
                points,
                colour,
                index,
            });
        }
        self.malformed(
            f,
            k,
            "backdrop #rrggbb INDEX { (x, y, z) (x, y, z) (x, y, z) }",
        );
    }

    /// `texture "FILE" filter F mode M ratio R [surface-wide]`: one more
    /// texture of the look, its image read from the file's folder.
    fn texture(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let file = match f.all().first().cloned() {
            Some(Val::Word(w, _)) if w.len() >= 2 && w.starts_with('"') && w.ends_with('"') => {
                Some(w[1..w.len() - 1].to_string())
            }
            v => f.fail(v.as_ref(), "the image's file name in double quotes".into()),
        };
        let filter = f.word("filter", &["nearest", "linear"]);
        let mode = f.word("mode", &["modulate", "decal", "blend"]);
        let ratio = f.number("ratio");
        let per_surface = f.has("surface-wide");
        if let (Some(file), Some(filter), Some(mode), Some(ratio)) = (file, filter, mode, ratio) {
            let image = self.texture_image(&file, &k.line);
            self.lighting_mut().textures.push(Texture {
                filter: match filter.as_str() {
                    "linear" => Filter::Linear,
                    _ => Filter::Nearest,
                },
                mode: match mode.as_str() {
                    "decal" => TextureMode::Decal,
                    "blend" => TextureMode::Blend,
                    _ => TextureMode::Modulate,
                },
                per_surface,
                ratio,
                ..Texture::new(file, image)
            });
        }
        self.malformed(
            f,
            k,
            "texture \"leaf.png\" filter nearest mode modulate ratio 1 [surface-wide]",
        );
    }

    /// The decoded image `file` of the `.gft`'s folder, or a warning at
    /// `line` (W0904) saying why not: what it textures is then drawn
    /// untextured, as a cpfg view file's missing image is.
    pub(super) fn texture_image(
        &mut self,
        file: &str,
        line: &Span,
    ) -> Option<std::sync::Arc<Image>> {
        let why = match self.folder.map(|d| read_capped(&d.join(file))) {
            None => "cannot be read: the text has no folder".to_string(),
            Some(Err(e)) if e.kind() == std::io::ErrorKind::NotFound => {
                "is not in the file's folder".to_string()
            }
            Some(Err(e)) => format!("cannot be read: {e}"),
            Some(Ok(bytes)) => match crate::decode::decode(&bytes) {
                Ok(image) => return Some(std::sync::Arc::new(image)),
                Err(e) => format!("cannot be decoded: {e}"),
            },
        };
        self.diags.push(
            crate::diagnostics::Diagnostic::at(
                codes::GFT_TEXTURE_IMAGE,
                line.clone(),
                format!("the texture image `{file}` {why}: what it textures is drawn without it"),
            )
            .with_label("named here")
            .with_help(format!(
                "put `{file}` (a PNG or SGI .rgb image) beside the .gft file, or name it relative to the file's folder"
            )),
        );
        None
    }

    /// `surface NAME [texture N] { triangles }`: a triangle's three points,
    /// each followed or not by its corners' texture coordinates `(s, t)`
    /// on their patch (every triangle or none); those across the whole
    /// surface are derived from the points.
    pub(super) fn surface(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let name = f.word("", &[]);
        // `texture N`, counted from 1 (after the name, which may itself
        // be spelt `texture`).
        let texture = match (f.all().get(1).cloned(), f.all().get(2).cloned()) {
            (None, _) => None,
            (Some(Val::Word(w, _)), Some(Val::Num(n, s))) if w == "texture" => {
                match n.parse::<u16>() {
                    Ok(n) if n >= 1 => Some(n - 1),
                    _ => f.fail(Some(&Val::Num(n, s)), "a texture number from 1".into()),
                }
            }
            (v, _) => f.fail(v.as_ref(), "`texture N` or the block".into()),
        };
        let mesh = self.surface_block(k);
        if let (Some(name), Some((triangles, patch_uvs))) = (name, mesh) {
            let surface_uvs = if patch_uvs.is_empty() {
                Vec::new()
            } else {
                SurfaceMesh::extent_uvs(&triangles)
            };
            self.sys.surfaces.push(SurfaceMesh {
                name,
                triangles,
                patch_uvs,
                surface_uvs,
                texture,
            });
        }
        self.malformed(
            f,
            k,
            "surface NAME [texture N] { (x, y, z) (x, y, z) (x, y, z) [(s, t) (s, t) (s, t)] }",
        );
    }

    /// A surface block's triangles and their corners' texture coordinates
    /// (none, or one triple of `(s, t)` a triangle); `None` when malformed
    /// (reported).
    #[allow(clippy::type_complexity)]
    fn surface_block(&mut self, k: &Keyword) -> Option<(Vec<[[f64; 3]; 3]>, Vec<[[f64; 2]; 3]>)> {
        let vs = vals(&k.lines());
        let numbers = |v: &Val| match v {
            Val::Tuple(parts, _) => parts.iter().map(|p| p.parse().ok()).collect(),
            _ => None,
        };
        let tuples: Vec<Option<Vec<f64>>> = vs.iter().map(numbers).collect();
        let width = |i: usize| tuples.get(i).and_then(|t| t.as_ref().map(Vec::len));
        let (mut triangles, mut uvs) = (Vec::new(), Vec::new());
        let mut i = 0;
        let mut problem = None;
        while i < vs.len() {
            if (i..i + 3).any(|j| width(j) != Some(3)) {
                problem = Some((i..i + 3).find(|&j| width(j) != Some(3)).unwrap_or(i));
                break;
            }
            let p = |j: usize| {
                let t = tuples[j].as_deref().unwrap_or(&[0.0; 3]);
                [t[0], t[1], t[2]]
            };
            triangles.push([p(i), p(i + 1), p(i + 2)]);
            i += 3;
            if width(i) == Some(2) {
                if let Some(bad) = (i..i + 3).find(|&j| width(j) != Some(2)) {
                    problem = Some(bad);
                    break;
                }
                let q = |j: usize| {
                    let t = tuples[j].as_deref().unwrap_or(&[0.0; 2]);
                    [t[0], t[1]]
                };
                uvs.push([q(i), q(i + 1), q(i + 2)]);
                i += 3;
            }
        }
        if let Some(at) = problem {
            let span = vs.get(at).map_or(k.line.clone(), |v| v.span().clone());
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &span,
                "a surface's lines are triangles",
                "not a point `(x, y, z)` of a triangle, or one of its three `(s, t)`",
                "write three points `(x, y, z)` a triangle, then, or not, three `(s, t)`",
            ));
            return None;
        }
        if !uvs.is_empty() && uvs.len() != triangles.len() {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "a surface's triangles all have texture coordinates, or none",
                "some triangles without `(s, t)`",
                "give every triangle its three `(s, t)`, or none",
            ));
            return None;
        }
        Some((triangles, uvs))
    }

    /// `contour ID cross-section|curve closed|open length L { points }`.
    fn contour(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let id = f.number("");
        let role = f.all().get(1).cloned();
        let role = match role {
            Some(Val::Word(w, _)) if w == "cross-section" => Some(ContourRole::CrossSection),
            Some(Val::Word(w, _)) if w == "curve" => Some(ContourRole::Curve),
            v => f.fail(v.as_ref(), "cross-section or curve".into()),
        };
        let closed = match f.all().get(2).cloned() {
            Some(Val::Word(w, _)) if w == "closed" || w == "open" => Some(w == "closed"),
            v => f.fail(v.as_ref(), "closed or open".into()),
        };
        let length = f.number("length");
        let points = self.block_points(k);
        if let (Some(id), Some(role), Some(closed), Some(length), Some(points)) =
            (id, role, closed, length, points)
        {
            self.sys.contours.push(Contour {
                id,
                role,
                points,
                closed,
                length,
            });
        }
        self.malformed(
            f,
            k,
            "contour 1 cross-section closed length 1 { (x, y, z) … }",
        );
    }

    /// `function [NAME] = SAMPLES`: a `.func` file's function may have no
    /// name (`func(1, x)` calls it by number).
    fn function(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let is_eq = |v: &Val| matches!(v, Val::Word(w, _) if w == "=");
        let unnamed = f.all().first().is_some_and(is_eq);
        let name = if unnamed {
            Some(String::new())
        } else {
            f.word("", &[])
        };
        let at = usize::from(!unnamed);
        let eq = f.all().get(at).map(is_eq);
        if eq != Some(true) {
            let v = f.all().get(at).cloned();
            let _: Option<()> = f.fail(v.as_ref(), "`=` after the name".into());
        }
        let samples: Option<Vec<f64>> = (f.all().iter().skip(at + 1))
            .map(|v| match v {
                Val::Num(t, _) => t.parse().ok(),
                _ => None,
            })
            .collect();
        if samples.is_none() {
            let _: Option<()> = f.fail(None, "numbers after `=`".into());
        }
        if let (Some(name), Some(samples), Some(true)) = (name, samples, eq) {
            self.sys.program.functions.push(Function { name, samples });
        }
        self.malformed(f, k, "function NAME = 0 0.5 1");
    }

    /// `tropism (x,y,z) angle A intensity I elasticity E step S [torque|after-step]`.
    fn tropism(&mut self, k: &Keyword) {
        let mut f = Fields::new(k);
        let vector = f.triple("");
        let (angle, intensity) = (f.number("angle"), f.number("intensity"));
        let (elasticity, step) = (f.number("elasticity"), f.number("step"));
        let kind = if f.has("torque") {
            TropismKind::Torque
        } else if f.has("after-step") {
            TropismKind::BendAfterStep
        } else {
            TropismKind::Bend
        };
        if let (Some(vector), Some(angle), Some(intensity), Some(elasticity), Some(step)) =
            (vector, angle, intensity, elasticity, step)
        {
            self.sys.settings.tropisms.push(Tropism {
                vector,
                angle,
                intensity,
                elasticity,
                step,
                kind,
            });
        }
        self.malformed(
            f,
            k,
            "tropism (0, -1, 0) angle 0 intensity 1 elasticity 0.2 step 0 [torque|after-step]",
        );
    }
}

impl Cx<'_> {
    /// `query KIND`, `colour-shift ±N`, `elasticity CHANGE [tropism N]`,
    /// `surface NAME` (`g`: the operation's words, joined where written
    /// without space).
    pub(super) fn named_op(&mut self, g: &[(String, Span)], span: &Span) -> Option<TurtleOp> {
        let word = |k: usize| g.get(k).map_or("", |w| w.0.as_str());
        let op = match word(0) {
            "query" => Some(TurtleOp::Query(match word(1) {
                "position" => QueryKind::Position,
                "heading" => QueryKind::Heading,
                "left" => QueryKind::Left,
                "up" => QueryKind::Up,
                "environment" => QueryKind::Environment,
                _ => return self.bad_op(g, span, "query position|heading|left|up|environment"),
            })),
            "colour-shift" => {
                let (up, by) = match word(1).split_at_checked(1) {
                    Some(("+", n)) => (true, n.parse().ok()),
                    Some(("-", n)) => (false, n.parse().ok()),
                    _ => (true, None),
                };
                by.map(|by| TurtleOp::ShiftColour { by, up })
            }
            "elasticity" => self.elasticity(g),
            _ => {
                let name = word(1);
                let found = (self.sys.surfaces.iter()).position(|s| s.name == name);
                let index = found.or_else(|| name.parse().ok());
                index
                    .and_then(|i| u16::try_from(i).ok())
                    .map(TurtleOp::Surface)
            }
        };
        if op.is_none() {
            let shape = match word(0) {
                "colour-shift" => "colour-shift +1",
                "elasticity" => "elasticity set|increase|decrease|set-or-increase [tropism N]",
                _ => "surface NAME (a `surface NAME { … }` of the file)",
            };
            return self.bad_op(g, span, shape);
        }
        op
    }

    fn elasticity(&mut self, g: &[(String, Span)]) -> Option<TurtleOp> {
        let change = match g.get(1).map(|w| w.0.as_str()) {
            Some("set") => ElasticityChange::Set,
            Some("increase") => ElasticityChange::Increase,
            Some("decrease") => ElasticityChange::Decrease,
            Some("set-or-increase") => ElasticityChange::SetOrIncrease,
            _ => return None,
        };
        let tropism = match g.get(2..) {
            Some([]) | None => None,
            // Counted from 1, as cpfg counts.
            Some([(t, _), (n, _)]) if t == "tropism" => {
                let n: u16 = n.parse().ok().filter(|&n| n >= 1)?;
                Some(n - 1)
            }
            Some(_) => return None,
        };
        Some(TurtleOp::Elasticity { tropism, change })
    }

    fn bad_op(&mut self, g: &[(String, Span)], span: &Span, shape: &str) -> Option<TurtleOp> {
        let name = g.first().map_or("", |w| w.0.as_str());
        self.diags.push(err(
            codes::GFT_BAD_VALUE,
            span,
            format!("malformed `{name}`"),
            "not what this operation takes",
            &format!("write `{shape}`"),
        ));
        None
    }
}

/// The bytes of the file at `path`, refused past the size graftal reads a
/// source to.
fn read_capped(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let cap = crate::source::MAX_SOURCE_BYTES as u64;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(cap + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(std::io::Error::other("the file is too large"));
    }
    Ok(bytes)
}
