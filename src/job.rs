//! The handle a long computation gets: progress, previews of partial results, cancellation.
//!
//! A [`Job`] holds no threads, channels or clocks. The front end that starts a run decides what
//! happens to the events: the headless exporter prints a progress bar on stderr, the terminal UI
//! forwards them through a channel to its drawing loop, tests record them. `Job` is `Sync`, so a
//! rayon sweep can report from every worker.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

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

/// Progress, partial results and cancellation of one run.
pub struct Job {
    cancel: Arc<AtomicBool>,
    sink: Option<Box<Sink>>,
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
        }
    }

    /// A job whose events go to `sink`. The sink is called from the computing thread(s) and
    /// should return quickly (throttle or forward).
    pub fn with_sink(sink: impl Fn(&JobEvent<'_>) + Send + Sync + 'static) -> Self {
        Self {
            cancel: Arc::new(AtomicBool::new(false)),
            sink: Some(Box::new(sink)),
        }
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
            let fraction = if fraction.is_finite() {
                fraction.clamp(0.0, 1.0)
            } else {
                0.0
            };
            sink(&JobEvent::Progress { fraction, message });
        }
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
        use rayon::prelude::*;
        let done = std::sync::atomic::AtomicUsize::new(0);
        items
            .par_iter()
            .map(|item| {
                let out = f(item);
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                self.progress(n as f64 / items.len() as f64, message);
                out
            })
            .collect()
    }

    /// Whether anyone listens for previews; build a partial figure only if so.
    pub fn wants_preview(&self) -> bool {
        self.sink.is_some()
    }

    /// Stream the figure as far as it is computed.
    pub fn preview(&self, figure: &Figure) {
        if let Some(sink) = &self.sink {
            sink(&JobEvent::Preview(figure));
        }
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
}
