//! Random rough surfaces (appendices B and C, section 3.2.2): generation, spectra, spectral
//! moments, Nayak statistics, and import/export of height maps.
//!
//! - [`spectrum`]: the PSD models (C.1.3), (3.16) and self-affine, their moments (3.8), Nayak's
//!   α, the asperity density (3.9), and the PDFs (3.7), (3.11);
//! - [`height_map`]: the sampled surface;
//! - [`generate`]: FFT filtering of white noise (appendix C.1);
//! - [`analysis`]: discrete PSD (B.1.8)-(B.1.10), autocorrelation, moments and peaks of a map;
//! - [`psd_fit`]: least-squares fit of (3.16) to an isotropic PSD;
//! - [`io`]: text matrix and Gwyddion `.gsf` import/export;
//! - [`formats`]: readers of instrument and exchange files (recognised by content).
//!
//! All lengths are SI metres; PSDs follow the convention m0 = σ_rms² of (3.8).

pub mod analysis;
pub mod command;
pub mod formats;
pub mod generate;
pub mod height_map;
pub mod io;
pub mod psd_fit;
pub mod spectrum;

pub use analysis::{
    PeakStatistics, RadialPsd, autocorrelation, hann, moments_of_map, peak_statistics, peaks, periodogram,
    psd_2d, radial_model, radial_psd, radial_psd_and_moments,
};
pub use generate::{generate, wavenumber};
pub use height_map::HeightMap;
pub use io::{read_height_map, write_height_map};
pub use psd_fit::{AbcFit, Cutoff, fit_abc};
pub use spectrum::{
    Moments, PreparedSpectrum, Spectrum, moments_of_psd, nayak_c1, nayak_c2, nayak_curvature_pdf,
    nayak_joint_pdf,
};

/// Options of the surface commands (flattened into [`crate::cli::Cli`]).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct SurfaceArgs {
    /// Generate a random rough surface and write it to --out FILE.csv|FILE.gsf (with --headless).
    #[arg(long)]
    pub generate_surface: bool,
    /// PSD of the generated surface: gaussian (C.1.3), abc (3.16) or self-affine.
    #[arg(long, value_name = "KIND", default_value = "gaussian", value_parser = ["gaussian", "abc", "self-affine"])]
    pub spectrum: String,
    /// RMS height σ_rms of the generated surface [m].
    #[arg(long, allow_negative_numbers = true, value_name = "M")]
    pub rms: Option<f64>,
    /// Correlation length L_c [m] (gaussian, abc).
    #[arg(long, allow_negative_numbers = true, value_name = "M")]
    pub correlation_length: Option<f64>,
    /// Grid points N [M] in x [and y] (M = N if omitted).
    #[arg(long, value_name = "N", num_args = 1..=2)]
    pub size: Vec<usize>,
    /// Period L [L2] in x [and y] [m] (L2 = L if omitted).
    #[arg(long, allow_negative_numbers = true, value_name = "M", num_args = 1..=2)]
    pub length: Vec<f64>,
    /// Power-law index n of (3.16) (abc).
    #[arg(long, value_name = "N", default_value_t = 3.28)]
    pub exponent: f64,
    /// Cut-off wavenumber q0 of (3.16) [1/m] (abc; 0 for none).
    #[arg(long, value_name = "1/M", default_value_t = 1.0e8)]
    pub cutoff: f64,
    /// Hurst exponent H (self-affine).
    #[arg(long, value_name = "H", default_value_t = 0.8)]
    pub hurst: f64,
    /// Lower cut-off wavenumber [1/m] (self-affine).
    #[arg(long, value_name = "1/M", default_value_t = 0.0)]
    pub q_low: f64,
    /// Roll-off wavenumber [1/m] (self-affine).
    #[arg(long, value_name = "1/M")]
    pub q_roll: Option<f64>,
    /// Upper cut-off wavenumber [1/m] (self-affine; default the grid's Nyquist wavenumber).
    #[arg(long, value_name = "1/M")]
    pub q_high: Option<f64>,
    /// Seed of the random generator (same seed, same surface).
    #[arg(long, value_name = "SEED", default_value_t = 1)]
    pub seed: u64,
    /// Print the statistics of a height map as JSON (with --headless): text matrix or xyz,
    /// .gsf, .gwy, .x3p, .sdf, .sur, Asylum .ibw, Nanoscope .di/.spm, .mi, .al3d, Nanosurf .nid,
    /// Sensofar .plu, Zygo MetroPro .dat, Bruker .opd/.opdx (format from the content).
    #[arg(long, value_name = "FILE")]
    pub analyze_surface: Option<std::path::PathBuf>,
    /// Channel of a height-map file holding several (by name; see --list-channels), for
    /// --analyze-surface and for --surface of a scene (also written FILE#CHANNEL).
    #[arg(long, value_name = "NAME")]
    pub channel: Option<String>,
    /// List the channels of the --analyze-surface FILE (name, grid, size, units) instead of
    /// analysing it.
    #[arg(long)]
    pub list_channels: bool,
    /// Pixel size of a text height map [m] (square pixels).
    #[arg(long, allow_negative_numbers = true, value_name = "M")]
    pub pixel_size: Option<f64>,
    /// Analyse the map as one period of a periodic surface (plain FFT, peaks wrap around); by
    /// default an imported map is a finite patch, windowed before its FFT.
    #[arg(long)]
    pub periodic: bool,
    /// Subtract the least-squares plane before analysing.
    #[arg(long)]
    pub remove_tilt: bool,
    /// Cut-off q0 of the (3.16) fit: a value [1/m] held fixed, `free`, or `none`.
    #[arg(long, value_name = "Q0|free|none", default_value = "1e8")]
    pub fit_cutoff: String,
    /// Height map for scene fig3.7d (with --figure fig3.7d; sets its `surface` parameter).
    #[arg(long, value_name = "FILE")]
    pub surface: Option<std::path::PathBuf>,
}
