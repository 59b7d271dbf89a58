//! Readout time and camera-gyro time offset from real pairs with gyro logs.
//!
//! For a candidate frame readout time `T = H λ` and time offset `δ` (gyro time of a frame's
//! row 0 minus its frame time), every match is undistorted exactly with the gyro: image 1's
//! bearing to its row-0 frame, `b1 = Q(t1, t1 + v1 λ) m1`, and image 2's to image 1's row-0
//! frame, `b2 = Q(t1, t2) Q(t2, t2 + v2 λ) m2` (`Q` the orientation integrated from the log,
//! [`GyroLog::rotation_between`], `t_k = frame_time_k + δ`). What is left is a pure
//! translation, `t · (b1 × b2) = 0`: the cost of a pair is its robust pure-translation fit,
//! the distance (pixels) of each `b2` from the epipolar plane of `b1` and `t`. The right `(T, δ)` makes the derotated matches most consistent with one
//! translation; wrong values leave rotation residuals that no translation explains (the
//! pair cost is the Cauchy loss of those distances, see `translation_fit_cost`). The
//! search is a grid, then a finer grid around the best cell.

use crate::data::pair_file::PairFile;
use crate::model::epipolar::{observe_matches, UnobservableMatch};
use crate::model::gyro_log::{GyroLog, GyroLogError};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use serde::Serialize;
use thiserror::Error;

/// Why a calibration cannot run.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CalibrationError {
    /// No pairs given.
    #[error("no pairs to calibrate from")]
    NoPairs,
    /// A pair has no gyro log.
    #[error("pair {0} has no gyro_log (calibration needs gyro samples)")]
    NoGyroLog(usize),
    /// A pair's log is unusable.
    #[error("pair {pair}: {source}")]
    Log {
        /// Pair index.
        pair: usize,
        /// What is wrong.
        source: GyroLogError,
    },
    /// A grid is empty, reversed or not finite.
    #[error("invalid search grid `{0}`: needs finite min <= max and a positive step")]
    InvalidGrid(&'static str),
    /// A pair's samples do not reach as far as the searched offsets and readouts need.
    #[error("pair {pair}: {source}; make the pairs with `make-pair --margin` of at least {margin:.3} s, or search a narrower --offset-ms range")]
    NotCovered {
        /// Pair index.
        pair: usize,
        /// The margin the search needs around the frames, s.
        margin: f64,
        /// What is missing.
        source: GyroLogError,
    },
    /// The search would take too long: more than [`MAX_GRID_CELLS`] coarse cells, or more
    /// than [`MAX_GRID_WORK`] cells × matches.
    #[error("search grid of {readouts} readouts x {offsets} offsets over {matches} matches is too large (at most {max_cells} cells and {max_work:e} cells x matches); use a coarser step or a narrower range", max_cells = MAX_GRID_CELLS, max_work = MAX_GRID_WORK)]
    GridTooLarge {
        /// Readout values of the grid.
        readouts: usize,
        /// Offset values of the grid.
        offsets: usize,
        /// Matches the cost sums over (after [`MAX_PAIR_MATCHES`]).
        matches: usize,
    },
    /// A pair's match has a pixel without a bearing in its camera.
    #[error("pair {pair}: {source}")]
    Unobservable {
        /// Pair index.
        pair: usize,
        /// The match and why.
        source: UnobservableMatch,
    },
}

/// Why a calibration's optimum is in doubt (a warning beside the result, not an error).
#[derive(Debug, Clone, PartialEq, Serialize, Error)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CalibrationDoubt {
    /// The best value is on the edge of its search range: the optimum may lie beyond it.
    #[error("the best {parameter} ({value_ms:.2} ms) is on the edge of the searched range {min_ms:.2} to {max_ms:.2} ms: widen the range")]
    OnEdge {
        /// `readout` or `offset`.
        parameter: &'static str,
        /// The best value, ms.
        value_ms: f64,
        /// The range searched, ms.
        min_ms: f64,
        /// The range searched, ms.
        max_ms: f64,
    },
    /// The cost hardly changes over the parameter's range: the pairs do not determine it
    /// (too little rotation, or too few matches).
    #[error("the cost varies by only {percent:.1} % over the searched {parameter} range: the pairs hardly determine it (more rotation or more matches needed)")]
    Flat {
        /// `readout` or `offset`.
        parameter: &'static str,
        /// (highest − lowest) / lowest of the parameter's cost profile, %.
        percent: f64,
    },
}

/// A cost profile whose relative range is below this is [`CalibrationDoubt::Flat`].
pub const FLAT_RELATIVE_RANGE: f64 = 0.02;

/// A search range `min..=max` in steps of `step` (seconds).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    /// First value, s.
    pub min: f64,
    /// Last value, s.
    pub max: f64,
    /// Step, s.
    pub step: f64,
}

/// Most coarse grid cells (readouts × offsets) a calibration searches: the default grid
/// has about a thousand, and each cell costs a pass over every match.
pub const MAX_GRID_CELLS: usize = 100_000;

/// Most cells × matches of a search, which bounds its time (about a minute on one core).
pub const MAX_GRID_WORK: f64 = 1e8;

/// Most matches of one pair that enter the cost: a pair with more is subsampled with a
/// deterministic stride (every k-th match), since the readout and offset are
/// determined by a few thousand matches spread over the image and the cost's time grows
/// with their number.
pub const MAX_PAIR_MATCHES: usize = 5_000;

impl Range {
    fn values(&self, name: &'static str) -> Result<Vec<f64>, CalibrationError> {
        if !(self.min.is_finite()
            && self.max.is_finite()
            && self.step.is_finite()
            && self.step > 0.0
            && self.min <= self.max
            && (self.max - self.min) / self.step <= 10_000.0)
        {
            return Err(CalibrationError::InvalidGrid(name));
        }
        let n = ((self.max - self.min) / self.step + 1e-9).floor() as usize;
        Ok((0..=n).map(|i| self.min + i as f64 * self.step).collect())
    }
}

/// Options of [`calibrate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibrationOptions {
    /// Frame readout times `H λ` to try, s (default 0 to 40 ms in 1 ms steps).
    pub readout: Range,
    /// Time offsets to try, s (default −15 to 15 ms in 1 ms steps).
    pub offset: Range,
    /// Scale of the Cauchy loss on the per-match distance, pixels (default 1).
    pub loss_scale_px: f64,
    /// Step of the fine grid around the best coarse cell, s (default 0.1 ms).
    pub fine_step: f64,
}

impl Default for CalibrationOptions {
    fn default() -> Self {
        CalibrationOptions {
            readout: Range {
                min: 0.0,
                max: 0.040,
                step: 0.001,
            },
            offset: Range {
                min: -0.015,
                max: 0.015,
                step: 0.001,
            },
            loss_scale_px: 1.0,
            fine_step: 0.0001,
        }
    }
}

/// The calibration: the best values and the cost over the coarse grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Calibration {
    /// Best frame readout time `H λ`, s.
    pub readout: f64,
    /// Best readout time per line `λ` of the first pair's first camera, s/line.
    pub readout_per_row: f64,
    /// Best time offset, s.
    pub offset: f64,
    /// Mean robust cost per match at the best values, px².
    pub cost: f64,
    /// Coarse readout values, s.
    pub readouts: Vec<f64>,
    /// Coarse offset values, s.
    pub offsets: Vec<f64>,
    /// Mean robust cost per match over the coarse grid, `cost[i][j]` at `readouts[i]`, `offsets[j]`, px².
    pub grid: Vec<Vec<f64>>,
    /// Why the optimum may be wrong (empty when it is well determined inside the grid).
    pub doubts: Vec<CalibrationDoubt>,
}

impl Calibration {
    /// For each coarse readout, the lowest cost over the offsets (the readout cost curve).
    pub fn readout_profile(&self) -> Vec<(f64, f64)> {
        self.readouts
            .iter()
            .zip(&self.grid)
            .map(|(&r, row)| (r, row.iter().copied().fold(f64::INFINITY, f64::min)))
            .collect()
    }

    /// For each coarse offset, the lowest cost over the readouts (the offset cost curve).
    pub fn offset_profile(&self) -> Vec<(f64, f64)> {
        self.offsets
            .iter()
            .enumerate()
            .map(|(j, &o)| {
                let best = self
                    .grid
                    .iter()
                    .map(|row| row[j])
                    .fold(f64::INFINITY, f64::min);
                (o, best)
            })
            .collect()
    }
}

struct PairData {
    log: GyroLog,
    frame_times: [f64; 2],
    /// Lines per frame of image 1 and image 2 (the frame readout is shared).
    lines: [f64; 2],
    focal: f64,
    bearings: Vec<(f64, Vector3<f64>, f64, Vector3<f64>)>,
}

impl PairData {
    /// Robust cost of the pure-translation fit (px²) at `(T, δ)`.
    fn cost(&self, readout: f64, offset: f64, scale_px: f64) -> f64 {
        let lambda = [readout / self.lines[0], readout / self.lines[1]];
        let (t1, t2) = (self.frame_times[0] + offset, self.frame_times[1] + offset);
        let track1 = self.log.row_track(t1, readout);
        let track2 = self.log.row_track(t2, readout);
        let q12 = self.log.rotation_between(t1, t2);
        let dirs: Vec<(Vector3<f64>, Vector3<f64>)> = self
            .bearings
            .iter()
            .map(|(v1, m1, v2, m2)| {
                let b1 = (track1.orientation(v1 * lambda[0]) * m1).normalize();
                let b2 = (q12 * track2.orientation(v2 * lambda[1]) * m2).normalize();
                (b1, b2)
            })
            .collect();
        translation_fit_cost(&dirs, scale_px / self.focal) * self.focal * self.focal
    }
}

/// Robust pure-translation fit: the unit `t` minimising the Cauchy cost
/// `Σ τ² ln(1 + d_i² / τ²)` with `d_i = t·(b1 × b2) / sqrt((|t × b1|² + |t × b2|²) / 2)`, the
/// symmetric (Sampson-like) angular distance of the two rays from a common epipolar plane,
/// by iteratively reweighted smallest eigenvectors of the scatter of `b1 × b2` (started
/// unweighted). Returns the cost. The Cauchy loss keeps the cost smooth in `(T, δ)` where a
/// truncation would make it jump as matches cross the threshold.
fn translation_fit_cost(dirs: &[(Vector3<f64>, Vector3<f64>)], tau: f64) -> f64 {
    let tau2 = tau * tau;
    let distances = |t: &Vector3<f64>| -> Vec<f64> {
        dirs.iter()
            .map(|(b1, b2)| {
                let s = 0.5 * (t.cross(b1).norm_squared() + t.cross(b2).norm_squared());
                t.dot(&b1.cross(b2)) / s.sqrt().max(1e-9)
            })
            .collect()
    };
    let cost_of = |d: &[f64]| d.iter().map(|d| tau2 * (d * d / tau2).ln_1p()).sum::<f64>();
    let fit = |weights: &[f64]| -> Option<Vector3<f64>> {
        let mut m = Matrix3::zeros();
        for ((b1, b2), w) in dirs.iter().zip(weights) {
            let c = b1.cross(b2);
            m += c * c.transpose() * *w;
        }
        let e = SymmetricEigen::new(m);
        let t = e.eigenvectors.column(e.eigenvalues.imin()).into_owned();
        t.iter().all(|x| x.is_finite()).then_some(t)
    };
    let Some(t) = fit(&vec![1.0; dirs.len()]) else {
        return f64::INFINITY;
    };
    let mut d = distances(&t);
    let mut best = cost_of(&d);
    for _ in 0..10 {
        let weights: Vec<f64> = d.iter().map(|d| 1.0 / (1.0 + d * d / tau2)).collect();
        let Some(next) = fit(&weights) else {
            break;
        };
        let dn = distances(&next);
        let c = cost_of(&dn);
        if c >= best * (1.0 - 1e-9) {
            break;
        }
        (best, d) = (c, dn);
    }
    best
}

fn mean_cost(pairs: &[PairData], readout: f64, offset: f64, tau: f64, total: usize) -> f64 {
    pairs
        .iter()
        .map(|p| p.cost(readout, offset, tau))
        .sum::<f64>()
        / total.max(1) as f64
}

/// Estimates the frame readout time and the camera-gyro time offset from `pairs` (each with
/// a gyro log whose samples span both frames and the offsets searched). The pairs' own
/// `camera.readout` and `time_offset` are ignored: they are what is estimated.
pub fn calibrate(
    pairs: &[PairFile],
    options: &CalibrationOptions,
) -> Result<Calibration, CalibrationError> {
    if pairs.is_empty() {
        return Err(CalibrationError::NoPairs);
    }
    let readouts = options.readout.values("readout")?;
    let offsets = options.offset.values("offset")?;
    if !(options.fine_step.is_finite() && options.fine_step > 0.0) {
        return Err(CalibrationError::InvalidGrid("fine_step"));
    }
    let mut data = Vec::with_capacity(pairs.len());
    for (i, p) in pairs.iter().enumerate() {
        let spec = p.gyro_log.as_ref().ok_or(CalibrationError::NoGyroLog(i))?;
        let log = spec
            .log()
            .map_err(|source| CalibrationError::Log { pair: i, source })?;
        let (lo, hi) = (
            spec.frame_times[0].min(spec.frame_times[1]),
            spec.frame_times[0].max(spec.frame_times[1]),
        );
        let (start, end) = (
            lo + options.offset.min,
            hi + options.offset.max + options.readout.max,
        );
        log.check_covers(
            start,
            end,
            "both frames over the searched offsets and readouts",
        )
        .map_err(|source| CalibrationError::NotCovered {
            pair: i,
            margin: (lo - start).max(end - hi).max(0.0),
            source,
        })?;
        let [cam1, cam2] = p.cameras;
        let observations = observe_matches(&cam1, &cam2, &p.matches)
            .map_err(|source| CalibrationError::Unobservable { pair: i, source })?;
        let stride = observations.len().div_ceil(MAX_PAIR_MATCHES).max(1);
        data.push(PairData {
            log,
            frame_times: spec.frame_times,
            lines: [cam1.lines(), cam2.lines()],
            focal: 0.5 * (cam1.mean_focal() + cam2.mean_focal()),
            bearings: observations
                .iter()
                .step_by(stride)
                .map(|[a, b]| (a.line, a.bearing, b.line, b.bearing))
                .collect(),
        });
    }
    let total: usize = data.iter().map(|d| d.bearings.len()).sum();
    let cells = readouts.len() * offsets.len();
    if cells > MAX_GRID_CELLS || cells as f64 * total as f64 > MAX_GRID_WORK {
        return Err(CalibrationError::GridTooLarge {
            readouts: readouts.len(),
            offsets: offsets.len(),
            matches: total,
        });
    }
    let tau = options.loss_scale_px;
    let grid: Vec<Vec<f64>> = readouts
        .iter()
        .map(|&r| {
            offsets
                .iter()
                .map(|&o| mean_cost(&data, r, o, tau, total))
                .collect()
        })
        .collect();
    let (mut readout, mut offset, mut cost) = (readouts[0], offsets[0], f64::INFINITY);
    for (i, row) in grid.iter().enumerate() {
        for (j, &c) in row.iter().enumerate() {
            if c < cost {
                (readout, offset, cost) = (readouts[i], offsets[j], c);
            }
        }
    }
    // A finer grid over the coarse cell around the best point.
    let fine = |centre: f64, half: f64, lo: f64, hi: f64| -> Vec<f64> {
        let n = (half / options.fine_step).round() as i64;
        (-n..=n)
            .map(|k| centre + k as f64 * options.fine_step)
            .filter(|v| *v >= lo && *v <= hi)
            .collect()
    };
    let fine_r = fine(
        readout,
        options.readout.step,
        options.readout.min,
        options.readout.max,
    );
    let fine_o = fine(
        offset,
        options.offset.step,
        options.offset.min,
        options.offset.max,
    );
    for &r in &fine_r {
        for &o in &fine_o {
            let c = mean_cost(&data, r, o, tau, total);
            if c < cost {
                (readout, offset, cost) = (r, o, c);
            }
        }
    }
    let lines = pairs[0].cameras[0].lines();
    let mut c = Calibration {
        readout,
        readout_per_row: readout / lines,
        offset,
        cost,
        readouts,
        offsets,
        grid,
        doubts: Vec::new(),
    };
    c.doubts = doubts(&c, options);
    Ok(c)
}

/// The doubts about `c`'s optimum: on the edge of a range (a readout of 0 at the lower
/// edge is a global-shutter camera, not a doubt), or a flat cost profile.
fn doubts(c: &Calibration, options: &CalibrationOptions) -> Vec<CalibrationDoubt> {
    let mut out = Vec::new();
    let ms = 1e3;
    for (parameter, value, range, profile) in [
        ("readout", c.readout, options.readout, c.readout_profile()),
        ("offset", c.offset, options.offset, c.offset_profile()),
    ] {
        let half = 0.5 * options.fine_step;
        let at_min = value <= range.min + half && !(parameter == "readout" && range.min == 0.0);
        let at_max = value >= range.max - half;
        if (at_min || at_max) && range.max > range.min {
            out.push(CalibrationDoubt::OnEdge {
                parameter,
                value_ms: value * ms,
                min_ms: range.min * ms,
                max_ms: range.max * ms,
            });
        }
        let lo = profile.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let hi = profile
            .iter()
            .map(|p| p.1)
            .fold(f64::NEG_INFINITY, f64::max);
        if profile.len() > 1 && lo > 0.0 && hi.is_finite() && (hi - lo) / lo < FLAT_RELATIVE_RANGE {
            out.push(CalibrationDoubt::Flat {
                parameter,
                percent: 100.0 * (hi - lo) / lo,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::pair_file::GyroLogSpec;
    use crate::model::camera::Camera;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A camera turning with a time-varying rate (the log), translating between two frames;
    /// each point projects through the orientation of the instant its row is read
    /// (`t = frame_time + δ + v λ`, fixed point over `v`). Calibration must recover the
    /// readout and the offset used to make the images.
    #[test]
    fn recovers_readout_and_offset_from_a_synthetic_recording() {
        let (readout, offset) = (0.020, -0.003);
        let cam = Camera::pinhole(500.0, 500.0, 400.0, 300.0, 800.0, 600.0, readout / 600.0);
        let rate = |t: f64| {
            Vector3::new(
                1.5 * (9.0 * t).sin(),
                2.0 * (7.0 * t + 1.0).cos(),
                0.8 * (5.0 * t).sin(),
            )
        };
        let samples: Vec<[f64; 4]> = (0..400)
            .map(|i| {
                let t = i as f64 / 400.0;
                let w = rate(t);
                [t, w.x, w.y, w.z]
            })
            .collect();
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let log = GyroLog::new(&samples, &Matrix3::identity()).unwrap();
        let frame_times = [0.40, 0.4667];
        let centres = [Vector3::zeros(), Vector3::new(0.3, 0.05, 1.0)];
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut matches = Vec::new();
        while matches.len() < 300 {
            let x = Vector3::new(
                rng.gen_range(-8.0..8.0),
                rng.gen_range(-6.0..6.0),
                rng.gen_range(8.0..30.0),
            );
            let project = |k: usize| -> Option<[f64; 2]> {
                let mut v = 300.0;
                for _ in 0..50 {
                    let t = frame_times[k] + offset + v * cam.readout;
                    // World = the camera frame at time 0.
                    let xc = log.rotation_between(0.0, t).transpose() * (x - centres[k]);
                    let p = cam.project(&xc)?;
                    if (p.y - v).abs() < 1e-10 {
                        return Some([p.x, p.y]);
                    }
                    v = p.y;
                }
                None
            };
            if let (Some(a), Some(b)) = (project(0), project(1)) {
                let inside =
                    |p: [f64; 2]| (0.0..800.0).contains(&p[0]) && (0.0..600.0).contains(&p[1]);
                if inside(a) && inside(b) {
                    let n = |rng: &mut ChaCha8Rng| 0.2 * (rng.gen::<f64>() - 0.5);
                    matches.push([
                        [a[0] + n(&mut rng), a[1] + n(&mut rng)],
                        [b[0] + n(&mut rng), b[1] + n(&mut rng)],
                    ]);
                }
            }
        }
        let pair = PairFile {
            cameras: [Camera {
                readout: 1e-5,
                ..cam
            }; 2],
            gyro: None,
            gyro_bias: None,
            gravity: None,
            gyro_log: Some(GyroLogSpec {
                camera_from_gyro: identity,
                time_offset: 0.0,
                frame_times,
                samples,
                gyro_bias: None,
            }),
            matches,
            ground_truth: None,
        };
        let c = calibrate(std::slice::from_ref(&pair), &CalibrationOptions::default()).unwrap();
        assert!(c.doubts.is_empty(), "{:?}", c.doubts);
        // A range that excludes the true offset: its best value is on the edge, in doubt.
        let narrow = CalibrationOptions {
            offset: Range {
                min: 0.0,
                max: 0.005,
                step: 0.001,
            },
            ..CalibrationOptions::default()
        };
        let edge = calibrate(std::slice::from_ref(&pair), &narrow).unwrap();
        assert!(
            edge.doubts.iter().any(|d| matches!(
                d,
                CalibrationDoubt::OnEdge {
                    parameter: "offset",
                    ..
                }
            )),
            "{:?}",
            edge.doubts
        );
        // A camera that does not rotate: neither value is determined.
        let mut still = pair.clone();
        if let Some(spec) = &mut still.gyro_log {
            for s in &mut spec.samples {
                s[1..].fill(0.0);
            }
        }
        let flat = calibrate(&[still], &CalibrationOptions::default()).unwrap();
        for parameter in ["readout", "offset"] {
            assert!(
                flat.doubts.iter().any(
                    |d| matches!(d, CalibrationDoubt::Flat { parameter: p, .. } if *p == parameter)
                ),
                "{parameter}: {:?}",
                flat.doubts
            );
        }
        assert!(
            (c.readout - readout).abs() < 0.0015,
            "readout {}",
            c.readout
        );
        assert!((c.offset - offset).abs() < 0.0015, "offset {}", c.offset);
        // The curves are lowest at the answer.
        let (r_best, _) = c
            .readout_profile()
            .into_iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!((r_best - readout).abs() < 0.0015);
    }

    #[test]
    fn bad_input_is_named() {
        assert_eq!(
            calibrate(&[], &CalibrationOptions::default()),
            Err(CalibrationError::NoPairs)
        );
        let pair = crate::data::simulate::simulate(&Default::default()).unwrap();
        assert_eq!(
            calibrate(&[pair], &CalibrationOptions::default()),
            Err(CalibrationError::NoGyroLog(0))
        );
        let mut o = CalibrationOptions::default();
        o.offset.step = 0.0;
        assert_eq!(
            o.offset.values("offset"),
            Err(CalibrationError::InvalidGrid("offset"))
        );
    }
}
