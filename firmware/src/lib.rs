//! Firmware for the STM32F405RG lathe motion board (and the STM32F446RE, feature
//! `f446`; QEMU `netduinoplus2`, feature `qemu`): the board file, the motion
//! interrupts with the task side's [`motion::MotionPort`], outputs and debounced
//! inputs as `hal` traits, the flash store region, and the link placeholder the
//! controller replaces.
#![no_std]

#[cfg(all(feature = "f405", feature = "f446"))]
compile_error!("features `f405` and `f446` select the chip: enable exactly one");
#[cfg(all(feature = "hw", feature = "qemu"))]
compile_error!("`qemu` replaces `hw`: build with `--no-default-features --features f405,qemu`");

pub mod board;
pub mod io;
pub mod link;
pub mod motion;
#[cfg(feature = "qemu")]
pub mod qemu;
pub mod store;
