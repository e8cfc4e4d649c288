//! A derived word streamed to Python in chunks of text: the library writes
//! it (`driver::write_derived`, as `graftal derive` writes it to a pipe) on
//! a thread of its own into a channel of a few chunks, and each `next()`
//! takes one, so that a word larger than memory can be read through.

use crate::diagnostic;
use graftal::diagnostics::Diagnostic as Found;
use graftal::driver::{self, Compiled, RunOptions};
use pyo3::exceptions::PyStopIteration;
use pyo3::prelude::*;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex};

/// Chunks waiting in the channel: the writer runs this far ahead.
const CHUNKS_AHEAD: usize = 4;

/// What the writing thread sends.
enum Sent {
    Bytes(Vec<u8>),
    /// The word is written, or why not.
    Done(Result<(), Stop>),
}

/// Why the word was not written whole.
enum Stop {
    /// A limit, or an error of the model's program.
    Diagnostic(Box<Found>),
    /// A panic in the library.
    Panic,
}

/// The writer's end: each write is a chunk sent; a closed channel (the
/// iterator dropped) is a closed pipe, which ends the writing.
struct Channel(SyncSender<Sent>);

impl std::io::Write for Channel {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0
            .send(Sent::Bytes(buf.to_vec()))
            .map_err(|_| std::io::ErrorKind::BrokenPipe)?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The word's text, chunk by chunk (`Model.derive(stream=True)`): joined,
/// the chunks are `Model.derive()`'s string.
#[pyclass(module = "graftal")]
pub struct WordChunks {
    compiled: Arc<Compiled>,
    received: Mutex<Receiver<Sent>>,
    /// The chunk held back until the next arrives (the word's last
    /// newline is not part of it), and the bytes of a character cut at a
    /// chunk's end.
    held: Option<Vec<u8>>,
    finished: bool,
}

impl WordChunks {
    /// Starts writing the word of `c`'s system on a thread of its own.
    pub fn start(compiled: Arc<Compiled>, opts: RunOptions) -> PyResult<WordChunks> {
        let (send, received) = sync_channel(CHUNKS_AHEAD);
        let c = compiled.clone();
        std::thread::Builder::new()
            .name("graftal derive".into())
            .stack_size(crate::STACK_BYTES)
            .spawn(move || write_word(&c, &opts, send))?;
        Ok(WordChunks {
            compiled,
            received: Mutex::new(received),
            held: None,
            finished: false,
        })
    }

    /// The next message of the writer (the GIL released while it waits).
    fn receive(&self, py: Python<'_>) -> Sent {
        let received = &self.received;
        py.detach(|| {
            let r = received.lock().unwrap_or_else(|e| e.into_inner());
            r.recv().unwrap_or(Sent::Done(Ok(())))
        })
    }
}

/// Writes the word into `send`, then says how it went; a panic in the
/// library ends the word with an error.
fn write_word(c: &Compiled, opts: &RunOptions, send: SyncSender<Sent>) {
    let Some(sys) = &c.system else { return };
    let mut out = Channel(send.clone());
    let written = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        driver::write_derived(c.front, sys, opts, &mut out, |_, _| {})
    }));
    let done = match written {
        Ok(w) => w.map_err(|d| Stop::Diagnostic(Box::new(d))),
        Err(_) => Err(Stop::Panic),
    };
    let _ = send.send(Sent::Done(done));
}

#[pymethods]
impl WordChunks {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&mut self, py: Python<'_>) -> PyResult<String> {
        while !self.finished {
            match self.receive(py) {
                Sent::Bytes(bytes) => {
                    if let Some(ready) = self.held.replace(bytes).filter(|b| !b.is_empty()) {
                        return Ok(self.text_of(ready));
                    }
                }
                Sent::Done(Err(Stop::Diagnostic(d))) => {
                    self.finished = true;
                    let message = d.message.clone();
                    return Err(diagnostic::error(py, &[*d], &self.compiled, &message));
                }
                Sent::Done(Err(Stop::Panic)) => {
                    self.finished = true;
                    return Err(diagnostic::plain(
                        py,
                        "graftal stopped while writing the word",
                    ));
                }
                Sent::Done(Ok(())) => {
                    self.finished = true;
                    let mut last = self.held.take().unwrap_or_default();
                    if last.last() == Some(&b'\n') {
                        last.pop();
                    }
                    if !last.is_empty() {
                        return Ok(self.text_of(last));
                    }
                }
            }
        }
        Err(PyStopIteration::new_err(()))
    }
}

impl WordChunks {
    /// `bytes` as text: a character cut at the end waits for the next
    /// chunk (carried at the front of the one held).
    fn text_of(&mut self, mut bytes: Vec<u8>) -> String {
        let whole = match std::str::from_utf8(&bytes) {
            Ok(_) => bytes.len(),
            Err(e) if e.error_len().is_none() => e.valid_up_to(),
            Err(_) => bytes.len(),
        };
        let cut = bytes.split_off(whole);
        if let Some(next) = self.held.as_mut() {
            next.splice(0..0, cut);
        }
        String::from_utf8_lossy(&bytes).into_owned()
    }
}
