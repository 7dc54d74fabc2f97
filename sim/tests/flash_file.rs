//! The virtual board with a flash file (`lathe board --flash`): what the board
//! keeps (grbl settings, parameters, offsets, common variables, programs) is
//! written while the machine is at rest and read back by the next power-on, with
//! the same code the firmware runs on its flash.

use interp_core::{MachineConfig, ProgramStore};
use sim::board::VirtualBoard;

/// 1 ms of simulated time.
const MS: u64 = 1_000_000;

/// Sends `line` and runs the board until it answers `ok` or `error:…`; the answer.
fn command(b: &mut VirtualBoard, line: &str) -> String {
    b.receive(format!("{line}\n").as_bytes());
    let mut text = String::new();
    for _ in 0..2_000 {
        b.run_for(MS);
        text.push_str(&String::from_utf8_lossy(&b.transmit()));
        if let Some(end) = text.lines().find(|l| *l == "ok" || l.starts_with("error:")) {
            return end.to_string();
        }
    }
    panic!("no answer to {line}: {text}");
}

fn image(name: &str) -> std::path::PathBuf {
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_file(&path);
    path
}

#[test]
fn what_the_board_keeps_survives_a_restart_of_the_virtual_board() {
    let path = image("keep.flash");
    let (mut b, restored) = VirtualBoard::with_flash(MachineConfig::default(), &path).unwrap();
    assert_eq!(restored.programs, 0);
    assert_eq!(std::fs::metadata(&path).unwrap().len(), 256 * 1024, "an erased F405 store");
    assert_eq!(command(&mut b, "$110=5000"), "ok");
    assert_eq!(command(&mut b, "$P5147=2.5"), "ok");
    assert_eq!(command(&mut b, "#401=12.5"), "ok");
    assert_eq!(command(&mut b, "M30"), "ok");
    b.ctl.memory_mut().load(b"O0010\nG00 X10. Z2.\nM30\n", None).unwrap();
    b.run_for(1_500 * MS);
    assert!(b.saves >= 1, "saved at rest");
    assert_eq!(b.save_error, None);
    drop(b);

    let (b, restored) = VirtualBoard::with_flash(MachineConfig::default(), &path).unwrap();
    assert_eq!(restored.programs, 1);
    assert!(restored.refused.is_empty());
    assert_eq!(b.ctl.memory().text(10), Some(&b"O0010\nG00 X10. Z2.\nM30\n"[..]));
    assert_eq!(b.ctl.param(5147), Some(2.5));
    assert_eq!(b.ctl.interpreter().variables().get(401), Ok(Some(12.5)));
    let mut b = b;
    let all = {
        b.receive(b"$$\n");
        b.run_for(20 * MS);
        String::from_utf8_lossy(&b.transmit()).to_string()
    };
    assert!(all.lines().any(|l| l == "$110=5000"), "{all}");
}

#[test]
fn a_file_that_is_not_a_store_image_is_refused() {
    let path = image("not-a-store.flash");
    std::fs::write(&path, b"hello").unwrap();
    let e = VirtualBoard::with_flash(MachineConfig::default(), &path).err().expect("refused");
    assert_eq!(e.to_string(), "5 bytes: a store image is 262144 bytes");
}
