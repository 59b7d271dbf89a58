//! G-RSRP on data that satisfies its own linearised model exactly (ARCHITECTURE §4):
//! m2ᵀ [t]× (I + v2 [w2]×) R0 (I + [a]×) (I − v1 [w1]×) m1 = 0 with R0 a few degrees off the
//! truth and a known a ≠ 0: both generated solvers (10 and 20 solutions) recover a and t
//! to 1e-9.

use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10};

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

struct Instance {
    x1: [[f64; 2]; 5],
    x2: [[f64; 2]; 5],
    v1: [f64; 5],
    v2: [f64; 5],
    w1: [f64; 3],
    w2: [f64; 3],
    r0: [[f64; 3]; 3],
    a: Vector3<f64>,
    t: Vector3<f64>,
}

fn instance(rng: &mut ChaCha8Rng) -> Instance {
    let r0 = Rotation3::from_scaled_axis(Vector3::new(
        rng.gen_range(-0.3..0.3),
        rng.gen_range(-0.3..0.3),
        rng.gen_range(-0.3..0.3),
    ));
    // a: a few degrees, the correction the linearised model solves for.
    let a = Vector3::new(
        rng.gen_range(-0.06..0.06),
        rng.gen_range(-0.06..0.06),
        rng.gen_range(-0.06..0.06),
    );
    let t = Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
    .normalize();
    // w = λω: 60 µs/row times up to 2.5 rad/s.
    let w1 = Vector3::new(
        rng.gen_range(-1.5e-4..1.5e-4),
        rng.gen_range(-1.5e-4..1.5e-4),
        rng.gen_range(-1.5e-4..1.5e-4),
    );
    let w2 = Vector3::new(
        rng.gen_range(-1.5e-4..1.5e-4),
        rng.gen_range(-1.5e-4..1.5e-4),
        rng.gen_range(-1.5e-4..1.5e-4),
    );
    let i = Matrix3::identity();
    let mut inst = Instance {
        x1: [[0.0; 2]; 5],
        x2: [[0.0; 2]; 5],
        v1: [0.0; 5],
        v2: [0.0; 5],
        w1: w1.into(),
        w2: w2.into(),
        r0: [[0.0; 3]; 3],
        a,
        t,
    };
    for r in 0..3 {
        for c in 0..3 {
            inst.r0[r][c] = r0[(r, c)];
        }
    }
    for k in 0..5 {
        let (v1, v2) = (rng.gen_range(0.0..1080.0), rng.gen_range(0.0..1080.0));
        let m1 = Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-0.8..0.8), 1.0);
        let w = (i + skew(&w2) * v2) * r0.matrix() * (i + skew(&a)) * (i - skew(&w1) * v1);
        // The epipolar line of m1 in image 2; pick x2 and solve the line for y2.
        let l = skew(&t) * w * m1;
        let x2 = rng.gen_range(-1.0..1.0);
        let y2 = -(l.x * x2 + l.z) / l.y;
        inst.x1[k] = [m1.x, m1.y];
        inst.x2[k] = [x2, y2];
        inst.v1[k] = v1;
        inst.v2[k] = v2;
    }
    inst
}

/// Smallest distance of (a, ±t) to the truth over the returned solutions.
fn best_error(sols: impl Iterator<Item = ([f64; 3], [f64; 3])>, inst: &Instance) -> f64 {
    sols.map(|(a, t)| {
        let (a, t) = (Vector3::from(a), Vector3::from(t).normalize());
        (a - inst.a).amax() + (t - inst.t).amax().min((t + inst.t).amax())
    })
    .fold(f64::INFINITY, f64::min)
}

#[test]
fn grsrp_recovers_a_and_t_on_exact_linearised_data() {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let (mut worst10, mut worst20) = (0.0f64, 0.0f64);
    for _ in 0..50 {
        let inst = instance(&mut rng);
        let d10 = grsrp10::Data {
            x1: inst.x1,
            x2: inst.x2,
            v1: inst.v1,
            v2: inst.v2,
            w1: inst.w1,
            w2: inst.w2,
            r0: inst.r0,
        };
        let d20 = grsrp::Data {
            x1: inst.x1,
            x2: inst.x2,
            v1: inst.v1,
            v2: inst.v2,
            w1: inst.w1,
            w2: inst.w2,
            r0: inst.r0,
        };
        let e10 = best_error(grsrp10::solve(&d10).iter().map(|s| (s.a, s.t)), &inst);
        let e20 = best_error(grsrp::solve(&d20).iter().map(|s| (s.a, s.t)), &inst);
        worst10 = worst10.max(e10);
        worst20 = worst20.max(e20);
    }
    println!("worst error over 50 instances: grsrp10 {worst10:.2e}, grsrp {worst20:.2e}");
    assert!(worst10 < 1e-9, "grsrp10: {worst10:e}");
    assert!(worst20 < 1e-9, "grsrp: {worst20:e}");
}
