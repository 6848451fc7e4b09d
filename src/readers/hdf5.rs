//! afmformats' HDF5 export (`.h5`): not read (no HDF5 reader without a system library is used);
//! the same data exported by afmformats as `.tab` are.

use super::{ForceFile, ReadOptions};
use crate::{Error, Result};
use std::path::Path;

/// Refuse an HDF5 file with the way around.
pub(crate) fn read(_bytes: &[u8], path: &Path, _opts: &ReadOptions) -> Result<ForceFile> {
    Err(Error::data_file(
        path,
        0,
        "HDF5 export (.h5) is not read: export the file from afmformats as .tab",
    ))
}
