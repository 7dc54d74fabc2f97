//! The board's USB link on the host: the real controller (`controller::Board`) and
//! motion core behind the link driver's packet logic — a packet read only into room
//! for a whole one, held bytes offered after every poll, output cut into packets
//! with a zero-length packet after a full last one — and in front of it a PC: a USB
//! host that moves at most 19 bulk packets each way per 1 ms frame (full speed),
//! whose serial driver hands received bytes to the sender only when a transfer ends
//! (a short packet, or 128 bytes: Linux cdc-acm's two-packet read), and a grbl
//! sender, with or without character counting.

use std::collections::VecDeque;

use controller::{Inputs, WELCOME};
use embassy_futures::block_on;
use interp_core::MachineConfig;
use interp_core::axis::Pos;
use link_driver::Endpoint;
use link_driver::held::Held;
use link_driver::packets::{Disconnected, MAX_PACKET, Output, PacketIn, PacketOut, has_room, read};
use link_driver::select::{Link, Selector, drop_output};
use motion_core::motion::{Feedback, MotionCore};

/// Bulk packets a full-speed host moves per 1 ms frame, each way (19 × 64 bytes).
const PACKETS_PER_FRAME: usize = 19;
/// The firmware's held bytes (`HELD` in firmware/src/main.rs).
const HELD: usize = 512;
/// A sender's character-counting window: the controller's receive buffer.
const WINDOW: usize = controller::RX;

/// The PC's side of the bulk endpoints.
#[derive(Default)]
struct Pc {
    /// Bytes the sender wrote, not yet in a packet.
    to_board: VecDeque<u8>,
    /// Packets sent this frame.
    out_this_frame: usize,
    /// The read request being filled (cdc-acm: two packets' worth).
    urb: Vec<u8>,
    /// Bytes the sender has read.
    from_board: Vec<u8>,
    /// Full-size packets followed by nothing for a whole frame (a transfer left open).
    stuck: usize,
    /// Packets received (for the record).
    packets_in: usize,
}

impl PacketIn for Pc {
    fn max_packet_size(&self) -> usize {
        MAX_PACKET
    }

    async fn read_packet(&mut self, buf: &mut [u8]) -> Result<usize, Disconnected> {
        assert!(buf.len() >= MAX_PACKET);
        let n = self.to_board.len().min(MAX_PACKET);
        for (slot, b) in buf.iter_mut().zip(self.to_board.drain(..n)) {
            *slot = b;
        }
        self.out_this_frame += 1;
        Ok(n)
    }
}

impl PacketOut for Pc {
    fn max_packet_size(&self) -> usize {
        MAX_PACKET
    }

    async fn write_packet(&mut self, data: &[u8]) -> Result<(), Disconnected> {
        assert!(data.len() <= MAX_PACKET);
        self.packets_in += 1;
        self.urb.extend_from_slice(data);
        if data.len() < MAX_PACKET || self.urb.len() >= 2 * MAX_PACKET {
            self.from_board.append(&mut self.urb);
        }
        Ok(())
    }
}

/// The board: controller, motion core, the USB link's held bytes and output.
struct Board {
    ctl: Box<controller::Board>,
    core: Box<MotionCore<64>>,
    held: Held<HELD>,
    output: Output,
    now: u64,
}

impl Board {
    fn new() -> Self {
        let cfg = MachineConfig::default();
        let core = Box::new(MotionCore::new(&cfg, Pos::ZERO).expect("machine"));
        let ctl = Box::new(controller::Board::new(cfg, Pos::ZERO));
        Board { ctl, core, held: Held::new(), output: Output::new(), now: 0 }
    }

    /// One millisecond: the host's OUT packets while the held bytes have room for
    /// them (each offered to the controller as it comes, as the receive task does),
    /// the control task's poll and period, the held bytes offered again, the output.
    fn frame(&mut self, pc: &mut Pc) {
        pc.out_this_frame = 0;
        let mut packet = [0; MAX_PACKET];
        while !pc.to_board.is_empty() && pc.out_this_frame < PACKETS_PER_FRAME && has_room(&self.held) {
            let got = block_on(read(pc, &mut packet)).expect("connected");
            assert_eq!(self.held.push(got), got.len());
            self.held.offer(&mut *self.ctl, self.now);
        }
        self.ctl.poll(self.now, &mut *self.core, &mut (), Inputs::default());
        self.core.tick(self.now, Feedback::default());
        for axis in 0..4 {
            while self.core.next_step(axis, self.now + 1_000_000).is_some() {}
        }
        self.held.offer(&mut *self.ctl, self.now);
        let urb_before = pc.urb.len();
        let ctl = &mut self.ctl;
        block_on(self.output.send(pc, |buf| ctl.transmit(buf))).expect("connected");
        if !pc.urb.is_empty() && pc.urb.len() == urb_before {
            pc.stuck += 1;
        }
        self.now += 1_000_000;
    }
}

/// Lines the sender has read.
fn take_lines(pc: &mut Pc) -> Vec<String> {
    let mut lines = Vec::new();
    while let Some(i) = pc.from_board.windows(2).position(|w| w == b"\r\n") {
        lines.push(String::from_utf8_lossy(&pc.from_board[..i]).into_owned());
        pc.from_board.drain(..i + 2);
    }
    lines
}

/// What a streamed program did.
struct Streamed {
    oks: usize,
    seconds: f64,
    blocks: u64,
    starvations: u32,
}

/// Streams `program` with grbl character counting until M30 has run and the
/// machine rests; panics on an error, an alarm, or a line never answered.
fn stream(board: &mut Board, pc: &mut Pc, program: &[String]) -> Streamed {
    let (mut next, mut in_flight, mut oks, mut ended) = (0, VecDeque::<usize>::new(), 0, false);
    let start = board.now;
    let mut quiet = 0;
    while !(ended && board.core.is_idle()) {
        while let Some(line) = program.get(next) {
            let n = line.len() + 1;
            if in_flight.iter().sum::<usize>() + n > WINDOW {
                break;
            }
            pc.to_board.extend(line.as_bytes());
            pc.to_board.push_back(b'\n');
            in_flight.push_back(n);
            next += 1;
        }
        board.frame(pc);
        let lines = take_lines(pc);
        quiet = if lines.is_empty() { quiet + 1 } else { 0 };
        assert!(quiet < 5_000, "no reply for 5 s: {} of {} lines answered", oks, program.len());
        for l in lines {
            assert!(!l.starts_with("error") && !l.starts_with("ALARM"), "{l}");
            if l == "ok" {
                in_flight.pop_front().expect("an ok for a line sent");
                oks += 1;
            }
            ended |= l == "[MSG:Pgm End]";
        }
    }
    let st = board.core.stats();
    Streamed { oks, seconds: (board.now - start) as f64 / 1e9, blocks: st.blocks, starvations: st.starvations }
}

fn program(block: &str, count: usize) -> Vec<String> {
    let mut p = vec!["G98 G00 X20 Z0".to_string()];
    p.extend(std::iter::repeat_n(block.to_string(), count));
    p.push("M30".into());
    p
}

#[test]
fn a_program_streamed_over_usb_runs_to_its_end_every_line_ok_and_the_planner_never_empty() {
    let (mut board, mut pc) = (Board::new(), Pc::default());
    board.frame(&mut pc);
    assert_eq!(take_lines(&mut pc), [WELCOME]);
    let p = program("G01 W-0.050 F3000", 3_000);
    let r = stream(&mut board, &mut pc, &p);
    assert_eq!(r.oks, p.len());
    assert_eq!(r.blocks, 3_001, "the rapid and every G01");
    // The period consumes one block per millisecond: 3,001 blocks need 3 s at least.
    let rate = r.blocks as f64 / r.seconds;
    assert!(rate > 650.0, "{rate:.0} blocks/s");
    assert_eq!(r.starvations, 0, "the planner ran empty while streaming");
    assert_eq!(pc.stuck, 0, "a full packet waited in the PC for the end of its transfer");
    eprintln!("usb: {} blocks of 0.05 mm in {:.2} s: {rate:.0} blocks/s, planner empty {} times", r.blocks, r.seconds, r.starvations);
}

#[test]
fn lines_that_queue_no_motion_go_over_usb_as_fast_as_the_controller_takes_them() {
    let (mut board, mut pc) = (Board::new(), Pc::default());
    board.frame(&mut pc);
    take_lines(&mut pc);
    let mut p = vec!["#1=0".to_string()];
    p.extend((0..4_000).map(|i| format!("#1=#1+{}", i % 7)));
    p.push("M30".into());
    let r = stream(&mut board, &mut pc, &p);
    assert_eq!(r.oks, p.len());
    let rate = r.oks as f64 / r.seconds;
    let limit = (controller::LINES_PER_POLL * 1_000) as f64;
    eprintln!("usb: {} macro lines in {:.2} s: {rate:.0} lines/s (the controller takes {limit:.0}/s)", r.oks, r.seconds);
    // With character counting the sender keeps 128 bytes in flight and USB returns
    // every `ok` within its frame: the controller's lines per poll are the limit.
    assert!(rate > 0.9 * limit, "{rate:.0} lines/s");
}

#[test]
fn a_status_poll_behind_a_burst_of_jogs_is_answered_at_once_and_no_jog_is_lost() {
    let (mut board, mut pc) = (Board::new(), Pc::default());
    board.frame(&mut pc);
    take_lines(&mut pc);
    // 100 jogs of 60 ms (0.1 mm on the diameter at F50), no character counting:
    // 1,500 bytes; the planner takes 64, the receive buffer 8, the held bytes 34,
    // the rest waits at the PC (NAKed), then a `?`.
    let jog = b"$J=G91 X0.1 F50\n";
    for _ in 0..100 {
        pc.to_board.extend(jog);
    }
    pc.to_board.push_back(b'?');
    let (mut oks, mut report_after, mut frames) = (0, None, 0);
    while oks < 100 {
        board.frame(&mut pc);
        frames += 1;
        assert!(frames < 20_000, "{oks} of 100 jogs answered");
        for l in take_lines(&mut pc) {
            match l.as_str() {
                "ok" => oks += 1,
                _ if l.starts_with("<Jog|") => {
                    assert!(report_after.is_none(), "answered twice");
                    report_after = Some((oks, frames));
                }
                _ => panic!("{l}"),
            }
        }
    }
    let (before, at) = report_after.expect("the `?` was answered");
    // The `?` crossed the PC's queue behind 1,500 bytes as the board made room, and
    // was answered when it reached the held bytes — not after the jogs ahead of it.
    assert!(before < 100, "answered after {before} ok: it waited for the jogs ahead of it");
    assert!(at < 100 * 60 / 2, "answered in frame {at}");
    assert!(pc.to_board.is_empty());
}

#[test]
fn a_host_opening_the_usb_port_takes_the_controller_from_usart2_and_is_greeted() {
    let mut board = Board::new();
    let mut sel = Selector::new();
    let mut usart = Pc::default();
    // Lines over USART2: the controller answers there.
    assert_eq!(sel.active(), Link::Uart);
    board.frame(&mut usart);
    board.held.push(b"G98\nG00 X10\n");
    board.held.offer(&mut *board.ctl, 0);
    board.ctl.poll(0, &mut *board.core, &mut (), Inputs::default());
    assert!(board.ctl.pending_output() > 0);
    // A host opens the USB port: the answers meant for USART2 are dropped, the held
    // bytes of USART2 with them, and the host is greeted.
    assert_eq!(sel.usb_port(true), Some(Link::Usb));
    assert!(drop_output(&mut *board.ctl) > 0);
    board.held.clear();
    let mut pc = Pc::default();
    let greeting = [WELCOME.as_bytes(), b"\r\n"].concat();
    let mut g = &greeting[..];
    block_on(board.output.send(&mut pc, |buf| {
        let n = buf.len().min(g.len());
        buf[..n].copy_from_slice(&g[..n]);
        g = &g[n..];
        n
    }))
    .expect("connected");
    assert_eq!(take_lines(&mut pc), [WELCOME]);
    let r = stream(&mut board, &mut pc, &program("G01 W-0.500 F3000", 20));
    assert_eq!(r.oks, 22);
    // The host closes the port: USART2 again.
    assert_eq!(sel.usb_port(false), Some(Link::Uart));
    assert_eq!(board.ctl.transmit(&mut [0; 64]), 0);
}

#[test]
fn the_endpoint_trait_is_the_controller() {
    let mut board = Board::new();
    let mut out = [0u8; 64];
    let n = Endpoint::transmit(&mut *board.ctl, &mut out);
    assert_eq!(&out[..n], [WELCOME.as_bytes(), b"\r\n"].concat().as_slice());
}

#[test]
fn a_reply_that_fills_its_last_packet_reaches_the_sender_in_the_same_frame() {
    let (mut board, mut pc) = (Board::new(), Pc::default());
    board.frame(&mut pc);
    take_lines(&mut pc);
    // `$N` answers "$N0=<block>", "$N1=", "ok": 16 bytes besides the block; a
    // 48-character startup block makes the whole answer exactly one packet.
    let block = "G21 G97 G98 G40 (STARTUP BLOCK OF 48 BYTES.....)";
    assert_eq!(block.len(), 48);
    pc.to_board.extend(format!("$N0={block}\n").as_bytes());
    for _ in 0..3 {
        board.frame(&mut pc);
    }
    assert_eq!(take_lines(&mut pc), ["ok"]);
    pc.to_board.extend(b"$N\n");
    board.frame(&mut pc);
    let reply = take_lines(&mut pc);
    assert_eq!(reply, [format!("$N0={block}"), "$N1=".to_string(), "ok".to_string()]);
    assert_eq!(reply.iter().map(|l| l.len() + 2).sum::<usize>(), MAX_PACKET);
    assert_eq!(pc.stuck, 0);
}
