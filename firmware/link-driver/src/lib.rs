//! The firmware's link logic without any hardware: what its link tasks do between a
//! byte link (USART2, or USB CDC-ACM) and the controller, as plain code the host
//! tests with the real controller behind it.
//!
//! - [`held`]: the bytes a link received that the controller cannot take yet;
//!   offered again after every poll, with their real-time bytes picked out at once.
//! - [`packets`]: USB full-speed bulk packets both ways — a packet read only into
//!   room for a whole packet (the host is NAKed meanwhile, nothing is lost), the
//!   controller's output cut into packets and every transfer ended by a short or
//!   zero-length packet (a host holds a full packet back until one comes).
//! - [`select`]: which link the controller talks to — USB while a host has its
//!   port open, USART2 otherwise — and what a switch drops.
//! - [`usb`]: the USB device (one CDC-ACM port), for any embassy-usb driver.
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

pub mod held;
pub mod packets;
pub mod select;
pub mod usb;

/// The controller as the link tasks see it: bytes in, bytes out
/// ([`controller::Controller::receive`], [`controller::Controller::transmit`]).
pub trait Endpoint {
    /// Takes what it can of `bytes` (real-time bytes anywhere in them act now and are
    /// removed; what it leaves is moved to the end of `bytes`); how many it consumed.
    fn receive(&mut self, bytes: &mut [u8], now: u64) -> usize;
    /// Moves waiting output into `out`; how many bytes.
    fn transmit(&mut self, out: &mut [u8]) -> usize;
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Endpoint for controller::Controller<W, T, P, S> {
    fn receive(&mut self, bytes: &mut [u8], now: u64) -> usize {
        controller::Controller::receive(self, bytes, now)
    }

    fn transmit(&mut self, out: &mut [u8]) -> usize {
        controller::Controller::transmit(self, out)
    }
}
