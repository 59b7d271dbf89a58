//! Laurent equations: reciprocals of unknowns in the tape, and the shifts that clear them.

use super::*;

/// The reciprocals of unknowns in the tape and, per scalar equation, the monomial that
/// clears its negative exponents. Evaluation runs the tape with one extra variable per
/// inverted unknown (`1/x_i` as a variable `y_j`), then folds each term `x^e y^f` to
/// `x^(e - f + s)` with the equation's shift `s`: the smallest exponents that make every
/// term of the equation a monomial (found from the equation's support on two random
/// instances mod p, where a coefficient vanishes by accident with probability about
/// 1/p). The shifted equation has the solutions of the Laurent equation with every
/// inverted unknown non-zero, and may have more where one vanishes (`nonzero x` removes
/// those).
#[derive(Clone, Debug, Default)]
pub(super) struct Laurent {
    /// The unknowns with a reciprocal in the tape (flat indices, increasing); the extra
    /// variable `n + j` stands for `1 / x_inverted[j]`.
    pub(super) inverted: Vec<usize>,
    /// Per scalar equation, the exponent of each unknown in its shift monomial.
    pub(super) shifts: Vec<Vec<Exponent>>,
}

impl Laurent {
    /// The polynomial in `n + inverted.len() + rest` variables (unknowns, reciprocals, any
    /// others) as a polynomial in `n + rest` variables, multiplied by the shift of
    /// equation `eq`. Exponents that the shift does not clear (a term outside the support
    /// the shift was found on) are clamped at zero.
    pub(super) fn fold<C: Ring>(&self, p: Poly<C>, n: usize, eq: usize) -> Poly<C> {
        let k = self.inverted.len();
        if k == 0 {
            return p;
        }
        let shift = self.shifts.get(eq);
        let total = p.nvars();
        let mut out: BTreeMap<Monomial, C> = BTreeMap::new();
        for (m, c) in p.terms() {
            let mut e: Vec<Exponent> = Vec::with_capacity(total - k);
            for i in 0..n {
                let s = shift.and_then(|s| s.get(i)).copied().unwrap_or(0);
                let neg = self
                    .inverted
                    .iter()
                    .position(|&v| v == i)
                    .map_or(0, |j| m.0[n + j]);
                e.push((m.0[i] + s).saturating_sub(neg));
            }
            e.extend_from_slice(&m.0[n + k..]);
            let key = Monomial(e);
            match out.get_mut(&key) {
                Some(acc) => *acc = acc.add(c),
                None => {
                    out.insert(key, c.clone());
                }
            }
        }
        Poly::from_terms(total - k, out.into_iter().filter(|(_, c)| !c.is_zero()))
    }

    /// The shift of each equation from the raw (unfolded) equations of some instances:
    /// per unknown, the largest excess of its reciprocal's exponent over its own.
    pub(super) fn shifts_from<C: Ring>(&mut self, n: usize, instances: &[Vec<Poly<C>>]) {
        let count = instances.first().map_or(0, Vec::len);
        self.shifts = (0..count)
            .map(|eq| {
                let mut s = vec![0 as Exponent; n];
                for polys in instances {
                    let Some(p) = polys.get(eq) else { continue };
                    for (m, _) in p.terms() {
                        for (j, &v) in self.inverted.iter().enumerate() {
                            let excess = m.0[n + j].saturating_sub(m.0[v]);
                            s[v] = s[v].max(excess);
                        }
                    }
                }
                s
            })
            .collect();
    }
}
