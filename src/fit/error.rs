//! The fit layer's error: why a dataset could not be read for a fit, or a law not fitted.

/// Why a fit could not be made; the message names the data or the film.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Fewer usable points than free parameters (plus one).
    #[error("{points} usable points for {params} parameters: too few to fit")]
    TooFewPoints {
        /// Usable data points.
        points: usize,
        /// Free parameters.
        params: usize,
    },
    /// A film, M or L that is not positive and finite.
    #[error("data contain a non-positive or non-finite value")]
    BadData,
    /// The fitted law is not finite on the data.
    #[error("the fitted model is not finite on the data")]
    NotFinite,
    /// A film's fit failed: the contact and the film, and why.
    #[error("{contact} {film}: {source}")]
    Film {
        /// "line" or "point".
        contact: String,
        /// H_c, H_pm or H_min.
        film: &'static str,
        /// Why.
        source: Box<FitError>,
    },
    /// No converged case in the datasets.
    #[error(
        "no converged cases in {datasets} ({failed} failed rows, {excluded} excluded for an \
         error estimate above 2 %): nothing to fit"
    )]
    NoCases {
        /// The dataset directories, comma-separated.
        datasets: String,
        /// Failed rows.
        failed: usize,
        /// Rows left out for their error estimate.
        excluded: usize,
    },
    /// No contact has enough converged cases for its law.
    #[error("too few converged cases to fit: line {line}; point {point}")]
    TooFewCases {
        /// Why the line contact was skipped.
        line: String,
        /// Why the point contact was skipped.
        point: String,
    },
    /// A dataset could not be read.
    #[error("{0}")]
    Dataset(String),
}
