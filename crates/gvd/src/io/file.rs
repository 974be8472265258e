//! Output files written safely: the whole file or nothing, never through a link.
//!
//! Refused: a symbolic link (never followed, so a planted link cannot redirect the
//! write), a directory, a read-only file. A path that is not a regular file (a FIFO,
//! `/dev/null`) is written in place, never replaced. A regular file (or a new one) is
//! replaced by a temporary file created exclusively beside it (`O_EXCL`, a random name)
//! and renamed over it, so a reader never sees half a file and a failure leaves it as
//! it was; an existing file keeps its permissions.

use std::fs::Permissions;
use std::io::{Error, ErrorKind, Write};
use std::path::{Path, PathBuf};

/// Where an output file goes.
#[derive(Debug)]
pub enum Target {
    /// A FIFO or a device: opened and written, never renamed over.
    InPlace(PathBuf),
    /// A regular file (with its permissions) or a new one: replaced by renaming a
    /// temporary file over it.
    File {
        /// The file.
        path: PathBuf,
        /// The existing file's permissions, kept by the replacement.
        mode: Option<Permissions>,
    },
}

/// What kind of target `path` is, refusing links, directories and read-only files
/// with a message naming the path.
pub fn target(path: &Path) -> std::io::Result<Target> {
    let shown = path.display();
    let refuse = |kind, why: &str| Err(Error::new(kind, format!("output {shown} {why}")));
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => refuse(
            ErrorKind::InvalidInput,
            "is a symbolic link: refusing to write through it (give the path it points to)",
        ),
        Ok(m) if m.is_dir() => refuse(ErrorKind::IsADirectory, "is a directory"),
        Ok(m) if m.is_file() && m.permissions().readonly() => refuse(
            ErrorKind::PermissionDenied,
            "is read-only: refusing to replace it",
        ),
        Ok(m) if m.is_file() => Ok(Target::File {
            path: path.to_path_buf(),
            mode: Some(m.permissions()),
        }),
        Ok(_) => Ok(Target::InPlace(path.to_path_buf())),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(Target::File {
            path: path.to_path_buf(),
            mode: None,
        }),
        Err(e) => Err(Error::new(e.kind(), format!("cannot write {shown}: {e}"))),
    }
}

/// A new temporary file `.{name}.{random}.tmp` beside `path`, created exclusively with
/// `mode` (or rw-rw-rw- less the umask, like any new file), to be persisted over it.
pub fn temp_beside(
    path: &Path,
    mode: Option<&Permissions>,
) -> std::io::Result<tempfile::NamedTempFile> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let prefix = format!(".{}.", name.as_deref().unwrap_or("gvd"));
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(
        mode.cloned()
            .unwrap_or_else(|| std::os::unix::fs::PermissionsExt::from_mode(0o666)),
    );
    #[cfg(not(unix))]
    let _ = mode;
    builder.tempfile_in(dir)
}

/// Writes `bytes` to `path` all or none, by the rules above.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    match target(path)? {
        Target::InPlace(path) => std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .and_then(|mut f| f.write_all(bytes)),
        Target::File { path, mode } => {
            let mut tmp = temp_beside(&path, mode.as_ref())?;
            tmp.write_all(bytes)?;
            tmp.as_file().sync_all()?;
            tmp.persist(&path).map(drop).map_err(|e| e.error)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::write_file;

    #[test]
    fn replaces_a_file_and_refuses_links_directories_and_read_only_files() {
        let dir = std::env::temp_dir().join(format!("gvd-write-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("out.png");
        write_file(&out, b"one").unwrap();
        write_file(&out, b"two").unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"two");
        let err = write_file(&dir, b"x").unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        #[cfg(unix)]
        {
            let link = dir.join("link.png");
            std::os::unix::fs::symlink(&out, &link).unwrap();
            let err = write_file(&link, b"x").unwrap_err();
            assert!(err.to_string().contains("symbolic link"), "{err}");
            assert_eq!(std::fs::read(&out).unwrap(), b"two");
        }
        let mut ro = std::fs::metadata(&out).unwrap().permissions();
        ro.set_readonly(true);
        std::fs::set_permissions(&out, ro).unwrap();
        let err = write_file(&out, b"x").unwrap_err();
        assert!(err.to_string().contains("read-only"), "{err}");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(
            names.len(),
            2 + usize::from(cfg!(unix)) - 1,
            "no temporary file left"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
