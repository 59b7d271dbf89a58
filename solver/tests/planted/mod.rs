//! Random instances of the generated solvers with a planted real solution, shared by the
//! accuracy test (`tests/generated_accuracy.rs`) and the benchmark (`benches/solvers.rs`).

#![allow(dead_code)]

use nalgebra::{Matrix3, Vector3};
use rand::Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, gs5pt};
use rspose::model::geometry::{epipolar_nullspace, exp_so3, skew};

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

fn unit<R: Rng>(rng: &mut R) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

fn rotation<R: Rng>(rng: &mut R, max_angle: f64) -> Matrix3<f64> {
    exp_so3(&(unit(rng) * rng.gen_range(0.0..max_angle)))
}

/// A 5-point instance: the nullspace basis of five random correspondences of a random
/// pose, and the true essential matrix (Frobenius-normalised).
pub struct Gs5pt {
    pub data: gs5pt::Data,
    pub basis: [Matrix3<f64>; 4],
    pub e_true: Matrix3<f64>,
    /// The five bearing pairs (unnormalised rays) the basis was computed from.
    pub bearings: ([Vector3<f64>; 5], [Vector3<f64>; 5]),
}

pub fn gs5pt_instance<R: Rng>(rng: &mut R) -> Gs5pt {
    loop {
        let r = rotation(rng, 0.5);
        let t = unit(rng);
        let mut b1 = [Vector3::zeros(); 5];
        let mut b2 = [Vector3::zeros(); 5];
        for k in 0..5 {
            let x = Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0)
                * rng.gen_range(2.0..10.0);
            b1[k] = x;
            b2[k] = r * x + t;
        }
        let Some(basis) = epipolar_nullspace(&b1, &b2) else {
            continue;
        };
        let e_true = (skew(&t) * r).normalize();
        return Gs5pt {
            data: gs5pt::Data {
                e1: rows(&basis[0]),
                e2: rows(&basis[1]),
                e3: rows(&basis[2]),
                e4: rows(&basis[3]),
            },
            basis,
            e_true,
            bearings: (b1, b2),
        };
    }
}

/// Smallest sign-invariant distance between the planted essential matrix and a solution's.
pub fn gs5pt_error(inst: &Gs5pt, sols: &gs5pt::Solutions) -> f64 {
    let mut best = f64::INFINITY;
    for s in sols.iter() {
        let e = inst.basis[0] * s.x + inst.basis[1] * s.y + inst.basis[2] * s.z + inst.basis[3];
        let e = e / e.norm();
        let d = (e - inst.e_true).norm().min((e + inst.e_true).norm());
        if d.is_finite() {
            best = best.min(d);
        }
    }
    best
}

/// Shared G-RSRP data: five correspondences consistent with the linearised model
/// `x2' [t]x (I + v2 [w2]x) R0 (I + [a]x) (I - v1 [w1]x) x1 = 0`, realistic magnitudes
/// (normalised points in [-0.6, 0.6], rows in [0, 720] pixels, `w` about 1e-4 rad/row,
/// `|a|` about 0.05 rad).
pub struct Grsrp {
    pub x1: [[f64; 2]; 5],
    pub x2: [[f64; 2]; 5],
    pub v1: [f64; 5],
    pub v2: [f64; 5],
    pub w1: [f64; 3],
    pub w2: [f64; 3],
    pub r0: [[f64; 3]; 3],
    pub a: Vector3<f64>,
    pub t: Vector3<f64>,
}

/// A point `[x, y]` on the line `l . [x, y, 1] = 0` near the image centre, or `None`.
fn on_line<R: Rng>(rng: &mut R, l: &Vector3<f64>) -> Option<[f64; 2]> {
    let s = rng.gen_range(-0.6..0.6);
    let p = if l.y.abs() >= l.x.abs() {
        [s, -(l.x * s + l.z) / l.y]
    } else {
        [-(l.y * s + l.z) / l.x, s]
    };
    (p[0].abs() < 2.0 && p[1].abs() < 2.0).then_some(p)
}

pub fn grsrp_instance<R: Rng>(rng: &mut R) -> Grsrp {
    'retry: loop {
        let r0 = rotation(rng, 0.5);
        let a = unit(rng) * rng.gen_range(0.02..0.1);
        let t = unit(rng);
        let w1 = unit(rng) * rng.gen_range(0.0..2e-4);
        let w2 = unit(rng) * rng.gen_range(0.0..2e-4);
        let mut inst = Grsrp {
            x1: [[0.0; 2]; 5],
            x2: [[0.0; 2]; 5],
            v1: [0.0; 5],
            v2: [0.0; 5],
            w1: w1.into(),
            w2: w2.into(),
            r0: rows(&r0),
            a,
            t,
        };
        let i = Matrix3::identity();
        for k in 0..5 {
            let x1 = [rng.gen_range(-0.6..0.6), rng.gen_range(-0.6..0.6)];
            let v1 = rng.gen_range(0.0..720.0);
            let v2 = rng.gen_range(0.0..720.0);
            let m = (i + skew(&w2) * v2) * r0 * (i + skew(&a)) * (i - skew(&w1) * v1);
            let l = skew(&t) * m * Vector3::new(x1[0], x1[1], 1.0);
            let Some(x2) = on_line(rng, &l) else {
                continue 'retry;
            };
            inst.x1[k] = x1;
            inst.x2[k] = x2;
            inst.v1[k] = v1;
            inst.v2[k] = v2;
        }
        return inst;
    }
}

impl Grsrp {
    pub fn data10(&self) -> grsrp10::Data {
        grsrp10::Data {
            x1: self.x1,
            x2: self.x2,
            v1: self.v1,
            v2: self.v2,
            w1: self.w1,
            w2: self.w2,
            r0: self.r0,
        }
    }
    pub fn data20(&self) -> grsrp::Data {
        grsrp::Data {
            x1: self.x1,
            x2: self.x2,
            v1: self.v1,
            v2: self.v2,
            w1: self.w1,
            w2: self.w2,
            r0: self.r0,
        }
    }
    /// Relative error of the closest solution `(a, t)` (t up to sign).
    pub fn error<'a>(&self, sols: impl Iterator<Item = ([f64; 3], [f64; 3])> + 'a) -> f64 {
        let scale = (self.a.norm_squared() + 1.0).sqrt();
        let mut best = f64::INFINITY;
        for (a, t) in sols {
            let (a, t) = (Vector3::from(a), Vector3::from(t));
            let tn = t / t.norm();
            let dt = (tn - self.t).norm().min((tn + self.t).norm());
            let d = ((a - self.a).norm_squared() + dt * dt).sqrt() / scale;
            if d.is_finite() {
                best = best.min(d);
            }
        }
        best
    }
}

/// A G-RSRP-with-gravity instance (3 correspondences), planted yaw and translation.
pub struct Gravity {
    pub data: grsrp_gravity::Data,
    pub c: f64,
    pub s: f64,
    pub t: Vector3<f64>,
}

pub fn gravity_instance<R: Rng>(rng: &mut R) -> Gravity {
    'retry: loop {
        let g1 = rotation(rng, 0.3);
        let g2 = rotation(rng, 0.3);
        let yaw: f64 = rng.gen_range(-1.0..1.0);
        let (s, c) = yaw.sin_cos();
        let ry = Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
        let r = g2.transpose() * ry * g1;
        let t = unit(rng);
        let w1 = unit(rng) * rng.gen_range(0.0..2e-4);
        let w2 = unit(rng) * rng.gen_range(0.0..2e-4);
        let mut data = grsrp_gravity::Data {
            x1: [[0.0; 2]; 3],
            x2: [[0.0; 2]; 3],
            v1: [0.0; 3],
            v2: [0.0; 3],
            w1: w1.into(),
            w2: w2.into(),
            g1: rows(&g1),
            g2: rows(&g2),
        };
        let i = Matrix3::identity();
        for k in 0..3 {
            let x1 = [rng.gen_range(-0.6..0.6), rng.gen_range(-0.6..0.6)];
            let v1 = rng.gen_range(0.0..720.0);
            let v2 = rng.gen_range(0.0..720.0);
            let m = (i + skew(&w2) * v2) * r * (i - skew(&w1) * v1);
            let l = skew(&t) * m * Vector3::new(x1[0], x1[1], 1.0);
            let Some(x2) = on_line(rng, &l) else {
                continue 'retry;
            };
            data.x1[k] = x1;
            data.x2[k] = x2;
            data.v1[k] = v1;
            data.v2[k] = v2;
        }
        return Gravity { data, c, s, t };
    }
}

impl Gravity {
    /// Error of the closest solution `(c, s, t)` (t up to sign).
    pub fn error(&self, sols: &grsrp_gravity::Solutions) -> f64 {
        let mut best = f64::INFINITY;
        for sol in sols.iter() {
            let t = Vector3::from(sol.t);
            let dt = (t - self.t).norm().min((t + self.t).norm());
            let d = ((sol.c - self.c).powi(2) + (sol.s - self.s).powi(2) + dt * dt).sqrt();
            if d.is_finite() {
                best = best.min(d);
            }
        }
        best / 2f64.sqrt()
    }
}
