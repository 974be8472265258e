//! One output file written safely: the whole file or nothing, never through a link.

use std::io::{Error, ErrorKind, Write};
use std::path::Path;

/// Writes `bytes` to `path` all or none, by the rules of the `gvd` command's outputs: a
/// temporary file is created exclusively (`O_EXCL`) beside `path`, filled, then renamed
/// over it, so a reader never sees half a file and a failure leaves `path` as it was;
/// an existing file keeps its permissions.
///
/// Refused: a symbolic link (never followed, so a planted link cannot redirect the
/// write), a directory, a read-only file. A path that is not a regular file (a FIFO,
/// `/dev/null`) is written in place, never replaced.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let shown = path.display();
    let refuse = |kind, why: &str| Err(Error::new(kind, format!("output {shown} {why}")));
    let mode = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            return refuse(
                ErrorKind::InvalidInput,
                "is a symbolic link: refusing to write through it (give the path it points to)",
            )
        }
        Ok(m) if m.is_dir() => return refuse(ErrorKind::IsADirectory, "is a directory"),
        Ok(m) if m.is_file() && m.permissions().readonly() => {
            return refuse(
                ErrorKind::PermissionDenied,
                "is read-only: refusing to replace it",
            )
        }
        Ok(m) if m.is_file() => Some(m.permissions()),
        Ok(_) => {
            return std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .and_then(|mut f| f.write_all(bytes))
        }
        Err(e) if e.kind() == ErrorKind::NotFound => None,
        Err(e) => return Err(e),
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| Error::new(ErrorKind::InvalidInput, "the path has no file name"))?
        .to_string_lossy();
    let (tmp, mut file) = create_beside(dir, &name, mode)?;
    let done = file
        .write_all(bytes)
        .and_then(|_| file.sync_all())
        .and_then(|_| std::fs::rename(&tmp, path));
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// A new file `.{name}.{unique}.tmp` in `dir`, created exclusively with `mode` (or
/// rw-rw-rw-), less the umask.
fn create_beside(
    dir: &Path,
    name: &str,
    mode: Option<std::fs::Permissions>,
) -> std::io::Result<(std::path::PathBuf, std::fs::File)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let mut last = None;
    for _ in 0..64 {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let unique = format!(
            "{:x}{:x}{:x}",
            std::process::id(),
            nanos,
            COUNT.fetch_add(1, Ordering::Relaxed)
        );
        let tmp = dir.join(format!(".{name}.{unique}.tmp"));
        let mut open = std::fs::OpenOptions::new();
        open.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::{OpenOptionsExt, PermissionsExt};
            open.mode(mode.as_ref().map_or(0o666, |m| m.mode()));
        }
        #[cfg(not(unix))]
        let _ = &mode;
        match open.open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| Error::other("cannot create a temporary file")))
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
