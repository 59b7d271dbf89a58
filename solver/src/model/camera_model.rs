//! Camera models: COLMAP's names, parameter orders and distortion formulas
//! (`src/colmap/sensor/models.h`), on normalised image coordinates.
//!
//! A camera-frame point `X` (`X.z > 0`) has undistorted normalised coordinates
//! `x = (X.x / X.z, X.y / X.z)`; the model maps them to distorted normalised coordinates
//! `x_d = d(x)`, and the pixel is `(fx x_d + cx, fy x_d.y + cy)` (`fx = fy = f` for the
//! `SIMPLE_*` models and `RADIAL`). With `s = x² + y²` (`r = √s`):
//!
//! - `SIMPLE_PINHOLE [f, cx, cy]`, `PINHOLE [fx, fy, cx, cy]`: `d(x) = x`.
//! - `SIMPLE_RADIAL [f, cx, cy, k]`: `d(x) = x (1 + k s)`.
//! - `RADIAL [f, cx, cy, k1, k2]`: `d(x) = x (1 + k1 s + k2 s²)`.
//! - `OPENCV [fx, fy, cx, cy, k1, k2, p1, p2]`: `x (1 + k1 s + k2 s²)` plus the tangential
//!   terms `(2 p1 x y + p2 (s + 2 x²), 2 p2 x y + p1 (s + 2 y²))`.
//! - `FULL_OPENCV [fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6]`: the rational radial
//!   factor `(1 + k1 s + k2 s² + k3 s³) / (1 + k4 s + k5 s² + k6 s³)` and OPENCV's
//!   tangential terms.
//! - `OPENCV_FISHEYE [fx, fy, cx, cy, k1, k2, k3, k4]` (equidistant): `θ = atan(r)`,
//!   `θ_d = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸)`, `d(x) = x θ_d / r` (`d(x) = x` for
//!   `r ≤ ε`, the machine epsilon, as COLMAP).
//!
//! **Invertibility.** Undistortion inverts `d` by Newton's method and accepts the result
//! only where `d` is invertible: for the fisheye, `θ_d(θ)` must be increasing on `[0, θ]`
//! with `θ < π/2`; for the other models the radial map `ρ(r) = r · factor(r²)` must be
//! increasing on `[0, r]` (and the rational factor's denominator positive there), and
//! `det ∂d/∂x > 0` at the solution (which the tangential terms could break). Beyond that
//! radius the model folds back on itself, and a pixel there has no unique bearing.

use nalgebra::{Matrix2, Vector2};

/// A COLMAP camera model (see the module documentation for the formulas).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CameraModel {
    /// `SIMPLE_PINHOLE [f, cx, cy]`.
    SimplePinhole,
    /// `PINHOLE [fx, fy, cx, cy]`.
    Pinhole,
    /// `SIMPLE_RADIAL [f, cx, cy, k]`.
    SimpleRadial,
    /// `RADIAL [f, cx, cy, k1, k2]`.
    Radial,
    /// `OPENCV [fx, fy, cx, cy, k1, k2, p1, p2]`.
    OpenCv,
    /// `OPENCV_FISHEYE [fx, fy, cx, cy, k1, k2, k3, k4]` (equidistant).
    OpenCvFisheye,
    /// `FULL_OPENCV [fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6]` (rational).
    FullOpenCv,
}

impl CameraModel {
    /// Every model.
    pub const ALL: [CameraModel; 7] = [
        CameraModel::SimplePinhole,
        CameraModel::Pinhole,
        CameraModel::SimpleRadial,
        CameraModel::Radial,
        CameraModel::OpenCv,
        CameraModel::OpenCvFisheye,
        CameraModel::FullOpenCv,
    ];

    /// COLMAP's name, e.g. `"OPENCV"`.
    pub fn name(self) -> &'static str {
        match self {
            CameraModel::SimplePinhole => "SIMPLE_PINHOLE",
            CameraModel::Pinhole => "PINHOLE",
            CameraModel::SimpleRadial => "SIMPLE_RADIAL",
            CameraModel::Radial => "RADIAL",
            CameraModel::OpenCv => "OPENCV",
            CameraModel::OpenCvFisheye => "OPENCV_FISHEYE",
            CameraModel::FullOpenCv => "FULL_OPENCV",
        }
    }

    /// The model with COLMAP's name `name` (exact, upper case).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The parameter names in COLMAP's order.
    pub fn param_names(self) -> &'static [&'static str] {
        match self {
            CameraModel::SimplePinhole => &["f", "cx", "cy"],
            CameraModel::Pinhole => &["fx", "fy", "cx", "cy"],
            CameraModel::SimpleRadial => &["f", "cx", "cy", "k"],
            CameraModel::Radial => &["f", "cx", "cy", "k1", "k2"],
            CameraModel::OpenCv => &["fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"],
            CameraModel::OpenCvFisheye => &["fx", "fy", "cx", "cy", "k1", "k2", "k3", "k4"],
            CameraModel::FullOpenCv => &[
                "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6",
            ],
        }
    }

    /// Number of parameters (COLMAP's `num_params`).
    pub fn num_params(self) -> usize {
        self.param_names().len()
    }

    /// Whether the model has one focal length `f` (`fx = fy = f`).
    pub fn single_focal(self) -> bool {
        matches!(
            self,
            CameraModel::SimplePinhole | CameraModel::SimpleRadial | CameraModel::Radial
        )
    }

    /// Number of distortion coefficients (the parameters after the focal length(s) and the
    /// principal point).
    pub fn num_distortion(self) -> usize {
        self.num_params() - if self.single_focal() { 3 } else { 4 }
    }

    /// Whether the model has no distortion (`d(x) = x`).
    pub fn is_pinhole(self) -> bool {
        matches!(self, CameraModel::SimplePinhole | CameraModel::Pinhole)
    }
}

impl std::fmt::Display for CameraModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a distorted point has no undistorted one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum UndistortFailure {
    /// The solution lies where the distortion map is not invertible (see the module
    /// documentation), or there is none in the model's domain.
    NotInvertible,
    /// Newton's iteration did not reach the tolerance.
    NotConverged,
}

/// Most Newton iterations of an undistortion.
pub const MAX_UNDISTORT_ITERATIONS: usize = 100;
/// Residual accepted by an undistortion, `|d(x) − x_d| ≤ UNDISTORT_TOLERANCE (1 + |x_d|)`
/// (normalised image units: a focal length of 10⁴ px makes it 10⁻⁶ px).
pub const UNDISTORT_TOLERANCE: f64 = 1e-10;

/// Radial numerator and denominator coefficients in `s = r²` (ascending) and `(p1, p2)` of
/// a non-fisheye model with distortion coefficients `k` (COLMAP order).
fn rational(model: CameraModel, k: &[f64; 8]) -> ([f64; 4], [f64; 4], f64, f64) {
    let one = [1.0, 0.0, 0.0, 0.0];
    match model {
        CameraModel::SimplePinhole | CameraModel::Pinhole | CameraModel::OpenCvFisheye => {
            (one, one, 0.0, 0.0)
        }
        CameraModel::SimpleRadial => ([1.0, k[0], 0.0, 0.0], one, 0.0, 0.0),
        CameraModel::Radial => ([1.0, k[0], k[1], 0.0], one, 0.0, 0.0),
        CameraModel::OpenCv => ([1.0, k[0], k[1], 0.0], one, k[2], k[3]),
        CameraModel::FullOpenCv => ([1.0, k[0], k[1], k[4]], [1.0, k[5], k[6], k[7]], k[2], k[3]),
    }
}

/// `p(s)`, coefficients ascending.
fn eval(p: &[f64], s: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * s + c)
}

/// Derivative of a polynomial (ascending coefficients).
fn derivative(p: &[f64]) -> Vec<f64> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(i, &c)| i as f64 * c)
        .collect()
}

/// The polynomial without its zero leading coefficients.
fn trim(p: &[f64]) -> &[f64] {
    let n = p.iter().rposition(|&c| c != 0.0).map_or(0, |i| i + 1);
    &p[..n]
}

/// The real roots of `p` in `[a, b]`: the roots of `p'` split the interval into pieces on
/// which `p` is monotone, and each piece whose ends differ in sign is bisected.
fn roots_in(p: &[f64], a: f64, b: f64) -> Vec<f64> {
    let p = trim(p);
    if p.len() <= 1 {
        return Vec::new();
    }
    let mut knots = vec![a];
    if p.len() > 2 {
        knots.extend(roots_in(&derivative(p), a, b));
    }
    knots.push(b);
    let mut roots = Vec::new();
    for w in knots.windows(2) {
        let (mut lo, mut hi) = (w[0], w[1]);
        let (flo, fhi) = (eval(p, lo), eval(p, hi));
        if flo == 0.0 {
            roots.push(lo);
        } else if flo * fhi < 0.0 {
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if (eval(p, mid) < 0.0) == (flo < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            roots.push(0.5 * (lo + hi));
        }
    }
    roots
}

/// Whether `p(s) > 0` on all of `[0, s_max]`: its minimum there is at an end or at a root of
/// `p'`.
fn positive_on(p: &[f64], s_max: f64) -> bool {
    let dp = derivative(p);
    let mut candidates = roots_in(&dp, 0.0, s_max);
    candidates.extend([0.0, s_max]);
    candidates.iter().all(|&s| eval(p, s) > 0.0)
}

/// Product of two polynomials.
fn mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// The numerator `N D + 2 s (N' D − N D')` of `dρ/dr = (N D + 2 s (N' D − N D')) / D²`,
/// the radial map's derivative in `r` (`'` is `d/ds`, `s = r²`).
fn radial_slope_numerator(n: &[f64; 4], d: &[f64; 4]) -> Vec<f64> {
    let (dn, dd) = (derivative(n), derivative(d));
    let mut p = mul(n, d);
    p.push(0.0);
    for (i, (a, b)) in mul(&dn, d).iter().zip(mul(n, &dd)).enumerate() {
        p[i + 1] += 2.0 * (a - b);
    }
    p
}

/// Whether the radial map of a non-fisheye model is invertible on `[0, r]`, `s_max = r²`:
/// the denominator `D(s) > 0` and `dρ/dr > 0` there.
fn radial_invertible(n: &[f64; 4], d: &[f64; 4], s_max: f64) -> bool {
    positive_on(d, s_max) && positive_on(&radial_slope_numerator(n, d), s_max)
}

/// `θ_d(θ)` of the fisheye and its derivative.
fn fisheye_theta_d(k: &[f64; 8], theta: f64) -> (f64, f64) {
    let t2 = theta * theta;
    let poly = [1.0, k[0], k[1], k[2], k[3]];
    let dpoly = [1.0, 3.0 * k[0], 5.0 * k[1], 7.0 * k[2], 9.0 * k[3]];
    (theta * eval(&poly, t2), eval(&dpoly, t2))
}

/// Whether the fisheye's `θ_d` is increasing on `[0, θ]` (`θ < π/2`).
fn fisheye_invertible(k: &[f64; 8], theta: f64) -> bool {
    let dpoly = [1.0, 3.0 * k[0], 5.0 * k[1], 7.0 * k[2], 9.0 * k[3]];
    (0.0..std::f64::consts::FRAC_PI_2).contains(&theta) && positive_on(&dpoly, theta * theta)
}

/// The distortion `d(x)` of normalised coordinates and its Jacobian `∂d/∂x`.
pub(crate) fn distort_with_jacobian(
    model: CameraModel,
    k: &[f64; 8],
    x: Vector2<f64>,
) -> (Vector2<f64>, Matrix2<f64>) {
    if model == CameraModel::OpenCvFisheye {
        let r = x.norm();
        if r <= f64::EPSILON {
            return (x, Matrix2::identity());
        }
        let theta = r.atan();
        let (td, dtd) = fisheye_theta_d(k, theta);
        let g = td / r;
        // d = x g(r); ∂d/∂x = g I + x (dg/dr) xᵀ / r, dg/dr = (θ_d' θ' r − θ_d) / r².
        let dg = (dtd / (1.0 + r * r) * r - td) / (r * r);
        let j = Matrix2::identity() * g + x * x.transpose() * (dg / r);
        return (x * g, j);
    }
    let (n, d, p1, p2) = rational(model, k);
    let (u, v) = (x.x, x.y);
    let s = u * u + v * v;
    let (ns, ds) = (eval(&n, s), eval(&d, s));
    let radial = ns / ds;
    let dradial = (eval(&derivative(&n), s) * ds - ns * eval(&derivative(&d), s)) / (ds * ds);
    let xd = Vector2::new(
        u * radial + 2.0 * p1 * u * v + p2 * (s + 2.0 * u * u),
        v * radial + 2.0 * p2 * u * v + p1 * (s + 2.0 * v * v),
    );
    let j = Matrix2::new(
        radial + 2.0 * u * u * dradial + 2.0 * p1 * v + 6.0 * p2 * u,
        2.0 * u * v * dradial + 2.0 * p1 * u + 2.0 * p2 * v,
        2.0 * u * v * dradial + 2.0 * p2 * v + 2.0 * p1 * u,
        radial + 2.0 * v * v * dradial + 2.0 * p2 * u + 6.0 * p1 * v,
    );
    (xd, j)
}

/// Whether the distortion is invertible at the undistorted point `x` (see the module
/// documentation).
pub(crate) fn invertible_at(model: CameraModel, k: &[f64; 8], x: Vector2<f64>) -> bool {
    if model.is_pinhole() {
        return true;
    }
    if model == CameraModel::OpenCvFisheye {
        return fisheye_invertible(k, x.norm().atan());
    }
    let (n, d, _, _) = rational(model, k);
    let (_, j) = distort_with_jacobian(model, k, x);
    radial_invertible(&n, &d, x.norm_squared()) && j.determinant() > 0.0
}

/// Undistort normalised coordinates: the `x` with `d(x) = x_d` in the invertible region,
/// by Newton's method (the fisheye in `θ`, the other models in `x` with the Jacobian
/// `∂d/∂x`, each step halved until the residual decreases).
pub(crate) fn undistort(
    model: CameraModel,
    k: &[f64; 8],
    xd: Vector2<f64>,
) -> Result<Vector2<f64>, UndistortFailure> {
    if model.is_pinhole() {
        return Ok(xd);
    }
    let tol = UNDISTORT_TOLERANCE * (1.0 + xd.norm());
    if model == CameraModel::OpenCvFisheye {
        return undistort_fisheye(k, xd, tol);
    }
    let residual = |x: Vector2<f64>| distort_with_jacobian(model, k, x).0 - xd;
    let mut x = xd;
    let mut res = residual(x).norm();
    for _ in 0..MAX_UNDISTORT_ITERATIONS {
        if res <= tol * 1e-3 {
            break;
        }
        let (dx, j) = distort_with_jacobian(model, k, x);
        let Some(inv) = j.try_inverse() else {
            return Err(beyond_reach(model, k, xd));
        };
        let step = inv * (dx - xd);
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..40 {
            let next = x - step * scale;
            let r = residual(next).norm();
            if r < res {
                x = next;
                res = r;
                improved = true;
                break;
            }
            scale *= 0.5;
        }
        if !improved {
            break;
        }
    }
    if res.is_nan() || res > tol || !x.iter().all(|c| c.is_finite()) {
        return Err(beyond_reach(model, k, xd));
    }
    if !invertible_at(model, k, x) {
        return Err(UndistortFailure::NotInvertible);
    }
    Ok(x)
}

/// Why Newton's iteration failed for `x_d` (non-fisheye models): `NotInvertible` if the
/// radial map `ρ(r)` stops increasing (or its denominator vanishes) at some `r_max` with
/// `ρ(r_max) < |x_d|`, so that no point of the invertible region reaches the pixel's radius
/// (the tangential terms aside), else `NotConverged`.
fn beyond_reach(model: CameraModel, k: &[f64; 8], xd: Vector2<f64>) -> UndistortFailure {
    let (n, d, _, _) = rational(model, k);
    let p = radial_slope_numerator(&n, &d);
    // Far beyond any lens's field of view (r = 100).
    let s_far = 1e4;
    let first = roots_in(&p, 0.0, s_far)
        .into_iter()
        .chain(roots_in(&d, 0.0, s_far))
        .fold(f64::INFINITY, f64::min);
    if first.is_finite() {
        let reach = first.sqrt() * eval(&n, first) / eval(&d, first);
        if reach.is_nan() || reach < xd.norm() {
            return UndistortFailure::NotInvertible;
        }
    }
    UndistortFailure::NotConverged
}

/// The fisheye's undistortion: `θ_d` is increasing on `[0, θ_max]`, `θ_max` the first
/// root of `θ_d'` below `π/2` (else `π/2`); solve `θ_d(θ) = |x_d|` there by Newton's method
/// kept inside a bisection bracket, then `x = x_d tan(θ) / |x_d|`.
fn undistort_fisheye(
    k: &[f64; 8],
    xd: Vector2<f64>,
    tol: f64,
) -> Result<Vector2<f64>, UndistortFailure> {
    let rd = xd.norm();
    if rd <= f64::EPSILON {
        return Ok(xd);
    }
    let half_pi = std::f64::consts::FRAC_PI_2;
    let dpoly = [1.0, 3.0 * k[0], 5.0 * k[1], 7.0 * k[2], 9.0 * k[3]];
    let theta_max = roots_in(&dpoly, 0.0, half_pi * half_pi)
        .first()
        .map_or(half_pi, |s| s.sqrt());
    let (mut lo, mut hi) = (0.0, theta_max);
    let reach = fisheye_theta_d(k, hi).0;
    if reach.is_nan() || reach < rd {
        return Err(UndistortFailure::NotInvertible);
    }
    let mut theta = rd.min(0.5 * hi);
    for _ in 0..MAX_UNDISTORT_ITERATIONS {
        let (td, dtd) = fisheye_theta_d(k, theta);
        let f = td - rd;
        if f.abs() <= tol * 1e-3 {
            break;
        }
        if f < 0.0 {
            lo = theta;
        } else {
            hi = theta;
        }
        let newton = theta - f / dtd;
        let next = if dtd > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == theta {
            break;
        }
        theta = next;
    }
    let miss = (fisheye_theta_d(k, theta).0 - rd).abs();
    if miss.is_nan() || miss > tol {
        return Err(UndistortFailure::NotConverged);
    }
    if !fisheye_invertible(k, theta) {
        return Err(UndistortFailure::NotInvertible);
    }
    Ok(xd * (theta.tan() / rd))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_positivity_finds_interior_minima() {
        // 1 - 3s + 2s² = (1 - s)(1 - 2s): negative on (0.5, 1), positive again beyond.
        let p = [1.0, -3.0, 2.0];
        assert!(positive_on(&p, 0.4));
        assert!(!positive_on(&p, 0.7));
        assert!(!positive_on(&p, 3.0));
        // (s - 0.5)² (s + 1) + 0.01 > 0 everywhere; the cubic's interior minimum is found.
        let q = [0.26, -0.75, 0.0, 1.0];
        assert!(positive_on(&q, 3.0));
        assert!(!positive_on(&[0.24, -0.75, 0.0, 1.0], 3.0));
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let k = [0.1, -0.05, 0.01, -0.02, 0.003, 0.02, -0.01, 0.004];
        let x = Vector2::new(0.3, -0.2);
        for model in CameraModel::ALL {
            let (_, j) = distort_with_jacobian(model, &k, x);
            let h = 1e-7;
            for c in 0..2 {
                let mut e = Vector2::zeros();
                e[c] = h;
                let fd = (distort_with_jacobian(model, &k, x + e).0
                    - distort_with_jacobian(model, &k, x - e).0)
                    / (2.0 * h);
                assert!((j.column(c) - fd).norm() < 1e-7, "{model}: {j} vs {fd}");
            }
        }
    }
}
