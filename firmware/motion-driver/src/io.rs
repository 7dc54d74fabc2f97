//! Machine inputs and outputs away from the step path: switch debouncing, the M codes
//! that switch the board's outputs, and the spindle speed command as a PWM duty.

/// A machine output switched by M codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AuxOut {
    /// Flood coolant (M08 on, M09 off).
    Flood,
    /// Air/mist coolant (M07 on, M09 off).
    Mist,
    /// Chuck clamp (M10 clamp, M11 unclamp).
    Chuck,
    /// Tailstock quill (M12 forward, M13 back).
    Tailstock,
    /// Way-lube pump (M32 on, M33 off).
    Lube,
}

impl AuxOut {
    /// Every output, in the order of their `hal::DigitalOutputs` numbers (0–4).
    pub const ALL: [AuxOut; 5] = [AuxOut::Flood, AuxOut::Mist, AuxOut::Chuck, AuxOut::Tailstock, AuxOut::Lube];

    /// The output's number for `hal::DigitalOutputs::set_output`.
    pub const fn number(self) -> u16 {
        self as u16
    }

    /// The output numbered `n`.
    pub fn from_number(n: u16) -> Option<Self> {
        Self::ALL.into_iter().find(|o| o.number() == n)
    }
}

/// The output switches of M code `m`: up to two (M09 switches both coolants off).
/// Other M codes switch nothing on this board.
pub fn aux_switches(m: u16) -> &'static [(AuxOut, bool)] {
    match m {
        7 => &[(AuxOut::Mist, true)],
        8 => &[(AuxOut::Flood, true)],
        9 => &[(AuxOut::Flood, false), (AuxOut::Mist, false)],
        10 => &[(AuxOut::Chuck, true)],
        11 => &[(AuxOut::Chuck, false)],
        12 => &[(AuxOut::Tailstock, true)],
        13 => &[(AuxOut::Tailstock, false)],
        32 => &[(AuxOut::Lube, true)],
        33 => &[(AuxOut::Lube, false)],
        _ => &[],
    }
}

/// A switch input of the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Switch {
    /// Emergency stop (active = stop).
    EStop,
    /// Feed hold button.
    FeedHold,
    /// Cycle start button.
    CycleStart,
    /// X limit (either end).
    XLimit,
    /// Z limit (either end).
    ZLimit,
    /// X home switch.
    XHome,
    /// Z home switch.
    ZHome,
    /// Y limit (either end; a mill's).
    YLimit,
    /// Y home switch (a mill's).
    YHome,
    /// A mill's automatic tool changer reports done.
    ToolChangeDone,
}

impl Switch {
    /// Every switch, in the order of their bits in a [`Debounce`] sample and their
    /// `hal::DigitalInputs` numbers (0–9; Y's and the tool changer's after the
    /// lathe's so that their numbers stay).
    pub const ALL: [Switch; 10] = [
        Switch::EStop,
        Switch::FeedHold,
        Switch::CycleStart,
        Switch::XLimit,
        Switch::ZLimit,
        Switch::XHome,
        Switch::ZHome,
        Switch::YLimit,
        Switch::YHome,
        Switch::ToolChangeDone,
    ];

    /// The switch's bit in a sample.
    pub const fn bit(self) -> u16 {
        1 << (self as u16)
    }
}

/// Debounced switch levels: a switch changes state after `K` consecutive equal
/// samples that differ from it (K ms at the control task's 1 ms sampling).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Debounce<const K: u8> {
    stable: u16,
    counts: [u8; 16],
}

impl<const K: u8> Debounce<K> {
    /// Starts with every switch at the levels of `initial` (bit set = active).
    pub const fn new(initial: u16) -> Self {
        Debounce { stable: initial, counts: [0; 16] }
    }

    /// Takes one sample of every switch (bit set = active); returns the debounced
    /// levels.
    pub fn sample(&mut self, raw: u16) -> u16 {
        for (bit, n) in self.counts.iter_mut().enumerate() {
            let mask = 1u16 << bit;
            if (raw ^ self.stable) & mask == 0 {
                *n = 0;
                continue;
            }
            *n += 1;
            if *n >= K {
                self.stable ^= mask;
                *n = 0;
            }
        }
        self.stable
    }

    /// The debounced levels.
    pub const fn levels(&self) -> u16 {
        self.stable
    }

    /// Whether `s` is active.
    pub const fn active(&self, s: Switch) -> bool {
        self.stable & s.bit() != 0
    }
}

/// The PWM compare value for `rpm` with a timer period of `max_duty` counts and
/// `max_rpm` at full output (10 V); stopped or `max_rpm` 0 gives 0.
pub fn spindle_duty(rpm: u32, max_rpm: u32, max_duty: u32) -> u32 {
    if max_rpm == 0 {
        return 0;
    }
    let duty = u64::from(rpm.min(max_rpm)) * u64::from(max_duty) / u64::from(max_rpm);
    duty as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn m_codes_switch_their_outputs() {
        assert_eq!(aux_switches(8), [(AuxOut::Flood, true)]);
        assert_eq!(aux_switches(9), [(AuxOut::Flood, false), (AuxOut::Mist, false)]);
        assert_eq!(aux_switches(13), [(AuxOut::Tailstock, false)]);
        assert_eq!(aux_switches(32), [(AuxOut::Lube, true)]);
        assert!(aux_switches(41).is_empty());
        assert_eq!(AuxOut::from_number(3), Some(AuxOut::Tailstock));
        assert_eq!(AuxOut::from_number(5), None);
    }

    #[test]
    fn a_switch_changes_after_k_equal_samples() {
        let mut d: Debounce<3> = Debounce::new(0);
        let e = Switch::EStop.bit();
        let h = Switch::FeedHold.bit();
        assert_eq!(d.sample(e), 0);
        assert_eq!(d.sample(e | h), 0);
        assert_eq!(d.sample(e | h), e);
        // A bounce restarts the count.
        assert_eq!(d.sample(e), e);
        assert_eq!(d.sample(e | h), e);
        assert_eq!(d.sample(e | h), e);
        assert_eq!(d.sample(e | h), e | h);
        assert!(d.active(Switch::FeedHold));
        assert!(!d.active(Switch::ZHome));
    }

    #[test]
    fn duty_scales_to_the_top_speed() {
        assert_eq!(spindle_duty(1_500, 3_000, 84_000), 42_000);
        assert_eq!(spindle_duty(9_000, 3_000, 84_000), 84_000);
        assert_eq!(spindle_duty(100, 0, 84_000), 0);
    }
}
