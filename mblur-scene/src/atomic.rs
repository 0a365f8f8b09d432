//! Writing output files so that a failure leaves nothing behind: the bytes go to a
//! temporary file in the target folder, which is flushed, synced and then renamed over the
//! target. A crash, a full disk or a bad path never leaves a partial or empty file with the
//! target's name (the renderer's "no partial output" rule).

use std::io::Write;
use std::path::Path;

use crate::error::{Error, Result};

/// Writes `bytes` to `path` atomically (a temporary file in the same folder, then rename).
/// The file gets ordinary permissions (0644 on Unix; temporary files are created
/// owner-only). Errors name the path and the OS reason.
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("hello.txt");
/// mblur_scene::atomic::write_atomic(&path, b"hello")?;
/// assert_eq!(std::fs::read(&path)?, b"hello");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let werr = |m: String| Error::Write {
        path: path.to_path_buf(),
        message: m,
    };
    let mut tmp = temp_file_beside(path)?;
    tmp.write_all(bytes)
        .and_then(|()| tmp.flush())
        .and_then(|()| tmp.as_file().sync_all())
        .map_err(|e| werr(e.to_string()))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .map_err(|e| werr(e.to_string()))?;
    }
    tmp.persist(path).map_err(|e| werr(e.error.to_string()))?;
    Ok(())
}

/// A temporary file (`.mblur-*.tmp`, removed when dropped) in the folder `path` will be
/// written to. The error names `path` and says whether its folder is missing or not
/// writable, never the temporary file's name.
pub fn temp_file_beside(path: &Path) -> Result<tempfile::NamedTempFile> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    tempfile::Builder::new()
        .prefix(".mblur-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(|e| Error::Write {
            path: path.to_path_buf(),
            message: if dir.is_dir() {
                format!(
                    "the folder {} is not writable ({})",
                    dir.display(),
                    e.kind()
                )
            } else {
                format!("the folder {} does not exist", dir.display())
            },
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_folder_is_an_error_naming_the_path_and_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no-such-folder").join("x.png");
        let e = write_atomic(&path, b"data").unwrap_err().to_string();
        assert!(e.contains("no-such-folder"), "{e}");
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn an_existing_file_is_replaced_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.txt");
        write_atomic(&path, b"first, longer content").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        // No temporary file is left behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
