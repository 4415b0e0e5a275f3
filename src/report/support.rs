//! The Markdown of a point correction's support ([`crate::fit::support`]): the range of
//! a = ln(H_EI/H_RI) of the fitted cases at each D, beyond which the correction fades to 0 over
//! [`FADE_WIDTH`] (coefficients to 5 significant digits, ready to copy).

use crate::fit::correction::Correction;
use crate::fit::support::FADE_WIDTH;
use crate::report::digits::sig5;
use std::fmt::Write;

/// The support table of `c`; nothing when the correction has no terms or no support.
pub fn support_table(md: &mut String, c: &Correction) {
    let Some(s) = c.support.as_ref().filter(|_| !c.terms.is_empty()) else {
        return;
    };
    let _ = writeln!(
        md,
        "The correction's support: C is multiplied by F = t((a - a_hi)/W) t((a_lo - a)/W), W = {}, \
         a_lo and a_hi linear in ln D between these nodes and held beyond them:\n",
        sig5(FADE_WIDTH)
    );
    let _ = writeln!(md, "| D | a_lo | a_hi |\n|---|---|---|");
    for ((d, lo), hi) in s.ln_d.iter().zip(&s.lo).zip(&s.hi) {
        let _ = writeln!(md, "| {} | {} | {} |", sig5(d.exp()), sig5(*lo), sig5(*hi));
    }
    md.push('\n');
}
