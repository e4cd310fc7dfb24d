//! Progress bars on stderr, one per long phase; `--quiet` hides them.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A phase's progress bar (hidden when quiet).
pub fn bar(quiet: bool, len: u64, label: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
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
