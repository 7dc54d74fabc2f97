//! Keys while streaming: the terminal in cbreak mode (keys arrive one by one,
//! without echo; output is left as it is so lines still end properly), a thread
//! reading standard input, and the keys' meanings. Only when standard input is a
//! terminal; the terminal is restored when [`Keys`] is dropped.

use std::io::{IsTerminal, Read};
use std::sync::mpsc::{Receiver, TryRecvError, channel};

/// What a key asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// `!` or space: feed hold.
    Hold,
    /// `~` or `c`: cycle start / resume.
    Resume,
    /// `x` or Ctrl-X: soft reset, abort at once.
    Reset,
    /// `q` or Ctrl-C: abort (feed hold, then soft reset once stopped).
    Quit,
}

/// The meaning of the key `byte`, if it has one.
pub fn key_of(byte: u8) -> Option<Key> {
    match byte {
        b'!' | b' ' => Some(Key::Hold),
        b'~' | b'c' | b'C' => Some(Key::Resume),
        b'x' | b'X' | 0x18 => Some(Key::Reset),
        b'q' | b'Q' | 0x03 => Some(Key::Quit),
        _ => None,
    }
}

/// The help line shown while streaming.
pub const HELP: &str = "keys: ! or space hold, ~ or c resume, x reset, q abort";

/// Keys from the terminal.
pub struct Keys {
    rx: Receiver<u8>,
    _mode: cbreak::Guard,
}

impl Keys {
    /// Starts reading keys, when standard input is a terminal that can be put in cbreak mode.
    pub fn open() -> Option<Keys> {
        if !std::io::stdin().is_terminal() {
            return None;
        }
        let mode = cbreak::Guard::enter()?;
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let mut byte = [0u8; 1];
            while let Ok(1) = std::io::stdin().read(&mut byte) {
                if tx.send(byte[0]).is_err() {
                    break;
                }
            }
        });
        Some(Keys { rx, _mode: mode })
    }

    /// The next key pressed with a meaning, if any.
    pub fn poll(&self) -> Option<Key> {
        loop {
            match self.rx.try_recv() {
                Ok(b) => {
                    if let Some(k) = key_of(b) {
                        return Some(k);
                    }
                }
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => return None,
            }
        }
    }
}

#[cfg(unix)]
mod cbreak {
    use std::os::fd::AsRawFd;

    use nix::sys::termios::{LocalFlags, SetArg, SpecialCharacterIndices, Termios, tcgetattr, tcsetattr};

    /// The terminal settings to restore.
    pub struct Guard {
        saved: Termios,
    }

    impl Guard {
        /// Switches standard input to cbreak mode (no line editing, no echo, no
        /// signals from Ctrl-C: it arrives as a key).
        pub fn enter() -> Option<Guard> {
            let fd = std::io::stdin().as_raw_fd();
            let saved = tcgetattr(fd).ok()?;
            let mut t = saved.clone();
            t.local_flags.remove(LocalFlags::ICANON | LocalFlags::ECHO | LocalFlags::ISIG);
            t.control_chars[SpecialCharacterIndices::VMIN as usize] = 1;
            t.control_chars[SpecialCharacterIndices::VTIME as usize] = 0;
            tcsetattr(fd, SetArg::TCSANOW, &t).ok()?;
            Some(Guard { saved })
        }
    }

    impl Drop for Guard {
        fn drop(&mut self) {
            let _ = tcsetattr(std::io::stdin().as_raw_fd(), SetArg::TCSANOW, &self.saved);
        }
    }
}

#[cfg(not(unix))]
mod cbreak {
    /// No key reading on this platform.
    pub struct Guard;

    impl Guard {
        /// Never available.
        pub fn enter() -> Option<Guard> {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_their_meanings() {
        assert_eq!(key_of(b' '), Some(Key::Hold));
        assert_eq!(key_of(b'!'), Some(Key::Hold));
        assert_eq!(key_of(b'~'), Some(Key::Resume));
        assert_eq!(key_of(b'c'), Some(Key::Resume));
        assert_eq!(key_of(0x18), Some(Key::Reset));
        assert_eq!(key_of(b'x'), Some(Key::Reset));
        assert_eq!(key_of(b'q'), Some(Key::Quit));
        assert_eq!(key_of(0x03), Some(Key::Quit));
        assert_eq!(key_of(b'a'), None);
    }
}
