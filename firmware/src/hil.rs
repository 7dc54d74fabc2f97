//! What the bring-up tests share (`src/bin/hil_*.rs`, docs/BRINGUP.md): each
//! binary checks one piece of the board and reports every check and its figures,
//! then its result. On the board the report goes over RTT (defmt) and the result is
//! the semihosting exit status, so `probe-rs run` prints the report and exits with
//! 0 or 1. In the QEMU build (feature `qemu`) the report also goes to QEMU's console by
//! semihosting and QEMU exits with the result (`firmware/hil-qemu.py`); the checks
//! that need the board's hardware (timers, GPIO, flash, watchdog, USB) report SKIP
//! there, so a QEMU run proves the binary boots, configures its peripherals and
//! passes its self-check.

use defmt::{error, info, warn};

/// Whether this build runs on QEMU (hardware checks are skipped).
pub const QEMU: bool = cfg!(feature = "qemu");

/// The QEMU build's entry of a bring-up test: the test's `main` task on the QEMU
/// executor (on the board, `#[embassy_executor::main]` on `main` is the entry).
/// Invoked once at the end of each `src/bin/hil_*.rs`.
#[macro_export]
macro_rules! hil_qemu_entry {
    () => {
        /// The QEMU build's entry: `main` on the QEMU executor.
        #[cfg(feature = "qemu")]
        #[cortex_m_rt::entry]
        fn entry() -> ! {
            firmware::qemu::run_executor(|spawner| spawner.spawn(defmt::unwrap!(main(spawner))))
        }
    };
}

/// One bring-up test's checks and result.
pub struct Report {
    name: &'static str,
    passed: u32,
    failed: u32,
    skipped: u32,
}

/// Prints `args` on QEMU's console (semihosting); nothing on the board.
macro_rules! console {
    ($($arg:tt)*) => {
        #[cfg(feature = "qemu")]
        cortex_m_semihosting::hprintln!($($arg)*);
    };
}

impl Report {
    /// Starts the report of test `name`.
    pub fn new(name: &'static str) -> Self {
        info!("{=str}: start", name);
        console!("{}: start", name);
        Report { name, passed: 0, failed: 0, skipped: 0 }
    }

    /// A check that passed or failed.
    pub fn check(&mut self, what: &str, ok: bool) -> bool {
        if ok {
            self.passed += 1;
            info!("{=str}: PASS {=str}", self.name, what);
            console!("{}: PASS {}", self.name, what);
        } else {
            self.failed += 1;
            error!("{=str}: FAIL {=str}", self.name, what);
            console!("{}: FAIL {}", self.name, what);
        }
        ok
    }

    /// A measured figure that must lie in `lo..=hi` (`unit` names it).
    pub fn within(&mut self, what: &str, value: i64, unit: &str, lo: i64, hi: i64) -> bool {
        let ok = (lo..=hi).contains(&value);
        if ok {
            self.passed += 1;
            info!("{=str}: PASS {=str} = {} {=str} (in {}..={})", self.name, what, value, unit, lo, hi);
            console!("{}: PASS {} = {} {} (in {}..={})", self.name, what, value, unit, lo, hi);
        } else {
            self.failed += 1;
            error!("{=str}: FAIL {=str} = {} {=str} (not in {}..={})", self.name, what, value, unit, lo, hi);
            console!("{}: FAIL {} = {} {} (not in {}..={})", self.name, what, value, unit, lo, hi);
        }
        ok
    }

    /// A figure for the record (no verdict).
    pub fn figure(&self, what: &str, value: i64, unit: &str) {
        info!("{=str}: {=str} = {} {=str}", self.name, what, value, unit);
        console!("{}: {} = {} {}", self.name, what, value, unit);
    }

    /// A check this build cannot make (`why`: what it needs).
    pub fn skip(&mut self, what: &str, why: &str) {
        self.skipped += 1;
        warn!("{=str}: SKIP {=str} ({=str})", self.name, what, why);
        console!("{}: SKIP {} ({})", self.name, what, why);
    }

    /// Skips `what` when this is the QEMU build; whether it may run.
    pub fn on_board(&mut self, what: &str) -> bool {
        if QEMU {
            self.skip(what, "needs the board");
        }
        !QEMU
    }

    /// Whether every check so far passed.
    pub fn ok(&self) -> bool {
        self.failed == 0
    }

    /// Reports the result and ends the run: semihosting exit 0 if every check
    /// passed, 1 otherwise (`probe-rs run` and QEMU return it).
    pub fn finish(self) -> ! {
        let (name, p, f, s) = (self.name, self.passed, self.failed, self.skipped);
        if f == 0 {
            info!("{=str}: done: PASS ({} passed, {} skipped)", name, p, s);
            console!("{}: done: PASS ({} passed, {} skipped)", name, p, s);
        } else {
            error!("{=str}: done: FAIL ({} failed, {} passed, {} skipped)", name, f, p, s);
            console!("{}: done: FAIL ({} failed, {} passed, {} skipped)", name, f, p, s);
        }
        exit(f == 0)
    }
}

/// Ends the run with semihosting's exit call.
pub fn exit(pass: bool) -> ! {
    use cortex_m_semihosting::debug;
    debug::exit(if pass { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // Without a debugger or QEMU, semihosting does not return here either (it
    // faults); stay put in case it does.
    loop {
        cortex_m::asm::wfi();
    }
}

/// Busy-waits `us` microseconds of embassy time (for short hardware settling).
pub fn spin_us(us: u64) {
    let end = embassy_time::Instant::now() + embassy_time::Duration::from_micros(us);
    while embassy_time::Instant::now() < end {}
}

/// The STEP probe: TIM1 channel 1 on PA8, a jumper from X STEP (PC6)
/// ([`crate::board::bench`]). Counts STEP rises, or times each pulse.
pub mod probe {
    use embassy_stm32::pac::timer::vals::{CcmrInputCcs, FilterValue, Sms, Ts};

    use crate::board::bench::{PROBE_TIMER as T, probe_pin};

    /// Counts X STEP rises from 0 (external clock mode 1 on TI1, 16 bits).
    pub fn count_steps() {
        probe_pin();
        T.cr1().write(|_| {});
        T.ccmr_input(0).write(|w| {
            w.set_ccs(0, CcmrInputCcs::TI4); // IC1 on TI1
            w.set_icf(0, FilterValue::NO_FILTER);
        });
        T.ccer().write(|w| w.set_ccp(0, false)); // rising edges
        T.smcr().write(|w| {
            w.set_ts(Ts::TI1FP1);
            w.set_sms(Sms::EXT_CLOCK_MODE);
        });
        T.psc().write_value(0);
        T.arr().write(|w| w.set_arr(u16::MAX));
        T.egr().write(|w| w.set_ug(true));
        T.cnt().write(|w| w.set_cnt(0));
        T.cr1().write(|w| w.set_cen(true));
    }

    /// STEP rises counted (modulo 2¹⁶).
    pub fn steps() -> u16 {
        T.cnt().read().cnt()
    }

    /// Prescaler of the pulse timing: 84 MHz, 11.9 ns per tick, 780 µs range.
    pub const TIMING_HZ: u32 = 84_000_000;

    /// Times every X STEP pulse (PWM input: the counter restarts at each rise;
    /// capture 1 = the period that ended there, capture 2 = the high time).
    pub fn time_steps() {
        probe_pin();
        T.cr1().write(|_| {});
        T.ccmr_input(0).write(|w| {
            w.set_ccs(0, CcmrInputCcs::TI4); // IC1 on TI1
            w.set_ccs(1, CcmrInputCcs::TI3); // IC2 on TI1 too
        });
        T.ccer().write(|w| {
            w.set_ccp(0, false); // IC1 at the rise
            w.set_ccp(1, true); // IC2 at the fall
            w.set_cce(0, true);
            w.set_cce(1, true);
        });
        T.smcr().write(|w| {
            w.set_ts(Ts::TI1FP1);
            w.set_sms(Sms::RESET_MODE);
        });
        T.psc().write_value((crate::board::bench::PROBE_TIMER_HZ / TIMING_HZ - 1) as u16);
        T.arr().write(|w| w.set_arr(u16::MAX));
        T.egr().write(|w| w.set_ug(true));
        T.cr1().write(|w| w.set_cen(true));
    }

    /// The last pulse: (period, high time) in ticks of [`TIMING_HZ`], or `None` before
    /// a whole pulse was seen. A period of more than 780 µs reads short (wrapped).
    pub fn last_pulse() -> Option<(u32, u32)> {
        let sr = T.sr().read();
        if !(sr.ccif(0) && sr.ccif(1)) {
            return None;
        }
        let period = u32::from(T.ccr(0).read().ccr());
        let high = u32::from(T.ccr(1).read().ccr());
        Some((period, high))
    }

    /// Ticks of [`TIMING_HZ`] in ns.
    pub fn ns(ticks: u32) -> i64 {
        i64::from(ticks) * 1_000_000_000 / i64::from(TIMING_HZ)
    }
}

/// Moves of the bring-up tests, queued straight into the motion core.
pub mod moves {
    use interp_core::axis::Pos;
    use interp_core::canon::CanonSink;
    use interp_core::canon::{Action, Canon, Endpoint, Feed, FeedMode, Move, SpindleSpeed};

    use crate::motion::MotionPort;

    /// A millimetre, nm.
    pub const MM: i64 = 1_000_000;

    /// Queues a straight move to X `x` (radius), Z `z` (nm, machine) at `mm_min`;
    /// false if the planner is full.
    pub fn line(port: &mut MotionPort, x: i64, z: i64, mm_min: i64) -> bool {
        let at = Pos::xz(x, z);
        let m = Move {
            to: Endpoint { machine: at, work: at },
            feed: Feed { mode: FeedMode::PerMin, value: mm_min * MM },
            spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 0 },
            exact_stop: true,
            independent: false,
        };
        port.push(Canon { line: 0, action: Action::Linear(m) }).is_ok()
    }

    /// Waits (polling every millisecond) until the motion core is idle; false after
    /// `timeout_ms`.
    pub async fn wait_idle(port: &mut MotionPort, timeout_ms: u32) -> bool {
        for _ in 0..timeout_ms {
            if port.peek(|m| m.core.is_idle()).unwrap_or(true) {
                return true;
            }
            embassy_time::Timer::after_millis(1).await;
        }
        false
    }

    /// The commanded X position, whole steps.
    pub fn x_steps(port: &MotionPort) -> i64 {
        port.peek(|m| m.core.commanded()[interp_core::axis::Axis::X.index()] >> 16).unwrap_or(0)
    }
}
