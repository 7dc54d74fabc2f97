//! What a board keeps (`controller::persist::keep`, run by the firmware and by
//! `lathe board --flash`) on the controller's simulated NOR flash: what a board
//! saves at rest comes back after a restart.

use controller::persist::Persist;
use controller::persist::keep;
use controller::persist::sim::SimFlash;
use controller::{Controller, Inputs, Settings};
use interp_core::MachineConfig;
use interp_core::ProgramStore;
use interp_core::config::Param;
use motion_core::motion::MotionCore;

/// The firmware's F446 controller size (small enough for the test thread's stack).
type Ctl = Controller<1024, 2048, 8, 64>;
/// Eight 2 KB pages.
type Flash = SimFlash<{ 8 * 2048 }, 2048, 4>;

const PROGRAM: &[u8] = b"O0010\nG00 X10. Z2.\nM30\n";

/// A controller fed `lines` (each polled to its answer) on a motion core.
fn controller_after(lines: &[&str]) -> (Box<Ctl>, MotionCore<64>) {
    let cfg = MachineConfig::default();
    let pos = cfg.reference[0];
    let mut core = MotionCore::<64>::new(&cfg, pos).unwrap();
    let mut ctl = Box::new(Ctl::new(cfg, pos));
    let mut now = 0;
    for line in lines {
        assert_eq!(ctl.receive(&mut line.as_bytes().to_vec(), now), line.len());
        for _ in 0..5 {
            now += 1_000_000;
            ctl.poll(now, &mut core, &mut (), Inputs::default());
        }
    }
    let mut out = [0u8; 2048];
    let n = ctl.transmit(&mut out);
    let text = String::from_utf8_lossy(&out[..n]).to_string();
    assert!(!text.contains("error"), "{text}");
    (ctl, core)
}

#[test]
fn settings_parameters_offsets_commons_and_programs_survive_a_restart() {
    let mut flash = Flash::new();
    let (mut ctl, _core) = controller_after(&["$110=6000\n", "$20=0\n", "$P5147=2.5\n", "#401=12.5\n"]);
    ctl.memory_mut().load(PROGRAM, None).unwrap();
    // G54 X4 (diameter) Z-7.5 (this interpreter has no G10 yet).
    ctl.interpreter_mut().config_mut().work_offsets[0].0[0] = 2_000_000;
    ctl.interpreter_mut().config_mut().work_offsets[0].0[2] = -7_500_000;
    let before = keep::fingerprint(&ctl);
    assert_ne!(before, keep::fingerprint(&Ctl::new(MachineConfig::default(), Default::default())));
    {
        let mut store = Persist::new(&mut flash, 0..8 * 2048).unwrap();
        keep::save(&mut store, &mut ctl).unwrap();
    }

    // Power-on: configuration first (the motion core is built from it), then the rest.
    let mut store = Persist::new(&mut flash, 0..8 * 2048).unwrap();
    let mut cfg = MachineConfig::default();
    let mut settings = Settings::default();
    let refused = keep::load_config(&mut store, &mut cfg, &mut settings).unwrap();
    assert!(refused.is_empty(), "{refused:?}");
    assert_eq!(controller::settings::get(110, &cfg, &settings), Some(6000.0));
    assert!(!settings.soft_limits);
    assert_eq!(cfg.params.get(Param::by_number(5147).unwrap()), 2_500_000);
    assert_eq!(cfg.work_offsets[0].0[0], 2_000_000, "X4 diameter is 2 mm radius");
    assert_eq!(cfg.work_offsets[0].0[2], -7_500_000);
    let pos = cfg.reference[0];
    let mut again = Box::new(Ctl::new(cfg, pos));
    *again.settings_mut() = settings;
    let mut scratch = [0u8; 2048];
    assert_eq!(keep::load_rest(&mut store, &mut again, &mut scratch).unwrap(), 1);
    assert_eq!(again.memory().text(10), Some(PROGRAM));
    assert_eq!(again.interpreter().variables().get(401).unwrap(), Some(12.5));
    assert_eq!(keep::fingerprint(&again), before);
}

#[test]
fn a_deleted_program_is_deleted_from_the_store() {
    let mut flash = Flash::new();
    let (mut ctl, _core) = controller_after(&[]);
    ctl.memory_mut().load(PROGRAM, None).unwrap();
    let mut store = Persist::new(&mut flash, 0..8 * 2048).unwrap();
    keep::save(&mut store, &mut ctl).unwrap();
    assert_eq!(store.programs::<8>().unwrap().len(), 1);
    assert!(ctl.memory_mut().remove(10));
    keep::save(&mut store, &mut ctl).unwrap();
    assert!(store.programs::<8>().unwrap().is_empty());
}

/// The F446RE board's store: its three 16 KB sectors (1–3) hold a full program
/// memory of its controller (8 KB), every common variable, the settings and
/// offsets, and still have room to replace the largest program.
#[test]
fn the_f446_store_holds_a_full_program_memory_and_can_replace_a_program() {
    type F446 = Controller<4096, 8192, 16, 256>;
    type Sectors = SimFlash<{ 3 * 16384 }, 16384, 4>;
    let program = |n: u32, blocks: usize| {
        let mut t = format!("O{n:04}\n");
        for i in 0..blocks {
            t += &format!("N{} G01 X{}.5 Z-{}.25 F1000. M08\n", (i + 1) * 10, i % 50, i % 30);
        }
        t + "M30\n"
    };
    let cfg = MachineConfig::default();
    let pos = cfg.reference[0];
    let mut ctl = Box::new(F446::new(cfg, pos));
    // 4 × 60 sequence numbers of the 256 indexed.
    let texts: Vec<String> = (1..=4).map(|n| program(n, 60)).collect();
    for t in &texts {
        ctl.memory_mut().load(t.as_bytes(), None).unwrap();
    }
    assert!(texts.iter().map(String::len).sum::<usize>() > 7 * 1024);
    for n in 401..=600 {
        ctl.interpreter_mut().variables_mut().set(n, Some(f64::from(n) + 0.5)).unwrap();
    }
    let mut flash = Sectors::new();
    {
        let mut store = Persist::new(&mut flash, 0..3 * 16384).unwrap();
        keep::save(&mut store, &mut ctl).unwrap();
        // The largest program replaced by another as long: old and new text at once.
        let id = ctl.memory().numbers().next().unwrap();
        assert!(ctl.memory_mut().remove(id));
        let replaced = program(id, 59);
        ctl.memory_mut().load(replaced.as_bytes(), None).unwrap();
        keep::save(&mut store, &mut ctl).unwrap();
    }
    let before = keep::fingerprint(&ctl);
    let mut store = Persist::new(&mut flash, 0..3 * 16384).unwrap();
    let (mut cfg, mut settings) = (MachineConfig::default(), Settings::default());
    assert!(keep::load_config(&mut store, &mut cfg, &mut settings).unwrap().is_empty());
    let mut again = Box::new(F446::new(cfg, pos));
    let mut scratch = vec![0u8; 8192];
    assert_eq!(keep::load_rest(&mut store, &mut again, &mut scratch).unwrap(), 4);
    assert_eq!(again.interpreter().variables().get(600).unwrap(), Some(600.5));
    assert_eq!(keep::fingerprint(&again), before);
}

/// `$311=1` is stored and applied first at power-on, so the Y axis it gives is
/// there for `$101`/`$131` stored after it (docs/MILL-BOARD.md).
#[test]
fn the_machine_kind_and_y_settings_survive_a_restart() {
    use interp_core::axis::Axis;
    use interp_core::config::MachineKind;
    let mut flash = Flash::new();
    let (mut ctl, _core) = controller_after(&["$311=1\n", "$101=800\n", "$131=250\n"]);
    {
        let mut store = Persist::new(&mut flash, 0..8 * 2048).unwrap();
        keep::save(&mut store, &mut ctl).unwrap();
    }
    let mut store = Persist::new(&mut flash, 0..8 * 2048).unwrap();
    let mut cfg = MachineConfig::default();
    let mut settings = Settings::default();
    let refused = keep::load_config(&mut store, &mut cfg, &mut settings).unwrap();
    assert!(refused.is_empty(), "{refused:?}");
    assert_eq!(cfg.kind, MachineKind::Mill);
    assert!(!cfg.diameter_x);
    assert!(cfg.axis(Axis::Y).present);
    assert_eq!(controller::settings::get(311, &cfg, &settings), Some(1.0));
    assert_eq!(controller::settings::get(101, &cfg, &settings), Some(800.0));
    assert_eq!(controller::settings::get(131, &cfg, &settings), Some(250.0));
}

/// Feeds `line` to a running controller and polls it to its answer.
fn send(ctl: &mut Ctl, core: &mut MotionCore<64>, line: &str) -> String {
    thread_local!(static NOW: std::cell::Cell<u64> = const { std::cell::Cell::new(1_000_000_000) });
    let mut now = NOW.get();
    assert_eq!(ctl.receive(&mut line.as_bytes().to_vec(), now), line.len());
    for _ in 0..5 {
        now += 1_000_000;
        ctl.poll(now, core, &mut (), Inputs::default());
    }
    NOW.set(now);
    let mut out = [0u8; 2048];
    let n = ctl.transmit(&mut out);
    String::from_utf8_lossy(&out[..n]).to_string()
}

/// Saves `ctl` to `flash`, restarts from it: the configuration a board boots with.
fn save_and_boot(flash: &mut Flash, ctl: &mut Ctl) -> MachineConfig {
    {
        let mut store = Persist::new(&mut *flash, 0..8 * 2048).unwrap();
        keep::save(&mut store, ctl).unwrap();
    }
    let mut store = Persist::new(&mut *flash, 0..8 * 2048).unwrap();
    let (mut cfg, mut settings) = (MachineConfig::default(), Settings::default());
    // (After `$RST=$` on a mill the stored Y settings are the former mill's: unused, not refused.)
    let refused = keep::load_config(&mut store, &mut cfg, &mut settings).unwrap();
    assert!(refused.is_empty(), "{refused:?}");
    cfg
}

/// G54.1 P1–P48 (set by G10 L20 on a mill) survive a restart as G54–G59 do;
/// `$RST=$` keeps them, `$RST=#` clears them (issue 20).
#[test]
fn g54_1_offsets_survive_a_restart_and_rst_rules() {
    let mut flash = Flash::new();
    let (mut ctl, mut core) = controller_after(&["$311=1\n"]);
    for line in ["G90 G10 L20 P2 X-123.456 Y78.9 Z-0.001\n", "G10 L20 P48 X1. Y2. Z3.\n", "G10 L2 P1 X-5. Y-6. Z-7.\n"]
    {
        let text = send(&mut ctl, &mut core, line);
        assert!(text.contains("ok") && !text.contains("error"), "{line}: {text}");
    }
    let mm = |v: f64| (v * 1e6).round() as i64;
    let pos = |x, y, z| interp_core::Pos([mm(x), mm(y), mm(z), 0]);
    assert_eq!(ctl.interpreter().config().extra_offsets.get(2), Some(pos(-123.456, 78.9, -0.001)));
    let before = keep::fingerprint(&ctl);
    let cfg = save_and_boot(&mut flash, &mut ctl);
    assert_eq!(cfg.extra_offsets.get(2), Some(pos(-123.456, 78.9, -0.001)));
    assert_eq!(cfg.extra_offsets.get(48), Some(pos(1.0, 2.0, 3.0)));
    assert_eq!(cfg.extra_offsets.get(1), Some(interp_core::Pos::ZERO));
    assert_eq!(cfg.work_offsets[0], pos(-5.0, -6.0, -7.0));
    let again = Ctl::new(cfg.clone(), cfg.reference[0]);
    assert_eq!(keep::fingerprint(&again), before, "what is stored is what the board held");

    // Nothing changed: nothing is written.
    let stored = flash.contents().to_vec();
    save_and_boot(&mut flash, &mut ctl);
    assert!(flash.contents() == &stored[..], "a save without changes wrote to flash");
    // One row changed: the board's fingerprint changes, the restart has the new value.
    let text = send(&mut ctl, &mut core, "G10 L20 P2 X0 Y0 Z0\n");
    assert!(!text.contains("error"), "{text}");
    assert_ne!(keep::fingerprint(&ctl), before);
    assert_eq!(save_and_boot(&mut flash, &mut ctl).extra_offsets.get(2), Some(interp_core::Pos::ZERO));
    send(&mut ctl, &mut core, "G10 L20 P2 X7. Y8. Z9.\n");

    // $RST=$ keeps them; $RST=# clears them, on flash too.
    let text = send(&mut ctl, &mut core, "$RST=$\n");
    assert!(!text.contains("error"), "{text}");
    let cfg = save_and_boot(&mut flash, &mut ctl);
    assert_eq!(cfg.extra_offsets.get(2), Some(pos(7.0, 8.0, 9.0)));
    assert_eq!(cfg.extra_offsets.get(48), Some(pos(1.0, 2.0, 3.0)));
    send(&mut ctl, &mut core, "$311=1\n");
    let text = send(&mut ctl, &mut core, "$RST=#\n");
    assert!(!text.contains("error"), "{text}");
    let cfg = save_and_boot(&mut flash, &mut ctl);
    assert_eq!(cfg.extra_offsets.get(2), Some(interp_core::Pos::ZERO));
    assert_eq!(cfg.extra_offsets.get(48), Some(interp_core::Pos::ZERO));
    assert_eq!(cfg.work_offsets[0], interp_core::Pos::ZERO);
}
