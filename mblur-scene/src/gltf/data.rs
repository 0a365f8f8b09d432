//! The bytes of a glTF file: its buffers (the GLB binary chunk, `data:` URIs in base64 and
//! files relative to the glTF file) and bounds-checked accessor reads. Every offset, stride
//! and count is checked against the buffer before anything is allocated or read, so a
//! hostile file gives an error naming the accessor, never a panic or an oversized
//! allocation.

use std::path::Path;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::{Accessor, Document};
use base64::Engine;

use crate::error::{Error, Result};

/// Most elements one accessor may hold (2^26: 64 M, enough for 21 M triangles' indices).
pub const MAX_ACCESSOR_COUNT: usize = 1 << 26;

/// Largest external buffer file read, in bytes (1 GiB, as mesh files).
pub const MAX_BUFFER_BYTES: u64 = crate::input::MAX_MESH_BYTES;

/// The decoded buffers of a document, by buffer index.
#[derive(Debug, Clone, Default)]
pub struct Buffers {
    data: Vec<Vec<u8>>,
}

/// Decodes a `data:` URI (base64 payload) or returns `None` for another URI.
pub fn data_uri(uri: &str) -> Option<std::result::Result<Vec<u8>, String>> {
    let rest = uri.strip_prefix("data:")?;
    let Some((head, payload)) = rest.split_once(',') else {
        return Some(Err("a data: URI without a `,`".into()));
    };
    if !head.ends_with(";base64") {
        return Some(Err(format!(
            "data: URIs must be base64 (`;base64,`), got `data:{head},...`"
        )));
    }
    Some(
        base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| format!("invalid base64 in a data: URI: {e}")),
    )
}

/// The file a relative URI names (percent-escapes of the path decoded), refusing
/// absolute paths and other schemes.
pub fn relative_file(base: &Path, uri: &str) -> std::result::Result<std::path::PathBuf, String> {
    if uri.contains("://") || uri.starts_with('/') || uri.contains(':') {
        return Err(format!(
            "URI `{uri}` is not a relative file path (only data: URIs and paths relative to \
             the glTF file are read)"
        ));
    }
    let mut out = Vec::with_capacity(uri.len());
    let bytes = uri.as_bytes();
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        let hex = bytes.get(i + 1..i + 3).and_then(|h| {
            std::str::from_utf8(h)
                .ok()
                .and_then(|h| u8::from_str_radix(h, 16).ok())
        });
        match (b, hex) {
            (b'%', Some(v)) => {
                out.push(v);
                i += 3;
            }
            _ => {
                out.push(b);
                i += 1;
            }
        }
    }
    let decoded = String::from_utf8(out).map_err(|_| format!("URI `{uri}` is not UTF-8"))?;
    Ok(base.join(decoded))
}

impl Buffers {
    /// Loads every buffer of `doc`: the GLB binary chunk `blob`, data URIs and relative
    /// files (resolved against `base`). `file` names the glTF file in errors.
    pub fn load(doc: &Document, blob: Option<Vec<u8>>, file: &Path, base: &Path) -> Result<Self> {
        let mut blob = blob;
        let mut data = Vec::new();
        for buffer in doc.buffers() {
            let i = buffer.index();
            let bytes = match buffer.source() {
                ::gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                    Error::format(
                        file,
                        format!("buffers[{i}] refers to the GLB binary chunk, which is missing"),
                    )
                })?,
                ::gltf::buffer::Source::Uri(uri) => match data_uri(uri) {
                    Some(r) => r.map_err(|m| Error::format(file, format!("buffers[{i}]: {m}")))?,
                    None => {
                        let path = relative_file(base, uri)
                            .map_err(|m| Error::format(file, format!("buffers[{i}]: {m}")))?;
                        crate::input::read_bounded(&path, MAX_BUFFER_BYTES, "glTF buffer")?
                    }
                },
            };
            if bytes.len() < buffer.length() {
                return Err(Error::format(
                    file,
                    format!(
                        "buffers[{i}] declares {} bytes but holds {}",
                        buffer.length(),
                        bytes.len()
                    ),
                ));
            }
            data.push(bytes);
        }
        Ok(Buffers { data })
    }

    /// The bytes of buffer view `view`, checked against its buffer.
    pub fn view<'a>(
        &'a self,
        view: &::gltf::buffer::View<'_>,
    ) -> std::result::Result<&'a [u8], String> {
        let buffer = self
            .data
            .get(view.buffer().index())
            .ok_or_else(|| format!("bufferViews[{}]: buffer missing", view.index()))?;
        let end = view.offset().checked_add(view.length());
        end.and_then(|end| buffer.get(view.offset()..end))
            .ok_or_else(|| {
                format!(
                    "bufferViews[{}] (offset {}, length {}) runs past the end of buffers[{}] ({} bytes)",
                    view.index(),
                    view.offset(),
                    view.length(),
                    view.buffer().index(),
                    buffer.len()
                )
            })
    }
}

/// Number of components of an accessor element.
fn components(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// Bytes of one component.
fn component_bytes(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// One component as f64: floats as stored, integers normalised to \[0, 1\] or \[-1, 1\]
/// when `normalized` (glTF's rule), else as integers.
fn component(t: DataType, b: &[u8], normalized: bool) -> f64 {
    let raw = |n: usize| -> [u8; 4] {
        let mut a = [0u8; 4];
        for (d, s) in a.iter_mut().zip(b.iter().take(n)) {
            *d = *s;
        }
        a
    };
    let (v, scale) = match t {
        DataType::I8 => (f64::from(raw(1)[0] as i8), 127.0),
        DataType::U8 => (f64::from(raw(1)[0]), 255.0),
        DataType::I16 => {
            let r = raw(2);
            (f64::from(i16::from_le_bytes([r[0], r[1]])), 32767.0)
        }
        DataType::U16 => {
            let r = raw(2);
            (f64::from(u16::from_le_bytes([r[0], r[1]])), 65535.0)
        }
        DataType::U32 => (f64::from(u32::from_le_bytes(raw(4))), 4294967295.0),
        DataType::F32 => (f64::from(f32::from_le_bytes(raw(4))), 1.0),
    };
    if normalized && t != DataType::F32 {
        (v / scale).max(-1.0)
    } else {
        v
    }
}

/// Reads accessor `a` as `count` elements of `want` components each (flattened), refusing
/// other element types, sparse accessors, non-finite floats and any range outside its
/// buffer view. `what` names the use in messages (`mesh "cube" primitive 0 POSITION`).
pub fn read(
    buffers: &Buffers,
    a: &Accessor<'_>,
    want: &[Dimensions],
    what: &str,
) -> std::result::Result<(Vec<f64>, usize), String> {
    let at = format!("accessors[{}] ({what})", a.index());
    if a.sparse().is_some() {
        return Err(format!("{at}: sparse accessors are not supported"));
    }
    if !want.contains(&a.dimensions()) {
        return Err(format!(
            "{at}: is {:?}, expected {}",
            a.dimensions(),
            want.iter()
                .map(|d| format!("{d:?}"))
                .collect::<Vec<_>>()
                .join(" or ")
        ));
    }
    let count = a.count();
    if count > MAX_ACCESSOR_COUNT {
        return Err(format!(
            "{at}: count {count} exceeds the limit of {MAX_ACCESSOR_COUNT}"
        ));
    }
    let n = components(a.dimensions());
    let t = a.data_type();
    let elem = n * component_bytes(t);
    let Some(view) = a.view() else {
        // No buffer view: all zeros (glTF's rule), bounded like a view's content.
        if count * n > MAX_ACCESSOR_COUNT {
            return Err(format!(
                "{at}: {count} elements without a buffer view exceed the limit of \
                 {MAX_ACCESSOR_COUNT} values"
            ));
        }
        return Ok((vec![0.0; count * n], n));
    };
    let bytes = buffers.view(&view).map_err(|m| format!("{at}: {m}"))?;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "{at}: byte stride {stride} is smaller than an element ({elem} bytes)"
        ));
    }
    let needed = match count {
        0 => Some(0),
        c => (c - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(elem))
            .and_then(|x| x.checked_add(a.offset())),
    };
    let fits = needed.is_some_and(|needed| needed <= bytes.len());
    if !fits {
        return Err(format!(
            "{at}: {count} elements of {elem} bytes (stride {stride}, offset {}) run past the \
             end of bufferViews[{}] ({} bytes)",
            a.offset(),
            view.index(),
            bytes.len()
        ));
    }
    let cb = component_bytes(t);
    let mut out = Vec::with_capacity(count * n);
    for i in 0..count {
        let base = a.offset() + i * stride;
        for k in 0..n {
            let s = base + k * cb;
            let v = component(t, bytes.get(s..s + cb).unwrap_or_default(), a.normalized());
            if !v.is_finite() {
                return Err(format!("{at}: element {i} is not finite"));
            }
            out.push(v);
        }
    }
    Ok((out, n))
}

/// Reads an accessor of integer indices (`SCALAR` or `VEC4` of unsigned integers), each
/// checked to be below `bound`.
pub fn read_indices(
    buffers: &Buffers,
    a: &Accessor<'_>,
    want: Dimensions,
    bound: usize,
    what: &str,
) -> std::result::Result<Vec<u32>, String> {
    let at = format!("accessors[{}] ({what})", a.index());
    if !matches!(a.data_type(), DataType::U8 | DataType::U16 | DataType::U32) || a.normalized() {
        return Err(format!(
            "{at}: indices must be unsigned integers, got {:?}",
            a.data_type()
        ));
    }
    let (values, _) = read(buffers, a, &[want], what)?;
    values
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let k = v as usize;
            if k < bound {
                Ok(k as u32)
            } else {
                Err(format!(
                    "{at}: element {i} is {k}, out of range (must be below {bound})"
                ))
            }
        })
        .collect()
}
