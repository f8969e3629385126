//! Keeping the two threads of a long program's run (`stats`, see `run_pieces_beside`) on
//! processors of their own.
//!
//! Left to itself, the Linux scheduler often wakes the reading thread on the processor of the
//! thread that woke it, and the two then take turns on one processor while the other idles,
//! until the load balancer moves one of them: 1 to 3 ms of a 15 ms run were measured that way
//! on a two-processor machine. So the running thread is kept on the processor it is on and the
//! reading thread off it for as long as the two work side by side. Elsewhere than Linux, and
//! where fewer than two processors are allowed, nothing is done.

/// The processors of a run on two threads: the one the thread that made this is on, for it,
/// and the others it may use, for the reading thread.
pub(crate) struct Apart {
    #[cfg(target_os = "linux")]
    sets: Option<Sets>,
}

/// The allowed processors, the one kept by the running thread and the others.
#[cfg(target_os = "linux")]
struct Sets {
    all: rustix::thread::CpuSet,
    here: rustix::thread::CpuSet,
    away: rustix::thread::CpuSet,
}

/// Where the reading thread may run: every allowed processor but the running thread's.
pub(crate) struct Away {
    #[cfg(target_os = "linux")]
    set: Option<rustix::thread::CpuSet>,
}

impl Apart {
    /// The processors of the calling thread's run: it keeps the one it is on now.
    pub(crate) fn new() -> Self {
        #[cfg(target_os = "linux")]
        {
            use rustix::thread::{CpuSet, sched_getaffinity, sched_getcpu};
            let sets = sched_getaffinity(None).ok().and_then(|all| {
                let cpu = sched_getcpu();
                if all.count() < 2 || !all.is_set(cpu) {
                    return None;
                }
                let mut here = CpuSet::new();
                here.set(cpu);
                let mut away = all;
                away.unset(cpu);
                Some(Sets { all, here, away })
            });
            Apart { sets }
        }
        #[cfg(not(target_os = "linux"))]
        Apart {}
    }

    /// Where the reading thread is to run (it calls [`Away::go`]).
    pub(crate) fn away(&self) -> Away {
        #[cfg(target_os = "linux")]
        return Away {
            set: self.sets.as_ref().map(|sets| sets.away),
        };
        #[cfg(not(target_os = "linux"))]
        Away {}
    }

    /// Keeps the calling thread (the one that made this) on its processor. Best effort: a
    /// system that refuses leaves the thread where the scheduler puts it.
    pub(crate) fn stay(&self) {
        #[cfg(target_os = "linux")]
        if let Some(sets) = &self.sets {
            let _ = rustix::thread::sched_setaffinity(None, &sets.here);
        }
    }

    /// Lets the calling thread run on every processor it could before [`Apart::stay`].
    pub(crate) fn release(&self) {
        #[cfg(target_os = "linux")]
        if let Some(sets) = &self.sets {
            let _ = rustix::thread::sched_setaffinity(None, &sets.all);
        }
    }
}

impl Away {
    /// Moves the calling thread off the running thread's processor (best effort).
    pub(crate) fn go(&self) {
        #[cfg(target_os = "linux")]
        if let Some(set) = &self.set {
            let _ = rustix::thread::sched_setaffinity(None, set);
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// The two threads end on different processors, and the running thread may run anywhere
    /// again once it lets go.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_threads_keep_apart_and_the_runner_is_let_go() {
        use rustix::thread::{sched_getaffinity, sched_getcpu};
        let before = sched_getaffinity(None).unwrap();
        let apart = Apart::new();
        if before.count() < 2 {
            assert!(apart.sets.is_none());
            return;
        }
        apart.stay();
        let here = sched_getaffinity(None).unwrap();
        assert_eq!(here.count(), 1);
        let away = apart.away();
        let there = std::thread::spawn(move || {
            away.go();
            (sched_getaffinity(None).unwrap(), sched_getcpu())
        })
        .join()
        .unwrap();
        assert_eq!(there.0.count(), before.count() - 1);
        assert!(!there.0.is_set(sched_getcpu()));
        assert_ne!(there.1, sched_getcpu());
        apart.release();
        assert_eq!(sched_getaffinity(None).unwrap(), before);
    }
}
