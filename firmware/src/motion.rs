//! The motion interrupts and the task side's handle on the motion core.
//!
//! Priorities (NVIC, lower number = more urgent; see README "Interrupts and tasks"):
//!
//! | priority | interrupt | does |
//! |---|---|---|
//! | P0 [`STEP_PRIORITY`] | TIM2 compare 1 (step), EXTI2 (index) | plays queued STEP/DIR edges through GPIOC's BSRR; latches TIM5's count at the index |
//! | P1 [`MOTION_PRIORITY`] | TIM7 update (period), TIM5 compare 3/4 (encoder count) | `MotionCore::tick` one period ahead and queues its edges; while locked to the spindle, `on_encoder` at the counts where a step falls due (the compares sit there) |
//! | P3 [`DRIVER_PRIORITY`] | USART2, TIM4 (embassy time) | serial buffers, task timers |
//! | thread | executor tasks | control (interpreter + planner via [`MotionPort`]), link, I/O |
//!
//! The motion core and the engine ([`Motion`]) belong to priority P1: the period and
//! encoder interrupts use them directly (same priority, so never at the same time);
//! thread mode reaches them only through [`MotionPort::lock`], which raises BASEPRI to
//! P1 for one short closure: P1 and below wait, the step interrupt keeps playing
//! edges already queued (up to two periods ahead), so a long planner call delays the
//! next period computation, never a step. The step player belongs to P0 alone.
//! Edges pass from P1 to P0 through lock-free rings.

use core::cell::UnsafeCell;
use core::marker::PhantomData;
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use embassy_stm32::interrupt::Priority;
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::config::{MachineConfig, MachineKind};
use motion_driver::board::{self, BoardEngine, BoardPlayer};
use motion_driver::engine::{Engine, EngineAxis, RING};
use motion_driver::playback::{PlayTiming, Player};
use motion_driver::ring::EdgeRing;
use motion_driver::timebase::{TimeBase, TimeBaseError};

use crate::board::STEP_PINS;

/// Driven axes of a machine kind, on [`STEP_PINS`] in this order: X, Z and the
/// third channel — C on a lathe, Y on a mill.
pub const fn axes(kind: MachineKind) -> [Axis; 3] {
    match kind {
        MachineKind::Lathe => [Axis::X, Axis::Z, Axis::C],
        MachineKind::Mill => [Axis::X, Axis::Z, Axis::Y],
    }
}

/// The step channel whose axis depends on the machine kind.
pub const THIRD_CHANNEL: usize = 2;

/// The step interrupt and the index latch.
pub const STEP_PRIORITY: Priority = Priority::P0;
/// The period and encoder-count interrupts (owners of the motion core).
pub const MOTION_PRIORITY: Priority = Priority::P1;
/// Serial and time-driver interrupts.
pub const DRIVER_PRIORITY: Priority = Priority::P3;

/// BASEPRI value masking [`MOTION_PRIORITY`] and below (4 priority bits on the F4).
const MOTION_BASEPRI: u8 = (MOTION_PRIORITY as u8) & 0xF0;

/// The motion core with the firmware's look-ahead depth.
pub use motion_driver::board::Core;

/// What the priority-P1 interrupts own: the motion core and the period engine.
pub struct Motion {
    /// Planner, interpolator, step generators, spindle gearbox.
    pub core: Core,
    /// Period pipeline and encoder widening.
    pub engine: BoardEngine,
}

/// A static used by one execution priority only (plus set-up before that priority's
/// interrupts are enabled).
struct PriorityCell<T> {
    value: UnsafeCell<MaybeUninit<T>>,
    ready: AtomicBool,
}

// SAFETY: each cell is used by one priority level (documented at each static); code
// of one level never preempts itself, and thread mode enters P1's cell only with
// BASEPRI at P1 (MotionPort::lock).
unsafe impl<T> Sync for PriorityCell<T> {}

impl<T> PriorityCell<T> {
    const fn new() -> Self {
        PriorityCell { value: UnsafeCell::new(MaybeUninit::uninit()), ready: AtomicBool::new(false) }
    }

    /// Stores the value (once, before the owning interrupts are enabled).
    fn init(&self, v: T) -> bool {
        if self.ready.load(Ordering::Acquire) {
            return false;
        }
        // SAFETY: not ready yet: nothing else reads or writes the cell.
        unsafe { (*self.value.get()).write(v) };
        self.ready.store(true, Ordering::Release);
        true
    }

    /// The value, if set.
    ///
    /// # Safety
    ///
    /// Only from the cell's owning priority level, never twice at once.
    #[allow(clippy::mut_from_ref)]
    unsafe fn get(&self) -> Option<&mut T> {
        if !self.ready.load(Ordering::Acquire) {
            return None;
        }
        // SAFETY: initialised (ready), exclusive by the caller's contract.
        Some(unsafe { (*self.value.get()).assume_init_mut() })
    }

    /// The value for reading, if set.
    ///
    /// # Safety
    ///
    /// Only from the cell's owning priority level, and never while a `get` of it is
    /// alive.
    unsafe fn get_ref(&self) -> Option<&T> {
        if !self.ready.load(Ordering::Acquire) {
            return None;
        }
        // SAFETY: initialised (ready), no exclusive reference by the caller's contract.
        Some(unsafe { (*self.value.get()).assume_init_ref() })
    }
}

/// Owned by priority P1 (period and encoder interrupts; thread mode via MotionPort).
static MOTION: PriorityCell<Motion> = PriorityCell::new();
/// Owned by priority P0 (step interrupt) on the board; by the software motion task
/// in the QEMU build.
static PLAYER: PriorityCell<BoardPlayer> = PriorityCell::new();
/// Edge rings X, Z, C: P1 produces, P0 consumes.
static RINGS: [EdgeRing<RING>; 3] = [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()];
/// Raw TIM5 count latched by the index interrupt, and whether one was seen.
static INDEX_RAW: AtomicU32 = AtomicU32::new(0);
static INDEX_SEEN: AtomicBool = AtomicBool::new(false);

/// Why the motion interrupts could not start.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub enum StartError {
    /// The machine configuration is refused by the motion core.
    Config,
    /// The interpolation period is not a whole number of timer ticks.
    TimeBase(TimeBaseError),
    /// Started twice.
    Twice,
}

/// Builds the motion core for `cfg` with the axes at `pos`, the engine on a timer of
/// `tb`, and the step player; `start`/`raw_count` are the timer and encoder readings
/// that are time 0 and count 0. Returns the thread-mode handle.
pub fn init(cfg: &MachineConfig, pos: Pos, tb: TimeBase, start: u32, raw_count: u32) -> Result<MotionPort, StartError> {
    if MOTION.ready.load(Ordering::Acquire) {
        return Err(StartError::Twice);
    }
    // The core (~21 KB) goes straight into its static: the stack holds one
    // temporary at most.
    // SAFETY: not ready: nothing else reads or writes the cell (interrupts that use
    // it are not enabled yet).
    let cell = unsafe { &mut *MOTION.value.get() };
    let slot = cell.as_mut_ptr();
    let core = match Core::new(cfg, pos) {
        // SAFETY: `slot` points to the cell's storage; the field is written once
        // and the cell marked ready only when every field is.
        Ok(core) => unsafe { &mut *core::ptr::addr_of_mut!((*slot).core).cast::<MaybeUninit<Core>>() }.write(core),
        Err(_) => return Err(StartError::Config),
    };
    let [rx, rz, rc] = &RINGS;
    let (Some((tx, px)), Some((tz, pz)), Some((tc, pc))) = (rx.split(), rz.split(), rc.split()) else {
        return Err(StartError::Twice);
    };
    let axes = axes(cfg.kind);
    let timing = |a: Axis| core.stepper(a.index()).map(|s| PlayTiming::new(s.timing(), &tb));
    let (Some(ttx), Some(ttz), Some(ttc)) = (timing(axes[0]), timing(axes[1]), timing(axes[2])) else {
        return Err(StartError::Config);
    };
    let [pins_x, pins_z, pins_c] = STEP_PINS;
    let player = Player::new([(px, pins_x, ttx), (pz, pins_z, ttz), (pc, pins_c, ttc)]);
    let axes = [
        EngineAxis::new(axes[0].index(), tx),
        EngineAxis::new(axes[1].index(), tz),
        EngineAxis::new(axes[2].index(), tc),
    ];
    // SAFETY: as above; the core is written, the engine now, then the cell is ready.
    unsafe { core::ptr::addr_of_mut!((*slot).engine).write(Engine::new(tb, axes, start, raw_count)) };
    MOTION.ready.store(true, Ordering::Release);
    if !PLAYER.init(player) {
        return Err(StartError::Twice);
    }
    Ok(MotionPort { _thread_only: PhantomData })
}

/// The index latch for the period: the raw count at the last index pulse.
pub fn index_latch() -> Option<u32> {
    INDEX_SEEN.load(Ordering::Acquire).then(|| INDEX_RAW.load(Ordering::Relaxed))
}

/// Records an index pulse at raw count `raw` (the index interrupt's work).
pub fn latch_index(raw: u32) {
    INDEX_RAW.store(raw, Ordering::Relaxed);
    INDEX_SEEN.store(true, Ordering::Release);
}

/// Runs `f` on what priority P1 owns.
///
/// # Safety
///
/// Only from a priority-P1 interrupt (or with BASEPRI at P1).
pub unsafe fn with_motion<R>(f: impl FnOnce(&mut Motion) -> R) -> Option<R> {
    // SAFETY: the caller runs at P1, which owns the cell.
    unsafe { MOTION.get() }.map(f)
}

/// Runs `f` on the step player.
///
/// # Safety
///
/// Only from the step interrupt (P0), or from the one task that plays edges in
/// the QEMU build (no step interrupt there).
pub unsafe fn with_player<R>(f: impl FnOnce(&mut BoardPlayer) -> R) -> Option<R> {
    // SAFETY: the caller is the player's only user.
    unsafe { PLAYER.get() }.map(f)
}

/// Thread mode's handle on the motion core: every call is one short critical
/// section that masks the period and encoder interrupts (P1 and below) but not the
/// step interrupt. One handle exists; it is neither `Send` nor `Sync`, so it stays in
/// thread mode (the executor's tasks).
pub struct MotionPort {
    _thread_only: PhantomData<*const ()>,
}

impl MotionPort {
    /// Runs `f` with the motion core and engine, the motion interrupts held off.
    /// Keep `f` short: one core call (a planner push is at most ~8,500 instructions,
    /// 51 µs at 168 MHz; the period interrupt then starts that much later, well
    /// inside the period of slack the pipeline has).
    pub fn lock<R>(&mut self, f: impl FnOnce(&mut Motion) -> R) -> Option<R> {
        let old = cortex_m::register::basepri::read();
        cortex_m::register::basepri_max::write(MOTION_BASEPRI);
        // SAFETY: BASEPRI at P1: no P1 interrupt runs until it is restored, so this is
        // the only user of P1's state; the closure cannot leak the reference.
        let r = unsafe { MOTION.get() }.map(f);
        // SAFETY: back to the level we came in with.
        unsafe { cortex_m::register::basepri::write(old) };
        r
    }

    /// Runs `f` reading the motion core and engine, the motion interrupts held off
    /// (for status snapshots: `&self`, so it cannot overlap a [`Self::lock`]).
    pub fn peek<R>(&self, f: impl FnOnce(&Motion) -> R) -> Option<R> {
        let old = cortex_m::register::basepri::read();
        cortex_m::register::basepri_max::write(MOTION_BASEPRI);
        // SAFETY: BASEPRI at P1 (no P1 interrupt runs); `lock` needs `&mut self`, so
        // no exclusive reference exists while this shared one does.
        let r = unsafe { MOTION.get_ref() }.map(f);
        // SAFETY: back to the level we came in with.
        unsafe { cortex_m::register::basepri::write(old) };
        r
    }

    /// Whether the look-ahead queue has room (what a sender's `Bf:` reports).
    pub fn queued(&mut self) -> usize {
        self.lock(|m| m.core.queued()).unwrap_or(0)
    }
}

impl CanonSink for MotionPort {
    /// Queues a canonical action in the motion core: the interpreter writes straight
    /// into the planner, one critical section per action.
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        self.lock(|m| board::push(&mut m.core, &action)).unwrap_or(Err(Full))
    }

    /// As [`CanonSink::push`], the action read where the interpreter keeps it.
    fn push_ref(&mut self, action: &Canon) -> Result<(), Full> {
        self.lock(|m| board::push(&mut m.core, action)).unwrap_or(Err(Full))
    }
}

/// Builds the motion core at reference position 1 and starts the step, period and
/// encoder interrupts (on the board) — or, in the QEMU build, the software time base
/// that the control task advances (`soft.rs`).
pub fn start(cfg: &MachineConfig) -> Result<MotionPort, StartError> {
    let pos = cfg.reference[0];
    #[cfg(feature = "hw")]
    {
        use crate::board::{ENCODER_TIMER, TIMER_HZ};
        let tb = TimeBase::new(TIMER_HZ, cfg.motion.tick_ns).map_err(StartError::TimeBase)?;
        let mut port = init(cfg, pos, tb, 0, 0)?;
        let start = isr::start_timers(tb.period_ticks);
        let raw = ENCODER_TIMER.cnt().read();
        port.lock(|m| m.engine.set_origin(start, raw));
        isr::enable();
        defmt::info!("motion: period {} ns = {} ticks of {} Hz", tb.period_ns, tb.period_ticks, tb.timer_hz);
        Ok(port)
    }
    #[cfg(not(feature = "hw"))]
    {
        // Software time base: microseconds of embassy time.
        let tb = TimeBase::new(1_000_000, cfg.motion.tick_ns).map_err(StartError::TimeBase)?;
        let now = embassy_time::Instant::now().as_micros() as u32;
        let port = init(cfg, pos, tb, now, 0)?;
        defmt::info!("motion: software time base, period {} ns", tb.period_ns);
        Ok(port)
    }
}

/// The hardware motion interrupts (not in the QEMU build: QEMU models neither the
/// timers' compares nor GPIO).
#[cfg(feature = "hw")]
pub mod isr {
    use embassy_stm32::interrupt::{self, InterruptExt};
    use embassy_stm32::pac;
    use embassy_stm32::pac::timer::regs::{SrCore, SrGp16};
    use motion_driver::board;
    use motion_driver::encoder::Window;
    use motion_driver::engine::Sample;

    use super::{DRIVER_PRIORITY, MOTION_PRIORITY, STEP_PRIORITY, index_latch, latch_index, with_motion, with_player};
    use crate::board::{DRIVE_ENABLE_BIT, ENCODER_TIMER, ESTOP_BIT, PERIOD_TIMER, STEP_PORT, STEP_TIMER};

    /// An edge due within this many ticks is played in the same interrupt run
    /// (about the interrupt's entry and exit: 30 ticks = 60 cycles).
    const MIN_LEAD: i32 = 30;

    /// Starts the step time base (TIM2 free running at 84 MHz, compare 1 for edges)
    /// and the period timer (TIM7, one update per `period_ticks`) and sets every
    /// interrupt's priority. Returns TIM2's count at the start of period 0.
    pub fn start_timers(period_ticks: u32) -> u32 {
        STEP_TIMER.psc().write_value(0);
        STEP_TIMER.arr().write_value(u32::MAX);
        STEP_TIMER.egr().write(|w| w.set_ug(true));
        STEP_TIMER.sr().write_value(SrGp16(0));
        STEP_TIMER.dier().write(|w| w.set_ccie(0, true));
        // The period timer is 16-bit: the smallest prescaler that fits.
        let psc = (1..=65_536u32).find(|p| period_ticks.is_multiple_of(*p) && period_ticks / p <= 65_536).unwrap_or(1);
        PERIOD_TIMER.psc().write_value((psc - 1) as u16);
        PERIOD_TIMER.arr().write(|w| w.set_arr((period_ticks / psc - 1) as u16));
        PERIOD_TIMER.egr().write(|w| w.set_ug(true));
        PERIOD_TIMER.sr().write_value(SrCore(0));
        PERIOD_TIMER.dier().write(|w| w.set_uie(true));
        ENCODER_TIMER.sr().write_value(SrGp16(0));
        interrupt::TIM2.set_priority(STEP_PRIORITY);
        interrupt::EXTI2.set_priority(STEP_PRIORITY);
        interrupt::TIM7.set_priority(MOTION_PRIORITY);
        interrupt::TIM5.set_priority(MOTION_PRIORITY);
        interrupt::USART2.set_priority(DRIVER_PRIORITY);
        interrupt::TIM4.set_priority(DRIVER_PRIORITY);
        STEP_TIMER.cr1().modify(|w| w.set_cen(true));
        PERIOD_TIMER.cr1().modify(|w| w.set_cen(true));
        STEP_TIMER.cnt().read()
    }

    /// Enables the motion interrupts; period 0 is computed at once.
    pub fn enable() {
        // SAFETY: the handlers below are ready (motion::init ran before).
        unsafe {
            interrupt::TIM2.enable();
            interrupt::EXTI2.enable();
            interrupt::TIM5.enable();
            interrupt::TIM7.enable();
        }
        interrupt::TIM7.pend();
    }

    /// Step interrupt (P0): plays due edges, programs the compare for the next one.
    /// While the e-stop input is high it raises no STEP pin and drops drive enable.
    fn step_isr() {
        STEP_TIMER.sr().write_value(SrGp16(!(1 << 1)));
        // SAFETY: this is the step interrupt, the player's owner.
        let _ = unsafe {
            with_player(|player| {
                loop {
                    let now = STEP_TIMER.cnt().read();
                    let estop = STEP_PORT.idr().read().0 & ESTOP_BIT != 0;
                    let out = board::play(player, now, estop);
                    let bsrr = out.bsrr | if estop { DRIVE_ENABLE_BIT << 16 } else { 0 };
                    if bsrr != 0 {
                        STEP_PORT.bsrr().write_value(pac::gpio::regs::Bsrr(bsrr));
                    }
                    // Nothing queued: the compare stays armed one wrap (51 s) away.
                    let next = out.next.unwrap_or(now.wrapping_sub(1));
                    STEP_TIMER.ccr(0).write_value(next);
                    if out.next.is_none() || next.wrapping_sub(STEP_TIMER.cnt().read()) as i32 > MIN_LEAD {
                        break;
                    }
                }
            })
        };
    }

    /// Period interrupt (P1): the next interpolation period, then the player is
    /// kicked to pick up the new edges; the encoder compares go where the core
    /// next needs a count (a pass may have started or ended, a leg been announced).
    fn period_isr() {
        PERIOD_TIMER.sr().write_value(SrCore(0));
        let sample = Sample {
            now: STEP_TIMER.cnt().read(),
            raw_count: ENCODER_TIMER.cnt().read(),
            index: index_latch(),
            estop: STEP_PORT.idr().read().0 & ESTOP_BIT != 0,
        };
        // SAFETY: this is a P1 interrupt.
        let missed = unsafe {
            with_motion(|m| {
                board::period(&mut m.engine, &mut m.core, sample);
                let w = board::window(&mut m.engine, &mut m.core);
                arm(w);
                m.engine.reached(&w, ENCODER_TIMER.cnt().read())
            })
        };
        if missed == Some(true) {
            // The count is already at or past a due count: the count interrupt
            // (same priority) runs right after this one.
            interrupt::TIM5.pend();
        }
        interrupt::TIM2.pend();
    }

    /// Sets TIM5's compares: channel 3 at the due count above, channel 4 at the one
    /// below, each interrupt enabled only when there is one. Flags are cleared
    /// after the values are written, so only a match with the new values pends
    /// the interrupt; the caller checks a fresh reading for a count that went past
    /// a compare before it was set ([`motion_driver::engine::Engine::reached`]).
    #[inline(always)]
    fn arm(w: Window) {
        if let Some(up) = w.up {
            ENCODER_TIMER.ccr(2).write_value(up);
        }
        if let Some(down) = w.down {
            ENCODER_TIMER.ccr(3).write_value(down);
        }
        ENCODER_TIMER.sr().write_value(SrGp16(!((1 << 3) | (1 << 4))));
        ENCODER_TIMER.dier().write(|d| {
            d.set_ccie(2, w.up.is_some());
            d.set_ccie(3, w.down.is_some());
        });
    }

    /// Encoder-count interrupt (P1, while something follows the spindle): the
    /// counter reached a count where a step falls due. The count goes to the core
    /// with its time, the step interrupt (P0) is pended at once to play the step,
    /// then the compares move to the next due counts; again while the counter has
    /// already reached one of them.
    fn encoder_isr() {
        ENCODER_TIMER.sr().write_value(SrGp16(!((1 << 3) | (1 << 4))));
        // SAFETY: this is a P1 interrupt.
        let _ = unsafe {
            with_motion(|m| {
                loop {
                    let raw = ENCODER_TIMER.cnt().read();
                    let now = STEP_TIMER.cnt().read();
                    if board::encoder(&mut m.engine, &mut m.core, now, raw) {
                        // Preempts this interrupt: the step edge is played now.
                        interrupt::TIM2.pend();
                    }
                    let w = board::window(&mut m.engine, &mut m.core);
                    arm(w);
                    if !m.engine.reached(&w, ENCODER_TIMER.cnt().read()) {
                        break;
                    }
                }
            })
        };
    }

    /// Index interrupt (P0): the count at the index, read within the interrupt's
    /// entry time (well under one count: 7.3 µs at 2000 rpm × 4096).
    fn index_isr() {
        pac::EXTI.pr(0).write(|w| w.set_line(2, true));
        latch_index(ENCODER_TIMER.cnt().read());
    }

    /// The vector table entries.
    #[allow(non_snake_case)]
    mod vectors {
        #[unsafe(no_mangle)]
        extern "C" fn TIM2() {
            super::step_isr();
        }
        #[unsafe(no_mangle)]
        extern "C" fn TIM7() {
            super::period_isr();
        }
        #[unsafe(no_mangle)]
        extern "C" fn TIM5() {
            super::encoder_isr();
        }
        #[unsafe(no_mangle)]
        extern "C" fn EXTI2() {
            super::index_isr();
        }
    }
}
