//! The persistent store on simulated NOR flash: every record kind round-trips
//! through a restart, unchanged values are not rewritten, programs are listed,
//! replaced, deleted, and a full store keeps what it had.

use controller::persist::sim::SimFlash;
use controller::persist::{Error, Offsets, Persist, ProgramInfo};
use interp_core::Pos;
use interp_core::config::ToolOffset;
use interp_core::lang::fanuc::macros::{CommonStore, Variables};
use interp_core::program::{ProgramMemory, ProgramStore};

/// 8 sectors of 2 KB, 4-byte words.
type Small = SimFlash<{ 8 * 2048 }, 2048, 4>;
/// The F405 choice: sectors 10–11, 2 × 128 KB (offsets relative to the range).
type F405 = SimFlash<{ 2 * 131_072 }, 131_072, 4>;

fn small() -> Box<Small> {
    Box::new(Small::new())
}

fn open(flash: &mut Small) -> Persist<&mut Small> {
    Persist::new(flash, 0..8 * 2048).unwrap()
}

fn params(p: &mut Persist<&mut Small>) -> Vec<(u16, i64)> {
    let mut out = std::collections::BTreeMap::new();
    p.load_params(|n, v| {
        out.insert(n, v);
    })
    .unwrap();
    out.into_iter().collect()
}

/// A program text of `len` bytes, different for each `seed`.
fn text(o: u32, len: usize, seed: u8) -> Vec<u8> {
    let mut t = format!("O{o:04}\n").into_bytes();
    let mut i = 0u32;
    while t.len() < len {
        t.extend_from_slice(format!("N{i} G01 X{} Z-{}\n", i * 7 + u32::from(seed), i).as_bytes());
        i += 1;
    }
    t.truncate(len);
    t
}

#[test]
fn params_survive_a_restart_and_the_last_value_wins() {
    let mut flash = small();
    {
        let mut p = open(&mut flash);
        p.save_param(5147, 1_500_000).unwrap();
        p.save_param(10, 1).unwrap();
        p.save_param(5147, -2_000_000).unwrap();
    }
    let mut p = open(&mut flash);
    assert_eq!(params(&mut p), vec![(10, 1), (5147, -2_000_000)]);
}

#[test]
fn an_unchanged_value_is_not_rewritten() {
    let mut flash = small();
    let mut p = open(&mut flash);
    p.save_param(1, 42).unwrap();
    p.store(401, Some(2.5)).unwrap();
    let _ = p.release();
    let before = flash.ops();
    let mut p = open(&mut flash);
    p.save_param(1, 42).unwrap();
    p.store(401, Some(2.5)).unwrap();
    p.save_program(1, b"").unwrap();
    p.save_program(1, b"").unwrap();
    let _ = p.release();
    let after_first_program = flash.ops();
    let mut p = open(&mut flash);
    p.save_program(1, b"").unwrap();
    let _ = p.release();
    assert!(after_first_program > before, "the new program was written");
    assert_eq!(flash.ops(), after_first_program, "the same program again writes nothing");
    assert_eq!(flash.ones_over_zeros(), 0);
}

#[test]
fn commons_round_trip_through_the_variable_table() {
    let mut flash = small();
    {
        let mut p = open(&mut flash);
        let mut vars = Variables::new();
        vars.set(401, Some(1.25)).unwrap();
        vars.set(500, Some(-3.0e9)).unwrap();
        vars.set(600, Some(7.0)).unwrap();
        vars.flush_commons(&mut p).unwrap();
        vars.set(600, None).unwrap();
        vars.flush_commons(&mut p).unwrap();
    }
    let mut p = open(&mut flash);
    let mut vars = Variables::new();
    vars.load_commons(&mut p).unwrap();
    assert_eq!(vars.get(401).unwrap(), Some(1.25));
    assert_eq!(vars.get(500).unwrap(), Some(-3.0e9));
    assert_eq!(vars.get(600).unwrap(), None);
    assert_eq!(vars.get(402).unwrap(), None);
    assert_eq!(p.load(400), Err(Error::BadNumber));
    assert_eq!(p.store(601, Some(1.0)), Err(Error::BadNumber));
}

#[test]
fn offsets_round_trip() {
    let mut flash = small();
    let mut offsets = Offsets::default();
    offsets.work[0] = Pos::xz(-150_000_000, -300_250_000);
    offsets.work[5] = Pos([1, 2, 3, 4]);
    offsets.external = Pos::xz(0, 12_000);
    *offsets.tools.get_mut(1).unwrap() = ToolOffset {
        x: 1_000,
        z: -2_000,
        x_wear: 30,
        z_wear: -40,
        radius: 400_000,
        tip: 3,
        clearance_udeg: 60_000_000,
    };
    *offsets.tools.get_mut(32).unwrap() =
        ToolOffset { x: -5, z: 6, x_wear: 0, z_wear: 0, radius: 0, tip: 9, clearance_udeg: 0 };
    {
        let mut p = open(&mut flash);
        p.save_offsets(&Offsets::default()).unwrap();
        p.save_offsets(&offsets).unwrap();
    }
    let mut p = open(&mut flash);
    let mut back = Offsets::default();
    back.work[1] = Pos::xz(9, 9); // overwritten by the stored zero record
    p.load_offsets(&mut back).unwrap();
    assert_eq!(back, offsets);
    // One record at a time (a G10 or an offset page edit).
    p.save_work_offset(6, &Pos::xz(5, 5)).unwrap();
    p.save_tool_offset(2, &ToolOffset { x_wear: -12, ..ToolOffset::default() }).unwrap();
    assert_eq!(p.save_work_offset(7, &Pos::ZERO), Err(Error::BadNumber));
    assert_eq!(p.save_tool_offset(0, &ToolOffset::default()), Err(Error::BadNumber));
    assert_eq!(p.save_tool_offset(33, &ToolOffset::default()), Err(Error::BadNumber));
    let mut back = Offsets::default();
    p.load_offsets(&mut back).unwrap();
    assert_eq!(back.external, Pos::xz(5, 5));
    assert_eq!(back.tools.get(2).unwrap().x_wear, -12);
    assert_eq!(back.work, offsets.work);
}

#[test]
fn programs_are_saved_listed_replaced_and_deleted() {
    let mut flash = small();
    let a = text(1, 700, 1);
    let b = text(20, 1500, 2);
    let a2 = text(1, 300, 3);
    {
        let mut p = open(&mut flash);
        p.save_program(1, &a).unwrap();
        p.save_program(20, &b).unwrap();
        p.save_program(1, &a2).unwrap();
    }
    let mut p = open(&mut flash);
    let list = p.programs::<8>().unwrap();
    assert_eq!(list.as_slice(), &[ProgramInfo { number: 1, len: 300 }, ProgramInfo { number: 20, len: 1500 }]);
    let mut buf = vec![0; 2000];
    let n = p.load_program(1, &mut buf).unwrap();
    assert_eq!(&buf[..n], &a2[..]);
    let n = p.load_program(20, &mut buf).unwrap();
    assert_eq!(&buf[..n], &b[..]);
    assert_eq!(p.load_program(20, &mut buf[..100]), Err(Error::BufferTooSmall { needed: 1500 }));
    assert_eq!(p.delete_program(20), Ok(true));
    assert_eq!(p.delete_program(20), Ok(false));
    assert_eq!(p.load_program(20, &mut buf), Err(Error::NoProgram { program: 20 }));
    assert_eq!(p.programs::<8>().unwrap().len(), 1);
    assert_eq!(p.programs::<0>(), Err(Error::TooManyPrograms));
    assert_eq!(p.save_program(0, b"x"), Err(Error::BadNumber));
    assert_eq!(p.save_program(10_000, b"x"), Err(Error::BadNumber));
    let _ = p.release();
    assert_eq!(flash.ones_over_zeros(), 0);
}

#[test]
fn deleted_and_replaced_programs_leave_no_chunks_behind() {
    let mut flash = small();
    let mut p = open(&mut flash);
    // 20 rounds of ~1.5 KB on 14 KB of usable flash: only works if old
    // generations are really deleted.
    for round in 0..20u8 {
        p.save_program(7, &text(7, 1500, round)).unwrap();
        p.save_program(8, &text(8, 900, round)).unwrap();
        assert!(p.delete_program(8).unwrap());
    }
    let mut buf = vec![0; 2000];
    let n = p.load_program(7, &mut buf).unwrap();
    assert_eq!(&buf[..n], &text(7, 1500, 19)[..]);
}

#[test]
fn a_full_store_keeps_the_old_program() {
    let mut flash = small();
    let mut p = open(&mut flash);
    let keep = text(1, 3000, 1);
    p.save_program(1, &keep).unwrap();
    let mut stored = 1;
    let err = loop {
        match p.save_program(100 + stored, &text(100 + stored, 2500, 0)) {
            Ok(()) => stored += 1,
            Err(e) => break e,
        }
        assert!(stored < 20, "the store never filled up");
    };
    assert_eq!(err, Error::Full);
    assert_eq!(p.save_program(1, &text(1, 6000, 2)), Err(Error::Full));
    let mut buf = vec![0; 7000];
    let n = p.load_program(1, &mut buf).unwrap();
    assert_eq!(&buf[..n], &keep[..]);
    // Deleting makes room again.
    for o in 101..100 + stored {
        assert!(p.delete_program(o).unwrap());
    }
    p.save_program(1, &text(1, 6000, 2)).unwrap();
    let n = p.load_program(1, &mut buf).unwrap();
    assert_eq!(&buf[..n], &text(1, 6000, 2)[..]);
}

#[test]
fn format_erases_everything() {
    let mut flash = small();
    let mut p = open(&mut flash);
    p.save_param(3, 3).unwrap();
    p.store(450, Some(1.0)).unwrap();
    p.save_program(3, b"O0003\n%\n").unwrap();
    p.format().unwrap();
    assert!(params(&mut p).is_empty());
    assert_eq!(p.load(450), Ok(None));
    assert!(p.programs::<4>().unwrap().is_empty());
    p.save_param(4, 4).unwrap();
    let _ = p.release();
    assert!(flash.contents()[..].iter().any(|b| *b != 0xFF));
    let mut p = open(&mut flash);
    assert_eq!(params(&mut p), vec![(4, 4)]);
}

#[test]
fn bad_ranges_are_refused() {
    let mut flash = small();
    assert!(matches!(Persist::new(&mut *flash, 0..2048), Err(Error::BadRange)));
    assert!(matches!(Persist::new(&mut *flash, 100..4096), Err(Error::BadRange)));
    assert!(matches!(Persist::new(&mut *flash, 0..9 * 2048), Err(Error::BadRange)));
    assert!(matches!(Persist::new(&mut *flash, core::ops::Range { start: 4096, end: 0 }), Err(Error::BadRange)));
    assert!(matches!(Persist::new(&mut *flash, 4096..4096), Err(Error::BadRange)));
    let mut big = Box::new(SimFlash::<{ 20 * 1024 }, 1024, 4>::new());
    assert!(matches!(Persist::new(&mut *big, 0..17 * 1024), Err(Error::BadRange)));
    assert!(Persist::new(&mut *big, 1024..17 * 1024).is_ok());
}

#[test]
fn stored_programs_load_into_program_memory() {
    let mut flash = small();
    let mut p = open(&mut flash);
    p.save_program(12, b"O0012\nN10 G00 X10\nM99\n").unwrap();
    p.save_program(3, b"N1 G01 Z-5 F0.2\nM30\n").unwrap();
    let mut memory = ProgramMemory::<4096, 8, 64>::new();
    let mut scratch = [0u8; 512];
    assert_eq!(p.load_all_programs(&mut memory, &mut scratch), Ok(2));
    assert_eq!(memory.numbers().collect::<Vec<_>>(), vec![3, 12]);
    assert_eq!(memory.text(3).unwrap(), b"N1 G01 Z-5 F0.2\nM30\n");
}

#[test]
fn the_f405_sectors_hold_a_large_program_store() {
    let mut flash = Box::new(F405::new());
    let mut p = Persist::new(&mut *flash, 0..2 * 131_072).unwrap();
    let mut vars = Variables::new();
    for n in 401..=600 {
        vars.set(n, Some(f64::from(n) * 0.5)).unwrap();
    }
    vars.flush_commons(&mut p).unwrap();
    for n in 0..100u16 {
        p.save_param(n, i64::from(n) * 1000).unwrap();
    }
    // 80 KB of program text in four programs, then each replaced once (a
    // replacement needs room for the old and the new text).
    for round in 0..2u8 {
        for o in 1..=4u32 {
            p.save_program(o, &text(o, 20_000, round)).unwrap();
        }
    }
    let _ = p.release();
    let mut p = Persist::new(&mut *flash, 0..2 * 131_072).unwrap();
    let mut buf = vec![0; 30_000];
    for o in 1..=4u32 {
        let n = p.load_program(o, &mut buf).unwrap();
        assert_eq!(&buf[..n], &text(o, 20_000, 1)[..]);
    }
    let mut back = Variables::new();
    back.load_commons(&mut p).unwrap();
    assert_eq!(back.get(599).unwrap(), Some(299.5));
    // Fill up with 10 KB programs: how much text fits besides the above.
    let mut extra = 0;
    while p.save_program(100 + extra, &text(100 + extra, 10_000, 0)).is_ok() {
        extra += 1;
    }
    println!("F405 sectors: {} KB of program text stored", 80 + 10 * extra);
    assert!(extra >= 3, "at least 110 KB of program text fit");
    let _ = p.release();
    assert_eq!(flash.ones_over_zeros(), 0);
    println!("F405 sectors: erase counts {:?}", flash.erase_counts());
}

/// Saves, replaces and reads back records and programs on a flash with `WRITE`-byte
/// words, through a restart.
fn round_trip_with_word_size<const WRITE: usize>() {
    let mut flash = Box::new(SimFlash::<{ 8 * 2048 }, 2048, WRITE>::new());
    let a = text(4, 999, 1);
    {
        let mut p = Persist::new(&mut *flash, 0..8 * 2048).unwrap();
        for round in 0..30u8 {
            p.save_param(7, i64::from(round)).unwrap();
            p.store(420, Some(f64::from(round))).unwrap();
            p.save_program(4, &text(4, 500 + usize::from(round) * 17, round)).unwrap();
        }
        p.save_program(4, &a).unwrap();
    }
    let mut p = Persist::new(&mut *flash, 0..8 * 2048).unwrap();
    let mut last = None;
    p.load_params(|n, v| {
        if n == 7 {
            last = Some(v);
        }
    })
    .unwrap();
    assert_eq!(last, Some(29), "word size {WRITE}");
    assert_eq!(p.load(420), Ok(Some(29.0)));
    let mut buf = vec![0; 1000];
    let n = p.load_program(4, &mut buf).unwrap();
    assert_eq!(&buf[..n], &a[..]);
    let _ = p.release();
    assert_eq!(flash.ones_over_zeros(), 0);
    assert!(flash.erase_counts().iter().all(|c| *c > 0), "the pages were reused");
}

#[test]
fn byte_word_and_128_bit_writes_work() {
    round_trip_with_word_size::<1>();
    round_trip_with_word_size::<2>();
    round_trip_with_word_size::<16>();
}
