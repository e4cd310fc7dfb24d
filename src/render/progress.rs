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
