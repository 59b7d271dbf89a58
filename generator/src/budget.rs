//! Resource budgets. The searches whose size depends on the problem (the Gröbner basis
//! degree, the template's candidate degree) have no fixed cap: they raise their degree
//! until they succeed or until the budget runs out, and then say which budget ran out
//! and at what degree.
//!
//! ## Public API
//! - [`Budget`]: the limits (wall-clock seconds, bytes of working memory). The command
//!   line's defaults are [`DEFAULT_MAX_SECONDS`] and [`DEFAULT_MAX_MEMORY_MB`]; the
//!   library's [`Budget::default`] has the same memory limit and no wall-clock limit, so
//!   that build scripts and `generate --all` checks never fail on a slow machine.
//! - [`Deadline`]: a budget started at one instant; [`Deadline::check_time`] and
//!   [`Deadline::check_memory`] return [`Exhausted`] once a limit is passed.
//!
//! Memory is accounted by estimate (the dominant data structures of each search: the
//! terms of the Gröbner basis and its pairs, the dense matrices of the template search),
//! checked before a structure is built, so a search stops before it allocates past the
//! limit.

use std::fmt;
use std::time::Instant;

/// The command line's default wall-clock budget of one problem's algebra (count,
/// templates, validation).
pub const DEFAULT_MAX_SECONDS: f64 = 300.0;
/// Default memory budget of one problem's algebra, in MiB.
pub const DEFAULT_MAX_MEMORY_MB: u64 = 4096;

/// Limits of one problem's algebra.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Wall-clock seconds.
    pub max_seconds: f64,
    /// Bytes of working memory (estimated, see the module documentation).
    pub max_memory_bytes: u64,
}

impl Default for Budget {
    /// No wall-clock limit; [`DEFAULT_MAX_MEMORY_MB`].
    fn default() -> Self {
        Budget {
            max_seconds: f64::INFINITY,
            max_memory_bytes: DEFAULT_MAX_MEMORY_MB << 20,
        }
    }
}

impl Budget {
    /// A budget of `max_seconds` seconds and `max_memory_mb` MiB.
    pub fn new(max_seconds: f64, max_memory_mb: u64) -> Budget {
        Budget {
            max_seconds,
            max_memory_bytes: max_memory_mb << 20,
        }
    }
    /// Starts the clock now.
    pub fn start(self) -> Deadline {
        Deadline {
            started: Instant::now(),
            budget: self,
            stated_seconds: self.max_seconds,
        }
    }
}

/// Which limit ran out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exhausted {
    /// The wall-clock budget (seconds allowed).
    Time(f64),
    /// The memory budget: the estimated bytes a step needed, and the bytes allowed.
    Memory {
        /// Estimated bytes of the step that was refused.
        needed: u64,
        /// Bytes allowed.
        allowed: u64,
    },
}

impl Eq for Exhausted {}

impl fmt::Display for Exhausted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Exhausted::Time(s) => write!(
                f,
                "the time budget of {s} s ran out (raise it with --max-seconds)"
            ),
            Exhausted::Memory { needed, allowed } => write!(
                f,
                "the next step needs about {} MiB, over the memory budget of {} MiB (raise it with --max-memory)",
                needed >> 20,
                allowed >> 20
            ),
        }
    }
}

/// A [`Budget`] started at an instant.
#[derive(Clone, Copy, Debug)]
pub struct Deadline {
    started: Instant,
    budget: Budget,
    /// The wall-clock budget as the caller stated it, which a [`Deadline::portion`] keeps
    /// and errors report.
    stated_seconds: f64,
}

impl Deadline {
    /// The limits.
    pub fn budget(&self) -> Budget {
        self.budget
    }
    /// The wall-clock budget the caller stated (a [`Deadline::portion`] keeps it).
    pub fn stated_seconds(&self) -> f64 {
        self.stated_seconds
    }
    /// Seconds since the start.
    pub fn elapsed(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }
    /// Seconds left of the wall-clock budget (0 once it has run out).
    pub fn remaining(&self) -> f64 {
        (self.budget.max_seconds - self.elapsed()).max(0.0)
    }
    /// The same start with `fraction` (in `(0, 1]`) of the wall-clock budget: a step that
    /// may stop early without starving the steps after it. Its errors still name the
    /// whole budget (the one a user can raise).
    pub fn portion(&self, fraction: f64) -> Deadline {
        Deadline {
            started: self.started,
            budget: Budget {
                max_seconds: self.budget.max_seconds * fraction.clamp(0.0, 1.0),
                ..self.budget
            },
            stated_seconds: self.stated_seconds,
        }
    }
    /// `Err` once the wall-clock budget has run out (reported as the budget the caller
    /// stated, also for a portion of it).
    pub fn check_time(&self) -> Result<(), Exhausted> {
        if self.elapsed() > self.budget.max_seconds {
            Err(Exhausted::Time(self.stated_seconds))
        } else {
            Ok(())
        }
    }
    /// `Err` if a step needing `bytes` (estimated) would pass the memory budget.
    pub fn check_memory(&self, bytes: u64) -> Result<(), Exhausted> {
        if bytes > self.budget.max_memory_bytes {
            Err(Exhausted::Memory {
                needed: bytes,
                allowed: self.budget.max_memory_bytes,
            })
        } else {
            Ok(())
        }
    }
    /// Both checks.
    pub fn check(&self, bytes: u64) -> Result<(), Exhausted> {
        self.check_time()?;
        self.check_memory(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_enforced() {
        let d = Budget::new(1000.0, 1).start();
        assert!(d.check_time().is_ok());
        assert!(d.check_memory(1 << 20).is_ok());
        let e = d.check_memory((1 << 20) + 1).unwrap_err();
        assert!(e.to_string().contains("--max-memory"));
        let d = Budget::new(0.0, 1).start();
        std::thread::sleep(std::time::Duration::from_millis(2));
        assert_eq!(d.check_time(), Err(Exhausted::Time(0.0)));
    }

    #[test]
    fn a_portion_runs_out_first_and_names_the_whole_budget() {
        let d = Budget::new(60.0, 1).start();
        let part = d.portion(1e-5);
        std::thread::sleep(std::time::Duration::from_millis(2));
        assert!(d.check_time().is_ok());
        assert_eq!(part.check_time(), Err(Exhausted::Time(60.0)));
        assert_eq!(part.stated_seconds(), 60.0);
    }
}
