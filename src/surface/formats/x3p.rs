//! ISO 25178-72 XML 3D surface profiles (`.x3p`): a zip holding `main.xml` and the binary heights
//! it links (`Record3/DataLink/PointDataLink`, usually `bindata/data.bin`).
//!
//! `Record1/Axes`: CX and CY of AxisType `I` (incremental: a uniform grid of spacing `Increment`
//! [m]), CZ of AxisType `A` with DataType `I` (u16), `L` (u32), `F` (f32) or `D` (f64),
//! little-endian, and an optional `Increment` (metres per stored unit). `Record3/MatrixDimension`:
//! SizeX, SizeY, SizeZ (1). Heights in x-fastest order. NaN heights are missing points. An
//! absolute axis (a non-uniform grid), volumetric data and inline data lists are refused.

use std::path::Path;

use super::{Channel, ChannelInfo, Num};
use crate::error::{Error, Result};
use crate::readers::archive::Zip;

/// The inner text of the first element `name` (any namespace prefix) in `xml`.
pub(crate) fn element<'x>(xml: &'x str, name: &str) -> Option<&'x str> {
    let mut from = 0;
    while let Some(k) = xml[from..].find('<') {
        let start = from + k + 1;
        let rest = &xml[start..];
        let tag_end = rest.find('>')?;
        let tag = &rest[..tag_end];
        let tag_name = tag
            .split(|c: char| c.is_whitespace() || c == '/')
            .next()
            .unwrap_or("");
        let local = tag_name.rsplit(':').next().unwrap_or("");
        if local == name && !tag.starts_with('/') {
            if tag.ends_with('/') {
                return Some("");
            }
            let body_start = start + tag_end + 1;
            let close = format!("</{tag_name}>");
            let end = xml[body_start..].find(&close)?;
            return Some(&xml[body_start..body_start + end]);
        }
        from = start;
    }
    None
}

/// The element at a path of names.
fn at<'x>(xml: &'x str, names: &[&str]) -> Option<&'x str> {
    names.iter().try_fold(xml, |x, n| element(x, n)).map(str::trim)
}

/// The channel of an `.x3p` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, m);
    let mut zip = Zip::open(bytes, path)?;
    if !zip.has("main.xml") {
        return Err(err(
            "a zip archive without main.xml: not an ISO 25178 .x3p file".into()
        ));
    }
    let xml = zip.read("main.xml")?;
    let xml = String::from_utf8(xml).map_err(|_| err("main.xml of the .x3p is not UTF-8".into()))?;
    let need = |names: &[&str]| -> Result<&str> {
        at(&xml, names).ok_or_else(|| err(format!("main.xml lacks {}", names.join("/"))))
    };
    let num = |names: &[&str]| -> Result<f64> {
        let t = need(names)?;
        t.parse::<f64>()
            .map_err(|_| err(format!("main.xml {} = `{t}` is not a number", names.join("/"))))
    };
    let count = |names: &[&str]| -> Result<usize> {
        let t = need(names)?;
        t.parse::<usize>()
            .map_err(|_| err(format!("main.xml {} = `{t}` is not a count", names.join("/"))))
    };
    let feature = need(&["Record1", "FeatureType"])?;
    if feature != "SUR" {
        return Err(err(format!(
            ".x3p FeatureType {feature} is not read (only SUR, an areal surface)"
        )));
    }
    for axis in ["CX", "CY"] {
        let ty = need(&["Record1", "Axes", axis, "AxisType"])?;
        if ty != "I" {
            return Err(err(format!(
                ".x3p axis {axis} of AxisType {ty}: a non-uniform grid (absolute coordinates) is \
                 not read; resample it onto a uniform grid first"
            )));
        }
    }
    let dx = num(&["Record1", "Axes", "CX", "Increment"])?;
    let dy = num(&["Record1", "Axes", "CY", "Increment"])?;
    let dt = need(&["Record1", "Axes", "CZ", "DataType"])?;
    let ty = match dt {
        "I" => Num::U16,
        "L" => Num::U32,
        "F" => Num::F32,
        "D" => Num::F64,
        other => {
            return Err(err(format!(
                ".x3p CZ DataType `{other}` is not read (I, L, F or D)"
            )));
        }
    };
    let dz = match at(&xml, &["Record1", "Axes", "CZ", "Increment"]) {
        Some(_) => num(&["Record1", "Axes", "CZ", "Increment"])?,
        None => 1.0,
    };
    let nx = count(&["Record3", "MatrixDimension", "SizeX"])?;
    let ny = count(&["Record3", "MatrixDimension", "SizeY"])?;
    let nz = count(&["Record3", "MatrixDimension", "SizeZ"])?;
    if nz != 1 {
        return Err(err(format!(".x3p SizeZ = {nz}: volumetric data is not read")));
    }
    let link = at(&xml, &["Record3", "DataLink", "PointDataLink"])
        .ok_or_else(|| {
            err(".x3p without Record3/DataLink/PointDataLink (inline data lists are not read)".into())
        })?
        .to_string();
    if !zip.has(&link) {
        return Err(err(format!(".x3p links {link}, which the archive lacks")));
    }
    for (name, d) in [("CX", dx), ("CY", dy)] {
        if !(d > 0.0 && d.is_finite()) {
            return Err(err(format!(
                ".x3p {name} Increment {d} must be positive and finite"
            )));
        }
    }
    let info = ChannelInfo::single_in_metres(nx, ny, dx, dy);
    let decode = move || -> Result<Vec<f64>> {
        let data = zip.read(&link)?;
        let n = nx * ny;
        let mut z = super::numbers(&data, 0, n, ty, true, path, &format!(".x3p entry {link}"))?;
        if dz != 1.0 {
            z.iter_mut().for_each(|v| *v *= dz);
        }
        Ok(z)
    };
    Ok(vec![Channel {
        info,
        decode: Box::new(decode),
    }])
}
