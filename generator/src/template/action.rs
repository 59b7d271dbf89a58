//! The action: the linear form in the unknowns whose multiplication matrix on the quotient
//! ring the solver builds. Usually a single unknown; a combination with small integer
//! coefficients (exact mod p and in f64) when no single unknown separates the solutions;
//! or the inverse `1 / x_v` of an unknown (a Laurent action, Martyushev, Bhayani and
//! Pajdla, arXiv 2307.00320), on a basis whose monomials are all multiples of `x_v`.

use crate::algebra::{Fp, Monomial, Poly};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A linear form `sum_i c_i x_i` with integer coefficients (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Action {
    /// Coefficient of each unknown, in variable order.
    pub coefficients: Vec<i64>,
    /// Whether the action is the inverse `1 / x_v` of its single unknown `x_v` (then
    /// `coefficients` is the unit vector of `v`): multiplication by it maps a basis
    /// monomial `b` to `b / x_v`, so every basis monomial must be a multiple of `x_v`
    /// ([`Action::basis_for`]). Sound where `x_v` is non-zero on every solution, which
    /// the template proves: it reduces `b / x_v` for `b = x_v` onto `x_v B`, i.e. the
    /// relation `1 - x_v q ∈ I`.
    pub inverse: bool,
}

impl Action {
    /// The single unknown `x_v` of `nvars`.
    pub fn var(nvars: usize, v: usize) -> Action {
        let mut coefficients = vec![0; nvars];
        coefficients[v] = 1;
        Action {
            coefficients,
            inverse: false,
        }
    }
    /// The Laurent action `1 / x_v` of `nvars` unknowns.
    pub fn inverse_of_var(nvars: usize, v: usize) -> Action {
        Action {
            inverse: true,
            ..Action::var(nvars, v)
        }
    }
    /// A combination of the first `active` of `nvars` unknowns with coefficients drawn
    /// from `seed`: magnitudes 1..=9, random signs, the first coefficient 1 (a generic
    /// linear form, exact in f64); the other unknowns get 0.
    pub fn random(nvars: usize, active: usize, seed: u64) -> Action {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let coefficients = (0..nvars)
            .map(|i| {
                if i >= active {
                    0
                } else if i == 0 {
                    1
                } else {
                    let m = rng.gen_range(1..=9i64);
                    if rng.gen_bool(0.5) {
                        m
                    } else {
                        -m
                    }
                }
            })
            .collect();
        Action {
            coefficients,
            inverse: false,
        }
    }
    /// Number of unknowns.
    pub fn nvars(&self) -> usize {
        self.coefficients.len()
    }
    /// The variable, if the action is a single unknown with coefficient 1 (not its
    /// inverse): the eigenvalues are that unknown's values.
    pub fn single(&self) -> Option<usize> {
        if self.inverse {
            return None;
        }
        self.variable()
    }
    /// The variable `v` of a Laurent action `1 / x_v`.
    pub fn inverse_of(&self) -> Option<usize> {
        if self.inverse {
            self.variable()
        } else {
            None
        }
    }
    /// The single unknown with coefficient 1, inverted or not.
    fn variable(&self) -> Option<usize> {
        let nz: Vec<usize> = (0..self.nvars())
            .filter(|&i| self.coefficients[i] != 0)
            .collect();
        match nz[..] {
            [v] if self.coefficients[v] == 1 => Some(v),
            _ => None,
        }
    }
    /// Whether the action maps every monomial to one monomial with coefficient 1 (a single
    /// unknown or its inverse), so that a row of the action matrix is a unit vector or a
    /// negated template row.
    pub fn is_monomial(&self) -> bool {
        self.variable().is_some()
    }
    /// Whether `action * b` is a monomial (a polynomial one): always, but for a Laurent
    /// action `1 / x_v` and a `b` that is not a multiple of `x_v`.
    pub fn applies_to(&self, b: &Monomial) -> bool {
        self.inverse_of().map_or(true, |v| b.0[v] > 0)
    }
    /// The basis a template of this action is built on from the quotient basis `basis`:
    /// `basis` itself, except for a Laurent action `1 / x_v` when some monomial of it is
    /// not a multiple of `x_v`: then `x_v * basis` (a basis of the same quotient where
    /// `x_v` is non-zero on every solution; its unit is `x_v` times `basis`'s, see
    /// [`crate::template::basis_unit`]).
    pub fn basis_for(&self, basis: &[Monomial]) -> Vec<Monomial> {
        match self.inverse_of() {
            Some(v) if !basis.iter().all(|b| self.applies_to(b)) => {
                let x = Monomial::var(self.nvars(), v);
                basis.iter().map(|b| b.mul(&x)).collect()
            }
            _ => basis.to_vec(),
        }
    }
    /// The terms `(x_i b, c_i)` of `action * b`, in variable order, zero coefficients left
    /// out; for a Laurent action `1 / x_v`, the one term `(b / x_v, 1)`, none where `b`
    /// is not a multiple of `x_v` (see [`Action::applies_to`]).
    pub fn products<'a>(&'a self, b: &'a Monomial) -> impl Iterator<Item = (Monomial, i64)> + 'a {
        let inverse = self.inverse_of();
        self.coefficients
            .iter()
            .enumerate()
            .filter(move |(i, &c)| c != 0 && (inverse.is_none() || b.0[*i] > 0))
            .map(move |(i, &c)| {
                let x = Monomial::var(self.nvars(), i);
                match inverse {
                    Some(_) => (x.divide_into(b).expect("a multiple of x_v"), c),
                    None => (b.mul(&x), c),
                }
            })
    }
    /// The monomial `b / action` of a monomial action (a single unknown `x_v`: `b / x_v`;
    /// its inverse `1 / x_v`: `x_v b`), `None` for a linear form or where `b / x_v` is not a
    /// polynomial monomial: the other side of a basis monomial's relation in a pencil
    /// template (see [`crate::template::EliminationTemplate::flipped`]).
    pub fn inverse_product(&self, b: &Monomial) -> Option<Monomial> {
        let v = self.variable()?;
        let x = Monomial::var(self.nvars(), v);
        if self.inverse {
            Some(b.mul(&x))
        } else {
            x.divide_into(b)
        }
    }
    /// A coefficient as a residue mod P.
    pub fn residue<const P: u32>(c: i64) -> u32 {
        c.rem_euclid(P as i64) as u32
    }
    /// The action as a polynomial over Z_P; for a Laurent action `1 / x_v`, the
    /// polynomial `x_v` it inverts.
    pub fn poly<const P: u32>(&self) -> Poly<Fp<P>> {
        let n = self.nvars();
        Poly::from_terms(
            n,
            (0..n).filter(|&i| self.coefficients[i] != 0).map(|i| {
                (
                    Monomial::var(n, i),
                    Fp::<P>(Self::residue::<P>(self.coefficients[i])),
                )
            }),
        )
    }
    /// The form written with the unknowns' names, e.g. `t1`, `a1 - 3*a2 + 7*t3` or `1/t1`.
    pub fn display_with(&self, names: &[String]) -> String {
        if let Some(v) = self.inverse_of() {
            return format!("1/{}", Monomial::var(self.nvars(), v).display_with(names));
        }
        let mut s = String::new();
        for (i, &c) in self.coefficients.iter().enumerate() {
            if c == 0 {
                continue;
            }
            let name = Monomial::var(self.nvars(), i).display_with(names);
            let mag = c.unsigned_abs();
            let term = if mag == 1 {
                name
            } else {
                format!("{mag}*{name}")
            };
            if s.is_empty() {
                if c < 0 {
                    s.push('-');
                }
                s.push_str(&term);
            } else {
                s.push_str(if c < 0 { " - " } else { " + " });
                s.push_str(&term);
            }
        }
        if s.is_empty() {
            s.push('0');
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_render_and_multiply() {
        let names: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
        let a = Action {
            coefficients: vec![1, -3, 0],
            inverse: false,
        };
        assert_eq!(a.display_with(&names), "x - 3*y");
        assert_eq!(a.single(), None);
        assert_eq!(Action::var(3, 2).single(), Some(2));
        assert_eq!(Action::var(3, 2).display_with(&names), "z");
        let b = Monomial(vec![0, 1, 0]);
        let p: Vec<(Monomial, i64)> = a.products(&b).collect();
        assert_eq!(
            p,
            vec![(Monomial(vec![1, 1, 0]), 1), (Monomial(vec![0, 2, 0]), -3)]
        );
        let r = Action::random(4, 4, 7);
        assert_eq!(r.coefficients[0], 1);
        assert!(r.coefficients.iter().all(|&c| c != 0 && c.abs() <= 9));
        assert_eq!(r, Action::random(4, 4, 7));
        assert_eq!(Action::random(4, 3, 7).coefficients[3], 0);
        assert_eq!(Action::residue::<7>(-3), 4);
        // 1/y: b / y on multiples of y, the basis shifted by y otherwise.
        let inv = Action::inverse_of_var(3, 1);
        assert_eq!(inv.display_with(&names), "1/y");
        assert_eq!((inv.single(), inv.inverse_of()), (None, Some(1)));
        let p: Vec<(Monomial, i64)> = inv.products(&Monomial(vec![1, 2, 0])).collect();
        assert_eq!(p, vec![(Monomial(vec![1, 1, 0]), 1)]);
        assert!(!inv.applies_to(&Monomial(vec![1, 0, 0])));
        assert_eq!(inv.products(&Monomial(vec![1, 0, 0])).count(), 0);
        let basis = vec![Monomial(vec![1, 0, 0]), Monomial(vec![0, 0, 0])];
        assert_eq!(
            inv.basis_for(&basis),
            vec![Monomial(vec![1, 1, 0]), Monomial(vec![0, 1, 0])]
        );
        let shifted = inv.basis_for(&basis);
        assert_eq!(inv.basis_for(&shifted), shifted);
        // The other side of a relation: y b for 1/y, b / y for y, none for a form.
        let b = Monomial(vec![1, 1, 0]);
        assert_eq!(inv.inverse_product(&b), Some(Monomial(vec![1, 2, 0])));
        assert_eq!(
            Action::var(3, 1).inverse_product(&b),
            Some(Monomial(vec![1, 0, 0]))
        );
        assert_eq!(Action::var(3, 2).inverse_product(&b), None);
        assert_eq!(a.inverse_product(&b), None);
    }
}
