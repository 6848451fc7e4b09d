//! The handle a long computation gets: progress, previews of partial results, cancellation.
//!
//! A [`Job`] holds no threads, channels or clocks. The front end that starts a run decides what
//! happens to the events: the headless exporter prints a progress bar on stderr, the terminal UI
//! forwards them through a channel to its drawing loop, tests record them. `Job` is `Sync`, so a
//! rayon sweep can report from every worker.
//!
//! A run made of stages hands each stage a [`Job::part`] (its 0..1 becomes a span of the run's),
//! and parts that run side by side get [`Job::parts`] (the run's fraction is their weighted
//! mean), so a cycle inside a sweep point or a solver inside a stage reports its own steps
//! without knowing where it sits. Counts of items finished in parallel go through a
//! [`Ticker`], which reports them in order. So the fractions a run reports never move back, and
//! only its last report reaches 1: stages end below it, and the scene says `done` at the end.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use crate::error::{Error, Result};
use crate::figure::Figure;

/// What a running computation reports.
#[derive(Debug)]
pub enum JobEvent<'a> {
    /// Fraction done in [0, 1] and a short message ("alpha 37/100").
    Progress {
        /// Fraction done, 0 to 1.
        fraction: f64,
        /// What is being done.
        message: &'a str,
    },
    /// The figure as far as it is computed: series appear and grow as the run proceeds.
    Preview(&'a Figure),
}

type Sink = dyn Fn(&JobEvent<'_>) + Send + Sync;

/// Send a progress event, `fraction` clamped to [0, 1] (NaN as 0).
fn send(sink: &Sink, fraction: f64, message: &str) {
    let fraction = if fraction.is_finite() {
        fraction.clamp(0.0, 1.0)
    } else {
        0.0
    };
    sink(&JobEvent::Progress { fraction, message });
}

/// Progress, partial results and cancellation of one run.
pub struct Job {
    cancel: Arc<AtomicBool>,
    sink: Option<Arc<Sink>>,
    /// Whether the sink wants previews (a progress bar does not).
    previews: bool,
}

impl Default for Job {
    fn default() -> Self {
        Self::quiet()
    }
}

impl std::fmt::Debug for Job {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job")
            .field("cancelled", &self.is_cancelled())
            .field("has_sink", &self.sink.is_some())
            .finish()
    }
}

impl Job {
    /// A job that reports nowhere and is never cancelled from outside.
    pub fn quiet() -> Self {
        Self {
            cancel: Arc::new(AtomicBool::new(false)),
            sink: None,
            previews: false,
        }
    }

    /// A job whose events go to `sink`. The sink is called from the computing thread(s) and
    /// should return quickly (throttle or forward).
    pub fn with_sink(sink: impl Fn(&JobEvent<'_>) + Send + Sync + 'static) -> Self {
        Self {
            cancel: Arc::new(AtomicBool::new(false)),
            sink: Some(Arc::new(sink)),
            previews: true,
        }
    }

    /// The same job for a sink that only shows progress: [`Job::wants_preview`] says no, so
    /// no partial figure is built for it (nor for its parts).
    #[must_use]
    pub fn without_previews(mut self) -> Self {
        self.previews = false;
        self
    }

    /// Use `flag` as the cancellation flag (set it to `true` from another thread to cancel).
    #[must_use]
    pub fn with_cancel_flag(mut self, flag: Arc<AtomicBool>) -> Self {
        self.cancel = flag;
        self
    }

    /// The cancellation flag, to hand to another thread.
    pub fn cancel_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.cancel)
    }

    /// Request cancellation.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Whether cancellation was requested.
    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// `Err(Error::Cancelled)` once cancellation was requested; call it in every loop that can
    /// run for more than a few milliseconds.
    ///
    /// # Errors
    /// [`Error::Cancelled`] when the job was cancelled.
    pub fn check(&self) -> Result<()> {
        if self.is_cancelled() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }

    /// Report progress: `fraction` in [0, 1] (clamped) and a short message.
    pub fn progress(&self, fraction: f64, message: &str) {
        if let Some(sink) = &self.sink {
            send(sink.as_ref(), fraction, message);
        }
    }

    /// A counter of `total` items finished in parallel, reporting `lo + (hi - lo) · done/total`
    /// with `message` as each finishes, in order (see [`Ticker`]).
    pub fn ticker(&self, total: usize, message: &str, lo: f64, hi: f64) -> Ticker<'_> {
        Ticker {
            job: self,
            done: Mutex::new(0),
            total: total.max(1),
            message: message.to_string(),
            span: (lo, hi),
        }
    }

    /// A job for one stage of this run, sharing its cancellation: the stage's fractions 0..1
    /// are reported as `lo`..`hi` of this job's, its previews pass unchanged. Give the last
    /// stage an `hi` below 1 when work follows it (the run's own `done` ends at 1).
    pub fn part(&self, lo: f64, hi: f64) -> Job {
        let Some(parent) = self.sink.clone() else {
            return self.silent_child();
        };
        self.child(move |event: &JobEvent<'_>| match event {
            JobEvent::Progress { fraction, message } => {
                send(parent.as_ref(), lo + (hi - lo) * fraction, message);
            }
            JobEvent::Preview(_) => parent(event),
        })
    }

    /// Jobs for parts of this run weighted by `weights` (their cost, in any unit), which may
    /// run side by side (rayon) or one after another: this job's fraction is `lo` plus
    /// `hi - lo` times the weighted mean of the parts' fractions. Previews pass unchanged.
    pub fn parts(&self, weights: &[f64], lo: f64, hi: f64) -> Vec<Job> {
        let Some(parent) = self.sink.clone() else {
            return weights.iter().map(|_| self.silent_child()).collect();
        };
        let weights: Vec<f64> = weights
            .iter()
            .map(|w| if w.is_finite() && *w > 0.0 { *w } else { 0.0 })
            .collect();
        let total: f64 = weights.iter().sum();
        let done = Arc::new(Mutex::new(vec![0.0_f64; weights.len()]));
        (0..weights.len())
            .map(|i| {
                let parent = Arc::clone(&parent);
                let done = Arc::clone(&done);
                let weights = weights.clone();
                self.child(move |event: &JobEvent<'_>| match event {
                    JobEvent::Progress { fraction, message } => {
                        // A part counts with the largest fraction it reported, and the parent
                        // is called under the lock: the sums reach it in order.
                        let Ok(mut done) = done.lock() else { return };
                        done[i] = done[i].max(*fraction);
                        let sum: f64 = done.iter().zip(&weights).map(|(f, w)| f * w).sum();
                        let mean = if total > 0.0 {
                            sum / total
                        } else {
                            done.iter().sum::<f64>() / done.len() as f64
                        };
                        send(parent.as_ref(), lo + (hi - lo) * mean, message);
                    }
                    JobEvent::Preview(_) => parent(event),
                })
            })
            .collect()
    }

    fn child(&self, sink: impl Fn(&JobEvent<'_>) + Send + Sync + 'static) -> Job {
        let mut job = Job::with_sink(sink).with_cancel_flag(self.cancel_flag());
        job.previews = self.previews;
        job
    }

    fn silent_child(&self) -> Job {
        Job::quiet().with_cancel_flag(self.cancel_flag())
    }

    /// Map `f` over `items` in parallel (rayon), in order, reporting the fraction of items done
    /// with `message` as each finishes; the first error is returned.
    ///
    /// # Errors
    /// The first error of `f`.
    pub fn map_parallel<T: Sync, R: Send>(
        &self,
        items: &[T],
        message: &str,
        f: impl Fn(&T) -> Result<R> + Sync + Send,
    ) -> Result<Vec<R>> {
        self.map_parallel_within(items, message, 0.0, 1.0, f)
    }

    /// [`Job::map_parallel`] reporting the fraction of items done as `lo`..`hi` of this job's.
    ///
    /// # Errors
    /// The first error of `f`.
    pub fn map_parallel_within<T: Sync, R: Send>(
        &self,
        items: &[T],
        message: &str,
        lo: f64,
        hi: f64,
        f: impl Fn(&T) -> Result<R> + Sync + Send,
    ) -> Result<Vec<R>> {
        use rayon::prelude::*;
        let ticker = self.ticker(items.len(), message, lo, hi);
        items
            .par_iter()
            .map(|item| {
                let out = f(item);
                ticker.tick();
                out
            })
            .collect()
    }

    /// Map `f` over `items` in parallel (rayon), in order, each item with its own part of this
    /// job ([`Job::parts`] with `weights`, one per item, spanning `lo`..`hi`): the fraction
    /// advances with the steps the items report, and an item's part is full once it returns.
    ///
    /// # Errors
    /// The first error of `f`.
    ///
    /// # Panics
    /// If `weights` and `items` differ in length.
    pub fn map_parallel_parts<T: Sync, R: Send>(
        &self,
        items: &[T],
        weights: &[f64],
        message: &str,
        (lo, hi): (f64, f64),
        f: impl Fn(&T, &Job) -> Result<R> + Sync + Send,
    ) -> Result<Vec<R>> {
        use rayon::prelude::*;
        assert_eq!(items.len(), weights.len(), "one weight per item");
        let parts = self.parts(weights, lo, hi);
        let done = std::sync::atomic::AtomicUsize::new(0);
        items
            .par_iter()
            .zip(&parts)
            .map(|(item, part)| {
                let out = f(item, part);
                if out.is_ok() {
                    let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                    part.progress(1.0, &format!("{message} {n}/{}", items.len()));
                }
                out
            })
            .collect()
    }

    /// Whether anyone listens for previews; build a partial figure only if so.
    pub fn wants_preview(&self) -> bool {
        self.previews && self.sink.is_some()
    }

    /// Stream the figure as far as it is computed.
    pub fn preview(&self, figure: &Figure) {
        if let Some(sink) = self.sink.as_ref().filter(|_| self.previews) {
            sink(&JobEvent::Preview(figure));
        }
    }
}

/// Counts items finished in parallel and reports the count as a fraction of a span, under a
/// lock, so the reports arrive in order (a plain atomic counter can report 6 before 5).
pub struct Ticker<'a> {
    job: &'a Job,
    done: Mutex<usize>,
    total: usize,
    message: String,
    span: (f64, f64),
}

impl Ticker<'_> {
    /// One more item finished.
    pub fn tick(&self) {
        let Ok(mut done) = self.done.lock() else { return };
        *done += 1;
        let (lo, hi) = self.span;
        self.job
            .progress(lo + (hi - lo) * *done as f64 / self.total as f64, &self.message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn cancellation_is_seen_by_check_and_progress_is_clamped() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s = Arc::clone(&seen);
        let job = Job::with_sink(move |e| {
            if let JobEvent::Progress { fraction, .. } = e {
                s.lock().expect("test mutex").push(*fraction);
            }
        });
        job.progress(1.5, "over");
        job.progress(f64::NAN, "nan");
        assert!(job.check().is_ok());
        job.cancel_flag().store(true, Ordering::Relaxed);
        assert!(matches!(job.check(), Err(Error::Cancelled)));
        assert_eq!(*seen.lock().expect("test mutex"), vec![1.0, 0.0]);
    }

    fn recording() -> (Job, Arc<Mutex<Vec<f64>>>) {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s = Arc::clone(&seen);
        let job = Job::with_sink(move |e| {
            if let JobEvent::Progress { fraction, .. } = e {
                s.lock().expect("test mutex").push(*fraction);
            }
        });
        (job, seen)
    }

    #[test]
    fn a_ticker_reports_the_items_done_in_order() {
        let (job, seen) = recording();
        let ticker = job.ticker(100, "items", 0.5, 1.0);
        {
            use rayon::prelude::*;
            (0..100).into_par_iter().for_each(|_| ticker.tick());
        }
        let got = seen.lock().expect("test mutex").clone();
        assert_eq!(got.len(), 100);
        assert!(got.windows(2).all(|w| w[1] > w[0]), "{got:?}");
        assert!((got[0] - 0.505).abs() < 1e-12 && (got[99] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_part_maps_its_fractions_into_its_span_and_shares_cancellation() {
        let (job, seen) = recording();
        let stage = job.part(0.25, 0.75);
        stage.progress(0.0, "a");
        stage.progress(0.5, "b");
        stage.progress(1.0, "c");
        // A stage of a stage.
        stage.part(0.5, 1.0).progress(0.5, "d");
        assert_eq!(*seen.lock().expect("test mutex"), vec![0.25, 0.5, 0.75, 0.625]);
        job.cancel();
        assert!(matches!(stage.check(), Err(Error::Cancelled)));
        // A quiet job's parts are quiet and still cancellable.
        let quiet = Job::quiet();
        let part = quiet.part(0.0, 0.5);
        assert!(!part.wants_preview());
        quiet.cancel();
        assert!(part.is_cancelled());
        // A progress-only job's parts want no previews either.
        let bar = Job::with_sink(|_| {}).without_previews();
        assert!(!bar.part(0.0, 0.5).wants_preview() && !bar.parts(&[1.0], 0.0, 1.0)[0].wants_preview());
        assert!(Job::with_sink(|_| {}).part(0.0, 0.5).wants_preview());
    }

    #[test]
    fn parts_report_their_weighted_mean_and_items_fill_their_parts() {
        let (job, seen) = recording();
        let parts = job.parts(&[1.0, 3.0], 0.0, 0.8);
        parts[1].progress(0.5, "b");
        parts[0].progress(1.0, "a");
        parts[1].progress(1.0, "b");
        let got = seen.lock().expect("test mutex").clone();
        let want = [0.8 * 1.5 / 4.0, 0.8 * 2.5 / 4.0, 0.8];
        assert_eq!(got.len(), 3);
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{got:?}");
        }

        let (job, seen) = recording();
        let items = [1usize, 2, 3, 4];
        let out = job
            .map_parallel_parts(&items, &[1.0; 4], "items", (0.1, 0.9), |&k, part| {
                part.progress(0.5, "half");
                Ok(k * 10)
            })
            .expect("no error");
        assert_eq!(out, vec![10, 20, 30, 40]);
        let got = seen.lock().expect("test mutex").clone();
        assert_eq!(got.len(), 8);
        assert!(got.windows(2).all(|w| w[1] >= w[0]), "{got:?}");
        assert!((got[7] - 0.9).abs() < 1e-12, "{got:?}");
    }
}
