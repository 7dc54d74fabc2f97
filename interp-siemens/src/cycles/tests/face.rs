//! CYCLE71/CYCLE76/CYCLE77 under a scaling (the frame of the machining centre):
//! no SINUMERIK program can set one on this controller yet (SCALE/ASCALE are not
//! read), so the alarms 61011 and 61012 are checked on the state directly.

use super::*;
use interp_core::alarm::CycleAlarm;
use interp_core::canon::Plane;
use interp_core::modal::mill::on;

/// G17 at X0 Y0 Z20 with tool 1, D1 of radius 5 mm, F500 mm/min, the frame
/// scaling X, Y, Z by `k` thousandths.
fn scaled(k: [i32; 3]) -> (MachineConfig, State) {
    let mut cfg = machine();
    cfg.axes[1] = cfg.axes[0];
    let mut st = at(&cfg, 0.0, 20.0);
    st.modal.plane = Plane::Xy;
    st.modal.feed_mode = FeedMode::PerMin;
    st.feed.per_min = mm(500.0);
    (st.tool.tool, st.tool.offset_number, st.tool.nose_radius) = (1, 1, mm(5.0));
    st.mill.frame.active = on::SCALE;
    st.mill.frame.scale = k;
    (cfg, st)
}

fn args(v: &[f64]) -> Vec<Arg<'static>> {
    reals(&v.iter().map(|&x| Some(x)).collect::<Vec<_>>())
}

/// 61011: CYCLE71 under any scaling; 61012: a spigot under unequal factors of
/// the plane's axes (equal ones and the applicate's are accepted).
#[test]
fn scaling_alarms() {
    let c71 = args(&[10.0, 0.0, 2.0, -5.0, 20.0, 20.0, 30.0, 20.0, 0.0, 5.0, 8.0, 2.0, 0.0, 300.0, 11.0, 1.0]);
    let c77 = args(&[10.0, 0.0, 2.0, -5.0, 0.0, 30.0, 40.0, 40.0, 5.0, 0.5, 0.0, 300.0, 100.0, 2.0, 1.0, 40.0]);
    let alarm = |name: &str, a: &[Arg<'_>], k| {
        let (cfg, st) = scaled(k);
        call(name, a, &st, &cfg).err()
    };
    assert_eq!(alarm("CYCLE71", &c71, [1000, 1000, 1000]), None);
    assert_eq!(alarm("CYCLE71", &c71, [1000, 1000, 2000]), Some(CycleAlarm::ScaleNotAllowed.into()));
    assert_eq!(alarm("CYCLE71", &c71, [2000, 2000, 1000]), Some(CycleAlarm::ScaleNotAllowed.into()));
    assert_eq!(alarm("CYCLE77", &c77, [2000, 2000, 500]), None);
    assert_eq!(alarm("CYCLE77", &c77, [2000, 1500, 1000]), Some(CycleAlarm::ScaleDiffers.into()));
}
