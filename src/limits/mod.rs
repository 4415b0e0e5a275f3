//! The asymptote limit solves: the solver's own rigid, isoviscous and piezoviscous limits that
//! the fitted laws are checked against.

pub mod line_ep;
pub mod rigid_d_factor;
pub mod rigid_point;
pub mod rigid_rp;
pub mod solves;
