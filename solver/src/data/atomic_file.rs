//! Writing output files whole or not at all: a temporary file in the same directory,
//! flushed to disk, then renamed over the target, so a reader (or a crashed run) never
//! sees a half-written pair file, CSV or SVG; outputs that are not regular files
//! (devices, FIFOs) are written in place, never replaced.

use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Writes `contents` to the output `path` whole or not at all, and never destroys what
/// is not a regular file:
/// - a new path or a regular file: a temporary file in the same directory is written,
///   flushed to disk and renamed over `path` (keeping an existing file's permissions), so
///   readers never see a partial file; on error the temporary file is removed;
/// - a symbolic link: resolved, and its target written as above (the link stays);
/// - a device, FIFO or socket (`/dev/null`, `/dev/stdout`): written in place, never
///   renamed over;
/// - a directory, a read-only file (refused even where the user could replace it, e.g.
///   as root) or one of `inputs` (the same file, by device and inode): an error naming why.
///
/// The parent directory must exist.
pub fn write_output(path: &Path, contents: &[u8], inputs: &[&Path]) -> io::Result<()> {
    let refuse = |kind, why: &str| Err(io::Error::new(kind, why.to_string()));
    let target = match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => match fs::canonicalize(path) {
            Ok(t) => t,
            Err(_) => return refuse(io::ErrorKind::NotFound, "is a dangling symbolic link"),
        },
        _ => path.to_path_buf(),
    };
    let meta = match fs::metadata(&target) {
        Ok(m) => Some(m),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(e),
    };
    if let Some(m) = &meta {
        if m.is_dir() {
            return refuse(io::ErrorKind::InvalidInput, "is a directory");
        }
        if inputs.iter().any(|i| same_file(m, i)) {
            return refuse(
                io::ErrorKind::InvalidInput,
                "is also an input of this command: refusing to overwrite it",
            );
        }
        if !m.is_file() {
            // A device, FIFO or socket: written in place.
            let mut f = fs::OpenOptions::new().write(true).open(&target)?;
            return f.write_all(contents).and_then(|()| f.flush());
        }
        if m.permissions().readonly() {
            return refuse(io::ErrorKind::PermissionDenied, "is read-only");
        }
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = target
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "path has no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(file_name);
    tmp_name.push(format!(".{}.tmp", std::process::id()));
    let tmp = dir.join(tmp_name);
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        drop(f);
        if let Some(m) = &meta {
            fs::set_permissions(&tmp, m.permissions())?;
        }
        fs::rename(&tmp, &target)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Whether `input` is the file `output` describes (same device and inode on Unix, same
/// canonical path elsewhere); an input that cannot be read is not.
fn same_file(output: &fs::Metadata, input: &Path) -> bool {
    let Ok(m) = fs::metadata(input) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        m.dev() == output.dev() && m.ino() == output.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (m, output);
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_whole_file() {
        let dir = std::env::temp_dir().join(format!("rspose-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("x.csv");
        write_output(&p, b"one", &[]).unwrap();
        write_output(&p, b"two", &[]).unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "two");
        assert!(write_output(&dir.join("missing/x.csv"), b"z", &[]).is_err());
        assert!(write_output(&p, b"z", &[&p]).is_err());
        write_output(Path::new("/dev/null"), b"z", &[]).unwrap();
        assert!(!fs::metadata("/dev/null").unwrap().is_file());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
