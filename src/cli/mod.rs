//! The command line: a thin layer over the library, one file per subcommand. Bad input exits
//! with code 2 and a one-line message naming the bad value ([`error::InputError`]); a solve that
//! fails numerically still prints its outputs with its status (exit code 0: a failure is a
//! result), so scripts read `status`. This is the only module that parses arguments, prints or
//! chooses exit codes.

pub mod bench;
pub mod case;
pub mod chart;
pub mod error;
pub mod fit;
pub mod output;
pub mod solve;
pub mod sweep;

use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "ehlmap",
    version,
    about = "Steady isothermal EHL by full multigrid"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve one contact and print its film thickness, pressure and convergence.
    Solve(solve::SolveArgs),
    /// Run a sweep spec (TOML) into a Parquet dataset: resumable, shardable.
    Sweep(sweep::SweepArgs),
    /// Fit a Moes-style film formula to sweep datasets; report, fit.json and charts.
    Fit(fit::FitArgs),
    /// A dimensional case (SI units in a TOML file): groups, numerical solve, published formulas.
    Case(case::CaseArgs),
    /// Speed against accuracy of every method over a grid ladder (Parquet table and charts).
    Bench(bench::BenchArgs),
    /// Where methods fail: each method's status over an (M, L) map.
    Stability(bench::StabilityArgs),
    /// Charts: `regimes`, the regime map in Moes' (M, L) axes.
    Chart(chart::ChartArgs),
}

/// Run a parsed command line; returns the process exit code (bad input: printed, code 2).
pub fn run(cli: &Cli) -> i32 {
    let result = match &cli.command {
        Command::Solve(a) => solve::run_solve(a),
        Command::Sweep(a) => sweep::run_sweep(a),
        Command::Fit(a) => fit::run_fit(a),
        Command::Case(a) => case::run_case(a),
        Command::Bench(a) => bench::run_bench(a),
        Command::Stability(a) => bench::run_stability(a),
        Command::Chart(a) => chart::run_chart(a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("ehlmap: {e}");
            error::InputError::EXIT_CODE
        }
    }
}
