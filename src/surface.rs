//! Random rough surfaces (appendices B and C, section 3.2.2): generation, spectra, spectral
//! moments, Nayak statistics, and import/export of height maps.
//!
//! - [`spectrum`]: the PSD models (C.1.3), (3.16) and self-affine, their moments (3.8), Nayak's
//!   α, the asperity density (3.9), and the PDFs (3.7), (3.11);
//! - [`height_map`]: the sampled surface;
//! - [`generate`]: FFT filtering of white noise (appendix C.1);
//! - [`analysis`]: discrete PSD (B.1.8)-(B.1.10) and moments of a map.
//!
//! All lengths are SI metres; PSDs follow the convention m0 = σ_rms² of (3.8).

pub mod analysis;
pub mod generate;
pub mod height_map;
pub mod spectrum;

pub use analysis::{moments_of_map, periodogram, psd_2d};
pub use generate::{generate, wavenumber};
pub use height_map::HeightMap;
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
}
