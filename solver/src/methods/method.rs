//! The methods' names: [`Method`], its command-line names and the smallest sample each
//! needs.

use crate::minimal::EssentialSolver;
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
    /// in the paper preset; see [`GrsrpModel`](super::GrsrpModel)).
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
