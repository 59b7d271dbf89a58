//! Adapter between the estimator and the minimal solvers emitted into `crate::generated`
//! (each a `mingen_runtime::MinimalSolver`). Only this file changes if the generated API
//! shifts.
//!
//! Generated API coded against:
//! - `generated::gs5pt::{Data { e1, e2, e3, e4 }, Solution { x, y, z }, solve}`: the four
//!   row-major nullspace matrices of the 5x9 epipolar system; `E = x E1 + y E2 + z E3 + E4`.
//! - `generated::grsrp10` / `generated::grsrp`: `Data { x1, x2: [[f64; 2]; 5], v1, v2: [f64; 5],
//!   w1, w2: [f64; 3], r0: [[f64; 3]; 3] }` with normalised image points (bearing
//!   `[x, y, 1]`), rows in pixels, `w = −λ ω` (rad/row, the paper's sign: [`crate::model::camera::View::paper_rate_per_row`]), `R_0` row-major;
//!   `Solution { a: [f64; 3], t: [f64; 3] }` and `R = R_0 exp([a]×)`.
//! - `generated::grsrp_gravity` / `generated::grsrp_gravity6` (t eliminated): `Data { x1,
//!   x2: [[f64; 2]; 3], v1, v2: [f64; 3], w1, w2, g1, g2: [[f64; 3]; 3] }` (points, rows and
//!   rates as for G-RSRP; `G_c` row-major rotations taking each camera's gravity to the y
//!   axis), `Solution { c, s, t }` with `R = G2^T Ry(c, s) G1`,
//!   `Ry = [[c, 0, s], [0, 1, 0], [−s, 0, c]]`; `grsrp_gravity` gives each pose with both
//!   signs of `t`.
//!
//! Also provides the linear 8-point essential solver (non-minimal, needs ≥ 8 points), usable
//! as a non-minimal alternative to the 5-point solver ([`EssentialSolver::EightPoint`]).

use crate::model::epipolar::PointData;
use crate::model::geometry::{epipolar_nullspace, exp_so3};
use mingen_runtime::{FlatValues, MinimalSolver};
use nalgebra::{Matrix3, SMatrix, Vector3};

use crate::generated;

/// Which essential-matrix solver the `gsrp`, `rectified` (and `R_0` of `grsrp`) use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EssentialSolver {
    /// The generated 5-point solver (minimal, up to 10 solutions). Default.
    #[default]
    FivePoint,
    /// Linear 8-point algorithm (non-minimal; for testing and as a fallback).
    EightPoint,
}

crate::names::name_table!(
    EssentialSolver,
    "solver",
    [FivePoint = "five_point", EightPoint = "eight_point"]
);

impl EssentialSolver {
    /// Points per sample.
    pub fn sample_size(&self) -> usize {
        match self {
            EssentialSolver::FivePoint => 5,
            EssentialSolver::EightPoint => 8,
        }
    }

    /// Essential matrices consistent with the bearing pairs (`b2^T E b1 = 0`), appended to
    /// `out`. `b1.len() == b2.len() == sample_size()`.
    pub fn solve(&self, b1: &[Vector3<f64>], b2: &[Vector3<f64>], out: &mut Vec<Matrix3<f64>>) {
        match self {
            EssentialSolver::FivePoint => {
                if b1.len() == 5 && b2.len() == 5 {
                    essential_5pt(
                        &std::array::from_fn(|k| b1[k]),
                        &std::array::from_fn(|k| b2[k]),
                        out,
                    )
                }
            }
            EssentialSolver::EightPoint => {
                if let Some(e) = essential_8pt(b1, b2) {
                    out.push(e)
                }
            }
        }
    }
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// 5-point solver: nullspace basis ([`epipolar_nullspace`]) + generated `gs5pt` solve.
/// Appends the (finite) essential matrices, Frobenius-normalised.
pub fn essential_5pt(b1: &[Vector3<f64>; 5], b2: &[Vector3<f64>; 5], out: &mut Vec<Matrix3<f64>>) {
    let Some(basis) = epipolar_nullspace(b1, b2) else {
        return;
    };
    let data = generated::gs5pt::Data {
        e1: rows(&basis[0]),
        e2: rows(&basis[1]),
        e3: rows(&basis[2]),
        e4: rows(&basis[3]),
    };
    let sols = generated::gs5pt::solve(&data);
    for s in sols.iter() {
        let e = basis[0] * s.x + basis[1] * s.y + basis[2] * s.z + basis[3];
        let n = e.norm();
        if n.is_finite() && n > 0.0 {
            out.push(e / n);
        }
    }
}

/// Linear 8-point essential matrix from `n ≥ 8` bearing pairs: least-squares null vector of
/// the `n x 9` constraint matrix (via the 9x9 normal matrix's eigenvector), projected onto
/// the essential manifold (singular values `(1, 1, 0)`). `None` on degenerate input.
pub fn essential_8pt(b1: &[Vector3<f64>], b2: &[Vector3<f64>]) -> Option<Matrix3<f64>> {
    if b1.len() < 8 || b1.len() != b2.len() {
        return None;
    }
    let mut ata = SMatrix::<f64, 9, 9>::zeros();
    for (p, q) in b1.iter().zip(b2) {
        let p = p.normalize();
        let q = q.normalize();
        let row = SMatrix::<f64, 9, 1>::from_fn(|k, _| q[k / 3] * p[k % 3]);
        ata += row * row.transpose();
    }
    if !ata.iter().all(|x| x.is_finite()) {
        return None;
    }
    let eig = ata.try_symmetric_eigen(1e-15, 500)?;
    let imin = (0..9).min_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]))?;
    let v = eig.eigenvectors.column(imin);
    let e = Matrix3::from_fn(|i, j| v[3 * i + j]);
    let svd = e.try_svd(true, true, 1e-15, 200)?;
    let (u, vt) = (svd.u?, svd.v_t?);
    let mut s = svd.singular_values;
    // Zero the smallest singular value, equalise the other two.
    let imin = (0..3).min_by(|&a, &b| s[a].total_cmp(&s[b]))?;
    for k in 0..3 {
        s[k] = if k == imin { 0.0 } else { 1.0 };
    }
    let e = u * Matrix3::from_diagonal(&s) * vt;
    e.iter().all(|x| x.is_finite()).then_some(e)
}

/// Which generated G-RSRP solver to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GrsrpSolver {
    /// `grsrp10`: `t` eliminated, 10 solutions (t up to sign). Default.
    #[default]
    Ten,
    /// `grsrp`: the paper's 6-unknown formulation, 20 solutions (±t).
    Twenty,
}

crate::names::name_table!(GrsrpSolver, "solver", [Ten = "ten", Twenty = "twenty"]);

/// One minimal G-RSRP sample: normalised image points `x = [m.x, m.y]` (bearing `[x, y, 1]`),
/// rows `v` (pixels), `w = −λ ω` (rad/row, the paper's sign: [`crate::model::camera::View::paper_rate_per_row`]), initial rotation `R_0`.
#[derive(Debug, Clone, Copy)]
pub struct GrsrpSample {
    /// Image-1 normalised points.
    pub x1: [[f64; 2]; 5],
    /// Image-2 normalised points.
    pub x2: [[f64; 2]; 5],
    /// Image-1 rows.
    pub v1: [f64; 5],
    /// Image-2 rows.
    pub v2: [f64; 5],
    /// `−λ ω1`.
    pub w1: Vector3<f64>,
    /// `−λ ω2`.
    pub w2: Vector3<f64>,
    /// `R_0`.
    pub r0: Matrix3<f64>,
}

impl GrsrpSample {
    /// The sample of the matches `sample` (indices into `data`): their normalised points and
    /// rows, the views' rates `w = −λ ω` as `data` holds them, and `r0`.
    pub fn from_points(data: &PointData, sample: &[usize; 5], r0: Matrix3<f64>) -> Self {
        GrsrpSample {
            x1: sample.map(|i| [data.m1[i].x, data.m1[i].y]),
            x2: sample.map(|i| [data.m2[i].x, data.m2[i].y]),
            v1: sample.map(|i| data.v1[i]),
            v2: sample.map(|i| data.v2[i]),
            w1: data.w1,
            w2: data.w2,
            r0,
        }
    }

    /// The flat data of the `grsrp10` / `grsrp` problem files (their data declarations are
    /// the same): `x1[5]: point, x2[5]: point, v1[5], v2[5], w1: vec3, w2: vec3,
    /// R0: rotation`, in the slot order of [`FlatValues`].
    fn slots(&self) -> [f64; GRSRP_SLOTS] {
        let points = self.x1.iter().chain(&self.x2).flatten();
        let scalars = self.v1.iter().chain(&self.v2);
        let vectors = self.w1.iter().chain(self.w2.iter());
        let r0 = (0..9).map(|k| &self.r0[(k / 3, k % 3)]);
        fill(points.chain(scalars).chain(vectors).chain(r0))
    }
}

/// Data slots of the G-RSRP problem files: 2 x 5 points (2 slots each), 2 x 5 rows,
/// 2 rates (3 each), `R_0` (9).
const GRSRP_SLOTS: usize = 20 + 10 + 6 + 9;

/// The flat slots of a problem's data, in order.
fn fill<'a, const N: usize>(values: impl Iterator<Item = &'a f64>) -> [f64; N] {
    let mut s = [0.0; N];
    for (d, x) in s.iter_mut().zip(values) {
        *d = *x;
    }
    s
}

/// Runs the solver `S` on flat data and calls `each` with the flat unknowns (`U` of them)
/// of every solution; nothing if the data do not fit `S`.
fn solve_flat<S: MinimalSolver, const U: usize>(slots: &[f64], mut each: impl FnMut(&[f64; U])) {
    let Some(data) = S::Data::from_flat(slots) else {
        return;
    };
    let mut u = [0.0; U];
    for sol in S::solve(&data).as_ref() {
        if !sol.write_flat(&mut u) {
            return;
        }
        each(&u);
    }
}

/// Runs the G-RSRP solver `S` on `sample`; its unknowns are `a[3], t[3]` (in that order).
fn solve_grsrp<S: MinimalSolver>(
    sample: &GrsrpSample,
    out: &mut Vec<(Matrix3<f64>, Vector3<f64>)>,
) {
    solve_flat::<S, 6>(&sample.slots(), |u| {
        let a = Vector3::new(u[0], u[1], u[2]);
        let t = Vector3::new(u[3], u[4], u[5]);
        let n = t.norm();
        if a.iter().all(|x| x.is_finite()) && n.is_finite() && n > 0.0 {
            out.push((sample.r0 * exp_so3(&a), t / n));
        }
    });
}

impl GrsrpSolver {
    /// Solve one sample; appends `(R = R_0 exp([a]×), t / |t|)` for each finite solution.
    pub fn solve(&self, s: &GrsrpSample, out: &mut Vec<(Matrix3<f64>, Vector3<f64>)>) {
        match self {
            GrsrpSolver::Ten => solve_grsrp::<generated::grsrp10::Solver>(s, out),
            GrsrpSolver::Twenty => solve_grsrp::<generated::grsrp::Solver>(s, out),
        }
    }
}

/// One minimal known-gravity sample (`templates/grsrp_gravity.mp`): three matches as for
/// [`GrsrpSample`] (normalised points, rows, `w = −λ ω`) and the rotations `G1`, `G2` that
/// take each camera's gravity direction to the y axis (`G_c g_c = e_y`).
#[derive(Debug, Clone, Copy)]
pub struct GravitySample {
    /// Image-1 normalised points.
    pub x1: [[f64; 2]; 3],
    /// Image-2 normalised points.
    pub x2: [[f64; 2]; 3],
    /// Image-1 rows.
    pub v1: [f64; 3],
    /// Image-2 rows.
    pub v2: [f64; 3],
    /// `−λ ω1`.
    pub w1: Vector3<f64>,
    /// `−λ ω2`.
    pub w2: Vector3<f64>,
    /// `G1`.
    pub g1: Matrix3<f64>,
    /// `G2`.
    pub g2: Matrix3<f64>,
}

impl GravitySample {
    /// The sample of the matches `sample` (indices into `data`) for views whose gravity
    /// directions are `gravity` (camera axes, any length) and whose frames have `rows`
    /// rows: normalised points and rows from `data`, the alignments
    /// [`gravity_alignment`], and the views' rates `w = −λ ω` through
    /// [`gravity_solver_rate`].
    pub fn from_points(
        data: &PointData,
        sample: &[usize; 3],
        gravity: [Vector3<f64>; 2],
        rows: [f64; 2],
    ) -> Self {
        GravitySample {
            x1: sample.map(|i| [data.m1[i].x, data.m1[i].y]),
            x2: sample.map(|i| [data.m2[i].x, data.m2[i].y]),
            v1: sample.map(|i| data.v1[i]),
            v2: sample.map(|i| data.v2[i]),
            w1: gravity_solver_rate(&data.w1, rows[0]),
            w2: gravity_solver_rate(&data.w2, rows[1]),
            g1: gravity_alignment(&gravity[0]),
            g2: gravity_alignment(&gravity[1]),
        }
    }

    /// The flat data of the `grsrp_gravity` / `grsrp_gravity6` problem files (the same data
    /// declarations): `x1[3]: point, x2[3]: point, v1[3], v2[3], w1: vec3, w2: vec3,
    /// G1: rotation, G2: rotation`, in the slot order of [`FlatValues`].
    fn slots(&self) -> [f64; GRAVITY_SLOTS] {
        let points = self.x1.iter().chain(&self.x2).flatten();
        let scalars = self.v1.iter().chain(&self.v2);
        let vectors = self.w1.iter().chain(self.w2.iter());
        let g = (0..18).map(|k| {
            let m = if k < 9 { &self.g1 } else { &self.g2 };
            &m[((k % 9) / 3, k % 3)]
        });
        fill(points.chain(scalars).chain(vectors).chain(g))
    }
}

/// Data slots of the known-gravity problem files: 2 x 3 points (2 slots each), 2 x 3 rows,
/// 2 rates (3 each), `G1`, `G2` (9 each).
const GRAVITY_SLOTS: usize = 12 + 6 + 6 + 18;

/// The rotation `G` with `G g = e_y` (the smallest such rotation; `g` any non-zero length).
pub fn gravity_alignment(g: &Vector3<f64>) -> Matrix3<f64> {
    let u = g.normalize();
    let axis = u.cross(&Vector3::y());
    let (sn, cs) = (axis.norm(), u.y);
    if sn < 1e-12 {
        // Parallel (identity) or antiparallel (half a turn about x).
        return if cs > 0.0 {
            Matrix3::identity()
        } else {
            Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0))
        };
    }
    exp_so3(&(axis * (sn.atan2(cs) / sn)))
}

/// Which generated known-gravity solver to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GravitySolver {
    /// `grsrp_gravity6`: `t` eliminated, 6 solutions (t up to sign), a 9 x 15 template.
    /// Default.
    #[default]
    Six,
    /// `grsrp_gravity`: 5 unknowns, 12 solutions (±t), a 71 x 83 template (a weighted
    /// monomial order) after its equations are row-reduced on the data.
    Twelve,
}

crate::names::name_table!(GravitySolver, "solver", [Six = "six", Twelve = "twelve"]);

impl GravitySolver {
    /// Solve one sample; appends `(R = G2^T Ry G1, t / |t|)` for each finite solution
    /// (`(c, s)` normalised onto the unit circle; `Twelve` gives each pose with both signs
    /// of `t`). Both templates are degenerate when a view's rate `w` vanishes (no solution);
    /// see [`gravity_solver_rate`].
    pub fn solve(&self, s: &GravitySample, out: &mut Vec<(Matrix3<f64>, Vector3<f64>)>) {
        match self {
            GravitySolver::Six => solve_gravity::<generated::grsrp_gravity6::Solver>(s, out),
            GravitySolver::Twelve => solve_gravity::<generated::grsrp_gravity::Solver>(s, out),
        }
    }
}

/// The smallest rotation over a frame, rad, that [`gravity_solver_rate`] passes to the
/// known-gravity solvers.
pub const MIN_GRAVITY_SOLVER_ROTATION: f64 = 1e-3;

/// The rate `w` (rad/row) to give the known-gravity solvers for a view whose rate is `w`
/// and whose frame has `rows` rows. Their elimination templates, built on generic data,
/// lose pivots when a view's `w` vanishes (a global-shutter or still camera): a rate that
/// turns the frame by less than [`MIN_GRAVITY_SOLVER_ROTATION`] gets that much added, a
/// model error of at most that angle (0.6 px at f = 640 px), far inside the consensus
/// threshold `grsrp-gravity` scores the solver's hypotheses with.
pub fn gravity_solver_rate(w: &Vector3<f64>, rows: f64) -> Vector3<f64> {
    let rows = rows.max(1.0);
    if w.norm() * rows >= MIN_GRAVITY_SOLVER_ROTATION {
        return *w;
    }
    let dither = Vector3::new(1.0, 1.0, 1.0).normalize() * (MIN_GRAVITY_SOLVER_ROTATION / rows);
    w + dither
}

/// Runs the known-gravity solver `S` on `sample`; its unknowns are `c, s, t[3]`.
fn solve_gravity<S: MinimalSolver>(
    sample: &GravitySample,
    out: &mut Vec<(Matrix3<f64>, Vector3<f64>)>,
) {
    solve_flat::<S, 5>(&sample.slots(), |u| {
        let (n, t) = (u[0].hypot(u[1]), Vector3::new(u[2], u[3], u[4]));
        let tn = t.norm();
        if n.is_finite() && n > 0.0 && tn.is_finite() && tn > 0.0 {
            let (c, sn) = (u[0] / n, u[1] / n);
            let ry = Matrix3::new(c, 0.0, sn, 0.0, 1.0, 0.0, -sn, 0.0, c);
            out.push((sample.g2.transpose() * ry * sample.g1, t / tn));
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::{essential_from_pose, exp_so3};

    #[test]
    fn grsrp_slots_follow_the_generated_data_layout() {
        let s = GrsrpSample {
            x1: std::array::from_fn(|k| [k as f64, 10.0 + k as f64]),
            x2: std::array::from_fn(|k| [20.0 + k as f64, 30.0 + k as f64]),
            v1: std::array::from_fn(|k| 40.0 + k as f64),
            v2: std::array::from_fn(|k| 50.0 + k as f64),
            w1: Vector3::new(60.0, 61.0, 62.0),
            w2: Vector3::new(70.0, 71.0, 72.0),
            r0: Matrix3::from_fn(|i, j| 80.0 + (3 * i + j) as f64),
        };
        let typed = generated::grsrp10::Data {
            x1: s.x1,
            x2: s.x2,
            v1: s.v1,
            v2: s.v2,
            w1: s.w1.into(),
            w2: s.w2.into(),
            r0: rows(&s.r0),
        };
        assert_eq!(s.slots(), typed.to_slots());
        assert_eq!(
            <generated::grsrp::Solver as MinimalSolver>::Data::from_flat(&s.slots())
                .map(|d| d.to_slots()),
            Some(typed.to_slots())
        );
    }

    #[test]
    fn gravity_alignment_takes_gravity_to_y() {
        for g in [
            Vector3::new(0.3, -9.0, 2.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(0.0, -2.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
        ] {
            let a = gravity_alignment(&g);
            assert!((a * g.normalize() - Vector3::y()).norm() < 1e-12, "{g}");
            assert!((a.transpose() * a - Matrix3::identity()).norm() < 1e-12);
            assert!((a.determinant() - 1.0).abs() < 1e-12);
        }
    }

    /// A planted pose with exact gravity and the paper's row model (`w = −λω`): one of each
    /// solver's poses is the planted one, with the data in the generated slot order. With a
    /// rate of zero the templates are degenerate; the dithered rate restores them.
    #[test]
    fn the_gravity_solvers_find_a_planted_pose() {
        let r = exp_so3(&Vector3::new(0.1, -0.25, 0.05));
        let t = Vector3::new(0.4, -0.2, 0.9).normalize();
        let g1 = Vector3::new(0.2, 0.95, -0.1).normalize();
        let g2 = r * g1;
        let plant = |w1: Vector3<f64>, w2: Vector3<f64>| {
            // x1 and its row, then x2 on the epipolar line of
            // (I + v2 [w2]×) R (I − v1 [w1]×) x1 at a chosen row.
            let mut s = GravitySample {
                x1: [[0.0; 2]; 3],
                x2: [[0.0; 2]; 3],
                v1: [0.0; 3],
                v2: [0.0; 3],
                w1,
                w2,
                g1: gravity_alignment(&g1),
                g2: gravity_alignment(&g2),
            };
            for k in 0..3 {
                let m1 = Vector3::new(0.3 * k as f64 - 0.3, 0.2 - 0.15 * k as f64, 1.0);
                let (v1, v2) = (200.0 + 300.0 * k as f64, 700.0 - 200.0 * k as f64);
                let y = r * (m1 - (w1 * v1).cross(&m1));
                let l = t.cross(&(y + (w2 * v2).cross(&y)));
                let x = 0.1 * k as f64;
                s.x1[k] = [m1.x, m1.y];
                s.x2[k] = [x, -(l.x * x + l.z) / l.y];
                s.v1[k] = v1;
                s.v2[k] = v2;
            }
            s
        };
        let best = |out: &[(Matrix3<f64>, Vector3<f64>)]| {
            out.iter()
                .map(|(rr, tt)| (rr - r).norm() + (tt - t).norm().min((tt + t).norm()))
                .fold(f64::INFINITY, f64::min)
        };
        let s = plant(
            Vector3::new(1e-5, -3e-5, 2e-5),
            Vector3::new(-2e-5, 1e-5, 3e-5),
        );
        let typed = generated::grsrp_gravity::Data {
            x1: s.x1,
            x2: s.x2,
            v1: s.v1,
            v2: s.v2,
            w1: s.w1.into(),
            w2: s.w2.into(),
            g1: rows(&s.g1),
            g2: rows(&s.g2),
        };
        assert_eq!(s.slots(), typed.to_slots());
        let still = plant(Vector3::zeros(), Vector3::zeros());
        let dithered = GravitySample {
            w1: gravity_solver_rate(&still.w1, 1080.0),
            w2: gravity_solver_rate(&still.w2, 1080.0),
            ..still
        };
        for solver in [GravitySolver::Six, GravitySolver::Twelve] {
            let mut out = Vec::new();
            solver.solve(&s, &mut out);
            assert!(best(&out) < 1e-8, "{solver:?}: {}", best(&out));
            out.clear();
            solver.solve(&still, &mut out);
            assert!(
                out.is_empty(),
                "{solver:?}: the degenerate instance has solutions"
            );
            solver.solve(&dithered, &mut out);
            // Near the pose: the dither is a model error of 1e-3 rad, which the translation
            // direction, fitted to three points, amplifies.
            assert!(best(&out) < 2e-2, "{solver:?}: {}", best(&out));
        }
        assert_eq!(gravity_solver_rate(&s.w1, 1080.0), s.w1);
    }

    #[test]
    fn eight_point_recovers_noise_free_essential() {
        let r = exp_so3(&Vector3::new(0.1, -0.2, 0.05));
        let t = Vector3::new(0.3, -0.1, 0.8).normalize();
        let mut b1 = Vec::new();
        let mut b2 = Vec::new();
        for k in 0..12 {
            let x = Vector3::new(
                (k as f64 * 0.7).sin() * 3.0,
                (k as f64 * 1.3).cos() * 2.0,
                5.0 + k as f64,
            );
            b1.push(x);
            b2.push(r * x + t);
        }
        let e = essential_8pt(&b1, &b2).unwrap();
        let e_true = essential_from_pose(&r, &t).normalize();
        let e = e.normalize();
        assert!((e - e_true).norm() < 1e-9 || (e + e_true).norm() < 1e-9);
        assert!(essential_8pt(&b1[..7], &b2[..7]).is_none());
        let nan = vec![Vector3::new(f64::NAN, 0.0, 1.0); 8];
        assert!(essential_8pt(&nan, &nan).is_none());
    }
}
