//! Firmware entry point: clocks, board bring-up, the stored settings and programs,
//! the motion interrupts, the controller (`controller` crate, docs/PROTOCOL.md) and
//! the task set (control, link receive, link transmit, heartbeat). See `motion.rs`
//! for the interrupt priorities.
#![no_std]
#![no_main]

use core::cell::RefCell;

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
use motion_driver::timebase::TimeBase;
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

/// Set when the controller may have output for the link.
static TX_READY: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// Set after every poll: the receive buffer may have room again.
static POLLED: Signal<ThreadModeRawMutex, ()> = Signal::new();

/// Pins and timers nobody touches after set-up, kept so they stay configured.
struct Kept {
    _axes: [Axis; 3],
    _encoder: Qei<'static, TIM5>,
    _index: Input<'static>,
    _timers: MotionTimers,
}
static KEPT: StaticCell<Kept> = StaticCell::new();

/// System clock from the board's 8 MHz crystal: 168 MHz core, 42 MHz APB1
/// (84 MHz timers), 84 MHz APB2 (168 MHz timers), 48 MHz for USB. Same on the F446.
#[cfg(not(feature = "qemu"))]
fn clock_config() -> embassy_stm32::Config {
    use embassy_stm32::rcc::{
        AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllMul, PllPDiv, PllPreDiv, PllQDiv, PllSource, Sysclk,
    };
    use embassy_stm32::time::Hertz;
    let mut config = embassy_stm32::Config::default();
    let rcc = &mut config.rcc;
    rcc.hse = Some(Hse { freq: Hertz::mhz(8), mode: HseMode::Oscillator });
    rcc.pll_src = PllSource::HSE;
    rcc.pll = Some(Pll {
        prediv: PllPreDiv::DIV4,   // 2 MHz PLL input
        mul: PllMul::MUL168,       // 336 MHz VCO
        divp: Some(PllPDiv::DIV2), // 168 MHz system clock
        divq: Some(PllQDiv::DIV7), // 48 MHz USB/SDIO clock
        divr: None,
    });
    rcc.sys = Sysclk::PLL1_P;
    rcc.ahb_pre = AHBPrescaler::DIV1;
    rcc.apb1_pre = APBPrescaler::DIV4;
    rcc.apb2_pre = APBPrescaler::DIV2;
    config
}

/// QEMU: the reset clocks (HSI 16 MHz) and no backup domain (QEMU's PWR never
/// acknowledges DBP).
#[cfg(feature = "qemu")]
fn clock_config() -> embassy_stm32::Config {
    let mut config = embassy_stm32::Config::default();
    config.rcc.ls = embassy_stm32::rcc::LsConfig::off();
    config
}

/// Boot: clocks, board, store, motion, controller; then the tasks. On the board
/// embassy's thread-mode executor runs it; the QEMU build runs it on
/// [`firmware::qemu::run_executor`], which sleeps with WFI (see there).
#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(spawner: Spawner) {
    #[cfg(feature = "qemu")]
    let mut cp = {
        firmware::qemu::rcc_workaround();
        let mut cp = unwrap!(cortex_m::Peripherals::take());
        firmware::qemu::trap_pwr(&mut cp.MPU);
        cp
    };
    let p = embassy_stm32::init(clock_config());
    #[cfg(feature = "qemu")]
    {
        firmware::qemu::untrap_pwr(&mut cp.MPU);
        firmware::qemu::start_time_driver(&mut cp.SYST);
    }
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
    let port = match start_motion(&cfg) {
        Ok(port) => port,
        Err(e) => {
            warn!("stored machine description refused ({}): defaults", e);
            cfg = MachineConfig::default();
            settings = controller::Settings::default();
            unwrap!(start_motion(&cfg))
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
            warn!("persist: stored variables/programs: {}", defmt::Display2Format(&e));
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
            warn!("persist: no store: {}", defmt::Display2Format(&e));
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
                warn!("persist: format failed: {}", defmt::Display2Format(&e));
                return None;
            }
        }
        Err(e) => warn!("persist: stored settings: {}", defmt::Display2Format(&e)),
    }
    Some(store)
}

/// Builds the motion core at reference position 1 and starts the step, period and
/// encoder interrupts (on the board) — or, in the QEMU build, the software time base
/// that the control task advances.
fn start_motion(cfg: &MachineConfig) -> Result<MotionPort, motion::StartError> {
    let pos = cfg.reference[0];
    #[cfg(feature = "hw")]
    {
        use firmware::board::{ENCODER_TIMER, TIMER_HZ};
        let tb = TimeBase::new(TIMER_HZ, cfg.motion.tick_ns).map_err(motion::StartError::TimeBase)?;
        let mut port = motion::init(cfg, pos, tb, 0, 0)?;
        let start = motion::isr::start_timers(tb.period_ticks);
        let raw = ENCODER_TIMER.cnt().read();
        port.lock(|m| m.engine.set_origin(start, raw));
        motion::isr::enable();
        info!("motion: period {} ns = {} ticks of {} Hz", tb.period_ns, tb.period_ticks, tb.timer_hz);
        Ok(port)
    }
    #[cfg(not(feature = "hw"))]
    {
        // Software time base: microseconds of embassy time.
        let tb = TimeBase::new(1_000_000, cfg.motion.tick_ns).map_err(motion::StartError::TimeBase)?;
        let now = embassy_time::Instant::now().as_micros() as u32;
        let port = motion::init(cfg, pos, tb, now, 0)?;
        info!("motion: software time base, period {} ns", tb.period_ns);
        Ok(port)
    }
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

/// Bytes the link receive task holds for the controller: what arrived and its
/// receive buffer could not take yet. The task keeps reading while it holds bytes,
/// so a real-time byte (`!`, 0x18, `?`) behind a buffer that a sender ignoring
/// character counting overfilled still acts at once — up to this many bytes behind
/// it (beyond that, bytes wait in the UART's ring until there is room here).
const HELD: usize = 512;

/// Link receive: bytes from USART2 into the controller as they arrive. What its
/// receive buffer cannot take yet is held and offered again after every poll and
/// with every new byte; the controller removes the real-time bytes it acted on
/// from what is held (`Controller::receive`).
#[embassy_executor::task]
async fn link_rx(mut rx: BufferedUartRx<'static>) {
    let mut buf = [0u8; HELD];
    let mut len = 0;
    loop {
        len += arrived(&mut rx, buf.get_mut(len..).unwrap_or(&mut []), len > 0).await;
        let now = now_ns();
        let held = buf.get_mut(..len).unwrap_or(&mut []);
        let taken = CONTROLLER.lock(|c| c.borrow_mut().as_deref_mut().map_or(0, |c| c.receive(held, now)));
        let taken = taken.min(len);
        buf.copy_within(taken..len, 0);
        len -= taken;
        TX_READY.signal(());
    }
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
        loop {
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

/// Blinks the status LED at 1 Hz: visible proof that the executor and time driver run.
#[embassy_executor::task]
async fn heartbeat(mut led: Output<'static>) {
    loop {
        led.toggle();
        Timer::after_millis(500).await;
    }
}
