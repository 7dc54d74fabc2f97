//! The board's USB device: one CDC-ACM serial port at full speed (embassy-usb),
//! described here for any USB driver — the board's OTG_FS driver in the firmware,
//! a simulated host in the tests (`tests/usb_device.rs`), which enumerate it, open
//! the port and move data through the same class code.
//!
//! Identity: VID 0x1209 / PID 0x0001 (pid.codes' test pair, for development: a
//! product needs a pair of its own). CDC-ACM behind an interface association, so
//! every OS binds its own serial driver (Linux `ttyACM`, macOS `cu.usbmodem`,
//! Windows `usbser`).

use embassy_usb::class::cdc_acm::{CdcAcmClass, ControlChanged, Receiver, Sender, State};
use embassy_usb::driver::{Driver, EndpointError};
use embassy_usb::{Builder, UsbDevice};

use crate::packets::{Disconnected, MAX_PACKET, PacketIn, PacketOut};

/// Vendor ID (pid.codes).
pub const VID: u16 = 0x1209;
/// Product ID (pid.codes test PID).
pub const PID: u16 = 0x0001;
/// The device's product string.
pub const PRODUCT: &str = "Lathe motion board";

/// The memory the device description and the class keep (static on the board).
pub struct Buffers<'d> {
    /// The configuration descriptor: one CDC-ACM function with its association
    /// is 75 bytes.
    pub config_descriptor: [u8; 96],
    /// The BOS descriptor.
    pub bos_descriptor: [u8; 32],
    /// Control transfers' data (CDC's line coding is 7 bytes).
    pub control: [u8; 64],
    /// The CDC-ACM class's shared state (line coding, DTR/RTS).
    pub state: State<'d>,
}

impl Default for Buffers<'_> {
    fn default() -> Self {
        Buffers { config_descriptor: [0; 96], bos_descriptor: [0; 32], control: [0; 64], state: State::new() }
    }
}

/// The device and its serial port's halves.
pub struct Usb<'d, D: Driver<'d>> {
    /// The device: enumeration, control requests, bus events — run it
    /// (`UsbDevice::run`) in a task of its own.
    pub device: UsbDevice<'d, D>,
    /// Board → host packets.
    pub tx: Sender<'d, D>,
    /// Host → board packets.
    pub rx: Receiver<'d, D>,
    /// DTR/RTS (the host opening and closing the port).
    pub control: ControlChanged<'d>,
}

/// Describes the device on `driver`: one CDC-ACM function with 64-byte bulk packets.
pub fn build<'d, D: Driver<'d>>(driver: D, buffers: &'d mut Buffers<'d>) -> Usb<'d, D> {
    let Buffers { config_descriptor, bos_descriptor, control, state } = buffers;
    let mut config = embassy_usb::Config::new(VID, PID);
    config.manufacturer = Some("Lathe retrofit");
    config.product = Some(PRODUCT);
    config.serial_number = Some("0001");
    config.max_power = 100;
    config.max_packet_size_0 = 64;
    config.self_powered = true;
    // CDC in an interface association (Windows binds usbser to it without an .inf).
    config.device_class = 0xEF;
    config.device_sub_class = 0x02;
    config.device_protocol = 0x01;
    config.composite_with_iads = true;
    let mut builder = Builder::new(driver, config, config_descriptor, bos_descriptor, &mut [], control);
    let class = CdcAcmClass::new(&mut builder, state, MAX_PACKET as u16);
    let (tx, rx, control) = class.split_with_control();
    Usb { device: builder.build(), tx, rx, control }
}

/// Any endpoint error: the endpoint is gone (a buffer overflow cannot happen with
/// whole-packet buffers).
fn gone(_: EndpointError) -> Disconnected {
    Disconnected
}

impl<'d, D: Driver<'d>> PacketIn for Receiver<'d, D> {
    fn max_packet_size(&self) -> usize {
        usize::from(Receiver::max_packet_size(self))
    }

    async fn read_packet(&mut self, buf: &mut [u8]) -> Result<usize, Disconnected> {
        Receiver::read_packet(self, buf).await.map_err(gone)
    }
}

impl<'d, D: Driver<'d>> PacketOut for Sender<'d, D> {
    fn max_packet_size(&self) -> usize {
        usize::from(Sender::max_packet_size(self))
    }

    async fn write_packet(&mut self, data: &[u8]) -> Result<(), Disconnected> {
        Sender::write_packet(self, data).await.map_err(gone)
    }
}
