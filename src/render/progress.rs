//! Progress bars on stderr, one per long phase; `--quiet` hides them. An [`Observer`] lets
//! another thread read the current phase's progress instead (the Python package draws it with
//! tqdm).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::Mutex;

/// Where a run's progress shows: nowhere (`quiet`), in an [`Observer`], or on stderr.
#[derive(Clone, Copy, Debug, Default)]
pub struct Bars<'a> {
    /// Hide progress.
    pub quiet: bool,
    /// Hand each phase's bar to this observer instead of drawing it.
    pub observer: Option<&'a Observer>,
}

impl Bars<'_> {
    /// A phase's progress bar of `len` steps, named `label`: hidden when quiet, handed (hidden)
    /// to the observer when there is one, else drawn on stderr.
    pub fn bar(&self, len: u64, label: &str) -> ProgressBar {
        if self.quiet {
            return ProgressBar::hidden();
        }
        if let Some(o) = self.observer {
            let pb = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
            pb.set_prefix(label.to_string());
            o.watch(&pb);
            return pb;
        }
        bar(len, label)
    }
}

/// The progress bars of a run's phases, in the order they started, readable from another
/// thread (a reader polling now and then also sees the phases that started and ended between
/// two of its polls).
#[derive(Debug, Default)]
pub struct Observer {
    phases: Mutex<Vec<ProgressBar>>,
}

/// A phase's progress as an [`Observer`] reads it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PhaseProgress {
    /// The phase ("global photons", "eye pass").
    pub phase: String,
    /// Steps done.
    pub done: u64,
    /// Steps in the phase.
    pub total: u64,
}

impl Observer {
    fn watch(&self, pb: &ProgressBar) {
        if let Ok(mut c) = self.phases.lock() {
            c.push(pb.clone());
        }
    }

    /// The latest phase's progress (`None` before the first phase starts).
    pub fn read(&self) -> Option<PhaseProgress> {
        self.read_all().pop()
    }

    /// Every phase's progress so far, in the order the phases started.
    pub fn read_all(&self) -> Vec<PhaseProgress> {
        let Ok(c) = self.phases.lock() else { return Vec::new() };
        c.iter()
            .map(|pb| PhaseProgress { phase: pb.prefix(), done: pb.position(), total: pb.length().unwrap_or(0) })
            .collect()
    }
}

/// A phase's progress bar drawn on stderr.
fn bar(len: u64, label: &str) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template("{prefix:>16} [{bar:32}] {percent:>3}% {elapsed_precise} eta {eta}")
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
    pb.set_style(style);
    pb.set_prefix(label.to_string());
    pb
}

/// A line on stderr as a phase of a multi-rank run starts (progress bars only show on a
/// terminal; these lines also reach a log). Hidden when quiet or on one rank.
pub fn note(quiet: bool, ranks: usize, what: &str) {
    if !quiet && ranks > 1 {
        eprintln!("morgana: {what}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_observer_reads_the_latest_phase() {
        let o = Observer::default();
        assert_eq!(o.read(), None);
        let bars = Bars { quiet: false, observer: Some(&o) };
        let a = bars.bar(10, "global photons");
        a.inc(4);
        assert_eq!(o.read(), Some(PhaseProgress { phase: "global photons".into(), done: 4, total: 10 }));
        let b = bars.bar(3, "eye pass");
        b.inc(3);
        assert_eq!(o.read(), Some(PhaseProgress { phase: "eye pass".into(), done: 3, total: 3 }));
        let quiet = Bars { quiet: true, observer: Some(&o) };
        quiet.bar(5, "hidden").inc(1);
        assert_eq!(o.read().map(|p| p.phase), Some("eye pass".to_string()));
        // Every phase stays readable at its last position, also one that ended between polls.
        let all: Vec<(String, u64)> = o.read_all().into_iter().map(|p| (p.phase, p.done)).collect();
        assert_eq!(all, vec![("global photons".to_string(), 4), ("eye pass".to_string(), 3)]);
    }
}
