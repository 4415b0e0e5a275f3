//! Speed against accuracy, and where methods fail (line contacts).
//!
//! [`speed`] runs every method on reference cases over a ladder of grids, times them (median of
//! repeats) and measures the error of H_c and H_min against a Richardson extrapolation of the
//! two finest multigrid solutions; [`stability`] classifies each method's outcome over an (M, L)
//! map. Both write a Parquet table and charts. [`selection`] measures what model selection and
//! accuracy targets save on a sweep spec (`ehlmap bench --selection SPEC`). [`box_map`] solves
//! the whole box of line and point cases as a user's default would, with a time limit per case
//! (`ehlmap stability --box`).

pub mod box_map;
pub mod selection;
pub mod speed;
pub mod stability;
