//! Renderers of a [`crate::figure::Figure`]: PNG and SVG through plotters ([`plot`]), CSV and
//! JSON ([`data`]), and a ratatui chart for the terminal ([`terminal`]); labels in a small math
//! markup laid out with the embedded font ([`text`]), strokes and fills of the PNG anti-aliased
//! ([`raster`]). All file output is
//! atomic ([`write_atomic`]): a temporary file in the target folder, renamed on success.

pub mod axes;
pub mod data;
pub mod labels;
pub mod pdf;
pub mod plot;
pub mod raster;
pub mod terminal;
pub mod text;

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// Export formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Raster figure.
    Png,
    /// Vector figure.
    Svg,
    /// Long-form data `panel,series,style,x,y`.
    Csv,
    /// Parameters, results, fields, version, run time.
    Json,
    /// Vector figure for print and LaTeX: the SVG's drawing with the font embedded, labels as
    /// text.
    Pdf,
}

impl Format {
    /// The formats written unless `--format` says otherwise.
    pub const ALL: [Format; 4] = [Format::Png, Format::Svg, Format::Csv, Format::Json];

    /// Every format there is.
    pub const KNOWN: [Format; 5] = [Format::Png, Format::Svg, Format::Csv, Format::Json, Format::Pdf];

    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Svg => "svg",
            Format::Csv => "csv",
            Format::Json => "json",
            Format::Pdf => "pdf",
        }
    }

    /// Parse one name (`png`, `svg`, `csv`, `json`, `pdf`).
    pub fn parse(name: &str) -> Option<Format> {
        Format::KNOWN
            .into_iter()
            .find(|f| f.extension() == name.trim().to_ascii_lowercase())
    }
}

/// Write `bytes` to `path` atomically ([`write_set`] of one file).
///
/// # Errors
/// [`Error::File`] naming the path and the operation; `path` is then untouched.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_set(&[(path.to_path_buf(), bytes)])
}

/// Write a set of files so that they appear together or not at all, each replacing what was
/// there (the formats of one export, a report's Markdown and JSON).
///
/// Every file is first written in full to a temporary file in its target folder, created
/// exclusively (`O_EXCL`: an existing file or a planted symlink of that name is never opened;
/// the name has a random part) and flushed to disk. Then, holding an exclusive lock on each
/// target folder (so that two exports into one folder do not interleave their sets), the
/// temporaries are renamed over the targets. When a rename fails, the targets already replaced
/// get their previous content back (kept as hard links until the end) or are removed if they
/// are new. Temporaries are removed on every error and, through [`cleanup_on_signal`], on
/// SIGINT, SIGTERM and SIGHUP.
///
/// # Errors
/// [`Error::File`] naming the first path that failed and the operation (creating, writing,
/// replacing); nothing of the set is then left behind.
pub fn write_set<B: AsRef<[u8]>>(files: &[(PathBuf, B)]) -> Result<()> {
    cleanup_on_signal();
    for (path, _) in files {
        if path.is_dir() {
            return Err(Error::file("writing", path)(std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "a folder of that name is in the way",
            )));
        }
    }
    let mut staged = Staged::default();
    let result = staged.write(files);
    staged.remove_all();
    result
}

/// Temporaries and backups of one [`write_set`], removed when it ends.
#[derive(Default)]
struct Staged {
    temps: Vec<PathBuf>,
    backups: Vec<Option<PathBuf>>,
}

impl Staged {
    fn write<B: AsRef<[u8]>>(&mut self, files: &[(PathBuf, B)]) -> Result<()> {
        let file_error = Error::file;
        for (path, bytes) in files {
            let tmp = create_exclusive(path, "tmp").map_err(file_error("creating a temporary for", path))?;
            self.temps.push(tmp.1.clone());
            let mut f = tmp.0;
            f.write_all(bytes.as_ref())
                .and_then(|()| f.sync_all())
                .map_err(file_error("writing", path))?;
        }
        let mut folders: Vec<PathBuf> = files.iter().map(|(p, _)| folder_of(p)).collect();
        folders.sort();
        folders.dedup();
        for d in &folders {
            remove_stale_temporaries(d);
        }
        // Held until the end of this function; a folder that cannot be locked (a file system
        // without locks) is written without.
        let _locks: Vec<std::fs::File> = folders
            .iter()
            .filter_map(|d| std::fs::File::open(d).ok())
            .filter(|f| f.lock().is_ok())
            .collect();
        // A signal arriving now waits until the set is complete (or rolled back).
        let _renaming = RENAMING.lock();
        for (path, _) in files {
            let backup = if path.is_file() { create_backup(path) } else { None };
            self.backups.push(backup);
        }
        for (k, (path, _)) in files.iter().enumerate() {
            if let Err(e) = std::fs::rename(&self.temps[k], path) {
                // Undo the renames done: previous content back, new files removed.
                for (j, (done, _)) in files.iter().enumerate().take(k) {
                    match &self.backups[j] {
                        Some(b) => {
                            let _ = std::fs::rename(b, done);
                        }
                        None => {
                            let _ = std::fs::remove_file(done);
                        }
                    }
                }
                return Err(file_error("replacing", path)(e));
            }
        }
        Ok(())
    }

    fn remove_all(&mut self) {
        let paths: Vec<PathBuf> = self
            .temps
            .drain(..)
            .chain(self.backups.drain(..).flatten())
            .collect();
        for p in &paths {
            // Renamed temporaries are gone already; the error is expected then.
            let _ = std::fs::remove_file(p);
        }
        forget_temporaries(&paths);
    }
}

/// The folder of `path` ("." for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A hard link to `path` under a fresh name, to restore it if a set fails half-way.
fn create_backup(path: &Path) -> Option<PathBuf> {
    for _ in 0..16 {
        let name = temporary_name(path, "bak");
        remember_temporary(&name);
        match std::fs::hard_link(path, &name) {
            Ok(()) => return Some(name),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => forget_temporaries(&[name]),
            Err(_) => {
                forget_temporaries(&[name]);
                return None;
            }
        }
    }
    None
}

/// A file created exclusively next to `path`, under a fresh hidden name.
fn create_exclusive(path: &Path, kind: &str) -> std::io::Result<(std::fs::File, PathBuf)> {
    let mut last = None;
    for _ in 0..16 {
        let name = temporary_name(path, kind);
        remember_temporary(&name);
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&name)
        {
            Ok(f) => return Ok((f, name)),
            Err(e) => {
                forget_temporaries(std::slice::from_ref(&name));
                if e.kind() != std::io::ErrorKind::AlreadyExists {
                    return Err(e);
                }
                last = Some(e);
            }
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no free temporary name")))
}

/// `.<name>.<pid>@<host>-<random>.<kind>` next to `path`: the process that owns a temporary
/// can be told from its name ([`temporary_owner`]), so that the temporaries of a killed run are
/// removed by the next write into the folder ([`remove_stale_temporaries`]).
fn temporary_name(path: &Path, kind: &str) -> PathBuf {
    use std::hash::{BuildHasher, Hasher};
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // A randomly keyed hasher of the clock: a name no other process can predict.
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    path.with_file_name(format!(
        ".{name}.{}@{}-{:016x}.{kind}",
        std::process::id(),
        host_tag(),
        h.finish()
    ))
}

/// This machine's name as it appears in temporary names: the host name up to its first dot,
/// other characters than letters, digits and `-` as `_` (`localhost` when it is not known).
/// Temporaries are only judged stale by a process of the same host: a shared folder (a
/// cluster's scratch) holds temporaries of processes on other nodes.
pub fn host_tag() -> String {
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .unwrap_or_default();
    let short: String = name
        .trim()
        .split('.')
        .next()
        .unwrap_or("")
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if short.is_empty() {
        "localhost".into()
    } else {
        short
    }
}

/// The process id and host of a temporary's file name (`.<name>.<pid>@<host>-<16 hex>.tmp` or
/// `.bak`), or `None` for another name.
pub fn temporary_owner(file_name: &str) -> Option<(u32, String)> {
    let rest = file_name.strip_prefix('.')?;
    let rest = rest.strip_suffix(".tmp").or_else(|| rest.strip_suffix(".bak"))?;
    let (rest, random) = rest.rsplit_once('-')?;
    if random.len() != 16 || !random.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let (_, owner) = rest.rsplit_once('.')?;
    let (pid, host) = owner.split_once('@')?;
    if host.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((pid.parse().ok()?, host.to_string()))
}

/// Remove the temporaries in `folder` left by killed runs on this host: those whose process is
/// gone (no `/proc/<pid>`). Temporaries of live processes, of other hosts and other files are
/// left alone; nothing is done without `/proc`. Returns the files removed.
pub fn remove_stale_temporaries(folder: &Path) -> Vec<PathBuf> {
    if !Path::new("/proc/self").exists() {
        return Vec::new();
    }
    let Ok(entries) = std::fs::read_dir(folder) else {
        return Vec::new();
    };
    let (me, host) = (std::process::id(), host_tag());
    let mut removed = Vec::new();
    for e in entries.filter_map(std::result::Result::ok) {
        let name = e.file_name();
        let Some((pid, owner_host)) = name.to_str().and_then(temporary_owner) else {
            continue;
        };
        if owner_host != host || pid == me || Path::new(&format!("/proc/{pid}")).exists() {
            continue;
        }
        if e.file_type().is_ok_and(|t| t.is_file()) && std::fs::remove_file(e.path()).is_ok() {
            removed.push(e.path());
        }
    }
    removed
}

/// Held while a set is renamed into place, and by the signal handler before it exits.
static RENAMING: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Temporaries of this process not yet renamed or removed.
static LIVE_TEMPORARIES: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn remember_temporary(path: &Path) {
    if let Ok(mut v) = LIVE_TEMPORARIES.lock() {
        v.push(path.to_path_buf());
    }
}

fn forget_temporaries(paths: &[PathBuf]) {
    if let Ok(mut v) = LIVE_TEMPORARIES.lock() {
        v.retain(|p| !paths.contains(p));
    }
}

/// Remove this process's temporaries when it is interrupted (SIGINT, SIGTERM, SIGHUP), then
/// exit with 128 + the signal number as the default action would. Installed once, by the first
/// [`write_set`]; without signal support it does nothing.
pub fn cleanup_on_signal() {
    static INSTALL: std::sync::Once = std::sync::Once::new();
    INSTALL.call_once(|| {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        let _ = std::thread::Builder::new()
            .name("cleanup-on-signal".into())
            .spawn(move || {
                if let Some(sig) = signals.forever().next() {
                    // Never in the middle of a set's renames: they take microseconds.
                    let _renaming = RENAMING.lock();
                    // Held to the exit, so no new temporary appears after the removal.
                    let live = LIVE_TEMPORARIES.lock();
                    if let Ok(v) = &live {
                        for p in v.iter() {
                            let _ = std::fs::remove_file(p);
                        }
                    }
                    std::process::exit(128 + sig);
                }
            });
    });
}
