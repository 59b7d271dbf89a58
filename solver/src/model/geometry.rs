//! Two-view geometry primitives.
//!
//! Conventions: `[v]×` is the skew matrix with `[v]× x = v × x`. Rotations act on column
//! vectors. Relative pose `(R, t)` maps camera-1 coordinates to camera-2 coordinates,
//! `x2 = R x1 + t`; the essential matrix is `E = [t]× R` and bearings satisfy
//! `m2^T E m1 = 0`. Essential matrices as 9-vectors are row-major: `E_ij = e[3 i + j]`.

use nalgebra::{Matrix3, Vector3};

/// Skew-symmetric matrix `[v]×`, so that `skew(v) * x == v.cross(&x)`.
pub fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Rodrigues exponential `exp([w]×)`: rotation by angle `|w|` about axis `w/|w|`
/// (Taylor expansion near zero).
pub fn exp_so3(w: &Vector3<f64>) -> Matrix3<f64> {
    let theta2 = w.norm_squared();
    let k = skew(w);
    let (a, b) = if theta2 < 1e-10 {
        (1.0 - theta2 / 6.0, 0.5 - theta2 / 24.0)
    } else {
        let theta = theta2.sqrt();
        (theta.sin() / theta, (1.0 - theta.cos()) / theta2)
    };
    Matrix3::identity() + k * a + k * k * b
}

/// Rodrigues logarithm: the rotation vector `w` (angle `|w|` in `[0, π]`) with
/// `exp_so3(w) == r`. `r` must be a rotation matrix; near `π` the axis is taken from the
/// symmetric part.
pub fn log_so3(r: &Matrix3<f64>) -> Vector3<f64> {
    let cos = ((r.trace() - 1.0) * 0.5).clamp(-1.0, 1.0);
    let theta = cos.acos();
    let v = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    );
    if theta < 1e-6 {
        return v * 0.5;
    }
    if std::f64::consts::PI - theta < 1e-4 {
        // R ≈ 2 a a^T - I: take the column of R + I with largest norm.
        let s = r + Matrix3::identity();
        let mut best = 0;
        for j in 1..3 {
            if s.column(j).norm() > s.column(best).norm() {
                best = j;
            }
        }
        let mut axis = s.column(best).normalize();
        if axis.dot(&v) < 0.0 {
            axis = -axis;
        }
        return axis * theta;
    }
    v * (theta / (2.0 * theta.sin()))
}

/// Rotation error in degrees: `acos((tr(R_gt^T R) - 1) / 2)`. Evaluated as the equivalent
/// `atan2(|vee(D - D^T)| / 2, (tr D - 1) / 2)` with `D = R_gt^T R`, which equals the `acos`
/// form for rotations but keeps full precision near 0° (the bare `acos` cannot resolve
/// errors below ~1e-6°).
pub fn rotation_error_deg(r_gt: &Matrix3<f64>, r: &Matrix3<f64>) -> f64 {
    let d = r_gt.transpose() * r;
    let c = (d.trace() - 1.0) * 0.5;
    let s = 0.5
        * Vector3::new(
            d[(2, 1)] - d[(1, 2)],
            d[(0, 2)] - d[(2, 0)],
            d[(1, 0)] - d[(0, 1)],
        )
        .norm();
    s.atan2(c.clamp(-1.0, 1.0)).to_degrees()
}

/// Translation direction error in degrees: `acos(t_gt · t)` for unit vectors (both inputs are
/// normalised), evaluated as `atan2(|t_gt × t|, t_gt · t)` for precision near 0°.
/// The sign is not folded: the caller fixes it by cheirality.
pub fn translation_error_deg(t_gt: &Vector3<f64>, t: &Vector3<f64>) -> f64 {
    let (a, b) = (t_gt.normalize(), t.normalize());
    a.cross(&b).norm().atan2(a.dot(&b)).to_degrees()
}

/// Project a 3x3 matrix onto SO(3) (nearest rotation in Frobenius norm, det = +1).
/// Non-finite or non-convergent input is returned unchanged (callers check finiteness).
pub fn orthonormalize(m: &Matrix3<f64>) -> Matrix3<f64> {
    if !m.iter().all(|x| x.is_finite()) {
        return *m;
    }
    let Some(svd) = m.try_svd(true, true, 1e-15, 200) else {
        return *m;
    };
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
        return *m;
    };
    let mut d = Matrix3::identity();
    if (u * vt).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    u * d * vt
}

/// Essential matrix `E = [t]× R`.
pub fn essential_from_pose(r: &Matrix3<f64>, t: &Vector3<f64>) -> Matrix3<f64> {
    skew(t) * r
}

/// The four `(R, t)` decompositions of an essential matrix (`|t| = 1`):
/// `R ∈ {U W V^T, U W^T V^T}`, `t = ±u_3`. Empty if `E` is not finite or has rank < 2.
pub fn decompose_essential(e: &Matrix3<f64>) -> Vec<(Matrix3<f64>, Vector3<f64>)> {
    if !e.iter().all(|x| x.is_finite()) {
        return Vec::new();
    }
    let Some(svd) = e.try_svd(true, true, 1e-15, 200) else {
        return Vec::new();
    };
    let (Some(mut u), Some(mut vt)) = (svd.u, svd.v_t) else {
        return Vec::new();
    };
    let mut s: Vec<f64> = svd.singular_values.iter().copied().collect();
    s.sort_by(|a, b| b.partial_cmp(a).unwrap_or(std::cmp::Ordering::Equal));
    if s[0].is_nan() || s[0] <= 0.0 || s[1] < 1e-12 * s[0] {
        return Vec::new();
    }
    // Reorder so that the smallest singular value is the last.
    let sv = svd.singular_values;
    let imin = (0..3)
        .min_by(|&a, &b| {
            sv[a]
                .partial_cmp(&sv[b])
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .unwrap_or(2);
    if imin != 2 {
        u.swap_columns(imin, 2);
        vt.swap_rows(imin, 2);
    }
    if u.determinant() < 0.0 {
        u = -u;
    }
    if vt.determinant() < 0.0 {
        vt = -vt;
    }
    let w = Matrix3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    let r1 = u * w * vt;
    let r2 = u * w.transpose() * vt;
    let t: Vector3<f64> = u.column(2).into_owned().normalize();
    vec![(r1, t), (r1, -t), (r2, t), (r2, -t)]
}

/// Depths `(d1, d2)` of the point seen along bearings `m1` (camera 1) and `m2` (camera 2)
/// with `d2 m2 ≈ R (d1 m1) + t` (least squares); `None` if the rays are parallel.
pub fn triangulate_depths(
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    m1: &Vector3<f64>,
    m2: &Vector3<f64>,
) -> Option<(f64, f64)> {
    // d1 a - d2 b = -t with a = R m1, b = m2.
    let a = r * m1;
    let b = m2;
    let (aa, ab, bb) = (a.dot(&a), a.dot(b), b.dot(b));
    let (at, bt) = (a.dot(t), b.dot(t));
    let det = aa * bb - ab * ab;
    if det.is_nan() || det.abs() <= 1e-14 * aa * bb {
        return None;
    }
    // Normal equations: [aa -ab; -ab bb] [d1 d2] = [-at, bt].
    let d1 = (-at * bb + ab * bt) / det;
    let d2 = (aa * bt - ab * at) / det;
    Some((d1, d2))
}

/// Depths `(a, b)` along two rays `o1 + a g1` and `o2 + b g2` at their closest approach
/// (least squares of `a g1 − b g2 = d`, `d = o2 − o1`); `None` if the rays are parallel.
/// A point in front of both cameras has both positive.
pub fn ray_depths(g1: &Vector3<f64>, g2: &Vector3<f64>, d: &Vector3<f64>) -> Option<(f64, f64)> {
    let (aa, ab, bb) = (g1.dot(g1), g1.dot(g2), g2.dot(g2));
    let (ad, bd) = (g1.dot(d), g2.dot(d));
    let det = aa * bb - ab * ab;
    if det.is_nan() || det.abs() <= 1e-14 * aa * bb {
        return None;
    }
    Some(((ad * bb - ab * bd) / det, (ab * ad - aa * bd) / det))
}

/// Cheirality: the triangulated point lies in front of both cameras (both depths positive).
pub fn cheirality(
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    m1: &Vector3<f64>,
    m2: &Vector3<f64>,
) -> bool {
    matches!(triangulate_depths(r, t, m1, m2), Some((d1, d2)) if d1 > 0.0 && d2 > 0.0)
}

/// Of the four decompositions of `E`, the one with the most bearing pairs passing
/// [`cheirality`] (ties: the first of `(R_a, t), (R_a, -t), (R_b, t), (R_b, -t)`). `None` if
/// `E` cannot be decomposed or no pair passes.
///
/// Closed form (no SVD): with `E` scaled to `|E|_F = √2` (singular values `1, 1, 0`) and
/// `E = [t]× R`, the cofactor matrix is `cof(E) = cof([t]×) cof(R) = t t^T R`: its rows are
/// multiples of `R^T t` and its columns multiples of `t` (`t^T E = 0`), so `t` is its
/// normalised largest column, and the two rotations are `cof(E) ∓ [t]× E` (as
/// `[t]× E = (t t^T - I) R`; the second is the twisted pair `(2 t t^T - I) R`). Each rotation is checked for orthonormality; if `E` is too
/// far from an essential matrix for that, the SVD decomposition
/// ([`decompose_essential`]) is used instead. Cheirality of `-t` is read off the depths of
/// `t` (both flip sign), so each pair is triangulated once per rotation.
pub fn pose_from_essential(
    e: &Matrix3<f64>,
    m1: &[Vector3<f64>],
    m2: &[Vector3<f64>],
) -> Option<(Matrix3<f64>, Vector3<f64>)> {
    let candidates = essential_rotations(e).or_else(|| {
        let d = decompose_essential(e);
        (d.len() == 4).then(|| ([d[0].0, d[2].0], d[0].1))
    })?;
    let (rots, t) = candidates;
    let mut best = None;
    let mut best_count = 0;
    for r in rots {
        let (pos, neg) = cheirality_counts(&r, &t, m1, m2);
        if pos > best_count {
            best_count = pos;
            best = Some((r, t));
        }
        if neg > best_count {
            best_count = neg;
            best = Some((r, -t));
        }
    }
    best
}

/// The two rotations and the (unsigned) unit translation of an essential matrix in closed
/// form (see [`pose_from_essential`]); `None` if `E` is not finite, has rank < 2, or the
/// rotations are not orthonormal to 1e-6.
fn essential_rotations(e: &Matrix3<f64>) -> Option<([Matrix3<f64>; 2], Vector3<f64>)> {
    let n = e.norm();
    if !(n.is_finite() && n > 0.0) {
        return None;
    }
    let e = e * (std::f64::consts::SQRT_2 / n);
    let r0: Vector3<f64> = e.row(0).transpose();
    let r1: Vector3<f64> = e.row(1).transpose();
    let r2: Vector3<f64> = e.row(2).transpose();
    // Row i of the cofactor matrix is the cross product of the other two rows.
    let cof = Matrix3::from_rows(&[
        r1.cross(&r2).transpose(),
        r2.cross(&r0).transpose(),
        r0.cross(&r1).transpose(),
    ]);
    let norms = [0, 1, 2].map(|j| cof.column(j).norm_squared());
    let j = if norms[0] >= norms[1] && norms[0] >= norms[2] {
        0
    } else if norms[1] >= norms[2] {
        1
    } else {
        2
    };
    // The column norms of t t^T R are |(R^T t)_j| and sum in square to 1: the largest is
    // at least 1/√3.
    let cn = norms[j];
    if cn.is_nan() || cn <= 1e-4 {
        return None;
    }
    let t: Vector3<f64> = cof.column(j) / cn.sqrt();
    let te = skew(&t) * e;
    let ra = cof - te;
    let rb = cof + te;
    let ok = |r: &Matrix3<f64>| {
        (r.transpose() * r - Matrix3::identity()).norm() < 1e-6 && r.determinant() > 0.0
    };
    (ok(&ra) && ok(&rb)).then_some(([ra, rb], t))
}

/// Numbers of bearing pairs passing [`cheirality`] with `t` and with `-t`.
fn cheirality_counts(
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    m1: &[Vector3<f64>],
    m2: &[Vector3<f64>],
) -> (usize, usize) {
    let (mut pos, mut neg) = (0, 0);
    for (a, b) in m1.iter().zip(m2) {
        if let Some((d1, d2)) = triangulate_depths(r, t, a, b) {
            if d1 > 0.0 && d2 > 0.0 {
                pos += 1;
            } else if d1 < 0.0 && d2 < 0.0 {
                neg += 1;
            }
        }
    }
    (pos, neg)
}

/// Flip the sign of `t` if fewer bearing pairs pass [`cheirality`] with `t` than with `-t`.
pub fn fix_translation_sign(
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    m1: &[Vector3<f64>],
    m2: &[Vector3<f64>],
) -> Vector3<f64> {
    let (pos, neg) = cheirality_counts(r, t, m1, m2);
    if neg > pos {
        -t
    } else {
        *t
    }
}

/// The 4-dimensional nullspace of the 5x9 epipolar constraint matrix built from five bearing
/// pairs: rows `kron(m2, m1)` so that `row · e = m2^T E m1` with `E_ij = e[3i + j]`.
/// Returns `[E1, E2, E3, E4]` (orthonormal in Frobenius norm), each satisfying
/// `m2_k^T E_i m1_k ≈ 0` for all five pairs. Computed as the last four columns of `Q` in the
/// Householder QR decomposition of the (row-normalised) 9x5 transposed constraint matrix, as
/// PoseLib does: no normal equations, so the conditioning is that of the constraint matrix
/// itself, and about a tenth of the cost of an SVD. `None` on non-finite input.
pub fn epipolar_nullspace(
    m1: &[Vector3<f64>; 5],
    m2: &[Vector3<f64>; 5],
) -> Option<[Matrix3<f64>; 4]> {
    // Columns of A = M^T (9x5), one per constraint.
    let mut a = [[0.0f64; 9]; 5];
    for k in 0..5 {
        let col = &mut a[k];
        for i in 0..3 {
            for j in 0..3 {
                col[3 * i + j] = m2[k][i] * m1[k][j];
            }
        }
        let n = col.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(n.is_finite() && n > 0.0) {
            return None;
        }
        col.iter_mut().for_each(|x| *x /= n);
    }
    // Householder vectors v_j (entries j..9) and factors beta_j: H_j = I - beta_j v_j v_j^T.
    let mut vs = [[0.0f64; 9]; 5];
    let mut betas = [0.0f64; 5];
    for j in 0..5 {
        let norm = a[j][j..].iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm.is_nan() || norm <= 0.0 {
            continue; // H_j = I (rank-deficient sample); Q stays orthogonal.
        }
        let alpha = if a[j][j] > 0.0 { -norm } else { norm };
        let mut v = [0.0f64; 9];
        v[j..].copy_from_slice(&a[j][j..]);
        v[j] -= alpha;
        let vn = v[j..].iter().map(|x| x * x).sum::<f64>();
        if vn.is_nan() || vn <= 0.0 {
            continue;
        }
        let beta = 2.0 / vn;
        for col in a.iter_mut().skip(j + 1) {
            let d: f64 = (j..9).map(|i| v[i] * col[i]).sum::<f64>() * beta;
            for i in j..9 {
                col[i] -= d * v[i];
            }
        }
        vs[j] = v;
        betas[j] = beta;
    }
    // Q e_k = H_1 ... H_5 e_k for k = 5..8.
    let mut out = [Matrix3::zeros(); 4];
    for (o, k) in out.iter_mut().zip(5..9) {
        let mut x = [0.0f64; 9];
        x[k] = 1.0;
        for j in (0..5).rev() {
            let v = &vs[j];
            let d: f64 = (j..9).map(|i| v[i] * x[i]).sum::<f64>() * betas[j];
            for i in j..9 {
                x[i] -= d * v[i];
            }
        }
        *o = Matrix3::new(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8]);
    }
    if out.iter().any(|m| !m.iter().all(|x| x.is_finite())) {
        return None;
    }
    Some(out)
}

/// Unit vector `b1, b2` spanning the plane orthogonal to unit `t` (a tangent basis of S²).
pub fn tangent_basis(t: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let a = if t.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let b1 = t.cross(&a).normalize();
    let b2 = t.cross(&b1);
    (b1, b2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn rand_vec(rng: &mut ChaCha8Rng, s: f64) -> Vector3<f64> {
        Vector3::new(
            rng.gen_range(-s..s),
            rng.gen_range(-s..s),
            rng.gen_range(-s..s),
        )
    }

    #[test]
    fn exp_log_roundtrip() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..100 {
            let w = rand_vec(&mut rng, 1.7);
            let r = exp_so3(&w);
            assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-12);
            assert!((r.determinant() - 1.0).abs() < 1e-12);
            assert!((log_so3(&r) - w).norm() < 1e-9);
        }
        let tiny = Vector3::new(1e-9, -2e-9, 3e-9);
        assert!((log_so3(&exp_so3(&tiny)) - tiny).norm() < 1e-15);
        let near_pi = Vector3::new(0.0, 0.0, std::f64::consts::PI - 1e-7);
        assert!((exp_so3(&log_so3(&exp_so3(&near_pi))) - exp_so3(&near_pi)).norm() < 1e-6);
        assert!(
            (skew(&w3()) * Vector3::new(4.0, 5.0, 6.0) - w3().cross(&Vector3::new(4.0, 5.0, 6.0)))
                .norm()
                < 1e-15
        );
    }

    fn w3() -> Vector3<f64> {
        Vector3::new(1.0, 2.0, 3.0)
    }

    #[test]
    fn error_metrics() {
        let r = exp_so3(&Vector3::new(0.0, 0.0, 10f64.to_radians()));
        assert!((rotation_error_deg(&Matrix3::identity(), &r) - 10.0).abs() < 1e-9);
        assert_eq!(rotation_error_deg(&r, &r), 0.0);
        let t = Vector3::new(1.0, 0.0, 0.0);
        assert!((translation_error_deg(&t, &Vector3::new(1.0, 1.0, 0.0)) - 45.0).abs() < 1e-9);
        assert!((translation_error_deg(&t, &-t) - 180.0).abs() < 1e-9);
        assert_eq!(translation_error_deg(&t, &(t * 3.0)), 0.0);
    }

    type Scene = (
        Matrix3<f64>,
        Vector3<f64>,
        Vec<Vector3<f64>>,
        Vec<Vector3<f64>>,
    );

    fn random_scene(rng: &mut ChaCha8Rng) -> Scene {
        let r = exp_so3(&rand_vec(rng, 0.3));
        let t = rand_vec(rng, 1.0).normalize();
        let mut m1 = Vec::new();
        let mut m2 = Vec::new();
        for _ in 0..10 {
            let x = Vector3::new(
                rng.gen_range(-2.0..2.0),
                rng.gen_range(-2.0..2.0),
                rng.gen_range(4.0..10.0),
            );
            let y = r * x + t;
            m1.push(x / x.z);
            m2.push(y / y.z);
        }
        (r, t, m1, m2)
    }

    #[test]
    fn decomposition_and_cheirality_recover_pose() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        for _ in 0..50 {
            let (r, t, m1, m2) = random_scene(&mut rng);
            let e = essential_from_pose(&r, &t) * 3.7;
            let cands = decompose_essential(&e);
            assert_eq!(cands.len(), 4);
            assert!(cands
                .iter()
                .any(|(rr, tt)| rotation_error_deg(&r, rr) < 1e-6
                    && translation_error_deg(&t, tt) < 1e-6));
            // The closed form itself succeeds (no SVD fallback) and contains the pose.
            let (rots, t_closed) = essential_rotations(&e).expect("closed form");
            assert!(t_closed.cross(&t).norm() < 1e-9, "t up to sign");
            assert!(rots.iter().any(|rr| rotation_error_deg(&r, rr) < 1e-6));
            let (rr, tt) = pose_from_essential(&e, &m1, &m2).unwrap();
            assert!(rotation_error_deg(&r, &rr) < 1e-6);
            assert!(translation_error_deg(&t, &tt) < 1e-6);
            for (a, b) in m1.iter().zip(&m2) {
                assert!(cheirality(&r, &t, a, b));
                assert!(!cheirality(&r, &-t, a, b));
            }
            assert!((fix_translation_sign(&r, &-t, &m1, &m2) - t).norm() < 1e-12);
        }
        assert!(decompose_essential(&Matrix3::zeros()).is_empty());
        assert!(decompose_essential(&Matrix3::from_element(f64::NAN)).is_empty());
    }

    #[test]
    fn nullspace_satisfies_constraints() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..50 {
            let (r, t, m1, m2) = random_scene(&mut rng);
            let a: [Vector3<f64>; 5] = std::array::from_fn(|k| m1[k]);
            let b: [Vector3<f64>; 5] = std::array::from_fn(|k| m2[k]);
            let basis = epipolar_nullspace(&a, &b).unwrap();
            for e in &basis {
                assert!((e.norm() - 1.0).abs() < 1e-9);
                for k in 0..5 {
                    assert!((b[k].transpose() * e * a[k])[0].abs() < 1e-12);
                }
            }
            // The true E lies in the span.
            let e_true = essential_from_pose(&r, &t).normalize();
            let proj: Matrix3<f64> = basis.iter().map(|b| b * b.dot(&e_true)).sum();
            assert!((proj - e_true).norm() < 1e-9);
        }
        let nan = [Vector3::new(f64::NAN, 0.0, 1.0); 5];
        assert!(epipolar_nullspace(&nan, &nan).is_none());
    }

    #[test]
    fn triangulation_depths() {
        let r = Matrix3::identity();
        let t = Vector3::new(-1.0, 0.0, 0.0);
        let x = Vector3::new(0.5, 0.2, 5.0);
        let y = r * x + t;
        let (d1, d2) = triangulate_depths(&r, &t, &(x / x.z), &(y / y.z)).unwrap();
        assert!((d1 - 5.0).abs() < 1e-9 && (d2 - 5.0).abs() < 1e-9);
        assert!(triangulate_depths(
            &r,
            &t,
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0)
        )
        .is_none());
        let (b1, b2) = tangent_basis(&Vector3::new(0.0, 0.6, 0.8));
        assert!(b1.dot(&b2).abs() < 1e-15 && (b1.norm() - 1.0).abs() < 1e-15);
    }
}
