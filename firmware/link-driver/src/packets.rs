//! USB full-speed bulk packets, both ways, for the CDC-ACM link.
//!
//! - In (host → board): a packet is read only when the held bytes have room for a
//!   whole one ([`has_room`], [`read`]). While the held bytes have less room the board does not read,
//!   the host controller is NAKed and retries: unlike a UART, nothing is lost, the
//!   sender just waits.
//! - Out (board → host): the controller's output goes out in packets of up to the
//!   endpoint's size ([`Output`]). A host's driver keeps a full-size packet back
//!   until the transfer ends with a shorter one (Linux's cdc-acm reads two packets'
//!   worth per request), so when the output runs out right after a full packet, a
//!   zero-length packet ends the transfer — else an `ok` of exactly the wrong
//!   length would sit in the PC until the next reply.

use crate::held::Held;

/// The endpoint went away (cable out, host reset or reconfigured the device).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Disconnected;

/// Largest packet of a full-speed bulk endpoint.
pub const MAX_PACKET: usize = 64;

// Async fns in these traits: the firmware's executor is single-threaded, nothing
// needs their futures to be `Send`.

/// A bulk OUT endpoint (host → board).
#[allow(async_fn_in_trait)]
pub trait PacketIn {
    /// The endpoint's packet size.
    fn max_packet_size(&self) -> usize;
    /// Waits for the next packet into `buf` (at least one packet long); its length.
    async fn read_packet(&mut self, buf: &mut [u8]) -> Result<usize, Disconnected>;
}

/// A bulk IN endpoint (board → host).
#[allow(async_fn_in_trait)]
pub trait PacketOut {
    /// The endpoint's packet size.
    fn max_packet_size(&self) -> usize;
    /// Sends one packet (at most one packet long; empty = a zero-length packet) when
    /// the host asks for it.
    async fn write_packet(&mut self, data: &[u8]) -> Result<(), Disconnected>;
}

/// One packet's bytes.
pub type Packet = [u8; MAX_PACKET];

/// Waits for the next packet from the host; its bytes. Read one only when the held
/// bytes have room for it ([`has_room`]): until then the host is NAKed and waits.
pub async fn read<'a, I: PacketIn>(inp: &mut I, packet: &'a mut Packet) -> Result<&'a [u8], Disconnected> {
    let n = inp.read_packet(packet).await?.min(MAX_PACKET);
    Ok(&packet[..n])
}

/// Whether `held` has room for a whole packet.
pub fn has_room<const N: usize>(held: &Held<N>) -> bool {
    held.room_len() >= MAX_PACKET
}

/// The controller's output as bulk IN transfers.
#[derive(Debug, Default)]
pub struct Output {
    /// The last packet sent was full-size: the transfer is still open.
    open: bool,
}

impl Output {
    /// No transfer open.
    pub const fn new() -> Self {
        Output { open: false }
    }

    /// Sends what `take` gives (it fills a buffer, returns how many bytes; 0 =
    /// nothing more now) packet by packet, then ends the transfer: with the last,
    /// short packet, or with a zero-length packet after a full one. Returns the
    /// bytes sent.
    pub async fn send<O: PacketOut>(
        &mut self,
        out: &mut O,
        mut take: impl FnMut(&mut [u8]) -> usize,
    ) -> Result<usize, Disconnected> {
        let size = out.max_packet_size().clamp(1, MAX_PACKET);
        let mut buf = [0u8; MAX_PACKET];
        let mut sent = 0;
        loop {
            let n = take(&mut buf[..size]).min(size);
            if n == 0 {
                break;
            }
            out.write_packet(&buf[..n]).await?;
            self.open = n == size;
            sent += n;
        }
        if self.open {
            out.write_packet(&[]).await?;
            self.open = false;
        }
        Ok(sent)
    }

    /// The host went away: whatever was open is gone.
    pub fn reset(&mut self) {
        self.open = false;
    }
}

#[cfg(test)]
mod tests {
    use std::collections::VecDeque;
    use std::vec;
    use std::vec::Vec;

    use embassy_futures::block_on;

    use super::*;

    struct Host {
        packets: Vec<Vec<u8>>,
        incoming: VecDeque<Vec<u8>>,
    }

    impl PacketOut for Host {
        fn max_packet_size(&self) -> usize {
            64
        }
        async fn write_packet(&mut self, data: &[u8]) -> Result<(), Disconnected> {
            assert!(data.len() <= 64);
            self.packets.push(data.to_vec());
            Ok(())
        }
    }

    impl PacketIn for Host {
        fn max_packet_size(&self) -> usize {
            64
        }
        async fn read_packet(&mut self, buf: &mut [u8]) -> Result<usize, Disconnected> {
            assert!(buf.len() >= 64, "a packet is read into room for a whole one");
            let p = self.incoming.pop_front().ok_or(Disconnected)?;
            buf[..p.len()].copy_from_slice(&p);
            Ok(p.len())
        }
    }

    fn source(mut bytes: &[u8]) -> impl FnMut(&mut [u8]) -> usize + '_ {
        move |buf| {
            let n = buf.len().min(bytes.len());
            buf[..n].copy_from_slice(&bytes[..n]);
            bytes = &bytes[n..];
            n
        }
    }

    fn lens(h: &Host) -> Vec<usize> {
        h.packets.iter().map(Vec::len).collect()
    }

    #[test]
    fn output_is_cut_into_packets_and_a_full_last_packet_is_followed_by_a_zero_length_one() {
        for (len, want) in [
            (0, vec![]),
            (4, vec![4]),
            (63, vec![63]),
            (64, vec![64, 0]),
            (100, vec![64, 36]),
            (128, vec![64, 64, 0]),
            (129, vec![64, 64, 1]),
        ] {
            let mut h = Host { packets: Vec::new(), incoming: VecDeque::new() };
            let data: Vec<u8> = (0..len).map(|i| i as u8).collect();
            let sent = block_on(Output::new().send(&mut h, source(&data))).unwrap();
            assert_eq!(sent, len);
            assert_eq!(lens(&h), want, "{len} bytes");
            assert_eq!(h.packets.concat(), data);
        }
    }

    #[test]
    fn a_packet_is_read_only_into_room_for_a_whole_one() {
        let mut h = Host { packets: Vec::new(), incoming: VecDeque::from([vec![b'a'; 64], vec![b'b'; 10]]) };
        let mut held = Held::<100>::new();
        let mut packet = [0; MAX_PACKET];
        assert!(has_room(&held));
        let got = block_on(read(&mut h, &mut packet)).unwrap();
        assert_eq!(held.push(got), 64);
        assert!(!has_room(&held), "36 bytes of room: the next packet waits at the host");
        assert_eq!(h.incoming.len(), 1);
    }
}
