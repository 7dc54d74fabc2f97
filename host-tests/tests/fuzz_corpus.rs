//! Replays every committed fuzz corpus file (fuzz/corpus/<target>/) through the
//! fuzz harnesses on stable Rust, so a finding once fixed stays fixed without the
//! fuzzing toolchain. The harnesses are fuzz/src/lib.rs itself.

#[path = "../../fuzz/src/lib.rs"]
mod harness;

use std::path::PathBuf;

/// Every file of `fuzz/corpus/<target>`, sorted.
fn corpus(target: &str) -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus").join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("corpus entry").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

/// Runs `harness` on every corpus file of `target`, naming the file that fails.
fn replay(target: &str, min_files: usize, harness: fn(&[u8])) {
    let files = corpus(target);
    assert!(files.len() >= min_files, "{target}: {} corpus files", files.len());
    for f in &files {
        let data = std::fs::read(f).expect("corpus file reads");
        let r = std::panic::catch_unwind(|| harness(&data));
        assert!(r.is_ok(), "{target}: {} fails", f.display());
    }
}

#[test]
fn parser_corpus_replays() {
    replay("parser", 20, harness::parser);
}

#[test]
fn program_corpus_replays() {
    replay("program", 20, harness::program);
}

#[test]
fn cycles_corpus_replays() {
    replay("cycles", 9, harness::cycles);
}

#[test]
fn board_corpus_replays() {
    replay("board", 5, harness::board);
}

/// Fuzz finding (board): a sender that ignores character counting overfills the
/// receive buffer with jogs of a minute each; the final `?` sits behind bytes the
/// buffer cannot take and must still be answered within the harness's second.
#[test]
fn status_behind_a_buffer_overfilled_with_slow_jogs_is_answered() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/board");
    let data = std::fs::read(dir.join("finding_status_behind_backpressure")).expect("finding file");
    assert!(data.windows(13).any(|w| w == b"$J=G91 X5 F5\n"), "slow jogs");
    harness::board(&data);
}

#[test]
fn cycle_programs_cover_every_cycle() {
    let heads: Vec<String> = (0u8..9).map(|h| harness::cycle_program(&[h, 100, 0, 40, 0, 20, 0, 30])).collect();
    for (h, g) in heads.iter().zip(["G71", "G72", "G73", "G74", "G75", "G76", "G90", "G92", "G94"]) {
        assert!(h.contains(g), "{g}: {h}");
    }
}

#[test]
fn status_report_is_recognised() {
    assert!(harness::has_status_report(b"ok\r\n<Idle|MPos:0.000,0.000|FS:0,0>\r\n"));
    assert!(!harness::has_status_report(b"ok\r\n<Idle|MPos:0.0"));
    // Fuzz finding (board): in tape mode the board's XON may come right before the
    // report; it is flow control, not text (fuzz/corpus/board/finding_xon_status).
    assert!(harness::has_status_report(b"\x11<Idle|MPos:0.000>\r\n"));
    // In checksum mode every board line carries `*<crc>` (PROTOCOL.md).
    assert!(harness::has_status_report(b"error:88*345D\r\n<Run|MPos:1.000|Lk:1>*260A\r\n"));
    assert!(!harness::has_status_report(b"<Run|MPos:1.0*260A\r\n"));
}
