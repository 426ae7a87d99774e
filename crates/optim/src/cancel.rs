//! Cooperative cancellation of long computations: a token another thread (or a deadline)
//! cancels, and checkpoints that the loops of the optimisers and fairing strategies call.
//!
//! A [`Cancel`] is a shared flag plus an optional deadline. Work runs under it with
//! [`Cancel::scope`], which makes it the *current* token of the calling thread; the loops
//! below call [`checkpoint`], which returns [`Err(Cancelled)`](Cancelled) once the flag is set
//! or the deadline has passed, and the error travels up as each crate's own `Cancelled`
//! variant (`optim::Error::Cancelled`, `fairing::Error::Cancelled`). Nothing is interrupted
//! from outside: the work stops at its next checkpoint, between iterations, and its partial
//! result is dropped.
//!
//! Why a thread-scoped token rather than a parameter of every call: the checkpoints sit deep
//! inside strategies and optimisers whose signatures are public and shared with programs that
//! never cancel; a scope reaches them all without changing one signature, and code run
//! outside any scope (the command, the bindings, a program) pays one thread-local read per
//! checkpoint and never stops.
//!
//! Threads: the token is not inherited by threads the work starts. The fairing loops run on
//! the thread that called them (the strategies start no threads); the measurements that run
//! on rayon's threads (quadrature, summaries) are single passes over the points with no
//! checkpoint, so a cancelled request finishes at most the measurement it is in. Work that
//! spreads a cancellable loop over threads must take the token ([`Cancel::current`]) and enter
//! a scope on each thread itself.
//!
//! Cost: a checkpoint outside any scope reads one thread-local; inside, one atomic load per
//! enclosing token and, when the token has a deadline, one clock read (tens of nanoseconds),
//! negligible beside one iteration of any loop that calls it.
//!
//! ```
//! use optim::cancel::{checkpoint, Cancel};
//!
//! let token = Cancel::new();
//! let stopped = token.scope(|| {
//!     let mut i = 0;
//!     while checkpoint().is_ok() {
//!         i += 1;
//!         if i == 3 {
//!             Cancel::current().unwrap().cancel(); // as another thread would
//!         }
//!     }
//!     i
//! });
//! assert_eq!(stopped, 3);
//! assert!(checkpoint().is_ok()); // outside the scope nothing is cancelled
//! ```

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// A cancellation token: cloned tokens share one flag. Cancelled when [`Cancel::cancel`] is
/// called on any clone or when its deadline (if any) passes.
#[derive(Debug, Clone, Default)]
pub struct Cancel {
    inner: Arc<Inner>,
}

#[derive(Debug, Default)]
struct Inner {
    cancelled: AtomicBool,
    deadline: Option<Instant>,
}

/// The error a [`checkpoint`] returns once the current token is cancelled: the work was
/// stopped on purpose (by its caller or its deadline), its result is incomplete.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled: the work was stopped before it finished (its deadline passed or its caller left)")]
pub struct Cancelled;

thread_local! {
    /// The tokens of the scopes the current thread is in, innermost last.
    static CURRENT: RefCell<Vec<Cancel>> = const { RefCell::new(Vec::new()) };
}

impl Cancel {
    /// A token that is cancelled only by [`Cancel::cancel`].
    pub fn new() -> Self {
        Self::default()
    }

    /// A token that is also cancelled once `deadline` has passed.
    pub fn with_deadline(deadline: Instant) -> Self {
        Cancel {
            inner: Arc::new(Inner {
                cancelled: AtomicBool::new(false),
                deadline: Some(deadline),
            }),
        }
    }

    /// The deadline, if the token has one.
    pub fn deadline(&self) -> Option<Instant> {
        self.inner.deadline
    }

    /// Cancels the token (and every clone of it); work under it stops at its next checkpoint.
    /// Callable from any thread, any number of times.
    pub fn cancel(&self) {
        self.inner.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether the token was cancelled or its deadline has passed.
    pub fn is_cancelled(&self) -> bool {
        if self.inner.cancelled.load(Ordering::Relaxed) {
            return true;
        }
        match self.inner.deadline {
            Some(deadline) if Instant::now() >= deadline => {
                self.inner.cancelled.store(true, Ordering::Relaxed);
                true
            }
            _ => false,
        }
    }

    /// Whether the deadline (if any) has passed, as opposed to a cancellation by
    /// [`Cancel::cancel`] alone.
    pub fn deadline_passed(&self) -> bool {
        self.inner.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// Runs `work` with this token current on the calling thread: every [`checkpoint`] inside
    /// fails once this token (or the token of an enclosing scope) is cancelled. The previous
    /// scopes are restored when `work` returns or unwinds.
    pub fn scope<R>(&self, work: impl FnOnce() -> R) -> R {
        struct Leave;
        impl Drop for Leave {
            fn drop(&mut self) {
                let _ = CURRENT.try_with(|c| c.borrow_mut().pop());
            }
        }
        CURRENT.with(|c| c.borrow_mut().push(self.clone()));
        let _leave = Leave;
        work()
    }

    /// The token of the innermost scope the calling thread is in, to hand to another thread.
    pub fn current() -> Option<Cancel> {
        CURRENT.with(|c| c.borrow().last().cloned())
    }
}

/// `Err(Cancelled)` when the calling thread is inside a [`Cancel::scope`] whose token (or an
/// enclosing one) is cancelled; `Ok(())` otherwise, and always outside any scope. Loops call
/// it once per iteration.
pub fn checkpoint() -> Result<(), Cancelled> {
    CURRENT.with(|c| {
        if c.borrow().iter().any(Cancel::is_cancelled) {
            Err(Cancelled)
        } else {
            Ok(())
        }
    })
}

/// Whether [`checkpoint`] would fail: for loops that stop by returning what they have.
pub fn cancelled() -> bool {
    checkpoint().is_err()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn outside_any_scope_nothing_is_cancelled() {
        let token = Cancel::new();
        token.cancel();
        assert!(token.is_cancelled());
        assert_eq!(checkpoint(), Ok(()));
        assert!(Cancel::current().is_none());
    }

    #[test]
    fn scopes_nest_and_an_outer_cancel_reaches_the_inner_work() {
        let outer = Cancel::new();
        let inner = Cancel::new();
        outer.scope(|| {
            assert_eq!(checkpoint(), Ok(()));
            inner.scope(|| {
                assert_eq!(checkpoint(), Ok(()));
                outer.cancel();
                assert_eq!(checkpoint(), Err(Cancelled));
                assert!(!inner.is_cancelled());
            });
            assert_eq!(checkpoint(), Err(Cancelled));
        });
        assert_eq!(checkpoint(), Ok(()));
        // An inner cancel stops the inner work only.
        let outer = Cancel::new();
        let inner = Cancel::new();
        outer.scope(|| {
            inner.scope(|| {
                inner.cancel();
                assert_eq!(checkpoint(), Err(Cancelled));
                assert!(Cancel::current().is_some_and(|c| c.is_cancelled()));
            });
            assert_eq!(checkpoint(), Ok(()));
        });
    }

    #[test]
    fn a_scope_is_left_when_its_work_panics() {
        let token = Cancel::new();
        token.cancel();
        let caught = std::panic::catch_unwind(|| token.scope(|| panic!("work failed")));
        assert!(caught.is_err());
        assert!(Cancel::current().is_none());
        assert_eq!(checkpoint(), Ok(()));
    }

    #[test]
    fn a_checkpoint_fails_after_the_deadline() {
        let token = Cancel::with_deadline(Instant::now() + Duration::from_millis(30));
        token.scope(|| {
            assert_eq!(checkpoint(), Ok(()));
            std::thread::sleep(Duration::from_millis(60));
            assert_eq!(checkpoint(), Err(Cancelled));
        });
        assert!(token.deadline_passed());
        assert!(token.is_cancelled());
        let past = Cancel::with_deadline(Instant::now());
        assert!(past.is_cancelled());
        assert!(!Cancel::new().deadline_passed());
    }

    #[test]
    fn another_thread_cancels_a_running_loop() {
        let token = Cancel::new();
        let worker = {
            let token = token.clone();
            std::thread::spawn(move || {
                token.scope(|| {
                    let mut iterations = 0u64;
                    while checkpoint().is_ok() {
                        iterations += 1;
                        std::thread::yield_now();
                    }
                    iterations
                })
            })
        };
        std::thread::sleep(Duration::from_millis(50));
        token.cancel();
        let iterations = worker.join().unwrap();
        assert!(iterations > 0);
        // The scope was the worker's: this thread's checkpoints are untouched.
        assert_eq!(checkpoint(), Ok(()));
    }

    #[test]
    fn a_cancelled_search_is_an_error_and_stops_within_an_iteration() {
        use crate::nelder_mead::{minimize, NelderMeadSettings};
        use std::cell::Cell;
        // Cancelled by the objective itself after 50 evaluations (as another thread would):
        // the search makes at most one iteration's evaluations more.
        let evaluations = Cell::new(0u64);
        let objective = |p: &[f64]| {
            evaluations.set(evaluations.get() + 1);
            if evaluations.get() == 50 {
                Cancel::current().unwrap().cancel();
            }
            Ok(p.iter().map(|x| (x - 3.0).powi(2)).sum::<f64>().sqrt().sin() + 2.0)
        };
        let token = Cancel::new();
        let result = token.scope(|| {
            minimize(
                &objective,
                &[0.0, 0.0, 0.0],
                NelderMeadSettings::default().with_sd_tolerance(0.0),
            )
        });
        assert_eq!(result.unwrap_err(), crate::Error::Cancelled(Cancelled));
        assert_eq!(evaluations.get(), 50);
        // L-BFGS likewise.
        let gradient = |p: &[f64]| Ok(((p[0] - 3.0).powi(2), vec![2.0 * (p[0] - 3.0)]));
        let result = token.scope(|| crate::lbfgs::minimize_lbfgs(&gradient, &[0.0], Default::default()));
        assert_eq!(result.unwrap_err(), crate::Error::Cancelled(Cancelled));
        // Not cancelled, the same search runs on.
        let fresh = Cancel::new();
        let ok = fresh.scope(|| crate::lbfgs::minimize_lbfgs(&gradient, &[0.0], Default::default()));
        assert!(ok.is_ok());
    }

    #[test]
    fn the_token_is_not_inherited_by_spawned_threads() {
        let token = Cancel::new();
        token.cancel();
        token.scope(|| {
            assert!(cancelled());
            let other = std::thread::spawn(cancelled).join().unwrap();
            assert!(!other);
        });
    }
}
