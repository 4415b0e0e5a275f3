//! The case as a user states it: Moes' parameters and their Hertzian scaling ([`case`]), the
//! lubricant's viscosity and density laws ([`lubricant`]), the Hertz ellipse ([`hertz`]), the
//! published film formulas ([`formulas`]), oils by their Walther line ([`oils`]) and the
//! textbook regime classification ([`regimes`]).

pub mod asperity;
pub mod case;
pub mod case_file;
pub mod dimensional;
pub mod error;
pub mod flow_factors;
pub mod formulas;
pub mod gt_table;
pub mod hertz;
pub mod lubricant;
pub mod oils;
pub mod regimes;
pub mod roughness;
