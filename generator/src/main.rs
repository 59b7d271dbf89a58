//! The `mingen` command line, one subcommand per file of `cli/`. Each returns a
//! `CliError`; `main` prints it on one line and exits with its code (2 for bad input).

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    match cli::run(cli::Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{}", e.message);
            ExitCode::from(e.code)
        }
    }
}
