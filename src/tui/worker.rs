//! The background solver: one thread per run, a channel back to the drawing loop.
//!
//! A run gets a [`Job`] whose sink forwards progress and previews (throttled to a few dozen a
//! second; the final figure always arrives) as [`JobMsg`]s tagged with the run's id, and whose
//! cancellation flag the worker keeps. The work is CPU-bound, so there is no async runtime. A
//! panic inside a scene is caught and reported as a failed run.
//!
//! Work that is not a scene (reading a measured file, fitting one of its curves) runs the same
//! way as a [`Task`]: one thread, one [`JobMsg::Task`] back with its [`TaskDone`] or the
//! one-line reason it failed.

use std::collections::HashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::error::Error;
use crate::figure::Figure;
use crate::fit::instrument::{PrepareOptions, fit_curve};
use crate::fit::{FitSettings, fit_figure};
use crate::job::{Job, JobEvent};
use crate::params::ParamValues;
use crate::readers::{ForceCurve, ForceFile, ReadOptions, read_force_file};
use crate::scenes::SceneDyn;
use std::path::PathBuf;

use super::curves::FittedCurve;

/// Name of the worker threads (the panic hook lets their panics through to the worker).
pub const WORKER_THREAD: &str = "adhesion-worker";

/// Shortest interval between two progress messages (the last one always passes).
const PROGRESS_INTERVAL: Duration = Duration::from_millis(30);
/// Shortest interval between two previews (cloning a figure is not free).
const PREVIEW_INTERVAL: Duration = Duration::from_millis(60);

/// How a run ended.
#[derive(Debug)]
pub enum Outcome {
    /// The complete figure.
    Done(Box<Figure>),
    /// Cancelled through the job.
    Cancelled,
    /// The scene returned an error or panicked: the one-line message.
    Failed(String),
}

/// Background work that is not a scene run.
#[derive(Debug, Clone)]
pub enum Task {
    /// Read a force-curve file.
    Open {
        /// The file.
        path: PathBuf,
    },
    /// Prepare and fit one curve of a file, and draw data, fit and residuals.
    Fit {
        /// The file (words errors).
        path: PathBuf,
        /// The curve.
        curve: Box<ForceCurve>,
        /// Position of the curve in its file.
        position: usize,
        /// The fit's settings.
        settings: FitSettings,
    },
    /// Run a scene for a pinned run: its figure with other display parameters (units).
    Convert {
        /// The scene.
        scene: SceneRef,
        /// The pin's parameters with the display parameters of the current run.
        values: ParamValues,
    },
}

/// A scene, printed by its id.
#[derive(Clone, Copy)]
pub struct SceneRef(pub &'static dyn SceneDyn);

impl std::fmt::Debug for SceneRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0.info().id)
    }
}

/// What a [`Task`] produced.
#[derive(Debug)]
pub enum TaskDone {
    /// A file was read.
    Opened {
        /// The file.
        path: PathBuf,
        /// Its curves.
        file: Box<ForceFile>,
    },
    /// A curve was fitted.
    Fitted {
        /// Position of the curve in its file.
        position: usize,
        /// The fit and its figure.
        fitted: Box<FittedCurve>,
    },
    /// A pinned run was recomputed with other display parameters.
    Converted {
        /// The parameters it was computed with.
        values: ParamValues,
        /// Its figure.
        figure: Box<Figure>,
    },
}

impl Task {
    /// Do the work (on a worker thread).
    fn run(self) -> crate::error::Result<TaskDone> {
        let start = Instant::now();
        match self {
            Task::Open { path } => {
                let file = read_force_file(&path, &ReadOptions::default())?;
                if file.curves.is_empty() {
                    return Err(Error::data_file(&path, 0, "the file holds no curve"));
                }
                Ok(TaskDone::Opened {
                    path,
                    file: Box::new(file),
                })
            }
            Task::Fit {
                path,
                curve,
                position,
                settings,
            } => {
                let (data, fit) = fit_curve(&curve, &path, &PrepareOptions::default(), &settings)?;
                let mut figure = fit_figure(&data, &fit.fit)?;
                figure.title = format!("curve {} fitted", curve.index);
                Ok(TaskDone::Fitted {
                    position,
                    fitted: Box::new(FittedCurve {
                        fit,
                        figure,
                        run_time_s: start.elapsed().as_secs_f64(),
                    }),
                })
            }
            Task::Convert { scene, values } => {
                let figure = scene.0.run(&values, &Job::quiet())?;
                Ok(TaskDone::Converted {
                    values,
                    figure: Box::new(figure),
                })
            }
        }
    }
}

/// A message from a run to the drawing loop.
#[derive(Debug)]
pub enum JobMsg {
    /// Fraction done and what is being done.
    Progress {
        /// The run.
        job: u64,
        /// 0 to 1.
        fraction: f64,
        /// Short message.
        message: String,
        /// Seconds since the run started.
        elapsed_s: f64,
    },
    /// The figure as far as it is computed.
    Preview {
        /// The run.
        job: u64,
        /// Partial figure.
        figure: Box<Figure>,
    },
    /// A task ended.
    Task {
        /// The run.
        job: u64,
        /// What it produced, or why it failed (one line).
        outcome: Result<TaskDone, String>,
    },
    /// The run ended.
    Finished {
        /// The run.
        job: u64,
        /// Result.
        outcome: Outcome,
        /// Wall time of the run in seconds.
        run_time_s: f64,
        /// When it ended.
        finished_at: std::time::SystemTime,
    },
}

impl JobMsg {
    /// The id of the run that sent the message.
    pub fn job(&self) -> u64 {
        match self {
            JobMsg::Progress { job, .. }
            | JobMsg::Preview { job, .. }
            | JobMsg::Task { job, .. }
            | JobMsg::Finished { job, .. } => *job,
        }
    }
}

/// Starts runs on background threads and collects their messages.
pub struct Worker {
    tx: Sender<JobMsg>,
    rx: Receiver<JobMsg>,
    flags: HashMap<u64, Arc<AtomicBool>>,
}

impl Default for Worker {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for Worker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Worker").field("runs", &self.flags.len()).finish()
    }
}

impl Worker {
    /// A worker with no runs.
    pub fn new() -> Self {
        let (tx, rx) = channel();
        Self {
            tx,
            rx,
            flags: HashMap::new(),
        }
    }

    /// Run `scene` with `values` on a new thread, reporting as run `job`.
    pub fn start(&mut self, job: u64, scene: &'static dyn SceneDyn, values: ParamValues) {
        let flag = Arc::new(AtomicBool::new(false));
        self.flags.insert(job, Arc::clone(&flag));
        let tx = self.tx.clone();
        let sink_tx = self.tx.clone();
        let last = Mutex::new((None::<Instant>, None::<Instant>));
        let started = Instant::now();
        let sink = move |event: &JobEvent<'_>| {
            let now = Instant::now();
            let Ok(mut last) = last.lock() else { return };
            let due = |t: Option<Instant>, every: Duration| t.is_none_or(|t| now.duration_since(t) >= every);
            let msg = match event {
                JobEvent::Progress { fraction, message } => {
                    if !(due(last.0, PROGRESS_INTERVAL) || *fraction >= 1.0) {
                        return;
                    }
                    last.0 = Some(now);
                    JobMsg::Progress {
                        job,
                        fraction: *fraction,
                        message: (*message).to_string(),
                        elapsed_s: now.duration_since(started).as_secs_f64(),
                    }
                }
                JobEvent::Preview(figure) => {
                    if !due(last.1, PREVIEW_INTERVAL) {
                        return;
                    }
                    last.1 = Some(now);
                    JobMsg::Preview {
                        job,
                        figure: Box::new((*figure).clone()),
                    }
                }
            };
            drop(last);
            // The receiver is gone only when the UI has quit.
            let _ = sink_tx.send(msg);
        };
        let run_job = Job::with_sink(sink).with_cancel_flag(flag);
        let spawned = std::thread::Builder::new().name(WORKER_THREAD.into()).spawn({
            let tx = tx.clone();
            move || {
                let start = Instant::now();
                let result = catch_unwind(AssertUnwindSafe(|| scene.run(&values, &run_job)));
                let outcome = match result {
                    Ok(Ok(figure)) => Outcome::Done(Box::new(figure)),
                    Ok(Err(Error::Cancelled)) => Outcome::Cancelled,
                    Ok(Err(e)) => Outcome::Failed(e.to_string()),
                    Err(payload) => Outcome::Failed(format!(
                        "the computation stopped on an internal error: {}",
                        panic_text(payload.as_ref())
                    )),
                };
                let _ = tx.send(JobMsg::Finished {
                    job,
                    outcome,
                    run_time_s: start.elapsed().as_secs_f64(),
                    finished_at: std::time::SystemTime::now(),
                });
            }
        });
        if let Err(e) = spawned {
            let _ = tx.send(JobMsg::Finished {
                job,
                outcome: Outcome::Failed(format!("cannot start a worker thread: {e}")),
                run_time_s: 0.0,
                finished_at: std::time::SystemTime::now(),
            });
        }
    }

    /// Do `task` on a new thread, reporting as run `job` (a panic is reported as a failure).
    pub fn task(&mut self, job: u64, task: Task) {
        let tx = self.tx.clone();
        let spawned = std::thread::Builder::new().name(WORKER_THREAD.into()).spawn({
            let tx = tx.clone();
            move || {
                let outcome = match catch_unwind(AssertUnwindSafe(|| task.run())) {
                    Ok(Ok(done)) => Ok(done),
                    Ok(Err(e)) => Err(e.to_string()),
                    Err(payload) => Err(format!(
                        "the computation stopped on an internal error: {}",
                        panic_text(payload.as_ref())
                    )),
                };
                let _ = tx.send(JobMsg::Task { job, outcome });
            }
        });
        if let Err(e) = spawned {
            let _ = tx.send(JobMsg::Task {
                job,
                outcome: Err(format!("cannot start a worker thread: {e}")),
            });
        }
    }

    /// Ask run `job` to stop (it stops at its next `job.check()`).
    pub fn cancel(&mut self, job: u64) {
        if let Some(flag) = self.flags.get(&job) {
            flag.store(true, Ordering::Relaxed);
        }
    }

    /// The messages that have arrived, without waiting.
    pub fn drain(&mut self) -> Vec<JobMsg> {
        let msgs: Vec<JobMsg> = self.rx.try_iter().collect();
        self.forget_finished(&msgs);
        msgs
    }

    /// Wait up to `timeout` for the next message.
    pub fn recv_timeout(&mut self, timeout: Duration) -> Option<JobMsg> {
        let msg = self.rx.recv_timeout(timeout).ok()?;
        self.forget_finished(std::slice::from_ref(&msg));
        Some(msg)
    }

    fn forget_finished(&mut self, msgs: &[JobMsg]) {
        for m in msgs {
            if let JobMsg::Finished { job, .. } = m {
                self.flags.remove(job);
            }
        }
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        for flag in self.flags.values() {
            flag.store(true, Ordering::Relaxed);
        }
    }
}

/// The text of a panic payload.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown".into())
}
