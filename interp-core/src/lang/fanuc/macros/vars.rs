//! The macro variable table of 2.24.1: `#0` always null, `#1–#400` and `#601–#999`
//! local (null at power-on), `#401–#600` common and kept through power-off by a
//! [`CommonStore`] (backup SRAM or flash on the board, a file on the host).

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

/// The variable table.
///
/// Null is stored as a NaN ("NaN-boxing"): macro arithmetic never yields NaN (every
/// NaN-producing case is an alarm), so one `f64` per variable suffices: 999 × 8 B.
#[derive(Clone)]
pub struct Variables {
    /// `#1–#999` at index `n - 1`; NaN = null.
    values: [f64; MAX_VARIABLE as usize],
    /// Commons changed since the last flush, bit `n - 401`.
    dirty: [u32; DIRTY_WORDS],
}

impl fmt::Debug for Variables {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let set = self.values.iter().filter(|v| !v.is_nan()).count();
        write!(f, "Variables {{ {set} set }}")
    }
}

impl Default for Variables {
    fn default() -> Self {
        Self::new()
    }
}

impl Variables {
    /// The power-on table: every variable null.
    pub const fn new() -> Self {
        Variables { values: [f64::NAN; MAX_VARIABLE as usize], dirty: [0; DIRTY_WORDS] }
    }

    /// Whether `n` is a common (persistent) variable.
    pub const fn is_common(n: u16) -> bool {
        n >= FIRST_COMMON && n <= LAST_COMMON
    }

    /// The value of `#n`; alarm 0115 beyond #999.
    pub fn get(&self, n: u16) -> Result<Value, AlarmKind> {
        if n == 0 {
            return Ok(None);
        }
        let v = *self.values.get(usize::from(n) - 1).ok_or(out_of_range(i64::from(n)))?;
        Ok(if v.is_nan() { None } else { Some(v) })
    }

    /// Sets `#n`; alarm 0116 for #0, 0115 beyond #999. A NaN is stored as null.
    pub fn set(&mut self, n: u16, value: Value) -> Result<(), AlarmKind> {
        if n == 0 {
            return Err(AlarmKind::WriteProtectedVariable { number: 0 });
        }
        let slot = self.values.get_mut(usize::from(n) - 1).ok_or(out_of_range(i64::from(n)))?;
        let v = value.unwrap_or(f64::NAN);
        if slot.to_bits() != v.to_bits() && Self::is_common(n) {
            let bit = usize::from(n - FIRST_COMMON);
            self.dirty[bit / 32] |= 1 << (bit % 32);
        }
        *slot = v;
        Ok(())
    }

    /// Power-off for the local variables: `#1–#400` and `#601–#999` become null.
    pub fn clear_locals(&mut self) {
        for n in 1..=MAX_VARIABLE {
            if !Self::is_common(n) {
                self.values[usize::from(n) - 1] = f64::NAN;
            }
        }
    }

    /// Reads every common variable from `store` (at power-on).
    pub fn load_commons<S: CommonStore + ?Sized>(&mut self, store: &mut S) -> Result<(), S::Error> {
        for n in FIRST_COMMON..=LAST_COMMON {
            let v = store.load(n)?.filter(|v| v.is_finite());
            self.values[usize::from(n) - 1] = v.unwrap_or(f64::NAN);
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
                let v = self.values[bit + usize::from(FIRST_COMMON) - 1];
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

    /// The variables that are not null, in number order.
    pub fn defined(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        (1..=MAX_VARIABLE).zip(self.values.iter()).filter(|(_, v)| !v.is_nan()).map(|(n, v)| (n, *v))
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
