//! The tape's evaluation: small dense matrices of ring elements or polynomials, walked node
//! by node under a budget [`Guard`].

use super::*;

/// Term products a polynomial multiplication is assumed to do per second when a budget
/// decides whether to start it: optimistic, so that only a product sure to overrun the
/// remaining time is refused before it starts (the clock is read after every step).
pub(super) const TERM_PRODUCTS_PER_SECOND: f64 = 5e7;

/// Bounds one evaluation of the tape by a budget: the clock is read after every node, the
/// memory of the values computed so far is estimated from their terms, and a product of
/// polynomials is refused before it starts when its result (at most the product of the
/// term counts, and at most the number of monomials up to its degree) would not fit in the
/// memory budget, or its term products in the time left.
pub(super) struct Guard<'a> {
    deadline: &'a Deadline,
    /// Estimated bytes of one stored term (monomial, coefficient, map overhead).
    term_bytes: u64,
    /// Estimated bytes of the values computed so far.
    held: std::cell::Cell<u64>,
    /// Nodes computed so far.
    nodes: std::cell::Cell<u64>,
}

/// A small expansion is not worth reading the clock for (as the Gröbner bases read it
/// only every few steps, a problem this small is always expanded): the clock is read every
/// this many nodes, after a value of more than [`LARGE_VALUE_TERMS`] terms, and before a
/// product of at least [`SMALL_PRODUCT`] term products.
pub(super) const CLOCK_EVERY_NODES: u64 = 64;
/// See [`CLOCK_EVERY_NODES`].
pub(super) const LARGE_VALUE_TERMS: usize = 10_000;
/// See [`CLOCK_EVERY_NODES`].
pub(super) const SMALL_PRODUCT: f64 = 1e6;

impl<'a> Guard<'a> {
    pub(super) fn new<C>(deadline: &'a Deadline, nvars: usize) -> Guard<'a> {
        Guard {
            deadline,
            term_bytes: 96 + 2 * nvars as u64 + std::mem::size_of::<C>() as u64,
            held: std::cell::Cell::new(0),
            nodes: std::cell::Cell::new(0),
        }
    }

    /// Whether the product of two matrices of polynomials in `n` variables may start.
    pub(super) fn before_mul<C: Ring>(
        &self,
        a: &Mat<Poly<C>>,
        b: &Mat<Poly<C>>,
        n: usize,
    ) -> Result<(), EvalError> {
        let len = |p: &Poly<C>| p.len() as f64;
        let deg = |m: &Mat<Poly<C>>| m.e.iter().filter_map(Poly::degree).max().unwrap_or(0);
        // Term products: sum over the inner index l of (terms in column l of a) times
        // (terms in row l of b); a 1x1 side scales every entry of the other.
        let work = if a.shape.is_scalar() || b.shape.is_scalar() {
            a.e.iter().map(len).sum::<f64>() * b.e.iter().map(len).sum::<f64>()
        } else {
            (0..a.shape.cols)
                .map(|l| {
                    let col: f64 = (0..a.shape.rows).map(|i| len(a.at(i, l))).sum();
                    let row: f64 = (0..b.shape.cols).map(|j| len(b.at(l, j))).sum();
                    col * row
                })
                .sum()
        };
        let entries = (a.e.len().max(b.e.len())) as f64;
        let dense = entries * monomials_up_to(n, deg(a) + deg(b));
        let bytes = work.min(dense) * self.term_bytes as f64 + self.held.get() as f64;
        self.deadline
            .check_memory(bytes.min(u64::MAX as f64) as u64)
            .map_err(EvalError::Budget)?;
        let left = self.deadline.budget().max_seconds - self.deadline.elapsed();
        if work >= SMALL_PRODUCT && work / TERM_PRODUCTS_PER_SECOND > left {
            return Err(EvalError::Budget(Exhausted::Time(
                self.deadline.stated_seconds(),
            )));
        }
        Ok(())
    }

    /// Accounts a computed value of `terms` terms and reads the clock.
    pub(super) fn after(&self, terms: usize) -> Result<(), EvalError> {
        let held = self
            .held
            .get()
            .saturating_add((terms as u64).saturating_mul(self.term_bytes));
        self.held.set(held);
        self.deadline
            .check_memory(held)
            .map_err(EvalError::Budget)?;
        let nodes = self.nodes.get() + 1;
        self.nodes.set(nodes);
        if nodes % CLOCK_EVERY_NODES == 0 || terms > LARGE_VALUE_TERMS {
            self.deadline.check_time().map_err(EvalError::Budget)?;
        }
        Ok(())
    }

    /// The checks of a run of the tape over polynomials in `n` variables.
    pub(super) fn hooks<C: Ring>(&'a self, n: usize) -> TapeHooks<'a, Poly<C>> {
        TapeHooks {
            before_mul: Box::new(move |a, b| self.before_mul(a, b, n)),
            after: Box::new(move |m| self.after(m.e.iter().map(Poly::len).sum())),
        }
    }
}

/// The number of monomials of degree at most `d` in `n` variables, `C(n + d, n)`, as a
/// float (it only bounds a size).
pub(super) fn monomials_up_to(n: usize, d: u32) -> f64 {
    (1..=n).fold(1.0, |acc, k| acc * (d as f64 + k as f64) / k as f64)
}

/// A small dense matrix (any shape RxC) over a ring, row-major.
#[derive(Clone, Debug)]
pub(super) struct Mat<T> {
    shape: Shape,
    e: Vec<T>,
}

impl<T: Ring> Mat<T> {
    pub(super) fn scalar(x: T) -> Self {
        Mat {
            shape: Shape::SCALAR,
            e: vec![x],
        }
    }
    pub(super) fn at(&self, i: usize, j: usize) -> &T {
        &self.e[i * self.shape.cols + j]
    }
    pub(super) fn zip(&self, o: &Self, f: impl Fn(&T, &T) -> T) -> Self {
        Mat {
            shape: self.shape,
            e: self.e.iter().zip(&o.e).map(|(a, b)| f(a, b)).collect(),
        }
    }
    pub(super) fn add_sub(&self, o: &Self, sub: bool) -> Self {
        if sub {
            self.zip(o, sub_skip)
        } else {
            self.zip(o, |a, b| a.add(b))
        }
    }
    pub(super) fn map(&self, f: impl Fn(&T) -> T) -> Self {
        Mat {
            shape: self.shape,
            e: self.e.iter().map(f).collect(),
        }
    }
    pub(super) fn mul(&self, o: &Self) -> Self {
        mat_mul(self, o, |a, b| a.mul(b))
    }
    pub(super) fn transpose(&self) -> Self {
        let s = self.shape;
        let mut e = Vec::with_capacity(s.len());
        for j in 0..s.cols {
            for i in 0..s.rows {
                e.push(self.at(i, j).clone());
            }
        }
        Mat {
            shape: Shape {
                rows: s.cols,
                cols: s.rows,
            },
            e,
        }
    }
    pub(super) fn skew(&self) -> Self {
        let (x, y, z) = (&self.e[0], &self.e[1], &self.e[2]);
        Mat {
            shape: Shape::MAT,
            e: vec![
                T::zero(),
                z.neg(),
                y.clone(),
                z.clone(),
                T::zero(),
                x.neg(),
                y.neg(),
                x.clone(),
                T::zero(),
            ],
        }
    }
    pub(super) fn det(&self) -> T {
        if self.shape.rows != 3 {
            let all: Vec<usize> = (0..self.shape.cols).collect();
            return self.cofactor_det(0, &all);
        }
        let m = |i, j| self.at(i, j);
        let minor = |a: usize, b: usize| {
            // Columns other than the first of the 2x2 minor on rows 1, 2.
            sub_skip(&mul_skip(m(1, a), m(2, b)), &mul_skip(m(1, b), m(2, a)))
        };
        let t0 = mul_skip(m(0, 0), &minor(1, 2));
        let t1 = mul_skip(m(0, 1), &minor(0, 2));
        let t2 = mul_skip(m(0, 2), &minor(0, 1));
        t0.sub(&t1).add(&t2)
    }
    /// The determinant of the square block on rows `row..` and columns `cols`, by
    /// cofactor expansion along its first row (any size; the checker allows up to 6x6).
    pub(super) fn cofactor_det(&self, row: usize, cols: &[usize]) -> T {
        match cols {
            [] => T::one(),
            [c] => self.at(row, *c).clone(),
            _ => {
                let mut acc = T::zero();
                for (k, &c) in cols.iter().enumerate() {
                    let x = self.at(row, c);
                    if x.is_zero() {
                        continue;
                    }
                    let rest: Vec<usize> = cols.iter().copied().filter(|&d| d != c).collect();
                    let term = mul_skip(x, &self.cofactor_det(row + 1, &rest));
                    acc = if k % 2 == 0 {
                        acc.add(&term)
                    } else {
                        sub_skip(&acc, &term)
                    };
                }
                acc
            }
        }
    }
    pub(super) fn trace(&self) -> T {
        if self.shape.rows != 3 {
            return (1..self.shape.rows)
                .fold(self.at(0, 0).clone(), |acc, i| acc.add(self.at(i, i)));
        }
        self.at(0, 0).add(self.at(1, 1)).add(self.at(2, 2))
    }
}

/// The product of two small matrices over possibly different rings `A`, `B` with values in
/// `R` (`f` multiplies entries): the matrix product, or scaling when one side is 1x1.
/// Products with a zero factor are skipped.
pub(super) fn mat_mul<A: Ring, B: Ring, R: Ring>(
    a: &Mat<A>,
    b: &Mat<B>,
    f: impl Fn(&A, &B) -> R,
) -> Mat<R> {
    let g = |x: &A, y: &B| {
        if x.is_zero() || y.is_zero() {
            R::zero()
        } else {
            f(x, y)
        }
    };
    if a.shape.is_scalar() {
        let s = &a.e[0];
        return Mat {
            shape: b.shape,
            e: b.e.iter().map(|y| g(s, y)).collect(),
        };
    }
    if b.shape.is_scalar() {
        let s = &b.e[0];
        return Mat {
            shape: a.shape,
            e: a.e.iter().map(|x| g(x, s)).collect(),
        };
    }
    let (r, n, c) = (a.shape.rows, a.shape.cols, b.shape.cols);
    let mut e = Vec::with_capacity(r * c);
    for i in 0..r {
        for j in 0..c {
            let mut acc: Option<R> = None;
            for k in 0..n {
                let (x, y) = (a.at(i, k), b.at(k, j));
                if x.is_zero() || y.is_zero() {
                    continue;
                }
                let p = f(x, y);
                acc = Some(match acc {
                    None => p,
                    Some(s) => s.add(&p),
                });
            }
            e.push(acc.unwrap_or_else(R::zero));
        }
    }
    Mat {
        shape: Shape { rows: r, cols: c },
        e,
    }
}

/// A tape value during polynomial evaluation: free of unknowns (kept in the coefficient
/// ring, cheap) or a matrix of polynomials in the unknowns.
pub(super) enum Mixed<C> {
    K(Mat<C>),
    P(Mat<Poly<C>>),
}

impl<C: Ring> Mixed<C> {
    pub(super) fn lift(&self, n: usize) -> std::borrow::Cow<'_, Mat<Poly<C>>> {
        match self {
            Mixed::P(m) => std::borrow::Cow::Borrowed(m),
            Mixed::K(m) => std::borrow::Cow::Owned(Mat {
                shape: m.shape,
                e: m.e.iter().map(|c| Poly::constant(n, c.clone())).collect(),
            }),
        }
    }
    /// Applies `k` if unknown-free, else `p` on the polynomial matrix.
    pub(super) fn map(
        &self,
        k: impl Fn(&Mat<C>) -> Mat<C>,
        p: impl Fn(&Mat<Poly<C>>) -> Mat<Poly<C>>,
    ) -> Self {
        match self {
            Mixed::K(m) => Mixed::K(k(m)),
            Mixed::P(m) => Mixed::P(p(m)),
        }
    }
}

/// Runs the tape with polynomial values only where unknowns enter.
pub(super) fn run_mixed<C: Ring>(
    nodes: &[Node],
    needed: &[bool],
    n: usize,
    inverted: &[usize],
    data: &[C],
    guard: Option<&Guard<'_>>,
) -> Result<Vec<Option<Mixed<C>>>, EvalError> {
    // The reciprocal of unknown `inverted[j]` is variable `n - inverted.len() + j`.
    let first_recip = n - inverted.len();
    let mut vals: Vec<Option<Mixed<C>>> = Vec::with_capacity(nodes.len());
    for (id, node) in nodes.iter().enumerate() {
        if !needed.get(id).copied().unwrap_or(false) {
            vals.push(None);
            continue;
        }
        let get = |x: &NodeId| -> &Mixed<C> {
            vals[*x]
                .as_ref()
                .expect("operands precede their users and are needed")
        };
        // Entrywise sum or difference, in the ring when both sides are unknown-free.
        let add_sub = |a: &NodeId, b: &NodeId, sub: bool| match (get(a), get(b)) {
            (Mixed::K(x), Mixed::K(y)) => Mixed::K(x.add_sub(y, sub)),
            (x, y) => Mixed::P(x.lift(n).add_sub(&y.lift(n), sub)),
        };
        let v = match &node.op {
            Op::Const(q) => Mixed::K(Mat::scalar(
                C::from_rational(q).ok_or(EvalError::Constant(q.clone()))?,
            )),
            Op::Data(s) => Mixed::K(Mat::scalar(data[*s].clone())),
            Op::Unknown(i) => Mixed::P(Mat::scalar(Poly::var(n, *i))),
            Op::Recip(i) => Mixed::P(Mat::scalar(Poly::var(
                n,
                first_recip + inverted.iter().position(|v| v == i).unwrap_or(0),
            ))),
            Op::Build(shape, entries) => {
                if entries.iter().all(|x| matches!(get(x), Mixed::K(_))) {
                    Mixed::K(Mat {
                        shape: *shape,
                        e: entries
                            .iter()
                            .map(|x| match get(x) {
                                Mixed::K(m) => m.e[0].clone(),
                                Mixed::P(_) => C::zero(),
                            })
                            .collect(),
                    })
                } else {
                    Mixed::P(Mat {
                        shape: *shape,
                        e: entries
                            .iter()
                            .map(|x| get(x).lift(n).e[0].clone())
                            .collect(),
                    })
                }
            }
            Op::Identity => Mixed::K(Mat {
                shape: Shape::MAT,
                e: (0..9)
                    .map(|k| if k % 4 == 0 { C::one() } else { C::zero() })
                    .collect(),
            }),
            Op::Add(a, b) => add_sub(a, b, false),
            Op::Sub(a, b) => add_sub(a, b, true),
            Op::Mul(a, b) => match (get(a), get(b)) {
                (Mixed::K(x), Mixed::K(y)) => Mixed::K(x.mul(y)),
                (Mixed::P(x), Mixed::K(y)) => Mixed::P(mat_mul(x, y, |p, c| p.scale(c))),
                (Mixed::K(x), Mixed::P(y)) => Mixed::P(mat_mul(x, y, |c, p| p.scale(c))),
                (Mixed::P(x), Mixed::P(y)) => {
                    if let Some(g) = guard {
                        g.before_mul(x, y, n)?;
                    }
                    Mixed::P(x.mul(y))
                }
            },
            Op::Neg(a) => get(a).map(|m| m.map(C::neg), |m| m.map(Ring::neg)),
            Op::Transpose(a) => get(a).map(Mat::transpose, Mat::transpose),
            Op::Skew(a) => get(a).map(Mat::skew, Mat::skew),
            Op::Det(a) => get(a).map(|m| Mat::scalar(m.det()), |m| Mat::scalar(m.det())),
            Op::Trace(a) => get(a).map(|m| Mat::scalar(m.trace()), |m| Mat::scalar(m.trace())),
            Op::Entry(a, i, j) => get(a).map(
                |m| Mat::scalar(m.at(*i, *j).clone()),
                |m| Mat::scalar(m.at(*i, *j).clone()),
            ),
        };
        if let (Some(g), Mixed::P(m)) = (guard, &v) {
            g.after(m.e.iter().map(Poly::len).sum())?;
        }
        vals.push(Some(v));
    }
    Ok(vals)
}

pub(super) fn mul_skip<T: Ring>(a: &T, b: &T) -> T {
    if a.is_zero() || b.is_zero() {
        T::zero()
    } else {
        a.mul(b)
    }
}

pub(super) fn sub_skip<T: Ring>(a: &T, b: &T) -> T {
    if b.is_zero() {
        a.clone()
    } else {
        a.sub(b)
    }
}

/// A budget's checks on a run of the tape: before each product, after each node.
pub(super) struct TapeHooks<'a, T> {
    before_mul: Box<BeforeMul<'a, T>>,
    after: Box<AfterNode<'a, T>>,
}

/// The check before a product of two tape values.
pub(super) type BeforeMul<'a, T> = dyn Fn(&Mat<T>, &Mat<T>) -> Result<(), EvalError> + 'a;
/// The check after a tape value is computed.
pub(super) type AfterNode<'a, T> = dyn Fn(&Mat<T>) -> Result<(), EvalError> + 'a;

/// Runs the tape over `T`, with leaves (constants, unknowns, data slots) from `leaf`, and
/// the checks of `hooks` if any.
pub(super) fn run_tape<T: Ring>(
    nodes: &[Node],
    needed: &[bool],
    identity: (&T, &T),
    mut leaf: impl FnMut(&Op) -> Result<T, EvalError>,
    hooks: Option<TapeHooks<'_, T>>,
) -> Result<Vec<Option<Mat<T>>>, EvalError> {
    let mut vals: Vec<Option<Mat<T>>> = Vec::with_capacity(nodes.len());
    for (id, node) in nodes.iter().enumerate() {
        if !needed.get(id).copied().unwrap_or(false) {
            vals.push(None);
            continue;
        }
        let get = |n: &NodeId| -> &Mat<T> {
            vals[*n]
                .as_ref()
                .expect("operands precede their users and are needed")
        };
        let v = match &node.op {
            Op::Const(_) | Op::Unknown(_) | Op::Data(_) | Op::Recip(_) => {
                Mat::scalar(leaf(&node.op)?)
            }
            Op::Build(shape, entries) => Mat {
                shape: *shape,
                e: entries.iter().map(|n| get(n).e[0].clone()).collect(),
            },
            Op::Identity => Mat {
                shape: Shape::MAT,
                e: (0..9)
                    .map(|k| {
                        if k % 4 == 0 {
                            identity.1.clone()
                        } else {
                            identity.0.clone()
                        }
                    })
                    .collect(),
            },
            Op::Add(a, b) => get(a).zip(get(b), |x, y| x.add(y)),
            Op::Sub(a, b) => get(a).zip(get(b), sub_skip),
            Op::Neg(a) => get(a).map(T::neg),
            Op::Mul(a, b) => {
                if let Some(h) = &hooks {
                    (h.before_mul)(get(a), get(b))?;
                }
                get(a).mul(get(b))
            }
            Op::Transpose(a) => get(a).transpose(),
            Op::Skew(a) => get(a).skew(),
            Op::Det(a) => Mat::scalar(get(a).det()),
            Op::Trace(a) => Mat::scalar(get(a).trace()),
            Op::Entry(a, i, j) => Mat::scalar(get(a).at(*i, *j).clone()),
        };
        if let Some(h) = &hooks {
            (h.after)(&v)?;
        }
        vals.push(Some(v));
    }
    Ok(vals)
}
