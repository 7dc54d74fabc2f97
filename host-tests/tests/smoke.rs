use host_tests::run;

#[test]
fn smoke() {
    let r = run("%\nO0001\nG00 X20 Z25\nG01 X60 Z7 F500\nM30\n%\n");
    for a in &r.actions {
        println!("{a:?}");
    }
    println!("{:?}", r.alarms);
    assert!(r.alarms.is_empty());
}
