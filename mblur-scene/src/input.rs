//! Reading input files with bounds: only regular files, no larger than a documented limit,
//! checked before anything is read, so a path to a device (`/dev/zero`), a FIFO or a huge
//! file is an error naming it instead of unbounded time or memory.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

/// Largest scene file read, in bytes (64 MiB).
pub const MAX_SCENE_BYTES: u64 = 1 << 26;
/// Largest mesh or point-cloud file read (OBJ, PLY), in bytes (1 GiB).
pub const MAX_MESH_BYTES: u64 = 1 << 30;
/// Largest texture file read (PNG), in bytes (256 MiB).
pub const MAX_TEXTURE_BYTES: u64 = 1 << 28;
/// Largest image file read for comparison (`mblur diff`, a compare reference), in bytes
/// (1 GiB: an 8192 x 8192 RGBA float EXR).
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;

/// The whole content of the regular file at `path`, refused when it is not a regular file
/// or is larger than `limit` bytes (`what` names the kind of file in the message).
pub fn read_bounded(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| Error::read(path, e))?;
    if !meta.is_file() {
        return Err(Error::format(
            path,
            format!(
                "is not a regular file (a {what} must be a file, not a device, folder or pipe)"
            ),
        ));
    }
    if meta.len() > limit {
        return Err(Error::format(
            path,
            format!(
                "{what} of {} bytes exceeds the limit of {limit} bytes",
                meta.len()
            ),
        ));
    }
    let file = std::fs::File::open(path).map_err(|e| Error::read(path, e))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // The file may grow after the check: read at most one byte past the limit to tell.
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::read(path, e))?;
    if bytes.len() as u64 > limit {
        return Err(Error::format(
            path,
            format!("{what} grew past the limit of {limit} bytes while being read"),
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_folders_and_oversized_files_are_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_bounded(dir.path(), 10, "mesh file").unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        if Path::new("/dev/zero").exists() {
            let e = read_bounded(Path::new("/dev/zero"), 10, "mesh file").unwrap_err();
            assert!(
                e.to_string()
                    .starts_with("/dev/zero: is not a regular file"),
                "{e}"
            );
        }
        let f = dir.path().join("big.obj");
        std::fs::write(&f, [b'x'; 11]).unwrap();
        let e = read_bounded(&f, 10, "mesh file").unwrap_err();
        assert!(
            e.to_string().contains("11 bytes exceeds the limit of 10"),
            "{e}"
        );
        assert_eq!(read_bounded(&f, 11, "mesh file").unwrap().len(), 11);
    }
}
