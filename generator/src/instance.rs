//! Random problem instances that respect the data kinds.
//!
//! - `f64` ([`random_data_f64`]): scalar, vec3 and mat3 entries and a point's x, y are
//!   uniform in [-1, 1]; a rotation comes from a uniformly random unit quaternion (a
//!   4-vector drawn uniformly in the unit ball by rejection, then normalised).
//! - `Z_p` ([`random_data_fp`]): scalar, vec3 and mat3 entries and a point's x, y are
//!   uniform in Z_p; a rotation is the Cayley transform of a uniform q in Z_p^3,
//!   `R = ((1 - q'q) I + 2 q q' + 2 [q]x) / (1 + q'q)` (q redrawn if `1 + q'q = 0`), an exact
//!   rotation mod p: `R R' = I` and `det R = 1`.
//!
//! Slots are filled in layout order (see [`ProblemLayout`]); a point contributes x, y only
//! (its third entry is the constant 1 of the language).

use crate::algebra::{Field, Fp, Ring};
use crate::problem::{DataKind, ProblemLayout};
use rand::Rng;

/// A random f64 instance: one value per data slot, in layout order.
pub fn random_data_f64(layout: &ProblemLayout, rng: &mut impl Rng) -> Vec<f64> {
    let mut out = Vec::with_capacity(layout.data_slot_count());
    for d in &layout.data {
        for _ in 0..d.len.unwrap_or(1) {
            match d.kind {
                DataKind::Rotation => out.extend(random_rotation_f64(rng)),
                k => out.extend((0..k.slots()).map(|_| rng.gen_range(-1.0..=1.0))),
            }
        }
    }
    out
}

/// A random rotation (row-major) from a uniformly random unit quaternion.
pub fn random_rotation_f64(rng: &mut impl Rng) -> [f64; 9] {
    let q = loop {
        let q: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-1.0..=1.0));
        let n2: f64 = q.iter().map(|x| x * x).sum();
        if n2 > 1e-4 && n2 <= 1.0 {
            let n = n2.sqrt();
            break q.map(|x| x / n);
        }
    };
    let [w, x, y, z] = q;
    [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    ]
}

/// A random instance over Z_P: one value per data slot, in layout order.
pub fn random_data_fp<const P: u32>(layout: &ProblemLayout, rng: &mut impl Rng) -> Vec<Fp<P>> {
    let mut out = Vec::with_capacity(layout.data_slot_count());
    for d in &layout.data {
        for _ in 0..d.len.unwrap_or(1) {
            match d.kind {
                DataKind::Rotation => out.extend(random_rotation_fp::<P>(rng)),
                k => out.extend((0..k.slots()).map(|_| Fp::<P>(rng.gen_range(0..P)))),
            }
        }
    }
    out
}

/// An exact rotation mod P (row-major) by the Cayley transform of a random q in Z_P^3.
pub fn random_rotation_fp<const P: u32>(rng: &mut impl Rng) -> [Fp<P>; 9] {
    loop {
        let q: [Fp<P>; 3] = std::array::from_fn(|_| Fp::<P>(rng.gen_range(0..P)));
        if let Some(r) = cayley(q) {
            return r;
        }
    }
}

/// `((1 - q'q) I + 2 q q' + 2 [q]x) / (1 + q'q)`, or `None` when `1 + q'q = 0`.
pub fn cayley<const P: u32>(q: [Fp<P>; 3]) -> Option<[Fp<P>; 9]> {
    let one = Fp::<P>::one();
    let two = Fp::<P>::new(2);
    let qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    let inv = (one + qq).inv()?;
    let [x, y, z] = q;
    let skew = [Fp(0), -z, y, z, Fp(0), -x, -y, x, Fp(0)];
    Some(std::array::from_fn(|k| {
        let (i, j) = (k / 3, k % 3);
        let diag = if i == j { one - qq } else { Fp(0) };
        (diag + two * q[i] * q[j] + two * skew[k]) * inv
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{P1, P2};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    fn check_rotation<const P: u32>(r: &[Fp<P>; 9]) {
        for i in 0..3 {
            for j in 0..3 {
                let dot = (0..3).fold(Fp::<P>(0), |acc, k| acc + r[3 * i + k] * r[3 * j + k]);
                assert_eq!(dot, if i == j { Fp(1) } else { Fp(0) });
            }
        }
        let m = |i: usize, j: usize| r[3 * i + j];
        let det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
        assert_eq!(det, Fp(1));
    }

    #[test]
    fn cayley_rotations_are_exact_mod_p() {
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        for _ in 0..500 {
            check_rotation(&random_rotation_fp::<P1>(&mut rng));
            check_rotation(&random_rotation_fp::<P2>(&mut rng));
        }
        // Small q too (where 1 + q'q could vanish for a small prime).
        for a in 0..5 {
            if let Some(r) = cayley::<7>([Fp::new(a), Fp::new(1), Fp::new(2)]) {
                check_rotation(&r);
            }
        }
        assert!(cayley::<5>([Fp::new(2), Fp::new(0), Fp::new(0)]).is_none());
    }

    #[test]
    fn f64_rotations_are_orthonormal() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..500 {
            let r = nalgebra::Matrix3::from_row_slice(&random_rotation_f64(&mut rng));
            assert!((r * r.transpose() - nalgebra::Matrix3::identity()).norm() < 1e-12);
            assert!((r.determinant() - 1.0).abs() < 1e-12);
        }
    }
}
