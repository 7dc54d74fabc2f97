//! The fast link: a USB full-speed CDC-ACM serial port (embassy-usb) on OTG_FS, with
//! the same controller behind it as USART2 (the link tasks are in `main.rs`; their
//! byte handling is `link-driver`'s, tested on the host). A grbl sender sees the
//! same protocol on either; the controller talks to the USB port while a host has
//! it open, to USART2 otherwise (`link_driver::select`).
//!
//! Identity: VID 0x1209 / PID 0x0001 (pid.codes' test pair, for development: a
//! product needs a pair of its own). Class: CDC-ACM behind an interface
//! association, so every OS binds its own serial driver (Linux `ttyACM`, macOS
//! `cu.usbmodem`, Windows `usbser`).

use embassy_usb::class::cdc_acm::{CdcAcmClass, ControlChanged, Receiver, Sender, State};
use embassy_usb::driver::EndpointError;
use embassy_usb::{Builder, UsbDevice};
use link_driver::packets::{Disconnected, MAX_PACKET, PacketIn, PacketOut};
use static_cell::{ConstStaticCell, StaticCell};

use crate::board::UsbDriver;

/// Vendor ID (pid.codes).
pub const VID: u16 = 0x1209;
/// Product ID (pid.codes test PID).
pub const PID: u16 = 0x0001;

/// The USB device and the CDC-ACM port's halves.
pub struct Usb {
    /// The device: run it (`UsbDevice::run`) in a task of its own.
    pub device: UsbDevice<'static, UsbDriver>,
    /// Host → board packets.
    pub rx: UsbIn,
    /// Board → host packets.
    pub tx: UsbOut,
    /// DTR/RTS changes (the host opening and closing the port).
    pub control: ControlChanged<'static>,
}

/// Builds the device: one CDC-ACM function with 64-byte bulk packets.
///
/// # Panics
///
/// If called twice (its buffers are handed out once).
pub fn build(driver: UsbDriver) -> Usb {
    // The configuration descriptor of one CDC-ACM function with its association: 75 bytes.
    static CONFIG_DESC: ConstStaticCell<[u8; 96]> = ConstStaticCell::new([0; 96]);
    static BOS_DESC: ConstStaticCell<[u8; 32]> = ConstStaticCell::new([0; 32]);
    static CONTROL_BUF: ConstStaticCell<[u8; 64]> = ConstStaticCell::new([0; 64]);
    static STATE: StaticCell<State<'static>> = StaticCell::new();

    let mut config = embassy_usb::Config::new(VID, PID);
    config.manufacturer = Some("Lathe retrofit");
    config.product = Some("Lathe motion board");
    config.serial_number = Some("0001");
    config.max_power = 100;
    config.max_packet_size_0 = 64;
    config.self_powered = true;
    // CDC in an interface association (Windows binds usbser to it without an .inf).
    config.device_class = 0xEF;
    config.device_sub_class = 0x02;
    config.device_protocol = 0x01;
    config.composite_with_iads = true;

    let mut builder = Builder::new(driver, config, CONFIG_DESC.take(), BOS_DESC.take(), &mut [], CONTROL_BUF.take());
    let class = CdcAcmClass::new(&mut builder, STATE.init(State::new()), MAX_PACKET as u16);
    let (tx, rx, control) = class.split_with_control();
    Usb { device: builder.build(), rx: UsbIn(rx), tx: UsbOut(tx), control }
}

/// The CDC-ACM port's bulk OUT endpoint as `link-driver` reads it.
pub struct UsbIn(pub Receiver<'static, UsbDriver>);

/// The CDC-ACM port's bulk IN endpoint as `link-driver` writes it.
pub struct UsbOut(pub Sender<'static, UsbDriver>);

impl UsbIn {
    /// Waits until the host has configured the device.
    pub async fn wait_connection(&mut self) {
        self.0.wait_connection().await;
    }
}

impl UsbOut {
    /// Waits until the host has configured the device.
    pub async fn wait_connection(&mut self) {
        self.0.wait_connection().await;
    }
}

/// Any endpoint error: the endpoint is gone (a buffer overflow cannot happen with
/// whole-packet buffers).
fn gone(_: EndpointError) -> Disconnected {
    Disconnected
}

impl PacketIn for UsbIn {
    fn max_packet_size(&self) -> usize {
        usize::from(self.0.max_packet_size())
    }

    async fn read_packet(&mut self, buf: &mut [u8]) -> Result<usize, Disconnected> {
        self.0.read_packet(buf).await.map_err(gone)
    }
}

impl PacketOut for UsbOut {
    fn max_packet_size(&self) -> usize {
        usize::from(self.0.max_packet_size())
    }

    async fn write_packet(&mut self, data: &[u8]) -> Result<(), Disconnected> {
        self.0.write_packet(data).await.map_err(gone)
    }
}
