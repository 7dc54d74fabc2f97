//! The simulated NOR flash itself: erase to 0xFF, programming only clears bits,
//! alignment rules, and what a power cut leaves.

use controller::persist::sim::{SimError, SimFlash};
use embedded_storage::nor_flash::{NorFlash, ReadNorFlash};

type Flash = SimFlash<1024, 256, 4>;

fn read(f: &mut Flash, at: u32, n: usize) -> Vec<u8> {
    let mut b = vec![0; n];
    f.read(at, &mut b).unwrap();
    b
}

#[test]
fn programming_clears_bits_and_erasing_sets_them() {
    let mut f = Flash::new();
    assert_eq!(read(&mut f, 0, 4), [0xFF; 4]);
    f.write(4, &[0x0F, 0xF0, 0x00, 0xFF]).unwrap();
    f.write(4, &[0xFF, 0x30, 0xFF, 0x01]).unwrap();
    assert_eq!(read(&mut f, 4, 4), [0x0F, 0x30, 0x00, 0x01]);
    assert_eq!(f.ones_over_zeros(), 2, "two bytes asked for 1 bits over 0 bits");
    f.erase(0, 256).unwrap();
    assert_eq!(read(&mut f, 4, 4), [0xFF; 4]);
    assert_eq!(f.erase_counts(), &[1, 0, 0, 0]);
    assert_eq!(f.ops(), 3, "two words programmed, one sector erased");
}

#[test]
fn misaligned_and_out_of_range_accesses_fail() {
    let mut f = Flash::new();
    assert_eq!(f.write(2, &[0; 4]), Err(SimError::NotAligned));
    assert_eq!(f.write(0, &[0; 3]), Err(SimError::NotAligned));
    assert_eq!(f.erase(0, 100), Err(SimError::NotAligned));
    assert_eq!(f.erase(256, 0), Err(SimError::NotAligned));
    assert_eq!(f.write(1024, &[0; 4]), Err(SimError::OutOfBounds));
    assert_eq!(f.erase(0, 2048), Err(SimError::OutOfBounds));
    assert_eq!(f.read(1022, &mut [0; 4]), Err(SimError::OutOfBounds));
    assert_eq!(f.ops(), 0);
}

#[test]
fn a_cut_word_is_half_programmed_and_power_stays_off() {
    // Operation 4 is the cut: 4 % 3 == 1 programs the first half of the word.
    let mut f = Flash::new();
    f.cut_power_at(4);
    assert_eq!(f.write(0, &[0; 12]), Ok(()));
    assert_eq!(f.write(12, &[0x11, 0x22, 0x33, 0x44]), Err(SimError::PowerLost));
    assert!(f.power_lost());
    assert_eq!(f.read(0, &mut [0; 4]), Err(SimError::PowerLost));
    assert_eq!(f.erase(0, 256), Err(SimError::PowerLost));
    f.restore_power();
    assert_eq!(read(&mut f, 12, 4), [0x11, 0x22, 0xFF, 0xFF]);
    assert_eq!(f.ops(), 4);
}

#[test]
fn a_cut_erase_leaves_the_sector_partly_erased() {
    let mut f = Flash::new();
    f.write(256, &[0; 256]).unwrap();
    assert_eq!(f.ops(), 64);
    // Operation 65 (65 % 3 == 2): every other 64-byte block erased.
    f.cut_power_at(65);
    assert_eq!(f.erase(256, 512), Err(SimError::PowerLost));
    f.restore_power();
    let s = read(&mut f, 256, 256);
    assert!(s[..64].iter().all(|b| *b == 0xFF) && s[64..128].iter().all(|b| *b == 0));
    assert!(s[128..192].iter().all(|b| *b == 0xFF) && s[192..].iter().all(|b| *b == 0));
    // A write cut with nothing done (66 % 3 == 0).
    f.cut_power_at(66);
    assert_eq!(f.write(0, &[0; 4]), Err(SimError::PowerLost));
    f.restore_power();
    assert_eq!(read(&mut f, 0, 4), [0xFF; 4]);
}
