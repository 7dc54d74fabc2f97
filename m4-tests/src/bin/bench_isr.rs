//! Instruction counts of the firmware's interrupt bodies on the Cortex-M4F — the code
//! the step (TIM2), period (TIM7) and encoder-count (TIM5) interrupts run, from
//! `motion-driver`, with the same motion core and machine as the board:
//!
//! - period interrupt (`Engine::period`): `MotionCore::tick` one period ahead and
//!   every step edge of that period queued — on a line at 1000 mm/min, on an arc, and
//!   in a rapid with both axes at their top rates (the worst case: most steps);
//! - step interrupt (`Player::run`): one edge, edges on three axes at once, a pulse
//!   end, nothing due;
//! - encoder-count interrupt (`Engine::encoder`, then `Engine::window` for the
//!   compares) at the counts where a step of a G32 falls due, 4096 counts per
//!   revolution: single interrupts, the sum per spindle revolution at 500, 2000 and
//!   3000 rpm, and the largest part before the step is queued (the step latency);
//!   `sync_cpu.py` turns the sums into CPU shares per revolution.
//!
//! The register reads and writes around these bodies (about 10 loads and stores)
//! and the interrupt entry and exit (12 + 12 cycles on the M4) come on top. Run
//! through `bench.sh bench_isr`.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::axis::Pos;
use interp_core::canon::{
    Action, ArcMove, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, Plane, SpindleCommand, SpindleDir,
    SpindleSpeed, ThreadMove, ThreadSync,
};
use interp_core::config::MachineConfig;
use m4_tests::{exit, measure};
use motion_core::motion::State;
use motion_core::sync::Phase;
use motion_driver::board::{self, BoardEngine, BoardPlayer, Core};
use motion_driver::encoder::Window;
use motion_driver::engine::{Engine, EngineAxis, RING, Sample};
use motion_driver::playback::{AxisPins, PlayTiming, Player};
use motion_driver::ring::{Edge, EdgeRing, Timed};
use motion_driver::timebase::TimeBase;

const MM: i64 = 1_000_000;
/// The board's step timer clock.
const TIMER_HZ: u32 = 84_000_000;

fn at(x: i64, z: i64) -> Endpoint {
    let p = Pos::xz(x, z);
    Endpoint { machine: p, work: p }
}

fn spindle(rpm: u32) -> SpindleSpeed {
    SpindleSpeed { rpm: Some(rpm), css: None, max_rpm: 3_000 }
}

fn linear(x: i64, z: i64, mm_min: i64) -> Action {
    let feed = Feed { mode: FeedMode::PerMin, value: mm_min * MM };
    Action::Linear(Move { to: at(x, z), feed, spindle: spindle(1_000), exact_stop: true, independent: false })
}

fn rapid(x: i64, z: i64) -> Action {
    let feed = Feed { mode: FeedMode::PerMin, value: 0 };
    Action::Rapid(Move { to: at(x, z), feed, spindle: spindle(1_000), exact_stop: true, independent: false })
}

/// The machine the firmware runs and its driven axes X, Z, C (rings 0–2).
struct Rig {
    core: Core,
    engine: BoardEngine,
    player: BoardPlayer,
    /// Simulated step timer and spindle.
    now: u32,
    /// Step timer tick the player has played up to.
    played: u32,
    count: f64,
    counts_per_tick: f64,
    /// The encoder timer's compare values (TIM5 channels 3 and 4), and its count
    /// as the count interrupt reads it.
    window: Window,
    raw: u32,
}

/// Rings for the rigs (each rig splits its own three).
static RINGS: [[EdgeRing<RING>; 3]; 2] =
    [[EdgeRing::new(), EdgeRing::new(), EdgeRing::new()], [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()]];

impl Rig {
    fn new(rings: &'static [EdgeRing<RING>; 3], pos: Pos) -> Rig {
        let cfg = MachineConfig::default();
        let core: Core = Core::new(&cfg, pos).unwrap_or_else(|_| exit(false));
        let tb = TimeBase::new(TIMER_HZ, cfg.motion.tick_ns).unwrap_or_else(|_| exit(false));
        let ends = rings.each_ref().map(|r| r.split().unwrap_or_else(|| exit(false)));
        let pins = [AxisPins { step: 6, dir: 10 }, AxisPins { step: 7, dir: 11 }, AxisPins { step: 8, dir: 12 }];
        let axis = [0usize, 2, 3];
        let timing = |a: usize| {
            let t = core.stepper(a).map(|s| s.timing()).unwrap_or_else(|| exit(false));
            PlayTiming::new(t, &tb)
        };
        let [(tx, rx), (tz, rz), (tc, rc)] = ends;
        let player = Player::new([
            (rx, pins[0], timing(axis[0])),
            (rz, pins[1], timing(axis[1])),
            (rc, pins[2], timing(axis[2])),
        ]);
        let engine = Engine::new(
            tb,
            [EngineAxis::new(axis[0], tx), EngineAxis::new(axis[1], tz), EngineAxis::new(axis[2], tc)],
            0,
            0,
        );
        Rig { core, engine, player, now: 0, played: 0, count: 0.0, counts_per_tick: 0.0, window: Window::OFF, raw: 0 }
    }

    /// The spindle's raw count and the raw count at its last index (every 4096).
    fn encoder(&self) -> (u32, Option<u32>) {
        let c = self.count as u32;
        (c, (c >= 4_096).then_some(c & !4_095))
    }

    fn sample(&self) -> Sample {
        let (raw_count, index) = self.encoder();
        Sample { now: self.now, raw_count, index, estop: false }
    }

    /// Plays every edge due by `self.now` at its own time (what the step interrupt
    /// does meanwhile), from where the last call stopped.
    fn play(&mut self) {
        let mut t = self.played;
        for _ in 0..10_000 {
            match board::play(&mut self.player, t, false).next {
                Some(n) if self.now.wrapping_sub(n) as i32 >= 0 => {
                    t = if n.wrapping_sub(t) as i32 > 0 { n } else { t.wrapping_add(1) };
                }
                _ => break,
            }
        }
        self.played = self.now;
    }

    /// One period (unmeasured): the period interrupt, then the period's playing.
    fn period(&mut self) {
        let s = self.sample();
        board::period(&mut self.engine, &mut self.core, s);
        self.advance_period();
    }

    fn advance_period(&mut self) {
        let ticks = self.engine.time_base().period_ticks;
        let step = ticks / 16;
        for _ in 0..16 {
            self.now = self.now.wrapping_add(step);
            self.count += self.counts_per_tick / 16.0;
            self.play();
        }
    }
}

/// The period interrupt's body.
fn period(rig: &mut Rig) {
    let s = rig.sample();
    board::period(&mut rig.engine, &mut rig.core, s);
}

/// The step interrupt's body at the rig's time.
fn step(rig: &mut Rig) -> u32 {
    board::play(&mut rig.player, rig.now, false).bsrr
}

/// Measures three period interrupts after `warm` periods of `action`.
fn bench_periods(rig: &mut Rig, label: &str, warm: u32) {
    for _ in 0..warm {
        rig.period();
    }
    hprintln!("bench period interrupt: {} ({} edges queued so far)", label, rig.engine.stats().edges);
    for _ in 0..3 {
        measure(period, &mut *rig);
        rig.advance_period();
    }
}

fn periods() {
    let mut rig = Rig::new(&RINGS[0], Pos::xz(40 * MM, 0));
    let _ = rig.core.push(Canon { line: 1, action: linear(40 * MM, -100 * MM, 1_000) });
    let arc = ArcMove {
        to: at(40 * MM, -140 * MM),
        center: at(40 * MM, -120 * MM),
        plane: Plane::Zx,
        cw: true,
        full_circle: false,
        feed: Feed { mode: FeedMode::PerMin, value: 1_000 * MM },
        spindle: spindle(1_000),
        exact_stop: true,
    };
    let _ = rig.core.push(Canon { line: 2, action: Action::Arc(arc) });
    // A rapid that leaves X and Z at their top rates together (6000 and 8000 mm/min).
    let _ = rig.core.push(Canon { line: 3, action: rapid(40 * MM + 75 * MM, -140 * MM - 100 * MM) });
    bench_periods(&mut rig, "line at 1000 mm/min (Z, 5.3 steps per period)", 300);
    while rig.core.line() == 1 {
        rig.period();
    }
    bench_periods(&mut rig, "arc R20 at 1000 mm/min", 300);
    while rig.core.line() == 2 {
        rig.period();
    }
    bench_periods(&mut rig, "rapid X 6000 + Z 8000 mm/min (40 + 43 steps per period)", 400);
    let st = rig.engine.stats();
    if st.late != 0 || st.ring_full != 0 {
        hprintln!("late {} ring full {}", st.late, st.ring_full);
        exit(false);
    }
}

fn steps() {
    static PLAY: [EdgeRing<RING>; 3] = [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()];
    let t = PlayTiming { pulse: 210, dir_setup: 420, min_period: 840 };
    let pins = [AxisPins { step: 6, dir: 10 }, AxisPins { step: 7, dir: 11 }, AxisPins { step: 8, dir: 12 }];
    let [(mut tx, rx), (mut tz, rz), (mut tc, rc)] = PLAY.each_ref().map(|r| r.split().unwrap_or_else(|| exit(false)));
    let mut player = Player::new([(rx, pins[0], t), (rz, pins[1], t), (rc, pins[2], t)]);
    let _ = tx.push(Timed { at: 1_000, edge: Edge::Step });
    let _ = tx.push(Timed { at: 5_000, edge: Edge::Step });
    let _ = tz.push(Timed { at: 5_000, edge: Edge::Step });
    let _ = tc.push(Timed { at: 5_000, edge: Edge::Dir(true) });
    let run = |input: (&mut BoardPlayer, u32)| board::play(input.0, input.1, false).bsrr;
    hprintln!("bench step interrupt: nothing due");
    measure(run, (&mut player, 500));
    hprintln!("bench step interrupt: one STEP rise");
    measure(run, (&mut player, 1_000));
    hprintln!("bench step interrupt: its pulse end");
    measure(run, (&mut player, 1_210));
    hprintln!("bench step interrupt: X and Z rise, C direction, one write");
    let bsrr = measure(run, (&mut player, 5_000));
    if bsrr != (1 << 6) | (1 << 7) | (1 << 12) {
        exit(false);
    }
    let mut rig = Rig::new(&RINGS[1], Pos::xz(40 * MM, 0));
    let _ = rig.core.push(Canon { line: 1, action: rapid(40 * MM + 75 * MM, -100 * MM) });
    for _ in 0..300 {
        rig.period();
    }
    hprintln!("bench step interrupt in a rapid (next edge of the queue)");
    let s = rig.sample();
    board::period(&mut rig.engine, &mut rig.core, s);
    for _ in 0..4 {
        let mut next = board::play(&mut rig.player, rig.now, false).next.unwrap_or(rig.now);
        if next.wrapping_sub(rig.now) as i32 <= 0 {
            next = rig.now.wrapping_add(1);
        }
        rig.now = next;
        measure(step, &mut rig);
    }
}

/// The count interrupt's body (TIM5, P1) as the board runs it: the reading to the
/// core and the steps it makes queued (the step interrupt is pended then), the
/// compares set to the next due counts, and whether a fresh reading has already
/// reached one (then it runs again).
fn count_isr(rig: &mut Rig) -> bool {
    count_isr_step(rig);
    count_isr_window(rig)
}

/// Its first part: up to the step edges queued (what a due step waits for).
fn count_isr_step(rig: &mut Rig) -> bool {
    board::encoder(&mut rig.engine, &mut rig.core, rig.now, rig.raw)
}

/// Its second part: the gearbox glides to the next due counts, the compares are set.
fn count_isr_window(rig: &mut Rig) -> bool {
    rig.window = board::window(&mut rig.engine, &mut rig.core);
    rig.engine.reached(&rig.window, rig.raw)
}

/// What a thread run measures.
#[derive(Clone, Copy, PartialEq)]
enum Sums {
    /// The whole count interrupt, summed per spindle revolution.
    Revolutions,
    /// Only its first part, summed over the pass: the largest is the worst step latency.
    Latency,
    /// Only its second part (for profiling).
    Window,
    /// The whole count interrupt, summed over the ramps' interrupts only (for
    /// profiling what a ramp's step costs more than a locked one's).
    Ramps,
    /// A few single interrupts and periods of the locked pass, each printed.
    Singles,
}

/// A G32 from X20 Z5 to X`x_end` Z−40 (radius, mm; a taper unless 20) at `lead_um`,
/// the spindle turning at `rpm` from the start with 4096 counts a revolution and an
/// index at every 4096th. The count interrupt runs only when the count reaches one
/// of the compares the engine sets (as TIM5's on the board), the period interrupt
/// every 84,000 ticks, the edges are played when due.
fn thread_at(rings: &'static [EdgeRing<RING>; 3], rpm: u32, lead_um: i64, x_end: i64, sums: Sums) {
    let mut rig = Rig::new(rings, Pos::xz(20 * MM, 5 * MM));
    let on = SpindleCommand { dir: SpindleDir::Cw, rpm: Some(rpm), css: None };
    let _ = rig.core.push(Canon { line: 1, action: Action::Spindle(on) });
    let thread = ThreadMove {
        to: at(x_end * MM, -40 * MM),
        lead: lead_um * 1_000,
        lead_delta: 0,
        start_udeg: 0,
        sync: ThreadSync::Index,
        spindle: spindle(rpm),
    };
    let _ = rig.core.push(Canon { line: 2, action: Action::Thread(thread) });
    let _ = rig.core.push(Canon { line: 3, action: Action::End { rewind: false } });
    let ticks_per_count = f64::from(TIMER_HZ) * 60.0 / (f64::from(rpm) * 4_096.0);
    let period_ticks = rig.engine.time_base().period_ticks;
    let (mut next_period, mut next_count) = (0u32, ticks_per_count);
    let (mut count, mut edges, mut singles) = (0u32, 0u32, 0u32);
    let measured_isr = match sums {
        Sums::Revolutions => |rig: &mut Rig| m4_tests::measure_sum(count_isr, rig),
        Sums::Latency => |rig: &mut Rig| {
            m4_tests::measure_sum(count_isr_step, rig);
            count_isr_window(rig)
        },
        Sums::Window => |rig: &mut Rig| {
            count_isr_step(rig);
            m4_tests::measure_sum(count_isr_window, rig)
        },
        Sums::Singles => count_isr,
        Sums::Ramps => |rig: &mut Rig| {
            if rig.core.gear().is_some_and(|g| matches!(g.phase(), Phase::RampUp { .. } | Phase::RampDown { .. })) {
                m4_tests::measure_sum(count_isr, rig)
            } else {
                count_isr(rig)
            }
        },
    };
    for _ in 0..40_000_000u32 {
        if f64::from(next_period) <= next_count {
            rig.now = next_period;
            let locked = rig.core.state() == State::Locked && rig.core.stats().ticks % 37 == 0;
            if sums == Sums::Singles && locked && singles < 3 {
                hprintln!("bench period interrupt, G32 locked, {} rpm (the count interrupt waits for it)", rpm);
                measure(period, &mut rig);
                singles += 1;
            } else {
                period(&mut rig);
            }
            next_period = next_period.wrapping_add(period_ticks);
            rig.window = board::window(&mut rig.engine, &mut rig.core);
            if rig.engine.reached(&rig.window, rig.raw) {
                while measured_isr(&mut rig) {}
            }
            if rig.core.ended() && rig.core.is_idle() {
                break;
            }
        } else {
            rig.now = next_count as u32;
            next_count += ticks_per_count;
            count += 1;
            rig.count = f64::from(count);
            rig.raw = count;
            if rig.window.up == Some(count) || rig.window.down == Some(count) {
                let locked = rig.core.gear().is_some_and(|g| g.phase() == Phase::Locked && g.remaining() < 8_000);
                if sums == Sums::Singles && locked && (3..11).contains(&singles) {
                    if singles == 3 {
                        hprintln!(
                            "bench count interrupt at a due count, G32 locked: to the step queued, then the compares"
                        );
                    }
                    measure(count_isr_step, &mut rig);
                    while measure(count_isr_window, &mut rig) {
                        count_isr(&mut rig);
                    }
                    singles += 1;
                } else {
                    while measured_isr(&mut rig) {}
                }
            }
            if sums == Sums::Revolutions && count % 4_096 == 0 && rig.core.gear().is_some() {
                let e = rig.engine.stats().edges;
                let phase = rig.core.gear().map(|g| g.phase());
                hprintln!("revolution {} ({:?}): {} edges; count interrupt:", count / 4_096, phase, e - edges);
                m4_tests::report_sum();
            }
            if count % 4_096 == 0 {
                edges = rig.engine.stats().edges;
            }
        }
        rig.play();
    }
    if sums == Sums::Revolutions {
        hprintln!("the rest of the pass; count interrupt:");
        m4_tests::report_sum();
    }
    let st = rig.engine.stats();
    hprintln!(
        "thread {} rpm, lead {} um, X{} at the end: {} counts, {} count interrupts ({} moved an axis), Z at {} steps, X at {}",
        rpm,
        lead_um,
        x_end,
        count,
        st.sync_counts,
        st.sync_moves,
        rig.core.steps()[2],
        rig.core.steps()[0]
    );
    if sums == Sums::Latency {
        hprintln!("count interrupt up to the step queued, over the pass:");
        m4_tests::report_sum();
    }
    if !rig.core.ended() || rig.core.steps()[2] != -40 * 320 || st.ring_full != 0 || rig.core.alarm().is_some() {
        hprintln!("thread failed: {:?} {:?}", rig.core.state(), rig.core.alarm());
        exit(false);
    }
}

fn threads() {
    static T: [[EdgeRing<RING>; 3]; 6] = [const { [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()] }; 6];
    // Single interrupts of a locked pass, then per revolution: 1.5 mm (the most the
    // default Z takes at 3000 rpm, 10 % margin) at 500, 2000, 3000 rpm, and the most
    // the Z's 5000 mm/min allows at 500 and 2000 (9 and 2.25 mm: 24,000 steps/s).
    thread_at(&T[0], 2_000, 1_500, 20, Sums::Singles);
    for (k, (rpm, lead)) in [(500, 1_500), (2_000, 1_500), (3_000, 1_500), (500, 9_000)].into_iter().enumerate() {
        hprintln!("bench count interrupts per spindle revolution, G32 {} um lead at {} rpm × 4096 counts", lead, rpm);
        thread_at(&T[k + 1], rpm, lead, 20, Sums::Revolutions);
    }
    // The worst step latency: a taper (both axes step at some counts) at 3000 rpm.
    hprintln!("bench count interrupt up to the step queued, taper X20 -> X22 over Z45 at 3000 rpm, 1.5 mm lead");
    thread_at(&T[5], 3_000, 1_500, 22, Sums::Latency);
}

/// `BENCH_ONLY=sync` (at build time) measures only the count interrupt of one
/// 2000 rpm pass, summed per revolution (for `profile.sh bench_isr`); `singles` its
/// single interrupts; `latency` only their part up to the step queued; `ramps`
/// the interrupts of a 3000 rpm pass's ramps.
const ONLY: Option<&str> = option_env!("BENCH_ONLY");

#[entry]
fn main() -> ! {
    if let Some(only @ ("sync" | "singles" | "latency" | "window" | "ramps")) = ONLY {
        static T: [EdgeRing<RING>; 3] = [EdgeRing::new(), EdgeRing::new(), EdgeRing::new()];
        let sums = match only {
            "sync" => Sums::Revolutions,
            "singles" => Sums::Singles,
            "window" => Sums::Window,
            "ramps" => Sums::Ramps,
            _ => Sums::Latency,
        };
        thread_at(&T, if sums == Sums::Ramps { 3_000 } else { 2_000 }, 1_500, 20, sums);
        exit(true)
    }
    periods();
    steps();
    threads();
    exit(true)
}
