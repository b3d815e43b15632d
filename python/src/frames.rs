//! `fm.frames` and `fm.save_gif`: rollout frames and animated GIFs, drawn by the rasteriser of
//! `fuzzymotiv-pipeline` (`render::frames`, the one `fuzzymotiv replay --gif` uses).
//!
//! A rollout is a trajectory (the columns of `fm.simulate`'s dict: `x`, `y`, `heading`, and
//! optionally `sensors`, `action`, `idle`) or a genome, run here exactly as `fm.simulate` runs
//! it. The room and the robot's body and sensors come from the config.

use std::path::PathBuf;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::simulation::{Action, Pose};
use fuzzymotiv::simulation::{Readings, RobotSpec, Room};
use fuzzymotiv_pipeline::render::frames::animate::{GifWriter, delay_of};
use fuzzymotiv_pipeline::render::frames::scene::{MAX_SIZE, MIN_SIZE, action_named};
use fuzzymotiv_pipeline::render::frames::{
    FrameError, FrameOptions, Track, gif, render, render_last,
};
use numpy::ndarray::{Array3, Array4};
use numpy::{
    IntoPyArray, PyArray3, PyArray4, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray4,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::gym::single_room;
use crate::terms::load_with_terms;
use crate::{config_err, finite, input_err, instance_of, seed_arg};

/// The columns of a trajectory dict, as the Python layer hands them over (float64 arrays, a
/// list of action labels, a list of booleans).
struct Columns {
    poses: Vec<Pose>,
    sensors: Option<Vec<Readings>>,
    actions: Option<Vec<Action>>,
    idle: Option<Vec<bool>>,
}

/// The columns of `d`, its `sensors` (when given) one reading per sensor of `robot`.
fn columns(d: &Bound<'_, PyDict>, robot: &RobotSpec) -> PyResult<Columns> {
    let get = |k: &str| -> PyResult<Vec<f64>> {
        let column = d
            .get_item(k)?
            .ok_or_else(|| input_err(format!("trajectory: no `{k}` column")))?;
        let a: PyReadonlyArray1<'_, f64> = column.extract()?;
        Ok(a.as_array().to_vec())
    };
    let (x, y, heading) = (get("x")?, get("y")?, get("heading")?);
    if y.len() != x.len() || heading.len() != x.len() {
        return Err(input_err(format!(
            "trajectory: x, y and heading have {}, {} and {} values; one per pose in each",
            x.len(),
            y.len(),
            heading.len()
        )));
    }
    let poses = (0..x.len())
        .map(|t| Pose {
            x: x[t],
            y: y[t],
            heading: heading[t],
        })
        .collect();
    let sensors = match d.get_item("sensors")?.filter(|v| !v.is_none()) {
        None => None,
        Some(s) => {
            let a: PyReadonlyArray2<'_, f64> = s.extract()?;
            let rows = a.as_array();
            let n = robot.sensors();
            if rows.ncols() != n {
                return Err(input_err(format!(
                    "trajectory['sensors']: expected a (T, {n}) array of readings (the robot {} has {n} sensors), got shape ({}, {})",
                    robot.name(),
                    rows.nrows(),
                    rows.ncols()
                )));
            }
            Some(
                rows.outer_iter()
                    .map(|r| Readings::from_slice(&r.to_vec()))
                    .collect(),
            )
        }
    };
    let actions = match d.get_item("action")?.filter(|v| !v.is_none()) {
        None => None,
        Some(a) => Some(action_labels(a.extract()?)?),
    };
    let idle = match d.get_item("idle")?.filter(|v| !v.is_none()) {
        None => None,
        Some(i) => Some(i.extract()?),
    };
    Ok(Columns {
        poses,
        sensors,
        actions,
        idle,
    })
}

fn action_labels(labels: Vec<String>) -> PyResult<Vec<Action>> {
    (labels.iter().enumerate())
        .map(|(t, l)| {
            action_named(l).ok_or_else(|| {
                input_err(format!(
                    "trajectory: action[{t}] is `{l}`; expected straight, left30, right30 or turn180"
                ))
            })
        })
        .collect()
}

/// Where a rollout comes from: the config (`fm.run`'s `config` and `overrides`), the room and,
/// for a genome, the base seed.
pub(crate) struct Setting {
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    room: Option<String>,
    seed: Option<u64>,
    /// The names of terms Python supplies, which the config's motivations may weigh (the
    /// `terms=` of the Gymnasium env, `fm.frames` and `fm.save_gif`; nothing is computed from
    /// them here: a rollout's path does not depend on F).
    terms: Vec<String>,
}

impl Setting {
    /// The setting of `fm.frames` / `fm.save_gif`'s arguments (the seed checked).
    fn of_args(
        room: Option<String>,
        seed: Option<Bound<'_, PyAny>>,
        config_path: Option<PathBuf>,
        config_text: Option<String>,
        sets: Vec<String>,
    ) -> PyResult<Setting> {
        Ok(Setting {
            config_path,
            config_text,
            sets,
            room,
            seed: seed.map(|s| seed_arg(&s)).transpose()?,
            terms: Vec::new(),
        })
    }

    /// The experiment of the rollout: the config with its one room (`room`, else the config's
    /// first), and, as `replay` and `fm.simulate`, no recognition or online orientation.
    fn experiment(&self) -> PyResult<Experiment> {
        let path = self.config_path.as_deref();
        let (text, sets) = (self.config_text.as_deref(), &self.sets);
        let loaded =
            load_with_terms(path, text, sets, self.seed, &self.terms).map_err(config_err)?;
        crate::warn_notes(&loaded.notes)?;
        let room = match &self.room {
            Some(r) => r.clone(),
            None => loaded.experiment.room_names()[0].clone(),
        };
        single_room(&loaded, &room, &self.terms)
    }
}

/// `paint` (e.g. [`render`] or [`gif`]) of a trajectory dict or a genome, without the GIL.
fn draw<T: Send>(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    setting: &Setting,
    opts: FrameOptions,
    paint: impl FnOnce(&Room, Track<'_>, FrameOptions) -> Result<T, FrameError> + Send,
) -> PyResult<T> {
    let exp = setting.experiment()?;
    let opts = opts.for_trial(exp.trial_params());
    let room = exp.arenas()[0].room();
    let fail = |e: FrameError| input_err(format!("trajectory: {e}"));
    if let Ok(d) = source.cast::<PyDict>() {
        let c = columns(d, exp.trial_params().robot().spec())?;
        let track = Track {
            poses: &c.poses,
            sensors: c.sensors.as_deref(),
            actions: c.actions.as_deref(),
            idle: c.idle.as_deref(),
        };
        py.detach(|| paint(room, track, opts)).map_err(fail)
    } else {
        let genome: Vec<f64> = source.extract()?;
        finite(
            "genome",
            &genome,
            |k| format!("weight {k}"),
            "expected the network's weights",
        )?;
        let tr = instance_of(py, &exp, &genome)?.trajectory;
        py.detach(|| paint(room, Track::of(&tr), opts))
            .map_err(fail)
    }
}

/// The frame options of `size` and `stride` (any whole numbers: the error names a bad one).
fn options(size: i64, stride: i64) -> PyResult<FrameOptions> {
    // Out-of-range values keep their own number in the message.
    let bad = |name: &str, v: i64| {
        let why = match name {
            "size" => format!("must be a frame side in {MIN_SIZE}..={MAX_SIZE} pixels, got {v}"),
            _ => format!("must be a whole number ≥ 1 (1 = a frame per step), got {v}"),
        };
        input_err(format!("{name}: {why}"))
    };
    let size = u32::try_from(size).map_err(|_| bad("size", size))?;
    let stride = usize::try_from(stride).map_err(|_| bad("stride", stride))?;
    FrameOptions::new(size, stride)
        .map_err(|e| input_err(format!("{}: {e}", e.field().unwrap_or("size"))))
}

/// `(T, H, W, 3)` uint8 frames of a trajectory dict or a genome (`fm.frames`).
#[pyfunction]
#[pyo3(signature = (source, room=None, size=320, stride=1, seed=None, config_path=None, config_text=None, sets=Vec::new(), terms=Vec::new()))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn frames<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    room: Option<String>,
    size: i64,
    stride: i64,
    seed: Option<Bound<'py, PyAny>>,
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    terms: Vec<String>,
) -> PyResult<Bound<'py, PyArray4<u8>>> {
    let mut setting = Setting::of_args(room, seed, config_path, config_text, sets)?;
    setting.terms = terms;
    let f = draw(py, source, &setting, options(size, stride)?, render)?;
    let (h, w) = (f.height as usize, f.width as usize);
    let a = Array4::from_shape_vec((f.len(), h, w, 3), f.rgb).expect("T × H × W × 3");
    Ok(a.into_pyarray(py))
}

/// The `(H, W, 3)` uint8 frame of a trajectory dict's last pose, drawn alone (the Gymnasium
/// env's `render()`: one frame per call, with the env's config and overrides).
#[pyfunction]
#[pyo3(signature = (source, room=None, size=320, config_path=None, config_text=None, sets=Vec::new(), terms=Vec::new()))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn last_frame<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyDict>,
    room: Option<String>,
    size: i64,
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    terms: Vec<String>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let mut setting = Setting::of_args(room, None, config_path, config_text, sets)?;
    setting.terms = terms;
    let f = draw(
        py,
        source.as_any(),
        &setting,
        options(size, 1)?,
        render_last,
    )?;
    let (h, w) = (f.height as usize, f.width as usize);
    let a = Array3::from_shape_vec((h, w, 3), f.rgb).expect("H × W × 3");
    Ok(a.into_pyarray(py))
}

/// The GIF of `(T, H, W, 3)` uint8 frames.
fn gif_of_array(py: Python<'_>, a: &PyReadonlyArray4<'_, u8>, delay: u16) -> PyResult<Vec<u8>> {
    let shape = a.shape().to_vec();
    if shape[..3].contains(&0) || shape[3] != 3 {
        return Err(input_err(format!(
            "frames: an array of shape {shape:?}; expected (T, H, W, 3) with T, H, W ≥ 1 (RGB, uint8)"
        )));
    }
    let view = a.as_array();
    let flat: Vec<u8> = view.iter().copied().collect();
    let (w, h) = (shape[2] as u32, shape[1] as u32);
    let n = shape[1] * shape[2] * 3;
    py.detach(|| {
        let mut writer = GifWriter::new(w, h, delay)?;
        for frame in flat.chunks_exact(n) {
            writer.push(frame)?;
        }
        writer.finish()
    })
    .map_err(|e| input_err(format!("frames: {e}")))
}

/// Writes the animated GIF of frames (an array) or of a rollout to `path` through the output
/// guard (`fm.save_gif`); returns the number of frames.
#[pyfunction]
#[pyo3(signature = (source, path, fps=25.0, force=false, room=None, size=320, stride=1, seed=None, config_path=None, config_text=None, sets=Vec::new(), terms=Vec::new()))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn save_gif<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    path: PathBuf,
    fps: f64,
    force: bool,
    room: Option<String>,
    size: i64,
    stride: i64,
    seed: Option<Bound<'py, PyAny>>,
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    terms: Vec<String>,
) -> PyResult<usize> {
    let delay = delay_of(fps).map_err(|e| input_err(format!("fps: {e}")))?;
    let (bytes, count) = if let Ok(a) = source.extract::<PyReadonlyArray4<'_, u8>>() {
        (gif_of_array(py, &a, delay)?, a.shape()[0])
    } else {
        let mut setting = Setting::of_args(room, seed, config_path, config_text, sets)?;
        setting.terms = terms;
        // Drawn and encoded a frame at a time (as `replay --gif`): any length fits in memory.
        draw(
            py,
            source,
            &setting,
            options(size, stride)?,
            |room, track, opts| {
                let count = opts.frame_poses(track.poses.len()).len();
                gif(room, track, opts, delay).map(|bytes| (bytes, count))
            },
        )?
    };
    crate::write_guarded(path, bytes, force)?;
    Ok(count)
}
