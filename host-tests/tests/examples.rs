//! Every program in `examples/` runs on the default machine without an alarm.

use host_tests::{kind_names, run};

#[test]
fn example_programs_run_without_alarms() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "nc") {
            let text = std::fs::read_to_string(&path).unwrap();
            let r = run(&text);
            assert!(r.alarms.is_empty(), "{}: {:?}", path.display(), r.alarms);
            assert_eq!(kind_names(&r).last().map(String::as_str), Some("end true"), "{}", path.display());
            count += 1;
        }
    }
    assert!(count >= 4, "found {count} examples");
}
