//! Binary glTF 2.0 (`.glb`): a JSON chunk describing meshes, materials
//! and nodes, and a binary chunk with the vertices and indices. Each mesh
//! has one primitive per colour; each node places a mesh, so a mesh
//! placed many times is stored once. A textured part has TEXCOORD_0
//! (glTF's: v down from the image's top row), and its material a base
//! colour texture: the image as PNG in the binary chunk, sampled with
//! REPEAT wrapping and the texture's filter, alpha below 0.5 cut out
//! (`MASK`) as cpfg's alpha test does. glTF's base colour texture
//! multiplies the base colour: cpfg's modulate mode; decal and blend
//! textures are written as modulated too.

use super::{Finish, Mesh, Part, Scene};
use serde_json::{json, Value};

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;
const NEAREST: u32 = 9728;
const LINEAR: u32 = 9729;
const REPEAT: u32 = 10497;

/// The binary chunk and the views and accessors into it.
#[derive(Default)]
struct Buffers {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffers {
    /// Appends `bytes` as a view (4-byte aligned); its index.
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": self.bin.len(),
            "byteLength": bytes.len(),
            "target": target,
        }));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    /// Appends `bytes` as a view with no target (an image); its index.
    fn image_view(&mut self, bytes: &[u8]) -> usize {
        let view = self.view(bytes, 0);
        if let Some(v) = self.views[view].as_object_mut() {
            v.remove("target");
        }
        view
    }

    /// A float accessor of `count` elements of type `kind` over the
    /// components `values`; its index.
    fn floats(&mut self, values: &[f32], count: usize, kind: &str) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": count,
            "type": kind,
        }));
        self.accessors.len() - 1
    }

    /// A VEC2 float accessor of texture coordinates, v turned to run
    /// down the image as glTF's do; its index.
    fn texcoords(&mut self, uvs: &[[f64; 2]]) -> usize {
        let f: Vec<f32> = uvs
            .iter()
            .flat_map(|t| [t[0] as f32, (1.0 - t[1]) as f32])
            .collect();
        self.floats(&f, uvs.len(), "VEC2")
    }

    /// A VEC3 float accessor over `v`, with its bounds; its index.
    fn vec3(&mut self, v: &[[f64; 3]]) -> usize {
        let f: Vec<[f32; 3]> = v.iter().map(|p| p.map(|x| x as f32)).collect();
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &f {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let flat: Vec<f32> = f.iter().flatten().copied().collect();
        let k = self.floats(&flat, f.len(), "VEC3");
        self.accessors[k]["min"] = json!(lo);
        self.accessors[k]["max"] = json!(hi);
        k
    }

    /// A SCALAR index accessor over `triangles`, in 16 bits when
    /// `vertices` allow; its index.
    fn indices(&mut self, triangles: &[[u32; 3]], vertices: usize) -> usize {
        let flat = triangles.iter().flatten();
        let (bytes, kind): (Vec<u8>, u32) = if vertices <= usize::from(u16::MAX) {
            let b = flat.flat_map(|&i| (i as u16).to_le_bytes()).collect();
            (b, UNSIGNED_SHORT)
        } else {
            (flat.flat_map(|i| i.to_le_bytes()).collect(), UNSIGNED_INT)
        };
        let view = self.view(&bytes, ELEMENT_ARRAY_BUFFER);
        let max = triangles.iter().flatten().max().copied().unwrap_or(0);
        let min = triangles.iter().flatten().min().copied().unwrap_or(0);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": kind,
            "count": triangles.len() * 3,
            "type": "SCALAR",
            "min": [min],
            "max": [max],
        }));
        self.accessors.len() - 1
    }

    /// The primitive of `part`, of material `material`.
    fn primitive(&mut self, part: &Part, material: usize) -> Value {
        let position = self.vec3(&part.positions);
        let normal = self.vec3(&part.normals);
        let indices = self.indices(&part.triangles, part.positions.len());
        let mut attributes = json!({ "POSITION": position, "NORMAL": normal });
        if part.finish.texture.is_some() && part.uvs.len() == part.positions.len() {
            attributes["TEXCOORD_0"] = json!(self.texcoords(&part.uvs));
        }
        json!({
            "attributes": attributes,
            "indices": indices,
            "material": material,
        })
    }
}

/// An sRGB channel (0..=255) as glTF's linear colour factors take it.
fn linear(c: u8) -> f64 {
    linear_of(f64::from(c) / 255.0)
}

/// An sRGB channel (0..=1) as glTF's linear colour factors take it.
fn linear_of(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// The glTF material of a finish. A plain colour is a rough diffuse
/// surface. A cpfg material keeps its diffuse colour (with alpha 1 −
/// transparency, blended when below 1) and its emission; its shininess
/// (a Phong exponent `Ns`, 0..=128) becomes roughness by the usual
/// Blinn-Phong-to-GGX match, roughness = √(2 / (Ns + 2)): 0 gives 1,
/// 128 gives 0.12. glTF's metallic-roughness model has no place for
/// ambient or a specular colour; dielectric (metallic 0) keeps its
/// highlight white.
fn material(f: &Finish) -> Value {
    let name = f.name();
    let Some((_, m)) = f.material else {
        let (r, g, b) = f.colour;
        return json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": [linear(r), linear(g), linear(b), 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 0.8,
            },
            "doubleSided": true,
        });
    };
    let rgb = |c: [f32; 3]| c.map(|x| linear_of(f64::from(x)));
    let [r, g, b] = rgb(m.diffuse);
    let alpha = 1.0 - f64::from(m.transparency).clamp(0.0, 1.0);
    let shininess = f64::from(m.shininess).clamp(0.0, 128.0);
    let mut v = json!({
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": [r, g, b, alpha],
            "metallicFactor": 0.0,
            "roughnessFactor": (2.0 / (shininess + 2.0)).sqrt(),
        },
        "doubleSided": true,
    });
    if m.emission.iter().any(|&x| x > 0.0) {
        v["emissiveFactor"] = json!(rgb(m.emission));
    }
    if alpha < 1.0 {
        v["alphaMode"] = json!("BLEND");
    }
    v
}

/// The `.glb` bytes of `scene`. Meshes without triangles, and the nodes
/// placing them, are left out (glTF wants a primitive in every mesh).
pub fn glb(scene: &Scene) -> Vec<u8> {
    let finishes = scene.materials();
    let mut materials: Vec<Value> = finishes.iter().map(material).collect();
    let mut buffers = Buffers::default();
    let textures = Textures::of(scene, &finishes, &mut materials, &mut buffers);
    let mut meshes: Vec<Value> = Vec::new();
    // Index in the file of each scene mesh, when it has triangles.
    let mut index: Vec<Option<usize>> = Vec::with_capacity(scene.meshes.len());
    for m in &scene.meshes {
        index.push(mesh(m, &finishes, &mut buffers).map(|v| {
            meshes.push(v);
            meshes.len() - 1
        }));
    }
    let nodes: Vec<Value> = scene
        .nodes
        .iter()
        .filter_map(|n| {
            let mesh = index[n.mesh]?;
            let p = &n.place;
            let mut node = json!({ "mesh": mesh });
            if p.translation != [0.0; 3] {
                node["translation"] = json!(p.translation);
            }
            if p.rotation != super::Transform::IDENTITY.rotation {
                node["rotation"] = json!(p.quaternion());
            }
            if p.scale != 1.0 {
                node["scale"] = json!([p.scale, p.scale, p.scale]);
            }
            Some(node)
        })
        .collect();
    let mut doc = json!({
        "asset": { "version": "2.0", "generator": concat!("graftal ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
    });
    if !meshes.is_empty() {
        doc["meshes"] = json!(meshes);
        doc["materials"] = json!(materials);
        doc["accessors"] = json!(buffers.accessors);
        doc["bufferViews"] = json!(buffers.views);
        doc["buffers"] = json!([{ "byteLength": buffers.bin.len() }]);
        if !textures.textures.is_empty() {
            doc["images"] = json!(textures.images);
            doc["samplers"] = json!(textures.samplers);
            doc["textures"] = json!(textures.textures);
        }
    }
    container(&doc.to_string(), &buffers.bin)
}

/// The glTF mesh of `m`, its parts' material indices among `finishes`;
/// `None` when it has no triangles.
fn mesh(m: &Mesh, finishes: &[Finish], buffers: &mut Buffers) -> Option<Value> {
    let primitives: Vec<Value> = m
        .parts
        .iter()
        .filter(|p| !p.triangles.is_empty())
        .map(|p| {
            let material = finishes
                .iter()
                .position(|f| f.key() == p.finish.key())
                .unwrap_or(0);
            buffers.primitive(p, material)
        })
        .collect();
    (!primitives.is_empty()).then(|| json!({ "primitives": primitives }))
}

/// The GLB container: header, JSON chunk (padded with spaces), binary
/// chunk (padded with zeros; left out when empty).
fn container(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json.as_bytes());
    out.resize(out.len() + pad(json.len()), b' ');
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_len as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(bin);
        out.resize(out.len() + pad(bin.len()), 0);
    }
    out
}

/// The images, samplers and textures of a scene's textured materials.
#[derive(Default)]
struct Textures {
    images: Vec<Value>,
    samplers: Vec<Value>,
    textures: Vec<Value>,
}

impl Textures {
    /// Each texture a finish wears, once: its image (PNG) in `buffers`,
    /// a sampler, and the finish's material given it as base colour
    /// texture. A texture whose image was not read is left out.
    fn of(
        scene: &Scene,
        finishes: &[Finish],
        materials: &mut [Value],
        buffers: &mut Buffers,
    ) -> Textures {
        let mut out = Textures::default();
        let Some(all) = scene
            .meshes
            .iter()
            .map(|m| &m.textures)
            .find(|t| !t.is_empty())
        else {
            return out;
        };
        // The glTF texture of each look texture already written.
        let mut written: Vec<(u16, usize)> = Vec::new();
        for (f, m) in finishes.iter().zip(materials.iter_mut()) {
            let Some(t) = f.texture else { continue };
            let index = match written.iter().find(|w| w.0 == t) {
                Some(w) => w.1,
                None => {
                    let Some(texture) = all.get(usize::from(t)) else {
                        continue;
                    };
                    let Some(png) = texture.image.as_deref().and_then(super::texture::png) else {
                        continue;
                    };
                    let view = buffers.image_view(&png);
                    out.images
                        .push(json!({ "bufferView": view, "mimeType": "image/png" }));
                    let filter = match texture.filter {
                        crate::ir::texture::Filter::Nearest => NEAREST,
                        crate::ir::texture::Filter::Linear => LINEAR,
                    };
                    out.samplers.push(json!({
                        "magFilter": filter,
                        "minFilter": filter,
                        "wrapS": REPEAT,
                        "wrapT": REPEAT,
                    }));
                    let k = out.textures.len();
                    out.textures.push(json!({ "sampler": k, "source": k }));
                    written.push((t, k));
                    k
                }
            };
            m["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": index });
            if m.get("alphaMode").is_none() {
                m["alphaMode"] = json!("MASK");
                m["alphaCutoff"] = json!(0.5);
            }
        }
        out
    }
}
