//! Bounded reading of input files (height maps, presets, profiles, force curves, point files of
//! sharded sweeps): regular files only, and at most a size limit, so that `/dev/zero`, a FIFO or
//! a huge file gives a one-line error instead of a hang or runaway memory.
//!
//! The limit is 2 GB unless the environment variable `ADHESION_INPUT_LIMIT` sets another (bytes,
//! with an optional `k`, `M`, `G` suffix in powers of 1000: `ADHESION_INPUT_LIMIT=500M`).

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

/// The default size limit of an input file: 2 GB.
pub const DEFAULT_LIMIT: u64 = 2_000_000_000;

/// The environment variable that sets the size limit of input files.
pub const LIMIT_VARIABLE: &str = "ADHESION_INPUT_LIMIT";

/// The size limit of input files: `ADHESION_INPUT_LIMIT` if it is set and valid, else
/// [`DEFAULT_LIMIT`].
pub fn limit() -> u64 {
    std::env::var(LIMIT_VARIABLE)
        .ok()
        .and_then(|t| parse_size(&t))
        .unwrap_or(DEFAULT_LIMIT)
}

/// A size as bytes: a whole number with an optional `k`, `M` or `G` suffix (powers of 1000).
pub fn parse_size(text: &str) -> Option<u64> {
    let t = text.trim();
    let (digits, factor) = match t.char_indices().last()? {
        (i, 'k' | 'K') => (&t[..i], 1_000),
        (i, 'M') => (&t[..i], 1_000_000),
        (i, 'G') => (&t[..i], 1_000_000_000),
        _ => (t, 1),
    };
    digits.trim().parse::<u64>().ok()?.checked_mul(factor)
}

/// The bytes of the input file `path`, read from a regular file of at most `limit` bytes.
///
/// Checks the file's type and size before reading, and reads at most `limit + 1` bytes, so a
/// file that grows while it is read does not grow the memory past the limit either.
///
/// # Errors
/// [`Error::DataFile`] naming the file when it is not a regular file (a folder, a FIFO, a
/// device), is larger than `limit`, or cannot be opened or read.
pub fn read_input(path: &Path, limit: u64) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(cannot_read(path))?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a folder"
        } else {
            special_kind(&meta)
        };
        return Err(Error::data_file(
            path,
            0,
            format!("{what}, not a regular file: give a file to read"),
        ));
    }
    let too_large = |size: u64| {
        Error::data_file(
            path,
            0,
            format!(
                "the file has {size} bytes or more, above the input limit of {limit} bytes \
                 (set {LIMIT_VARIABLE} to read larger files)"
            ),
        )
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(cannot_read(path))?;
    // Opened after the check: a file swapped for a FIFO in between is caught here.
    let opened = file.metadata().map_err(cannot_read(path))?;
    if !opened.is_file() {
        return Err(Error::data_file(
            path,
            0,
            format!(
                "{}, not a regular file: give a file to read",
                special_kind(&opened)
            ),
        ));
    }
    let mut bytes = Vec::with_capacity(usize::try_from(opened.len().min(limit)).unwrap_or(0));
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(cannot_read(path))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read_input`] at the [`limit`], as UTF-8 text.
///
/// # Errors
/// As [`read_input`]; [`Error::DataFile`] naming the line of the first byte that is not UTF-8.
pub fn read_text(path: &Path) -> Result<String> {
    let bytes = read_input(path, limit())?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        Error::data_file(path, line, "not UTF-8 text")
    })
}

/// An I/O error as [`Error::DataFile`] "cannot read: ..." naming the file.
fn cannot_read(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::data_file(path, 0, format!("cannot read: {e}"))
}

/// "a FIFO", "a device", "a socket" or "a special file".
fn special_kind(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_fifo() {
        "a FIFO (named pipe)"
    } else if t.is_char_device() || t.is_block_device() {
        "a device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_suffixes() {
        assert_eq!(parse_size("2G"), Some(2_000_000_000));
        assert_eq!(parse_size("500M"), Some(500_000_000));
        assert_eq!(parse_size("12"), Some(12));
        assert_eq!(parse_size("x"), None);
        assert_eq!(parse_size("99999999999999G"), None);
    }

    #[test]
    fn a_file_above_the_limit_and_a_device_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f");
        std::fs::write(&p, b"0123456789").unwrap();
        assert_eq!(read_input(&p, 10).unwrap(), b"0123456789");
        let e = read_input(&p, 9).unwrap_err().to_string();
        assert!(e.contains("above the input limit of 9 bytes"), "{e}");
        let e = read_input(Path::new("/dev/zero"), 9).unwrap_err().to_string();
        assert!(e.contains("/dev/zero") && e.contains("a device"), "{e}");
        let e = read_input(dir.path(), 9).unwrap_err().to_string();
        assert!(e.contains("a folder"), "{e}");
    }
}
