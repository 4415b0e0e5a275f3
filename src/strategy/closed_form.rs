//! Martin's closed form for the rigid-isoviscous line contact (Reynolds exit condition):
//! H_c = H_min = 2.4475/M, and the flux thickness 3/M at the pressure maximum.

use crate::solve::solution::Solution;
use crate::solve::solution::{ModelUsed, Outputs};

/// Martin's rigid-isoviscous line film at X = 0 (Reynolds exit condition), times M.
pub const MARTIN_CENTRAL: f64 = 2.4475;
/// The rigid-isoviscous flux thickness (the film where dP/dX = 0), times M.
pub const MARTIN_FLUX: f64 = 3.0;

/// The closed-form rigid-isoviscous line answer (no discretisation error: its estimate is 0
/// until the model selection adds the neglected effect).
pub fn closed_form_line(m: f64) -> Solution {
    let reason = "closed form: rigid-isoviscous line contact, H_c = H_min = 2.4475/M (Martin, \
                  Reynolds exit condition)"
        .to_string();
    let h = MARTIN_CENTRAL / m;
    let outputs = Outputs {
        x_min: 0.0,
        h0: h,
        load_error: 0.0,
        ..Outputs::without_solve(ModelUsed::ClosedForm, [h, MARTIN_FLUX / m, h], reason)
    };
    Solution::without_solve(outputs, Some(0.0))
}
