//! The headless surface commands: `--generate-surface` (write a generated map) and
//! `--analyze-surface FILE` (statistics as JSON).

use std::path::Path;

use serde::Serialize;

use super::analysis::{PeakStatistics, peak_statistics, radial_psd_and_moments};
use super::generate::generate;
use super::io::write_height_map;
use super::psd_fit::{AbcFit, Cutoff, fit_abc};
use super::spectrum::{Moments, Spectrum};
use super::{HeightMap, SurfaceArgs};
use crate::error::{Error, Result};
use crate::params::fmt_sig;

/// Statistics of a height map, as printed by `--analyze-surface`.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceReport {
    /// Conventions of the numbers.
    pub convention: &'static str,
    /// Whether the map was analysed as one period of a periodic surface (plain FFT) or as a
    /// finite patch (Hann window, peaks away from the border).
    pub periodic: bool,
    /// Grid points in x.
    pub nx: usize,
    /// Grid points in y.
    pub ny: usize,
    /// Size in x [m].
    pub lx: f64,
    /// Size in y [m].
    pub ly: f64,
    /// RMS height [m].
    pub sigma_rms: f64,
    /// m0 [m²].
    pub m0: f64,
    /// m2 [-].
    pub m2: f64,
    /// m4 [1/m²].
    pub m4: f64,
    /// Nayak's α.
    pub nayak_alpha: f64,
    /// Asperity density η (3.9) [1/m²].
    pub asperity_density: f64,
    /// Counted peak density [1/m²].
    pub peak_density: f64,
    /// Number of peaks.
    pub peak_count: usize,
    /// Mean nearest-peak distance [m].
    pub mean_nearest_peak_distance: f64,
    /// The (3.16) fit of the radial PSD (null when it failed).
    pub psd_fit: Option<AbcFit>,
    /// Why the fit failed (null when it succeeded).
    pub psd_fit_error: Option<String>,
}

/// Statistics of a map (mean removed first; `remove_tilt` also removes the plane). A
/// non-periodic map is windowed ([`crate::surface::analysis`]).
///
/// # Errors
/// [`Error::InvalidParameter`] naming the first statistic that is not finite (lengths or
/// heights so extreme that a spectral moment or a density leaves the f64 range); the mean
/// nearest-peak distance may be NaN (null) only when fewer than two peaks were found.
pub fn report(map: &HeightMap, cutoff: Cutoff) -> Result<SurfaceReport> {
    let r = report_unchecked(map, cutoff);
    let fields = [
        ("sigma_rms", r.sigma_rms),
        ("m0", r.m0),
        ("m2", r.m2),
        ("m4", r.m4),
        ("nayak_alpha", r.nayak_alpha),
        ("asperity_density", r.asperity_density),
        ("peak_density", r.peak_density),
        ("mean_nearest_peak_distance", r.mean_nearest_peak_distance),
    ];
    if let Some((name, v)) = [("m0", r.m0), ("m2", r.m2), ("m4", r.m4)]
        .into_iter()
        .find(|(_, v)| v.is_nan() || *v <= 0.0)
    {
        return Err(Error::invalid(
            "surface",
            format!("{} x {} map", map.nx, map.ny),
            format!(
                "its spectral moment {name} = {} is not positive: the map is flat or near-flat",
                fmt_sig(v)
            ),
        ));
    }
    for (name, v) in fields {
        let undefined_distance = name == "mean_nearest_peak_distance" && r.peak_count < 2 && v.is_nan();
        if !v.is_finite() && !undefined_distance {
            return Err(Error::invalid(
                "length",
                format!("{} x {} m", fmt_sig(map.lx), fmt_sig(map.ly)),
                format!(
                    "the map's `{name}` is {} in f64 (heights up to {} m): the lengths or heights \
                     are out of range",
                    fmt_sig(v),
                    fmt_sig(map.z.iter().fold(0.0_f64, |a, z| a.max(z.abs())))
                ),
            ));
        }
    }
    Ok(r)
}

/// The largest height of a map in magnitude [m].
pub fn largest_height(map: &HeightMap) -> f64 {
    map.z.iter().fold(0.0_f64, |a, z| a.max(z.abs()))
}

/// Why a map (its mean or plane removed) is too flat to analyse, or `None`: its RMS height is
/// zero, or below 1e-9 of `largest`, the largest height before the removal (what is left is
/// the rounding of the heights). The rule of `--analyze-surface` and of the scenes that read
/// a map.
pub fn flat_map(map: &HeightMap, largest: f64) -> Option<String> {
    let rms = map.rms();
    if rms > 1e-9 * largest && rms > 0.0 {
        return None;
    }
    Some(format!(
        "the map is flat: its RMS height is {} m after removing the mean (or tilt), with heights \
         up to {} m (nothing to analyse)",
        fmt_sig(rms),
        fmt_sig(largest)
    ))
}

fn report_unchecked(map: &HeightMap, cutoff: Cutoff) -> SurfaceReport {
    let (psd, m): (_, Moments) = radial_psd_and_moments(map);
    let peaks: PeakStatistics = peak_statistics(map);
    let fit = fit_abc(&psd, cutoff);
    SurfaceReport {
        convention: "SI units; m0 = sigma_rms^2, m2, m4 of a profile (3.8), isotropic average",
        periodic: map.periodic,
        nx: map.nx,
        ny: map.ny,
        lx: map.lx,
        ly: map.ly,
        sigma_rms: m.rms(),
        m0: m.m0,
        m2: m.m2,
        m4: m.m4,
        nayak_alpha: m.nayak_alpha(),
        asperity_density: m.asperity_density(),
        peak_density: peaks.density,
        peak_count: peaks.count,
        mean_nearest_peak_distance: peaks.mean_nearest_distance,
        psd_fit_error: fit.as_ref().err().map(ToString::to_string),
        psd_fit: fit.ok(),
    }
}

/// Parse `--fit-cutoff`: a positive number, `free` (starting at 1e8 1/m) or `none`.
///
/// # Errors
/// [`Error::InvalidParameter`] for anything else.
pub fn parse_cutoff(text: &str) -> Result<Cutoff> {
    match text {
        "free" => Ok(Cutoff::Free(1.0e8)),
        "none" => Ok(Cutoff::None),
        t => match t.parse::<f64>() {
            Ok(v) if v > 0.0 && v.is_finite() => Ok(Cutoff::Fixed(v)),
            _ => Err(Error::invalid(
                "fit-cutoff",
                t,
                "expects a positive number, `free` or `none`",
            )),
        },
    }
}

/// Largest grid of `--generate-surface`, 2^26 points (about 1 GiB of complex FFT data).
pub const MAX_GRID_POINTS: usize = 1 << 26;

/// The spectrum and grid of `--generate-surface`.
///
/// # Errors
/// [`Error::InvalidParameter`] naming a missing or bad option.
pub fn generation_request(args: &SurfaceArgs) -> Result<(Spectrum, usize, usize, f64, f64)> {
    let rms = args
        .rms
        .ok_or_else(|| Error::invalid("rms", "(missing)", "give --rms METRES"))?;
    let (nx, ny) = match args.size.as_slice() {
        [n] => (*n, *n),
        [n, m] => (*n, *m),
        _ => return Err(Error::invalid("size", "(missing)", "give --size N [M]")),
    };
    if nx.checked_mul(ny).is_none_or(|p| p > MAX_GRID_POINTS) {
        return Err(Error::invalid(
            "size",
            format!("{nx} x {ny}"),
            format!("the grid may have at most 2^26 = {MAX_GRID_POINTS} points"),
        ));
    }
    let (lx, ly) = match args.length.as_slice() {
        [l] => (*l, *l),
        [l, l2] => (*l, *l2),
        _ => {
            return Err(Error::invalid(
                "length",
                "(missing)",
                "give --length METRES [METRES]",
            ));
        }
    };
    let lc = || {
        args.correlation_length.ok_or_else(|| {
            Error::invalid(
                "correlation-length",
                "(missing)",
                "give --correlation-length METRES",
            )
        })
    };
    let spectrum = match args.spectrum.as_str() {
        "gaussian" => Spectrum::Gaussian {
            rms,
            correlation_length: lc()?,
        },
        "abc" => Spectrum::Abc {
            rms,
            correlation_length: lc()?,
            exponent: args.exponent,
            cutoff: (args.cutoff != 0.0).then_some(args.cutoff),
        },
        _ => {
            let q_nyq = std::f64::consts::PI * (nx as f64 / lx).min(ny as f64 / ly);
            Spectrum::SelfAffine {
                rms,
                hurst: args.hurst,
                q_low: args.q_low,
                q_roll: args.q_roll.unwrap_or(4.0 * std::f64::consts::PI / lx.max(ly)),
                q_high: args.q_high.unwrap_or(q_nyq),
            }
        }
    };
    spectrum.validate()?;
    Ok((spectrum, nx, ny, lx, ly))
}

/// Run `--generate-surface` (writing `out`) or `--analyze-surface`; the text to print.
///
/// # Errors
/// Bad options or files, as one-line [`Error`]s; nothing is written on error.
pub fn run(args: &SurfaceArgs, out: &Path) -> Result<String> {
    if args.generate_surface {
        let ext = out
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        if !matches!(ext.as_str(), "csv" | "txt" | "gsf") {
            return Err(Error::invalid(
                "out",
                out.display(),
                "give --out FILE.csv or FILE.gsf for --generate-surface",
            ));
        }
        let (spectrum, nx, ny, lx, ly) = generation_request(args)?;
        let map = generate(&spectrum, nx, ny, lx, ly, args.seed)?;
        if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(Error::file("creating the folder", dir))?;
        }
        write_height_map(&map, out)?;
        return Ok(format!("{}\n", out.display()));
    }
    if let Some(path) = &args.analyze_surface {
        let cutoff = parse_cutoff(&args.fit_cutoff)?;
        if args.list_channels {
            let (file, _) = super::formats::split_channel(path);
            return super::formats::list_channels(&file);
        }
        let (file, suffix) = super::formats::split_channel(path);
        let channel = args.channel.as_deref().or(suffix.as_deref());
        let measured = super::formats::read_measured(&file, channel)?;
        let text = measured.format == super::formats::Format::Text.name();
        if args.pixel_size.is_some() && !text {
            return Err(Error::Usage(format!(
                "--pixel-size does not apply to a {} map: its header gives the lengths",
                measured.format
            )));
        }
        let mut map = measured.into_height_map(&file, args.pixel_size, text)?;
        if args.periodic {
            map.periodic = true;
        }
        let largest = largest_height(&map);
        if args.remove_tilt {
            map.remove_tilt();
        } else {
            map.remove_mean();
        }
        if let Some(reason) = flat_map(&map, largest) {
            return Err(Error::data_file(path, 0, reason));
        }
        let r = report(&map, cutoff)?;
        if let Some(e) = &r.psd_fit_error {
            eprintln!("warning: {}: {e}", path.display());
        }
        let json =
            serde_json::to_string_pretty(&r).map_err(|e| Error::invalid("report", "json", e.to_string()))?;
        return Ok(format!("{json}\n"));
    }
    Err(Error::invalid(
        "surface",
        "(none)",
        "give --generate-surface or --analyze-surface FILE",
    ))
}
