use host_tests::{kind_names, path, run};

fn show(name: &str, prog: &str) {
    let r = run(prog);
    println!("== {name}: alarms {:?}", r.alarm_codes());
    let k = kind_names(&r);
    for (c, n) in r.actions.iter().zip(k) {
        println!("  L{} {n} {:?}", c.line, host_tests::xz(c));
    }
    let _ = path(&r);
}

#[test]
fn smoke() {
    show("G90", "M03 S300\nG00 X130 Z3\nG90 X120 Z-110 F200\nX110 Z-30\nX100\nG00 X120 Z-30\nG90 X120 Z-44 R-7.5 F150\nZ-56 R-15\nM30\n");
    show("G71", "G00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W2.0\nN80 G00 X40 S1200\nG01 Z-30 F100\nX60 W-30\nW-20\nN120 X100 W-10\nG70 P80 Q120\nM30\n");
    show("G92", "M3 S300 G0 X150 Z50 T0101\nG0 X65 Z5\nG92 X58.7 Z-28 F3\nX57.7\nM30\n");
    show("G76", "G00 X100 Z50\nG50 X100 Z50 M3 S300\nG00 X80 Z10\nG76 P020560 Q0.15 R0.1\nG76 X60.64 Z-62 P3.68 Q1.8 F6\nG00 X100 Z50\nM30\n");
}
