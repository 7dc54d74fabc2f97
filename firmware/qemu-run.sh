#!/usr/bin/env bash
# Boots the firmware's QEMU build (feature `qemu`) on QEMU's netduinoplus2 board
# (STM32F405). USART2, the DNC link, is on this terminal — or on a TCP socket that
# QEMU listens on (the guest starts when a client connects). Ctrl-A X quits QEMU.
#
# Usage: firmware/qemu-run.sh                 USART2 on stdio
#        firmware/qemu-run.sh --socket PORT   USART2 on tcp 127.0.0.1:PORT
#        firmware/qemu-run.sh --build         only build; print the ELF's path
set -euo pipefail
cd "$(dirname "$0")"

# A target directory of its own: the chip and time-driver features differ from the
# board build, and sharing one directory would rebuild embassy at every switch.
target_dir=${CARGO_TARGET_DIR:-$(realpath ..)/target}/qemu
cargo build -q --release --no-default-features --features f405,qemu,siemens,mill --target-dir "$target_dir"
elf=$(realpath "$target_dir/thumbv7em-none-eabihf/release/firmware")

case "${1:-}" in
--build)
    echo "$elf"
    exit 0
    ;;
--socket)
    serial=(-chardev "socket,id=dnc,host=127.0.0.1,port=${2:?port},server=on,wait=on" -serial null -serial chardev:dnc)
    ;;
*)
    serial=(-serial null -serial stdio)
    ;;
esac
# USART1 crashes QEMU 10.0.2 (NOTES.md): it gets `null`, USART2 the link. The clock
# counts instructions while the guest works (8 ns each, as qemu-test.py runs it;
# QEMU_ICOUNT=off for the host's clock).
icount=()
if [ "${QEMU_ICOUNT:-shift=3,sleep=on}" != off ]; then icount=(-icount "${QEMU_ICOUNT:-shift=3,sleep=on}"); fi
exec qemu-system-arm -M netduinoplus2 -nographic -monitor none "${serial[@]}" "${icount[@]}" -kernel "$elf"
