//! Asylum Research images saved as Igor binary waves (`.ibw`, version 5), parsed by the force
//! curve readers' Igor module ([`crate::readers`]).
//!
//! An image is a wave of nx × ny (× layers): x the first dimension, y the second, one layer per
//! channel, named by the labels of the third dimension (`no name (k)` where a layer has none, as
//! SurfaceTopography names them). Spacing from the dimensions' scaling (`sfA`), units from the
//! dimension and data units. The rows are stored from the bottom of the image: they are
//! reversed so that y counts from the top, as SurfaceTopography reads them.

use std::path::Path;

use super::{Channel, ChannelInfo, Unit};
use crate::error::{Error, Result};

/// The layers of an Igor image wave.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let version = crate::readers::igor::version(bytes)
        .ok_or_else(|| Error::data_file(path, 0, "not an Igor binary wave"))?;
    let wave = crate::readers::igor::wave(bytes, version, path)?;
    let err = |m: String| Error::data_file(path, 0, format!(".ibw: {m}"));
    let d = wave.dims;
    if d[3] > 1 {
        return Err(err("a four-dimensional wave is not an image".into()));
    }
    let (nx, ny) = (d[0] as usize, d[1] as usize);
    let layers = d[2].max(1) as usize;
    if ny == 0 {
        return Err(err(format!(
            "a one-dimensional wave of {nx} points: a line scan or force curve, not an image"
        )));
    }
    let (dx, dy) = (wave.sfa[0], wave.sfa[1]);
    if !(dx > 0.0 && dy > 0.0 && dx.is_finite() && dy.is_finite()) {
        return Err(err(format!("pixel size {dx} x {dy} must be positive and finite")));
    }
    let (ux, uy) = (Unit::named(&wave.dim_units[0]), Unit::named(&wave.dim_units[1]));
    let size = match (ux.metres, uy.metres) {
        (Some(fx), Some(fy)) => [dx * fx * nx as f64, dy * fy * ny as f64],
        _ if ux.name == uy.name => [dx * nx as f64, dy * ny as f64],
        _ => return Err(err(format!("x in `{}` and y in `{}`", ux.name, uy.name))),
    };
    let xy_unit = if ux.metres.is_some() && uy.metres.is_some() {
        Unit::metre()
    } else {
        ux
    };
    let z_unit = Unit::named(&wave.data_unit);
    let names: Vec<String> = wave.labels[2].iter().skip(1).cloned().collect();
    let wave = std::rc::Rc::new(wave);
    let mut out = Vec::with_capacity(layers);
    let mut unnamed = 0;
    for k in 0..layers {
        let name = match names.get(k).filter(|n| !n.is_empty()) {
            Some(n) => n.clone(),
            None => {
                unnamed += 1;
                format!("no name ({unnamed})")
            }
        };
        let info = ChannelInfo {
            name,
            nx,
            ny,
            size: Some(size),
            xy_unit: xy_unit.clone(),
            z_unit: z_unit.clone(),
            periodic: false,
        };
        let w = std::rc::Rc::clone(&wave);
        let decode = move || -> Result<Vec<f64>> {
            let n = nx * ny;
            if (k + 1) * n > w.len() {
                return Err(Error::data_file(path, 0, ".ibw: layer past the wave's data"));
            }
            let layer = w.values(k * n, n);
            let mut z = Vec::with_capacity(n);
            for j in (0..ny).rev() {
                z.extend((0..nx).map(|i| layer[j * nx + i]));
            }
            Ok(z)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
    }
    Ok(out)
}
