//! A progress bar on stderr for long runs (indicatif); drawn only when stderr is a terminal
//! and `--quiet` is not given.

use indicatif::{ProgressBar, ProgressStyle};

/// Steps of a bar that shows a fraction.
const STEPS: u64 = 1000;

/// A progress bar, or nothing.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A bar for one run: `label` and a fraction done.
    pub fn run(label: &str, quiet: bool) -> Progress {
        let bar = if quiet { ProgressBar::hidden() } else { ProgressBar::new(STEPS) };
        bar.set_style(
            ProgressStyle::with_template("{msg:>12} [{bar:40}] {percent:>3}% {elapsed}")
                .expect("a valid template")
                .progress_chars("=> "),
        );
        bar.set_message(label.to_string());
        Progress { bar }
    }

    /// A bar over `count` items, with the current item's name.
    pub fn items(count: u64, quiet: bool) -> Progress {
        let bar = if quiet { ProgressBar::hidden() } else { ProgressBar::new(count) };
        bar.set_style(
            ProgressStyle::with_template("{pos:>3}/{len} [{bar:40}] {elapsed} {msg}")
                .expect("a valid template")
                .progress_chars("=> "),
        );
        Progress { bar }
    }

    /// A hidden bar, for work inside a larger one.
    pub fn hidden() -> Progress {
        Progress { bar: ProgressBar::hidden() }
    }

    /// Whether nothing shows the bar (`--quiet`, work inside a larger bar, or no terminal).
    pub fn is_hidden(&self) -> bool {
        self.bar.is_hidden()
    }

    /// Sets the fraction done, 0 to 1.
    pub fn set_fraction(&self, fraction: f32) {
        self.bar.set_position((fraction.clamp(0.0, 1.0) * STEPS as f32) as u64);
    }

    /// Starts the next item.
    pub fn start(&self, item: &str) {
        self.bar.set_message(item.to_string());
    }

    /// One item done.
    pub fn done(&self) {
        self.bar.inc(1);
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
