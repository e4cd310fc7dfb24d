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

/// The progress bar of the phase running now, readable from another thread.
#[derive(Debug, Default)]
pub struct Observer {
    current: Mutex<Option<ProgressBar>>,
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
        if let Ok(mut c) = self.current.lock() {
            *c = Some(pb.clone());
        }
    }

    /// The current phase's progress (`None` before the first phase starts).
    pub fn read(&self) -> Option<PhaseProgress> {
        let c = self.current.lock().ok()?;
        let pb = c.as_ref()?;
        Some(PhaseProgress { phase: pb.prefix(), done: pb.position(), total: pb.length().unwrap_or(0) })
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
    }
}
