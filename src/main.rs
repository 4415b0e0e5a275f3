use clap::Parser;
use ehlmap::cli::{run_solve, Cli, Command};

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Solve(a) => run_solve(a),
        Command::Sweep(a) => ehlmap::cli::sweep::run_sweep(a),
        Command::Fit(a) => ehlmap::cli::fit::run_fit(a),
        Command::Case(a) => ehlmap::cli::run_case(a),
        Command::Bench(a) => ehlmap::cli::bench::run_bench(a),
        Command::Stability(a) => ehlmap::cli::bench::run_stability(a),
        Command::Chart(a) => ehlmap::model::regimes::run_chart(a),
    };
    match result {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("ehlmap: {}", e.0);
            std::process::exit(2);
        }
    }
}
