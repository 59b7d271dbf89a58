//! Rolling-shutter row model.
//!
//! Row `v` of a view is exposed `v λ` seconds after row 0; throughout, "row `v`" is the
//! line coordinate of a raw pixel along the camera's readout direction
//! ([`Camera::readout_line`]; the image row for the default top-to-bottom readout). The gyro convention is the
//! physical one: `ω` is what a gyroscope reports, rotated into camera axes (x right, y down,
//! z forward; rad/s, bias removed), i.e. the camera's angular velocity in its own frame,
//! `Ṙ_wc = R_wc [ω]×` for the camera-to-world rotation `R_wc`. So the world-to-camera
//! rotation of row `v` is `R_cw(v) = exp(−[v λ ω]×) R_cw(0)`, and the *row rotation*
//!
//! `Ω(v) = R_cw(v) R_cw(0)^T = exp(−[v λ ω]×)`
//!
//! takes row-0 camera coordinates to row-`v` camera coordinates. Camera `c` at row `v` has
//! orientation `Ω_c(v) R_c` (world-to-camera) and centre `C_c + v λ d_c` (`d_c` linear
//! velocity, world frame), so a world point `X` has camera coordinates
//! `Ω_c(v) R_c (X - C_c - v λ d_c)`. A bearing `m` observed at row `v` is brought to the
//! row-0 frame by `Ω(v)^T m = exp([v λ ω]×) m`.
//!
//! Check from first principles: a camera turning about its +y axis (y down) pans right, so a
//! world point straight ahead drifts left in the image as later rows are read: a vertical
//! world line images with `u` decreasing down the image (tested below).

use crate::model::camera::{Camera, CameraError, View};
pub use crate::model::gyro_log::row_rotation;
use nalgebra::{Matrix3, Vector2, Vector3};
use thiserror::Error;

/// Bearing of pixel `(u, v)` expressed in the line-0 camera frame: `Ω(l)^T m` with `m` the
/// pixel's undistorted bearing and `l` its line coordinate ([`Camera::observe`]) and the
/// view's line rotation ([`View::row_rotation`]: from its gyro samples where it has them,
/// else from its constant rate); not rescaled (its third component is generally not 1).
pub fn undistort_bearing(view: &View, u: f64, v: f64) -> Result<Vector3<f64>, CameraError> {
    let o = view.camera.observe([u, v])?;
    Ok(view.row_rotation(o.line).transpose() * o.bearing)
}

/// Pose of a moving rolling-shutter camera at row 0: `rotation = R_c` (world-to-camera),
/// `centre = C_c` (world), linear velocity `velocity = d_c` (m/s, world frame), angular
/// velocity `omega = ω` (rad/s, camera frame, as a gyroscope reports it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RsPose {
    /// World-to-camera rotation at row 0.
    pub rotation: Matrix3<f64>,
    /// Camera centre at row 0, world frame.
    pub centre: Vector3<f64>,
    /// Linear velocity `d`, world frame, m/s.
    pub velocity: Vector3<f64>,
    /// Angular velocity `ω`, camera frame, rad/s.
    pub omega: Vector3<f64>,
}

/// Why a world point has no rolling-shutter projection.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ProjectionError {
    /// At some iterate the point is behind the camera, outside the region where the
    /// camera's distortion is invertible, or the input is not finite.
    #[error(
        "point is behind the camera, outside the camera model's invertible region, or not finite"
    )]
    BehindCamera,
    /// The row fixed-point iteration did not converge within the iteration bound.
    #[error("rolling-shutter row fixed point did not converge in {0} iterations")]
    NotConverged(usize),
}

/// Maximum number of fixed-point iterations used by [`project_rs`].
pub const MAX_ROW_ITERATIONS: usize = 100;

/// Project world point `x` through the pose of the line it lands on: find the line
/// coordinate `l` with `l = line of K d(Ω(l) R (x - C - l λ d))` (`d(·)` the camera's
/// distortion, the line that of the raw distorted pixel, [`Camera::readout_line`]) by
/// fixed-point iteration starting at the principal point's line (tolerance 1e-9 px, at
/// most [`MAX_ROW_ITERATIONS`] iterations). Returns the pixel `(u, v)`; the caller checks
/// whether it lies inside the image.
pub fn project_rs(
    camera: &Camera,
    pose: &RsPose,
    x: &Vector3<f64>,
) -> Result<Vector2<f64>, ProjectionError> {
    let mut v = camera.readout_line(camera.cx, camera.cy);
    for _ in 0..MAX_ROW_ITERATIONS {
        let s = v * camera.readout;
        let r = row_rotation(v, camera.readout, &pose.omega) * pose.rotation;
        let xc = r * (x - pose.centre - pose.velocity * s);
        let p = camera.project(&xc).ok_or(ProjectionError::BehindCamera)?;
        let line = camera.readout_line(p.x, p.y);
        if (line - v).abs() < 1e-9 {
            return Ok(p);
        }
        // Guard against run-away iterates (far outside any image): keep them bounded.
        v = line.clamp(-1e7, 1e7);
    }
    Err(ProjectionError::NotConverged(MAX_ROW_ITERATIONS))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::{essential_from_pose, exp_so3};

    #[test]
    fn projection_is_a_fixed_point_and_undistortion_inverts_it() {
        let cam = Camera::paper();
        let pose1 = RsPose {
            rotation: Matrix3::identity(),
            centre: Vector3::zeros(),
            velocity: Vector3::zeros(),
            omega: Vector3::new(1.0, -2.0, 1.5),
        };
        let r2 = exp_so3(&Vector3::new(0.1, -0.05, 0.2));
        let c2 = Vector3::new(1.0, 0.3, -0.2);
        let pose2 = RsPose {
            rotation: r2,
            centre: c2,
            velocity: Vector3::zeros(),
            omega: Vector3::new(-2.0, 0.5, 0.7),
        };
        let r = r2;
        let t = -r2 * c2;
        let e = essential_from_pose(&r, &t);
        for x in [
            Vector3::new(0.5, 0.3, 6.0),
            Vector3::new(-3.0, 2.0, 20.0),
            Vector3::new(4.0, -1.0, 9.0),
        ] {
            let p1 = project_rs(&cam, &pose1, &x).unwrap();
            let p2 = project_rs(&cam, &pose2, &x).unwrap();
            // Fixed point: the row used equals the row landed on.
            let xc = row_rotation(p1.y, cam.readout, &pose1.omega) * x;
            assert!((cam.project(&xc).unwrap() - p1).norm() < 1e-6);
            let b1 = undistort_bearing(&View::new(cam, pose1.omega), p1.x, p1.y).unwrap();
            let b2 = undistort_bearing(&View::new(cam, pose2.omega), p2.x, p2.y).unwrap();
            assert!((b1.normalize() - x.normalize()).norm() < 1e-9);
            assert!((b2.transpose() * e * b1)[0].abs() < 1e-9);
        }
        assert_eq!(
            project_rs(&cam, &pose1, &Vector3::new(0.0, 0.0, -5.0)),
            Err(ProjectionError::BehindCamera)
        );
        assert!(project_rs(&cam, &pose1, &Vector3::new(f64::NAN, 0.0, 5.0)).is_err());
    }

    /// First principles, independent of `exp_so3` and `row_rotation`: a camera at the origin
    /// turning about its +y axis (y down) at `w` rad/s has camera-to-world rotation
    /// `R_wc(s) = R_y(w s)` (`Ṙ_wc = R_wc [ω]×`), whose forward axis `R_y(θ) e_z =
    /// (sin θ, 0, cos θ)` swings to +x: the camera pans right. A world point straight ahead
    /// then drifts left, so a vertical world line images with `u` decreasing down the image.
    /// The simulator's projection must show exactly that, and undistorting with the gyro
    /// reading `ω = (0, w, 0)` must make the line vertical again.
    #[test]
    fn a_camera_turning_about_plus_y_pans_right() {
        let cam = Camera::paper();
        let w = 1.5;
        let pose = RsPose {
            rotation: Matrix3::identity(),
            centre: Vector3::zeros(),
            velocity: Vector3::zeros(),
            omega: Vector3::new(0.0, w, 0.0),
        };
        let view = View::new(cam, pose.omega);
        let mut last: Option<Vector2<f64>> = None;
        for k in 0..9 {
            let x = Vector3::new(0.3, -4.0 + k as f64, 10.0);
            let p = project_rs(&cam, &pose, &x).unwrap();
            // The camera frame at the time row p.y is read, by hand.
            let th = w * p.y * cam.readout;
            let (sn, cs) = th.sin_cos();
            let r_wc = Matrix3::new(cs, 0.0, sn, 0.0, 1.0, 0.0, -sn, 0.0, cs);
            let xc = r_wc.transpose() * x;
            assert!(
                (cam.fx * xc.x / xc.z + cam.cx - p.x).abs() < 1e-6,
                "row {}",
                p.y
            );
            assert!((cam.fy * xc.y / xc.z + cam.cy - p.y).abs() < 1e-6);
            if let Some(q) = last {
                assert!(p.y > q.y, "points further down image further down");
                assert!(p.x < q.x, "u must decrease down the image: {q} then {p}");
            }
            last = Some(p);
            let b = undistort_bearing(&view, p.x, p.y).unwrap();
            assert!(
                (b.x / b.z - 0.03).abs() < 1e-9,
                "undistorted line is vertical"
            );
        }
        // The reversed turn pans left: u increases down the image.
        let left = RsPose {
            omega: -pose.omega,
            ..pose
        };
        let a = project_rs(&cam, &left, &Vector3::new(0.3, -4.0, 10.0)).unwrap();
        let b = project_rs(&cam, &left, &Vector3::new(0.3, 4.0, 10.0)).unwrap();
        assert!(b.y > a.y && b.x > a.x);
    }
}
