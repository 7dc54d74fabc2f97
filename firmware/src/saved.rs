//! What survives power-off on the board: `controller::persist` on the flash store
//! region (F405 sectors 10–11, F446 sectors 1–3; the memory.x files keep code out), with what is kept and
//! how in [`controller::persist::keep`] (the same code `lathe board --flash` runs).
//!
//! At boot [`load_config`] reads the numbered parameters, the grbl `$n` settings
//! and the offsets (before the motion core is built from them), [`load_rest`] the
//! common variables #401–#600 and the programs into the controller. The controller
//! has no "something changed" hook, so [`Saver`] keeps a fingerprint of everything
//! stored; while the machine is at rest (controller Idle, motion core idle) it
//! compares every [`keep::CHECK_NS`] and, if it (or a common variable) changed,
//! writes what changed: every store call writes only records that differ.
//!
//! Erasing a 128 KB sector stalls the CPU (interrupts included) for 1–2 s (a 16 KB
//! one on the F446 about 0.25–0.5 s), which is
//! why this runs only at rest; during a save the watchdog timeout is raised to
//! [`SAVE_WATCHDOG_US`] and put back to the normal timeout afterwards. Bytes that
//! arrive on the link during an erase can be lost (the UART interrupt is stalled
//! too): senders should not talk to a board right after changing settings or
//! uploading a program until it answers `?` again.

use controller::Settings;
use controller::persist::keep;
use controller::persist::{Error, Persist, Rewritable};
use defmt::{info, warn};
use embassy_stm32::flash::{Blocking, Flash};
use embassy_stm32::pac;
use embassy_stm32::pac::iwdg::vals::{Key, Pr};
use interp_core::MachineConfig;

use crate::board::{STORE_SIZE, STORE_START, WATCHDOG_TIMEOUT_US};
use crate::shell::{Ctl, TEXT, at_rest};

/// The flash the store is on: on the F405 embassy's whole-flash driver (its erase
/// unit is the 128 KB sector the store uses); on the F446 the region of its four
/// 16 KB sectors (0–3), whose offsets also count from the flash's first byte.
#[cfg(feature = "f405")]
pub type StoreFlash = Flash<'static, Blocking>;
/// The flash the store is on (see the F405's).
#[cfg(feature = "f446")]
pub type StoreFlash = embassy_stm32::flash::Bank1Region1<'static, Blocking>;

/// The persistent store on the board's flash.
pub type Store = Persist<Rewritable<StoreFlash>>;

/// Watchdog timeout while the flash is written: a sector erase takes up to 2 s
/// (4 s at low supply voltage); the normal timeout is back right after.
pub const SAVE_WATCHDOG_US: u32 = 8_000_000;

/// Flash base address: offset 0 of embassy's `Flash`.
const FLASH_BASE: u32 = 0x0800_0000;

/// The store over the board's store region.
pub fn open(flash: Flash<'static, Blocking>) -> Result<Store, Error> {
    #[cfg(feature = "f446")]
    let flash = flash.into_blocking_regions().bank1_region1;
    let start = STORE_START - FLASH_BASE;
    Persist::new(Rewritable(flash), start..start + STORE_SIZE)
}

/// Reads the stored parameters, grbl settings and offsets into `cfg` and `s`.
pub fn load_config(store: &mut Store, cfg: &mut MachineConfig, s: &mut Settings) -> Result<(), Error> {
    for n in keep::load_config(store, cfg, s)? {
        warn!("stored setting ${} refused", n);
    }
    Ok(())
}

/// Reads the common variables and the stored programs into the controller (the
/// programs through a scratch buffer on the stack, at boot only; out of line so the
/// buffer is not part of the caller's frame).
#[inline(never)]
pub fn load_rest(store: &mut Store, ctl: &mut Ctl) -> Result<usize, Error> {
    let mut scratch = [0u8; TEXT];
    keep::load_rest(store, ctl, &mut scratch)
}

/// Writes what changed to the store while the machine is at rest, the watchdog
/// stretched around the write.
pub struct Saver(keep::Saver<Rewritable<StoreFlash>>);

impl Saver {
    /// A saver that takes what the controller holds now as saved.
    pub fn new(store: Store, ctl: &Ctl) -> Self {
        Saver(keep::Saver::new(store, ctl))
    }

    /// Called after every poll at time `now` (ns): every [`keep::CHECK_NS`] at
    /// rest, saves what changed. Blocks while the flash is written.
    pub fn tick(&mut self, now: u64, ctl: &mut Ctl, port: &crate::motion::MotionPort) {
        if !self.0.due(now, ctl, || at_rest(ctl, port)) {
            return;
        }
        watchdog_timeout(SAVE_WATCHDOG_US);
        match self.0.save(ctl) {
            Ok(()) => info!("persist: saved"),
            // Not retried until something changes again (a full store stays full).
            Err(e) => warn!("persist: {}", e),
        }
        watchdog_timeout(WATCHDOG_TIMEOUT_US);
    }
}

/// Sets the running watchdog's timeout (the prescaler and reload embassy's driver
/// would choose for it) and reloads it.
fn watchdog_timeout(timeout_us: u32) {
    const LSI_HZ: u64 = 32_000;
    let ticks = |psc: u64| u64::from(timeout_us) * LSI_HZ / 1_000_000 / psc;
    let pr = (0u8..=6).find(|&pr| ticks(4 << pr) <= 0x1000).unwrap_or(6);
    let rl = ticks(4 << pr).clamp(1, 0x1000) - 1;
    let iwdg = pac::IWDG;
    iwdg.kr().write(|w| w.set_key(Key::RESET));
    let busy = || {
        let sr = iwdg.sr().read();
        sr.pvu() || sr.rvu()
    };
    while busy() {}
    iwdg.kr().write(|w| w.set_key(Key::ENABLE));
    iwdg.pr().write(|w| w.set_pr(Pr::from_bits(pr)));
    iwdg.rlr().write(|w| w.set_rl(rl as u16));
    while busy() {}
    iwdg.kr().write(|w| w.set_key(Key::RESET));
}
