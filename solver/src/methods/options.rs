//! The options of [`estimate_relative_pose`](super::estimate_relative_pose)(super::estimate_relative_pose): plain structs
//! whose [`Default`] is the library's documented choice, and the presets.

use super::method::Method;
use super::quality::QualityOptions;
use super::rectified_v::VelocityOptions;
use crate::estimation::gyro_bias::GyroBiasOptions;
use crate::estimation::readout::ReadoutOptions;
use crate::estimation::refine::LmOptions;
use crate::minimal::{EssentialSolver, GravitySolver, GrsrpSolver};
use crate::model::epipolar::PoseModel;
use nalgebra::Matrix3;

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
/// `RansacOptions`): a plain struct; [`Default`] gives the library's choice, documented on
/// each field, [`RobustOptions::paper`] the paper's. Defaults: Sampson threshold 2.5 px for the
/// rolling-shutter-aware models, on residuals scaled by each match's row noise (1 px
/// matching noise, 0.1 rad/s gyro noise), 2 px plus a gyro-rate allowance for the global-shutter
/// model, adaptive iteration
/// count with success probability 0.9999 within 50..1000 iterations, local optimisation,
/// final refinement. The paper preset ([`RobustOptions::paper`]): algebraic threshold 0.01
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
    /// Adaptive iteration count (else exactly `max_iterations`). Default true.
    pub adaptive: bool,
    /// Success probability of the adaptive stopping rule. Default 0.9999.
    pub success_probability: f64,
    /// Minimum iterations (adaptive). Default 50.
    pub min_iterations: usize,
    /// Maximum iterations (default 1000: bounds the cost of a hopeless problem to about
    /// 1000 minimal-solver calls; the adaptive rule stops far earlier once a model with a
    /// reasonable inlier ratio is found, e.g. 59 iterations at 70 % inliers).
    pub max_iterations: usize,
    /// Local optimisation (LO-RANSAC): every minimal model that beats all earlier minimal
    /// models is refined once (a truncated quadratic at the threshold over its 5τ²
    /// neighbourhood) and kept if it then scores best (see [`crate::estimation::ransac`]).
    /// Default true.
    pub local_optimisation: bool,
    /// Refine the final `gsrp` model on its inliers (Sampson, global-shutter model).
    /// Default true.
    pub final_refinement: bool,
    /// Sampler seed. Default 0.
    pub seed: u64,
    /// Pixel noise of the matches, px (default 1): with
    /// [`gyro_noise`](Self::gyro_noise), sizes the per-point noise that scales the Sampson
    /// residuals of the rolling-shutter models (see `epipolar::RowNoise`).
    pub pixel_noise: f64,
    /// Gyro-rate noise per axis, rad/s (default 0.1): a rate error moves row `v` by about
    /// `f λ v σ_ω` px, so late rows get a proportionally wider threshold.
    pub gyro_noise: f64,
    /// Fit the gyro-rate noise to the pair's residuals after the final refinement and
    /// classify the final inliers with it (pixel thresholds only). Default true, also in the
    /// paper preset: its thresholds are algebraic, so nothing is fitted and `grsrp` only
    /// classifies every match against its final pose with the algebraic threshold.
    /// [`gyro_noise`](Self::gyro_noise) is then only the starting point and
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

crate::names::name_table!(GrsrpModel, "model", [Paper = "paper", Exact = "exact"]);

impl GrsrpModel {
    /// The residual model it names.
    pub fn pose_model(self) -> PoseModel {
        match self {
            GrsrpModel::Paper => PoseModel::PaperLinear,
            GrsrpModel::Exact => PoseModel::ExactAngular,
        }
    }
}

/// All options of [`estimate_relative_pose`](super::estimate_relative_pose).
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
    /// method's inliers) and report it in [`Estimate::readout_scale`](super::Estimate::readout_scale). Gyro-aided methods
    /// only (not `gsrp` or `nrsrp`); default `None` (the readout is taken as given).
    pub readout: Option<ReadoutOptions>,
    /// For a gyro with an unknown constant bias: after the method (and after the readout
    /// refinement, with its scale), refine the pose together with one bias of both views'
    /// rates, their row rotations recomputed from rate − bias
    /// ([`crate::estimation::gyro_bias::refine_gyro_bias`], exact angular model, on the
    /// method's inliers), and report it in [`Estimate::gyro_bias`](super::Estimate::gyro_bias). Gyro-aided methods only
    /// (not `gsrp` or `nrsrp`); default `None` (the rates are taken as unbiased).
    pub gyro_bias: Option<GyroBiasOptions>,
}

impl Default for RobustOptions {
    /// The library defaults, each documented on its field.
    fn default() -> Self {
        RobustOptions {
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
            pixel_noise: 1.0,
            gyro_noise: 0.1,
            fit_gyro_noise: true,
            max_points: 20_000,
            gravity_noise_deg: 1.0,
        }
    }
}

impl RobustOptions {
    /// The paper's RANSAC: algebraic threshold 0.01 on `|m2^T E m1|` for every model, no
    /// rolling-shutter allowance, exactly 200 iterations, no local optimisation, no final
    /// `gsrp` refinement and no gyro-rate noise; the rest as [`Default`].
    pub fn paper() -> Self {
        RobustOptions {
            threshold: Threshold::Algebraic(0.01),
            global_shutter_threshold: Threshold::Algebraic(0.01),
            rolling_shutter_allowance: 0.0,
            adaptive: false,
            min_iterations: 200,
            max_iterations: 200,
            local_optimisation: false,
            final_refinement: false,
            gyro_noise: 0.0,
            ..Self::default()
        }
    }
}

impl EstimateOptions {
    /// The paper's settings for `method` ([`RobustOptions::paper`], `R_0` from `gsrp`, the
    /// paper's G-RSRP model); the rest as [`Default`].
    pub fn paper(method: Method) -> Self {
        EstimateOptions {
            method,
            r0_source: R0Source::Gsrp,
            grsrp_model: GrsrpModel::Paper,
            robust: RobustOptions::paper(),
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
    /// Library defaults: method `grsrp+`; [`RobustOptions::default`]; LM defaults; 5-point
    /// and 10-solution G-RSRP and 6-solution known-gravity solvers; `R_0` from `rectified`;
    /// the exact angular G-RSRP model; `nrsrp` Cauchy scale 2 px; the quality and velocity
    /// stages' defaults; no readout or gyro-bias refinement.
    fn default() -> Self {
        EstimateOptions {
            method: Method::GrsrpPlus,
            robust: RobustOptions::default(),
            refinement: LmOptions::default(),
            essential_solver: EssentialSolver::default(),
            grsrp_solver: GrsrpSolver::default(),
            gravity_solver: GravitySolver::default(),
            r0_source: R0Source::default(),
            grsrp_model: GrsrpModel::default(),
            nrsrp_cauchy_px: 2.0,
            quality: QualityOptions::default(),
            velocity: VelocityOptions::default(),
            readout: None,
            gyro_bias: None,
        }
    }
}

/// A named set of options: the paper's settings or the library's defaults.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Preset {
    /// The library defaults ([`EstimateOptions::for_method`]): adaptive RANSAC, a 2.5 px
    /// Sampson threshold scaled per match by its row noise (2 px plus a gyro-rate allowance
    /// for the global-shutter model), local optimisation, final refinement.
    #[default]
    Default,
    /// The paper ([`EstimateOptions::paper`]): 200 RANSAC iterations, threshold 0.01 on
    /// `|m2^T E m1|`.
    Paper,
}

crate::names::name_table!(Preset, "preset", [Default = "default", Paper = "paper"]);

impl Preset {
    /// The preset's options for `method`.
    pub fn options(self, method: Method) -> EstimateOptions {
        match self {
            Preset::Default => EstimateOptions::for_method(method),
            Preset::Paper => EstimateOptions::paper(method),
        }
    }
}
