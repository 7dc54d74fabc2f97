//! The SINUMERIK standard turning cycles (seed 001 chapter 4): each cycle's
//! parameter list, the checks and alarms (61xxx) its section names, and the mapping
//! of its parameters onto the engine's shared generators — CYCLE97/CYCLE98 onto the
//! thread infeed engine of G76, CYCLE95 onto the roughing generator of G71/G72 …
//! ([`Engine`], implemented by the engine in `interp_core::cycles`).
//!
//! General rules (seed lines 514–701, 10099–10184): parameters are positional, an
//! empty or missing one is zero; the plane is G18 (Z the longitudinal axis, X the
//! plane axis); under diameter programming (DIAMON) the plane-axis values (SPD,
//! DM1 …) are diameters; lengths are in the programmed unit (G70/G71);
//! G functions active before the call are active after it.
//!
//! One file per cycle family: [`drill`] (CYCLE81–CYCLE89, CYCLE840), [`thread`] (CYCLE97, CYCLE98, thread re-cutting),
//! [`pattern`] (HOLES1, HOLES2, CYCLE801: positions for the modal drilling cycle), [`groove`] (CYCLE93), [`stock`] (CYCLE95, CYCLE950), [`undercut`] (CYCLE94,
//! CYCLE96).

mod drill;
mod groove;
mod mill;
mod pattern;
mod stock;
mod thread;
mod undercut;

#[cfg(test)]
mod tests;

pub use drill::plane_axes;
pub use interp_core::lang::Engine;
pub use interp_core::lang::siemens::call::{Arg, ContourSource, Signature, Ty};
#[cfg(feature = "mill-island")]
pub use mill::island::{predrill, predrills};
pub use pattern::{Notice, hole_pattern, is_pattern};

use interp_core::alarm::AlarmKind;
use interp_core::canon::Plane;
use interp_core::command::Command;
use interp_core::modal::State;
use interp_core::units::Units;

use interp_core::signature;

/// Every cycle of this module with its parameter list as the manual gives it.
pub static SIGNATURES: &[Signature] = &[
    // Line 1528: CYCLE81 (the drilling cycles' common five, lines 1530-1534).
    signature!("CYCLE81" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R)),
    // Line 1619: CYCLE82.
    signature!("CYCLE82" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R)),
    // Line 1709: CYCLE83.
    signature!("CYCLE83" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, FDEP: R, FDPR: R, DAM: R, DTB: R, DTS: R, FRF: R, VARI: I, _AXN: I,
        _MDEP: R, _VRT: R, _DTD: R, _DIS1: R
    )),
    // Line 1964: CYCLE84.
    signature!("CYCLE84" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R, SDAC: I, MPIT: R, PIT: R, POSS: R, SST: R, SST1: R, _AXN: I,
        _PTAB: I, _TECHNO: I, _VARI: I, _DAM: R, _VRT: R
    )),
    // Line 2212 (the print runs "PIT- AXN" together): CYCLE840.
    signature!("CYCLE840" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R, SDR: I, SDAC: I, ENC: I, MPIT: R, PIT: R, _AXN: I, _PTAB: I,
        _TECHNO: I
    )),
    // Line 2512: CYCLE85.
    signature!("CYCLE85" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R, FFR: R, RFF: R)),
    // Line 2633: CYCLE86.
    signature!("CYCLE86" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R, SDIR: I, RPA: R, RPO: R, RPAP: R, POSS: R)),
    // Line 2759: CYCLE87.
    signature!("CYCLE87" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, SDIR: I)),
    // Line 2843: CYCLE88.
    signature!("CYCLE88" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R, SDIR: I)),
    // Line 2926: CYCLE89.
    signature!("CYCLE89" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DTB: R)),
    // Line 3117: HOLES1 (row of holes).
    signature!("HOLES1" (SPCA: R, SPCO: R, STA1: R, FDIS: R, DBH: R, NUM: I)),
    // Line 3250: HOLES2 (circle of holes).
    signature!("HOLES2" (CPA: R, CPO: R, RAD: R, STA1: R, INDA: R, NUM: I)),
    // Line 3332: CYCLE801 (grid of points).
    signature!("CYCLE801" (_SPCA: R, _SPCO: R, _STA: R, _DIS1: R, _DIS2: R, _NUM1: I, _NUM2: I)),
    // Line 3544: CYCLE90.
    signature!("CYCLE90" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, DIATH: R, KDIAM: R, PIT: R, FFR: R, CDIR: I, TYPTH: I, CPA: R,
        CPO: R
    )),
    // Line 3780: LONGHOLE.
    signature!("LONGHOLE" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, NUM: I, LENG: R, CPA: R, CPO: R, RAD: R, STA1: R, INDA: R, FFD: R,
        FFP1: R, MID: R
    )),
    // Line 3964: SLOT1.
    signature!("SLOT1" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, NUM: I, LENG: R, WID: R, CPA: R, CPO: R, RAD: R, STA1: R, INDA: R,
        FFD: R, FFP1: R, MID: R, CDIR: I, FAL: R, VARI: I, MIDF: R, FFP2: R, SSF: R, _FALD: R, _STA2: R
    )),
    // Line 4243: SLOT2.
    signature!("SLOT2" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, NUM: I, AFSL: R, WID: R, CPA: R, CPO: R, RAD: R, STA1: R, INDA: R,
        FFD: R, FFP1: R, MID: R, CDIR: I, FAL: R, VARI: I, MIDF: R, FFP2: R, SSF: R, _FFCP: R
    )),
    // Line 4427 (the signature prints CPD, the table CPO): POCKET1.
    signature!("POCKET1" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, LENG: R, WID: R, CRAD: R, CPA: R, CPO: R, STA1: R, FFD: R, FFP1: R,
        MID: R, CDIR: I, FAL: R, VARI: I, MIDF: R, FFP2: R, SSF: R
    )),
    // Line 4582: POCKET2.
    signature!("POCKET2" (
        RTP: R, RFP: R, SDIS: R, DP: R, DPR: R, PRAD: R, CPA: R, CPO: R, FFD: R, FFP1: R, MID: R, CDIR: I, FAL: R,
        VARI: I, MIDF: R, FFP2: R, SSF: R
    )),
    // Line 4724: POCKET3.
    signature!("POCKET3" (
        _RTP: R, _RFP: R, _SDIS: R, _DP: R, _LENG: R, _WID: R, _CRAD: R, _PA: R, _PO: R, _STA: R, _MID: R, _FAL: R,
        _FALD: R, _FFP1: R, _FFD: R, _CDIR: I, _VARI: I, _MIDA: R, _AP1: R, _AP2: R, _AD: R, _RAD1: R, _DP1: R
    )),
    // Line 5026: POCKET4.
    signature!("POCKET4" (
        _RTP: R, _RFP: R, _SDIS: R, _DP: R, _PRAD: R, _PA: R, _PO: R, _MID: R, _FAL: R, _FALD: R, _FFP1: R, _FFD: R,
        _CDIR: I, _VARI: I, _MIDA: R, _AP1: R, _AD: R, _RAD1: R, _DP1: R
    )),
    // Line 5270: CYCLE71.
    signature!("CYCLE71" (
        _RTP: R, _RFP: R, _SDIS: R, _DP: R, _PA: R, _PO: R, _LENG: R, _WID: R, _STA: R, _MID: R, _MIDA: R, _FDP: R,
        _FALD: R, _FFP1: R, _VARI: I, _FDP1: R
    )),
    // Line 5456: CYCLE72.
    signature!("CYCLE72" (
        _KNAME: S, _RTP: R, _RFP: R, _SDIS: R, _DP: R, _MID: R, _FAL: R, _FALD: R, _FFP1: R, _FFD: R, _VARI: I,
        _RL: I, _AS1: I, _LP1: R, _FF3: R, _AS2: I, _LP2: R
    )),
    // Line 6467: CYCLE73.
    signature!("CYCLE73" (
        _VARI: I, _BNAME: S, _PNAME: S, _TN: S, _RTP: R, _RFP: R, _SDIS: R, _DP: R, _DPR: R, _MID: R, _MIDA: R,
        _FAL: R, _FALD: R, _FFP1: R, _FFD: R, _CDIR: I, _PA: R, _PO: R, _RAD: R, _DP1: R
    )),
    // Line 6156: CYCLE74.
    signature!("CYCLE74" (_KNAME: S, _LSANF: S, _LSEND: S)),
    // Line 6156: CYCLE75.
    signature!("CYCLE75" (_KNAME: S, _LSANF: S, _LSEND: S)),
    // Line 5772: CYCLE76.
    signature!("CYCLE76" (
        _RTP: R, _RFP: R, _SDIS: R, _DP: R, _DPR: R, _LENG: R, _WID: R, _CRAD: R, _PA: R, _PO: R, _STA: R, _MID: R,
        _FAL: R, _FALD: R, _FFP1: R, _FFD: R, _CDIR: I, _VARI: I, _AP1: R, _AP2: R
    )),
    // Line 5961: CYCLE77.
    signature!("CYCLE77" (
        _RTP: R, _RFP: R, _SDIS: R, _DP: R, _DPR: R, _PRAD: R, _PA: R, _PO: R, _MID: R, _FAL: R, _FALD: R, _FFP1: R,
        _FFD: R, _CDIR: I, _VARI: I, _AP1: R
    )),
    // Line 7696: CYCLE800.
    signature!("CYCLE800" (
        _FR: I, _TC: S, _ST: I, _MODE: I, _X0: R, _Y0: R, _Z0: R, _A: R, _B: R, _C: R, _X1: R, _Y1: R, _Z1: R,
        _DIR: I, _FR_I: R
    )),
    // Line 9261: CYCLE832.
    signature!("CYCLE832" (_TOL: R, _TOLM: I)),
    // Line 9805: CYCLE60.
    signature!("CYCLE60" (
        _TEXT: S, _RTP: R, _RFP: R, _SDIS: R, _DP: R, _DPR: R, _PA: R, _PO: R, _STA: R, _CP1: R, _CP2: R, _WID: R,
        _DF: R, _FFD: R, _FFP1: R, _VARI: I, _CODEP: I
    )),
    // Line 10198: CYCLE93.
    signature!("CYCLE93" (
        SPD: R, SPL: R, WIDG: R, DIAG: R, STA1: R, ANG1: R, ANG2: R, RCO1: R, RCO2: R, RCI1: R, RCI2: R, FAL1: R,
        FAL2: R, IDEP: R, DTB: R, VARI: I, _VRT: R
    )),
    // Line 10459: CYCLE94.
    signature!("CYCLE94" (SPD: R, SPL: R, FORM: C, _VARI: I)),
    // Line 10602: CYCLE95.
    signature!("CYCLE95" (
        NPP: S, MID: R, FALZ: R, FALX: R, FAL: R, FF1: R, FF2: R, FF3: R, VARI: I, DT: R, DAM: R, _VRT: R
    )),
    // Line 10962: CYCLE96.
    signature!("CYCLE96" (DIATH: R, SPL: R, FORM: C, _VARI: I)),
    // Line 11069: CYCLE97.
    signature!("CYCLE97" (
        PIT: R, MPIT: R, SPL: R, FPL: R, DM1: R, DM2: R, APP: R, ROP: R, TDEP: R, FAL: R, IANG: R, NSP: R, NRC: I,
        NID: I, VARI: I, NUMT: I, _VRT: R
    )),
    // Line 11259: CYCLE98.
    signature!("CYCLE98" (
        PO1: R, DM1: R, PO2: R, DM2: R, PO3: R, DM3: R, PO4: R, DM4: R, APP: R, ROP: R, TDEP: R, FAL: R, IANG: R,
        NSP: R, NRC: I, NID: I, PP1: R, PP2: R, PP3: R, VARI: I, NUMT: I, _VRT: R
    )),
    // Line 9805: CYCLE60.
    signature!("CYCLE60" (
        _TEXT: S, _RTP: R, _RFP: R, _SDIS: R, _DP: R, _DPR: R, _PA: R, _PO: R, _STA: R, _CP1: R, _CP2: R, _WID: R,
        _DF: R, _FFD: R, _FFP1: R, _VARI: I, _CODEP: I
    )),
    // Lines 11523–11527: CYCLE950.
    signature!("CYCLE950" (
        _NP1: S, _NP2: S, _NP3: S, _NP4: S, _VARI: I, _MID: R, _FALZ: R, _FALX: R, _FF1: R, _FF2: R, _FF3: R,
        _FF4: R, _VRT: R, _ANGB: R, _SDIS: R, _NP5: S, _NP6: S, _NP7: S, _NP8: S, _APZ: R, _APZA: I, _APX: R,
        _APXA: I, _TOL1: R
    )),
];

/// The cycle called `name` (case-insensitive), if this module implements it.
pub fn signature(name: &[u8]) -> Option<&'static Signature> {
    SIGNATURES.iter().find(|s| s.name.as_bytes().eq_ignore_ascii_case(name))
}

/// Starts the cycle `sig` with `args` (already type-checked and padded with
/// [`Arg::Empty`]) on the state: checks the parameters (the cycle's 61xxx alarms),
/// maps them onto the engine's specification and starts the generator. Nothing
/// moves when an alarm is returned.
pub fn start(
    sig: &Signature,
    args: &[Arg<'_>],
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    let p = Params::new(args, st);
    let r = match sig.name {
        "CYCLE81" => drill::cycle(drill::Drill::C81, &p, cmd, st, ctx),
        "CYCLE82" => drill::cycle(drill::Drill::C82, &p, cmd, st, ctx),
        "CYCLE83" => drill::cycle(drill::Drill::C83, &p, cmd, st, ctx),
        "CYCLE84" => drill::cycle(drill::Drill::C84, &p, cmd, st, ctx),
        "CYCLE840" => drill::cycle(drill::Drill::C840, &p, cmd, st, ctx),
        "CYCLE85" => drill::cycle(drill::Drill::C85, &p, cmd, st, ctx),
        "CYCLE86" => drill::cycle(drill::Drill::C86, &p, cmd, st, ctx),
        "CYCLE87" => drill::cycle(drill::Drill::C87, &p, cmd, st, ctx),
        "CYCLE88" => drill::cycle(drill::Drill::C88, &p, cmd, st, ctx),
        "CYCLE89" => drill::cycle(drill::Drill::C89, &p, cmd, st, ctx),
        "CYCLE93" => groove::cycle93(&p, cmd, st, ctx),
        "CYCLE94" => undercut::cycle94(&p, cmd, st, ctx),
        "CYCLE95" => stock::cycle95(&p, cmd, st, ctx, contour),
        "CYCLE96" => undercut::cycle96(&p, cmd, st, ctx),
        "CYCLE950" => stock::cycle950(&p, cmd, st, ctx, contour),
        "CYCLE97" => thread::cycle97(&p, cmd, st, ctx),
        "CYCLE98" => thread::cycle98(&p, cmd, st, ctx),
        "CYCLE800" => mill::cycle800(&p).map_err(AlarmKind::from),
        "CYCLE90" => mill::thread::cycle90(&p, cmd, st, ctx),
        "CYCLE832" => mill::cycle832(&p, st, ctx),
        #[cfg(feature = "mill-slots")]
        "LONGHOLE" => mill::slot::slots(mill::slot::Kind::Longhole, &p, cmd, st, ctx),
        #[cfg(feature = "mill-slots")]
        "SLOT1" => mill::slot::slots(mill::slot::Kind::Slot1, &p, cmd, st, ctx),
        #[cfg(feature = "mill-slots")]
        "SLOT2" => mill::slot::slots(mill::slot::Kind::Slot2, &p, cmd, st, ctx),
        #[cfg(not(feature = "mill-slots"))]
        "LONGHOLE" | "SLOT1" | "SLOT2" => Err(LEFT_OUT),
        "POCKET1" => mill::pocket::pocket12(false, &p, cmd, st, ctx),
        "POCKET2" => mill::pocket::pocket12(true, &p, cmd, st, ctx),
        #[cfg(feature = "mill-pockets")]
        "POCKET3" => mill::pocket::pocket34(false, &p, cmd, st, ctx),
        #[cfg(feature = "mill-pockets")]
        "POCKET4" => mill::pocket::pocket34(true, &p, cmd, st, ctx),
        #[cfg(not(feature = "mill-pockets"))]
        "POCKET3" | "POCKET4" => Err(LEFT_OUT),
        #[cfg(feature = "mill-face")]
        "CYCLE71" => mill::face::cycle71(&p, cmd, st, ctx),
        #[cfg(feature = "mill-face")]
        "CYCLE76" => mill::face::spigot(false, &p, cmd, st, ctx),
        #[cfg(feature = "mill-face")]
        "CYCLE77" => mill::face::spigot(true, &p, cmd, st, ctx),
        #[cfg(not(feature = "mill-face"))]
        "CYCLE71" | "CYCLE76" | "CYCLE77" => Err(LEFT_OUT),
        #[cfg(feature = "mill-engrave")]
        "CYCLE60" => mill::engrave::cycle60(&p, cmd, st, ctx),
        #[cfg(not(feature = "mill-engrave"))]
        "CYCLE60" => Err(LEFT_OUT),
        #[cfg(feature = "mill-contour")]
        "CYCLE72" => mill::contour::cycle72(&p, cmd, st, ctx, contour),
        #[cfg(not(feature = "mill-contour"))]
        "CYCLE72" => Err(LEFT_OUT),
        // CYCLE74/CYCLE75 are kept by the driver for the CYCLE73 that follows.
        #[cfg(feature = "mill-island")]
        "CYCLE73" => mill::island::cycle73(&p, cmd, st, ctx, contour),
        #[cfg(not(feature = "mill-island"))]
        "CYCLE73" | "CYCLE74" | "CYCLE75" => Err(LEFT_OUT),
        // A drilling pattern is run by the driver (positions, then the MCALL at
        // each); called modally it is not a drilling cycle.
        _ => Err(AlarmKind::NotSupportedYet { what: "this SINUMERIK cycle" }),
    };
    // A length read out of range stopped the call where it was read: whatever the
    // cycle did after it (with 0 for the value) is void, its alarm is 61xxx's
    // Overflow (see [`Params::nm`]).
    if p.overflow.get() { Err(AlarmKind::Overflow) } else { r }
}

/// A milling cycle this board's build leaves out for flash (interp-siemens'
/// features; docs/FIRMWARE-SIZES.md): alarm 4007, nothing moves.
#[cfg(not(all(
    feature = "mill-face",
    feature = "mill-slots",
    feature = "mill-pockets",
    feature = "mill-engrave",
    feature = "mill-contour",
    feature = "mill-island"
)))]
const LEFT_OUT: AlarmKind = AlarmKind::NotInThisBuild { what: "this milling cycle" };

/// The turning cycles work in the ZX plane (G18, line 10113).
fn need_zx(st: &State) -> Result<(), AlarmKind> {
    if st.modal.plane != Plane::Zx {
        return Err(AlarmKind::CycleNotInZxPlane);
    }
    Ok(())
}

/// The arguments of a call, read as the manual declares them, in internal units.
struct Params<'s, 'a> {
    args: &'s [Arg<'a>],
    /// Nanometres per programmed length unit (mm or inch, G71/G70).
    per_unit: f64,
    /// Plane-axis values are diameters (DIAMON).
    diameter: bool,
    /// A length was out of range ([`Params::nm`]): the call's alarm is
    /// [`AlarmKind::Overflow`], whatever the cycle found after it. The lengths
    /// are read without a `?` each — one check per call instead of one per
    /// parameter; [`Params::ok`] before the cycle hands anything to the engine.
    overflow: core::cell::Cell<bool>,
}

/// 1 mm, the manual's default for retracts and clearances.
const MM: i64 = 1_000_000;

/// Largest length a cycle parameter may give (10 m).
const MAX_LENGTH_NM: f64 = 1e13;

impl<'s, 'a> Params<'s, 'a> {
    fn new(args: &'s [Arg<'a>], st: &State) -> Self {
        let per_unit = match st.modal.units {
            Units::Metric => 1e6,
            Units::Inch => 25.4e6,
        };
        Params { args, per_unit, diameter: st.modal.diameter, overflow: core::cell::Cell::new(false) }
    }

    fn arg(&self, i: usize) -> Arg<'a> {
        self.args.get(i).copied().unwrap_or(Arg::Empty)
    }

    /// REAL parameter `i` (an INT is converted, a left-out one is zero).
    fn real(&self, i: usize) -> f64 {
        match self.arg(i) {
            Arg::Real(v) => v,
            Arg::Int(v) => v as f64,
            _ => 0.0,
        }
    }

    /// STRING or CHAR parameter `i` (empty when left out).
    fn text(&self, i: usize) -> &'a [u8] {
        match self.arg(i) {
            Arg::Str(s) => s,
            _ => &[],
        }
    }

    /// INT parameter `i`.
    fn int(&self, i: usize) -> i64 {
        match self.arg(i) {
            Arg::Int(v) => v,
            Arg::Real(v) if v.is_finite() => v as i64,
            _ => 0,
        }
    }

    /// A length in nm from a value in program units. Beyond [`MAX_LENGTH_NM`] (or
    /// not finite) the call stops with [`AlarmKind::Overflow`]: the value reads as
    /// 0 and the call's result is the overflow ([`start`], [`Params::ok`]), as if
    /// the alarm had been returned here.
    fn nm(&self, v: f64) -> i64 {
        let nm = v * self.per_unit;
        if !nm.is_finite() || libm::fabs(nm) > MAX_LENGTH_NM {
            self.overflow.set(true);
            return 0;
        }
        interp_core::geom::round_i64(nm)
    }

    /// Overflow if a length read so far was out of range: called before a cycle
    /// hands its specification to the engine (nothing moves on an alarm).
    fn ok(&self) -> Result<(), AlarmKind> {
        if self.overflow.get() { Err(AlarmKind::Overflow) } else { Ok(()) }
    }

    /// Length parameter `i`, nm, signed.
    fn len(&self, i: usize) -> i64 {
        self.nm(self.real(i))
    }

    /// Length parameter `i` the manual gives without sign (不输入符号), nm.
    fn unsigned(&self, i: usize) -> i64 {
        self.len(i).abs()
    }

    /// A plane-axis (X) position, as a radius: halved under DIAMON.
    fn x(&self, i: usize) -> i64 {
        let v = self.len(i);
        if self.diameter { v / 2 } else { v }
    }

    /// A retract or clearance the manual defaults to 1 mm when zero (_VRT).
    fn or_1mm(&self, i: usize) -> i64 {
        let v = self.unsigned(i);
        if v == 0 { MM } else { v }
    }
}
