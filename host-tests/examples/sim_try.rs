use host_tests::sim::{Sim, SimOptions};
use interp_core::MachineConfig;

fn main() {
    let text = std::env::args().nth(1).map(|f| std::fs::read_to_string(f).unwrap()).unwrap_or_else(|| {
        "G0 X50 Z5\nM3 S800\nG1 Z-20 F200\nX60 Z-30\nG2 X80 Z-40 R10\nG1 Z-60\nG0 X100 Z50\nM30\n".into()
    });
    let mut sim = Sim::new(MachineConfig::default(), SimOptions { samples: true, ..SimOptions::default() }).unwrap();
    let r = sim.run_program(&text);
    println!("{r:#?}");
    for e in &sim.events {
        println!("{:?}", e);
    }
    println!("state {:?} alarm {:?}", sim.core.state(), sim.core.alarm());
}
