//! The `ehlmap` command: [`cli`] parses the arguments and runs a subcommand over the library.

mod cli;

fn main() {
    std::process::exit(cli::main());
}
