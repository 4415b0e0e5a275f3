//! The `ehlmap` command: [`cli`] parses the arguments and runs a subcommand over the library.

mod cli;

use clap::Parser;

fn main() {
    std::process::exit(cli::run(&cli::Cli::parse()));
}
