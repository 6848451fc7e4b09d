//! `adhesion`: the terminal UI, or headless export with `--headless`.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = adhesion::cli::Cli::parse();
    let interactive = !(cli.headless || cli.list || cli.describe.is_some() || cli.print_preset.is_some());
    let result = if interactive {
        adhesion::tui::run()
    } else {
        adhesion::headless::run(&cli)
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
