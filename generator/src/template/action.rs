//! The action: the linear form in the unknowns whose multiplication matrix on the quotient
//! ring the solver builds. Usually a single unknown; a combination with small integer
//! coefficients (exact mod p and in f64) when no single unknown separates the solutions.

use crate::algebra::{Fp, Monomial, Poly};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A linear form `sum_i c_i x_i` with integer coefficients (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Action {
    /// Coefficient of each unknown, in variable order.
    pub coefficients: Vec<i64>,
}

impl Action {
    /// The single unknown `x_v` of `nvars`.
    pub fn var(nvars: usize, v: usize) -> Action {
        let mut coefficients = vec![0; nvars];
        coefficients[v] = 1;
        Action { coefficients }
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
        Action { coefficients }
    }
    /// Number of unknowns.
    pub fn nvars(&self) -> usize {
        self.coefficients.len()
    }
    /// The variable, if the action is a single unknown with coefficient 1.
    pub fn single(&self) -> Option<usize> {
        let nz: Vec<usize> = (0..self.nvars())
            .filter(|&i| self.coefficients[i] != 0)
            .collect();
        match nz[..] {
            [v] if self.coefficients[v] == 1 => Some(v),
            _ => None,
        }
    }
    /// The terms `(x_i b, c_i)` of `action * b`, in variable order, zero coefficients left
    /// out.
    pub fn products<'a>(&'a self, b: &'a Monomial) -> impl Iterator<Item = (Monomial, i64)> + 'a {
        self.coefficients
            .iter()
            .enumerate()
            .filter(|(_, &c)| c != 0)
            .map(move |(i, &c)| (b.mul(&Monomial::var(self.nvars(), i)), c))
    }
    /// A coefficient as a residue mod P.
    pub fn residue<const P: u32>(c: i64) -> u32 {
        c.rem_euclid(P as i64) as u32
    }
    /// The action as a polynomial over Z_P.
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
    /// The form written with the unknowns' names, e.g. `t1` or `a1 - 3*a2 + 7*t3`.
    pub fn display_with(&self, names: &[String]) -> String {
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
    }
}
