//! Stopping and watching a run from outside ([`Control`] in [`crate::Options`]): a
//! cancel flag another thread may set, a time limit, and a progress callback. Every
//! engine's main loop draws on one [`Watch`] per run (the subdivision engines through
//! their box and point budget, the incremental engine per inserted site, the free-form
//! engine per pair of pieces), so a run stops within a few hundred units of work of
//! the flag being set or the time running out, with [`Error::Cancelled`] or
//! [`Error::Budget`] (`what = "seconds"`).

use crate::error::Error;
use std::fmt;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicU8, Ordering::Relaxed};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A progress callback: called with the run's stage and its work done so far.
pub type ProgressFn = Arc<dyn Fn(&Progress) + Send + Sync>;

/// How far a run has got, as a [`ProgressFn`] is told.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// What is being counted: `"boxes"` (subdivision engines), `"points"` or
    /// `"segments and arcs"` (sites inserted by the incremental engine), `"pairs"`
    /// (pairs of pieces traced by the free-form engine).
    pub stage: &'static str,
    /// Units of the stage done so far; never decreases within a stage.
    pub done: u64,
    /// The stage's number of units when known in advance (sites to insert); `None` for
    /// boxes, whose number the subdivision finds as it goes.
    pub total: Option<u64>,
}

/// Ways to stop or watch a run from outside; the default neither stops nor reports.
#[derive(Clone, Default)]
pub struct Control {
    /// Set to `true` (from any thread) to stop the run: [`crate::compute`] then returns
    /// [`Error::Cancelled`] soon after.
    pub cancel: Option<Arc<AtomicBool>>,
    /// The longest the run may take, from the call to [`crate::compute`]; past it the
    /// run ends with [`Error::Budget`] (`what = "seconds"`). Must be longer than zero.
    pub timeout: Option<Duration>,
    /// Called as the run goes (from the engine's threads, at most one call at a time,
    /// some hundreds of units of work apart): keep it cheap. The library prints nothing.
    pub progress: Option<ProgressFn>,
}

impl fmt::Debug for Control {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Control")
            .field("cancel", &self.cancel)
            .field("timeout", &self.timeout)
            .field("progress", &self.progress.as_ref().map(|_| "callback"))
            .finish()
    }
}

/// Units of work between two looks at the flag and the clock (and two reports).
const LOOK_EVERY: u64 = 256;

const RUNNING: u8 = 0;
const CANCELLED: u8 = 1;
const TIMED_OUT: u8 = 2;

/// The watch of one run over its [`Control`]: cheap to clone and to share between
/// threads; the default watches nothing.
#[derive(Clone, Default)]
pub(crate) struct Watch(Option<Arc<Inner>>);

struct Inner {
    cancel: Option<Arc<AtomicBool>>,
    deadline: Option<(Instant, Duration)>,
    progress: Option<ProgressFn>,
    /// Calls to [`Watch::tick`], to look at the flag and clock every [`LOOK_EVERY`].
    calls: AtomicU64,
    /// Work done in the current stage.
    done: AtomicU64,
    state: AtomicU8,
    /// The current stage, its total and the last count reported (reports are made
    /// under this lock, skipped when another thread holds it).
    report: Mutex<(&'static str, Option<u64>, u64)>,
}

impl Watch {
    /// Starts watching a run under `control` (its clock starts now), or refuses a zero
    /// timeout.
    pub fn start(control: &Control) -> Result<Watch, Error> {
        if control.timeout == Some(Duration::ZERO) {
            return Err(Error::InvalidOption {
                option: "timeout".into(),
                message: "must be longer than zero".into(),
            });
        }
        if control.cancel.is_none() && control.timeout.is_none() && control.progress.is_none() {
            return Ok(Watch(None));
        }
        Ok(Watch(Some(Arc::new(Inner {
            cancel: control.cancel.clone(),
            deadline: control.timeout.map(|t| (Instant::now() + t, t)),
            progress: control.progress.clone(),
            calls: AtomicU64::new(0),
            done: AtomicU64::new(0),
            state: AtomicU8::new(RUNNING),
            report: Mutex::new(("", None, 0)),
        }))))
    }

    /// Starts a new stage of `total` units (if known): the count restarts at 0.
    pub fn stage(&self, stage: &'static str, total: Option<u64>) {
        let Some(w) = &self.0 else { return };
        if let Ok(mut r) = w.report.lock() {
            w.done.store(0, Relaxed);
            *r = (stage, total, 0);
            if let Some(p) = &w.progress {
                p(&Progress {
                    stage,
                    done: 0,
                    total,
                });
            }
        }
    }

    /// Counts `work` units done (0 to only look); `false` once the run is to stop.
    pub fn tick(&self, work: u64) -> bool {
        let Some(w) = &self.0 else { return true };
        if w.state.load(Relaxed) != RUNNING {
            return false;
        }
        w.done.fetch_add(work, Relaxed);
        if w.calls.fetch_add(1, Relaxed) % LOOK_EVERY == LOOK_EVERY - 1 {
            self.look(w);
        }
        w.state.load(Relaxed) == RUNNING
    }

    /// Looks at the flag and the clock now and reports progress.
    fn look(&self, w: &Inner) {
        if w.cancel.as_ref().is_some_and(|c| c.load(Relaxed)) {
            w.state.store(CANCELLED, Relaxed);
        } else if w.deadline.is_some_and(|(d, _)| Instant::now() >= d) {
            w.state.store(TIMED_OUT, Relaxed);
        }
        let Some(p) = &w.progress else { return };
        if let Ok(mut r) = w.report.try_lock() {
            let done = w.done.load(Relaxed);
            if done > r.2 {
                r.2 = done;
                p(&Progress {
                    stage: r.0,
                    done,
                    total: r.1,
                });
            }
        }
    }

    /// `Ok` while the run may go on (looking at the flag and the clock now), else the
    /// error that stops it.
    pub fn check(&self) -> Result<(), Error> {
        let Some(w) = &self.0 else { return Ok(()) };
        if w.state.load(Relaxed) == RUNNING {
            self.look(w);
        }
        match w.state.load(Relaxed) {
            CANCELLED => Err(Error::Cancelled),
            TIMED_OUT => {
                let t = w.deadline.map_or(0.0, |(_, t)| t.as_secs_f64());
                Err(Error::Budget {
                    what: "seconds".into(),
                    limit: t.ceil() as usize,
                    message: format!(
                        "timed out after {t} s; raise --timeout (Options::control.timeout) or \
                         epsilon"
                    ),
                })
            }
            _ => Ok(()),
        }
    }

    /// Whether the run is to stop (as last looked).
    pub fn stopped(&self) -> bool {
        self.0
            .as_ref()
            .is_some_and(|w| w.state.load(Relaxed) != RUNNING)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_watch_stops_on_its_flag_and_reports_increasing_counts() {
        let flag = Arc::new(AtomicBool::new(false));
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s = seen.clone();
        let control = Control {
            cancel: Some(flag.clone()),
            progress: Some(Arc::new(move |p: &Progress| s.lock().unwrap().push(p.done))),
            ..Default::default()
        };
        let w = Watch::start(&control).unwrap();
        w.stage("points", Some(10_000));
        assert!((0..2000).all(|_| w.tick(1)));
        assert!(w.check().is_ok());
        flag.store(true, Relaxed);
        let more = (0..LOOK_EVERY).take_while(|_| w.tick(1)).count();
        assert!(more < LOOK_EVERY as usize && w.stopped());
        assert_eq!(w.check(), Err(Error::Cancelled));
        let seen = seen.lock().unwrap();
        assert!(
            seen.len() >= 7 && seen.windows(2).all(|p| p[0] < p[1]),
            "{seen:?}"
        );
    }

    #[test]
    fn a_watch_times_out_and_refuses_a_zero_timeout() {
        let timed = |t| Control {
            timeout: Some(t),
            ..Default::default()
        };
        assert!(Watch::start(&timed(Duration::ZERO)).is_err());
        let w = Watch::start(&timed(Duration::from_millis(1))).unwrap();
        std::thread::sleep(Duration::from_millis(5));
        let e = w.check().unwrap_err().to_string();
        assert!(
            e.contains("timed out after 0.001 s; raise --timeout"),
            "{e}"
        );
        assert!(!w.tick(1));
        assert!(Watch::default().tick(1) && Watch::default().check().is_ok());
    }
}
