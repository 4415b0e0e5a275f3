//! `--formula FIT` of `solve`, `case` and `sweep`: the fit report read as a formula that may
//! answer a case ([`ehlmap::strategy::formula`]); a file that cannot be read or is no usable fit
//! report is bad input naming the option.

use crate::cli::error::{input, CliError};
use ehlmap::report::surrogate::FittedFormula;
use ehlmap::report::FitReport;
use ehlmap::strategy::formula::FormulaRef;
use std::path::Path;

/// The formula of the fit report at `path` (`fit.json`, or a report directory holding one),
/// kept for the rest of the run; bad input names `flag`.
pub(crate) fn formula_arg(flag: &str, path: &Path) -> Result<FormulaRef, CliError> {
    let file = if path.is_dir() {
        path.join("fit.json")
    } else {
        path.to_path_buf()
    };
    let shown = file.display().to_string();
    let text = std::fs::read_to_string(&file)
        .map_err(|e| input(format!("{flag} {shown}: cannot read it: {e}")))?;
    let report: FitReport = serde_json::from_str(&text).map_err(|e| {
        input(format!(
            "{flag} {shown}: not a fit report (fit.json of `ehlmap fit`): {e}"
        ))
    })?;
    let formula =
        FittedFormula::from_report(&report, &shown).map_err(|e| input(format!("{flag} {e}")))?;
    Ok(FormulaRef::leak(formula))
}
