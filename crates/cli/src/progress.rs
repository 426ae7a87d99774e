//! Progress on standard error (indicatif): a bar for batches, a spinner for single long runs.
//!
//! Nothing is drawn with `--quiet` or when standard error is not a terminal (pipes, CI, tests),
//! so progress never mixes with reports or points. A single run shows its spinner only once
//! it has taken longer than [`SPINNER_DELAY`]: short runs stay silent.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// How long a single run goes before its spinner appears.
pub(crate) const SPINNER_DELAY: Duration = Duration::from_secs(1);

/// Whether progress may be drawn at all.
pub(crate) fn visible(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// A bar over `total` items (a batch), hidden when not [`visible`].
pub(crate) fn bar(total: u64, quiet: bool, message: &str) -> ProgressBar {
    if !visible(quiet) {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta} left)")
        .map(|s| s.progress_chars("=> "))
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_message(message.to_string());
    bar
}

/// A spinner that appears after [`SPINNER_DELAY`] if the work is still running, and is cleared
/// when this value is dropped.
#[derive(Debug)]
pub(crate) struct Activity {
    done: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Activity {
    /// Starts watching a piece of work described by `message`.
    pub(crate) fn start(message: &str, quiet: bool) -> Activity {
        let done = Arc::new(AtomicBool::new(false));
        if !visible(quiet) {
            return Activity { done, thread: None };
        }
        let flag = Arc::clone(&done);
        let message = message.to_string();
        let thread = std::thread::spawn(move || {
            let step = Duration::from_millis(50);
            let mut waited = Duration::ZERO;
            // Parked, not asleep: `drop` unparks the thread, so that a short piece of work
            // does not wait for the end of a step.
            while waited < SPINNER_DELAY {
                if flag.load(Ordering::Acquire) {
                    return;
                }
                std::thread::park_timeout(step);
                waited += step;
            }
            let spinner = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
                spinner.set_style(style);
            }
            spinner.set_message(message);
            spinner.enable_steady_tick(Duration::from_millis(100));
            while !flag.load(Ordering::Acquire) {
                std::thread::park_timeout(step);
            }
            spinner.finish_and_clear();
        });
        Activity {
            done,
            thread: Some(thread),
        }
    }
}

impl Drop for Activity {
    fn drop(&mut self) {
        self.done.store(true, Ordering::Release);
        if let Some(thread) = self.thread.take() {
            thread.thread().unpark();
            let _ = thread.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_means_hidden_and_no_thread() {
        assert!(bar(10, true, "x").is_hidden());
        let activity = Activity::start("x", true);
        assert!(activity.thread.is_none());
    }
}
