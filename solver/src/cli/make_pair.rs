//! `rspose make-pair`: a pair file from a real recording — a gyro log (CSV), frame
//! timestamps, a rig calibration and the matches of two frames.

use super::{check_output_dir, CliError};
use rspose::data::kalibr::{parse_kalibr, CalibrationImportError, ImportedRig};
use rspose::data::opencv_calibration::parse_opencv_calibration;
use rspose::data::pair_file::{matrix_from_rows, GyroLogSpec, Match, PairFile, PairFileError};
use rspose::model::camera::Camera;
use rspose::model::gyro_log::{
    parse_gyro_csv, plausible_rate, GyroLog, GyroLogError, MAX_ANGULAR_VELOCITY, MAX_SAMPLE_GAP,
};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Options of `rspose make-pair`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Rig calibration (JSON): `camera` (as in a pair file), `camera_from_gyro` (3x3 rows,
    /// ω_cam = M ω_gyro; default identity), `time_offset` (s, gyro time of a frame's row 0
    /// minus its frame time; default 0), `gyro_time_column` (0-based column of the time in
    /// the gyro CSV; default 3, for `gx,gy,gz,t`), `gyro_bias` (the gyro's known constant
    /// bias in its own axes, rad/s, subtracted from every sample; default none). One of
    /// --calibration, --kalibr and --opencv-calibration is required.
    #[arg(long)]
    calibration: Option<PathBuf>,
    /// Rig calibration from Kalibr's camera-IMU calibration (`camchain-imucam.yaml`): the
    /// camera, `camera_from_gyro` (rotation of `T_cam_imu`), `time_offset`
    /// (`timeshift_cam_imu`) and the readout time per line (`line_delay`, else --readout).
    #[arg(long)]
    kalibr: Option<PathBuf>,
    /// The camera of the Kalibr file to read.
    #[arg(long, default_value = "cam0", requires = "kalibr")]
    cam: String,
    /// The camera from an OpenCV calibration (`cv::FileStorage` YAML or ROS camera_info),
    /// with --readout; the gyro's axes are taken as the camera's and the time offset as 0.
    #[arg(long = "opencv-calibration")]
    opencv_calibration: Option<PathBuf>,
    /// Readout time per line, s, for --kalibr (over the file's `line_delay`) and
    /// --opencv-calibration (required there).
    #[arg(long)]
    readout: Option<f64>,
    /// Gyro log: one sample per line, four numbers separated by commas or spaces (the time
    /// in seconds and the rates in rad/s in the gyro's axes); `#` comments and a header line
    /// allowed.
    #[arg(long)]
    gyro: PathBuf,
    /// Frame timestamps, seconds, one per line: frame N is line N.
    #[arg(long = "frame-times")]
    frame_times: PathBuf,
    /// Matches (JSON): an object with `matches` ([[[u1, v1], [u2, v2]], ...], pixels) and
    /// optionally `frames` ([N1, N2]), as written by `tools/match_frames.py`.
    #[arg(long)]
    matches: PathBuf,
    /// Frame numbers of image 1 and image 2 (default: the matches file's `frames`).
    #[arg(long, num_args = 2, value_names = ["N1", "N2"])]
    frames: Option<Vec<usize>>,
    /// Samples kept around the two frames' readouts, seconds (room for calibrating the
    /// time offset).
    #[arg(long, default_value_t = 0.03)]
    margin: f64,
    /// Output pair file (JSON, one line).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
}

/// A camera-gyro rig's calibration file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigCalibration {
    /// The camera.
    pub camera: Camera,
    /// `ω_cam = M ω_gyro`, row-major rows.
    #[serde(default = "identity")]
    pub camera_from_gyro: [[f64; 3]; 3],
    /// Gyro time of a frame's row 0 minus its frame time, s.
    #[serde(default)]
    pub time_offset: f64,
    /// 0-based column of the time in the gyro CSV.
    #[serde(default = "default_time_column")]
    pub gyro_time_column: usize,
    /// A known constant bias of the gyro, in its own axes (rad/s), written into the pair's
    /// `gyro_log.gyro_bias` (subtracted from every sample before `camera_from_gyro`).
    #[serde(default)]
    pub gyro_bias: Option<[f64; 3]>,
}

fn identity() -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
}

fn default_time_column() -> usize {
    3
}

#[derive(Debug, Deserialize)]
struct MatchesFile {
    matches: Vec<Match>,
    #[serde(default)]
    frames: Option<[usize; 2]>,
}

/// The largest input file `make-pair` reads, bytes (256 MiB): hours of a 200 Hz gyro log.
/// The files are read whole, so a larger one would exhaust the memory of a small machine;
/// a longer recording is cut around the frames first.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// Reads a text input of at most [`MAX_INPUT_BYTES`] (devices and pipes included: the read
/// stops one byte past the limit).
fn read(path: &Path) -> Result<String, CliError> {
    use std::io::Read;
    let io = |e: std::io::Error| CliError::input(format!("{}: {e}", path.display()));
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(io)?
        .take(MAX_INPUT_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(io)?;
    if text.len() as u64 > MAX_INPUT_BYTES {
        return Err(CliError::input(format!(
            "{}: larger than the {} MiB make-pair reads (cut the recording around the frames)",
            path.display(),
            MAX_INPUT_BYTES >> 20
        )));
    }
    Ok(text)
}

fn parse_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, CliError> {
    serde_json::from_str(&read(path)?)
        .map_err(|e| CliError::input(format!("{}: {e}", path.display())))
}

/// The rig calibration the arguments name (JSON, Kalibr or OpenCV) and its file; errors
/// name the file and the key.
fn rig_calibration(a: &Args) -> Result<(RigCalibration, PathBuf), CliError> {
    let given = [&a.calibration, &a.kalibr, &a.opencv_calibration]
        .iter()
        .filter(|p| p.is_some())
        .count();
    if given != 1 {
        return Err(CliError::input(
            "give the rig's calibration with exactly one of --calibration, --kalibr and --opencv-calibration",
        ));
    }
    if a.readout.is_some() && a.calibration.is_some() {
        return Err(CliError::input(
            "--readout is for --kalibr and --opencv-calibration; a JSON calibration has its camera's `readout`",
        ));
    }
    if let Some(r) = a.readout {
        if !(r.is_finite() && r > 0.0) {
            return Err(CliError::input(
                "--readout must be a finite positive time per line, s",
            ));
        }
    }
    if let Some(path) = &a.calibration {
        return Ok((load_calibration(path)?, path.clone()));
    }
    let imported = |path: &PathBuf, rig: Result<ImportedRig, CalibrationImportError>| {
        let rig = rig.map_err(|e| CliError::input(format!("{}: {e}", path.display())))?;
        Ok((
            RigCalibration {
                camera: rig.camera,
                camera_from_gyro: rig.camera_from_gyro,
                time_offset: rig.time_offset,
                gyro_time_column: default_time_column(),
                gyro_bias: None,
            },
            path.clone(),
        ))
    };
    if let Some(path) = &a.kalibr {
        return imported(path, parse_kalibr(&read(path)?, &a.cam, a.readout));
    }
    let Some(path) = &a.opencv_calibration else {
        return Err(CliError::input("no calibration given"));
    };
    let Some(readout) = a.readout else {
        return Err(CliError::input(format!(
            "{}: an OpenCV calibration has no readout time; give it with --readout (s per line)",
            path.display()
        )));
    };
    imported(
        path,
        parse_opencv_calibration(&read(path)?, readout).map(|camera| ImportedRig {
            camera,
            camera_from_gyro: identity(),
            time_offset: 0.0,
        }),
    )
}

/// Reads a rig calibration and checks it (camera parameters, rotation, time column).
pub fn load_calibration(path: &Path) -> Result<RigCalibration, CliError> {
    let c: RigCalibration = parse_json(path)?;
    let bad = |what: String| CliError::input(format!("{}: {what}", path.display()));
    c.camera.validate().map_err(|e| bad(e.to_string()))?;
    if c.gyro_time_column > 3 {
        return Err(bad("gyro_time_column must be 0..=3".into()));
    }
    if !c.time_offset.is_finite() {
        return Err(bad("time_offset must be finite".into()));
    }
    if let Some(b) = c.gyro_bias {
        if !plausible_rate(&nalgebra::Vector3::from(b)) {
            return Err(bad(format!(
                "gyro_bias must be finite and at most {MAX_ANGULAR_VELOCITY} rad/s"
            )));
        }
    }
    GyroLog::new(
        &[[0.0; 4], [1.0; 4]],
        &matrix_from_rows(&c.camera_from_gyro),
    )
    .map_err(|_| bad("camera_from_gyro is not a rotation matrix".into()))?;
    Ok(c)
}

/// A gyro CSV's samples, each one's line, and the file's name for messages.
pub struct GyroCsv {
    /// The file.
    pub path: PathBuf,
    /// Samples `[t, ωx, ωy, ωz]` (gyro axes).
    pub samples: Vec<[f64; 4]>,
    /// 1-based line of each sample.
    pub lines: Vec<usize>,
}

impl GyroCsv {
    /// A gyro-log error about sample `first + index` as a message naming the file and line.
    pub fn error(&self, first: usize, e: &GyroLogError) -> CliError {
        let index = match e {
            GyroLogError::NonFinite { index }
            | GyroLogError::Implausible { index }
            | GyroLogError::DuplicateTime { index, .. }
            | GyroLogError::Unsorted { index, .. }
            | GyroLogError::Gap { index, .. } => Some(first + index),
            _ => None,
        };
        match index.and_then(|i| self.lines.get(i)) {
            Some(line) => CliError::input(format!("{}:{line}: {e}", self.path.display())),
            None => CliError::input(format!("{}: {e}", self.path.display())),
        }
    }

    /// Index of the first sample at or after time `t`.
    pub fn index_at(&self, t: f64) -> usize {
        self.samples.partition_point(|s| s[0] < t)
    }
}

/// Reads and checks a whole gyro CSV: numbers, sorted distinct times, finite values (gaps
/// are checked where a pair needs the samples). Errors name the file and line.
pub fn load_gyro_csv(
    path: &Path,
    calibration: &RigCalibration,
) -> Result<(GyroCsv, GyroLog), CliError> {
    let text = read(path)?;
    let at =
        |line: usize, what: String| CliError::input(format!("{}:{line}: {what}", path.display()));
    let parsed =
        parse_gyro_csv(&text, calibration.gyro_time_column).map_err(|e| at(e.line, e.reason))?;
    let csv = GyroCsv {
        path: path.to_path_buf(),
        samples: parsed.samples,
        lines: parsed.lines,
    };
    let log = GyroLog::new(
        &csv.samples,
        &matrix_from_rows(&calibration.camera_from_gyro),
    )
    .map_err(|e| csv.error(0, &e))?;
    Ok((csv, log))
}

/// Reads frame timestamps (one per line; frame N is line N). Errors name the line.
pub fn load_frame_times(path: &Path) -> Result<Vec<f64>, CliError> {
    read(path)?
        .lines()
        .enumerate()
        .map(|(i, l)| {
            l.trim()
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite())
                .ok_or_else(|| {
                    CliError::input(format!(
                        "{}:{}: not a finite time in seconds: `{}`",
                        path.display(),
                        i + 1,
                        l.trim()
                    ))
                })
        })
        .collect()
}

pub fn run(a: Args) -> Result<(), CliError> {
    check_output_dir(&a.output)?;
    let (calibration, calibration_path) = rig_calibration(&a)?;
    let camera = calibration.camera;
    let duration = camera.frame_readout();
    let (csv, full_log) = load_gyro_csv(&a.gyro, &calibration)?;
    let times = load_frame_times(&a.frame_times)?;
    let m: MatchesFile = parse_json(&a.matches)?;
    // A pair without matches has nothing to estimate; refuse it here rather than write it.
    if m.matches.is_empty() {
        return Err(CliError::input(format!(
            "{}: `matches` is empty (a pair needs at least one match)",
            a.matches.display()
        )));
    }
    let frames = match (&a.frames, m.frames) {
        (Some(f), _) => [f[0], f[1]],
        (None, Some(f)) => f,
        (None, None) => {
            return Err(CliError::input(format!(
                "{}: no `frames` in the matches file; give --frames N1 N2",
                a.matches.display()
            )))
        }
    };
    let frame_time = |n: usize| -> Result<f64, CliError> {
        (n >= 1)
            .then(|| times.get(n - 1).copied())
            .flatten()
            .ok_or_else(|| {
                CliError::input(format!(
                    "{}: no line {n} for frame {n} ({} lines)",
                    a.frame_times.display(),
                    times.len()
                ))
            })
    };
    let frame_times = [frame_time(frames[0])?, frame_time(frames[1])?];
    for (k, t) in frame_times.iter().enumerate() {
        let t0 = t + calibration.time_offset;
        full_log
            .check_covers(t0, t0 + duration, &format!("frame {}'s readout", frames[k]))
            .map_err(|e| csv.error(0, &e))?;
    }
    if !(a.margin.is_finite() && a.margin >= 0.0) {
        return Err(CliError::input("--margin must be finite and non-negative"));
    }
    let mut spec = GyroLogSpec::excerpt(
        &csv.samples,
        calibration.camera_from_gyro,
        calibration.time_offset,
        frame_times,
        duration,
        a.margin,
    );
    spec.gyro_bias = calibration.gyro_bias;
    let mut pair = PairFile {
        cameras: [camera; 2],
        gyro: None,
        gyro_bias: None,
        gyro_log: Some(spec),
        gravity: None,
        matches: m.matches,
        ground_truth: None,
    };
    // Gaps, checked on the samples the pair uses (a long log may pause elsewhere).
    if let Some(spec) = &pair.gyro_log {
        let first = spec.samples.first().map_or(0, |s| csv.index_at(s[0]));
        spec.log()
            .and_then(|log| log.check_gaps(MAX_SAMPLE_GAP))
            .map_err(|e| csv.error(first, &e))?;
    }
    let (v1, v2) = pair
        .views()
        .map_err(|e| CliError::input(format!("{}: {e}", a.gyro.display())))?;
    // The mean rates beside the samples, for readers that take one rate per frame.
    pair.gyro = Some([v1.omega.into(), v2.omega.into()]);
    let inputs = [
        calibration_path.as_path(),
        a.gyro.as_path(),
        a.frame_times.as_path(),
        a.matches.as_path(),
    ];
    pair.save_output(&a.output, true, &inputs)
        .map_err(|e| match e {
            // Writing failed: the message names the output.
            PairFileError::Io { .. } => CliError::input(e.to_string()),
            // The pair is invalid: its matches are what the user gave.
            e => CliError::input(format!("{}: {e}", a.matches.display())),
        })?;
    eprintln!(
        "wrote {} (frames {} and {}, {} matches, {} gyro samples)",
        a.output.display(),
        frames[0],
        frames[1],
        pair.matches.len(),
        pair.gyro_log.as_ref().map_or(0, |s| s.samples.len())
    );
    Ok(())
}
