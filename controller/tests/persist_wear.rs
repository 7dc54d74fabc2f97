//! Wear: thousands of updates over a small flash range keep working, stay
//! readable (also across restarts), and wear all sectors alike.

use std::collections::BTreeMap;

use controller::persist::Persist;
use controller::persist::sim::SimFlash;
use interp_core::lang::fanuc::macros::CommonStore;

/// 4 sectors of 1 KB.
type Flash = SimFlash<{ 4 * 1024 }, 1024, 4>;
const RANGE: core::ops::Range<u32> = 0..4 * 1024;

fn program(round: u32) -> Vec<u8> {
    format!("O0005\nN1 G00 X{round} Z2\nN2 G01 Z-{round} F0.1\nM30\n").into_bytes()
}

#[test]
fn thousands_of_updates_over_four_small_sectors() {
    let mut flash = Box::new(Flash::new());
    let mut params = BTreeMap::new();
    let mut commons = BTreeMap::new();
    const ROUNDS: u32 = 20_000;
    let mut p = Persist::new(&mut *flash, RANGE).unwrap();
    for round in 0..ROUNDS {
        let n = (round % 12) as u16;
        let v = i64::from(round) * 1_000 - 7;
        p.save_param(n, v).unwrap();
        params.insert(n, v);
        if round % 3 == 0 {
            let c = 401 + (round % 20) as u16;
            let v = (round % 7 != 0).then_some(f64::from(round) / 8.0);
            p.store(c, v).unwrap();
            commons.insert(c, v);
        }
        if round % 50 == 0 {
            p.save_program(5, &program(round)).unwrap();
        }
        if round % 1000 == 999 {
            // A restart, and a check of everything.
            let _ = p.release();
            p = Persist::new(&mut *flash, RANGE).unwrap();
            let mut got = BTreeMap::new();
            p.load_params(|n, v| {
                got.insert(n, v);
            })
            .unwrap();
            assert_eq!(got, params, "round {round}");
            for (n, v) in &commons {
                assert_eq!(p.load(*n).unwrap(), *v, "round {round}: #{n}");
            }
            let mut buf = [0u8; 64];
            let len = p.load_program(5, &mut buf).unwrap();
            assert_eq!(&buf[..len], &program(round / 50 * 50)[..]);
        }
    }
    let _ = p.release();
    let counts = flash.erase_counts().to_vec();
    println!("erase counts per sector after {ROUNDS} rounds: {counts:?}");
    let (min, max) = (*counts.iter().min().unwrap(), *counts.iter().max().unwrap());
    assert!(min >= 100, "the sectors were reused many times: {counts:?}");
    assert!(max - min <= 1, "wear is levelled: {counts:?}");
    assert_eq!(flash.ones_over_zeros(), 0);
}
