#!/usr/bin/env python3
"""Where the firmware's flash goes: symbol sizes grouped by crate and by module.

Usage: size-report.py ELF [MODULES] [SYMBOLS]

Reads `arm-none-eabi-nm --size-sort -S -C` of a release ELF (the release profile keeps
symbols) and prints the flash bytes (code and read-only data, from the symbol sizes)
per crate, the MODULES (default 25) largest `crate::module` groups and the SYMBOLS
(default 0) largest functions. A symbol `<A as B>::f` counts for the crate of A (the
type whose trait impl it is), or of B when A is a primitive; `<impl X for Y>` paths for
the crate that holds the impl. What the symbols do not cover (literal pools, anonymous
constants, alignment) is printed as "unnamed"; local constants (`.L…`: strings,
panic locations, switch tables) as "(anonymous constants)".
"""

import re
import subprocess
import sys
from collections import defaultdict

FLASH_TYPES = set("tTrRwWvV")
PRIMITIVES = {
    "u8", "u16", "u32", "u64", "u128", "usize", "i8", "i16", "i32", "i64", "i128",
    "isize", "f32", "f64", "bool", "char", "str", "()",
}


def owner_path(name):
    """The `crate::module::...` path a demangled symbol name belongs to."""
    name = name.strip()
    while True:
        m = re.match(r"^<(?:impl )?(?:&(?:mut )?)?(?:\[)?([^<>\s;\]]+)", name)
        if not m:
            break
        first = m.group(1)
        head = first.split("::")[0]
        if head in PRIMITIVES or first.startswith("dyn") or re.fullmatch(r"[A-Z]", head):
            # `<u128 as core::fmt::Display>::fmt`: the trait's crate.
            after = re.search(r" as ([^<>\s]+)", name)
            if after:
                return after.group(1)
        return first
    return name


def crate_and_module(name):
    """(crate, crate::module) of a symbol; compiler-generated names get a group."""
    if name.startswith("embassy_executor::raw::TaskStorage<F>::poll"):
        # An embassy task's poll function is the task's async body: firmware code.
        return ("firmware", "firmware (tasks)")
    if name.startswith(".L"):
        return ("(anonymous constants)",) * 2
    path = owner_path(name)
    parts = [p for p in path.split("::") if p]
    if len(parts) < 2:
        if name.startswith("__") or name.startswith("mem"):
            return ("compiler_builtins", "compiler_builtins::(abi)")
        return ("(interrupts and runtime)",) * 2
    crate = parts[0]
    module = "::".join(parts[:2]) if len(parts) > 2 else crate
    return (crate, module)


def section_sizes(elf):
    """Bytes of the flash sections (.vector_table, .text, .rodata, .data)."""
    out = subprocess.run(["arm-none-eabi-size", "-A", elf], capture_output=True,
                         text=True, check=True).stdout
    sizes = {}
    for line in out.splitlines():
        cols = line.split()
        if len(cols) >= 2 and cols[0].startswith(".") and cols[1].isdigit():
            sizes[cols[0]] = int(cols[1])
    return sizes


def symbols(elf):
    """(size, type, name) of every sized flash symbol."""
    out = subprocess.run(["arm-none-eabi-nm", "--size-sort", "-S", "-C", elf],
                         capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        cols = line.split(" ", 3)
        if len(cols) == 4 and cols[2] in FLASH_TYPES:
            yield int(cols[1], 16), cols[2], cols[3]


def print_table(title, rows, total):
    print(title)
    for key, size in rows:
        print(f"  {size / 1024:7.1f} KB {100 * size / total:5.1f} %  {key}")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    elf = sys.argv[1]
    n_modules = int(sys.argv[2]) if len(sys.argv) > 2 else 25
    n_symbols = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    sections = section_sizes(elf)
    flash = sum(sections.get(s, 0) for s in (".vector_table", ".text", ".rodata", ".data"))
    by_crate = defaultdict(int)
    by_module = defaultdict(int)
    syms = list(symbols(elf))
    for size, _kind, name in syms:
        crate, module = crate_and_module(name)
        by_crate[crate] += size
        by_module[module] += size
    named = sum(by_crate.values())
    by_crate["unnamed"] = max(flash - named, 0)
    print(f"{elf}: flash {flash} bytes ({flash / 1024:.1f} KB)")
    print_table("per crate:", sorted(by_crate.items(), key=lambda kv: -kv[1]), flash)
    print_table(f"largest {n_modules} modules:",
                sorted(by_module.items(), key=lambda kv: -kv[1])[:n_modules], flash)
    if n_symbols:
        top = sorted(syms, key=lambda s: -s[0])[:n_symbols]
        print_table(f"largest {n_symbols} symbols:", [(n, s) for s, _k, n in top], flash)


if __name__ == "__main__":
    main()
