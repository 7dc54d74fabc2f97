//! Firmware for the STM32F405RG lathe motion board (and the STM32F446RE, feature
//! `f446`; QEMU `netduinoplus2`, feature `qemu`): the board file, the motion
//! interrupts with the task side's [`motion::MotionPort`], outputs and debounced
//! inputs as `hal` traits, the board's side of the controller (`shell`: the
//! controller crate on the motion handle), its persistence on flash (`saved`,
//! not in the QEMU build) and the USB link (`usb`, feature `usb`).
#![no_std]

#[cfg(all(feature = "f405", feature = "f446"))]
compile_error!("features `f405` and `f446` select the chip: enable exactly one");
#[cfg(all(feature = "hw", feature = "qemu"))]
compile_error!("`qemu` replaces `hw`: build with `--no-default-features --features f405,qemu`");
#[cfg(all(feature = "usb", feature = "qemu"))]
compile_error!("QEMU's netduinoplus2 has no USB: the `qemu` build leaves `usb` out");

pub mod board;
pub mod chip;
pub mod hil;
pub mod io;
pub mod motion;
#[cfg(feature = "qemu")]
pub mod qemu;
#[cfg(persist)]
pub mod saved;
pub mod shell;
#[cfg(feature = "qemu")]
pub mod soft;
#[cfg(feature = "usb")]
pub mod usb;
