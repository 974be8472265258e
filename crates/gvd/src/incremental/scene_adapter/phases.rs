//! Wall-clock time per phase of a run, reported in the output's `stats` as
//! `seconds_<phase>`.

use std::collections::BTreeMap;
use std::time::Instant;

/// Phases in the order they ended, each with its seconds.
pub(crate) struct Phases {
    last: Instant,
    done: Vec<(&'static str, f64)>,
}

impl Default for Phases {
    fn default() -> Phases {
        Phases {
            last: Instant::now(),
            done: Vec::new(),
        }
    }
}

impl Phases {
    /// Ends phase `name`, which began when the previous one ended.
    pub(crate) fn end(&mut self, name: &'static str) {
        let now = Instant::now();
        self.done
            .push((name, now.duration_since(self.last).as_secs_f64()));
        self.last = now;
    }

    /// Writes each phase's seconds as `seconds_<name>` into `stats`.
    pub(crate) fn record(self, stats: &mut BTreeMap<String, serde_json::Value>) {
        for (name, s) in self.done {
            stats.insert(format!("seconds_{name}"), serde_json::json!(s));
        }
    }
}
