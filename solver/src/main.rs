//! The `rspose` command line: simulate pairs, estimate poses, run the paper's experiments.
//!
//! Exit codes: 0 success; 2 bad input (unreadable or malformed file, invalid option, too few
//! matches, ...), with one line on stderr naming what and where; 1 when valid input has no
//! answer (e.g. every RANSAC hypothesis failed).

mod cli;

use clap::Parser;

fn main() {
    let args = match cli::Cli::try_parse() {
        Ok(args) => args,
        // Help and version go to stdout with exit 0, as clap prints them.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprintln!("rspose: {}", cli::usage_error_line(&e.render().to_string()));
            std::process::exit(2);
        }
    };
    match cli::run(args) {
        Ok(()) => {}
        Err(e) => {
            eprintln!("rspose: {}", e.message);
            std::process::exit(e.code);
        }
    }
}
