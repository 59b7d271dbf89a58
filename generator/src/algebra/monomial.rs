//! Monomials as exponent vectors, and monomial orders.

use std::cmp::Ordering;
use std::fmt;

/// The exponent of one variable in a monomial.
pub type Exponent = u16;

/// A monomial x_0^e_0 * x_1^e_1 * ... as its exponent vector, one entry per variable
/// of the polynomial ring it belongs to.
///
/// The derived `Ord` is plain lexicographic on the exponent vector (x_0 > x_1 > ...);
/// it serves as a storage order. Algorithms that depend on a term order take a
/// [`MonomialOrder`] explicitly.
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Monomial(pub Vec<Exponent>);

impl Monomial {
    /// The monomial 1 in `nvars` variables.
    pub fn one(nvars: usize) -> Self {
        Monomial(vec![0; nvars])
    }
    /// The variable x_i in `nvars` variables.
    pub fn var(nvars: usize, i: usize) -> Self {
        let mut e = vec![0; nvars];
        e[i] = 1;
        Monomial(e)
    }
    /// Number of variables of the ring.
    pub fn nvars(&self) -> usize {
        self.0.len()
    }
    /// Total degree.
    pub fn degree(&self) -> u32 {
        self.0.iter().map(|&e| e as u32).sum()
    }
    /// Whether this is the monomial 1.
    pub fn is_one(&self) -> bool {
        self.0.iter().all(|&e| e == 0)
    }
    /// The product `self * other`.
    pub fn mul(&self, other: &Monomial) -> Monomial {
        debug_assert_eq!(self.nvars(), other.nvars());
        Monomial(self.0.iter().zip(&other.0).map(|(a, b)| a + b).collect())
    }
    /// Whether `self` divides `other`.
    pub fn divides(&self, other: &Monomial) -> bool {
        self.0.iter().zip(&other.0).all(|(a, b)| a <= b)
    }
    /// The quotient `other / self` if `self` divides `other`.
    pub fn divide_into(&self, other: &Monomial) -> Option<Monomial> {
        if self.divides(other) {
            Some(Monomial(
                other.0.iter().zip(&self.0).map(|(b, a)| b - a).collect(),
            ))
        } else {
            None
        }
    }
    /// The greatest common divisor.
    pub fn gcd(&self, other: &Monomial) -> Monomial {
        Monomial(
            self.0
                .iter()
                .zip(&other.0)
                .map(|(a, b)| *a.min(b))
                .collect(),
        )
    }
    /// The least common multiple.
    pub fn lcm(&self, other: &Monomial) -> Monomial {
        Monomial(
            self.0
                .iter()
                .zip(&other.0)
                .map(|(a, b)| *a.max(b))
                .collect(),
        )
    }
    /// Whether the two monomials share no variable.
    pub fn coprime(&self, other: &Monomial) -> bool {
        self.0.iter().zip(&other.0).all(|(a, b)| *a == 0 || *b == 0)
    }
    /// Renders the monomial with the given variable names, e.g. `a1*t3^2`; `1` for the unit.
    pub fn display_with(&self, names: &[String]) -> String {
        let parts: Vec<String> = self
            .0
            .iter()
            .enumerate()
            .filter(|(_, &e)| e > 0)
            .map(|(i, &e)| {
                let name = names.get(i).cloned().unwrap_or_else(|| format!("x{i}"));
                if e == 1 {
                    name
                } else {
                    format!("{name}^{e}")
                }
            })
            .collect();
        if parts.is_empty() {
            "1".to_string()
        } else {
            parts.join("*")
        }
    }
    /// All monomials in `nvars` variables of total degree exactly `d`, in descending
    /// order of `order`.
    pub fn all_of_degree(nvars: usize, d: u32, order: MonomialOrder) -> Vec<Monomial> {
        let mut out = Vec::new();
        let mut cur = vec![0 as Exponent; nvars];
        fn rec(i: usize, left: u32, cur: &mut Vec<Exponent>, out: &mut Vec<Monomial>) {
            if i + 1 == cur.len() {
                cur[i] = left as Exponent;
                out.push(Monomial(cur.clone()));
                return;
            }
            for e in (0..=left).rev() {
                cur[i] = e as Exponent;
                rec(i + 1, left - e, cur, out);
            }
            cur[i] = 0;
        }
        if nvars == 0 {
            if d == 0 {
                out.push(Monomial(vec![]));
            }
            return out;
        }
        rec(0, d, &mut cur, &mut out);
        out.sort_by(|a, b| order.cmp(b, a));
        out
    }
    /// All monomials in `nvars` variables of total degree at most `d`, in descending
    /// order of `order`.
    pub fn all_up_to_degree(nvars: usize, d: u32, order: MonomialOrder) -> Vec<Monomial> {
        let mut out: Vec<Monomial> = (0..=d)
            .flat_map(|k| Monomial::all_of_degree(nvars, k, order))
            .collect();
        out.sort_by(|a, b| order.cmp(b, a));
        out
    }
}

impl fmt::Debug for Monomial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.display_with(&[]))
    }
}

/// A term order on monomials.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum MonomialOrder {
    /// Graded reverse lexicographic with x_0 > x_1 > ... (the default for Gröbner work).
    #[default]
    Grevlex,
    /// Lexicographic with x_0 > x_1 > ...
    Lex,
}

impl MonomialOrder {
    /// Compares two monomials of the same ring; `Greater` means `a` is larger.
    pub fn cmp(self, a: &Monomial, b: &Monomial) -> Ordering {
        match self {
            MonomialOrder::Lex => a.0.cmp(&b.0),
            MonomialOrder::Grevlex => {
                let (da, db) = (a.degree(), b.degree());
                if da != db {
                    return da.cmp(&db);
                }
                // Same degree: the one with the smaller exponent in the last variable where
                // they differ is the larger.
                for (x, y) in a.0.iter().zip(&b.0).rev() {
                    if x != y {
                        return y.cmp(x);
                    }
                }
                Ordering::Equal
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grevlex_known_order() {
        // In grevlex with x > y > z: x^2 > xy > y^2 > xz > yz > z^2.
        let m = |v: [u16; 3]| Monomial(v.to_vec());
        let expected = [
            m([2, 0, 0]),
            m([1, 1, 0]),
            m([0, 2, 0]),
            m([1, 0, 1]),
            m([0, 1, 1]),
            m([0, 0, 2]),
        ];
        let got = Monomial::all_of_degree(3, 2, MonomialOrder::Grevlex);
        assert_eq!(got, expected);
        assert_eq!(
            Monomial::all_up_to_degree(3, 3, MonomialOrder::Grevlex).len(),
            20
        );
    }

    #[test]
    fn lex_known_order() {
        let m = |v: [u16; 2]| Monomial(v.to_vec());
        let got = Monomial::all_up_to_degree(2, 2, MonomialOrder::Lex);
        assert_eq!(
            got,
            [
                m([2, 0]),
                m([1, 1]),
                m([1, 0]),
                m([0, 2]),
                m([0, 1]),
                m([0, 0])
            ]
        );
    }

    #[test]
    fn division_and_lcm() {
        let a = Monomial(vec![1, 2, 0]);
        let b = Monomial(vec![2, 1, 3]);
        assert_eq!(a.lcm(&b), Monomial(vec![2, 2, 3]));
        assert!(!a.divides(&b));
        assert_eq!(a.divide_into(&a.mul(&b)), Some(b.clone()));
        assert_eq!(
            a.display_with(&["a1".into(), "t1".into(), "t3".into()]),
            "a1*t1^2"
        );
    }
}
