//! Firmware for the STM32F405RG lathe motion board: board bring-up shared by the
//! firmware binary (and, later, by its tasks for motion, spindle, I/O and DNC).
#![no_std]

pub mod board;
