//! `adhesion`: the terminal UI, or headless export with `--headless`.

use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match adhesion::cli::parse(std::env::args_os()) {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help, --version: a failed write to stdout is an error, as for every output.
            use std::io::Write;
            let printed = e.print().and_then(|()| std::io::stdout().flush());
            return match printed {
                Ok(()) => ExitCode::SUCCESS,
                Err(cause) => {
                    eprintln!("error: writing to standard output: {cause}");
                    ExitCode::FAILURE
                }
            };
        }
        Err(e) => {
            eprintln!("{}", adhesion::cli::one_line(&e));
            return ExitCode::from(2);
        }
    };
    let interactive = !(cli.headless || cli.list || cli.describe.is_some() || cli.print_preset.is_some());
    let result = if !interactive && let Some(file) = &cli.file {
        Err(anyhow::anyhow!(
            "{}: a file argument opens the terminal UI; with --headless fit it with --fit FILE",
            file.display()
        ))
    } else if interactive && let Some(first) = cli.given.iter().find(|g| *g != "file") {
        Err(anyhow::anyhow!(
            "--{} needs --headless (without options, adhesion starts the terminal UI)",
            first.replace('_', "-")
        ))
    } else if interactive {
        adhesion::tui::run(cli.file.as_deref())
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
