//! What a board keeps on flash, independent of the flash driver: reading the
//! stored parameters, grbl settings, offsets (a mill build's G54.1 P1–P48 too),
//! common variables and programs into a controller, writing back what changed,
//! the fingerprint that tells when something did, and the [`Saver`] that writes
//! while the machine is at rest. The
//! firmware runs it on the STM32's flash (`firmware/src/saved.rs`), `lathe board
//! --flash` on a file (`sim::board`); `tests/persist_keep.rs` tests it.
//!
//! grbl settings are stored as parameter records numbered [`SETTING_KEY`]` + n`
//! (the value's `f64` bits). Not stored: the startup blocks `$N0`/`$N1`.

use crate::persist::{Error, Offsets, Persist};
use crate::settings::{self, NUMBERS};
use crate::{Controller, Settings};
use embedded_storage::nor_flash::{MultiwriteNorFlash, NorFlash};
use interp_core::MachineConfig;
use interp_core::ProgramStore;
use interp_core::config::{EXTRA_FRAMES, MAX_OFFSETS, PARAMS, Param};

/// Parameter record number of grbl setting `$n`: `SETTING_KEY + n` (parameter
/// numbers of the interpreter are below 10000).
pub const SETTING_KEY: u16 = 0xE000;
/// The grbl settings stored, in the order they are applied at boot (`$311` first:
/// the machine kind gives the Y axis `$101`–`$131` set; `$20` before the travel
/// `$130`–`$132` it moves aside).
const SETTINGS: [&[u16]; 3] = [&[311], NUMBERS, &[301]];

/// Every stored grbl setting number, in order.
fn setting_numbers() -> impl Iterator<Item = u16> {
    SETTINGS.into_iter().flat_map(|l| l.iter().copied())
}

/// Reads the stored parameters, grbl settings and offsets into `cfg` and `s`; the
/// numbers of settings the stored value was refused for are skipped (returned).
/// A stored setting of an axis or device the stored machine kind does not have
/// (a mill's `$101`–`$131` and `$312`/`$313` after `$RST=$` made it a lathe) is
/// left unused, not refused: [`save`] writes only the settings a machine has, so
/// such a record is a former mill's, and a mill again overwrites it.
pub fn load_config<F: NorFlash + MultiwriteNorFlash>(
    store: &mut Persist<F>,
    cfg: &mut MachineConfig,
    s: &mut Settings,
) -> Result<heapless::Vec<u16, 32>, Error> {
    let mut grbl: heapless::Vec<(u16, f64), 40> = heapless::Vec::new();
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
    let mut refused = heapless::Vec::new();
    for n in setting_numbers() {
        if let Some(&(_, v)) = grbl.iter().find(|(m, _)| *m == n)
            && !settings::missing_axis(n, cfg)
            && settings::set(n, v, cfg, s).is_err()
        {
            let _ = refused.push(n);
        }
    }
    let mut o = Offsets { work: cfg.work_offsets, external: cfg.external_offset, tools: cfg.tools };
    store.load_offsets(&mut o)?;
    cfg.work_offsets = o.work;
    cfg.external_offset = o.external;
    cfg.tools = o.tools;
    store.load_extra_offsets(&mut cfg.extra_offsets)?;
    Ok(refused)
}

/// Reads the common variables and the stored programs into the controller (each
/// program through `scratch`, which must hold the longest); how many programs.
pub fn load_rest<F, const W: usize, const T: usize, const P: usize, const S: usize>(
    store: &mut Persist<F>,
    ctl: &mut Controller<W, T, P, S>,
    scratch: &mut [u8],
) -> Result<usize, Error>
where
    F: NorFlash + MultiwriteNorFlash,
{
    ctl.interpreter_mut().variables_mut().load_commons(store)?;
    store.load_all_programs(ctl.memory_mut(), scratch)
}

/// Writes parameters, settings, offsets, commons and programs (each only if it
/// differs from what is stored) and deletes stored programs no longer in memory.
pub fn save<F, const W: usize, const T: usize, const P: usize, const S: usize>(
    store: &mut Persist<F>,
    ctl: &mut Controller<W, T, P, S>,
) -> Result<(), Error>
where
    F: NorFlash + MultiwriteNorFlash,
{
    let cfg = ctl.interpreter().config();
    for d in PARAMS {
        store.save_param(d.number, cfg.params.get(d.id))?;
    }
    for n in setting_numbers() {
        if let Some(v) = settings::get(n, cfg, ctl.settings()) {
            store.save_param(SETTING_KEY + n, v.to_bits() as i64)?;
        }
    }
    store.save_offsets(&Offsets { work: cfg.work_offsets, external: cfg.external_offset, tools: cfg.tools })?;
    store.save_extra_offsets(&cfg.extra_offsets)?;
    let memory = ctl.memory();
    for n in memory.numbers() {
        if let Some(text) = memory.text(n) {
            store.save_program(n, text)?;
        }
    }
    // Stored programs no longer in memory (at most twice as many as memory holds
    // are looked at: more means the store holds programs memory never could).
    let stored = match store.programs::<64>() {
        Ok(list) => list,
        Err(Error::TooManyPrograms) => heapless::Vec::new(),
        Err(e) => return Err(e),
    };
    for p in stored {
        if !memory.numbers().any(|n| n == p.number) {
            store.delete_program(p.number)?;
        }
    }
    ctl.interpreter_mut().variables_mut().flush_commons(store)
}

/// FNV-1a 64 of everything [`save`] stores except the commons (which keep their
/// own dirty bits).
pub fn fingerprint<const W: usize, const T: usize, const P: usize, const S: usize>(
    ctl: &Controller<W, T, P, S>,
) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let cfg = ctl.interpreter().config();
    for d in PARAMS {
        h.i64(cfg.params.get(d.id));
    }
    for n in setting_numbers() {
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
    if interp_core::MILL {
        for p in 1..=EXTRA_FRAMES as u8 {
            cfg.extra_offsets.row(p).unwrap_or_default().iter().for_each(|v| h.i64(i64::from(*v)));
        }
    }
    let memory = ctl.memory();
    for n in memory.numbers() {
        h.i64(i64::from(n));
        h.bytes(memory.text(n).unwrap_or(&[]));
    }
    h.0
}

/// How often a [`Saver`] looks for changes while the machine is at rest, ns.
pub const CHECK_NS: u64 = 500_000_000;

/// Writes what changed to a store, only while the machine is at rest (an erase
/// can stall the CPU for seconds on a board). Split in two so that a board can
/// prepare for the write (stretch its watchdog) between [`Saver::due`] and
/// [`Saver::save`].
pub struct Saver<F: NorFlash + MultiwriteNorFlash> {
    store: Persist<F>,
    saved: u64,
    pending: u64,
    next_check: u64,
}

impl<F: NorFlash + MultiwriteNorFlash> Saver<F> {
    /// A saver over `store` that takes what `ctl` holds now as saved.
    pub fn new<const W: usize, const T: usize, const P: usize, const S: usize>(
        store: Persist<F>,
        ctl: &Controller<W, T, P, S>,
    ) -> Self {
        let saved = fingerprint(ctl);
        Saver { store, saved, pending: saved, next_check: 0 }
    }

    /// At time `now` (ns), every [`CHECK_NS`]: whether something changed and the
    /// machine is at rest (asked only then), so that [`Saver::save`] should run now.
    pub fn due<const W: usize, const T: usize, const P: usize, const S: usize>(
        &mut self,
        now: u64,
        ctl: &Controller<W, T, P, S>,
        at_rest: impl FnOnce() -> bool,
    ) -> bool {
        if now < self.next_check {
            return false;
        }
        self.next_check = now.saturating_add(CHECK_NS);
        if !at_rest() {
            return false;
        }
        self.pending = fingerprint(ctl);
        self.pending != self.saved || ctl.interpreter().variables().commons_dirty()
    }

    /// Writes what changed. A failure is not retried until something changes
    /// again (a full store stays full).
    pub fn save<const W: usize, const T: usize, const P: usize, const S: usize>(
        &mut self,
        ctl: &mut Controller<W, T, P, S>,
    ) -> Result<(), Error> {
        self.saved = self.pending;
        save(&mut self.store, ctl)
    }
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
