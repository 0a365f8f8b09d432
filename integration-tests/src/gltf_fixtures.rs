//! glTF test fixtures written by the tests themselves: a small document builder (JSON
//! through `gltf-json`, one binary buffer) writing `.glb` or `.gltf` with a `data:` URI,
//! and the animated scenes the glTF tests render (cubes with LINEAR, STEP and CUBICSPLINE
//! channels, a morph-target quad, a two-bone skinned strip, an animated camera).

use std::path::Path;

use base64::Engine;
use serde_json::{Value, json};

/// A glTF document under construction with its binary buffer.
#[derive(Debug, Clone)]
pub struct Doc {
    /// The document's JSON (the buffer is added when written).
    pub json: Value,
    /// The binary buffer.
    pub bin: Vec<u8>,
}

impl Default for Doc {
    fn default() -> Self {
        Doc::new()
    }
}

impl Doc {
    /// An empty document with one scene.
    pub fn new() -> Doc {
        Doc {
            json: json!({ "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [] }] }),
            bin: Vec::new(),
        }
    }

    /// Appends `value` to the top-level array `key`; returns its index.
    pub fn push(&mut self, key: &str, value: Value) -> usize {
        let arr = self.json[key].as_array_mut();
        match arr {
            Some(a) => {
                a.push(value);
                a.len() - 1
            }
            None => {
                self.json[key] = json!([value]);
                0
            }
        }
    }

    /// Adds node `n` to the scene's roots.
    pub fn root(&mut self, n: usize) {
        if let Some(a) = self.json["scenes"][0]["nodes"].as_array_mut() {
            a.push(json!(n));
        }
    }

    fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.push(
            "bufferViews",
            json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() }),
        )
    }

    /// An accessor of f32 elements of glTF type `ty` (`SCALAR`, `VEC3`, ...).
    pub fn floats(&mut self, data: &[f32], ty: &str) -> usize {
        let n = match ty {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            "VEC4" => 4,
            _ => 16,
        };
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let mut acc = json!({ "bufferView": view, "componentType": 5126, "count": data.len() / n, "type": ty });
        if ty == "VEC3" || ty == "SCALAR" {
            let (mut lo, mut hi) = (vec![f32::MAX; n], vec![f32::MIN; n]);
            for c in data.chunks(n) {
                for k in 0..n {
                    lo[k] = lo[k].min(c[k]);
                    hi[k] = hi[k].max(c[k]);
                }
            }
            acc["min"] = json!(lo);
            acc["max"] = json!(hi);
        }
        self.push("accessors", acc)
    }

    /// An accessor of u16 scalars (indices) or of `VEC4` (joints).
    pub fn u16s(&mut self, data: &[u16], ty: &str) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let n = if ty == "VEC4" { 4 } else { 1 };
        self.push(
            "accessors",
            json!({ "bufferView": view, "componentType": 5123, "count": data.len() / n, "type": ty }),
        )
    }

    /// An animation sampler's input and output accessors added to animation 0 as a channel
    /// on `node`'s `path` (`translation`, `rotation`, `scale`, `weights`).
    pub fn channel(
        &mut self,
        node: usize,
        path: &str,
        interp: &str,
        times: &[f32],
        values: &[f32],
    ) {
        let ty = match path {
            "rotation" => "VEC4",
            "weights" => "SCALAR",
            _ => "VEC3",
        };
        let input = self.floats(times, "SCALAR");
        let output = self.floats(values, ty);
        if self.json["animations"].as_array().is_none() {
            self.json["animations"] = json!([{ "name": "take", "channels": [], "samplers": [] }]);
        }
        let anim = &mut self.json["animations"][0];
        let s = anim["samplers"].as_array().map_or(0, Vec::len);
        if let Some(a) = anim["samplers"].as_array_mut() {
            a.push(json!({ "input": input, "output": output, "interpolation": interp }));
        }
        if let Some(a) = anim["channels"].as_array_mut() {
            a.push(json!({ "sampler": s, "target": { "node": node, "path": path } }));
        }
    }

    /// The final JSON with buffer 0 (`uri` for `.gltf`), checked by parsing it as a
    /// `gltf_json::Root` and written by gltf-json's serialiser.
    fn finish(&self, uri: Option<String>) -> Vec<u8> {
        let mut json = self.json.clone();
        let mut buffer = json!({ "byteLength": self.bin.len() });
        if let Some(u) = uri {
            buffer["uri"] = json!(u);
        }
        json["buffers"] = json!([buffer]);
        let root: gltf_json::Root = serde_json::from_value(json).expect("fixture is valid glTF");
        gltf_json::serialize::to_vec(&root).expect("serialise fixture")
    }

    /// Writes a `.gltf` with the buffer in a base64 `data:` URI.
    pub fn write_gltf(&self, path: &Path) {
        let b64 = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        let text = self.finish(Some(format!("data:application/octet-stream;base64,{b64}")));
        std::fs::write(path, text).expect("write .gltf");
    }

    /// The bytes of a `.glb`: header, JSON chunk, BIN chunk.
    pub fn glb_bytes(&self) -> Vec<u8> {
        let mut json = self.finish(None);
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }

    /// Writes a `.glb`.
    pub fn write_glb(&self, path: &Path) {
        std::fs::write(path, self.glb_bytes()).expect("write .glb");
    }

    /// A perspective camera node at `eye` looking down -Z (yfov 0.7 rad, aspect 4:3,
    /// znear 0.5, zfar 50), added to the scene; returns the node.
    pub fn camera(&mut self, name: &str, eye: [f32; 3]) -> usize {
        let c = self.push(
            "cameras",
            json!({ "type": "perspective", "name": name,
                    "perspective": { "yfov": 0.7, "aspectRatio": 1.3333334, "znear": 0.5, "zfar": 50.0 } }),
        );
        let n = self.push(
            "nodes",
            json!({ "name": name, "camera": c, "translation": eye }),
        );
        self.root(n);
        n
    }

    /// A mesh of non-indexed triangles `positions` (3 per triangle) with one material of
    /// colour `rgba`; returns the mesh.
    pub fn mesh(&mut self, positions: &[f32], rgba: [f32; 4]) -> usize {
        let p = self.floats(positions, "VEC3");
        let m = self.push(
            "materials",
            json!({ "pbrMetallicRoughness": { "baseColorFactor": rgba }, "alphaMode": "OPAQUE" }),
        );
        self.push(
            "meshes",
            json!({ "primitives": [{ "attributes": { "POSITION": p }, "material": m }] }),
        )
    }
}

/// The 36 corners of the 12 triangles of an axis-aligned cube of half-size `h`
/// (counter-clockwise seen from outside).
pub fn cube_triangles(h: f32) -> Vec<f32> {
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    let mut out = Vec::new();
    for (n, u, v) in faces {
        let c =
            |a: f32, b: f32| -> [f32; 3] { [0, 1, 2].map(|k| h * (n[k] + a * u[k] + b * v[k])) };
        for p in [
            c(-1.0, -1.0),
            c(1.0, -1.0),
            c(1.0, 1.0),
            c(-1.0, -1.0),
            c(1.0, 1.0),
            c(-1.0, 1.0),
        ] {
            out.extend_from_slice(&p);
        }
    }
    out
}

/// The quaternion (x, y, z, w) of `deg` degrees about unit `axis`.
pub fn quat(axis: [f32; 3], deg: f32) -> [f32; 4] {
    let h = deg.to_radians() * 0.5;
    [
        axis[0] * h.sin(),
        axis[1] * h.sin(),
        axis[2] * h.sin(),
        h.cos(),
    ]
}

/// Three cubes over a 1 s animation, camera at (0, 0, 8): "linear" translates and turns
/// 90° about Y (LINEAR), "step" jumps right at 0.5 s (STEP), "cubic" turns about Z and
/// rises along a CUBICSPLINE curve.
pub fn animated_cubes() -> Doc {
    let mut d = Doc::new();
    d.camera("cam", [0.0, 0.0, 8.0]);
    let cube = d.mesh(&cube_triangles(0.6), [0.9, 0.3, 0.2, 1.0]);
    let names = ["linear", "step", "cubic"];
    let at = [[-2.2, 1.0, 0.0], [0.0, 0.0, 0.0], [2.2, -1.0, 0.0]];
    let mut nodes = Vec::new();
    for (name, t) in names.iter().zip(at) {
        let n = d.push(
            "nodes",
            json!({ "name": name, "mesh": cube, "translation": t }),
        );
        d.root(n);
        nodes.push(n);
    }
    let times = [0.0, 0.5, 1.0];
    d.channel(
        nodes[0],
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[-2.6, 1.0, 0.0, -1.8, 1.2, 0.0],
    );
    let q: Vec<f32> = [0.0, 45.0, 90.0]
        .iter()
        .flat_map(|&a| quat([0.0, 1.0, 0.0], a))
        .collect();
    d.channel(nodes[0], "rotation", "LINEAR", &times, &q);
    d.channel(
        nodes[1],
        "translation",
        "STEP",
        &times,
        &[-0.4, 0.0, 0.0, 0.4, 0.0, 0.0, 0.4, 0.3, 0.0],
    );
    let mut cubic = Vec::new();
    for (a, tan) in [(0.0f32, 0.0f32), (40.0, 60.0), (70.0, 0.0)] {
        let r = quat([0.0, 0.0, 1.0], a);
        let dr = [
            0.0,
            0.0,
            0.5 * tan.to_radians() * r[3],
            -0.5 * tan.to_radians() * r[2],
        ];
        cubic.extend(dr);
        cubic.extend(r);
        cubic.extend(dr);
    }
    d.channel(nodes[2], "rotation", "CUBICSPLINE", &times, &cubic);
    let mut pos = Vec::new();
    for (y, dy) in [(-1.2f32, 0.0f32), (-0.8, 1.5), (-0.9, 0.0)] {
        pos.extend([0.0, dy, 0.0, 2.2, y, 0.0, 0.0, dy, 0.0]);
    }
    d.channel(nodes[2], "translation", "CUBICSPLINE", &times, &pos);
    d
}

/// The corners of the quad of [`morph_quad`]: two triangles over [-1, 1] x [-0.8, 0.8].
pub const QUAD: [f32; 18] = [
    -1.0, -0.8, 0.0, 1.0, -0.8, 0.0, 1.0, 0.8, 0.0, -1.0, -0.8, 0.0, 1.0, 0.8, 0.0, -1.0, 0.8, 0.0,
];

/// A quad whose morph target slides its top edge 1.2 right (weight 0 -> 1 -> 0.5 at 0,
/// 0.5, 1 s, LINEAR), camera at (0, 0, 5).
pub fn morph_quad() -> Doc {
    let mut d = Doc::new();
    d.camera("cam", [0.0, 0.0, 5.0]);
    let p = d.floats(&QUAD, "VEC3");
    let mut delta = [0.0f32; 18];
    for k in [2, 4, 5] {
        delta[3 * k] = 1.2;
    }
    let t = d.floats(&delta, "VEC3");
    let m = d.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.7, 0.9, 1.0] } }),
    );
    let mesh = d.push(
        "meshes",
        json!({ "primitives": [{ "attributes": { "POSITION": p }, "material": m,
                                 "targets": [{ "POSITION": t }] }], "weights": [0.0] }),
    );
    let n = d.push("nodes", json!({ "name": "quad", "mesh": mesh }));
    d.root(n);
    d.channel(n, "weights", "LINEAR", &[0.0, 0.5, 1.0], &[0.0, 1.0, 0.5]);
    d
}

/// A strip along X (0 to 2, height 0.5) skinned to two bones: the second, at x = 1,
/// turns 70° about Z over 1 s (LINEAR); camera at (1, 0.5, 5).
pub fn skinned_strip() -> Doc {
    let mut d = Doc::new();
    d.camera("cam", [1.0, 0.5, 5.0]);
    let xs = [0.0f32, 1.0, 2.0];
    let mut pos = Vec::new();
    for x in xs {
        pos.extend([x, -0.25, 0.0, x, 0.25, 0.0]);
    }
    let p = d.floats(&pos, "VEC3");
    let idx = d.u16s(&[0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3], "SCALAR");
    let joints = d.u16s(&[0u16, 1, 0, 0].repeat(6), "VEC4");
    let w: Vec<f32> = [[1.0f32, 0.0], [0.5, 0.5], [0.0, 1.0]]
        .iter()
        .flat_map(|[a, b]| [*a, *b, 0.0, 0.0, *a, *b, 0.0, 0.0])
        .collect();
    let weights = d.floats(&w, "VEC4");
    let m = d.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.9, 0.8, 0.2, 1.0] } }),
    );
    let mesh = d.push(
        "meshes",
        json!({ "primitives": [{ "attributes": { "POSITION": p, "JOINTS_0": joints, "WEIGHTS_0": weights },
                                 "indices": idx, "material": m }] }),
    );
    let j1 = d.push(
        "nodes",
        json!({ "name": "bone1", "translation": [1.0, 0.0, 0.0] }),
    );
    let j0 = d.push("nodes", json!({ "name": "bone0", "children": [j1] }));
    let mut ibm = vec![0.0f32; 32];
    for k in 0..4 {
        ibm[5 * k] = 1.0;
        ibm[16 + 5 * k] = 1.0;
    }
    ibm[16 + 12] = -1.0;
    let inv = d.floats(&ibm, "MAT4");
    let skin = d.push(
        "skins",
        json!({ "joints": [j0, j1], "inverseBindMatrices": inv }),
    );
    let n = d.push(
        "nodes",
        json!({ "name": "strip", "mesh": mesh, "skin": skin }),
    );
    d.root(j0);
    d.root(n);
    let q: Vec<f32> = [0.0, 70.0]
        .iter()
        .flat_map(|&a| quat([0.0, 0.0, 1.0], a))
        .collect();
    d.channel(j1, "rotation", "LINEAR", &[0.0, 1.0], &q);
    d
}

/// A static cube seen from a camera that slides from x = -1 to 1 and turns 20° about Y
/// over 1 s (LINEAR).
pub fn animated_camera() -> Doc {
    let mut d = Doc::new();
    let cam = d.camera("cam", [-1.0, 0.0, 6.0]);
    let cube = d.mesh(&cube_triangles(0.8), [0.3, 0.9, 0.4, 1.0]);
    let n = d.push("nodes", json!({ "name": "cube", "mesh": cube, "rotation": quat([1.0, 1.0, 0.0].map(|x: f32| x / 2f32.sqrt()), 30.0) }));
    d.root(n);
    d.channel(
        cam,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[-1.0, 0.0, 6.0, 1.0, 0.0, 6.0],
    );
    let q: Vec<f32> = [-10.0, 10.0]
        .iter()
        .flat_map(|&a| quat([0.0, 1.0, 0.0], a))
        .collect();
    d.channel(cam, "rotation", "LINEAR", &[0.0, 1.0], &q);
    d
}
