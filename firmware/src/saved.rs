//! What survives power-off on the board: `controller::persist` on the flash store
//! region (F405 sectors 10–11, F446 sectors 6–7; `memory.x` keeps code out).
//!
//! At boot [`load_config`] reads the numbered parameters, the grbl `$n` settings
//! and the offsets (before the motion core is built from them), [`load_rest`] the
//! common variables #401–#600 and the programs into the controller. The controller
//! has no "something changed" hook, so [`Saver`] keeps a fingerprint (FNV-1a 64) of
//! everything stored; while the machine is at rest (controller Idle, motion core
//! idle) it compares every [`CHECK_NS`] and, if it (or a common variable) changed,
//! writes what changed: every store call writes only records that differ.
//!
//! Erasing a 128 KB sector stalls the CPU (interrupts included) for 1–2 s, which is
//! why this runs only at rest; during a save the watchdog timeout is raised to
//! [`SAVE_WATCHDOG_US`] and put back to the normal timeout afterwards. Bytes that
//! arrive on the link during an erase can be lost (the UART interrupt is stalled
//! too): senders should not talk to a board right after changing settings or
//! uploading a program until it answers `?` again.
//!
//! grbl settings are stored as parameter records numbered [`SETTING_KEY`]` + n`
//! (the value's `f64` bits). Not stored: the startup blocks `$N0`/`$N1`.

use controller::Settings;
use controller::persist::{Error, Offsets, Persist, Rewritable};
use controller::settings::{self, NUMBERS};
use defmt::{info, warn};
use embassy_stm32::flash::{Blocking, Flash};
use embassy_stm32::pac;
use embassy_stm32::pac::iwdg::vals::{Key, Pr};
use interp_core::MachineConfig;
use interp_core::ProgramStore;
use interp_core::config::{MAX_OFFSETS, PARAMS, Param};

use crate::board::{STORE_SIZE, STORE_START, WATCHDOG_TIMEOUT_US};
use crate::shell::{Ctl, PROGRAMS, TEXT, at_rest};

/// The persistent store on the board's flash.
pub type Store = Persist<Rewritable<Flash<'static, Blocking>>>;

/// Parameter record number of grbl setting `$n`: `SETTING_KEY + n` (parameter
/// numbers of the interpreter are below 10000).
pub const SETTING_KEY: u16 = 0xE000;
/// The grbl settings stored, in the order they are applied at boot (`$20` before
/// the travel `$130`/`$132` it moves aside).
const SETTINGS: [&[u16]; 2] = [NUMBERS, &[301]];
/// How often the saver looks for changes while at rest, ns.
pub const CHECK_NS: u64 = 500_000_000;
/// Watchdog timeout while the flash is written: a sector erase takes up to 2 s
/// (4 s at low supply voltage); the normal timeout is back right after.
pub const SAVE_WATCHDOG_US: u32 = 8_000_000;

/// Flash base address: offset 0 of embassy's `Flash`.
const FLASH_BASE: u32 = 0x0800_0000;

/// The store over the board's store region.
pub fn open(flash: Flash<'static, Blocking>) -> Result<Store, Error> {
    let start = STORE_START - FLASH_BASE;
    Persist::new(Rewritable(flash), start..start + STORE_SIZE)
}

/// Reads the stored parameters, grbl settings and offsets into `cfg` and `s`.
pub fn load_config(store: &mut Store, cfg: &mut MachineConfig, s: &mut Settings) -> Result<(), Error> {
    let mut grbl: heapless::Vec<(u16, f64), 32> = heapless::Vec::new();
    store.load_params(|n, v| match n.checked_sub(SETTING_KEY) {
        Some(k) => {
            let value = f64::from_bits(v as u64);
            match grbl.iter_mut().find(|(m, _)| *m == k) {
                Some(slot) => slot.1 = value,
                None => {
                    let _ = grbl.push((k, value));
                }
            }
        }
        None => {
            if let Some(p) = Param::by_number(n) {
                cfg.params.set(p, v);
            }
        }
    })?;
    for &n in SETTINGS.iter().flat_map(|l| l.iter()) {
        if let Some(&(_, v)) = grbl.iter().find(|(m, _)| *m == n)
            && settings::set(n, v, cfg, s).is_err()
        {
            warn!("stored setting ${} refused", n);
        }
    }
    let mut o = Offsets { work: cfg.work_offsets, external: cfg.external_offset, tools: cfg.tools };
    store.load_offsets(&mut o)?;
    cfg.work_offsets = o.work;
    cfg.external_offset = o.external;
    cfg.tools = o.tools;
    Ok(())
}

/// Reads the common variables and the stored programs into the controller (the
/// programs through a scratch buffer on the stack, at boot only; out of line so the
/// buffer is not part of the caller's frame).
#[inline(never)]
pub fn load_rest(store: &mut Store, ctl: &mut Ctl) -> Result<usize, Error> {
    ctl.interpreter_mut().variables_mut().load_commons(store)?;
    let mut scratch = [0u8; TEXT];
    store.load_all_programs(ctl.memory_mut(), &mut scratch)
}

/// Writes what changed to the store while the machine is at rest.
pub struct Saver {
    store: Store,
    saved: u64,
    next_check: u64,
}

impl Saver {
    /// A saver that takes what the controller holds now as saved.
    pub fn new(store: Store, ctl: &Ctl) -> Self {
        Saver { store, saved: fingerprint(ctl), next_check: 0 }
    }

    /// Called after every poll at time `now` (ns): every [`CHECK_NS`] at rest,
    /// saves what changed. Blocks while the flash is written.
    pub fn tick(&mut self, now: u64, ctl: &mut Ctl, port: &crate::motion::MotionPort) {
        if now < self.next_check {
            return;
        }
        self.next_check = now + CHECK_NS;
        if !at_rest(ctl, port) {
            return;
        }
        let fp = fingerprint(ctl);
        if fp == self.saved && !ctl.interpreter().variables().commons_dirty() {
            return;
        }
        watchdog_timeout(SAVE_WATCHDOG_US);
        match save(&mut self.store, ctl) {
            Ok(()) => info!("persist: saved"),
            // Not retried until something changes again (a full store stays full).
            Err(e) => warn!("persist: {}", defmt::Display2Format(&e)),
        }
        watchdog_timeout(WATCHDOG_TIMEOUT_US);
        self.saved = fp;
    }
}

/// Writes parameters, settings, offsets, commons and programs (each only if it
/// differs from what is stored) and deletes stored programs no longer in memory.
fn save(store: &mut Store, ctl: &mut Ctl) -> Result<(), Error> {
    let cfg = ctl.interpreter().config();
    for d in PARAMS {
        store.save_param(d.number, cfg.params.get(d.id))?;
    }
    for &n in SETTINGS.iter().flat_map(|l| l.iter()) {
        if let Some(v) = settings::get(n, cfg, ctl.settings()) {
            store.save_param(SETTING_KEY + n, v.to_bits() as i64)?;
        }
    }
    store.save_offsets(&Offsets { work: cfg.work_offsets, external: cfg.external_offset, tools: cfg.tools })?;
    let memory = ctl.memory();
    for n in memory.numbers() {
        if let Some(text) = memory.text(n) {
            store.save_program(n, text)?;
        }
    }
    for p in store.programs::<{ 2 * PROGRAMS }>()? {
        if !memory.numbers().any(|n| n == p.number) {
            store.delete_program(p.number)?;
        }
    }
    ctl.interpreter_mut().variables_mut().flush_commons(store)
}

/// FNV-1a 64 of everything [`save`] stores except the commons (which keep their
/// own dirty bits).
fn fingerprint(ctl: &Ctl) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let cfg = ctl.interpreter().config();
    for d in PARAMS {
        h.i64(cfg.params.get(d.id));
    }
    for &n in SETTINGS.iter().flat_map(|l| l.iter()) {
        h.i64(settings::get(n, cfg, ctl.settings()).map_or(-1, |v| v.to_bits() as i64));
    }
    for p in cfg.work_offsets.iter().chain([&cfg.external_offset]) {
        p.0.iter().for_each(|v| h.i64(*v));
    }
    for n in 1..=MAX_OFFSETS as u16 {
        if let Some(t) = cfg.tools.get(n) {
            [t.x, t.z, t.x_wear, t.z_wear, t.radius, i64::from(t.tip)].iter().for_each(|v| h.i64(*v));
        }
    }
    let memory = ctl.memory();
    for n in memory.numbers() {
        h.i64(i64::from(n));
        h.bytes(memory.text(n).unwrap_or(&[]));
    }
    h.0
}

/// FNV-1a, 64 bits.
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 = (self.0 ^ u64::from(x)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn i64(&mut self, v: i64) {
        self.bytes(&v.to_le_bytes());
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
