//! What the QEMU `netduinoplus2` build (feature `qemu`) needs: QEMU's STM32F405 has
//! no usable TIM4 for embassy's time driver and never sets some ready bits, so this
//! build keeps time with SysTick, works around the RCC and PWR, and runs its tasks
//! on an executor that sleeps in WFI ([`run_executor`]).
//!
//! PWR is not modelled at all (reads are 0), and `embassy_stm32::init` always waits
//! for PWR's DBP bit (backup-domain unlock), with interrupts masked. During init the
//! MPU traps every PWR access; the fault handler emulates PWR's two registers as
//! plain memory (DBP reads back as written) and returns past the instruction. After
//! init the MPU is off again and SysTick runs the time driver.

use core::cell::{Cell, RefCell};
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use core::task::Waker;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{MPU, SYST};
use critical_section::{CriticalSection, Mutex};
use embassy_executor::{Spawner, raw};
use embassy_time_driver::Driver;
use embassy_time_queue_utils::Queue;
use static_cell::StaticCell;

/// SysTick interrupts per second: the time driver's resolution is 1 ms (tasks wake
/// on the next millisecond tick), its clock counts microseconds.
const SYSTICK_HZ: u32 = 1_000;
/// The clock QEMU runs SysTick from with CLKSOURCE = core: `netduinoplus2` feeds
/// the Cortex-M4 a fixed 168 MHz SYSCLK whatever the (barely modelled) RCC says, so
/// not the 16 MHz HSI this build leaves selected. (With 16 MHz here the time
/// driver ticked every 95 µs of QEMU's clock: the firmware's millisecond ran 10.5
/// times too fast, as fast as the host let QEMU deliver ticks, and the control
/// task was forever behind its ticker — issue 18.)
const CORE_HZ: u32 = 168_000_000;

/// QEMU's RCC resets CR to a value without HSIRDY; writing the reset value 0x83
/// (HSION, HSIRDY, trim 16) first lets `embassy_stm32::init` see the HSI ready.
pub fn rcc_workaround() {
    embassy_stm32::pac::RCC.cr().write_value(embassy_stm32::pac::rcc::regs::Cr(0x83));
}

/// A time driver on SysTick: a millisecond counter and a queue of wakers.
struct SysTickDriver {
    ms: Mutex<Cell<u64>>,
    queue: Mutex<RefCell<Queue>>,
}

embassy_time_driver::time_driver_impl!(static DRIVER: SysTickDriver = SysTickDriver {
    ms: Mutex::new(Cell::new(0)),
    queue: Mutex::new(RefCell::new(Queue::new())),
});

impl SysTickDriver {
    fn now_cs(&self, cs: CriticalSection) -> u64 {
        self.ms.borrow(cs).get() * 1_000
    }

    /// One SysTick: advances the clock and wakes every task whose time has come.
    fn on_tick(&self) {
        critical_section::with(|cs| {
            let ms = self.ms.borrow(cs);
            ms.set(ms.get() + 1);
            let now = self.now_cs(cs);
            self.queue.borrow(cs).borrow_mut().next_expiration(now);
        });
    }
}

impl Driver for SysTickDriver {
    fn now(&self) -> u64 {
        critical_section::with(|cs| self.now_cs(cs))
    }

    fn schedule_wake(&self, at: u64, waker: &Waker) {
        critical_section::with(|cs| {
            let mut q = self.queue.borrow(cs).borrow_mut();
            q.schedule_wake(at, waker);
            // Wake what is already due; the rest waits for the next tick.
            q.next_expiration(self.now_cs(cs));
        });
    }
}

/// Set by [`pender`] when a task was woken: the executor polls again before it
/// sleeps.
static WOKEN: AtomicBool = AtomicBool::new(false);

/// The executor's pender (embassy calls it when a task is woken, from a task or an
/// interrupt).
#[unsafe(export_name = "__pender")]
fn pender(_context: *mut ()) {
    WOKEN.store(true, Ordering::Release);
}

/// The QEMU build's thread-mode executor: embassy's raw executor, asleep in WFI
/// while no task is ready. embassy's own (`executor-thread`) sleeps in WFE, which
/// QEMU 10 runs as a yield, not a sleep: the guest spins at full host speed and,
/// under `-icount`, its clock races through the idle loop at a few million
/// instructions per second of host time. With WFI QEMU halts the CPU until the
/// next interrupt (SysTick, USART2), so the guest's time is the instructions it
/// runs while busy and the host's time while idle (`qemu-test.py`).
pub fn run_executor(init: impl FnOnce(Spawner)) -> ! {
    static EXECUTOR: StaticCell<raw::Executor> = StaticCell::new();
    let executor: &'static raw::Executor = EXECUTOR.init(raw::Executor::new(core::ptr::null_mut()));
    init(executor.spawner());
    loop {
        // SAFETY: polled from this loop only, in thread mode.
        unsafe { executor.poll() };
        // With interrupts masked, a wake between the check and WFI still ends the
        // WFI (a pending interrupt does, masked or not), and its handler runs
        // after `free`.
        cortex_m::interrupt::free(|_| {
            if !WOKEN.swap(false, Ordering::AcqRel) {
                cortex_m::asm::wfi();
            }
        });
    }
}

/// Starts SysTick at 1 kHz as the time driver.
pub fn start_time_driver(syst: &mut SYST) {
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(CORE_HZ / SYSTICK_HZ - 1);
    syst.clear_current();
    syst.enable_interrupt();
    syst.enable_counter();
}

#[cortex_m_rt::exception]
fn SysTick() {
    DRIVER.on_tick();
}

/// PWR's registers as QEMU should have them: CR (DBP sticks once written) and CSR
/// (regulator ready, VOSRDY).
static PWR_REGS: [AtomicU32; 2] = [AtomicU32::new(0), AtomicU32::new(1 << 14)];
/// Base address of PWR on the STM32F4.
const PWR_BASE: u32 = 0x4000_7000;

/// Traps every access to PWR with the MPU (region 0: 1 KB, no access), so
/// [`pwr_fault`] can emulate it. Call before `embassy_stm32::init`.
pub fn trap_pwr(mpu: &mut MPU) {
    // SAFETY: region 0 covers PWR only; the default map stays for everything else.
    unsafe {
        mpu.rnr.write(0);
        mpu.rbar.write(PWR_BASE);
        // XN, AP = 000 (no access), SIZE = 9 (2^10 bytes), ENABLE.
        mpu.rasr.write((1 << 28) | (9 << 1) | 1);
        mpu.ctrl.write(0b101); // ENABLE, PRIVDEFENA
    }
    cortex_m::asm::dsb();
    cortex_m::asm::isb();
}

/// Ends the PWR emulation (after `embassy_stm32::init`).
pub fn untrap_pwr(mpu: &mut MPU) {
    // SAFETY: switching the MPU off restores the default memory map.
    unsafe { mpu.ctrl.write(0) };
    cortex_m::asm::dsb();
    cortex_m::asm::isb();
}

// HardFault entry (QEMU build only): the MPU's PWR trap escalates here (MemManage is
// not enabled, and embassy's init runs with interrupts masked). Passes the exception
// frame (r0–r3, r12, lr, pc, xpsr) and the saved r4–r11 to `pwr_fault`, and restores
// r4–r11 (possibly written) before returning.
core::arch::global_asm!(
    ".section .text.HardFault,\"ax\",%progbits",
    ".global HardFault",
    ".type HardFault,%function",
    ".thumb_func",
    "HardFault:",
    "  tst lr, #4",
    "  ite eq",
    "  mrseq r0, msp",
    "  mrsne r0, psp",
    "  push {{r3-r11, lr}}",
    "  mov r1, sp",
    "  bl {handler}",
    "  pop {{r3-r11, lr}}",
    "  bx lr",
    handler = sym pwr_fault,
);

/// Emulates the trapped load or store to PWR (`ldr`/`str` with an immediate offset,
/// 16- or 32-bit encodings) and returns past it; any other fault stops here.
extern "C" fn pwr_fault(frame: *mut u32, saved: *mut u32) {
    // SAFETY: the entry stub passes the exception frame and its 10 saved words
    // (r3, r4–r11, lr); the faulting instruction is readable code at the stacked pc.
    let done = unsafe { emulate(frame, saved) };
    if !done {
        // A real hard fault: stop here (a debugger shows where from the frame).
        loop {
            cortex_m::asm::nop();
        }
    }
}

/// The register `r` of the interrupted code: in the exception frame or saved.
///
/// # Safety
///
/// As [`pwr_fault`]'s pointers.
unsafe fn reg(frame: *mut u32, saved: *mut u32, r: u32) -> Option<*mut u32> {
    // SAFETY: offsets inside the frame (8 words) and the saved block (10 words).
    unsafe {
        match r {
            0..=3 => Some(frame.add(r as usize)),
            4..=11 => Some(saved.add(r as usize - 3)),
            12 => Some(frame.add(4)),
            _ => None,
        }
    }
}

/// Decodes and performs the faulting access; false if it is not one we emulate.
///
/// # Safety
///
/// As [`pwr_fault`]'s pointers.
unsafe fn emulate(frame: *mut u32, saved: *mut u32) -> bool {
    // SAFETY: see the callers.
    unsafe {
        let pc = frame.add(6).read_volatile();
        let h1 = u32::from((pc as *const u16).read_volatile());
        let h2 = u32::from(((pc + 2) as *const u16).read_volatile());
        let (load, rt, rn, imm, size) = match h1 {
            _ if h1 & 0xF800 == 0x6800 => (true, h1 & 7, (h1 >> 3) & 7, ((h1 >> 6) & 0x1F) * 4, 2),
            _ if h1 & 0xF800 == 0x6000 => (false, h1 & 7, (h1 >> 3) & 7, ((h1 >> 6) & 0x1F) * 4, 2),
            _ if h1 & 0xFFF0 == 0xF8D0 => (true, h2 >> 12, h1 & 15, h2 & 0xFFF, 4),
            _ if h1 & 0xFFF0 == 0xF8C0 => (false, h2 >> 12, h1 & 15, h2 & 0xFFF, 4),
            _ => return false,
        };
        let (Some(rt), Some(rn)) = (reg(frame, saved, rt), reg(frame, saved, rn)) else { return false };
        let addr = rn.read_volatile().wrapping_add(imm);
        let Some(cell) = PWR_REGS.get((addr.wrapping_sub(PWR_BASE) / 4) as usize) else { return false };
        if load {
            rt.write_volatile(cell.load(Ordering::Relaxed));
        } else {
            cell.store(rt.read_volatile(), Ordering::Relaxed);
        }
        frame.add(6).write_volatile(pc + size);
        true
    }
}
