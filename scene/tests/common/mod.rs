//! A tiny glTF writer for tests: builds the JSON and one binary buffer, then writes the asset
//! as `.gltf` with an embedded data URI, `.gltf` with an external `.bin`, or `.glb`.

pub mod deformed;

use std::path::{Path, PathBuf};

use base64::Engine;
use serde_json::{json, Value};

/// glTF component type codes.
pub const BYTE: u32 = 5120;
pub const UNSIGNED_BYTE: u32 = 5121;
pub const SHORT: u32 = 5122;
pub const UNSIGNED_SHORT: u32 = 5123;
pub const UNSIGNED_INT: u32 = 5125;
pub const FLOAT: u32 = 5126;

/// A glTF document under construction. Top-level arrays are created on first push.
pub struct Gltf {
    pub json: Value,
    pub bin: Vec<u8>,
}

impl Default for Gltf {
    fn default() -> Self {
        Gltf {
            json: json!({ "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [] }] }),
            bin: Vec::new(),
        }
    }
}

impl Gltf {
    /// Appends `value` to the top-level array `key`, returning its index.
    pub fn push(&mut self, key: &str, value: Value) -> usize {
        let array = self.json[key]
            .as_array_mut()
            .map(std::mem::take)
            .unwrap_or_default();
        self.json[key] = Value::Array(array);
        let array = self.json[key].as_array_mut().unwrap();
        array.push(value);
        array.len() - 1
    }

    /// Adds a node to the scene's root list.
    pub fn root(&mut self, node: Value) -> usize {
        let index = self.push("nodes", node);
        self.json["scenes"][0]["nodes"]
            .as_array_mut()
            .unwrap()
            .push(json!(index));
        index
    }

    /// Appends raw bytes as a buffer view (4-byte aligned), returning the view index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.push(
            "bufferViews",
            json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() }),
        )
    }

    /// An accessor over `bytes` (a new view). VEC3 accessors get placeholder min/max: glTF
    /// validation requires them on POSITION, the loader never reads them.
    pub fn accessor(
        &mut self,
        bytes: &[u8],
        component: u32,
        count: usize,
        type_: &str,
        normalized: bool,
    ) -> usize {
        let view = self.view(bytes);
        let mut accessor = json!({ "bufferView": view, "componentType": component, "count": count, "type": type_ });
        if normalized {
            accessor["normalized"] = json!(true);
        }
        if type_ == "VEC3" {
            accessor["min"] = json!([-1e6, -1e6, -1e6]);
            accessor["max"] = json!([1e6, 1e6, 1e6]);
        }
        self.push("accessors", accessor)
    }

    pub fn floats<const N: usize>(&mut self, values: &[[f32; N]]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let type_ = if N == 1 {
            "SCALAR".to_owned()
        } else {
            format!("VEC{N}")
        };
        self.accessor(&bytes, FLOAT, values.len(), &type_, false)
    }

    pub fn indices_u16(&mut self, indices: &[u16]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.accessor(&bytes, UNSIGNED_SHORT, indices.len(), "SCALAR", false)
    }

    pub fn indices_u32(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.accessor(&bytes, UNSIGNED_INT, indices.len(), "SCALAR", false)
    }

    /// A mesh with one primitive `{ attributes, ...extra }` placed by a root node; returns the
    /// mesh index.
    pub fn mesh(&mut self, name: &str, primitive: Value) -> usize {
        let mesh = self.push("meshes", json!({ "name": name, "primitives": [primitive] }));
        self.root(json!({ "mesh": mesh }));
        mesh
    }

    /// A root-placed triangle (0,0,0), (1,0,0), (0,1,0) without normals, using `material`.
    pub fn triangle(&mut self, material: Option<usize>) -> usize {
        let positions = self.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let mut primitive = json!({ "attributes": { "POSITION": positions } });
        if let Some(material) = material {
            primitive["material"] = json!(material);
        }
        self.mesh("triangle", primitive)
    }

    /// An image of `width` x `height` RGBA8 texels `rgba8`, written as a PNG into a buffer
    /// view; returns the image index.
    pub fn png_image(&mut self, width: u32, height: u32, rgba8: &[u8]) -> usize {
        let image = image::RgbaImage::from_raw(width, height, rgba8.to_vec()).unwrap();
        let mut png = Vec::new();
        image
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let view = self.view(&png);
        self.push(
            "images",
            json!({ "bufferView": view, "mimeType": "image/png" }),
        )
    }

    /// A root-placed triangle whose material ("painted") has the PNG `png`, in a buffer
    /// view, as its base color texture; returns the mesh index.
    pub fn textured_triangle(&mut self, png: &[u8]) -> usize {
        let view = self.view(png);
        let image = self.push(
            "images",
            json!({ "bufferView": view, "mimeType": "image/png" }),
        );
        let texture = self.push("textures", json!({ "source": image }));
        let material = self.push(
            "materials",
            json!({ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": texture } } }),
        );
        self.triangle(Some(material))
    }

    /// An animation `name` of one channel driving `path` ("translation", "rotation",
    /// "scale") of `node` with an `interpolation` sampler over key `times` and FLOAT
    /// `values` (three per key for CUBICSPLINE); returns the animation index.
    pub fn animation<const N: usize>(
        &mut self,
        name: &str,
        node: usize,
        path: &str,
        interpolation: &str,
        times: &[f32],
        values: &[[f32; N]],
    ) -> usize {
        let times = times.iter().map(|&t| [t]).collect::<Vec<_>>();
        let input = self.floats(&times);
        let output = self.floats(values);
        self.push(
            "animations",
            json!({
                "name": name,
                "channels": [{ "sampler": 0, "target": { "node": node, "path": path } }],
                "samplers": [{ "input": input, "output": output, "interpolation": interpolation }],
            }),
        )
    }

    /// The JSON with `buffers[0]` pointing at `uri` (or at the GLB chunk when `None`).
    fn document(&self, uri: Option<String>) -> Value {
        let mut json = self.json.clone();
        if !self.bin.is_empty() {
            let mut buffer = json!({ "byteLength": self.bin.len() });
            if let Some(uri) = uri {
                buffer["uri"] = json!(uri);
            }
            json["buffers"] = json!([buffer]);
        }
        json
    }

    /// `.gltf` with the buffer as a base64 data URI.
    pub fn write_embedded(&self, path: &Path) {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        let json = self.document(Some(format!("data:application/octet-stream;base64,{data}")));
        std::fs::write(path, serde_json::to_vec_pretty(&json).unwrap()).unwrap();
    }

    /// `.gltf` plus the buffer in `bin_name` next to it (`uri` is how the JSON spells it).
    pub fn write_external(&self, path: &Path, bin_name: &str, uri: &str) {
        std::fs::write(path.with_file_name(bin_name), &self.bin).unwrap();
        let json = self.document(Some(uri.to_owned()));
        std::fs::write(path, serde_json::to_vec_pretty(&json).unwrap()).unwrap();
    }

    /// `.glb`: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros.
    pub fn write_glb(&self, path: &Path) {
        let mut json = serde_json::to_vec(&self.document(None)).unwrap();
        json.resize(json.len().next_multiple_of(4), b' ');
        let mut bin = self.bin.clone();
        bin.resize(bin.len().next_multiple_of(4), 0);
        let mut glb = Vec::new();
        let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2u32.to_le_bytes());
        glb.extend_from_slice(&(total as u32).to_le_bytes());
        glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&json);
        if !bin.is_empty() {
            glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
            glb.extend_from_slice(b"BIN\0");
            glb.extend_from_slice(&bin);
        }
        std::fs::write(path, glb).unwrap();
    }
}

/// A fresh, empty directory for one test's files.
pub fn temp_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("scene-tests")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The committed fixture `name` under `tests/fixtures/`.
pub fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}
