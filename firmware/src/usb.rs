//! The fast link: the USB device of `link_driver::usb` (one CDC-ACM port, tested on
//! the host against a simulated USB host) on the board's OTG_FS driver, with the
//! same controller behind it as USART2 (the link tasks are in `main.rs`; their
//! byte handling is `link-driver`'s). A grbl sender sees the same protocol on
//! either; the controller talks to the USB port while a host has it open, to
//! USART2 otherwise (`link_driver::select`).

use static_cell::StaticCell;

use crate::board::UsbDriver;

/// The device and its serial port on the board.
pub type Usb = link_driver::usb::Usb<'static, UsbDriver>;
/// Host → board packets.
pub type UsbIn = embassy_usb::class::cdc_acm::Receiver<'static, UsbDriver>;
/// Board → host packets.
pub type UsbOut = embassy_usb::class::cdc_acm::Sender<'static, UsbDriver>;

/// Builds the device on the board's driver.
///
/// # Panics
///
/// If called twice (its buffers are handed out once).
pub fn build(driver: UsbDriver) -> Usb {
    static BUFFERS: StaticCell<link_driver::usb::Buffers<'static>> = StaticCell::new();
    link_driver::usb::build(driver, BUFFERS.init(link_driver::usb::Buffers::default()))
}

/// The USB device's task: enumeration, control requests, bus events (spawned by the
/// firmware and by the `hil_link_echo` bring-up test).
#[embassy_executor::task]
pub async fn device(mut device: embassy_usb::UsbDevice<'static, UsbDriver>) -> ! {
    device.run().await
}
