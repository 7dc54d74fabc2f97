//! Dense programs on the Cortex-M4F (issue 22): a CAM-style chain of G01 blocks
//! of 0.01, 0.02 and 0.05 mm along a smooth curve at F6000, run through the whole
//! chain the board runs — the interpreter from the program text to the planned
//! block (`Interpreter::step` into the motion core, what the control task does),
//! the period interrupt (`Engine::period`: `MotionCore::tick` for the next period,
//! crossing as many blocks as the period's distance covers, and its step edges
//! queued) and the step interrupt (`Player::run` for every edge).
//!
//! Machine: the default lathe with X and Z at 5,000 mm/s² and 10 m/min (a servo
//! retrofit; on the default 500 mm/s² the 64-block queue limits such chains, see
//! docs/PERFORMANCE.md). After the chain has reached its speed, ten periods are
//! measured; each prints three counts: the period's fill (every block's text to
//! planned block, with the number of blocks), the period interrupt (blocks it
//! crossed, edges it queued) and all its step interrupts together (how many).
//! `python3 m4-tests/dense.py` sums them per block and as CPU load at 168 MHz.
//!
//! Run: `m4-tests/bench.sh bench_dense | python3 m4-tests/dense.py`
#![no_std]
#![no_main]

use core::fmt::Write as _;

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::config::{MachineConfig, Param};
use interp_core::{Interpreter, Panel, Progress, SingleProgram};
use m4_tests::{exit, measure};
use motion_core::motion::QUEUE;
use motion_driver::board::{self, BoardEngine, BoardPlayer, Core};
use motion_driver::engine::{Engine, EngineAxis, RING, Sample};
use motion_driver::playback::{AxisPins, PlayTiming, Player};
use motion_driver::ring::EdgeRing;
use motion_driver::timebase::TimeBase;

const MM: i64 = 1_000_000;
/// The board's step timer clock.
const TIMER_HZ: u32 = 84_000_000;
/// Blocks of each program.
const BLOCKS: usize = 1_500;

type Text = heapless::String<40_000>;

/// The lathe with X and Z at 5,000 mm/s² and 10 m/min.
fn machine() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    for ax in [Axis::X, Axis::Z] {
        cfg.axes[ax.index()].accel_per_s2 = 5_000 * MM;
        cfg.axes[ax.index()].max_feed_per_min = 10_000 * MM;
    }
    cfg.params.set(Param::MaxCuttingFeed, 10_000 * MM);
    cfg
}

/// `BLOCKS` blocks of `seg_um` µm along X = 80 + 4·sin(z / 10 mm) (diameter), in
/// IS-B text as CAM posts it: `X80.123 Z-0.020`.
fn program(seg_um: i64, text: &mut Text) {
    let mm = |t: &mut Text, v: i64| {
        let sign = if v < 0 { "-" } else { "" };
        let _ = write!(t, "{}{}.{:03}", sign, v.abs() / 1000, v.abs() % 1000);
    };
    let _ = text.push_str("G98 G01 F6000\n");
    for k in 1..=BLOCKS as i64 {
        let z_um = -k * seg_um;
        let x_um = libm::round(80_000.0 + 4_000.0 * libm::sin(z_um as f64 / 10_000.0)) as i64;
        let _ = text.push_str("X");
        mm(text, x_um);
        let _ = text.push_str(" Z");
        mm(text, z_um);
        let _ = text.push_str("\n");
    }
    let _ = text.push_str("M30\n");
}

/// The board's motion interrupts and what they drive: X and Z (rings 0–1; C on
/// ring 2 stands still), through the functions the board's interrupts call.
struct Rig {
    core: Core,
    engine: BoardEngine,
    player: BoardPlayer,
    /// Step timer now, and how far the player has played.
    now: u32,
    played: u32,
}

impl Rig {
    fn new(rings: &'static [EdgeRing<RING>; 3], cfg: &MachineConfig, pos: Pos) -> Rig {
        let core = Core::new(cfg, pos).unwrap_or_else(|_| exit(false));
        let tb = TimeBase::new(TIMER_HZ, cfg.motion.tick_ns).unwrap_or_else(|_| exit(false));
        let [(tx, rx), (tz, rz), (tc, rc)] = rings.each_ref().map(|r| r.split().unwrap_or_else(|| exit(false)));
        let timing =
            |a: Axis| PlayTiming::new(core.stepper(a.index()).map(|s| s.timing()).unwrap_or_else(|| exit(false)), &tb);
        let player = Player::new([
            (rx, AxisPins { step: 6, dir: 10 }, timing(Axis::X)),
            (rz, AxisPins { step: 7, dir: 11 }, timing(Axis::Z)),
            (rc, AxisPins { step: 8, dir: 12 }, timing(Axis::C)),
        ]);
        let axes = [
            EngineAxis::new(Axis::X.index(), tx),
            EngineAxis::new(Axis::Z.index(), tz),
            EngineAxis::new(Axis::C.index(), tc),
        ];
        let engine = Engine::new(tb, axes, 0, 0);
        Rig { core, engine, player, now: 0, played: 0 }
    }

    /// Moves the step timer on by one period.
    fn advance(&mut self) {
        self.now = self.now.wrapping_add(self.engine.time_base().period_ticks);
    }
}

/// The motion core as the board's control task reaches it: each action through
/// the non-generic push (`motion_driver::board::push`).
struct Port<'a>(&'a mut Core);

impl CanonSink for Port<'_> {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        board::push(self.0, &c)
    }

    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        board::push(self.0, c)
    }
}

/// The control task's part of a period: the interpreter steps (each block from
/// its text to its planned block, through the non-generic entry the firmware
/// calls) until the queue is full; returns the blocks.
fn fill(input: (&mut Interpreter, &SingleProgram, &mut Core)) -> u32 {
    let (interp, store, core) = input;
    let mut blocks = 0;
    for _ in 0..4 * QUEUE {
        match interp.step_dyn(store, &Panel::default(), &mut Port(&mut *core)) {
            Ok(Progress::Executed { .. }) => blocks += 1,
            Ok(Progress::Blocked | Progress::Ended | Progress::Paused) => break,
            Ok(_) => {}
            Err(_) => exit(false),
        }
    }
    blocks
}

/// The period interrupt's body.
fn period(rig: &mut Rig) {
    let s = Sample { now: rig.now, raw_count: 0, index: None, estop: false };
    board::period(&mut rig.engine, &mut rig.core, s);
}

/// Every step interrupt of the period that has just played, each at its edge's
/// tick (what TIM2's compare does); returns how many ran.
fn play(rig: &mut Rig) -> u32 {
    let mut t = rig.played;
    let mut runs = 0;
    for _ in 0..10_000 {
        runs += 1;
        match board::play(&mut rig.player, t, false).next {
            Some(n) if rig.now.wrapping_sub(n) as i32 >= 0 => {
                t = if n.wrapping_sub(t) as i32 > 0 { n } else { t.wrapping_add(1) };
            }
            _ => break,
        }
    }
    rig.played = rig.now;
    runs
}

fn run(rings: &'static [EdgeRing<RING>; 3], seg_um: i64, text: &mut Text) {
    text.clear();
    program(seg_um, text);
    let cfg = machine();
    let store = SingleProgram(text.as_bytes());
    let mut interp = Interpreter::new(cfg.clone());
    let mut rig = Rig::new(rings, &cfg, Pos::xz(40 * MM, 0));
    // Up to speed (1 mm at 5,000 mm/s² from rest), then ten periods measured.
    for k in 0..70u32 {
        let measured = k >= 60;
        if measured {
            hprintln!("bench dense {} um: period {}", seg_um, k);
        }
        let blocks = if measured {
            measure(fill, (&mut interp, &store, &mut rig.core))
        } else {
            fill((&mut interp, &store, &mut rig.core))
        };
        let (crossed, edges) = (rig.core.stats().blocks, rig.engine.stats().edges);
        if measured {
            measure(period, &mut rig);
        } else {
            period(&mut rig);
        }
        let crossed = rig.core.stats().blocks - crossed;
        let edges = rig.engine.stats().edges - edges;
        rig.advance();
        let runs = if measured { measure(play, &mut rig) } else { play(&mut rig) };
        if measured {
            let speed = rig.core.path_speed() / 1_000_000;
            hprintln!(
                "fill {} blocks, period crossed {} blocks, {} edges, {} step interrupts, {} mm/min",
                blocks,
                crossed,
                edges,
                runs,
                speed
            );
        }
    }
    let st = rig.core.stats();
    let es = rig.engine.stats();
    if st.starvations != 0 || st.overruns != 0 || es.late != 0 || es.ring_full != 0 || rig.core.alarm().is_some() {
        hprintln!("starved {} overruns {} late {} ring full {}", st.starvations, st.overruns, es.late, es.ring_full);
        exit(false);
    }
}

#[entry]
fn main() -> ! {
    static RINGS: [[EdgeRing<RING>; 3]; 3] = [const { [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()] }; 3];
    let mut text = Text::new();
    for (rings, seg_um) in RINGS.iter().zip([10, 20, 50]) {
        run(rings, seg_um, &mut text);
    }
    exit(true)
}
