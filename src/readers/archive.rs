//! Zip archives whose entries are decompressed under a budget.

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;

/// Largest decompressed size of one archive's entries together [bytes].
const MAX_DECOMPRESSED: u64 = 4 << 30;
/// Smallest budget, so that tiny archives of well-compressed text are read [bytes].
const MIN_BUDGET: u64 = 16 << 20;

/// A zip archive in memory, its entry names sorted (numbers in paths compared as numbers), read
/// under a decompression budget of 64 times the archive's size (between 16 MiB and 4 GiB) for all
/// its entries together.
pub(crate) struct Zip<'a> {
    zip: zip::ZipArchive<std::io::Cursor<&'a [u8]>>,
    /// Entry names (files and folders), sorted with [`path_order`].
    names: Vec<String>,
    /// Bytes still allowed to be decompressed.
    budget: u64,
    path: &'a Path,
}

impl<'a> Zip<'a> {
    /// Open an archive held in `bytes`.
    pub(crate) fn open(bytes: &'a [u8], path: &'a Path) -> Result<Self> {
        let zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| {
            Error::data_file(path, 0, format!("not a readable zip archive: {}", one_line(&e)))
        })?;
        let mut names = Vec::with_capacity(zip.len());
        for n in zip.file_names() {
            let n = n.map_err(|e| {
                Error::data_file(path, 0, format!("unreadable zip entry name: {}", one_line(&e)))
            })?;
            names.push(n.into_owned());
        }
        names.sort_by(|a, b| path_order(a, b));
        let budget = (bytes.len() as u64)
            .saturating_mul(64)
            .clamp(MIN_BUDGET, MAX_DECOMPRESSED);
        Ok(Zip {
            zip,
            names,
            budget,
            path,
        })
    }

    /// Entry names, sorted.
    pub(crate) fn names(&self) -> &[String] {
        &self.names
    }

    /// True when the archive has an entry of that name.
    pub(crate) fn has(&self, name: &str) -> bool {
        self.names.binary_search_by(|n| path_order(n, name)).is_ok()
    }

    /// The decompressed bytes of an entry, within the budget.
    pub(crate) fn read(&mut self, name: &str) -> Result<Vec<u8>> {
        let path = self.path;
        let err = |msg: String| Error::data_file(path, 0, format!("zip entry {name}: {msg}"));
        let entry = self.zip.by_name(name).map_err(|e| err(one_line(&e)))?;
        let mut out = Vec::new();
        let n = entry
            .take(self.budget.saturating_add(1))
            .read_to_end(&mut out)
            .map_err(|e| err(format!("cannot decompress: {}", one_line(&e))))? as u64;
        if n > self.budget {
            return Err(err(format!(
                "decompresses past the archive's budget of {} bytes (a zip bomb?)",
                self.budget
            )));
        }
        self.budget -= n;
        Ok(out)
    }
}

/// An error's message on one line.
pub(crate) fn one_line(e: &dyn std::fmt::Display) -> String {
    e.to_string().split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Order of archive paths: component by component, components that are numbers compared as
/// numbers (so `index/2/` comes before `index/10/`), others as bytes.
pub(crate) fn path_order(a: &str, b: &str) -> std::cmp::Ordering {
    let mut ia = a.split('/');
    let mut ib = b.split('/');
    loop {
        match (ia.next(), ib.next()) {
            (None, None) => return std::cmp::Ordering::Equal,
            (None, Some(_)) => return std::cmp::Ordering::Less,
            (Some(_), None) => return std::cmp::Ordering::Greater,
            (Some(x), Some(y)) => {
                let nx = numeric(x);
                let ny = numeric(y);
                let o = match (nx, ny) {
                    (Some(p), Some(q)) => p.cmp(&q).then_with(|| x.cmp(y)),
                    _ => x.cmp(y),
                };
                if o != std::cmp::Ordering::Equal {
                    return o;
                }
            }
        }
    }
}

/// A path component made of ASCII digits only, as a number (saturating).
fn numeric(s: &str) -> Option<u128> {
    if s.is_empty() || !s.bytes().all(|c| c.is_ascii_digit()) {
        return None;
    }
    Some(s.bytes().fold(0u128, |n, c| {
        n.saturating_mul(10).saturating_add(u128::from(c - b'0'))
    }))
}

/// Every file entry of a zip (folders skipped) parsed as one curve, in name order, each curve's
/// index its place; `parse` gets the entry's bytes, the archive's path, a message prefix naming
/// the entry, and the read options.
pub(crate) fn curves_of_entries(
    zip: &mut Zip,
    path: &std::path::Path,
    opts: &super::ReadOptions,
    parse: impl Fn(&[u8], &std::path::Path, &str, &super::ReadOptions) -> crate::Result<super::ForceCurve>,
) -> crate::Result<Vec<super::ForceCurve>> {
    let names: Vec<String> = zip
        .names()
        .iter()
        .filter(|n| !n.ends_with('/'))
        .cloned()
        .collect();
    let mut curves = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        let bytes = zip.read(name)?;
        let mut c = parse(&bytes, path, &format!("{name}: "), opts)?;
        c.index = i;
        curves.push(c);
    }
    Ok(curves)
}
