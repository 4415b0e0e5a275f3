//! Martin's closed form for the rigid-isoviscous line contact (Reynolds exit condition):
//! H_c = H_min = 2.4475/M, and the flux thickness 3/M at the pressure maximum.

use crate::solve::solution::Solution;
use crate::solve::solution::{ModelUsed, Outputs};
use crate::solve::{SolveInfo, Status};

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
        h_c: h,
        h_c_pmax: MARTIN_FLUX / m,
        h_min: h,
        x_min: 0.0,
        y_min: None,
        d: None,
        k: None,
        p_max: f64::NAN,
        spike: None,
        h0: h,
        f: f64::NAN,
        load_error: 0.0,
        status: Status::Converged,
        reason: reason.clone(),
        grid: 0,
        levels: 0,
        level: None,
        model_used: ModelUsed::ClosedForm,
        work_units: 0.0,
        wall_s: 0.0,
        algebraic_error: Some(0.0),
        h_c_err: Some(0.0),
        h_min_err: Some(0.0),
        error_estimate: Some(0.0),
        accuracy_met: Some(true),
        mixed: None,
    };
    let info = SolveInfo {
        status: Status::Converged,
        reason,
        history: vec![],
        work_units: 0.0,
        wall_s: 0.0,
        grid: 0,
        levels: 0,
        algebraic_error: Some(0.0),
        discretisation_error: Some(0.0),
    };
    Solution {
        outputs,
        info,
        profile: None,
        attempt: 1,
        fields: None,
    }
}
