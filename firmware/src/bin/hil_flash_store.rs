//! Bring-up test: the flash store (`firmware::saved`: `controller::persist` on the
//! store sectors) writes, reads back, and survives resets in the middle of a write.
//!
//! Run 1 formats the store (everything stored is erased: settings, offsets,
//! programs), writes eight parameters, reads them back. Then eight power-cut
//! cycles: each writes the eight parameters with a new value while TIM6 resets
//! the chip after a different delay (50 µs to 20 ms, inside the writes). After
//! each reset the store must open, and every parameter must hold its old or its
//! new value — a record is never half there. Last, the store is formatted again
//! (the firmware boots with defaults). A reset from software stops the flash
//! between two words, as most power cuts do; pull the supply during a run of
//! `hil_flash_store` to try the rest (docs/BRINGUP.md).
//!
//! `cargo run --release --bin hil_flash_store`
#![no_std]
#![no_main]

use embassy_executor::Spawner;
use firmware::board::Board;
use firmware::hil::Report;
use {defmt_rtt as _, panic_probe as _};

/// Parameters written (numbers outside the machine description's).
#[cfg(persist)]
const PARAMS: core::ops::Range<u16> = 9_000..9_008;
/// Power-cut cycles.
#[cfg(persist)]
const CYCLES: u32 = 8;
/// "Store test running" in [`STATE`]'s first word.
#[cfg(persist)]
const RUNNING: u32 = 0x53_54_4F_52; // "STOR"

/// Kept across a reset: the mark, the cycle, the value being written.
#[cfg(persist)]
#[unsafe(link_section = ".uninit.hil_flash_store")]
static mut STATE: core::mem::MaybeUninit<[u32; 3]> = core::mem::MaybeUninit::uninit();

/// Where [`STATE`] is (a plain static of words; only thread mode touches it).
#[cfg(persist)]
fn state() -> *mut [u32; 3] {
    core::ptr::addr_of_mut!(STATE).cast()
}

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_flash_store");
    let board = Board::new(firmware::chip::init());
    r.figure("store", i64::from(firmware::board::STORE_SIZE / 1024), "KB");
    #[cfg(persist)]
    store_test(&mut r, board);
    #[cfg(not(persist))]
    {
        let _ = board;
        r.skip("write, read and power cuts on the flash store", "QEMU's flash cannot be programmed");
    }
    r.finish()
}

/// The store test proper (board builds).
#[cfg(persist)]
fn store_test(r: &mut Report, board: Board) {
    use firmware::saved;
    let mut store = match saved::open(board.flash) {
        Ok(s) => s,
        Err(_) => {
            r.check("store opens", false);
            return;
        }
    };
    // SAFETY: see `state`.
    let [mark, cycle, value] = unsafe { state().read_volatile() };
    if mark != RUNNING {
        r.check("format", store.format().is_ok());
        r.check("write", PARAMS.clone().all(|n| store.save_param(n, 1).is_ok()));
        r.check("read back", read(&mut store).iter().all(|&v| v == 1));
        cut(&mut store, 0, 2);
    }
    // After a reset in the middle of writing `value` over `value - 1`.
    let values = read(&mut store);
    let old = i64::from(value) - 1;
    let whole = values.iter().all(|&v| v == old || v == i64::from(value));
    r.check("store opens after the cut, every record old or new", whole);
    if !whole || cycle + 1 >= CYCLES {
        r.figure("power-cut cycles", i64::from(cycle + 1), "cycles");
        r.check("store formatted for the firmware", store.format().is_ok());
        // SAFETY: see `state`.
        unsafe { state().write_volatile([0, 0, 0]) };
        return;
    }
    cut(&mut store, cycle + 1, value + 1);
}

/// The stored values of [`PARAMS`] (0 where missing).
#[cfg(persist)]
fn read(store: &mut firmware::saved::Store) -> [i64; 8] {
    let mut v = [0; 8];
    let _ = store.load_params(|n, x| {
        if let Some(slot) = v.get_mut(usize::from(n.wrapping_sub(PARAMS.start))) {
            *slot = x;
        }
    });
    v
}

/// Power-cut cycle `cycle`: arms TIM6 to reset the chip, then writes `value`
/// into every parameter (over and over, until the reset comes).
#[cfg(persist)]
fn cut(store: &mut firmware::saved::Store, cycle: u32, value: u32) -> ! {
    use embassy_stm32::interrupt::{self, InterruptExt};
    use embassy_stm32::pac;
    // SAFETY: see `state`.
    unsafe { state().write_volatile([RUNNING, cycle, value]) };
    // 50 µs .. 20 ms, different every cycle (TIM6 at 1 MHz: 84 MHz / 84).
    let delay = 50 + (cycle.wrapping_mul(2_654_435_761) >> 8) % 19_950;
    pac::RCC.apb1enr().modify(|w| w.set_tim6en(true));
    let t = pac::TIM6;
    t.psc().write_value(83);
    t.arr().write(|w| w.set_arr(delay as u16));
    t.egr().write(|w| w.set_ug(true));
    t.sr().write_value(pac::timer::regs::SrCore(0));
    t.dier().write(|w| w.set_uie(true));
    // SAFETY: the handler below only resets the chip.
    unsafe { interrupt::TIM6_DAC.enable() };
    t.cr1().write(|w| w.set_cen(true));
    loop {
        for n in PARAMS {
            let _ = store.save_param(n, i64::from(value));
        }
    }
}

/// TIM6's update: the "power cut".
#[cfg(persist)]
#[allow(non_snake_case)]
#[unsafe(no_mangle)]
extern "C" fn TIM6_DAC() {
    cortex_m::peripheral::SCB::sys_reset();
}

firmware::hil_qemu_entry!();
