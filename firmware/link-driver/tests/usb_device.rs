//! The board's USB device (`link_driver::usb`: embassy-usb's device and CDC-ACM
//! class, sized as the firmware builds them) on a simulated USB driver, driven by a
//! simulated host: enumeration as an OS does it (descriptors, address,
//! configuration), the port opened as a terminal or grbl sender opens it (line
//! coding, DTR), then traffic through the bulk endpoints to the real controller
//! behind the link driver — the firmware's `usb_rx`/`usb_tx` tasks in miniature.
//! What the board's OTG_FS hardware does (signalling, FIFOs) is not here: the
//! descriptors, the class requests, the packet rules and the link logic are.

use std::cell::RefCell;
use std::collections::{HashMap, VecDeque};
use std::future::poll_fn;
use std::rc::Rc;
use std::task::Poll;

use controller::Inputs;
use embassy_futures::block_on;
use embassy_futures::select::{Either, select};
use embassy_usb::driver::{
    Bus, ControlPipe, Direction, Driver, Endpoint, EndpointAddress, EndpointAllocError, EndpointError, EndpointIn,
    EndpointInfo, EndpointOut, EndpointType, Event, Unsupported,
};
use interp_core::MachineConfig;
use interp_core::axis::Pos;
use link_driver::held::Held;
use link_driver::packets::{MAX_PACKET, Output, has_room, read};
use link_driver::select::{Link, Selector, drop_output};
use link_driver::usb::{Buffers, PID, PRODUCT, VID, build};
use motion_core::motion::{Feedback, MotionCore};

/// What happened to a control transfer.
#[derive(Debug, PartialEq)]
enum Status {
    Accepted,
    Rejected,
    DataIn(Vec<u8>),
}

/// The wire between the simulated host and the simulated device controller.
#[derive(Default)]
struct Wire {
    events: VecDeque<Event>,
    setups: VecDeque<[u8; 8]>,
    out_stage: VecDeque<Vec<u8>>,
    in_stage: Vec<u8>,
    status: VecDeque<Status>,
    address: u8,
    /// (endpoint index, IN?) → enabled.
    enabled: HashMap<(usize, bool), bool>,
    /// Host → device packets per OUT endpoint index.
    to_device: HashMap<usize, VecDeque<Vec<u8>>>,
    /// Device → host packets per IN endpoint index.
    to_host: HashMap<usize, Vec<Vec<u8>>>,
}

type Shared = Rc<RefCell<Wire>>;

/// Waits until `f` gives a value (the simulation polls; every future here is
/// re-polled at once).
async fn until<T>(w: &Shared, mut f: impl FnMut(&mut Wire) -> Option<T>) -> T {
    poll_fn(|cx| match f(&mut w.borrow_mut()) {
        Some(v) => Poll::Ready(v),
        None => {
            cx.waker().wake_by_ref();
            Poll::Pending
        }
    })
    .await
}

struct SimDriver {
    w: Shared,
    next: [usize; 2],
}

struct SimBus(Shared);
struct SimControl(Shared);
struct SimOut(Shared, EndpointInfo);
struct SimIn(Shared, EndpointInfo);

impl SimDriver {
    fn alloc(&mut self, dir: Direction, ep_type: EndpointType, max_packet_size: u16, interval_ms: u8) -> EndpointInfo {
        let slot = &mut self.next[usize::from(dir == Direction::In)];
        *slot += 1;
        EndpointInfo { addr: EndpointAddress::from_parts(*slot, dir), ep_type, max_packet_size, interval_ms }
    }
}

impl<'a> Driver<'a> for SimDriver {
    type EndpointOut = SimOut;
    type EndpointIn = SimIn;
    type ControlPipe = SimControl;
    type Bus = SimBus;

    fn alloc_endpoint_out(
        &mut self,
        ep_type: EndpointType,
        _addr: Option<EndpointAddress>,
        max_packet_size: u16,
        interval_ms: u8,
    ) -> Result<SimOut, EndpointAllocError> {
        let info = self.alloc(Direction::Out, ep_type, max_packet_size, interval_ms);
        Ok(SimOut(self.w.clone(), info))
    }

    fn alloc_endpoint_in(
        &mut self,
        ep_type: EndpointType,
        _addr: Option<EndpointAddress>,
        max_packet_size: u16,
        interval_ms: u8,
    ) -> Result<SimIn, EndpointAllocError> {
        let info = self.alloc(Direction::In, ep_type, max_packet_size, interval_ms);
        Ok(SimIn(self.w.clone(), info))
    }

    fn start(self, control_max_packet_size: u16) -> (SimBus, SimControl) {
        assert_eq!(control_max_packet_size, 64);
        (SimBus(self.w.clone()), SimControl(self.w))
    }
}

impl Bus for SimBus {
    async fn enable(&mut self) {}
    async fn disable(&mut self) {}
    async fn poll(&mut self) -> Event {
        let e = until(&self.0, |w| w.events.pop_front()).await;
        if matches!(e, Event::Reset) {
            // A bus reset deconfigures the device: the controller disables every
            // endpoint but EP0 (the OTG core does it in hardware).
            self.0.borrow_mut().enabled.clear();
        }
        e
    }
    fn endpoint_set_enabled(&mut self, ep: EndpointAddress, enabled: bool) {
        self.0.borrow_mut().enabled.insert((ep.index(), ep.is_in()), enabled);
    }
    fn endpoint_set_stalled(&mut self, _ep: EndpointAddress, _stalled: bool) {}
    fn endpoint_is_stalled(&mut self, _ep: EndpointAddress) -> bool {
        false
    }
    async fn remote_wakeup(&mut self) -> Result<(), Unsupported> {
        Err(Unsupported)
    }
}

impl ControlPipe for SimControl {
    fn max_packet_size(&self) -> usize {
        64
    }
    async fn setup(&mut self) -> [u8; 8] {
        until(&self.0, |w| w.setups.pop_front()).await
    }
    async fn data_out(&mut self, buf: &mut [u8], _first: bool, _last: bool) -> Result<usize, EndpointError> {
        let data = until(&self.0, |w| w.out_stage.pop_front()).await;
        buf[..data.len()].copy_from_slice(&data);
        Ok(data.len())
    }
    async fn data_in(&mut self, data: &[u8], _first: bool, last: bool) -> Result<(), EndpointError> {
        assert!(data.len() <= 64);
        let mut w = self.0.borrow_mut();
        w.in_stage.extend_from_slice(data);
        if last {
            let all = std::mem::take(&mut w.in_stage);
            w.status.push_back(Status::DataIn(all));
        }
        Ok(())
    }
    async fn accept(&mut self) {
        self.0.borrow_mut().status.push_back(Status::Accepted);
    }
    async fn reject(&mut self) {
        self.0.borrow_mut().status.push_back(Status::Rejected);
    }
    async fn accept_set_address(&mut self, addr: u8) {
        let mut w = self.0.borrow_mut();
        w.address = addr;
        w.status.push_back(Status::Accepted);
    }
}

fn enabled(w: &Wire, info: &EndpointInfo) -> bool {
    w.enabled.get(&(info.addr.index(), info.addr.is_in())).copied().unwrap_or(false)
}

impl Endpoint for SimOut {
    fn info(&self) -> &EndpointInfo {
        &self.1
    }
    async fn wait_enabled(&mut self) {
        let info = self.1;
        until(&self.0, |w| enabled(w, &info).then_some(())).await;
    }
}

impl EndpointOut for SimOut {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, EndpointError> {
        let info = self.1;
        let p = until(&self.0, |w| {
            if !enabled(w, &info) {
                return Some(Err(EndpointError::Disabled));
            }
            w.to_device.get_mut(&info.addr.index()).and_then(VecDeque::pop_front).map(Ok)
        })
        .await?;
        assert!(p.len() <= usize::from(info.max_packet_size) && p.len() <= buf.len());
        buf[..p.len()].copy_from_slice(&p);
        Ok(p.len())
    }
}

impl Endpoint for SimIn {
    fn info(&self) -> &EndpointInfo {
        &self.1
    }
    async fn wait_enabled(&mut self) {
        let info = self.1;
        until(&self.0, |w| enabled(w, &info).then_some(())).await;
    }
}

impl EndpointIn for SimIn {
    async fn write(&mut self, buf: &[u8]) -> Result<(), EndpointError> {
        assert!(buf.len() <= usize::from(self.1.max_packet_size));
        let mut w = self.0.borrow_mut();
        if !enabled(&w, &self.1) {
            return Err(EndpointError::Disabled);
        }
        w.to_host.entry(self.1.addr.index()).or_default().push(buf.to_vec());
        Ok(())
    }
}

/// The host side: control transfers.
async fn control_in(w: &Shared, setup: [u8; 8]) -> Vec<u8> {
    w.borrow_mut().setups.push_back(setup);
    match until(w, |w| w.status.pop_front()).await {
        Status::DataIn(data) => data,
        s => panic!("{setup:02x?}: {s:?}"),
    }
}

async fn control_out(w: &Shared, setup: [u8; 8], data: &[u8]) {
    if !data.is_empty() {
        w.borrow_mut().out_stage.push_back(data.to_vec());
    }
    w.borrow_mut().setups.push_back(setup);
    let s = until(w, |w| w.status.pop_front()).await;
    assert_eq!(s, Status::Accepted, "{setup:02x?}");
}

fn get_descriptor(kind: u8, index: u8, lang: u16, len: u16) -> [u8; 8] {
    let [l0, l1] = lang.to_le_bytes();
    let [n0, n1] = len.to_le_bytes();
    [0x80, 6, index, kind, l0, l1, n0, n1]
}

/// A descriptor's parts: (type, bytes).
fn parts(mut d: &[u8]) -> Vec<(u8, Vec<u8>)> {
    let mut v = Vec::new();
    while let [len, kind, ..] = *d {
        v.push((kind, d[..usize::from(len)].to_vec()));
        d = &d[usize::from(len)..];
    }
    v
}

/// Enumerates the device as an OS does and checks what it describes; returns the
/// communication interface's number and the bulk endpoints (OUT, IN) indices.
async fn enumerate(w: &Shared) -> (u8, usize, usize) {
    w.borrow_mut().events.extend([Event::PowerDetected, Event::Reset]);
    let dev = control_in(w, get_descriptor(1, 0, 0, 64)).await;
    assert_eq!(dev.len(), 18);
    assert_eq!((dev[4], dev[5], dev[6], dev[7]), (0xEF, 0x02, 0x01, 64), "IAD class triple, EP0 64 bytes");
    assert_eq!(u16::from_le_bytes([dev[8], dev[9]]), VID);
    assert_eq!(u16::from_le_bytes([dev[10], dev[11]]), PID);
    control_out(w, [0, 5, 7, 0, 0, 0, 0, 0], &[]).await;
    assert_eq!(w.borrow().address, 7);
    let head = control_in(w, get_descriptor(2, 0, 0, 9)).await;
    let total = u16::from_le_bytes([head[2], head[3]]);
    let config = control_in(w, get_descriptor(2, 0, 0, total)).await;
    assert_eq!(config.len(), usize::from(total));
    assert!(config.len() <= 96, "the firmware's 96-byte configuration descriptor buffer");
    assert_eq!(config[4], 2, "two interfaces");
    assert_eq!(config[7] & 0x40, 0x40, "self-powered");
    assert_eq!(config[8], 50, "100 mA");
    let p = parts(&config);
    assert!(p.iter().any(|(k, _)| *k == 0x0B), "an interface association");
    let comm = p.iter().find(|(k, d)| *k == 4 && d[5] == 0x02 && d[6] == 0x02).expect("a CDC-ACM interface").1[2];
    assert!(p.iter().any(|(k, d)| *k == 4 && d[5] == 0x0A), "a CDC data interface");
    let bulk: Vec<&Vec<u8>> = p.iter().filter(|(k, d)| *k == 5 && d[3] == 2).map(|(_, d)| d).collect();
    assert_eq!(bulk.len(), 2);
    assert!(bulk.iter().all(|d| u16::from_le_bytes([d[4], d[5]]) == 64), "64-byte bulk packets");
    let out_ep = bulk.iter().find(|d| d[2] & 0x80 == 0).expect("bulk OUT")[2] & 0x0F;
    let in_ep = bulk.iter().find(|d| d[2] & 0x80 != 0).expect("bulk IN")[2] & 0x0F;
    let i_product = dev[15];
    let name = control_in(w, get_descriptor(3, i_product, 0x0409, 255)).await;
    let text: Vec<u16> = name[2..].chunks(2).map(|c| u16::from_le_bytes([c[0], c[1]])).collect();
    assert_eq!(String::from_utf16(&text).unwrap(), PRODUCT);
    control_out(w, [0, 9, 1, 0, 0, 0, 0, 0], &[]).await;
    (comm, usize::from(out_ep), usize::from(in_ep))
}

/// Opens (DTR set) or closes the port, as a serial program does.
async fn port(w: &Shared, comm: u8, open: bool) {
    let coding = [0x00, 0xC2, 0x01, 0x00, 0, 0, 8]; // 115200 8N1
    control_out(w, [0x21, 0x20, 0, 0, comm, 0, 7, 0], &coding).await;
    control_out(w, [0x21, 0x22, u8::from(open), 0, comm, 0, 0, 0], &[]).await;
}

/// The host writes `bytes` to the port: its driver cuts them into packets.
fn host_write(w: &Shared, out_ep: usize, bytes: &[u8]) {
    let mut w = w.borrow_mut();
    let q = w.to_device.entry(out_ep).or_default();
    q.extend(bytes.chunks(MAX_PACKET).map(<[u8]>::to_vec));
}

/// What the host has received: (bytes, packet lengths).
fn host_read(w: &Shared, in_ep: usize) -> (Vec<u8>, Vec<usize>) {
    let packets = w.borrow_mut().to_host.remove(&in_ep).unwrap_or_default();
    (packets.concat(), packets.iter().map(Vec::len).collect())
}

/// The board side: controller, motion core and the USB link's held bytes and
/// output.
struct Sim<'a> {
    ctl: &'a mut controller::Board,
    core: &'a mut MotionCore<64>,
    held: &'a mut Held<512>,
    output: &'a mut Output,
    now: u64,
}

impl Sim<'_> {
    /// `ms` milliseconds of the board: the packets the host sent, read while the
    /// held bytes have room for one and offered to the controller (usb_rx), the
    /// control task's poll and period, the output in packets (usb_tx). What the
    /// host received: bytes and packet lengths.
    async fn run<'d>(
        &mut self,
        w: &Shared,
        rx: &mut embassy_usb::class::cdc_acm::Receiver<'d, SimDriver>,
        tx: &mut embassy_usb::class::cdc_acm::Sender<'d, SimDriver>,
        out_ep: usize,
        in_ep: usize,
        ms: u64,
    ) -> (Vec<u8>, Vec<usize>) {
        let mut packet = [0; MAX_PACKET];
        let (mut got, mut sizes) = (Vec::new(), Vec::new());
        for _ in 0..ms {
            let now = self.now;
            while has_room(self.held) && w.borrow().to_device.get(&out_ep).is_some_and(|q| !q.is_empty()) {
                let bytes = read(rx, &mut packet).await.unwrap();
                self.held.push(bytes);
                self.held.offer(&mut *self.ctl, now);
            }
            self.ctl.poll(now, &mut *self.core, &mut (), Inputs::default());
            self.core.tick(now, Feedback::default());
            for axis in 0..4 {
                while self.core.next_step(axis, now + 1_000_000).is_some() {}
            }
            self.held.offer(&mut *self.ctl, now);
            let ctl = &mut *self.ctl;
            self.output.send(tx, |buf| ctl.transmit(buf)).await.unwrap();
            let (bytes, lens) = host_read(w, in_ep);
            got.extend(bytes);
            sizes.extend(lens);
            self.now += 1_000_000;
        }
        (got, sizes)
    }
}

/// Lines in `bytes` (CR LF stripped).
fn lines(bytes: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(bytes).split("\r\n").filter(|l| !l.is_empty()).map(str::to_string).collect()
}

#[test]
fn a_host_enumerates_the_board_opens_its_port_and_talks_to_the_controller() {
    let w: Shared = Rc::default();
    let driver = SimDriver { w: w.clone(), next: [0, 0] };
    let buffers: &'static mut Buffers<'static> = Box::leak(Box::default());
    let usb = build(driver, buffers);
    let (mut device, mut tx, mut rx, control) = (usb.device, usb.tx, usb.rx, usb.control);

    let cfg = MachineConfig::default();
    let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::ZERO).expect("machine"));
    let mut ctl = Box::new(controller::Board::new(cfg, Pos::ZERO));
    let (mut held, mut output, mut selector) = (Held::<512>::new(), Output::new(), Selector::new());

    let test = async {
        let (comm, out_ep, in_ep) = enumerate(&w).await;
        tx.wait_connection().await;
        rx.wait_connection().await;
        assert!(!control.dtr());
        assert_eq!(selector.usb_port(control.dtr()), None, "USART2 until the port is opened");

        // The port opens: the controller moves to USB; the answers for USART2 are
        // dropped; the host is greeted (the firmware's usb_tx task).
        port(&w, comm, true).await;
        assert!(control.dtr());
        assert_eq!(selector.usb_port(control.dtr()), Some(Link::Usb));
        drop_output(&mut *ctl);
        let mut greeting = controller::WELCOME.bytes().chain(*b"\r\n");
        output.send(&mut tx, |buf| buf.iter_mut().zip(&mut greeting).map(|(s, b)| *s = b).count()).await.unwrap();
        assert_eq!(lines(&host_read(&w, in_ep).0), [controller::WELCOME]);

        // A status poll and lines, then `$N`, whose answer is exactly one packet:
        // through the bulk endpoints, the held bytes and the controller, a
        // millisecond at a time (the usb_rx task and the control task).
        let block = "G21 G97 G98 G40 (STARTUP BLOCK OF 48 BYTES.....)";
        host_write(&w, out_ep, format!("?$N0={block}\nG98 G01 W-1. F600\nW-1.\n").as_bytes());
        let mut board = Sim { ctl: &mut ctl, core: &mut core, held: &mut held, output: &mut output, now: 0 };
        let (got, _) = board.run(&w, &mut rx, &mut tx, out_ep, in_ep, 1_000).await;
        let (reports, replies): (Vec<String>, Vec<String>) = lines(&got).into_iter().partition(|l| l.starts_with('<'));
        assert_eq!(reports.len(), 1, "{reports:?}");
        assert_eq!(replies, ["ok", "ok", "ok"]);
        assert!(board.core.is_idle() && board.core.stats().blocks == 2, "both moves ran");
        host_write(&w, out_ep, b"$N\n");
        let (got, sizes) = board.run(&w, &mut rx, &mut tx, out_ep, in_ep, 5).await;
        assert_eq!(lines(&got), [format!("$N0={block}"), "$N1=".to_string(), "ok".to_string()]);
        assert_eq!(sizes, [64, 0], "one full packet, then a zero-length one to end the transfer");

        // The port closes: USART2 again.
        port(&w, comm, false).await;
        assert_eq!(selector.usb_port(control.dtr()), Some(Link::Uart));

        // A bus reset (the cable out and in, or the host restarting): the bulk
        // endpoints are gone until the host configures the device again.
        w.borrow_mut().events.push_back(Event::Reset);
        until(&w, |w| (!w.enabled.get(&(in_ep, true)).copied().unwrap_or(false)).then_some(())).await;
        assert!(
            output
                .send(&mut tx, |buf| {
                    buf[0] = b'x';
                    1
                })
                .await
                .is_err()
        );
    };
    match block_on(select(device.run(), test)) {
        Either::First(never) => never,
        Either::Second(()) => {}
    }
}
