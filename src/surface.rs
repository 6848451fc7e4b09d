//! Random rough surfaces (appendices B and C, section 3.2.2): generation, spectra, spectral
//! moments, Nayak statistics, and import/export of height maps.

/// Options of the surface commands (flattened into [`crate::cli::Cli`]).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct SurfaceArgs {
    /// Generate a random rough surface and write it to --out FILE.csv|FILE.gsf (with --headless).
    #[arg(long)]
    pub generate_surface: bool,
}
