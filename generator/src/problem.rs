//! The checked form of a problem file: its symbols (unknowns and typed data) and equations.
//!
//! The parser (`lang`) produces a [`ProblemLayout`] plus the checked equations; the
//! symbolic expansion (`expand`) evaluates those equations over any [`crate::algebra::Ring`].
//! Variable numbering conventions, relied on by every later stage:
//! - unknown scalars are numbered in declaration order, vector unknowns element by element;
//!   `unknown a[3], t[3]` gives variables `a1 a2 a3 t1 t2 t3` (1-based suffixes);
//! - data scalars are numbered in declaration order, arrays element by element, and within
//!   an element by its kind's slots (see [`DataKind::slots`]).

/// The kind of a data symbol; decides its shape, its scalar slots and how random instances
/// are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DataKind {
    /// A real number (1 slot).
    Scalar,
    /// A 3-vector (3 slots).
    Vec3,
    /// An image point in normalised coordinates [x, y, 1]: a 3-vector whose third entry is
    /// the constant 1 (2 slots: x, y).
    Point,
    /// A general 3x3 matrix (9 slots, row-major).
    Mat3,
    /// A 3x3 rotation matrix (9 slots, row-major); random instances are rotations.
    Rotation,
}

impl DataKind {
    /// Number of free scalar slots of one element of this kind.
    pub fn slots(self) -> usize {
        match self {
            DataKind::Scalar => 1,
            DataKind::Vec3 => 3,
            DataKind::Point => 2,
            DataKind::Mat3 | DataKind::Rotation => 9,
        }
    }
    /// The kind named by a problem-file keyword (`scalar`, `vec3`, `point`, `mat3`,
    /// `rotation`).
    pub fn from_keyword(word: &str) -> Option<DataKind> {
        DataKind::ALL.into_iter().find(|k| k.keyword() == word)
    }
    /// All kinds.
    pub const ALL: [DataKind; 5] = [
        DataKind::Scalar,
        DataKind::Vec3,
        DataKind::Point,
        DataKind::Mat3,
        DataKind::Rotation,
    ];
    /// Display names of the slots of one element, appended to the element's name:
    /// `[""]` for a scalar, `[".x", ".y", ".z"]` for a vec3, `[".x", ".y"]` for a point,
    /// `["[0][0]", "[0][1]", ..., "[2][2]"]` (row-major) for a matrix.
    pub fn slot_suffixes(self) -> Vec<String> {
        match self {
            DataKind::Scalar => vec![String::new()],
            DataKind::Vec3 => vec![".x".into(), ".y".into(), ".z".into()],
            DataKind::Point => vec![".x".into(), ".y".into()],
            DataKind::Mat3 | DataKind::Rotation => {
                (0..9).map(|k| format!("[{}][{}]", k / 3, k % 3)).collect()
            }
        }
    }
    /// The keyword used in problem files.
    pub fn keyword(self) -> &'static str {
        match self {
            DataKind::Scalar => "scalar",
            DataKind::Vec3 => "vec3",
            DataKind::Point => "point",
            DataKind::Mat3 => "mat3",
            DataKind::Rotation => "rotation",
        }
    }
}

/// A data symbol, e.g. `x1[5]: point`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DataSymbol {
    /// Name as written in the problem file.
    pub name: String,
    /// Kind of each element.
    pub kind: DataKind,
    /// Array length for `name[n]`, `None` for a single element.
    pub len: Option<usize>,
    /// Index of its first scalar slot among all data scalars.
    pub first_slot: usize,
}

impl DataSymbol {
    /// Total number of scalar slots (elements times slots per element).
    pub fn slot_count(&self) -> usize {
        self.len.unwrap_or(1) * self.kind.slots()
    }
}

/// An unknown symbol, e.g. `t[3]` (three scalar unknowns t1, t2, t3) or `x` (one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownSymbol {
    /// Name as written in the problem file.
    pub name: String,
    /// Vector length for `name[n]`, `None` for a scalar unknown.
    pub len: Option<usize>,
    /// Index of its first scalar variable among all unknown scalars.
    pub first_var: usize,
    /// An auxiliary unknown that `nonzero EXPR` introduces (`EXPR * u = 1`): part of
    /// the polynomial system, never of a solution. Hidden unknowns come after all
    /// declared ones.
    pub hidden: bool,
}

/// Template-search options given in the problem file (`option NAME = VALUE`); the
/// command line overrides them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ProblemOptions {
    /// `option action = NAME` (an unknown scalar, e.g. `t1`) or `option action = random`.
    pub action: Option<String>,
    /// `option extra_degree = N`: candidate degrees tried above the start, a hard bound.
    pub extra_degree: Option<u32>,
    /// `option basis = standard` (grevlex standard monomials only) or `selected` (also
    /// bases selected among the template's columns, the default).
    pub basis: Option<String>,
    /// `option newton = N` (0 to 8, default 0): Gauss-Newton steps polishing every solution
    /// on the problem's original equations (eliminated unknowns included), each step kept
    /// only if it lowers their squared residual. For problems whose action matrix is too
    /// inaccurate on its own (`mingen audit` shows it); it costs a few evaluations of the
    /// equations and their gradients per solution and step.
    pub newton: Option<u32>,
    /// `option auto_eliminate = yes|no` (default yes): whether planning, when the file
    /// eliminates nothing and the solution count stays the same, solves unknowns from
    /// affine equations and substitutes them into the others, or else eliminates, as
    /// `eliminate` would, the unknowns that every equation has only in terms of degree one
    /// with data coefficients (a translation, say); see `rewrite.rs`.
    pub auto_eliminate: Option<bool>,
}

/// The symbols of a problem: what emitted solvers take as data and return as solutions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProblemLayout {
    /// The problem's name (`problem NAME`), also the emitted module name.
    pub name: String,
    /// Unknown symbols in declaration order.
    pub unknowns: Vec<UnknownSymbol>,
    /// Data symbols in declaration order.
    pub data: Vec<DataSymbol>,
    /// Flat indices of the unknown scalars named by `eliminate` (empty if none).
    pub eliminate: Vec<usize>,
    /// Options of the template search given in the file.
    pub options: ProblemOptions,
}

impl ProblemLayout {
    /// Names of the unknown scalars, e.g. `["a1", "a2", "a3", "t1", "t2", "t3"]`.
    pub fn unknown_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for u in &self.unknowns {
            match u.len {
                None => out.push(u.name.clone()),
                Some(n) => out.extend((1..=n).map(|i| format!("{}{}", u.name, i))),
            }
        }
        out
    }
    /// Number of unknown scalars (hidden ones included: the variables of the system).
    pub fn unknown_count(&self) -> usize {
        self.unknowns.iter().map(|u| u.len.unwrap_or(1)).sum()
    }
    /// Number of hidden unknowns (one per `nonzero`), the last variables.
    pub fn hidden_count(&self) -> usize {
        self.unknowns.iter().filter(|u| u.hidden).count()
    }
    /// The declared unknowns (without the hidden ones), in declaration order.
    pub fn declared_unknowns(&self) -> impl Iterator<Item = &UnknownSymbol> {
        self.unknowns.iter().filter(|u| !u.hidden)
    }
    /// Display names of the data slots in slot order, e.g. `x1[0].x`, `x1[0].y`, `v1[0]`,
    /// `w1.x`, `R0[2][1]`.
    pub fn data_slot_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for d in &self.data {
            let suffixes = d.kind.slot_suffixes();
            match d.len {
                None => out.extend(suffixes.iter().map(|s| format!("{}{s}", d.name))),
                Some(n) => {
                    for i in 0..n {
                        out.extend(suffixes.iter().map(|s| format!("{}[{i}]{s}", d.name)));
                    }
                }
            }
        }
        out
    }
    /// Number of data scalar slots.
    pub fn data_slot_count(&self) -> usize {
        self.data.iter().map(DataSymbol::slot_count).sum()
    }
}
