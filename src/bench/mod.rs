//! Speed against accuracy, and where methods fail (line contacts).
//!
//! [`speed`] runs every method on reference cases over a ladder of grids, times them (median of
//! repeats) and measures the error of H_c and H_min against a Richardson extrapolation of the
//! two finest multigrid solutions; [`stability`] classifies each method's outcome over an (M, L)
//! map. Both write a Parquet table and charts. [`selection`] measures what model selection and
//! accuracy targets save on a sweep spec (`ehlmap bench --selection SPEC`).

pub mod selection;
pub mod speed;
pub mod stability;
