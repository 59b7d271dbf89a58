//! Tests of the Gauss-Newton polish.

use super::*;

/// The sum of squares `Σ_i f_i(x)²` and whether every equation is at rounding level
/// ([`AT_ROUNDING_LEVEL`]); `None` if an equation is malformed or a value not finite.
fn squared_residual<const M: usize>(
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
    x: &[f64],
) -> Option<(f64, bool)> {
    let powers = Powers::<M>::new(x);
    let mut sum = 0.0;
    let mut converged = true;
    for eq in equations {
        let (f, magnitude) = value(eq, coefficients, &powers)?;
        sum += f * f;
        converged &= f.abs() <= AT_ROUNDING_LEVEL * magnitude;
    }
    sum.is_finite().then_some((sum, converged))
}

/// x² + y² − 2 = 0, x − y = 0, x y − 1 = 0 (overdetermined; root (1, 1)).
fn system() -> (Vec<Vec<NewtonTerm<'static>>>, Vec<f64>) {
    const X2: [u8; 2] = [2, 0];
    const Y2: [u8; 2] = [0, 2];
    const ONE: [u8; 2] = [0, 0];
    const X: [u8; 2] = [1, 0];
    const Y: [u8; 2] = [0, 1];
    const XY: [u8; 2] = [1, 1];
    let eqs = vec![
        vec![(0, &X2[..]), (1, &Y2[..]), (2, &ONE[..])],
        vec![(1, &X[..]), (3, &Y[..])],
        vec![(1, &XY[..]), (3, &ONE[..])],
    ];
    (eqs, vec![1.0, 1.0, -2.0, -1.0])
}

#[test]
fn value_and_gradient_match_the_direct_formula() {
    // 0.5 x^3 y^17 z - 2 y^2 z^4 + 3, exponents past the power table included.
    const A: [u8; 3] = [3, 17, 1];
    const B: [u8; 3] = [0, 2, 4];
    const ONE: [u8; 3] = [0, 0, 0];
    let terms = [(0, &A[..]), (1, &B[..]), (2, &ONE[..])];
    let c = [0.5, -2.0, 3.0];
    let x: [f64; 3] = [1.1, -0.9, 0.7];
    let (a, b, z) = (x[0], x[1], x[2]);
    let f = 0.5 * a.powi(3) * b.powi(17) * z - 2.0 * b * b * z.powi(4) + 3.0;
    let g = [
        1.5 * a * a * b.powi(17) * z,
        8.5 * a.powi(3) * b.powi(16) * z - 4.0 * b * z.powi(4),
        0.5 * a.powi(3) * b.powi(17) - 8.0 * b * b * z.powi(3),
    ];
    let powers = Powers::<3>::new(&x);
    let mut grad = [0.0; 3];
    let (v, magnitude) = value_and_gradient(&terms, &c, &powers, &mut grad).unwrap();
    let close = |p: f64, q: f64| (p - q).abs() <= 1e-14 * q.abs().max(1.0);
    assert!(close(v, f), "{v} {f}");
    assert_eq!(value(&terms, &c, &powers), Some((v, magnitude)));
    for k in 0..3 {
        assert!(close(grad[k], g[k]), "{k}: {} {}", grad[k], g[k]);
    }
}

#[test]
fn converges_quadratically_to_a_root() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    let mut x = [1.0 + 1e-5, 1.0 - 3e-6];
    let steps = newton_polish(&mut x, &eqs, &c, 3);
    assert!(steps >= 1);
    assert!(
        (x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
        "{x:?}"
    );
}

/// The system of [`system`] written out as the emitted solvers write it: the same
/// steps and the same bits as the table form.
#[test]
fn code_form_takes_the_same_steps_as_the_table() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    let values = |x: &[f64; 2], f: &mut [f64; 3], m: &mut [f64; 3]| {
        let t = [
            [c[0] * (x[0] * x[0]), c[1] * (x[1] * x[1]), c[2]],
            [c[1] * x[0], c[3] * x[1], 0.0],
            [c[1] * (x[0] * x[1]), c[3], 0.0],
        ];
        for i in 0..3 {
            f[i] = t[i].iter().sum();
            m[i] = t[i].iter().map(|t| t.abs()).sum();
        }
    };
    let jacobian = |x: &[f64; 2], f: &mut [f64; 3], j: &mut [[f64; 2]; 3]| {
        let mut m = [0.0; 3];
        values(x, f, &mut m);
        *j = [
            [c[0] * 2.0 * x[0], c[1] * 2.0 * x[1]],
            [c[1], c[3]],
            [c[1] * x[1], c[1] * x[0]],
        ];
    };
    for start in [
        [1.3, 0.8],
        [1.0 + 1e-5, 1.0 - 3e-6],
        [3.0, -2.0],
        [1.0, 1.0],
    ] {
        let (mut a, mut b) = (start, start);
        let steps = newton_polish(&mut a, &eqs, &c, 4);
        assert_eq!(newton_polish_with(&mut b, 4, values, jacobian), steps);
        assert_eq!(a, b, "from {start:?}");
    }
    let mut x = [f64::NAN, 1.0];
    assert_eq!(newton_polish_with(&mut x, 4, values, jacobian), 0);
    // The redundant basis's screen: kept as is, rescued by polishing, dropped.
    for start in [
        [1.0, 1.0],
        [1.0 + 1e-3, 1.0 - 2e-3],
        [1.3, 0.8],
        [3.0, -2.0],
    ] {
        let (mut a, mut b) = (start, start);
        let kept = screen_redundant_readout(&mut a, &eqs, &c);
        assert_eq!(
            screen_redundant_readout_with(&mut b, values, jacobian),
            kept
        );
        assert_eq!(a, b, "from {start:?}");
    }
    // Polishing of poor solutions only: the same test and steps.
    for start in [
        [1.0 + 1e-12, 1.0],
        [1.0 + 1e-6, 1.0 - 1e-6],
        [1.3, 0.8],
        [f64::NAN, 1.0],
    ] {
        let (mut a, mut b) = (start, start);
        let steps = polish_poor_solution(&mut a, &eqs, &c);
        assert_eq!(polish_poor_solution_with(&mut b, values, jacobian), steps);
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "from {start:?}");
    }
}

#[test]
fn never_makes_a_solution_worse_and_rejects_bad_input() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    // An exact root: nothing to do.
    let mut x = [1.0, 1.0];
    assert_eq!(newton_polish(&mut x, &eqs, &c, 3), 0);
    assert_eq!(x, [1.0, 1.0]);
    // Non-finite start, coefficient out of range, too few equations: untouched.
    let mut x = [f64::NAN, 1.0];
    assert_eq!(newton_polish(&mut x, &eqs, &c, 3), 0);
    let mut x = [1.1, 0.9];
    assert_eq!(newton_polish(&mut x, &eqs, &c[..2], 3), 0);
    assert_eq!(x, [1.1, 0.9]);
    assert_eq!(newton_polish(&mut x, &eqs[..1], &c, 3), 0);
    // Far from a root the cost still only goes down.
    let before = squared_residual::<3>(&eqs, &c, &[3.0, -2.0]).unwrap().0;
    let mut x = [3.0, -2.0];
    newton_polish(&mut x, &eqs, &c, 8);
    assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().0 <= before);
}

#[test]
fn relative_residuals_tell_roots_from_other_points() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    assert_eq!(worst_relative_residual(&[1.0, 1.0], &eqs, &c), Some(0.0));
    // At (2, 1): x^2 + y^2 - 2 = 3 of terms 4 + 1 + 2; x - y = 1 of 2 + 1; xy - 1 = 1
    // of 2 + 1.
    let r = worst_relative_residual(&[2.0, 1.0], &eqs, &c).unwrap();
    assert!((r - 3.0 / 7.0).abs() < 1e-15, "{r}");
    assert!(r > SPURIOUS_RESIDUAL);
    assert!(worst_relative_residual(&[1.0 + 1e-9, 1.0], &eqs, &c).unwrap() < SPURIOUS_RESIDUAL);
    assert_eq!(worst_relative_residual(&[f64::NAN, 1.0], &eqs, &c), None);
    assert_eq!(worst_relative_residual(&[1.0, 1.0], &eqs, &c[..2]), None);
    assert_eq!(worst_relative_residual(&[0.5; 25], &eqs, &c), None);
    // Screening: a close read-out is kept as it is, a poorer one is rescued by
    // polishing, a far one dropped.
    let mut x = [1.0 + 1e-9, 1.0];
    assert!(screen_redundant_readout(&mut x, &eqs, &c));
    assert_eq!(x, [1.0 + 1e-9, 1.0]);
    let mut x = [1.0 + 2e-3, 1.0 - 1e-3];
    assert!(worst_relative_residual(&x, &eqs, &c).unwrap() > SPURIOUS_RESIDUAL);
    assert!(screen_redundant_readout(&mut x, &eqs, &c));
    assert!(
        (x[0] - 1.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9,
        "{x:?}"
    );
    let mut x = [2.0, 1.0];
    assert!(!screen_redundant_readout(&mut x, &eqs, &c));
    assert_eq!(x, [2.0, 1.0]);
}

/// x^3 - 2x + 2 = 0 from x = 1: the Newton step goes back to 0, where the residual is
/// larger (the classic 0 <-> 1 cycle); a shorter step still descends.
#[test]
fn an_overshooting_step_is_halved() {
    const X3: [u8; 1] = [3];
    const X: [u8; 1] = [1];
    const ONE: [u8; 1] = [0];
    let eq: Vec<NewtonTerm> = vec![(0, &X3[..]), (1, &X[..]), (2, &ONE[..])];
    let eqs = [eq.as_slice()];
    let c = [1.0, -2.0, 2.0];
    let f = |x: f64| x * x * x - 2.0 * x + 2.0;
    let mut x = [1.0];
    assert_eq!(newton_polish(&mut x, &eqs, &c, 1), 1);
    assert!(f(x[0]).abs() < f(1.0).abs(), "{x:?}");
    // x = 0 and 0.5 do not lower the residual; 0.75, a quarter of the step, does.
    assert!((x[0] - 0.75).abs() < 1e-12, "{x:?}");
    // Enough steps reach the real root near -1.7693 and stop there.
    let mut x = [1.0];
    newton_polish(&mut x, &eqs, &c, 8);
    assert!(f(x[0]).abs() < f(1.0).abs(), "{x:?}");
}

/// A root far from the origin: x y = 1, x = 1e6 at (1e6, 1e-6), whose Jacobian
/// [[y, x], [1, 0]] has a condition near 1e12. The normal equations square it beyond
/// f64 (their ridge then damps the step); the step from the Jacobian's QR is accurate.
#[test]
fn a_poorly_conditioned_root_far_out_is_reached() {
    const XY: [u8; 2] = [1, 1];
    const X: [u8; 2] = [1, 0];
    const ONE: [u8; 2] = [0, 0];
    let product: Vec<NewtonTerm> = vec![(0, &XY[..]), (1, &ONE[..])];
    let position: Vec<NewtonTerm> = vec![(0, &X[..]), (2, &ONE[..])];
    let eqs = [product.as_slice(), position.as_slice()];
    let c = [1.0, -1.0, -1e6];
    let mut x = [1e6 * (1.0 + 1e-5), 1e-6 * (1.0 - 1e-5)];
    newton_polish(&mut x, &eqs, &c, 3);
    let r = worst_relative_residual(&x, &eqs, &c).unwrap();
    assert!(r < 1e-14, "{r:e} at {x:?}");
    assert!(
        (x[0] / 1e6 - 1.0).abs() < 1e-14 && (x[1] * 1e6 - 1.0).abs() < 1e-12,
        "{x:?}"
    );
}

/// An overdetermined system with a root far out, (1e5, 1e-3): x y = 100, x = 1e5,
/// x^2 y = 1e7, whose equations' magnitudes differ by five orders. From relative errors
/// of 1e-3 to 1e-6 two steps reach the rounding level.
#[test]
fn an_overdetermined_root_far_out_is_reached() {
    const XY: [u8; 2] = [1, 1];
    const X: [u8; 2] = [1, 0];
    const X2Y: [u8; 2] = [2, 1];
    const ONE: [u8; 2] = [0, 0];
    let e1: Vec<NewtonTerm> = vec![(0, &XY[..]), (1, &ONE[..])];
    let e2: Vec<NewtonTerm> = vec![(0, &X[..]), (2, &ONE[..])];
    let e3: Vec<NewtonTerm> = vec![(0, &X2Y[..]), (3, &ONE[..])];
    let eqs = [e1.as_slice(), e2.as_slice(), e3.as_slice()];
    let c = [1.0, -100.0, -1e5, -1e7];
    for d in [1e-3, 1e-4, 1e-5, 1e-6] {
        let mut x = [1e5 * (1.0 + d), 1e-3 * (1.0 - d)];
        newton_polish(&mut x, &eqs, &c, 2);
        let r = worst_relative_residual(&x, &eqs, &c).unwrap();
        assert!(r < 1e-14, "from {d:e}: {r:e} at {x:?}");
    }
}

#[test]
fn polishes_poor_solutions_only() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    // Off by 1e-12: a relative residual near 1e-12, not poor; left as it is although
    // not at rounding level (where `newton_polish` would step).
    let good = [1.0 + 1e-12, 1.0];
    let r = worst_relative_residual(&good, &eqs, &c).unwrap();
    assert!(
        r > 10.0 * AT_ROUNDING_LEVEL && r < POOR_SOLUTION_RESIDUAL,
        "{r}"
    );
    let mut x = good;
    assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
    assert_eq!(x, good);
    // Off by 1e-6: poor; polished to the root within its steps.
    let mut x = [1.0 + 1e-6, 1.0 - 1e-6];
    assert!(worst_relative_residual(&x, &eqs, &c).unwrap() > POOR_SOLUTION_RESIDUAL);
    let steps = polish_poor_solution(&mut x, &eqs, &c);
    assert!((1..=POOR_SOLUTION_STEPS).contains(&steps), "{steps}");
    assert!(
        worst_relative_residual(&x, &eqs, &c).unwrap() < 1e-14,
        "{x:?}"
    );
    // Non-finite input and too many unknowns: untouched.
    let mut x = [f64::NAN, 1.0];
    assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
    let mut x = [0.5; 25];
    assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
    assert_eq!(x, [0.5; 25]);
}

#[test]
fn stops_at_rounding_level() {
    let (eqs, c) = system();
    let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
    // One ulp off the root: the residual (about 4e-16 against terms of size 1) is at
    // rounding level, so no step is taken even with steps to spare.
    let mut x = [1.0 + f64::EPSILON, 1.0];
    assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().1);
    assert_eq!(newton_polish(&mut x, &eqs, &c, 8), 0);
    assert_eq!(x, [1.0 + f64::EPSILON, 1.0]);
    // A millionth off: not at rounding level; polishing takes steps and then stops
    // before its budget, once the residual is at rounding level.
    let mut x = [1.0 + 1e-6, 1.0 - 1e-6];
    assert!(!squared_residual::<3>(&eqs, &c, &x).unwrap().1);
    let steps = newton_polish(&mut x, &eqs, &c, 8);
    assert!((1..8).contains(&steps), "{steps}");
    assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().1, "{x:?}");
}
