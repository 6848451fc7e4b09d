//! `adhesion`: the terminal UI, or headless export with `--headless`.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli =
        match adhesion::cli::Cli::try_parse_from(adhesion::cli::join_negative_values(std::env::args_os())) {
            Ok(cli) => cli,
            Err(e) if !e.use_stderr() => {
                // --help, --version.
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            Err(e) => {
                eprintln!("{}", adhesion::cli::one_line(&e));
                return ExitCode::from(2);
            }
        };
    let interactive = !(cli.headless || cli.list || cli.describe.is_some() || cli.print_preset.is_some());
    let result = if interactive {
        adhesion::tui::run()
    } else {
        adhesion::headless::run(&cli)
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            let text = format!("{e:#}");
            eprintln!("error: {}", adhesion::params::escape_for_message(&text, 2000));
            ExitCode::FAILURE
        }
    }
}
