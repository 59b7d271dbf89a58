//! The paper's four synthetic sweeps ("Experiments on Synthetic Data") and their levels, and
//! this library's gravity-noise and readout-error sweeps.

use std::fmt;
use std::str::FromStr;

/// One synthetic sweep of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sweep {
    /// Angular velocity 0.5..2.5 rad/s in steps of 0.5, no linear velocity, 1 px, 0.1 rad/s.
    Angular,
    /// Levels 1..5: angular 0.5..2.5 rad/s together with linear 4..20 m/s, 1 px, 0.1 rad/s.
    AngularLinear,
    /// Gyro noise 0.1..0.5 rad/s at level 5 (2.5 rad/s, 20 m/s), 1 px.
    GyroNoise,
    /// Pixel noise 1..5 px at level 5 (2.5 rad/s, 20 m/s), 0.1 rad/s.
    PixelNoise,
    /// Gravity noise 0.5..64° per axis (doubling; 64° is no information) at 2.5 rad/s, no linear velocity, 1 px,
    /// 0.1 rad/s, with 50 % outliers (where a 3-point sample pays most).
    GravityNoise,
    /// The readout time the estimator is given, 0.7..1.3 times the true one in steps of 0.15,
    /// at 2.5 rad/s, no linear velocity, 1 px, 0.1 rad/s; every method, and `rectified` with
    /// the readout-scale refinement ([`crate::EstimateOptions::readout`]) as `rectified+k`.
    ReadoutError,
}

/// The scene parameters of one level of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Level {
    /// The value on the sweep's x axis (rad/s, level number, rad/s or px).
    pub value: f64,
    /// Magnitude of each camera's angular velocity (rad/s).
    pub angular: f64,
    /// Magnitude of each camera's linear velocity (m/s).
    pub linear: f64,
    /// Standard deviation of the pixel noise (px).
    pub pixel_noise: f64,
    /// Standard deviation of the gyro noise per axis (rad/s).
    pub gyro_noise: f64,
    /// Standard deviation of each view's gravity direction per axis (degrees).
    pub gravity_noise_deg: f64,
    /// Fraction of the matches that are outliers.
    pub outlier_fraction: f64,
    /// The readout time the estimator is given over the camera's true one (1: exact).
    pub readout_factor: f64,
    /// Also run `rectified` with the readout-scale refinement, labelled
    /// [`READOUT_REFINED_LABEL`].
    pub compare_readout_refinement: bool,
}

/// The label of `rectified` with the readout-scale refinement in a sweep's results.
pub const READOUT_REFINED_LABEL: &str = "rectified+k";

impl Sweep {
    /// All sweeps: the paper's, in its order, then the gravity-noise and readout-error
    /// sweeps.
    pub const ALL: [Sweep; 6] = [
        Sweep::Angular,
        Sweep::AngularLinear,
        Sweep::GyroNoise,
        Sweep::PixelNoise,
        Sweep::GravityNoise,
        Sweep::ReadoutError,
    ];

    /// The name used on the command line and for output files.
    pub fn name(self) -> &'static str {
        match self {
            Sweep::Angular => "angular",
            Sweep::AngularLinear => "angular-linear",
            Sweep::GyroNoise => "gyro-noise",
            Sweep::PixelNoise => "pixel-noise",
            Sweep::GravityNoise => "gravity-noise",
            Sweep::ReadoutError => "readout-error",
        }
    }

    /// The label of the x axis in plots.
    pub fn axis_label(self) -> &'static str {
        match self {
            Sweep::Angular => "angular velocity (rad/s)",
            Sweep::AngularLinear => "velocity level (0.5 rad/s + 4 m/s per level)",
            Sweep::GyroNoise => "gyro noise (rad/s)",
            Sweep::PixelNoise => "pixel noise (px)",
            Sweep::GravityNoise => "gravity noise per axis (deg), 50 % outliers",
            Sweep::ReadoutError => "nominal / true readout time, 2.5 rad/s",
        }
    }

    /// The levels of the sweep (five for the paper's and the readout error, eight for the
    /// gravity noise).
    pub fn levels(self) -> Vec<Level> {
        let level = |value, angular, linear, pixel_noise, gyro_noise| Level {
            value,
            angular,
            linear,
            pixel_noise,
            gyro_noise,
            gravity_noise_deg: 1.0,
            outlier_fraction: 0.0,
            readout_factor: 1.0,
            compare_readout_refinement: false,
        };
        let steps = (1..=5u32).map(f64::from);
        match self {
            Sweep::Angular => steps
                .map(|i| level(0.5 * i, 0.5 * i, 0.0, 1.0, 0.1))
                .collect(),
            Sweep::AngularLinear => steps
                .map(|i| level(i, 0.5 * i, 4.0 * i, 1.0, 0.1))
                .collect(),
            Sweep::GyroNoise => steps
                .map(|i| level(i / 10.0, 2.5, 20.0, 1.0, i / 10.0))
                .collect(),
            Sweep::PixelNoise => steps.map(|i| level(i, 2.5, 20.0, i, 0.1)).collect(),
            Sweep::GravityNoise => (0..8)
                .map(|k| {
                    let g = 0.5 * f64::from(1u32 << k);
                    Level {
                        gravity_noise_deg: g,
                        outlier_fraction: 0.5,
                        ..level(g, 2.5, 0.0, 1.0, 0.1)
                    }
                })
                .collect(),
            Sweep::ReadoutError => steps
                .map(|i| {
                    let factor = (55.0 + 15.0 * i) / 100.0;
                    Level {
                        readout_factor: factor,
                        compare_readout_refinement: true,
                        ..level(factor, 2.5, 0.0, 1.0, 0.1)
                    }
                })
                .collect(),
        }
    }
}

impl fmt::Display for Sweep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown sweep name.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown sweep '{0}' (expected one of: angular, angular-linear, gyro-noise, pixel-noise, gravity-noise, readout-error)")]
pub struct UnknownSweep(pub String);

impl FromStr for Sweep {
    type Err = UnknownSweep;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Sweep::ALL
            .into_iter()
            .find(|w| w.name() == s)
            .ok_or_else(|| UnknownSweep(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_match_the_paper() {
        let a = Sweep::Angular.levels();
        assert_eq!(
            a.iter().map(|l| l.angular).collect::<Vec<_>>(),
            [0.5, 1.0, 1.5, 2.0, 2.5]
        );
        assert!(a
            .iter()
            .all(|l| l.linear == 0.0 && l.pixel_noise == 1.0 && l.gyro_noise == 0.1));
        let al = Sweep::AngularLinear.levels();
        assert_eq!(
            al.iter().map(|l| l.linear).collect::<Vec<_>>(),
            [4.0, 8.0, 12.0, 16.0, 20.0]
        );
        let g = Sweep::GyroNoise.levels();
        assert!(
            (g[4].gyro_noise - 0.5).abs() < 1e-12 && g[0].angular == 2.5 && g[0].linear == 20.0
        );
        let p = Sweep::PixelNoise.levels();
        assert_eq!(
            p.iter().map(|l| l.pixel_noise).collect::<Vec<_>>(),
            [1.0, 2.0, 3.0, 4.0, 5.0]
        );
        let gr = Sweep::GravityNoise.levels();
        assert_eq!(
            gr.iter().map(|l| l.gravity_noise_deg).collect::<Vec<_>>(),
            [0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0]
        );
        assert!(gr
            .iter()
            .all(|l| l.outlier_fraction == 0.5 && l.angular == 2.5 && l.linear == 0.0));
        let r = Sweep::ReadoutError.levels();
        let factors: Vec<f64> = r.iter().map(|l| l.readout_factor).collect();
        for (f, want) in factors.iter().zip([0.7, 0.85, 1.0, 1.15, 1.3]) {
            assert!((f - want).abs() < 1e-12, "{factors:?}");
        }
        assert!(r.iter().all(|l| l.compare_readout_refinement
            && l.angular == 2.5
            && l.linear == 0.0
            && l.value == l.readout_factor));
        assert!(Sweep::ALL
            .iter()
            .filter(|&&s| s != Sweep::ReadoutError)
            .flat_map(|s| s.levels())
            .all(|l| l.readout_factor == 1.0 && !l.compare_readout_refinement));
        for s in Sweep::ALL {
            assert_eq!(s.name().parse::<Sweep>().unwrap(), s);
        }
        assert!("rotation".parse::<Sweep>().is_err());
    }
}
