//! The interface every emitted solver implements, so that code can be generic over
//! minimal solvers (test harnesses, benchmarks, estimators that choose a solver by type).

use crate::Stages;
use std::fmt::Debug;

/// A fixed-size record of `f64` values with a flat form.
///
/// A solver's input data and its solutions implement it. The flat form of the data lists
/// its slots in the problem file's order: symbols in declaration order, arrays element by
/// element, a point as `x, y`, a matrix row-major. The flat form of a solution lists the
/// unknowns in declaration order (`t[3]` as `t1, t2, t3`), eliminated unknowns included.
pub trait FlatValues: Copy {
    /// Number of scalars in the flat form.
    const LEN: usize;

    /// The record from its flat form; `None` unless `values.len() == Self::LEN`.
    fn from_flat(values: &[f64]) -> Option<Self>;

    /// Writes the flat form into `out[..Self::LEN]`; returns `false` and writes nothing if
    /// `out` is shorter than `Self::LEN`.
    fn write_flat(&self, out: &mut [f64]) -> bool;

    /// The flat form as a vector (allocates; for tests and tools, not for hot loops).
    fn to_flat_vec(&self) -> Vec<f64> {
        let mut v = vec![0.0; Self::LEN];
        self.write_flat(&mut v);
        v
    }
}

/// A minimal solver emitted by `mingen`: fixed-size data in, the real solutions out.
///
/// Each emitted module defines a unit type `Solver` implementing this trait; its methods
/// forward to the module's free functions `solve` and `solve_staged`.
///
/// Generic code over solvers uses the flat forms and the slice of solutions:
///
/// ```
/// use mingen_runtime::{FlatValues, MinimalSolver, SolutionSet, Stages};
///
/// /// A hand-written stand-in for an emitted module: x^2 = a.
/// struct Sqrt;
/// #[derive(Clone, Copy, Debug, PartialEq, Default)]
/// struct Data { a: f64 }
/// #[derive(Clone, Copy, Debug, PartialEq, Default)]
/// struct Solution { x: f64 }
/// impl FlatValues for Data {
///     const LEN: usize = 1;
///     fn from_flat(v: &[f64]) -> Option<Self> { (v.len() == 1).then(|| Data { a: v[0] }) }
///     fn write_flat(&self, out: &mut [f64]) -> bool {
///         out.first_mut().map(|o| *o = self.a).is_some()
///     }
/// }
/// impl FlatValues for Solution {
///     const LEN: usize = 1;
///     fn from_flat(v: &[f64]) -> Option<Self> { (v.len() == 1).then(|| Solution { x: v[0] }) }
///     fn write_flat(&self, out: &mut [f64]) -> bool {
///         out.first_mut().map(|o| *o = self.x).is_some()
///     }
/// }
/// impl MinimalSolver for Sqrt {
///     const NAME: &'static str = "sqrt";
///     const MAX_SOLUTIONS: usize = 2;
///     const TEMPLATE_SHAPE: [usize; 4] = [0, 0, 0, 0];
///     type Data = Data;
///     type Solution = Solution;
///     type Solutions = SolutionSet<Solution, 2>;
///     fn solve(d: &Data) -> Self::Solutions { Self::solve_staged(d, &mut ()) }
///     fn solve_staged<S: Stages>(d: &Data, _: &mut S) -> Self::Solutions {
///         let mut out = SolutionSet::new();
///         if d.a >= 0.0 {
///             out.push(Solution { x: d.a.sqrt() });
///             out.push(Solution { x: -d.a.sqrt() });
///         }
///         out
///     }
/// }
///
/// fn solution_count<S: MinimalSolver>(flat: &[f64]) -> usize {
///     S::Data::from_flat(flat).map_or(0, |d| S::solve(&d).as_ref().len())
/// }
/// assert_eq!(solution_count::<Sqrt>(&[4.0]), 2);
/// assert_eq!(solution_count::<Sqrt>(&[-4.0]), 0);
/// assert_eq!(solution_count::<Sqrt>(&[1.0, 2.0]), 0);
/// ```
pub trait MinimalSolver {
    /// The problem's name (the `problem` line of its file).
    const NAME: &'static str;
    /// The largest number of real solutions `solve` returns: the number of complex
    /// solutions of a generic instance (the size of the quotient-ring basis).
    const MAX_SOLUTIONS: usize;
    /// The elimination template's `[rows, cols, pivot columns, first reduced row]`, as the
    /// emitted solver allocates and reduces it.
    const TEMPLATE_SHAPE: [usize; 4];

    /// The input data (one field per data symbol of the problem file).
    type Data: FlatValues + Debug + PartialEq + Default;
    /// One real solution (one field per unknown symbol of the problem file).
    type Solution: FlatValues + Debug + PartialEq + Default;
    /// The real solutions of one instance: a
    /// [`SolutionSet`](crate::SolutionSet)`<Self::Solution, { Self::MAX_SOLUTIONS }>`.
    type Solutions: AsRef<[Self::Solution]> + Copy + Debug;

    /// All real solutions for `data`. Never panics: non-finite or degenerate data gives
    /// no solutions.
    fn solve(data: &Self::Data) -> Self::Solutions;

    /// [`solve`](Self::solve) with an observer called between the stages (benchmarks,
    /// diagnostics); see [`Stages`].
    fn solve_staged<S: Stages>(data: &Self::Data, stages: &mut S) -> Self::Solutions;
}
