//! Bring-up test: USART2 and USB echo at full rate. Every byte received on USART2
//! (115,200 8N1, PA2/PA3) is sent back on USART2, every USB CDC-ACM packet back on
//! USB, as fast as they come; a host script sends random text and compares
//! (`python3 firmware/hil/echo.py /dev/ttyUSB0` for USART2 through a USB-serial
//! adapter, `... /dev/ttyACM0` for USB; docs/BRINGUP.md). The script ends the run
//! with an EOT byte (0x04): the test then reports the bytes echoed per link, and
//! passes when it counted no receive error.
//!
//! `cargo run --release --bin hil_link_echo`, then the script in a second terminal.
#![no_std]
#![no_main]

use core::sync::atomic::{AtomicU32, Ordering};

use embassy_executor::Spawner;
use embassy_stm32::usart::{BufferedUartRx, BufferedUartTx};
use embassy_sync::blocking_mutex::raw::ThreadModeRawMutex;
use embassy_sync::signal::Signal;
use embassy_time::{Duration, with_timeout};
use embedded_io_async::{Read as _, Write as _};
use firmware::board::Board;
use firmware::hil::Report;
use {defmt_rtt as _, panic_probe as _};

/// End of transmission: the host's "done".
const EOT: u8 = 0x04;

/// Bytes echoed on USART2 and on USB, receive errors on USART2.
static ECHOED: [AtomicU32; 2] = [AtomicU32::new(0), AtomicU32::new(0)];
static ERRORS: AtomicU32 = AtomicU32::new(0);
/// Set when the host sent EOT.
static DONE: Signal<ThreadModeRawMutex, ()> = Signal::new();

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(spawner: Spawner) {
    let mut r = Report::new("hil_link_echo");
    let board = Board::new(firmware::chip::init());
    r.figure("USART2 baud", i64::from(firmware::board::DNC_BAUD), "baud");
    let (tx, rx) = board.dnc.split();
    spawner.spawn(defmt::unwrap!(uart_echo(rx, tx)));
    #[cfg(feature = "usb")]
    {
        let usb = firmware::usb::build(board.usb);
        spawner.spawn(defmt::unwrap!(firmware::usb::device(usb.device)));
        spawner.spawn(defmt::unwrap!(usb_echo(usb.rx, usb.tx)));
    }
    #[cfg(not(feature = "usb"))]
    r.skip("USB echo", "this build has no USB");
    DONE.wait().await;
    embassy_time::Timer::after_millis(50).await;
    r.figure("bytes echoed on USART2", i64::from(ECHOED[0].load(Ordering::Relaxed)), "bytes");
    r.figure("bytes echoed on USB", i64::from(ECHOED[1].load(Ordering::Relaxed)), "bytes");
    r.within("USART2 receive errors", i64::from(ERRORS.load(Ordering::Relaxed)), "errors", 0, 0);
    r.finish()
}

/// USART2: everything received, sent back.
#[embassy_executor::task]
async fn uart_echo(mut rx: BufferedUartRx<'static>, mut tx: BufferedUartTx<'static>) {
    let mut buf = [0u8; 64];
    loop {
        let n = match rx.read(&mut buf).await {
            Ok(n) => n,
            Err(_) => {
                ERRORS.fetch_add(1, Ordering::Relaxed);
                continue;
            }
        };
        let bytes = buf.get(..n).unwrap_or(&[]);
        // A write takes all its bytes or none, and nothing wakes one waiting for
        // room since `board::TcGuard` took the TC interrupt: retry every 1 ms.
        while !matches!(with_timeout(Duration::from_millis(1), tx.write(bytes)).await, Ok(Ok(_))) {}
        ECHOED[0].fetch_add(n as u32, Ordering::Relaxed);
        if bytes.contains(&EOT) {
            DONE.signal(());
        }
    }
}

/// USB: every packet received, sent back (a zero-length packet after a full one).
#[cfg(feature = "usb")]
#[embassy_executor::task]
async fn usb_echo(mut rx: firmware::usb::UsbIn, mut tx: firmware::usb::UsbOut) {
    use link_driver::packets::{MAX_PACKET, Output, read};
    let mut packet = [0u8; MAX_PACKET];
    let mut output = Output::new();
    loop {
        rx.wait_connection().await;
        loop {
            let Ok(bytes) = read(&mut rx, &mut packet).await else { break };
            let (n, eot) = (bytes.len(), bytes.contains(&EOT));
            let mut rest = bytes;
            let sent = output.send(&mut tx, |buf| {
                let k = buf.len().min(rest.len());
                buf[..k].copy_from_slice(&rest[..k]);
                rest = &rest[k..];
                k
            });
            if sent.await.is_err() {
                break;
            }
            ECHOED[1].fetch_add(n as u32, Ordering::Relaxed);
            if eot {
                DONE.signal(());
            }
        }
    }
}

firmware::hil_qemu_entry!();
