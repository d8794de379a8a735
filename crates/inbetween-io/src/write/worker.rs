//! The formatting thread behind [`super::FrameWriter`]: it formats the blocks it is sent, in
//! order, and hands each back with its bytes so the writer can write them in sequence.

use super::rows::{Fault, Frame, RowFormatter};
use std::io;

/// A block sent to the worker: frames, CSV track prefix, index of the first frame in its track;
/// a buffer to format into comes along and goes back with the result.
pub(super) type Job = (Vec<Frame>, Vec<u8>, usize, Vec<u8>);

/// A formatted block: its bytes, its frames (for reuse) and whether every frame could be
/// written (else the bytes are to be discarded).
pub(super) type Done = (Vec<u8>, Vec<Frame>, Result<(), Fault>);

/// The formatting thread: formats the blocks it is sent, in order.
pub(super) struct Worker {
    pub(super) jobs: std::sync::mpsc::Sender<Job>,
    pub(super) done: std::sync::mpsc::Receiver<Done>,
    handle: Option<std::thread::JoinHandle<()>>,
}

impl Worker {
    pub(super) fn spawn(mut rows: RowFormatter) -> Worker {
        let (jobs, inbox) = std::sync::mpsc::channel::<Job>();
        let (outbox, done) = std::sync::mpsc::channel();
        let handle = std::thread::spawn(move || {
            for (frames, track, start, mut out) in inbox {
                out.clear();
                let result = rows.rows(&mut out, &track, start, &frames);
                if outbox.send((out, frames, result)).is_err() {
                    break;
                }
            }
        });
        Worker {
            jobs,
            done,
            handle: Some(handle),
        }
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Closing the job channel ends the thread.
        let (closed, _) = std::sync::mpsc::channel();
        drop(std::mem::replace(&mut self.jobs, closed));
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

/// The error when the worker thread is gone.
pub(super) fn worker_gone() -> io::Error {
    io::Error::other("the formatting thread stopped")
}
