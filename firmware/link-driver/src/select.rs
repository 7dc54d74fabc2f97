//! Which link the controller talks to. The board has two: USART2 (115,200 baud, an
//! RS-232 or USB-serial cable) and its own USB port (CDC-ACM, full speed). One
//! controller is behind both and speaks the same protocol on either, but one sender
//! at a time: its lines, its replies.
//!
//! The rule: USB while a host has the USB port open — terminal programs and grbl
//! senders set DTR when they open a serial port, and clear it (or the cable goes)
//! when they close it — USART2 otherwise. Bytes from the other link are dropped.
//! At a switch the controller's waiting output is dropped (it answered the other
//! link's sender), and a host that opens the USB port is greeted with the welcome
//! line, as grbl greets a sender that opens its port.

use crate::Endpoint;

/// A link of the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Link {
    /// USART2.
    Uart,
    /// USB CDC-ACM.
    Usb,
}

/// The link the controller talks to (see the module documentation).
#[derive(Debug, Default)]
pub struct Selector {
    usb_open: bool,
}

impl Selector {
    /// USART2 until a USB host opens the port.
    pub const fn new() -> Self {
        Selector { usb_open: false }
    }

    /// The link the controller talks to.
    pub fn active(&self) -> Link {
        if self.usb_open { Link::Usb } else { Link::Uart }
    }

    /// The USB host opened (DTR set) or closed the port (DTR cleared, cable out,
    /// bus reset). The new link if that changed it.
    pub fn usb_port(&mut self, open: bool) -> Option<Link> {
        let before = self.active();
        self.usb_open = open;
        let now = self.active();
        (now != before).then_some(now)
    }
}

/// Drops the controller's waiting output; how many bytes.
pub fn drop_output<E: Endpoint + ?Sized>(e: &mut E) -> usize {
    let mut scratch = [0u8; 64];
    let mut dropped = 0;
    loop {
        let n = e.transmit(&mut scratch);
        if n == 0 {
            return dropped;
        }
        dropped += n;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usb_while_its_port_is_open_usart2_otherwise() {
        let mut s = Selector::new();
        assert_eq!(s.active(), Link::Uart);
        assert_eq!(s.usb_port(false), None);
        assert_eq!(s.usb_port(true), Some(Link::Usb));
        assert_eq!(s.usb_port(true), None);
        assert_eq!(s.active(), Link::Usb);
        assert_eq!(s.usb_port(false), Some(Link::Uart));
    }
}
