//! Firmware entry point: clocks, board bring-up, the stored settings and programs,
//! the motion interrupts, the controller (`controller` crate, docs/PROTOCOL.md) and
//! the task set (control, link receive, link transmit, heartbeat). See `motion.rs`
//! for the interrupt priorities.
#![no_std]
#![no_main]

use core::cell::RefCell;
use core::sync::atomic::{AtomicBool, Ordering};

use defmt::{info, unwrap, warn};
use embassy_executor::Spawner;
use embassy_futures::select::{Either, select};
use embassy_futures::yield_now;
use embassy_stm32::gpio::{Input, Output};
use embassy_stm32::peripherals::{IWDG, TIM5};
use embassy_stm32::timer::qei::Qei;
use embassy_stm32::usart::{BufferedUartRx, BufferedUartTx};
use embassy_stm32::wdg::IndependentWatchdog;
use embassy_sync::blocking_mutex::Mutex;
use embassy_sync::blocking_mutex::raw::ThreadModeRawMutex;
use embassy_sync::signal::Signal;
use embassy_time::{Duration, Ticker, Timer, with_timeout};
use embedded_io_async::{Read as _, Write as _};
use firmware::board::{Axis, Board, MotionTimers, Spindle};
use firmware::io::{Clock, Inputs, Outputs};
use firmware::motion::{self, MotionPort};
use firmware::shell::{self, Ctl, SpindleFollower};
use hal::MonotonicClock as _;
use interp_core::config::MachineConfig;
use link_driver::held::Held;
use static_cell::StaticCell;
use {defmt_rtt as _, panic_probe as _};

/// The controller's storage (it is tens of KB: built in place, see `shell::build`).
/// On the F405 it lives in the 64 KB core-coupled memory (CPU only, no DMA: the
/// controller is never a DMA buffer), so the 128 KB SRAM holds the other statics and
/// the stack, which the interpreter's deepest step (a G71 through the contour layer)
/// needs more than 64 KB of. `memory-f405/memory.x` puts `.ccmram` in the CCM, not initialised:
/// the slot is `MaybeUninit` and written once at boot.
#[cfg(feature = "f405")]
#[unsafe(link_section = ".ccmram")]
static mut CTL_SLOT: core::mem::MaybeUninit<Ctl> = core::mem::MaybeUninit::uninit();
#[cfg(not(feature = "f405"))]
static CTL: StaticCell<Ctl> = StaticCell::new();

/// The controller's slot, taken once at boot.
fn controller_slot() -> &'static mut core::mem::MaybeUninit<Ctl> {
    #[cfg(feature = "f405")]
    {
        static TAKEN: core::sync::atomic::AtomicBool = core::sync::atomic::AtomicBool::new(false);
        assert!(!TAKEN.swap(true, core::sync::atomic::Ordering::Relaxed), "controller slot taken twice");
        // SAFETY: the flag above makes this the only reference to the slot, ever.
        unsafe { &mut *core::ptr::addr_of_mut!(CTL_SLOT) }
    }
    #[cfg(not(feature = "f405"))]
    CTL.uninit()
}

/// The controller, shared by the control and link tasks (all in thread mode).
static CONTROLLER: Mutex<ThreadModeRawMutex, RefCell<Option<&'static mut Ctl>>> = Mutex::new(RefCell::new(None));

/// Set when the controller may have output for USART2.
static TX_READY: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// Set after every poll: the receive buffer may have room again (USART2's task).
static POLLED: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// Set when the controller may have output for USB.
#[cfg(feature = "usb")]
static USB_TX_READY: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// Set after every poll (the USB receive task's).
#[cfg(feature = "usb")]
static USB_POLLED: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// The controller talks to the USB port (a host has it open), not to USART2
/// (`link_driver::select`).
static USB_ACTIVE: AtomicBool = AtomicBool::new(false);

/// Whether the controller talks to the USB port now.
fn usb_active() -> bool {
    USB_ACTIVE.load(Ordering::Relaxed)
}

/// Pins and timers nobody touches after set-up, kept so they stay configured.
struct Kept {
    _axes: [Axis; 3],
    _encoder: Qei<'static, TIM5>,
    _index: Input<'static>,
    _timers: MotionTimers,
}
static KEPT: StaticCell<Kept> = StaticCell::new();

/// Boot: clocks, board, store, motion, controller; then the tasks. On the board
/// embassy's thread-mode executor runs it; the QEMU build runs it on
/// [`firmware::qemu::run_executor`], which sleeps with WFI (see there).
#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(spawner: Spawner) {
    let p = firmware::chip::init();
    #[cfg(feature = "usb")]
    let Board { x, z, c, drive_enable, spindle, aux, switches, dnc, usb, status_led, timers, watchdog, flash } =
        Board::new(p);
    #[cfg(not(feature = "usb"))]
    let Board { x, z, c, drive_enable, spindle, aux, switches, dnc, status_led, timers, watchdog, flash } =
        Board::new(p);
    let Spindle { encoder, index, speed, cw, ccw } = spindle;
    KEPT.init(Kept { _axes: [x, z, c], _encoder: encoder, _index: index, _timers: timers });
    let mut cfg = MachineConfig::default();
    let mut settings = controller::Settings::default();
    #[cfg(persist)]
    let store = open_store(flash, &mut cfg, &mut settings);
    #[cfg(not(persist))]
    let _ = flash; // Nothing persists in QEMU (build.rs).
    // One machine description in this frame (it is on the stack under every
    // call below): refused, it is reset in place.
    let port = match motion::start(&cfg) {
        Ok(port) => port,
        Err(e) => {
            warn!("stored machine description refused ({}): defaults", e);
            cfg = MachineConfig::default();
            settings = controller::Settings::default();
            unwrap!(motion::start(&cfg))
        }
    };
    let outputs = Outputs::new(aux, cw, ccw, speed, drive_enable, cfg.spindle.max_rpm);
    let pos = cfg.reference[0];
    let ctl = shell::build(controller_slot(), cfg, pos);
    *ctl.settings_mut() = settings;
    #[cfg(persist)]
    let saving: Saving = start_saving(store, ctl);
    #[cfg(not(persist))]
    let saving: Saving = ();
    info!("controller: {} bytes", core::mem::size_of::<Ctl>());
    CONTROLLER.lock(|c| *c.borrow_mut() = Some(ctl));
    info!("lathe motion board up");
    let (tx, rx) = dnc.split();
    spawner.spawn(unwrap!(control(port, outputs, Inputs::new(switches), watchdog, saving)));
    spawner.spawn(unwrap!(link_rx(rx)));
    spawner.spawn(unwrap!(link_tx(tx)));
    #[cfg(feature = "usb")]
    {
        let firmware::usb::Usb { device, rx, tx, control } = firmware::usb::build(usb);
        spawner.spawn(unwrap!(firmware::usb::device(device)));
        spawner.spawn(unwrap!(usb_rx(rx)));
        spawner.spawn(unwrap!(usb_tx(tx, control)));
    }
    spawner.spawn(unwrap!(heartbeat(status_led)));
}

/// The QEMU build's entry: [`main`] on the QEMU executor.
#[cfg(feature = "qemu")]
#[cortex_m_rt::entry]
fn entry() -> ! {
    firmware::qemu::run_executor(|spawner| spawner.spawn(unwrap!(main(spawner))))
}

/// The persistence the control task runs (none in QEMU).
#[cfg(persist)]
type Saving = Option<&'static mut firmware::saved::Saver>;

/// The saver (the store and its caches, ~5 KB): a static rather than in the control
/// task's future.
#[cfg(persist)]
static SAVER: StaticCell<firmware::saved::Saver> = StaticCell::new();
#[cfg(not(persist))]
type Saving = ();

/// Reads the stored variables and programs into the controller and starts the
/// saver on the store. Never inlined: its locals stay out of `main`'s frame, which
/// is on the stack while the controller and the motion core are built.
#[cfg(persist)]
#[inline(never)]
fn start_saving(store: Option<firmware::saved::Store>, ctl: &mut Ctl) -> Saving {
    store.map(|mut s| {
        if let Err(e) = firmware::saved::load_rest(&mut s, ctl) {
            warn!("persist: stored variables/programs: {}", e);
        }
        info!("persist: {} programs in memory", ctl.memory().numbers().count());
        &mut *SAVER.init_with(|| firmware::saved::Saver::new(s, ctl))
    })
}

/// Opens the store and reads the stored parameters, settings and offsets into
/// `cfg` and `settings`. A store beyond repair is formatted (everything stored is
/// lost; erasing takes seconds, before the watchdog starts).
#[cfg(persist)]
#[inline(never)]
fn open_store(
    flash: embassy_stm32::flash::Flash<'static, embassy_stm32::flash::Blocking>,
    cfg: &mut MachineConfig,
    settings: &mut controller::Settings,
) -> Option<firmware::saved::Store> {
    use controller::persist::Error;
    let mut store = match firmware::saved::open(flash) {
        Ok(s) => s,
        Err(e) => {
            warn!("persist: no store: {}", e);
            return None;
        }
    };
    match firmware::saved::load_config(&mut store, cfg, settings) {
        Ok(()) => {}
        Err(Error::Corrupted) => {
            warn!("persist: store corrupted: formatting it");
            *cfg = MachineConfig::default();
            *settings = controller::Settings::default();
            if let Err(e) = store.format() {
                warn!("persist: format failed: {}", e);
                return None;
            }
        }
        Err(e) => warn!("persist: stored settings: {}", e),
    }
    Some(store)
}

/// Nanoseconds since boot.
fn now_ns() -> u64 {
    Clock.now_ns()
}

/// The control task (thread mode, below every interrupt): every millisecond samples
/// and debounces the switches, runs the controller's `poll` (interpreter, planner
/// feed, events to outputs, status), lets the spindle drive follow the motion core,
/// saves what changed while at rest (board only), and feeds the watchdog. In the
/// QEMU build it also advances the software motion time base.
#[embassy_executor::task]
async fn control(
    mut port: MotionPort,
    mut outputs: Outputs,
    mut inputs: Inputs,
    mut watchdog: IndependentWatchdog<'static, IWDG>,
    mut saving: Saving,
) {
    watchdog.unleash();
    let mut ticker = Ticker::every(Duration::from_millis(1));
    let mut estop = false;
    let mut spindle = SpindleFollower::new();
    #[cfg(feature = "qemu")]
    let mut soft = {
        let cpr = CONTROLLER.lock(|c| c.borrow().as_ref().map_or(1, |c| c.interpreter().config().spindle.encoder_cpr));
        firmware::soft::SoftMotion::new(cpr, embassy_time::Instant::now().as_micros() as u32)
    };
    loop {
        ticker.next().await;
        let levels = inputs.sample();
        let e = levels.active(motion_driver::io::Switch::EStop);
        if e && !estop {
            warn!("e-stop");
            outputs.stop_all();
            spindle.forget();
        }
        estop = e;
        outputs.enable_drives(!e);
        #[cfg(feature = "qemu")]
        soft.run(&mut port, embassy_time::Instant::now().as_micros() as u32);
        let now = now_ns();
        CONTROLLER.lock(|c| {
            if let Some(ctl) = c.borrow_mut().as_deref_mut() {
                ctl.poll(now, &mut port, &mut outputs, shell::inputs(levels));
                save(&mut saving, now, ctl, &port);
            }
        });
        if !e {
            spindle.follow(&port, &mut outputs);
        }
        POLLED.signal(());
        TX_READY.signal(());
        #[cfg(feature = "usb")]
        {
            USB_POLLED.signal(());
            USB_TX_READY.signal(());
        }
        watchdog.pet();
        // The ticker returns at once while this loop is behind its ticks (after a
        // long interpreter step or flash write; in QEMU whenever the host is slower
        // than the guest's clock), and this task would then run tick after tick
        // without returning to the executor: the link tasks starve, received bytes
        // pile up in the UART's ring until it overflows and drops them — a `?` or
        // feed hold among them — and no reply leaves (issue 18). One turn for every
        // other ready task per tick.
        yield_now().await;
    }
}

/// Saves what changed while the machine is at rest (see `firmware::saved`). Never
/// inlined: the saver's locals stay out of the control task's frame, which is on
/// the stack under the interpreter's deepest step.
#[cfg(persist)]
#[inline(never)]
fn save(saving: &mut Saving, now: u64, ctl: &mut Ctl, port: &MotionPort) {
    if let Some(s) = saving.as_mut() {
        s.tick(now, ctl, port);
    }
}

/// Nothing persists in QEMU.
#[cfg(not(persist))]
fn save(_: &mut Saving, _: u64, _: &mut Ctl, _: &MotionPort) {}

/// Bytes the link receive tasks hold for the controller: what arrived and its
/// receive buffer could not take yet. The tasks keep reading while they hold bytes,
/// so a real-time byte (`!`, 0x18, `?`) behind a buffer that a sender ignoring
/// character counting overfilled still acts at once — up to this many bytes behind
/// it (beyond that, bytes wait in the UART's ring, or at the USB host, until there
/// is room here).
const HELD: usize = 512;

/// The held bytes, of the link the controller talks to (one sender at a time:
/// `link_driver::select`; a switch clears them).
static HELD_BYTES: Mutex<ThreadModeRawMutex, RefCell<Held<HELD>>> = Mutex::new(RefCell::new(Held::new()));

/// Bytes a receive task reads at once.
const CHUNK: usize = 64;

/// Link receive: bytes from USART2 into the controller as they arrive. What its
/// receive buffer cannot take yet is held and offered again after every poll and
/// with every new byte; the controller removes the real-time bytes it acted on
/// from what is held (`link_driver::held`). While the controller talks to the USB
/// port, USART2's bytes are read and dropped.
#[embassy_executor::task]
async fn link_rx(mut rx: BufferedUartRx<'static>) {
    let mut chunk = [0u8; CHUNK];
    loop {
        let (busy, room) = if usb_active() { (false, CHUNK) } else { held_state() };
        let n = arrived(&mut rx, chunk.get_mut(..room.min(CHUNK)).unwrap_or(&mut []), busy).await;
        if usb_active() {
            continue;
        }
        hold_and_offer(chunk.get(..n).unwrap_or(&[]));
        TX_READY.signal(());
    }
}

/// Whether bytes are held, and the room left.
fn held_state() -> (bool, usize) {
    HELD_BYTES.lock(|h| {
        let h = h.borrow();
        (!h.is_empty(), h.room_len())
    })
}

/// Appends `bytes` (they fit: the caller read no more than the room) to the held
/// bytes and offers them all to the controller.
fn hold_and_offer(bytes: &[u8]) {
    let now = now_ns();
    HELD_BYTES.lock(|h| {
        let mut held = h.borrow_mut();
        held.push(bytes);
        CONTROLLER.lock(|c| {
            if let Some(ctl) = c.borrow_mut().as_deref_mut() {
                held.offer(ctl, now);
            }
        });
    });
}

/// Waits for bytes from the UART into `free` — or, while bytes are `held`, also
/// for the next poll (it may have made room) — and returns how many arrived. With
/// `free` empty only a poll ends the wait.
async fn arrived(rx: &mut BufferedUartRx<'static>, free: &mut [u8], held: bool) -> usize {
    let got = match (held, free.is_empty()) {
        (true, true) => {
            POLLED.wait().await;
            return 0;
        }
        (true, false) => match select(POLLED.wait(), rx.read(free)).await {
            Either::First(()) => return 0,
            Either::Second(r) => r,
        },
        (false, _) => rx.read(free).await,
    };
    got.unwrap_or_else(|e| {
        warn!("link receive: {}", e);
        0
    })
}

/// Link transmit: whatever the controller has to say, to USART2.
#[embassy_executor::task]
async fn link_tx(mut tx: BufferedUartTx<'static>) {
    let mut buf = [0u8; 128];
    loop {
        TX_READY.wait().await;
        // USB's task drains the output while the controller talks to the USB port.
        while !usb_active() {
            let n = CONTROLLER.lock(|c| c.borrow_mut().as_deref_mut().map_or(0, |c| c.transmit(&mut buf)));
            if n == 0 {
                break;
            }
            send(&mut tx, buf.get(..n).unwrap_or(&[])).await;
        }
    }
}

/// Writes `bytes` (at most the transmit ring's 256) to the link. Nothing wakes a
/// write waiting for room in the ring since [`firmware::board::TcGuard`] took the
/// transmission-complete interrupt from embassy: it is retried every millisecond. A
/// write takes all its bytes or none, so a retry never sends a byte twice.
async fn send(tx: &mut BufferedUartTx<'static>, bytes: &[u8]) {
    loop {
        match with_timeout(Duration::from_millis(1), tx.write(bytes)).await {
            Ok(Ok(_)) => return,
            Ok(Err(_)) => {
                warn!("link transmit failed");
                return;
            }
            Err(_) => {}
        }
    }
}

/// USB receive: packets from the host into the controller, held as USART2's bytes
/// are (`link_driver::held`). A packet is read only when the held bytes have room
/// for a whole one; meanwhile the host is NAKed and waits, nothing is lost.
#[cfg(feature = "usb")]
#[embassy_executor::task]
async fn usb_rx(mut rx: firmware::usb::UsbIn) {
    use link_driver::packets::{Packet, has_room, read};
    let mut packet: Packet = [0; link_driver::packets::MAX_PACKET];
    loop {
        rx.wait_connection().await;
        loop {
            let (busy, room) = HELD_BYTES.lock(|h| {
                let h = h.borrow();
                (!h.is_empty(), has_room(&h))
            });
            let active = usb_active();
            let got = if active && !room {
                USB_POLLED.wait().await;
                Ok(&[][..])
            } else if active && busy {
                // A packet read is cancel-safe: a packet not yet taken stays in the
                // driver for the next read.
                match select(USB_POLLED.wait(), read(&mut rx, &mut packet)).await {
                    Either::First(()) => Ok(&[][..]),
                    Either::Second(r) => r,
                }
            } else {
                read(&mut rx, &mut packet).await
            };
            let Ok(bytes) = got else { break };
            if usb_active() {
                hold_and_offer(bytes);
                USB_TX_READY.signal(());
            }
        }
    }
}

/// USB transmit and port state: follows DTR (the host opening and closing the
/// port) to move the controller between USART2 and USB (`link_driver::select`),
/// greets a host that opens the port, and sends the controller's output in bulk
/// packets while USB is the controller's link (`link_driver::packets::Output`).
#[cfg(feature = "usb")]
#[embassy_executor::task]
async fn usb_tx(mut tx: firmware::usb::UsbOut, control: embassy_usb::class::cdc_acm::ControlChanged<'static>) {
    use link_driver::packets::Output;
    use link_driver::select::{Link, Selector, drop_output};
    let mut selector = Selector::new();
    let mut output = Output::new();
    loop {
        tx.wait_connection().await;
        output.reset();
        loop {
            if let Some(link) = selector.usb_port(control.dtr()) {
                USB_ACTIVE.store(link == Link::Usb, Ordering::Relaxed);
                // What the controller had to say, and the bytes held for it, were the
                // other link's sender's.
                CONTROLLER.lock(|c| c.borrow_mut().as_deref_mut().map(drop_output));
                HELD_BYTES.lock(|h| h.borrow_mut().clear());
                info!("link: {}", if link == Link::Usb { "USB" } else { "USART2" });
                if link == Link::Usb {
                    let mut greeting = controller::WELCOME.bytes().chain(*b"\r\n");
                    let sent = output
                        .send(&mut tx, |buf| buf.iter_mut().zip(&mut greeting).map(|(slot, b)| *slot = b).count());
                    if sent.await.is_err() {
                        break;
                    }
                }
            }
            if usb_active() {
                let take =
                    |buf: &mut [u8]| CONTROLLER.lock(|c| c.borrow_mut().as_deref_mut().map_or(0, |c| c.transmit(buf)));
                if output.send(&mut tx, take).await.is_err() {
                    break;
                }
            }
            select(control.control_changed(), USB_TX_READY.wait()).await;
        }
        // Unplugged or reset by the host: the port is closed.
        if selector.usb_port(false).is_some() {
            USB_ACTIVE.store(false, Ordering::Relaxed);
            HELD_BYTES.lock(|h| h.borrow_mut().clear());
            info!("link: USART2");
        }
    }
}

/// Blinks the status LED at 1 Hz: visible proof that the executor and time driver run.
#[embassy_executor::task]
async fn heartbeat(mut led: Output<'static>) {
    loop {
        led.toggle();
        Timer::after_millis(500).await;
    }
}
