//! Waiting for the other thread of a long program's run (`stats`, see `run_pieces_beside`)
//! by watching for a while before sleeping.
//!
//! The two threads hand each other a piece every tenth of a millisecond or so, and the one
//! that waits usually waits a few microseconds. Sleeping at each of those waits costs far
//! more than the wait: the sleeper's processor idles, and waking it takes a system call by
//! the other thread and an interrupt to the idle processor, which in a virtual machine goes
//! through the host (0.2–0.4 ms measured, up to a 4 ms tick when the host is busy). So a
//! waiting thread first watches, each thread having a processor of its own (`apart.rs`), and
//! sleeps only when the wait is a long one.

use std::sync::mpsc::{Receiver, RecvError, TryRecvError};
use std::time::{Duration, Instant};

/// How long a thread watches before it sleeps: longer than the other thread takes for a
/// piece, short enough that a thread left waiting (the other one was descheduled) gives its
/// processor back soon.
pub(crate) const WATCH: Duration = Duration::from_micros(500);

/// Polls between two looks at the clock.
const POLLS: u32 = 64;

/// Watches `ready` until it gives a value or [`WATCH`] has passed (`None`).
fn watch<T>(mut ready: impl FnMut() -> Option<T>) -> Option<T> {
    let start = Instant::now();
    loop {
        for _ in 0..POLLS {
            if let Some(value) = ready() {
                return Some(value);
            }
            std::hint::spin_loop();
        }
        if start.elapsed() >= WATCH {
            return None;
        }
    }
}

/// [`Receiver::recv`], watching before it sleeps.
pub(crate) fn recv<T>(from: &Receiver<T>) -> Result<T, RecvError> {
    let seen = watch(|| match from.try_recv() {
        Ok(value) => Some(Ok(value)),
        Err(TryRecvError::Disconnected) => Some(Err(RecvError)),
        Err(TryRecvError::Empty) => None,
    });
    seen.unwrap_or_else(|| from.recv())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;
    use std::sync::mpsc::{channel, sync_channel};

    /// A value sent while the receiver watches, one sent after it has gone to sleep, and a
    /// sender gone all come through as `Receiver::recv` gives them.
    #[test]
    fn recv_gives_what_a_blocking_receive_gives() {
        let (tx, rx) = channel::<u32>();
        let sender = std::thread::spawn(move || {
            tx.send(1).unwrap();
            std::thread::sleep(WATCH * 4);
            tx.send(2).unwrap();
        });
        assert_eq!(recv(&rx), Ok(1));
        assert_eq!(recv(&rx), Ok(2));
        sender.join().unwrap();
        assert_eq!(recv(&rx), Err(RecvError));
    }

    /// A ring already rung is heard at once; with the ringer gone, none comes.
    #[test]
    fn a_bell_is_heard_until_its_ringer_is_gone() {
        let (ring, bell) = sync_channel::<()>(1);
        ring.try_send(()).unwrap();
        assert_eq!(recv(&bell), Ok(()));
        drop(ring);
        assert_eq!(recv(&bell), Err(RecvError));
    }
}
