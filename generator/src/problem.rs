//! The checked form of a problem file: its symbols (unknowns and typed data) and equations.
//!
//! The parser (`lang`) produces a [`ProblemLayout`] plus the checked equations; the
//! symbolic expansion (`expand`) evaluates those equations over any [`crate::algebra::Ring`].
//! Variable numbering conventions, relied on by every later stage:
//! - unknown scalars are numbered in declaration order, vector unknowns element by element;
//!   `unknown a[3], t[3]` gives variables `a1 a2 a3 t1 t2 t3` (1-based suffixes);
//! - data scalars are numbered in declaration order, arrays element by element, and within
//!   an element by its kind's slots (see [`DataKind::slots`]).

/// Most scalar slots of one element of a data kind (`vecN`, `matRxC`): `vec4096` and
/// `mat64x64` are accepted, `vec4097` is an error.
pub const MAX_KIND_SLOTS: usize = 4096;

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
    /// `vecN` for N other than 3 (`vec3` is [`DataKind::Vec3`]): an Nx1 vector, N slots.
    Vector(usize),
    /// `matRxC` other than 3x3 (`mat3` and `mat3x3` are [`DataKind::Mat3`]): an RxC
    /// matrix, R*C slots row-major.
    Matrix(usize, usize),
}

impl DataKind {
    /// Number of free scalar slots of one element of this kind.
    pub fn slots(self) -> usize {
        match self {
            DataKind::Scalar => 1,
            DataKind::Vec3 => 3,
            DataKind::Point => 2,
            DataKind::Mat3 | DataKind::Rotation => 9,
            DataKind::Vector(n) => n,
            DataKind::Matrix(r, c) => r * c,
        }
    }
    /// The shape `(rows, columns)` of one element's value (a point is 3x1).
    pub fn shape(self) -> (usize, usize) {
        match self {
            DataKind::Scalar => (1, 1),
            DataKind::Vec3 | DataKind::Point => (3, 1),
            DataKind::Mat3 | DataKind::Rotation => (3, 3),
            DataKind::Vector(n) => (n, 1),
            DataKind::Matrix(r, c) => (r, c),
        }
    }
    /// The kind named by a problem-file keyword (`scalar`, `vec3`, `point`, `mat3`,
    /// `rotation`, `vecN`, `matRxC`), `None` if it names none or has more than
    /// [`MAX_KIND_SLOTS`] slots.
    pub fn from_keyword(word: &str) -> Option<DataKind> {
        DataKind::parse(word).ok()
    }
    /// [`DataKind::from_keyword`] with the reason for a refusal.
    pub fn parse(word: &str) -> Result<DataKind, String> {
        if let Some(k) = DataKind::ALL.into_iter().find(|k| k.keyword() == word) {
            return Ok(k);
        }
        // A size: digits without a leading zero, at least 1 (saturating, so that a long
        // run of digits is "too large", not an overflow).
        let size = |s: &str| -> Option<usize> {
            if s.is_empty() || s.starts_with('0') || !s.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            Some(s.bytes().fold(0usize, |a, b| {
                a.saturating_mul(10).saturating_add(usize::from(b - b'0'))
            }))
        };
        let kind = if let Some(n) = word.strip_prefix("vec").and_then(size) {
            DataKind::Vector(n)
        } else if let Some((r, c)) = word
            .strip_prefix("mat")
            .and_then(|rc| rc.split_once('x'))
            .and_then(|(r, c)| Some((size(r)?, size(c)?)))
        {
            DataKind::Matrix(r, c)
        } else {
            return Err(format!(
                "unknown kind '{word}': expected scalar, point, rotation, vecN (vec3, vec4, ...) or matRxC (mat3, mat2x2, mat3x4, ...)"
            ));
        };
        let slots = match kind {
            DataKind::Matrix(r, c) => r.saturating_mul(c),
            k => k.slots(),
        };
        if slots > MAX_KIND_SLOTS {
            return Err(format!(
                "kind '{word}' has too many entries ({slots}; at most {MAX_KIND_SLOTS})"
            ));
        }
        Ok(match kind {
            DataKind::Vector(3) => DataKind::Vec3,
            DataKind::Matrix(3, 3) => DataKind::Mat3,
            k => k,
        })
    }
    /// The kinds with a fixed keyword (`vecN` and `matRxC` of other sizes come on top).
    pub const ALL: [DataKind; 5] = [
        DataKind::Scalar,
        DataKind::Vec3,
        DataKind::Point,
        DataKind::Mat3,
        DataKind::Rotation,
    ];
    /// Display names of the slots of one element, appended to the element's name:
    /// `[""]` for a scalar, `[".x", ".y", ".z"]` for a vec3, `[".x", ".y"]` for a point,
    /// `["[0]", ..., "[N-1]"]` for a `vecN`, `["[0][0]", "[0][1]", ...]` (row-major) for
    /// a matrix.
    pub fn slot_suffixes(self) -> Vec<String> {
        match self {
            DataKind::Scalar => vec![String::new()],
            DataKind::Vec3 => vec![".x".into(), ".y".into(), ".z".into()],
            DataKind::Point => vec![".x".into(), ".y".into()],
            DataKind::Vector(n) => (0..n).map(|k| format!("[{k}]")).collect(),
            DataKind::Mat3 | DataKind::Rotation | DataKind::Matrix(..) => {
                let (r, c) = self.shape();
                (0..r * c)
                    .map(|k| format!("[{}][{}]", k / c, k % c))
                    .collect()
            }
        }
    }
    /// The keyword used in problem files (`vec4`, `mat2x3` for the sized kinds).
    pub fn keyword(self) -> String {
        match self {
            DataKind::Scalar => "scalar".into(),
            DataKind::Vec3 => "vec3".into(),
            DataKind::Point => "point".into(),
            DataKind::Mat3 => "mat3".into(),
            DataKind::Rotation => "rotation".into(),
            DataKind::Vector(n) => format!("vec{n}"),
            DataKind::Matrix(r, c) => format!("mat{r}x{c}"),
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

/// Gauss-Newton steps [`ProblemOptions::newton_steps`] reads when `option newton` is not
/// set: none. A plan sets it when neither the file nor the command line does, by measuring
/// its template (`crate::polishing`: [`crate::AutoPolishing`]), so this default applies
/// only to a layout that was not planned.
pub const DEFAULT_NEWTON_STEPS: u32 = 0;

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
    /// `option newton = N` (0 to 8): Gauss-Newton steps polishing every solution on the
    /// problem's original equations (eliminated unknowns included), each step kept only if
    /// it lowers the sum of their squared relative residuals, none once the residual is at
    /// rounding level. Not
    /// set, the plan chooses 0, 2, 4 or 8 by solving its template on random instances
    /// ([`crate::AutoPolishing`]). Read it through [`ProblemOptions::newton_steps`].
    pub newton: Option<u32>,
    /// `option auto_eliminate = yes|no` (default yes): whether planning, when the file
    /// eliminates nothing and the solution count stays the same, solves unknowns from
    /// affine equations and substitutes them into the others, or else eliminates, as
    /// `eliminate` would, the unknowns that every equation has only in terms of degree one
    /// with data coefficients (a translation, say); see `rewrite.rs`.
    pub auto_eliminate: Option<bool>,
    /// `option reduce_equations = yes|no` (default yes): whether the template search also
    /// builds templates from the equations row-reduced on their data (each reduced equation
    /// has a pivot monomial no other has; see `template/reduction.rs`) and keeps the smaller.
    pub reduce_equations: Option<bool>,
    /// `option sign_symmetry = yes|no` (default yes): whether planning, when every
    /// equation is even or odd in a set of unknowns (the solutions come in pairs `x`,
    /// `-x` on them), solves the system folded to half the solutions and recovers both
    /// signs (`symmetry.rs`); kept only where the count halves.
    pub sign_symmetry: Option<bool>,
    /// `option redundant_basis = yes|no` (default no): whether the template's basis may
    /// have more monomials than solutions when that makes the template smaller and the
    /// plan measures no lost solution (`template/redundant.rs`, `redundancy.rs`).
    pub redundant_basis: Option<bool>,
    /// `option weighted_orders = N` (default 32, at most [`MAX_WEIGHTED_ORDERS`]): how many
    /// weighted monomial orders the template search samples for other quotient bases (0:
    /// none); more can find smaller templates at the cost of planning time.
    pub weighted_orders: Option<usize>,
    /// `option saturation = smaller|template|unknown` (default `smaller`): how a `nonzero`
    /// polynomial with constant coefficients is saturated: inside the template (its
    /// columns standing for multiples of a power of it, `template/shift.rs`), by a hidden
    /// unknown `u` with `u s - 1 = 0`, or both searched and the smaller template kept.
    pub saturation: Option<PolynomialSaturation>,
}

impl ProblemOptions {
    /// The Gauss-Newton steps of `option newton`, [`DEFAULT_NEWTON_STEPS`] if not given.
    pub fn newton_steps(&self) -> u32 {
        self.newton.unwrap_or(DEFAULT_NEWTON_STEPS)
    }
}

/// How a `nonzero` polynomial with constant coefficients is saturated (`option saturation`,
/// [`ProblemOptions::saturation`]); a monomial is always saturated inside the template.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PolynomialSaturation {
    /// Both ways searched, the smaller template (after the fold) kept: the hidden unknown's
    /// equation `u s - 1` has numeric coefficients, and its multiples often fold away.
    #[default]
    Smaller,
    /// Inside the template only (the search is shorter).
    Template,
    /// By the hidden unknown only.
    Unknown,
}

impl PolynomialSaturation {
    /// The value of `option saturation` / `--saturation` (`smaller`, `template`, `unknown`).
    pub fn parse(value: &str) -> Option<PolynomialSaturation> {
        match value {
            "smaller" => Some(PolynomialSaturation::Smaller),
            "template" => Some(PolynomialSaturation::Template),
            "unknown" => Some(PolynomialSaturation::Unknown),
            _ => None,
        }
    }
}

/// The most weighted orders `option weighted_orders` may ask for.
pub const MAX_WEIGHTED_ORDERS: usize = 1024;

/// The symbols of a problem: what emitted solvers take as data and return as solutions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProblemLayout {
    /// The problem's name as written (`problem NAME`); the emitted module is
    /// [`ProblemLayout::module_name`].
    pub name: String,
    /// Unknown symbols in declaration order.
    pub unknowns: Vec<UnknownSymbol>,
    /// Data symbols in declaration order.
    pub data: Vec<DataSymbol>,
    /// Flat indices of the unknown scalars named by `eliminate` (empty if none).
    pub eliminate: Vec<usize>,
    /// Flat indices of the unknown scalars named by `positive`: solutions where one of
    /// them is not positive are dropped by the emitted solvers (and counted apart by the
    /// audit). Empty if none.
    pub positive: Vec<usize>,
    /// Options of the template search given in the file.
    pub options: ProblemOptions,
}

impl ProblemLayout {
    /// The Rust module and file stem of the emitted solver: the name lowercased, `p`
    /// prepended when it starts with a digit ([`crate::lang::names::module_name`]).
    pub fn module_name(&self) -> String {
        crate::lang::names::module_name(&self.name)
    }
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
    /// The names ([`ProblemLayout::unknown_names`]) of the unknown scalars with flat
    /// indices `vars` (as `eliminate` and `positive` hold them).
    pub fn names_of(&self, vars: &[usize]) -> Vec<String> {
        let names = self.unknown_names();
        vars.iter().filter_map(|&i| names.get(i).cloned()).collect()
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
