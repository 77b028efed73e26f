//! What the tool says on the terminal besides its results: how much (`--quiet`,
//! `--verbose`) and a spinner on stderr while work runs for more than a second.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

/// 0: `--quiet` (warnings and errors only), 1: normal, 2: `--verbose`.
static LEVEL: AtomicU8 = AtomicU8::new(1);

/// Sets the level from the global flags.
pub fn set_level(quiet: bool, verbose: bool) {
    let level = match (quiet, verbose) {
        (true, _) => 0,
        (false, true) => 2,
        (false, false) => 1,
    };
    LEVEL.store(level, Ordering::Relaxed);
}

fn level() -> u8 {
    LEVEL.load(Ordering::Relaxed)
}

/// Whether `--verbose` was given.
pub fn verbose() -> bool {
    level() >= 2
}

/// A line on stderr about what was done (hidden by `--quiet`).
macro_rules! info {
    ($($arg:tt)*) => {
        if $crate::ui::shows_info() {
            eprintln!($($arg)*);
        }
    };
}
pub(crate) use info;

/// A line on stdout that is a summary, not data (hidden by `--quiet`); a closed pipe
/// (`| head`) drops it quietly.
macro_rules! say {
    ($($arg:tt)*) => {
        if $crate::ui::shows_info() {
            let _ = $crate::print_out(format_args!($($arg)*));
        }
    };
}
pub(crate) use say;

/// Whether [`info!`] and [`say!`] print.
pub fn shows_info() -> bool {
    level() >= 1
}

/// A spinner on stderr, shown once the work has taken a second, on a thread of its own
/// (nothing in the engine's loop): hidden when stderr is not a terminal and with
/// `--quiet`. It disappears when dropped.
pub struct Spinner {
    stop: Option<mpsc::Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl Spinner {
    /// Starts the clock for a spinner saying `message`.
    pub fn start(message: impl Into<String>) -> Spinner {
        if !shows_info() || !std::io::stderr().is_terminal() {
            return Spinner {
                stop: None,
                thread: None,
            };
        }
        let message = message.into();
        let (stop, stopped) = mpsc::channel::<()>();
        let thread = std::thread::spawn(move || {
            // Work done within a second shows nothing.
            if stopped.recv_timeout(Duration::from_secs(1)) != Err(mpsc::RecvTimeoutError::Timeout)
            {
                return;
            }
            let bar = indicatif::ProgressBar::new_spinner().with_message(message);
            bar.enable_steady_tick(Duration::from_millis(120));
            let _ = stopped.recv();
            bar.finish_and_clear();
        });
        Spinner {
            stop: Some(stop),
            thread: Some(thread),
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
