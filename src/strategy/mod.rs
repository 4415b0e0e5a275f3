//! How a case is solved: Richardson accuracy estimates ([`accuracy`]) on the grids of an
//! accuracy target's ladder ([`grid_ladder`]), the cheapest adequate
//! model for a target ([`select`], with the slender-ellipse line model of [`slender`], and a
//! fitted film formula where its held-out errors allow, [`formula`]) and warm starts from a
//! neighbouring case ([`warm`]).

pub mod accuracy;
pub mod closed_form;
pub mod formula;
pub mod grid_ladder;
pub mod select;
pub mod slender;
pub mod solve_case;
pub mod warm;
