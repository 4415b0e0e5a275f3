use clap::Parser;

fn main() {
    std::process::exit(ehlmap::cli::run(&ehlmap::cli::Cli::parse()));
}
