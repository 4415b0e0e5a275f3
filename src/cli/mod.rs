//! The command line: a thin layer over the library, one file per subcommand. Every failure is
//! a [`CliError`] printed as one line `ehlmap: message` naming the input, with the exit code of
//! the table in [`error`] and docs/cli.md (2 bad input, 1 I/O error); a solve that fails
//! numerically still prints its outputs with its status (exit code 0: a failure is a result),
//! so scripts read `status`. Stdout is written through [`output::write_stdout`]: a reader that
//! closes it early stops the command quietly (exit code 0), never a panic. This is the only
//! module that parses arguments, prints or chooses exit codes.

pub mod anchor_arg;
pub mod bench;
pub mod case;
pub mod chart;
pub mod error;
pub mod fit;
pub mod formula_arg;
pub mod limits;
pub mod mixed;
pub mod output;
pub mod solve;
pub mod solve_args;
pub mod solve_progress;
pub mod summary;
pub mod sweep;

use clap::{Parser, Subcommand};
use error::CliError;
use output::note;

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
    Solve(Box<solve_args::SolveArgs>),
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
    /// Mixed lubrication: film and asperity load against Lambda from datasets with a sigma axis.
    Mixed(mixed::MixedArgs),
}

/// Parse the process's arguments and run the command; returns the exit code. A command-line
/// error of the parser is one line `ehlmap: message` with exit code 2, like every bad input;
/// `--help` and `--version` print to stdout (a closed stdout is ignored) and exit 0.
pub fn main() -> i32 {
    match Cli::try_parse() {
        Ok(cli) => run(&cli),
        Err(e) => parse_error(&e),
    }
}

/// The parser's error as the exit code and one line on stderr (help and version: their text).
fn parse_error(e: &clap::Error) -> i32 {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            error::EXIT_OK
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            error::EXIT_INPUT
        }
        _ => {
            note!("ehlmap: {}", one_line(&e.render().to_string()));
            error::EXIT_INPUT
        }
    }
}

/// The parser's message on one line: without the `error:` prefix, the usage and the `--help`
/// hint; its other lines (possible values, the missing arguments) joined.
fn one_line(text: &str) -> String {
    let mut parts = vec![];
    for line in text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with("For more information") {
            continue;
        }
        if line.starts_with("Usage:") {
            break;
        }
        parts.push(
            line.strip_prefix("error:")
                .unwrap_or(line)
                .trim()
                .to_string(),
        );
    }
    parts.join(" ")
}

/// Run a parsed command line; returns the process exit code (an error is printed as one line
/// on stderr; a closed stdout ends the command quietly).
pub fn run(cli: &Cli) -> i32 {
    let result = match &cli.command {
        Command::Solve(a) => solve::run_solve(a),
        Command::Sweep(a) => sweep::run_sweep(a),
        Command::Fit(a) => fit::run_fit(a),
        Command::Case(a) => case::run_case(a),
        Command::Bench(a) => bench::run_bench(a),
        Command::Stability(a) => bench::run_stability(a),
        Command::Chart(a) => chart::run_chart(a),
        Command::Mixed(a) => mixed::run_mixed(a),
    };
    match result {
        Ok(()) => error::EXIT_OK,
        Err(CliError::Closed) => error::EXIT_CLOSED,
        Err(e) => {
            note!("ehlmap: {e}");
            e.exit_code()
        }
    }
}
