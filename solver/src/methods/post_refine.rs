//! The refinements that may follow a method: the readout-time scale
//! ([`EstimateOptions::readout`]) and then the gyro bias ([`EstimateOptions::gyro_bias`]),
//! each refining the pose with its parameter on the method's inliers.

use super::{Estimate, EstimateOptions};
use crate::estimation::gyro_bias::{refine_gyro_bias, unbiased_view, EstimatedBias};
use crate::estimation::readout::refine_readout_scale;
use crate::model::camera::View;
use crate::model::matches::Match;

/// Runs the refinements `options` asks for on `est` (its pose replaced, `readout_scale`
/// and `gyro_bias` set where a refinement ran), over `working`, the matches the method
/// ran on. Returns the views with the fitted bias removed (and the readout scaled, as the
/// bias was refined with) when a bias was fitted, for the final classification and the
/// quality report; `None` leaves the given views in use.
pub(super) fn refine(
    view1: &View,
    view2: &View,
    working: &[Match],
    est: &mut Estimate,
    options: &EstimateOptions,
) -> Option<(View, View)> {
    if let Some(ro) = &options.readout {
        // On the method's own matches (the subset of a large input, before every match is
        // classified against the result). The method's inliers stay: they were classified
        // at the nominal readout, with a threshold that already allows for the rows' gyro
        // error.
        if let Some(fit) = refine_readout_scale(
            view1,
            view2,
            working,
            &est.inliers,
            &est.rotation,
            &est.translation,
            ro,
        ) {
            est.rotation = fit.rotation;
            est.translation = fit.translation;
            est.readout_scale = Some(fit.scale);
        }
    }
    // With a bias fitted, the views with it removed (and the readout scaled, as the bias
    // was refined with): the final classification and quality report use them.
    let mut corrected: Option<(View, View)> = None;
    if let Some(bo) = &options.gyro_bias {
        let (mut w1, mut w2) = (view1.clone(), view2.clone());
        if let Some(k) = est.readout_scale {
            w1.camera.readout *= k;
            w2.camera.readout *= k;
        }
        if let Some(fit) = refine_gyro_bias(
            &w1,
            &w2,
            working,
            &est.inliers,
            &est.rotation,
            &est.translation,
            bo,
        ) {
            est.rotation = fit.rotation;
            est.translation = fit.translation;
            est.gyro_bias = Some(EstimatedBias {
                bias: fit.bias,
                std: fit.std,
            });
            corrected = Some((unbiased_view(&w1, &fit.bias), unbiased_view(&w2, &fit.bias)));
        }
    }
    corrected
}
