//! Every chart and picture: fit charts ([`charts`], [`charts_map`]) and the pressure and film
//! pictures of one solve ([`pictures`], [`contour`]).

pub mod bench_charts;
pub mod charts;
pub mod charts_map;
pub mod contour;
pub mod pictures;
pub mod regime_map;
pub mod style;
