//! Gyroscope logs: timestamped angular-velocity samples, integrated into the camera's
//! orientation over a frame's readout ([`RowTrack`]) and between two frames.
//!
//! Convention (the physical one, as everywhere in this crate): a sample `ω` is the camera's
//! angular velocity in its own axes (x right, y down, z forward; rad/s), so the
//! camera-to-world rotation evolves as `Ṙ_wc = R_wc [ω]×`. The log stores samples already
//! rotated into camera axes, `ω_cam = M ω_gyro` with the camera-gyro rotation `M`, on the
//! gyro's clock. Between samples the rate is interpolated linearly; each interval between
//! consecutive sample times is integrated with the rate at its midpoint (second-order
//! accurate), so the orientation of the frame at `t1` in the frame at `t0` is
//! `Q(t0, t1) = R_wc(t0)^T R_wc(t1) = Π_k exp([ω(τ_k) Δ_k]×)`, in time order.

use crate::model::geometry::exp_so3;
use nalgebra::{Matrix3, Vector3};
use thiserror::Error;

/// Largest angular velocity accepted, rad/s (consumer gyroscopes saturate near 35 rad/s).
/// Every check of a rate, a bias or a sample uses [`plausible_rate`], and every message
/// formats this value.
pub const MAX_ANGULAR_VELOCITY: f64 = 100.0;

/// Whether an angular velocity (a rate, a sample or a bias) is finite and at most
/// [`MAX_ANGULAR_VELOCITY`] in norm.
pub fn plausible_rate(rate: &Vector3<f64>) -> bool {
    let n = rate.norm();
    n.is_finite() && n <= MAX_ANGULAR_VELOCITY
}

/// Row rotation `Ω(v) = exp(−[v λ ω]×)` (row-0 camera frame to row-`v` camera frame) for
/// row `v`, readout `λ` (s/row) and a constant gyro rate `ω` (rad/s, camera axes): the
/// row rotation of a log whose rate does not change over the readout.
pub fn row_rotation(v: f64, readout: f64, omega: &Vector3<f64>) -> Matrix3<f64> {
    exp_so3(&(omega * (-v * readout)))
}

/// The longest gap between consecutive gyro samples that pair files and `make-pair`
/// accept, s. Between samples the rate is interpolated linearly (and each interval
/// integrated at its midpoint): a gyroscope measures the rate, and a hand-held or mounted
/// camera's rate changes smoothly on the time scale of phone sensor logs (50-200 Hz), so
/// linear interpolation of it is second-order accurate. Gaps above 50 ms (logs slower than
/// 20 Hz, or dropped samples) span a good part of a shake and are refused rather than
/// bridged.
pub const MAX_SAMPLE_GAP: f64 = 0.05;

/// A time in seconds printed with a fixed number of decimals, or in exponent notation
/// when that would take more than a few digits before the point (a timestamp of 1e300
/// would otherwise print three hundred of them).
struct Seconds(f64, usize);

impl std::fmt::Display for Seconds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.abs() < 1e12 {
            write!(f, "{:.*}", self.1, self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Why a gyro log is unusable. `index` is the 0-based sample index; readers map it to a
/// file line or field (`rspose` names both).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GyroLogError {
    /// Fewer than two samples.
    #[error("a gyro log needs at least 2 samples, got {0}")]
    TooFewSamples(usize),
    /// A time or rate is NaN or infinite.
    #[error("sample {index}: non-finite value")]
    NonFinite {
        /// Sample index.
        index: usize,
    },
    /// An angular velocity faster than any gyroscope measures
    /// ([`MAX_ANGULAR_VELOCITY`]).
    #[error("sample {index}: angular velocity above {max} rad/s", max = MAX_ANGULAR_VELOCITY)]
    Implausible {
        /// Sample index.
        index: usize,
    },
    /// A timestamp equals the previous one.
    #[error("sample {index}: duplicate timestamp {time:?}")]
    DuplicateTime {
        /// Sample index.
        index: usize,
        /// The repeated time, s.
        time: f64,
    },
    /// A timestamp is earlier than the previous one.
    #[error("sample {index}: timestamp {time:?} is earlier than the previous one ({previous:?})")]
    Unsorted {
        /// Sample index.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The previous sample's time, s.
        previous: f64,
    },
    /// Two consecutive samples are further apart than the rate can be interpolated across
    /// ([`MAX_SAMPLE_GAP`]). The message gives the times; readers add the file line or field
    /// of the sample after the gap (`index`).
    #[error("gap of {} s between the samples at {} s and {} s: the rate is interpolated across gaps of at most {max_gap} s (gyros logged at 20 Hz or faster)", Seconds(*gap, 4), Seconds(*before, 6), Seconds(*after, 6))]
    Gap {
        /// Index of the sample after the gap.
        index: usize,
        /// Time of the sample before the gap, s.
        before: f64,
        /// Time of the sample after the gap, s.
        after: f64,
        /// The gap, s.
        gap: f64,
        /// The largest gap allowed, s.
        max_gap: f64,
    },
    /// The log does not span a time interval that is needed.
    #[error(
        "the samples ({} to {} s) do not cover {what} ({} to {} s)",
        Seconds(*first, 6), Seconds(*last, 6), Seconds(*start, 6), Seconds(*end, 6)
    )]
    NotCovered {
        /// What needed covering, e.g. "image 1's readout".
        what: String,
        /// Start of the interval needed, s (gyro clock).
        start: f64,
        /// End of the interval needed, s.
        end: f64,
        /// First sample time, s.
        first: f64,
        /// Last sample time, s.
        last: f64,
    },
    /// The camera-gyro rotation is not a rotation matrix.
    #[error("camera_from_gyro is not a rotation matrix")]
    NotARotation,
}

/// A validated gyro log in camera axes: strictly increasing times (s, gyro clock) and
/// angular velocities (rad/s, camera axes).
#[derive(Debug, Clone, PartialEq)]
pub struct GyroLog {
    times: Vec<f64>,
    rates: Vec<Vector3<f64>>,
}

impl GyroLog {
    /// A log from samples `[t, ωx, ωy, ωz]` in the gyro's axes, rotated into camera axes by
    /// `camera_from_gyro` (`ω_cam = M ω_gyro`). Errors on fewer than two samples, non-finite
    /// values, duplicate or decreasing times, or a matrix that is not a rotation.
    pub fn new(
        samples: &[[f64; 4]],
        camera_from_gyro: &Matrix3<f64>,
    ) -> Result<Self, GyroLogError> {
        let m = camera_from_gyro;
        if !m.iter().all(|x| x.is_finite())
            || (m.transpose() * m - Matrix3::identity()).norm() > 1e-6
            || (m.determinant() - 1.0).abs() > 1e-6
        {
            return Err(GyroLogError::NotARotation);
        }
        if samples.len() < 2 {
            return Err(GyroLogError::TooFewSamples(samples.len()));
        }
        let mut times = Vec::with_capacity(samples.len());
        let mut rates = Vec::with_capacity(samples.len());
        for (index, s) in samples.iter().enumerate() {
            if !s.iter().all(|x| x.is_finite()) {
                return Err(GyroLogError::NonFinite { index });
            }
            if !plausible_rate(&Vector3::new(s[1], s[2], s[3])) {
                return Err(GyroLogError::Implausible { index });
            }
            if let Some(&previous) = times.last() {
                if s[0] == previous {
                    return Err(GyroLogError::DuplicateTime { index, time: s[0] });
                }
                if s[0] < previous {
                    return Err(GyroLogError::Unsorted {
                        index,
                        time: s[0],
                        previous,
                    });
                }
            }
            times.push(s[0]);
            rates.push(m * Vector3::new(s[1], s[2], s[3]));
        }
        Ok(GyroLog { times, rates })
    }

    /// [`new`](Self::new) with a constant `bias` (rad/s, the gyro's axes) subtracted from
    /// every sample before the rotation: `ω_cam = M (ω_gyro − b)`. The plausibility check
    /// applies to the raw samples (what the gyroscope reported).
    pub fn with_bias(
        samples: &[[f64; 4]],
        camera_from_gyro: &Matrix3<f64>,
        bias: &Vector3<f64>,
    ) -> Result<Self, GyroLogError> {
        let mut log = Self::new(samples, camera_from_gyro)?;
        let b = camera_from_gyro * bias;
        log.rates.iter_mut().for_each(|r| *r -= b);
        Ok(log)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Always false (a log has at least two samples).
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Time of the first and the last sample, s.
    pub fn span(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// Error if two consecutive samples are more than `max_gap` seconds apart (readers of
    /// pair files and `make-pair` use [`MAX_SAMPLE_GAP`]).
    pub fn check_gaps(&self, max_gap: f64) -> Result<(), GyroLogError> {
        for (i, w) in self.times.windows(2).enumerate() {
            let gap = w[1] - w[0];
            if gap > max_gap {
                return Err(GyroLogError::Gap {
                    index: i + 1,
                    before: w[0],
                    after: w[1],
                    gap,
                    max_gap,
                });
            }
        }
        Ok(())
    }

    /// Error unless the samples span `[start, end]`; `what` names the interval.
    pub fn check_covers(&self, start: f64, end: f64, what: &str) -> Result<(), GyroLogError> {
        let (first, last) = self.span();
        if start >= first && end <= last {
            Ok(())
        } else {
            Err(GyroLogError::NotCovered {
                what: what.to_string(),
                start,
                end,
                first,
                last,
            })
        }
    }

    /// The rate at time `t`, interpolated linearly between samples (the end samples' rates
    /// outside the log).
    pub fn rate_at(&self, t: f64) -> Vector3<f64> {
        let n = self.times.len();
        let k = self.times.partition_point(|&s| s <= t);
        if k == 0 {
            return self.rates[0];
        }
        if k == n {
            return self.rates[n - 1];
        }
        let (a, b) = (self.times[k - 1], self.times[k]);
        let f = (t - a) / (b - a);
        self.rates[k - 1] * (1.0 - f) + self.rates[k] * f
    }

    /// Sample times strictly inside `(t0, t1)`, with `t0` and `t1` at the ends: the knots
    /// of the piecewise integration.
    fn knots(&self, t0: f64, t1: f64) -> Vec<f64> {
        let lo = self.times.partition_point(|&s| s <= t0);
        let hi = self.times.partition_point(|&s| s < t1);
        let mut k = Vec::with_capacity(hi.saturating_sub(lo) + 2);
        k.push(t0);
        k.extend_from_slice(&self.times[lo..hi.max(lo)]);
        k.push(t1);
        k
    }

    /// Mean angular velocity over `[t0, t1]` (rad/s, camera axes): the integral of the
    /// interpolated rate divided by the duration (the rate at `t0` if `t1 <= t0`).
    pub fn mean_rate(&self, t0: f64, t1: f64) -> Vector3<f64> {
        if t1 <= t0 {
            return self.rate_at(t0);
        }
        let knots = self.knots(t0, t1);
        let mut sum = Vector3::zeros();
        for w in knots.windows(2) {
            sum += (self.rate_at(w[0]) + self.rate_at(w[1])) * (0.5 * (w[1] - w[0]));
        }
        sum / (t1 - t0)
    }

    /// Orientation of the camera frame at `t1` expressed in the camera frame at `t0`,
    /// `Q = R_wc(t0)^T R_wc(t1)` (so `x_t0 = Q x_t1`); the transpose of the reverse when
    /// `t1 < t0`.
    pub fn rotation_between(&self, t0: f64, t1: f64) -> Matrix3<f64> {
        if t1 < t0 {
            return self.rotation_between(t1, t0).transpose();
        }
        let mut q = Matrix3::identity();
        for w in self.knots(t0, t1).windows(2) {
            let dt = w[1] - w[0];
            if dt > 0.0 {
                q *= exp_so3(&(self.rate_at(0.5 * (w[0] + w[1])) * dt));
            }
        }
        q
    }

    /// The camera's orientation over `[start, start + duration]` (a frame's readout), for
    /// rows read at `start + v λ`.
    pub fn row_track(&self, start: f64, duration: f64) -> RowTrack {
        let end = start + duration.max(0.0);
        let knots = self.knots(start, end);
        let mut offsets = Vec::with_capacity(knots.len());
        let mut orient = Vec::with_capacity(knots.len());
        let mut rates = Vec::with_capacity(knots.len());
        let mut q = Matrix3::identity();
        for (i, &k) in knots.iter().enumerate() {
            let rate = match knots.get(i + 1) {
                Some(&next) if next > k => self.rate_at(0.5 * (k + next)),
                _ => self.rate_at(k),
            };
            offsets.push(k - start);
            orient.push(q);
            rates.push(rate);
            if let Some(&next) = knots.get(i + 1) {
                q *= exp_so3(&(rate * (next - k)));
            }
        }
        RowTrack {
            offsets,
            orient,
            rates,
        }
    }
}

/// The orientation of a camera over one frame's readout, integrated from gyro samples:
/// `Q(s) = R_wc(t_row0)^T R_wc(t_row0 + s)`, the orientation at `s` seconds after row 0 in
/// the row-0 camera frame. Piecewise: at knot `k` (offset `s_k`) the orientation `Q_k`, then
/// the constant rate `ω_k` until the next knot; before the first knot and after the last,
/// the end segments' rates extrapolate.
#[derive(Debug, Clone, PartialEq)]
pub struct RowTrack {
    offsets: Vec<f64>,
    orient: Vec<Matrix3<f64>>,
    rates: Vec<Vector3<f64>>,
}

impl RowTrack {
    /// `Q(s)`: the camera frame `s` seconds after row 0, in the row-0 camera frame
    /// (`x_row0 = Q(s) x_s`).
    pub fn orientation(&self, s: f64) -> Matrix3<f64> {
        let k = self.offsets.partition_point(|&o| o <= s).saturating_sub(1);
        self.orient[k] * exp_so3(&(self.rates[k] * (s - self.offsets[k])))
    }

    /// The same track integrated from the rates minus a constant `bias` (rad/s, camera
    /// axes): `Q(s)` recomputed knot by knot with `ω_k − b`, for refining a gyro bias without
    /// the samples (the rate between knots is constant, so this is exact for the track).
    pub fn with_bias(&self, bias: &Vector3<f64>) -> RowTrack {
        let mut orient = Vec::with_capacity(self.orient.len());
        let mut q = Matrix3::identity();
        let rates: Vec<Vector3<f64>> = self.rates.iter().map(|r| r - bias).collect();
        for (k, rate) in rates.iter().enumerate() {
            orient.push(q);
            if let Some(&next) = self.offsets.get(k + 1) {
                q *= exp_so3(&(rate * (next - self.offsets[k])));
            }
        }
        RowTrack {
            offsets: self.offsets.clone(),
            orient,
            rates,
        }
    }

    /// Row rotation `Ω(v) = Q(v λ)^T` (row-0 camera frame to row-`v` camera frame) for row
    /// `v` and readout `λ` s/row; equals `exp(−[v λ ω]×)` for a constant rate `ω`.
    pub fn row_rotation(&self, v: f64, readout: f64) -> Matrix3<f64> {
        self.orientation(v * readout).transpose()
    }
}

/// Samples parsed from a gyro CSV, with the 1-based line each came from.
#[derive(Debug, Clone, PartialEq)]
pub struct GyroCsvSamples {
    /// Samples `[t, ωx, ωy, ωz]`.
    pub samples: Vec<[f64; 4]>,
    /// The line of each sample.
    pub lines: Vec<usize>,
}

/// A line of a gyro CSV that is not a sample.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("line {line}: {reason}")]
pub struct GyroCsvError {
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub reason: String,
}

/// Parses a gyro CSV (or whitespace-separated) log into samples `[t, ωx, ωy, ωz]`, with the
/// time in column `time_column` (0-based) of four and the rates in the other three, in
/// order. Blank lines and lines starting with `#` are skipped, as is a first line that does
/// not parse as numbers (a header). Errors name the line.
pub fn parse_gyro_csv(text: &str, time_column: usize) -> Result<GyroCsvSamples, GyroCsvError> {
    let mut samples = Vec::new();
    let mut lines = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = l
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let parsed: Result<Vec<f64>, _> = fields.iter().map(|f| f.parse::<f64>()).collect();
        let values = match parsed {
            Ok(v) => v,
            Err(_) if i == 0 => continue,
            Err(e) => {
                return Err(GyroCsvError {
                    line: line_no,
                    reason: format!("not a number: {e}"),
                })
            }
        };
        if values.len() != 4 {
            return Err(GyroCsvError {
                line: line_no,
                reason: format!("expected 4 values (time and 3 rates), got {}", values.len()),
            });
        }
        let t = values[time_column.min(3)];
        let mut rate = values
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != time_column.min(3));
        let mut next = || rate.next().map(|(_, &x)| x).unwrap_or(f64::NAN);
        samples.push([t, next(), next(), next()]);
        lines.push(line_no);
    }
    Ok(GyroCsvSamples { samples, lines })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constant_log(rate: Vector3<f64>, dt: f64, n: usize) -> GyroLog {
        let s: Vec<[f64; 4]> = (0..n)
            .map(|i| [i as f64 * dt, rate.x, rate.y, rate.z])
            .collect();
        GyroLog::new(&s, &Matrix3::identity()).unwrap()
    }

    #[test]
    fn constant_rate_matches_the_closed_form() {
        let w = Vector3::new(0.3, -1.2, 0.7);
        let log = constant_log(w, 0.0025, 200);
        let track = log.row_track(0.1013, 0.03);
        let readout = 0.03 / 600.0;
        for v in [-20.0, 0.0, 13.5, 300.0, 599.0, 640.0] {
            let a = track.row_rotation(v, readout);
            let b = row_rotation(v, readout, &w);
            assert!((a - b).norm() < 1e-12, "row {v}");
        }
        assert!((log.mean_rate(0.1, 0.2) - w).norm() < 1e-12);
        let q = log.rotation_between(0.05, 0.3);
        assert!((q - exp_so3(&(w * 0.25))).norm() < 1e-12);
        assert!((log.rotation_between(0.3, 0.05) - q.transpose()).norm() < 1e-12);
    }

    #[test]
    fn a_bias_is_subtracted_in_gyro_axes_and_from_a_track() {
        let m = Matrix3::new(0.0, -1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, -1.0);
        let s = [[0.0, 1.0, 2.0, 3.0], [1.0, 1.0, 2.0, 3.0]];
        let b = Vector3::new(0.5, 0.25, -1.0);
        let log = GyroLog::with_bias(&s, &m, &b).unwrap();
        // M ((1, 2, 3) − b) = M (0.5, 1.75, 4) = (−1.75, −0.5, −4).
        assert_eq!(log.rate_at(0.5), Vector3::new(-1.75, -0.5, -4.0));
        let w = Vector3::new(0.3, -1.2, 0.7);
        let cb = Vector3::new(0.02, -0.03, 0.01);
        let track = constant_log(w, 0.0025, 200).row_track(0.1013, 0.03);
        let unbiased = constant_log(w - cb, 0.0025, 200).row_track(0.1013, 0.03);
        let readout = 0.03 / 600.0;
        for v in [0.0, 13.5, 300.0, 599.0] {
            let a = track.with_bias(&cb).row_rotation(v, readout);
            assert!(
                (a - unbiased.row_rotation(v, readout)).norm() < 1e-12,
                "row {v}"
            );
        }
    }

    #[test]
    fn a_linear_ramp_integrates_to_second_order() {
        // ω(t) = (0, a t, 0) about one axis: the angle is a t² / 2 exactly.
        let a = 3.0;
        let s: Vec<[f64; 4]> = (0..101)
            .map(|i| {
                let t = i as f64 * 0.01;
                [t, 0.0, a * t, 0.0]
            })
            .collect();
        let log = GyroLog::new(&s, &Matrix3::identity()).unwrap();
        let q = log.rotation_between(0.123, 0.777);
        let angle = 0.5 * a * (0.777f64.powi(2) - 0.123f64.powi(2));
        assert!((q - exp_so3(&Vector3::new(0.0, angle, 0.0))).norm() < 1e-12);
        let mean = log.mean_rate(0.2, 0.6);
        assert!((mean.y - a * 0.4).abs() < 1e-12);
    }

    #[test]
    fn camera_from_gyro_rotates_the_rates() {
        let m = Matrix3::new(0.0, -1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, -1.0);
        let log = GyroLog::new(&[[0.0, 1.0, 2.0, 3.0], [1.0, 1.0, 2.0, 3.0]], &m).unwrap();
        assert_eq!(log.rate_at(0.5), Vector3::new(-2.0, -1.0, -3.0));
        assert_eq!(
            GyroLog::new(&[[0.0; 4], [1.0; 4]], &(m * 2.0)),
            Err(GyroLogError::NotARotation)
        );
    }

    #[test]
    fn bad_logs_are_rejected_naming_the_sample() {
        let id = Matrix3::identity();
        let ok = [0.0, 0.1, 0.2, 0.3];
        assert_eq!(
            GyroLog::new(&[ok], &id),
            Err(GyroLogError::TooFewSamples(1))
        );
        let e = GyroLog::new(&[ok, [1.0, f64::NAN, 0.0, 0.0]], &id).unwrap_err();
        assert_eq!(e, GyroLogError::NonFinite { index: 1 });
        let e = GyroLog::new(&[ok, [1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]], &id).unwrap_err();
        assert!(matches!(e, GyroLogError::DuplicateTime { index: 2, .. }));
        let e = GyroLog::new(&[[2.0, 0.0, 0.0, 0.0], ok], &id).unwrap_err();
        assert!(matches!(e, GyroLogError::Unsorted { index: 1, .. }));
        let log = GyroLog::new(&[ok, [0.01, 0.0, 0.0, 0.0], [0.2, 0.0, 0.0, 0.0]], &id).unwrap();
        assert!(matches!(
            log.check_gaps(0.03),
            Err(GyroLogError::Gap { index: 2, .. })
        ));
        assert!(log.check_covers(0.0, 0.2, "x").is_ok());
        let e = log.check_covers(0.1, 0.3, "image 2's readout").unwrap_err();
        assert!(e.to_string().contains("image 2's readout"), "{e}");
    }

    #[test]
    fn a_phone_rate_log_integrates_like_a_dense_one() {
        // A smooth hand shake, rate 1.5 rad/s at 3 Hz, logged at 1 kHz and at 50 Hz: the
        // rotation over a frame interval agrees to a third of a pixel's angle (1/f rad) at
        // f = 600 px.
        let id = Matrix3::identity();
        let rate = |t: f64| {
            let a = 2.0 * std::f64::consts::PI * 3.0 * t;
            [t, 1.5 * a.sin(), 0.8 * a.cos(), 0.3 * (0.5 * a).sin()]
        };
        let dense: Vec<[f64; 4]> = (0..=1000).map(|k| rate(k as f64 * 1e-3)).collect();
        let phone: Vec<[f64; 4]> = (0..=50).map(|k| rate(k as f64 * 0.02)).collect();
        let (dense, phone) = (
            GyroLog::new(&dense, &id).unwrap(),
            GyroLog::new(&phone, &id).unwrap(),
        );
        assert!(phone.check_gaps(MAX_SAMPLE_GAP).is_ok());
        let (a, b) = (
            dense.rotation_between(0.31, 0.345),
            phone.rotation_between(0.31, 0.345),
        );
        let angle = crate::model::geometry::log_so3(&(a.transpose() * b)).norm();
        assert!(angle < 0.33 / 600.0, "{angle} rad");
    }

    #[test]
    fn csv_parsing_names_lines() {
        let text = "gx,gy,gz,t\n0.1,0.2,0.3,10.0\n\n# comment\n0.1,0.2,0.3,10.01\n";
        let p = parse_gyro_csv(text, 3).unwrap();
        assert_eq!(
            p.samples,
            vec![[10.0, 0.1, 0.2, 0.3], [10.01, 0.1, 0.2, 0.3]]
        );
        assert_eq!(p.lines, vec![2, 5]);
        let p = parse_gyro_csv("10.0 0.1 0.2 0.3\n", 0).unwrap();
        assert_eq!(p.samples, vec![[10.0, 0.1, 0.2, 0.3]]);
        assert_eq!(parse_gyro_csv("1,2,3,4\n1,2,x,4\n", 3).unwrap_err().line, 2);
        assert_eq!(parse_gyro_csv("1,2,3,4\n1,2,4\n", 3).unwrap_err().line, 2);
    }
}
