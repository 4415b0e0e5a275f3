//! Every chart and picture: fit charts ([`charts`], [`charts_map`], the held-out
//! [`validity_map`]), the regime map in (M, L)
//! ([`regime_map`]), the bench charts ([`bench_charts`]) and the pressure and film pictures of
//! one solve ([`pictures`], [`contour`]); [`style`] holds the font, colours and helpers they
//! share.

pub mod bench_charts;
pub mod charts;
pub mod charts_map;
pub mod contour;
pub mod mixed_map;
pub mod pictures;
pub mod regime_map;
pub mod style;
pub mod validity_map;
