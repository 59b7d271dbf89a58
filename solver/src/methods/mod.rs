//! The relative-pose methods (ARCHITECTURE §3) and the public entry [`estimate_relative_pose`].
//!
//! Output convention (ARCHITECTURE §4): `R = R2 R1^T`, `t = R2 (C1 - C2) / |.|` between the row-0
//! poses of the two images, so `x2 = R x1 + t`; the sign of `t` is chosen by cheirality
//! (most inliers triangulating in front of both cameras).
//!
//! | method | file |
//! |---|---|
//! | `gsrp` | [`gsrp`]: global-shutter 5-point RANSAC (gyro ignored) |
//! | `nrsrp` | [`nrsrp`]: Dai et al. uniform RS model by LM, Cauchy loss, init from `gsrp` |
//! | `grsrp`, `grsrp+` | [`grsrp`]: the paper's G-RSRP solver in RANSAC (+ refinement) |
//! | `rectified` | [`rectified`]: gyro-undistorted bearings, 5-point RANSAC, Sampson refinement |
//! | `rectified+v` | [`rectified_v`]: `rectified`, then pose and linear velocities on the generalised epipolar model |
//! | `grsrp-gravity` | [`grsrp_gravity`]: known gravity, 3-point RANSAC on the generated solver, `rectified`'s refinement |

pub mod grsrp;
pub mod grsrp_gravity;
pub mod gsrp;
pub mod noise_fit;
pub mod nrsrp;
mod pose_ransac;
mod post_refine;
pub mod quality;
pub mod rectified;
pub mod rectified_v;
mod subset;

use crate::data::pair_file::Match;
use crate::estimation::gyro_bias::{EstimatedBias, GyroBiasOptions};
use crate::estimation::readout::ReadoutOptions;
use crate::estimation::refine::LmOptions;
use crate::minimal::{EssentialSolver, GravitySolver, GrsrpSolver};
use crate::model::camera::{CameraError, View};
use crate::model::epipolar::PoseModel;
use nalgebra::{Matrix3, Vector3};
pub use noise_fit::NoiseFit;
pub use quality::{Quality, QualityOptions};
pub use rectified_v::{VelocityFit, VelocityOptions};
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// A relative-pose method (names as on the command line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// `gsrp`: global-shutter 5-point RANSAC.
    Gsrp,
    /// `nrsrp`: Dai et al. CVPR 2016 nonlinear RS relative pose, no gyro.
    Nrsrp,
    /// `grsrp`: the paper's G-RSRP minimal solver in RANSAC.
    Grsrp,
    /// `grsrp+`: `grsrp` + a final refinement over the inliers (the paper's algebraic cost
    /// in the paper preset; see [`GrsrpModel`]).
    GrsrpPlus,
    /// `rectified`: undistort by gyro, 5-point RANSAC, Sampson refinement.
    Rectified,
    /// `rectified+v`: `rectified`, then the pose and both cameras' linear velocities.
    RectifiedV,
    /// `grsrp-gravity`: known gravity, 3-point RANSAC, `rectified`'s refinement.
    GrsrpGravity,
}

impl Method {
    /// All methods: the paper's and its baselines, then this library's own.
    pub const ALL: [Method; 7] = [
        Method::Gsrp,
        Method::Nrsrp,
        Method::Grsrp,
        Method::GrsrpPlus,
        Method::Rectified,
        Method::RectifiedV,
        Method::GrsrpGravity,
    ];

    /// The command-line name.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Gsrp => "gsrp",
            Method::Nrsrp => "nrsrp",
            Method::Grsrp => "grsrp",
            Method::GrsrpPlus => "grsrp+",
            Method::Rectified => "rectified",
            Method::RectifiedV => "rectified+v",
            Method::GrsrpGravity => "grsrp-gravity",
        }
    }

    /// Minimum number of matches the method needs with the given essential solver
    /// (5 for the minimal methods, 8 with the 8-point stand-in, 17 for `nrsrp`, 3 for
    /// `grsrp-gravity`).
    pub fn min_matches(&self, essential: EssentialSolver) -> usize {
        match self {
            Method::Nrsrp => 17,
            Method::GrsrpGravity => 3,
            Method::Grsrp | Method::GrsrpPlus => 5.max(essential.sample_size()),
            Method::Gsrp | Method::Rectified | Method::RectifiedV => essential.sample_size(),
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Unknown method name.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error(
    "unknown method `{0}` (expected one of gsrp, nrsrp, grsrp, grsrp+, rectified, rectified+v, grsrp-gravity)"
)]
pub struct ParseMethodError(pub String);

impl FromStr for Method {
    type Err = ParseMethodError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| ParseMethodError(s.to_string()))
    }
}

/// RANSAC inlier threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Threshold {
    /// On the algebraic residual `|m2^T E m1|` of the method's model (bearings `K^-1[u,v,1]`,
    /// `|t| = 1`). The paper uses 0.01.
    Algebraic(f64),
    /// On the Sampson error of the method's model, in pixels (converted to normalised units
    /// by the mean focal length of the two cameras).
    SampsonPixels(f64),
}

/// Robust-estimation settings shared by the methods (in the spirit of PoseLib's
/// `RansacOptions`). Defaults ([`EstimateOptions::default`]): Sampson threshold 2.5 px for the
/// rolling-shutter-aware models, on residuals scaled by each match's row noise (1 px
/// matching noise, 0.1 rad/s gyro noise), 2 px plus a gyro-rate allowance for the global-shutter
/// model, adaptive iteration
/// count with success probability 0.9999 within 50..1000 iterations, local optimisation,
/// final refinement. The paper preset ([`EstimateOptions::paper`]): algebraic threshold 0.01
/// for every model, exactly 200 iterations, no local optimisation or final refinement.
#[derive(Debug, Clone, PartialEq)]
pub struct RobustOptions {
    /// Inlier threshold of the rolling-shutter-aware models (`rectified`: exact angular
    /// model; `grsrp`/`grsrp+`: the paper's model). Default `SampsonPixels(2.5)`. The
    /// Sampson error is the first-order distance to the epipolar curve; with a pixel
    /// threshold it is scaled per match by `σ_px / σ_i`, `σ_i` its expected noise from
    /// [`pixel_noise`](Self::pixel_noise), [`gyro_noise`](Self::gyro_noise) and its rows
    /// (a gyro-rate error moves late rows further; see `epipolar::PointData::set_row_noise`),
    /// so the threshold is 2.5 standard deviations for every match: about 99 % of true
    /// matches pass whatever their row, where one fixed threshold either drops the late
    /// rows of a fast-turning camera or admits outliers near row 0.
    pub threshold: Threshold,
    /// Inlier threshold of the global-shutter model (`gsrp`, the initialisation of `nrsrp`
    /// and `R_0` from `gsrp`). Default `SampsonPixels(2.0)`, widened by
    /// [`rolling_shutter_allowance`](Self::rolling_shutter_allowance).
    pub global_shutter_threshold: Threshold,
    /// Widening of a pixel [`global_shutter_threshold`](Self::global_shutter_threshold):
    /// `+ allowance · f λ H max(|ω1|, |ω2|)` px (focal length `f`, readout `λ`, height `H`,
    /// gyro rates `ω`). The global-shutter model ignores the rolling-shutter distortion,
    /// which moves points by up to `f |ω| H λ` (about 100 px at 2.5 rad/s for the paper's
    /// camera); a threshold sized for the matching noise alone then rejects most true
    /// matches, leaves RANSAC with a small inlier ratio and runs it to the iteration cap.
    /// The gyro only sizes the threshold here (`gsrp` and `nrsrp` still estimate without
    /// it); with a still camera the threshold is the plain one. Default 0.15 (about 17 px
    /// at 2.5 rad/s). Ignored for algebraic thresholds.
    pub rolling_shutter_allowance: f64,
    /// Adaptive iteration count (else exactly `max_iterations`).
    pub adaptive: bool,
    /// Success probability of the adaptive stopping rule.
    pub success_probability: f64,
    /// Minimum iterations (adaptive).
    pub min_iterations: usize,
    /// Maximum iterations (default 1000: bounds the cost of a hopeless problem to about
    /// 1000 minimal-solver calls; the adaptive rule stops far earlier once a model with a
    /// reasonable inlier ratio is found, e.g. 59 iterations at 70 % inliers).
    pub max_iterations: usize,
    /// Local optimisation (LO-RANSAC): every minimal model that beats all earlier minimal
    /// models is refined once (a truncated quadratic at the threshold over its 5τ²
    /// neighbourhood) and kept if it then scores best (see [`crate::estimation::ransac`]).
    pub local_optimisation: bool,
    /// Refine the final `gsrp` model on its inliers (Sampson, global-shutter model).
    pub final_refinement: bool,
    /// Sampler seed.
    pub seed: u64,
    /// Pixel noise of the matches, px (default 1): with
    /// [`gyro_noise`](Self::gyro_noise), sizes the per-point noise that scales the Sampson
    /// residuals of the rolling-shutter models (see `epipolar::RowNoise`).
    pub pixel_noise: f64,
    /// Gyro-rate noise per axis, rad/s (default 0.1): a rate error moves row `v` by about
    /// `f λ v σ_ω` px, so late rows get a proportionally wider threshold.
    pub gyro_noise: f64,
    /// Fit the gyro-rate noise to the pair's residuals after the final refinement and
    /// classify the final inliers with it (pixel thresholds only; default true, false in the
    /// paper preset). [`gyro_noise`](Self::gyro_noise) is then only the starting point and
    /// the RANSAC stage's noise: the final threshold follows the gyro the data show, which
    /// may be several times better or worse than the prior (see `methods::noise_fit`).
    pub fit_gyro_noise: bool,
    /// RANSAC and refinement use at most this many matches, a random subset; every match
    /// is then classified against the final pose (default 20,000; see `methods::subset`).
    pub max_points: usize,
    /// Error of each view's gravity direction per axis, degrees (default 1): widens
    /// `grsrp-gravity`'s consensus threshold by the relative tilt it causes.
    pub gravity_noise_deg: f64,
}

/// Where `grsrp`/`grsrp+` take their initial rotation `R_0` from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum R0Source {
    /// The `gsrp` estimate (the paper; used by [`EstimateOptions::paper`]). Biased under
    /// rolling-shutter distortion, which the G-RSRP solver's linearisation about `R_0`
    /// must then absorb.
    Gsrp,
    /// The `rectified` estimate (exact for the angular model, so `R_0` is already close
    /// and the linearisation error of the G-RSRP model is smallest). Default.
    #[default]
    Rectified,
    /// A given rotation (e.g. from an IMU or a motion model).
    Given(Matrix3<f64>),
}

/// The model `grsrp`/`grsrp+` score, locally optimise and refine their hypotheses with.
/// The G-RSRP solver always generates the hypotheses from the paper's linearised model;
/// only what judges and polishes them differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GrsrpModel {
    /// The paper's linearised model
    /// `m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1` (used by [`EstimateOptions::paper`]).
    /// Its first-order row rotation errs by about `f (v λ |ω|)² / 2` px at row `v`, so
    /// the pose it refines to is biased at fast rotation and the inlier test must allow for
    /// the truncation error, which admits more outliers at late rows.
    Paper,
    /// The exact angular model `(Ω2(v2)^T m2)^T [t]× R (Ω1(v1)^T m1)` (`rectified`'s), of
    /// which the paper's is the first-order expansion in `v λ ω`. Default.
    #[default]
    Exact,
}

impl GrsrpModel {
    /// The residual model it names.
    pub fn pose_model(self) -> PoseModel {
        match self {
            GrsrpModel::Paper => PoseModel::PaperLinear,
            GrsrpModel::Exact => PoseModel::ExactAngular,
        }
    }
}

/// All options of [`estimate_relative_pose`].
#[derive(Debug, Clone, PartialEq)]
pub struct EstimateOptions {
    /// The method.
    pub method: Method,
    /// RANSAC settings.
    pub robust: RobustOptions,
    /// Levenberg-Marquardt settings of every refinement.
    pub refinement: LmOptions,
    /// Essential-matrix solver for `gsrp`, `rectified` and the `gsrp` initialisations.
    pub essential_solver: EssentialSolver,
    /// G-RSRP solver (10 or 20 solutions).
    pub grsrp_solver: GrsrpSolver,
    /// Known-gravity solver of `grsrp-gravity` (6 or 12 solutions).
    pub gravity_solver: GravitySolver,
    /// Source of `R_0` for `grsrp`/`grsrp+`.
    pub r0_source: R0Source,
    /// The model `grsrp`/`grsrp+` score and refine with (default [`GrsrpModel::Exact`];
    /// the paper preset: [`GrsrpModel::Paper`]).
    pub grsrp_model: GrsrpModel,
    /// Cauchy loss scale of `nrsrp`, in pixels (default 2).
    pub nrsrp_cauchy_px: f64,
    /// Thresholds of the quality flags on every estimate.
    pub quality: QualityOptions,
    /// The velocity stage of `rectified+v`.
    pub velocity: VelocityOptions,
    /// For a readout time known only roughly: after the method, refine the pose together
    /// with a common scale of both views' readout times
    /// ([`crate::estimation::readout::refine_readout_scale`], exact angular model, on the
    /// method's inliers) and report it in [`Estimate::readout_scale`]. Gyro-aided methods
    /// only (not `gsrp` or `nrsrp`); default `None` (the readout is taken as given).
    pub readout: Option<ReadoutOptions>,
    /// For a gyro with an unknown constant bias: after the method (and after the readout
    /// refinement, with its scale), refine the pose together with one bias of both views'
    /// rates, their row rotations recomputed from rate − bias
    /// ([`crate::estimation::gyro_bias::refine_gyro_bias`], exact angular model, on the
    /// method's inliers), and report it in [`Estimate::gyro_bias`]. Gyro-aided methods only
    /// (not `gsrp` or `nrsrp`); default `None` (the rates are taken as unbiased).
    pub gyro_bias: Option<GyroBiasOptions>,
}

impl EstimateOptions {
    /// The paper's settings for `method`: 200 fixed RANSAC iterations, algebraic threshold
    /// 0.01 on `|m2^T E m1|` for every model, no local optimisation, no final `gsrp`
    /// refinement, `R_0` from `gsrp`.
    pub fn paper(method: Method) -> Self {
        EstimateOptions {
            method,
            r0_source: R0Source::Gsrp,
            grsrp_model: GrsrpModel::Paper,
            robust: RobustOptions {
                threshold: Threshold::Algebraic(0.01),
                global_shutter_threshold: Threshold::Algebraic(0.01),
                rolling_shutter_allowance: 0.0,
                adaptive: false,
                success_probability: 0.9999,
                min_iterations: 200,
                max_iterations: 200,
                local_optimisation: false,
                final_refinement: false,
                seed: 0,
                max_points: 20_000,
                pixel_noise: 1.0,
                gyro_noise: 0.0,
                fit_gyro_noise: true,
                gravity_noise_deg: 1.0,
            },
            ..Self::default()
        }
    }

    /// The library defaults for `method` (see [`Default`]).
    pub fn for_method(method: Method) -> Self {
        EstimateOptions {
            method,
            ..Self::default()
        }
    }
}

impl Default for EstimateOptions {
    /// Library defaults: method `grsrp+`; adaptive RANSAC (success probability 0.9999,
    /// 50..1000 iterations), Sampson threshold 2.5 px (scaled per match by its row noise, 1 px
    /// and 0.1 rad/s) for the rolling-shutter-aware models and
    /// 2 px plus 0.15 of the gyro-predicted rolling-shutter displacement for the
    /// global-shutter model (see [`RobustOptions`]), local optimisation on
    /// improvement, final Sampson refinement for `gsrp`; LM defaults; 5-point and
    /// 10-solution G-RSRP and 6-solution known-gravity solvers; `R_0` from `rectified`;
    /// `nrsrp` Cauchy scale 2 px; gravity noise 1° per axis; the velocity stage's defaults
    /// ([`VelocityOptions`]).
    fn default() -> Self {
        EstimateOptions {
            method: Method::GrsrpPlus,
            robust: RobustOptions {
                threshold: Threshold::SampsonPixels(2.5),
                global_shutter_threshold: Threshold::SampsonPixels(2.0),
                rolling_shutter_allowance: 0.15,
                adaptive: true,
                success_probability: 0.9999,
                min_iterations: 50,
                max_iterations: 1000,
                local_optimisation: true,
                final_refinement: true,
                seed: 0,
                max_points: 20_000,
                pixel_noise: 1.0,
                gyro_noise: 0.1,
                fit_gyro_noise: true,
                gravity_noise_deg: 1.0,
            },
            refinement: LmOptions::default(),
            essential_solver: EssentialSolver::FivePoint,
            grsrp_solver: GrsrpSolver::Ten,
            gravity_solver: GravitySolver::Six,
            r0_source: R0Source::Rectified,
            grsrp_model: GrsrpModel::Exact,
            nrsrp_cauchy_px: 2.0,
            quality: QualityOptions::default(),
            velocity: VelocityOptions::default(),
            readout: None,
            gyro_bias: None,
        }
    }
}

/// The result of [`estimate_relative_pose`].
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The method that produced it.
    pub method: Method,
    /// Relative rotation `R` (camera 1 row 0 to camera 2 row 0).
    pub rotation: Matrix3<f64>,
    /// Unit relative translation `t`.
    pub translation: Vector3<f64>,
    /// Inlier mask, one flag per match.
    pub inliers: Vec<bool>,
    /// RANSAC iterations of the final RANSAC stage.
    pub iterations: usize,
    /// MSAC score of the best RANSAC hypothesis: `Σ min(r², τ²)` over the matches, in the
    /// units of the method's threshold (squared).
    pub ransac_score: f64,
    /// Levenberg-Marquardt iterations of the final refinement (0 if none).
    pub refinement_iterations: usize,
    /// Final cost of the refinement (`None` without one), in the refinement's units.
    pub refinement_cost: Option<f64>,
    /// Inlier ratio, parallax, homography fit and the flags computed from them.
    pub quality: Quality,
    /// `nrsrp` only: estimated angular velocities ω1, ω2 (rad/s, camera frames).
    pub angular_velocity: Option<[Vector3<f64>; 2]>,
    /// `nrsrp` and `rectified+v` (unless it fell back to `rectified`): estimated linear
    /// velocities d1, d2 (baseline units per second, camera-1 row-0 frame).
    pub linear_velocity: Option<[Vector3<f64>; 2]>,
    /// `rectified+v` only: whether the velocities were estimated, regularised by their
    /// prior, or left out (the `rectified` pose returned), and why.
    pub velocity_fit: Option<VelocityFit>,
    /// The noise model the final inliers were classified with, when it was fitted to the
    /// pair ([`RobustOptions::fit_gyro_noise`]; `rectified`, `grsrp`, `grsrp+`,
    /// `grsrp-gravity`, and `rectified+v` when it falls back to `rectified`).
    pub noise_fit: Option<NoiseFit>,
    /// With [`EstimateOptions::readout`]: the readout time the pose was refined with, over
    /// the views' nominal one (`None` if the refinement could not run: fewer than 8
    /// inliers or a non-finite result; the method's pose is then kept).
    pub readout_scale: Option<f64>,
    /// With [`EstimateOptions::gyro_bias`]: the bias of the views' gyro rates the pose was
    /// refined with and its standard deviation, camera axes, rad/s (true rate = the views'
    /// rate − the bias; `None` if the refinement could not run: fewer than 8 inliers or a
    /// non-finite result; the method's pose is then kept).
    pub gyro_bias: Option<EstimatedBias>,
}

impl Estimate {
    /// Number of inliers.
    pub fn num_inliers(&self) -> usize {
        self.inliers.iter().filter(|&&b| b).count()
    }

    /// The estimate as the JSON object `rspose estimate --json` prints (without the
    /// command's own `seconds` and the pair file's reference errors): `method`, `rotation`
    /// (row-major rows), `translation`, `inliers` (the count), `iterations`, `inlier_ratio`,
    /// `ransac_score`, `refinement_iterations`, `refinement_cost`, `quality`, `flags`, and
    /// where present `linear_velocity`, `velocity_fit`, `noise_fit`, `readout_scale` and
    /// `gyro_bias` (`[bx, by, bz]`, camera axes, rad/s) with `gyro_bias_std` (its standard
    /// deviation per axis; `null` where infinite). The Python package's
    /// `Estimate.to_dict()` is this object.
    pub fn report_json(&self) -> serde_json::Value {
        let rows: Vec<[f64; 3]> = (0..3)
            .map(|i| std::array::from_fn(|j| self.rotation[(i, j)]))
            .collect();
        let t = self.translation;
        let mut obj = serde_json::json!({
            "method": self.method.name(),
            "rotation": rows,
            "translation": [t.x, t.y, t.z],
            "inliers": self.num_inliers(),
            "iterations": self.iterations,
            "inlier_ratio": self.quality.inlier_ratio,
            "ransac_score": self.ransac_score,
            "refinement_iterations": self.refinement_iterations,
            "refinement_cost": self.refinement_cost,
            "quality": self.quality,
            "flags": self.quality.flags(),
        });
        if let Some(d) = self.linear_velocity {
            obj["linear_velocity"] = serde_json::json!(d.map(|v| [v.x, v.y, v.z]));
        }
        if let Some(fit) = self.velocity_fit {
            obj["velocity_fit"] = serde_json::json!(fit);
        }
        if let Some(fit) = self.noise_fit {
            obj["noise_fit"] = serde_json::json!({
                "gyro_noise": fit.gyro_noise,
                "truncation": fit.truncation,
            });
        }
        if let Some(k) = self.readout_scale {
            obj["readout_scale"] = k.into();
        }
        if let Some(EstimatedBias { bias: b, std: s }) = self.gyro_bias {
            obj["gyro_bias"] = serde_json::json!([b.x, b.y, b.z]);
            obj["gyro_bias_std"] = serde_json::json!([s.x, s.y, s.z]);
        }
        obj
    }
}

/// Why no estimate was produced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EstimateError {
    /// A camera or gyro reading is invalid.
    #[error("invalid view {view}: {source}")]
    InvalidCamera {
        /// 1 or 2.
        view: usize,
        /// What is wrong.
        source: CameraError,
    },
    /// A pixel lies where its camera's distortion is not invertible (or its undistortion
    /// does not converge), so it has no bearing.
    #[error("match {index}: image {image}'s pixel has no bearing: {source}")]
    Unobservable {
        /// Index of the match.
        index: usize,
        /// 1 or 2.
        image: usize,
        /// Why ([`CameraError::NotInvertible`] or [`CameraError::NotConverged`]).
        source: CameraError,
    },
    /// A pixel coordinate is NaN or infinite.
    #[error("match {index}: non-finite pixel coordinate in image {image}")]
    NonFinitePixel {
        /// Index of the match.
        index: usize,
        /// 1 or 2.
        image: usize,
    },
    /// Too few matches for the method.
    #[error("method {method} needs at least {needed} matches, got {got}")]
    TooFewMatches {
        /// The method.
        method: Method,
        /// Matches needed.
        needed: usize,
        /// Matches given.
        got: usize,
    },
    /// Too few distinct matches (e.g. only duplicates).
    #[error("degenerate input: only {distinct} distinct matches, method {method} needs {needed}")]
    Degenerate {
        /// The method.
        method: Method,
        /// Distinct matches.
        distinct: usize,
        /// Matches needed.
        needed: usize,
    },
    /// No model was found (degenerate geometry or every sample failed).
    #[error("no solution found")]
    NoSolution,
    /// The method needs a gravity direction on both views ([`View::gravity`]).
    #[error(
        "method grsrp-gravity needs the gravity direction of both views; view {view} has none"
    )]
    MissingGravity {
        /// 1 or 2.
        view: usize,
    },
    /// Invalid option value.
    #[error("invalid option `{option}`: {reason}")]
    InvalidOption {
        /// Option name.
        option: &'static str,
        /// What is wrong.
        reason: String,
    },
}

impl From<crate::model::epipolar::UnobservableMatch> for EstimateError {
    fn from(e: crate::model::epipolar::UnobservableMatch) -> Self {
        EstimateError::Unobservable {
            index: e.index,
            image: e.image,
            source: e.source,
        }
    }
}

fn distinct_matches(matches: &[Match]) -> usize {
    let mut keys: Vec<[u64; 4]> = matches
        .iter()
        .map(|m| {
            [m[0][0], m[0][1], m[1][0], m[1][1]].map(|x| if x == 0.0 { 0u64 } else { x.to_bits() })
        })
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys.len()
}

fn validate_options(o: &EstimateOptions) -> Result<(), EstimateError> {
    let bad = |option, reason: &str| {
        Err(EstimateError::InvalidOption {
            option,
            reason: reason.into(),
        })
    };
    for (name, t) in [
        ("robust.threshold", o.robust.threshold),
        (
            "robust.global_shutter_threshold",
            o.robust.global_shutter_threshold,
        ),
    ] {
        let (Threshold::Algebraic(x) | Threshold::SampsonPixels(x)) = t;
        if !(x.is_finite() && x > 0.0) {
            return bad(name, "must be finite and positive");
        }
    }
    let a = o.robust.rolling_shutter_allowance;
    if !(a.is_finite() && a >= 0.0) {
        return bad(
            "robust.rolling_shutter_allowance",
            "must be finite and non-negative",
        );
    }
    if !(o.robust.success_probability > 0.0 && o.robust.success_probability < 1.0) {
        return bad("robust.success_probability", "must be in (0, 1)");
    }
    if o.robust.max_iterations == 0 {
        return bad("robust.max_iterations", "must be at least 1");
    }
    for (name, x) in [
        ("robust.pixel_noise", o.robust.pixel_noise),
        ("robust.gyro_noise", o.robust.gyro_noise),
        ("robust.gravity_noise_deg", o.robust.gravity_noise_deg),
    ] {
        if !(x.is_finite() && x >= 0.0) {
            return bad(name, "must be finite and non-negative");
        }
    }
    if o.robust.max_points < 20 {
        return bad("robust.max_points", "must be at least 20");
    }
    if !(o.nrsrp_cauchy_px.is_finite() && o.nrsrp_cauchy_px > 0.0) {
        return bad("nrsrp_cauchy_px", "must be finite and positive");
    }
    o.velocity.validate()?;
    if o.method == Method::RectifiedV && o.robust.pixel_noise <= 0.0 {
        return bad(
            "robust.pixel_noise",
            "must be positive for rectified+v (it scales the velocity prior and test)",
        );
    }
    if let R0Source::Given(r) = o.r0_source {
        if !r.iter().all(|x| x.is_finite())
            || (r.transpose() * r - Matrix3::identity()).norm() > 1e-6
            || r.determinant() < 0.0
        {
            return bad("r0_source", "given R_0 is not a rotation");
        }
    }
    if let Some(ro) = &o.readout {
        if matches!(o.method, Method::Gsrp | Method::Nrsrp) {
            return bad(
                "readout",
                "refining the readout needs a gyro-aided method (not gsrp or nrsrp)",
            );
        }
        if let Some((option, reason)) = ro.invalid() {
            return bad(option, reason);
        }
    }
    if let Some(bo) = &o.gyro_bias {
        if matches!(o.method, Method::Gsrp | Method::Nrsrp) {
            return bad(
                "gyro_bias",
                "refining the gyro bias needs a gyro-aided method (not gsrp or nrsrp)",
            );
        }
        if let Some((option, reason)) = bo.invalid() {
            return bad(option, reason);
        }
    }
    Ok(())
}

/// Check views, pixels, counts and options; shared by every method.
pub(crate) fn validate_input(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<(), EstimateError> {
    view1
        .validate()
        .map_err(|source| EstimateError::InvalidCamera { view: 1, source })?;
    view2
        .validate()
        .map_err(|source| EstimateError::InvalidCamera { view: 2, source })?;
    validate_options(options)?;
    if options.method == Method::GrsrpGravity {
        for (k, v) in [view1, view2].into_iter().enumerate() {
            if v.gravity.is_none() {
                return Err(EstimateError::MissingGravity { view: k + 1 });
            }
        }
    }
    for (index, m) in matches.iter().enumerate() {
        for (k, p) in m.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(EstimateError::NonFinitePixel {
                    index,
                    image: k + 1,
                });
            }
        }
    }
    crate::model::epipolar::observe_matches(&view1.camera, &view2.camera, matches)?;
    let method = options.method;
    let needed = method.min_matches(options.essential_solver);
    if matches.len() < needed {
        return Err(EstimateError::TooFewMatches {
            method,
            needed,
            got: matches.len(),
        });
    }
    let distinct = distinct_matches(matches);
    if distinct < needed {
        return Err(EstimateError::Degenerate {
            method,
            distinct,
            needed,
        });
    }
    Ok(())
}

/// Estimate the relative pose of two rolling-shutter views from pixel matches
/// `[[u1, v1], [u2, v2]]` with `options.method` (see the module documentation).
///
/// Errors: invalid camera/gyro, non-finite pixels, pixels without a bearing (where a
/// camera's distortion is not invertible), too few (distinct) matches, invalid
/// options, or no solution (degenerate geometry). Never panics and never
/// returns non-finite poses.
pub fn estimate_relative_pose(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    validate_input(view1, view2, matches, options)?;
    let large = matches.len() > options.robust.max_points;
    let subset: Vec<Match>;
    let working = if large {
        let idx = subset::subset_indices(
            matches.len(),
            options.robust.max_points,
            options.robust.seed,
        );
        subset = idx.iter().map(|&i| matches[i]).collect();
        &subset[..]
    } else {
        matches
    };
    let mut est = match options.method {
        Method::Gsrp => gsrp::estimate(view1, view2, working, options),
        Method::Rectified => rectified::estimate(view1, view2, working, options),
        Method::RectifiedV => rectified_v::estimate(view1, view2, working, options),
        Method::GrsrpGravity => grsrp_gravity::estimate(view1, view2, working, options),
        Method::Grsrp => grsrp::estimate(view1, view2, working, options, false),
        Method::GrsrpPlus => grsrp::estimate(view1, view2, working, options, true),
        Method::Nrsrp => nrsrp::estimate(view1, view2, working, options),
    }?;
    let corrected = post_refine::refine(view1, view2, working, &mut est, options);
    let (view1, view2) = match &corrected {
        Some((w1, w2)) => (w1, w2),
        None => (view1, view2),
    };
    if large {
        est.inliers = subset::classify_all(view1, view2, matches, &est, options);
    }
    // The bearings each method works on: gyro-undistorted, undistorted with `nrsrp`'s own
    // rotation estimates, or raw.
    let (b1, b2) = match (options.method, est.angular_velocity) {
        (
            Method::Grsrp
            | Method::GrsrpPlus
            | Method::Rectified
            | Method::RectifiedV
            | Method::GrsrpGravity,
            _,
        ) => (view1.clone(), view2.clone()),
        (_, Some([w1, w2])) => (View::new(view1.camera, w1), View::new(view2.camera, w2)),
        _ => (
            View::new(view1.camera, Vector3::zeros()),
            View::new(view2.camera, Vector3::zeros()),
        ),
    };
    est.quality = quality::assess(
        &b1,
        &b2,
        matches,
        &est.inliers,
        &est.rotation,
        &est.translation,
        &options.quality,
        options.robust.seed,
    );
    let finite = est.rotation.iter().all(|x| x.is_finite())
        && est.translation.iter().all(|x| x.is_finite())
        && (est.translation.norm() - 1.0).abs() < 1e-6;
    if finite {
        Ok(est)
    } else {
        Err(EstimateError::NoSolution)
    }
}

#[cfg(test)]
mod tests;
