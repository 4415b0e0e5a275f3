//! The asymptote limit solves: the solver's own rigid, isoviscous and piezoviscous limits that
//! the fitted laws are checked against; the point elastic-isoviscous solve a decade of M beyond
//! the data ([`beyond`]); the anchors of the point approach factor half a decade beyond it
//! ([`anchors`]); and the solves that place the point H_c corner ([`jump`]).

pub mod anchors;
pub mod beyond;
pub mod jump;
pub mod line_ep;
pub mod point_ei;
pub mod rigid_d_factor;
pub mod rigid_point;
pub mod rigid_rp;
pub mod solves;
