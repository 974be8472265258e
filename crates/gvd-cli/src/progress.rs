//! `--timeout` and the progress bar of long runs: both go into the library's
//! [`gvd::Control`]. The bar is drawn on standard error only when it is a terminal,
//! and only once a run has taken longer than [`SHOW_AFTER`].

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A run shows its progress once it has taken this long.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// Options of a run's time and progress, shared by `compute` and `offset`.
#[derive(Args)]
pub struct RunArgs {
    /// Stop the computation after this many seconds (finite, > 0) with an error.
    #[arg(long, value_parser = positive_seconds)]
    timeout: Option<Duration>,
    /// Never draw the progress bar (it is drawn only on a terminal anyway).
    #[arg(long)]
    no_progress: bool,
}

/// A finite number of seconds > 0 that a [`Duration`] holds, at least 1 ns.
fn positive_seconds(s: &str) -> Result<Duration, String> {
    let x: f64 = s.parse().map_err(|e| format!("{e}"))?;
    if !(x.is_finite() && x > 0.0) {
        return Err(format!("must be a finite number of seconds > 0, found {x}"));
    }
    match Duration::try_from_secs_f64(x) {
        Ok(d) if !d.is_zero() => Ok(d),
        Ok(_) => Err(format!("{x} s is shorter than a nanosecond")),
        Err(_) => Err(format!("{x} s is longer than this machine can count")),
    }
}

/// The progress bar of one run (hidden until the run has taken [`SHOW_AFTER`]).
pub struct Bar {
    bar: ProgressBar,
    state: Mutex<(Option<&'static str>, bool)>,
    start: Instant,
}

impl RunArgs {
    /// The library's control for these options, with the bar it draws (when standard
    /// error is a terminal); finish the bar with [`finish`] when the run ends.
    pub fn control(&self) -> (gvd::Control, Option<Arc<Bar>>) {
        let bar = (!self.no_progress && std::io::stderr().is_terminal()).then(|| {
            Arc::new(Bar {
                bar: ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden()),
                state: Mutex::new((None, false)),
                start: Instant::now(),
            })
        });
        let progress = bar.clone().map(|b| {
            let f: gvd::ProgressFn = Arc::new(move |p: &gvd::Progress| b.update(p));
            f
        });
        let control = gvd::Control {
            cancel: None,
            timeout: self.timeout,
            progress,
        };
        (control, bar)
    }
}

impl Bar {
    fn update(&self, p: &gvd::Progress) {
        let Ok(mut state) = self.state.lock() else {
            return;
        };
        if state.0 != Some(p.stage) {
            state.0 = Some(p.stage);
            let style = match p.total {
                Some(n) => {
                    self.bar.set_length(n);
                    ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} ({elapsed})")
                }
                None => {
                    self.bar.unset_length();
                    ProgressStyle::with_template("{spinner} {msg}: {human_pos} ({elapsed})")
                }
            };
            if let Ok(style) = style {
                self.bar.set_style(style);
            }
            self.bar.set_message(p.stage);
        }
        self.bar.set_position(p.done);
        if !state.1 && self.start.elapsed() >= SHOW_AFTER {
            state.1 = true;
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }
}

/// Clears the bar (if any) from the terminal.
pub fn finish(bar: Option<Arc<Bar>>) {
    if let Some(b) = bar {
        b.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::positive_seconds;

    #[test]
    fn timeouts_are_positive_finite_and_countable() {
        assert_eq!(positive_seconds("1.5").unwrap().as_millis(), 1500);
        for bad in ["0", "-1", "NaN", "inf", "1e300", "1e-300", "x"] {
            assert!(positive_seconds(bad).is_err(), "{bad}");
        }
    }
}
