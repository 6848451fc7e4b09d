//! Sweeps: scenes made of many independent runs (a contour over two parameters, an average over
//! random surfaces), split into points that can be computed anywhere and in any order.
//!
//! A sweep scene enumerates its points deterministically from its parameters: the id of a point
//! is its index in [`Sweep::points`], and everything a point computes (its parameters, the seeds
//! of its random surfaces) follows from the scene's parameters and the id alone, never from the
//! process, the shard or the thread that computes it. [`Sweep::run_point`] computes one point
//! into a flat vector of numbers, and [`Sweep::assemble`] builds the figure from the vectors of
//! all points, in id order. An unsharded run ([`run`]) is exactly `points -> run_point (rayon)
//! -> assemble`, so a figure merged from shards computed in many processes is the same figure,
//! bit for bit: both go through the one `assemble`.
//!
//! The headless exporter stores each point's vector in a file of its own (`--shard I/N`, a job
//! array on a cluster) and assembles them later (`--merge`); see `crate::headless`.
//!
//! While a run goes on, a listener for previews (the terminal UI) gets the figure as far as it
//! is computed: the finished points assembled with the others missing
//! ([`Sweep::assemble_partial`]), at most every [`PREVIEW_INTERVAL`], marked "partial: k of n
//! points" and without the results and findings, which need every point.

use std::any::Any;
use std::marker::PhantomData;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::{Registered, Scene, SceneDyn, SceneInfo, memory_limit};
use crate::error::{Error, Result};
use crate::figure::Figure;
use crate::job::Job;
use crate::params::{ParamSpec, ParamValues};

/// Shortest interval between two previews of a sweep's partial figure; longer when assembling
/// takes long (at most a fifth of the time goes to previews).
pub const PREVIEW_INTERVAL: Duration = Duration::from_millis(200);

/// A scene that is a sweep of independent points.
pub trait Sweep: Scene {
    /// What the points computed in one process share, built once per process before its first
    /// point (the unit surfaces of the samples, the spectral moments of a substrate); `()` when
    /// the points share nothing. Building it must not depend on which points follow.
    type Context: Sync + 'static;

    /// The number of values every point gives when it does not depend on the parameters (one
    /// by default); a sweep whose points' lengths do overrides [`Sweep::point_len`] instead.
    const POINT_LEN: usize = 1;

    /// Build the shared context. The default builds the empty context `()`; a sweep with
    /// another context must build it here (the default refuses it with an error).
    ///
    /// # Errors
    /// Model errors, cancellation.
    fn context(_params: &Self::Params, _job: &Job) -> Result<Self::Context> {
        let empty: Box<dyn Any> = Box::new(());
        empty
            .downcast::<Self::Context>()
            .map(|c| *c)
            .map_err(|_| Error::Unresolvable {
                model: "sweep",
                reason: format!("scene {} has a context but does not build it", Self::ID),
            })
    }

    /// The points, in id order, each as a short label of its parameters ("n = 7, σ_rms/σ = 31.6").
    fn points(params: &Self::Params) -> Vec<String>;

    /// Compute point `id` (an index into [`Sweep::points`]).
    ///
    /// # Errors
    /// Model errors, cancellation.
    fn run_point(params: &Self::Params, context: &Self::Context, id: usize, job: &Job) -> Result<Vec<f64>>;

    /// Build the figure from the results of all points, in id order.
    ///
    /// # Errors
    /// Model errors of the parts of the figure that are not points.
    fn assemble(params: &Self::Params, points: &[Vec<f64>], job: &Job) -> Result<Figure>;

    /// Build the figure of a run that is not complete from the points finished so far (`None`
    /// for the others), for a preview. By default the missing points are NaN (of
    /// [`Sweep::point_len`]) and go through [`Sweep::assemble`]; the caller then drops the
    /// non-finite points, the results and the notes, and marks the figure partial.
    ///
    /// # Errors
    /// Those of the assembly (the preview is then skipped).
    fn assemble_partial(params: &Self::Params, points: &[Option<Vec<f64>>], job: &Job) -> Result<Figure> {
        let filled: Vec<Vec<f64>> = points
            .iter()
            .enumerate()
            .map(|(id, v)| {
                v.clone()
                    .unwrap_or_else(|| vec![f64::NAN; Self::point_len(params, id)])
            })
            .collect();
        Self::assemble(params, &filled, job)
    }

    /// The number of values [`Sweep::run_point`] gives for point `id`: a stored point of
    /// another length is refused by a merge. By default [`Sweep::POINT_LEN`].
    fn point_len(_params: &Self::Params, _id: usize) -> usize {
        Self::POINT_LEN
    }

    /// Whether a point's values may be NaN (a map cell where the quantity is not defined);
    /// otherwise a merge refuses a stored point with a non-finite value. Infinities are always
    /// refused.
    const NAN_VALUES: bool = false;

    /// The shares of an unsharded run's time spent building the context, computing the points
    /// and assembling the figure (any unit), for its progress: the gauge crosses each part in
    /// its share. By default nearly all of it is the points.
    fn progress_shares(_params: &Self::Params) -> [f64; 3] {
        [0.0, 0.98, 0.02]
    }

    /// The relative cost of each point, in id order, for its part of the points' share of the
    /// progress; by default all points cost alike.
    fn point_weights(params: &Self::Params) -> Vec<f64> {
        vec![1.0; Self::points(params).len()]
    }
}

/// Run every point of a sweep in parallel (rayon) and assemble the figure: the body of
/// [`Scene::run`] of every sweep scene. Progress: the context, the points and the assembly
/// each cross their [`Sweep::progress_shares`] of the gauge; each point has a part of the
/// points' share by its [`Sweep::point_weights`], which its own steps (a cycle's) fill as it
/// runs.
///
/// # Errors
/// The first error of a point, errors of the assembly.
pub fn run<S: Sweep>(params: &S::Params, job: &Job) -> Result<Figure> {
    let [context_share, points_share, assembly_share] = S::progress_shares(params);
    let total = context_share + points_share + assembly_share;
    let (a, b) = (context_share / total, (context_share + points_share) / total);
    let context = S::context(params, &job.part(0.0, a))?;
    let ids: Vec<usize> = (0..S::points(params).len()).collect();
    let mut weights = S::point_weights(params);
    weights.resize(ids.len(), 1.0);
    let compute = |finished: &(dyn Fn(usize, &[f64]) + Sync)| {
        job.map_parallel_parts(&ids, &weights, "points", (a, b), |&id, part| {
            part.check()?;
            let values = S::run_point(params, &context, id, part)?;
            finished(id, &values);
            Ok(values)
        })
    };
    let points = if job.wants_preview() {
        Previews::new(ids.len()).run::<S>(params, job, compute)?
    } else {
        compute(&|_, _| {})?
    };
    S::assemble(params, &points, &job.part(b, 1.0))
}

/// The points of a running sweep finished so far, for its previews.
struct Previews {
    state: Mutex<(Vec<Option<Vec<f64>>>, usize)>,
}

impl Previews {
    fn new(n: usize) -> Self {
        Self {
            state: Mutex::new((vec![None; n], 0)),
        }
    }

    /// The points finished so far and their count.
    fn snapshot(&self) -> Option<(Vec<Option<Vec<f64>>>, usize)> {
        self.state.lock().ok().map(|s| (*s).clone())
    }

    /// Run `compute` (the points, in parallel), told of each finished point: the worker that
    /// finishes a point sends a preview of the points finished so far when
    /// [`PREVIEW_INTERVAL`] (or four times the last assembly) has passed and no other worker
    /// is assembling one (the others go on computing). The previews share the run's
    /// cancellation but not its progress; the last point sends none (the complete figure
    /// follows). A cancelled run sends the points finished since the last preview, if a
    /// partial assembly was seen to be quick, so the figure it keeps shows all it computed.
    ///
    /// # Errors
    /// Those of `compute`.
    fn run<S: Sweep>(
        &self,
        params: &S::Params,
        job: &Job,
        compute: impl FnOnce(&(dyn Fn(usize, &[f64]) + Sync)) -> Result<Vec<Vec<f64>>>,
    ) -> Result<Vec<Vec<f64>>> {
        let silent = Job::quiet().with_cancel_flag(job.cancel_flag());
        // The points shown by the last preview, when the next is due, and the last assembly's
        // time.
        let schedule = Mutex::new((0usize, Instant::now(), None::<Duration>));
        // Assemble the points finished so far with `with` (a job without progress) and send
        // them; how long the assembly took.
        let send = |shown: &mut usize, with: &Job| {
            let (points, done) = self.snapshot()?;
            let start = Instant::now();
            if let Some(figure) = partial_figure::<S>(params, &points, done, with) {
                job.preview(&figure);
            }
            *shown = done;
            Some(start.elapsed())
        };
        let outcome = compute(&|id, values| {
            let Ok((done, n)) = self.state.lock().map(|mut s| {
                s.0[id] = Some(values.to_vec());
                s.1 += 1;
                (s.1, s.0.len())
            }) else {
                return;
            };
            if done == n {
                return;
            }
            if let Ok(mut sch) = schedule.try_lock()
                && done > sch.0
                && Instant::now() >= sch.1
                && let Some(c) = send(&mut sch.0, &silent)
            {
                sch.2 = Some(c);
                sch.1 = Instant::now() + PREVIEW_INTERVAL.max(4 * c);
            }
        });
        let (mut shown, _, cost) = schedule.into_inner().unwrap_or((0, Instant::now(), None));
        if matches!(outcome, Err(Error::Cancelled)) && cost.is_some_and(|c| c < Duration::from_millis(100)) {
            let done = self.state.lock().map_or(0, |s| s.1);
            if done > shown {
                send(&mut shown, &Job::quiet());
            }
        }
        outcome
    }
}

/// The partial figure of `done` finished points ([`Sweep::assemble_partial`]) with what needs
/// every point removed: the non-finite points of the lines (what is missing is absent), the
/// results, the notes and the panels' remarks (findings); a note "partial: k of n points"
/// instead. `None` when the assembly fails or panics: a preview never stops a run.
fn partial_figure<S: Sweep>(
    params: &S::Params,
    points: &[Option<Vec<f64>>],
    done: usize,
    job: &Job,
) -> Option<Figure> {
    let assembled = catch_unwind(AssertUnwindSafe(|| S::assemble_partial(params, points, job)));
    let mut fig = assembled.ok()?.ok()?;
    fig.results.clear();
    fig.notes.clear();
    for panel in &mut fig.panels {
        panel.notes.clear();
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        for series in &mut panel.series {
            series.points.retain(finite);
        }
        for region in &mut panel.regions {
            region.points.retain(finite);
        }
        panel.markers.retain(|m| m.x.is_finite() && m.y.is_finite());
        panel.arrows.retain(|a| finite(&a.from) && finite(&a.to));
    }
    fig.note(partial_note(done, points.len()));
    Some(fig)
}

/// The note of a sweep's partial figure.
pub fn partial_note(done: usize, total: usize) -> String {
    format!("partial: {done} of {total} points")
}

/// The computation of one point, handed to the caller of [`SweepDyn::run_points`] to run and
/// time.
pub type PointTask<'a> = &'a (dyn Fn() -> Result<Vec<f64>> + Sync);

/// Object-safe view of a [`Sweep`], used by the headless exporter to run some of the points
/// and to assemble stored points.
pub trait SweepDyn: Sync {
    /// Validate the values; the labels of the points in id order.
    ///
    /// # Errors
    /// Invalid values.
    fn points(&self, values: &ParamValues) -> Result<Vec<String>>;

    /// Compute the points `ids` in parallel (rayon): for each, `visit(id, task)` is called on a
    /// worker thread, and `task()` computes the point. The context is built once, and only if
    /// `ids` is not empty.
    ///
    /// # Errors
    /// Invalid values, the context's errors, the first error `visit` returns.
    fn run_points(
        &self,
        values: &ParamValues,
        ids: &[usize],
        job: &Job,
        visit: &(dyn Fn(usize, PointTask<'_>) -> Result<()> + Sync),
    ) -> Result<()>;

    /// Validate the values and build the figure from the results of all points, in id order.
    ///
    /// # Errors
    /// Invalid values, errors of the assembly; points of the wrong length.
    fn assemble(&self, values: &ParamValues, points: &[Vec<f64>], job: &Job) -> Result<Figure>;

    /// The number of values of point `id` ([`Sweep::point_len`]).
    ///
    /// # Errors
    /// Invalid values.
    fn point_len(&self, values: &ParamValues, id: usize) -> Result<usize>;

    /// Whether a point's values may be NaN ([`Sweep::NAN_VALUES`]).
    fn nan_values(&self) -> bool;
}

/// Adapter from a typed [`Sweep`] scene to [`SceneDyn`] (with [`SceneDyn::sweep`]) and
/// [`SweepDyn`]; list a sweep scene as `&Swept::<S>::NEW` in its chapter's `SCENES`.
pub struct Swept<S>(PhantomData<S>);

impl<S> Swept<S> {
    /// The adapter (a zero-sized constant).
    pub const NEW: Self = Swept(PhantomData);
}

impl<S: Sweep> Swept<S> {
    fn params(values: &ParamValues) -> Result<S::Params> {
        let p: S::Params = values.to_params()?;
        Registered::<S>::NEW.validate(values)?;
        Ok(p)
    }
}

impl<S: Sweep> SceneDyn for Swept<S> {
    fn info(&self) -> SceneInfo {
        Registered::<S>::NEW.info()
    }

    fn specs(&self) -> Vec<ParamSpec> {
        Registered::<S>::NEW.specs()
    }

    fn defaults(&self) -> ParamValues {
        Registered::<S>::NEW.defaults()
    }

    fn validate(&self, values: &ParamValues) -> Result<()> {
        Registered::<S>::NEW.validate(values)
    }

    fn quick(&self, values: &ParamValues) -> Result<ParamValues> {
        Registered::<S>::NEW.quick(values)
    }

    fn run(&self, values: &ParamValues, job: &Job) -> Result<Figure> {
        Registered::<S>::NEW.run(values, job)
    }

    fn sweep(&self) -> Option<&dyn SweepDyn> {
        Some(self)
    }
}

impl<S: Sweep> SweepDyn for Swept<S> {
    fn point_len(&self, values: &ParamValues, id: usize) -> Result<usize> {
        Ok(S::point_len(&Self::params(values)?, id))
    }

    fn nan_values(&self) -> bool {
        S::NAN_VALUES
    }

    fn points(&self, values: &ParamValues) -> Result<Vec<String>> {
        Ok(S::points(&Self::params(values)?))
    }

    fn run_points(
        &self,
        values: &ParamValues,
        ids: &[usize],
        job: &Job,
        visit: &(dyn Fn(usize, PointTask<'_>) -> Result<()> + Sync),
    ) -> Result<()> {
        let p = Self::params(values)?;
        if ids.is_empty() {
            return Ok(());
        }
        if let Some(m) = S::memory_estimate(&p) {
            m.check(memory_limit())?;
        }
        let baseline = self.baseline(values);
        let attribute = |e| crate::scenes::attribute_failure(S::ID, values, &baseline, e);
        let context = S::context(&p, job).map_err(attribute)?;
        ids.par_iter().try_for_each(|&id| {
            job.check()?;
            visit(id, &|| S::run_point(&p, &context, id, job).map_err(attribute))
        })
    }

    fn assemble(&self, values: &ParamValues, points: &[Vec<f64>], job: &Job) -> Result<Figure> {
        let p = Self::params(values)?;
        let labels = S::points(&p);
        if points.len() != labels.len() {
            return Err(crate::error::Error::Unresolvable {
                model: "sweep",
                reason: format!("{} points given, the sweep has {}", points.len(), labels.len()),
            });
        }
        if let Some((id, v)) = points
            .iter()
            .enumerate()
            .find(|(id, v)| v.len() != S::point_len(&p, *id))
        {
            return Err(crate::error::Error::Unresolvable {
                model: "sweep",
                reason: format!("point {id} has {} values, not {}", v.len(), S::point_len(&p, id)),
            });
        }
        let mut fig = crate::scenes::finish(
            S::ID,
            values,
            &self.baseline(values),
            S::assemble(&p, points, job),
        )?;
        if let Some(coarser) = crate::scenes::quick_form(self, values) {
            fig.mark_quick(&coarser);
        }
        Ok(fig)
    }
}
