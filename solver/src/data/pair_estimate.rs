//! Estimating one pair file: its views under a row model, `R_0` from its gyro log when
//! asked for, then [`estimate_relative_pose`]. The command line (`rspose estimate` and
//! `compare`), the Python package and [`crate::experiment::real`] all estimate a pair file
//! through [`estimate_pair`].

use crate::data::pair_file::{PairFile, PairFileError};
use crate::methods::{estimate_relative_pose, Estimate, EstimateError, EstimateOptions, R0Source};
use crate::model::camera::View;
use thiserror::Error;

/// The row rotations of a pair file's views when it has a gyro log.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RowModel {
    /// Integrated from the log's samples over each readout (exact). Default.
    #[default]
    Integrated,
    /// Constant: each frame's mean rate (the log's samples dropped).
    Constant,
}

crate::names::name_table!(
    RowModel,
    "rows",
    [Integrated = "integrated", Constant = "constant"]
);

impl RowModel {
    /// The pair's two views under this row model ([`PairFile::views`], then
    /// [`View::constant_rate`] for [`RowModel::Constant`]).
    pub fn views(self, pair: &PairFile) -> Result<(View, View), PairFileError> {
        let (v1, v2) = pair.views()?;
        Ok(match self {
            RowModel::Integrated => (v1, v2),
            RowModel::Constant => (v1.constant_rate(), v2.constant_rate()),
        })
    }
}

/// Where `grsrp`/`grsrp+` take `R_0` from, by name: the library's sources, or the rotation
/// integrated from the pair file's gyro log between the two frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum R0Choice {
    /// The `gsrp` estimate ([`R0Source::Gsrp`]).
    Gsrp,
    /// The `rectified` estimate ([`R0Source::Rectified`]).
    Rectified,
    /// Integrated from the pair's gyro log ([`PairFile::gyro_relative_rotation`]).
    Gyro,
}

crate::names::name_table!(
    R0Choice,
    "R_0 source",
    [Gsrp = "gsrp", Rectified = "rectified", Gyro = "gyro"]
);

/// A gyro-integrated `R_0` was asked for, but the pair has no gyro log whose samples span
/// both frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[error("R_0 from the gyro needs a gyro_log whose samples span both frames")]
pub struct NoGyroRotation;

impl R0Choice {
    /// The library's `R_0` source this choice names whatever the pair; `None` for
    /// [`R0Choice::Gyro`], which depends on the pair's gyro log.
    pub fn fixed_source(self) -> Option<R0Source> {
        match self {
            R0Choice::Gsrp => Some(R0Source::Gsrp),
            R0Choice::Rectified => Some(R0Source::Rectified),
            R0Choice::Gyro => None,
        }
    }

    /// The library's `R_0` source this choice names for `pair`.
    pub fn source(self, pair: &PairFile) -> Result<R0Source, NoGyroRotation> {
        match self.fixed_source() {
            Some(source) => Ok(source),
            None => pair
                .gyro_relative_rotation()
                .map(R0Source::Given)
                .ok_or(NoGyroRotation),
        }
    }
}

/// Why a pair file gave no estimate.
#[derive(Debug, Error)]
pub enum PairEstimateError {
    /// The pair file could not be read, or its views are invalid.
    #[error(transparent)]
    Pair(#[from] PairFileError),
    /// `R_0` from the gyro was asked for without a log spanning both frames.
    #[error(transparent)]
    NoGyroRotation(#[from] NoGyroRotation),
    /// The estimator's error.
    #[error(transparent)]
    Estimate(#[from] EstimateError),
}

/// Estimates the relative pose of `pair` with `options`: its views under `rows`, `R_0`
/// from `r0` where given (else `options.r0_source`), then [`estimate_relative_pose`].
pub fn estimate_pair(
    pair: &PairFile,
    options: &EstimateOptions,
    rows: RowModel,
    r0: Option<R0Choice>,
) -> Result<Estimate, PairEstimateError> {
    let (v1, v2) = rows.views(pair)?;
    let estimate = match r0 {
        None => estimate_relative_pose(&v1, &v2, &pair.matches, options)?,
        Some(choice) => {
            let options = EstimateOptions {
                r0_source: choice.source(pair)?,
                ..options.clone()
            };
            estimate_relative_pose(&v1, &v2, &pair.matches, &options)?
        }
    };
    Ok(estimate)
}
