//! Safe output files: every output of a command is written all or none, through a
//! temporary file created exclusively (random name, `O_EXCL`) in the target's directory
//! and renamed over the target only once every output is ready.
//!
//! Refused before any work: an output that is an input or is given twice, a symbolic
//! link (never followed: a planted link cannot redirect the write), a directory, a
//! read-only file. A path that is not a regular file (a FIFO, `/dev/null`,
//! `/dev/stdout`) is written in place, never replaced; `-` is standard output.

use anyhow::{bail, Context, Result};
use gvd::io::file::{temp_beside, Target};
use std::io::Write;
use std::path::{Path, PathBuf};

/// An output written to its temporary file (or held, for a stream), not yet in place.
enum Ready {
    Stdout(Vec<u8>),
    InPlace(PathBuf, Vec<u8>),
    File(tempfile::NamedTempFile, PathBuf),
}

/// The outputs of one command.
pub struct Outputs {
    inputs: Vec<PathBuf>,
    claimed: Vec<PathBuf>,
    ready: Vec<Ready>,
}

impl Outputs {
    /// Outputs for a command reading `inputs` (`-` for standard input is never an output).
    pub fn new(inputs: &[&Path]) -> Self {
        Outputs {
            inputs: inputs
                .iter()
                .filter(|p| p.as_os_str() != "-")
                .filter_map(|p| std::fs::canonicalize(p).ok())
                .collect(),
            claimed: Vec::new(),
            ready: Vec::new(),
        }
    }

    /// Checks that `path` may be written (see the module's rules) and reserves it.
    pub fn claim(&mut self, path: &Path) -> Result<()> {
        let shown = path.display();
        let key = identity(path).with_context(|| format!("cannot write {shown}"))?;
        if self.inputs.contains(&key) {
            bail!("output {shown} is an input of this command: refusing to overwrite it");
        }
        if self.claimed.contains(&key) {
            bail!("output {shown} is given twice");
        }
        target(path)?;
        self.claimed.push(key);
        Ok(())
    }

    /// Writes `path` (claimed before) through `write`, into a temporary file beside it
    /// or a buffer; nothing is in place until [`Outputs::commit`].
    pub fn write(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<()> {
        let fail = || format!("cannot write {}", path.display());
        let ready = match target(path)? {
            Some(Target::File { path, mode }) => {
                let mut tmp = temp_beside(&path, mode.as_ref()).with_context(fail)?;
                {
                    let mut w = std::io::BufWriter::with_capacity(1 << 20, tmp.as_file_mut());
                    write(&mut w).and_then(|_| w.flush()).with_context(fail)?;
                }
                Ready::File(tmp, path)
            }
            stream => {
                let mut buf = Vec::new();
                write(&mut buf).with_context(fail)?;
                match stream {
                    Some(Target::InPlace(path)) => Ready::InPlace(path, buf),
                    _ => Ready::Stdout(buf),
                }
            }
        };
        self.ready.push(ready);
        Ok(())
    }

    /// Puts every output in place (renames the temporary files, writes the streams).
    pub fn commit(self) -> Result<()> {
        for r in self.ready {
            match r {
                Ready::File(tmp, path) => {
                    tmp.persist(&path)
                        .map_err(|e| e.error)
                        .with_context(|| format!("cannot write {}", path.display()))?;
                }
                Ready::Stdout(buf) => {
                    let mut out = std::io::stdout().lock();
                    out.write_all(&buf)
                        .and_then(|_| out.flush())
                        .context("cannot write to standard output")?;
                }
                Ready::InPlace(path, buf) => {
                    std::fs::OpenOptions::new()
                        .write(true)
                        .open(&path)
                        .and_then(|mut f| f.write_all(&buf))
                        .with_context(|| format!("cannot write {}", path.display()))?;
                }
            }
        }
        Ok(())
    }
}

/// What kind of target `path` is (`None`: standard output), refusing the paths of the
/// module's rules.
fn target(path: &Path) -> Result<Option<Target>> {
    if path.as_os_str() == "-" {
        return Ok(None);
    }
    Ok(Some(gvd::io::file::target(path)?))
}

/// A path naming the same file whatever way it is written: the canonical path of an
/// existing file, else the canonical directory joined with the name.
fn identity(path: &Path) -> std::io::Result<PathBuf> {
    if path.as_os_str() == "-" {
        return Ok(PathBuf::from("-"));
    }
    if std::fs::symlink_metadata(path).is_ok() {
        return std::fs::canonicalize(path);
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().ok_or_else(|| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the path has no file name",
        )
    })?;
    Ok(std::fs::canonicalize(dir)?.join(name))
}
