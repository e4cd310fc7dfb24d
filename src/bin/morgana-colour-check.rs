//! Reads a colour-check request (JSON) on stdin and prints morgana's answer (JSON) on stdout;
//! used by `scripts/colour_check.py`. See [`morgana::cli::colour_check`] for the protocol.

use std::io::Read;
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut request = String::new();
    if let Err(e) = std::io::stdin().read_to_string(&mut request) {
        eprintln!("morgana-colour-check: cannot read the request from stdin: {e}");
        return ExitCode::FAILURE;
    }
    match morgana::cli::colour_check::run(&request) {
        Ok(answer) => {
            println!("{answer}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("morgana-colour-check: {e}");
            ExitCode::FAILURE
        }
    }
}
