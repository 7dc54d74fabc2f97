//! The macro variable table of 2.24.1: `#0` always null, `#1–#400` and `#601–#999`
//! local (null at power-on), `#401–#600` common and kept through power-off by a
//! [`CommonStore`] (backup SRAM or flash on the board, a file on the host).
//!
//! Of the manual's "local" variables, `#1–#33` are local to a macro level as in
//! FANUC 0i custom macro B: each macro call (G65, G66, a G or M code) starts a new
//! level whose `#1–#33` are its arguments, and M99 brings the caller's back; M98
//! shares its caller's level. The rest (`#34–#400`, `#601–#999`) are one set for
//! every level, like FANUC's `#100–#199`.
//!
//! Storage holds what exists: the levels' `#1–#33` (the main program's and four
//! macro levels, dense: they are read the most), the 200 commons (dense: they are
//! persisted), and of `#34–#400`/`#601–#999` only those that hold a value, in a
//! sorted table of [`POOL_SIZE`] (a null variable takes no room; alarm 4050 when a
//! 129th would hold a value). 4.2 KB instead of the 8 KB a dense `#1–#999` took,
//! with the saved levels of macro nesting included.

use core::fmt;

use crate::alarm::AlarmKind;

/// A variable's value: a real number, or `None` for null ("空", undefined).
pub type Value = Option<f64>;

/// Highest variable number.
pub const MAX_VARIABLE: u16 = 999;
/// First common (persistent) variable.
pub const FIRST_COMMON: u16 = 401;
/// Last common (persistent) variable.
pub const LAST_COMMON: u16 = 600;
/// Number of common variables.
pub const COMMON_COUNT: usize = (LAST_COMMON - FIRST_COMMON + 1) as usize;
/// Variables local to a macro level: `#1–#33`.
pub const LOCAL_COUNT: usize = 33;
/// Macro calls may nest 4 levels deep (FANUC 0i); the main program is level 0.
pub const MAX_MACRO_LEVEL: usize = 4;
/// Most of `#34–#400` and `#601–#999` that may hold a value at once.
pub const POOL_SIZE: usize = 128;

/// Words of the changed-commons bit set.
const DIRTY_WORDS: usize = COMMON_COUNT.div_ceil(32);

/// Where the common variables `#401–#600` survive power-off.
///
/// The interpreter only marks commons as changed; the driver calls
/// [`Variables::flush_commons`] when it suits the medium (after every step for
/// battery-backed RAM, at program end for flash, at exit for a host file).
pub trait CommonStore {
    /// What can go wrong with the medium.
    type Error;
    /// Reads the persisted value of common variable `number` (401–600).
    fn load(&mut self, number: u16) -> Result<Value, Self::Error>;
    /// Persists the new value of common variable `number` (401–600).
    fn store(&mut self, number: u16, value: Value) -> Result<(), Self::Error>;
}

/// One level of local variables `#1–#33`, or the arguments of a macro call (`#1–#33`
/// as argument specification I and II fill them).
///
/// Null is stored as a NaN ("NaN-boxing"): macro arithmetic never yields NaN (every
/// NaN-producing case is an alarm), so one `f64` per variable suffices.
#[derive(Clone, Copy, PartialEq)]
pub struct Locals([f64; LOCAL_COUNT]);

impl Locals {
    /// Every variable null: a level as a call without arguments starts it.
    pub const VACANT: Locals = Locals([f64::NAN; LOCAL_COUNT]);

    /// `#n` (1–33); null outside.
    pub fn get(&self, n: u16) -> Value {
        let v = *self.0.get(usize::from(n).wrapping_sub(1))?;
        if v.is_nan() { None } else { Some(v) }
    }

    /// Sets `#n` (1–33; others are ignored). A NaN is stored as null.
    pub fn set(&mut self, n: u16, value: Value) {
        if let Some(slot) = self.0.get_mut(usize::from(n).wrapping_sub(1)) {
            *slot = value.unwrap_or(f64::NAN);
        }
    }

    /// Every variable null.
    pub fn clear(&mut self) {
        *self = Locals::VACANT;
    }

    /// The variables that are not null, in number order.
    pub fn defined(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        (1..).zip(self.0.iter()).filter(|(_, v)| !v.is_nan()).map(|(n, v)| (n, *v))
    }
}

impl Default for Locals {
    fn default() -> Self {
        Locals::VACANT
    }
}

impl fmt::Debug for Locals {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_map().entries(self.defined()).finish()
    }
}

/// The variables of `#34–#400` and `#601–#999` that hold a value, by number.
#[derive(Clone)]
struct Pool {
    /// Numbers in ascending order; `keys[..len]` are used.
    keys: [u16; POOL_SIZE],
    /// The value of `keys[i]` (never NaN).
    values: [f64; POOL_SIZE],
    len: u8,
}

impl Pool {
    const EMPTY: Pool = Pool { keys: [0; POOL_SIZE], values: [0.0; POOL_SIZE], len: 0 };

    /// Where `n` is, or where it would go.
    fn find(&self, n: u16) -> Result<usize, usize> {
        self.keys[..usize::from(self.len)].binary_search(&n)
    }

    fn get(&self, n: u16) -> Value {
        self.find(n).ok().map(|i| self.values[i])
    }

    /// Whether `n` could be set to a value (it holds one, or there is room).
    fn has_room_for(&self, n: u16) -> bool {
        usize::from(self.len) < POOL_SIZE || self.find(n).is_ok()
    }

    fn set(&mut self, n: u16, value: Value) -> Result<(), AlarmKind> {
        let len = usize::from(self.len);
        match (self.find(n), value) {
            (Ok(i), Some(v)) => self.values[i] = v,
            (Ok(i), None) => {
                self.keys.copy_within(i + 1..len, i);
                self.values.copy_within(i + 1..len, i);
                self.len -= 1;
            }
            (Err(_), None) => {}
            (Err(_), Some(_)) if len == POOL_SIZE => return Err(AlarmKind::VariablesFull),
            (Err(i), Some(v)) => {
                self.keys.copy_within(i..len, i + 1);
                self.values.copy_within(i..len, i + 1);
                self.keys[i] = n;
                self.values[i] = v;
                self.len += 1;
            }
        }
        Ok(())
    }

    fn iter(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        let len = usize::from(self.len);
        self.keys[..len].iter().copied().zip(self.values[..len].iter().copied())
    }
}

/// The variable table.
#[derive(Clone)]
pub struct Variables {
    /// `#1–#33` of the main program (level 0) and of each macro level in force.
    levels: [Locals; MAX_MACRO_LEVEL + 1],
    /// The macro level in force: `levels[depth]` is `#1–#33`.
    depth: u8,
    /// `#401–#600` at index `n - 401`; NaN = null.
    commons: [f64; COMMON_COUNT],
    /// Commons changed since the last flush, bit `n - 401`.
    dirty: [u32; DIRTY_WORDS],
    /// `#34–#400` and `#601–#999` that hold a value.
    pool: Pool,
}

impl fmt::Debug for Variables {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let set = self.defined().count();
        write!(f, "Variables {{ level {}, {set} set }}", self.depth)
    }
}

impl Default for Variables {
    fn default() -> Self {
        Self::new()
    }
}

impl Variables {
    /// The power-on table: every variable null, the main program's level.
    pub const fn new() -> Self {
        Variables {
            levels: [Locals::VACANT; MAX_MACRO_LEVEL + 1],
            depth: 0,
            commons: [f64::NAN; COMMON_COUNT],
            dirty: [0; DIRTY_WORDS],
            pool: Pool::EMPTY,
        }
    }

    /// Whether `n` is a common (persistent) variable.
    pub const fn is_common(n: u16) -> bool {
        n >= FIRST_COMMON && n <= LAST_COMMON
    }

    /// Whether `n` is local to a macro level (`#1–#33`).
    pub const fn is_local(n: u16) -> bool {
        n >= 1 && n <= LOCAL_COUNT as u16
    }

    /// The value of `#n`; alarm 0115 beyond #999.
    #[inline]
    pub fn get(&self, n: u16) -> Result<Value, AlarmKind> {
        if Self::is_local(n) {
            return Ok(self.levels[usize::from(self.depth)].get(n));
        }
        match n {
            0 => Ok(None),
            FIRST_COMMON..=LAST_COMMON => {
                let v = self.commons[usize::from(n - FIRST_COMMON)];
                Ok(if v.is_nan() { None } else { Some(v) })
            }
            1..=MAX_VARIABLE => Ok(self.pool.get(n)),
            _ => Err(out_of_range(i64::from(n))),
        }
    }

    /// Sets `#n`; alarm 0116 for #0, 0115 beyond #999, 4050 when `#n` of
    /// `#34–#400`/`#601–#999` would be one more holding a value than there is room
    /// for. A NaN is stored as null.
    pub fn set(&mut self, n: u16, value: Value) -> Result<(), AlarmKind> {
        let value = value.filter(|v| !v.is_nan());
        if Self::is_local(n) {
            self.levels[usize::from(self.depth)].set(n, value);
            return Ok(());
        }
        match n {
            0 => Err(AlarmKind::WriteProtectedVariable { number: 0 }),
            FIRST_COMMON..=LAST_COMMON => {
                let i = usize::from(n - FIRST_COMMON);
                let v = value.unwrap_or(f64::NAN);
                if self.commons[i].to_bits() != v.to_bits() {
                    self.dirty[i / 32] |= 1 << (i % 32);
                }
                self.commons[i] = v;
                Ok(())
            }
            1..=MAX_VARIABLE => self.pool.set(n, value),
            _ => Err(out_of_range(i64::from(n))),
        }
    }

    /// Whether [`Variables::set`] of `#n` to a value would succeed (a variable of
    /// `#34–#400`/`#601–#999` needs room unless it holds a value already).
    pub fn can_set(&self, n: u16) -> bool {
        match n {
            0 => false,
            1..=33 | FIRST_COMMON..=LAST_COMMON => true,
            1..=MAX_VARIABLE => self.pool.has_room_for(n),
            _ => false,
        }
    }

    /// The macro level in force: 0 in the main program (and what it calls with
    /// M98), one more in each macro call.
    pub fn level(&self) -> usize {
        usize::from(self.depth)
    }

    /// `#1–#33` of the level in force.
    pub fn locals(&self) -> &Locals {
        &self.levels[usize::from(self.depth)]
    }

    /// A macro call: a new level whose `#1–#33` are `args` (the caller's level is
    /// kept for [`Variables::leave_level`]). Alarm 0077 past level 4.
    pub fn enter_level(&mut self, args: &Locals) -> Result<(), AlarmKind> {
        let next = usize::from(self.depth) + 1;
        let slot = self.levels.get_mut(next).ok_or(AlarmKind::MacroNestingTooDeep)?;
        *slot = *args;
        self.depth += 1;
        Ok(())
    }

    /// M99 from a macro: the caller's level again, as it was at the call.
    pub fn leave_level(&mut self) {
        self.depth = self.depth.saturating_sub(1);
    }

    /// Back to the main program's level (reset, rewind: the calls are dropped;
    /// the main program's `#1–#33` keep their values).
    pub fn leave_all_levels(&mut self) {
        self.depth = 0;
    }

    /// Power-off for the local variables: `#1–#400` and `#601–#999` become null.
    pub fn clear_locals(&mut self) {
        for l in self.levels.iter_mut() {
            l.clear();
        }
        self.depth = 0;
        self.pool = Pool::EMPTY;
    }

    /// Reads every common variable from `store` (at power-on).
    pub fn load_commons<S: CommonStore + ?Sized>(&mut self, store: &mut S) -> Result<(), S::Error> {
        for n in FIRST_COMMON..=LAST_COMMON {
            let v = store.load(n)?.filter(|v| v.is_finite());
            self.commons[usize::from(n - FIRST_COMMON)] = v.unwrap_or(f64::NAN);
        }
        self.dirty = [0; DIRTY_WORDS];
        Ok(())
    }

    /// Writes the commons changed since the last flush to `store`. A failed write
    /// leaves that variable marked, so a later flush tries again.
    pub fn flush_commons<S: CommonStore + ?Sized>(&mut self, store: &mut S) -> Result<(), S::Error> {
        for bit in 0..COMMON_COUNT {
            if self.dirty[bit / 32] & (1 << (bit % 32)) != 0 {
                let n = FIRST_COMMON + bit as u16;
                let v = self.commons[bit];
                store.store(n, if v.is_nan() { None } else { Some(v) })?;
                self.dirty[bit / 32] &= !(1 << (bit % 32));
            }
        }
        Ok(())
    }

    /// Whether commons changed since the last flush.
    pub fn commons_dirty(&self) -> bool {
        self.dirty.iter().any(|w| *w != 0)
    }

    /// The variables that are not null, in number order (`#1–#33` of the level
    /// in force).
    pub fn defined(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        let commons = (FIRST_COMMON..).zip(self.commons.iter()).filter(|(_, v)| !v.is_nan()).map(|(n, v)| (n, *v));
        self.locals()
            .defined()
            .chain(self.pool.iter().filter(|(n, _)| *n < FIRST_COMMON))
            .chain(commons)
            .chain(self.pool.iter().filter(|(n, _)| *n > LAST_COMMON))
    }
}

/// Alarm 0115 for variable number `n`.
pub(crate) fn out_of_range(n: i64) -> AlarmKind {
    AlarmKind::VariableNumberOutOfRange { number: n.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32 }
}

/// Writes commons in the text form of a host variables file: one `#n = value` line
/// per common that is not null (the shortest decimal that reads back exactly).
pub fn write_commons<W: fmt::Write>(vars: &Variables, out: &mut W) -> fmt::Result {
    for (n, v) in vars.defined().filter(|(n, _)| Variables::is_common(*n)) {
        writeln!(out, "#{n} = {v:?}")?;
    }
    Ok(())
}

/// One line of a host variables file: `#n = value` (blanks optional), a blank line
/// or a `;`/`(` comment. `Ok(None)` for lines without an assignment; `Err` with the
/// reason for anything else, including a number that is not a common variable.
pub fn parse_common_line(line: &str) -> Result<Option<(u16, f64)>, &'static str> {
    let t = line.trim();
    if t.is_empty() || t.starts_with(';') || t.starts_with('(') {
        return Ok(None);
    }
    let rest = t.strip_prefix('#').ok_or("expected '#n = value'")?;
    let (num, val) = rest.split_once('=').ok_or("expected '='")?;
    let n: u16 = num.trim().parse().map_err(|_| "bad variable number")?;
    if !Variables::is_common(n) {
        return Err("only common variables #401-#600 are kept");
    }
    let v: f64 = val.trim().parse().map_err(|_| "bad value")?;
    if !v.is_finite() {
        return Err("value is not a finite number");
    }
    Ok(Some((n, v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An in-memory store that counts writes.
    struct Mem {
        vals: [Value; COMMON_COUNT],
        writes: usize,
    }

    impl CommonStore for Mem {
        type Error = ();
        fn load(&mut self, n: u16) -> Result<Value, ()> {
            Ok(self.vals[usize::from(n - FIRST_COMMON)])
        }
        fn store(&mut self, n: u16, v: Value) -> Result<(), ()> {
            self.writes += 1;
            self.vals[usize::from(n - FIRST_COMMON)] = v;
            Ok(())
        }
    }

    #[test]
    fn power_on_everything_null_and_zero_is_write_protected() {
        let mut v = Variables::new();
        assert_eq!(v.get(0), Ok(None));
        assert_eq!(v.get(1), Ok(None));
        assert_eq!(v.get(999), Ok(None));
        assert_eq!(v.get(1000), Err(AlarmKind::VariableNumberOutOfRange { number: 1000 }));
        assert_eq!(v.set(0, Some(1.0)), Err(AlarmKind::WriteProtectedVariable { number: 0 }));
        assert_eq!(v.set(1000, Some(1.0)), Err(AlarmKind::VariableNumberOutOfRange { number: 1000 }));
        v.set(5, Some(-2.5)).unwrap();
        assert_eq!(v.get(5), Ok(Some(-2.5)));
        v.set(5, None).unwrap();
        assert_eq!(v.get(5), Ok(None));
    }

    #[test]
    fn locals_clear_commons_persist_through_the_store() {
        let mut store = Mem { vals: [None; COMMON_COUNT], writes: 0 };
        let mut v = Variables::new();
        v.set(1, Some(1.0)).unwrap();
        v.set(400, Some(2.0)).unwrap();
        v.set(401, Some(3.0)).unwrap();
        v.set(600, Some(4.0)).unwrap();
        v.set(601, Some(5.0)).unwrap();
        assert!(v.commons_dirty());
        v.flush_commons(&mut store).unwrap();
        assert_eq!(store.writes, 2);
        assert!(!v.commons_dirty());
        v.flush_commons(&mut store).unwrap();
        assert_eq!(store.writes, 2, "nothing changed, nothing written");
        // Power cycle: a fresh table loads the commons; locals are null.
        let mut after = Variables::new();
        after.load_commons(&mut store).unwrap();
        assert_eq!(after.get(401), Ok(Some(3.0)));
        assert_eq!(after.get(600), Ok(Some(4.0)));
        assert_eq!(after.get(1), Ok(None));
        v.clear_locals();
        assert_eq!((v.get(1), v.get(400), v.get(601), v.get(401)), (Ok(None), Ok(None), Ok(None), Ok(Some(3.0))));
        // Setting the same value again does not mark it.
        v.set(401, Some(3.0)).unwrap();
        assert!(!v.commons_dirty());
    }

    #[test]
    fn every_number_of_the_manuals_table_holds_a_value() {
        let mut v = Variables::new();
        for n in 1..=MAX_VARIABLE {
            // #34–#400 and #601–#999 only while there is room: clear as we go.
            v.set(n, Some(f64::from(n) / 8.0)).unwrap();
            assert_eq!(v.get(n), Ok(Some(f64::from(n) / 8.0)), "#{n}");
            if !Variables::is_local(n) && !Variables::is_common(n) {
                v.set(n, None).unwrap();
                assert_eq!(v.get(n), Ok(None));
            }
        }
        assert_eq!(v.defined().count(), 33 + COMMON_COUNT);
    }

    #[test]
    fn the_pool_keeps_128_values_in_order_and_a_null_frees_a_place() {
        let mut v = Variables::new();
        // Set out of order, among the numbers of both ranges.
        let numbers: heapless::Vec<u16, POOL_SIZE> =
            (0..POOL_SIZE as u16).map(|k| if k % 2 == 0 { 999 - k } else { 34 + k * 2 }).collect();
        for &n in &numbers {
            v.set(n, Some(f64::from(n))).unwrap();
        }
        assert!(v.can_set(999) && !v.can_set(101));
        assert_eq!(v.set(101, Some(1.0)), Err(AlarmKind::VariablesFull));
        assert_eq!(v.get(101), Ok(None), "the failed set changed nothing");
        let defined: heapless::Vec<u16, POOL_SIZE> = v.defined().map(|(n, _)| n).collect();
        assert!(defined.windows(2).all(|w| w[0] < w[1]), "{defined:?}");
        assert!(numbers.iter().all(|&n| v.get(n) == Ok(Some(f64::from(n)))));
        // Null frees a place; setting a held one again needs none.
        v.set(numbers[5], None).unwrap();
        v.set(101, Some(1.5)).unwrap();
        v.set(101, Some(2.5)).unwrap();
        assert_eq!(v.get(101), Ok(Some(2.5)));
        assert_eq!(v.set(numbers[5], Some(1.0)), Err(AlarmKind::VariablesFull));
        // Commons and locals never run out.
        v.set(401, Some(1.0)).unwrap();
        v.set(33, Some(1.0)).unwrap();
    }

    #[test]
    fn macro_levels_keep_the_callers_locals() {
        let mut v = Variables::new();
        v.set(1, Some(10.0)).unwrap();
        v.set(33, Some(33.0)).unwrap();
        v.set(100, Some(100.0)).unwrap();
        let mut args = Locals::VACANT;
        args.set(1, Some(1.5));
        args.set(26, Some(-2.0));
        v.enter_level(&args).unwrap();
        assert_eq!(v.level(), 1);
        assert_eq!((v.get(1), v.get(26), v.get(33)), (Ok(Some(1.5)), Ok(Some(-2.0)), Ok(None)));
        assert_eq!(v.get(100), Ok(Some(100.0)), "#100 is one for every level");
        v.set(2, Some(7.0)).unwrap();
        v.set(100, Some(101.0)).unwrap();
        for level in 2..=4 {
            v.enter_level(&Locals::VACANT).unwrap();
            assert_eq!(v.level(), level);
            assert_eq!(v.get(2), Ok(None));
        }
        assert_eq!(v.enter_level(&args), Err(AlarmKind::MacroNestingTooDeep));
        assert_eq!(v.level(), 4);
        for _ in 0..3 {
            v.leave_level();
        }
        assert_eq!((v.get(1), v.get(2)), (Ok(Some(1.5)), Ok(Some(7.0))));
        v.leave_level();
        assert_eq!((v.get(1), v.get(2), v.get(33)), (Ok(Some(10.0)), Ok(None), Ok(Some(33.0))));
        assert_eq!(v.get(100), Ok(Some(101.0)));
    }

    #[test]
    fn host_file_lines_round_trip() {
        let mut v = Variables::new();
        v.set(401, Some(0.1)).unwrap();
        v.set(450, Some(-12.0)).unwrap();
        v.set(5, Some(7.0)).unwrap();
        let mut s = heapless::String::<128>::new();
        write_commons(&v, &mut s).unwrap();
        assert_eq!(s.as_str(), "#401 = 0.1\n#450 = -12.0\n");
        let back: heapless::Vec<_, 4> = s.lines().filter_map(|l| parse_common_line(l).unwrap()).collect();
        assert_eq!(back.as_slice(), &[(401, 0.1), (450, -12.0)]);
        assert_eq!(parse_common_line("  ; comment"), Ok(None));
        assert!(parse_common_line("#5 = 1").is_err());
        assert!(parse_common_line("#401 = x").is_err());
        assert!(parse_common_line("#401 = inf").is_err());
    }
}
