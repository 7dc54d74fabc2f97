#!/usr/bin/env python3
"""Worst-case stack bound of a firmware ELF by static analysis of its machine code
(arm-none-eabi-objdump), per embassy task and per interrupt handler, and the gate CI
runs on it (issue 22).

How the bound is found:
- Frame of a function: every stack decrement anywhere in its body (push, vpush,
  `sub sp`, `str rX, [sp, #-N]!`), added up. Branches that restore sp are not
  subtracted, so the frame is an upper bound of what the function holds at once.
- Calls: `bl`/`blx` to a label and tail branches (`b`/`b.w`) into another function.
- Indirect calls (`blx rN`, `bx rN`, rN any register: objdump names r9-r11 `sb`, `sl`,
  `fp`, calls through them were missed until 28 November 2026), by where rN was loaded
  from (the last write of rN in the 6 instructions before the call; a store or compare
  naming rN does not write it):
  * `ldr rN, [rM, #off]`, rM a register other than sp and the frame pointer, off
    >= 12: a vtable's method slot — or a `fn` field of a struct. It may reach the
    function in slot `off` of *any* vtable in .rodata/.data (class-hierarchy
    analysis by slot offset) and any plain function pointer: a function whose
    address is built in code (`movw`/`movt`) or lies in the data outside a vtable's
    methods (a pointer in memory is one or the other).
  * `ldr rN, [r7, #off]` in a function whose prologue made r7 the frame pointer
    (`add r7, sp, #K`): a stack load, never a vtable slot (reading it as one gave
    `Expansion::run` the functions of slot 20 of every vtable, and not the one it
    calls). Above the entry sp it is a stack argument: a function pointer its
    callers pass (LLVM's argument promotion of a `&mut dyn Out` method or of a
    `&mut dyn FnMut` closure whose every caller it knows). Each caller's
    `bl` is read back, within its basic block, to the store into that argument's
    slot and the stored register to its definition: a `movw`/`movt` function
    address, or a load as above (its slot and the plain pointers). Why this is
    sound: a call's stack arguments are stored by its call sequence, in the call's
    basic block (the outgoing area is shared by all calls of the caller, so no
    such store is hoisted out of it); a caller read otherwise (a tail call, a value
    from elsewhere), or a callee whose address is taken (callers unknown), leaves
    the call unresolved and listed.
  * A pointer the function built itself (`movw`/`movt`); the executor's poll of a
    task (each task's `TaskStorage::poll` is a root of its own, and the thread-mode
    bound is the executor's own depth plus the deepest task). Any other indirect
    call is listed as unresolved: the bound cannot see below it.
- Narrowing by method name (the default; `--slots` turns it off to compare): a call
  through a slot is narrowed by the call's source line (`addr2line -i`, the
  innermost inlined frame): of the slot's functions only those whose name ends in a
  method called on that line (`.name(` or `::name(`) are kept, and the closures and
  plain function pointers only if a function value is called there (`f(`, `)(`,
  `|`). Why this is sound: a call's instruction carries the location of the call
  expression (rustc's span of the call, kept by inlining as the innermost frame);
  where LLVM merges calls of different lines it sets line 0, and a Rust call
  through a trait object names its method on that line or calls a function value,
  which keeps every function value. Nothing is narrowed where that does not hold:
  a line that cannot be read (line 0, a file not at hand), a line with a macro
  (`write!` calls `.write_fmt(` unnamed), a line naming no function of the slot —
  these keep the slot and the plain pointers. Functions whose name may not be the
  method they serve (one body merged for several methods: seen at two slot
  offsets, or in a vtable of another Self type; a trait's default method named
  `Trait::m`) are kept at every narrowed call, and a function is matched by every
  symbol name at its address. Assumed, not checked: a method call written over two
  lines (`x\n    .m(`) is located on the line of `.m(` (rustc's span of the call's
  method and arguments). One
  fact about the toolchain's own core::fmt, whose source is not at hand: it calls
  the `Write` methods of its `dyn Write`, `fmt` of `dyn Debug` entries and its
  `Argument` formatters (`<T as Display>::fmt` …, a closure for the no-op Debug),
  so a slot call there keeps the slot's and the plain pointers' `write_str`,
  `write_char`, `write_fmt`, `fmt` and closures.
- Recursion: a call back into a function already on the path is listed and not
  followed (the bound then holds for one level of it only).
- An interrupt adds the Cortex-M4F exception frame (26 words with the FPU's lazy
  state, aligned: 108 bytes) to its handler's depth. Interrupts nest by priority, so
  the whole stack needs the thread bound plus one handler per priority level in use.

Usage: firmware/stack-bound.py ELF [--task-limit BYTES] [--isr-limit BYTES] [--slots]
Exits non-zero when the control task's bound is over --task-limit, an interrupt's
over --isr-limit, or the whole (thread + deepest task + one handler per priority
level) over the ELF's stack region (`_stack_start - _stack_end`, memory.x).

What it cannot see (listed in its output, per task): core::fmt's calls of its
`Argument` formatters (a fn pointer at offset 4), wakers (RawWakerVTable: embassy's
wake is a few dozen bytes), closures polled through `PollFn`, embassy-usb's handler
pointers, fn pointers spilled to the stack. None of them
leads into the interpreter or the motion core; the painted high-water mark
(qemu-test.py) is the measured check beside this bound.
"""
import argparse
import re
import struct
import subprocess
import sys

EXCEPTION_FRAME = 108
FUNC = re.compile(r"^([0-9a-f]+) <(.*)>:$")
INSN = re.compile(r"^\s*([0-9a-f]+):\t(\S+)\s*(.*)$")


def disassemble(elf):
    out = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", "-C", elf],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    return out.splitlines()


def words_of(elf, sections):
    """{address: 32-bit word} of the named sections (their link addresses)."""
    out = subprocess.run(["arm-none-eabi-objdump", "-s"] + [f"-j{s}" for s in sections] + [elf],
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    data = {}
    for line in out.splitlines():
        m = re.match(r"^ ([0-9a-f]{4,8}) ((?:[0-9a-f]{1,8} ){1,4})", line)
        if not m:
            continue
        addr = int(m.group(1), 16)
        blob = bytes.fromhex("".join(m.group(2).split()))
        for i in range(0, len(blob) - 3, 4):
            data[addr + i] = struct.unpack_from("<I", blob, i)[0]
    return data


def reg_list_count(regs):
    n = 0
    for r in regs.split(","):
        r = r.strip()
        if "-" in r:
            a, b = r.split("-")
            n += int(b.strip()[1:]) - int(a.strip()[1:]) + 1
        elif r:
            n += 1
    return n


def sp_decrement(op, args, prev):
    """Bytes one instruction takes off sp (0 if none); None for an amount not known."""
    if op in ("push", "push.w", "stmdb", "stmdb.w") and (op.startswith("push") or args.startswith("sp!")):
        return 4 * reg_list_count(args[args.index("{") + 1:args.index("}")])
    if op in ("vpush", "vpush.64", "vstmdb") and (op.startswith("vpush") or args.startswith("sp!")):
        regs = args[args.index("{") + 1:args.index("}")]
        return (8 if "d" in regs else 4) * reg_list_count(regs.replace("d", "r").replace("s", "r"))
    m = re.match(r"sp, (?:sp, )?#(\d+)", args)
    if op in ("sub", "sub.w", "subw", "subs") and m:
        return int(m.group(1))
    m = re.match(r"sp, (?:sp, )?(r\d+|ip)$", args)
    if op in ("sub", "sub.w", "subs") and m:
        for p in reversed(prev):
            mm = re.match(r"(?:movw|mov\.w|mov)\s+%s, #(\d+)" % m.group(1), p)
            if mm:
                return int(mm.group(1))
        return None
    m = re.match(r"\S+, \[sp, #-(\d+)\]!", args)
    if op.startswith("str") and m:
        return int(m.group(1))
    return 0


def analyse(lines):
    names, frame, calls, indirect, unknown_sub, consts = {}, {}, {}, {}, {}, {}
    insns, fp = {}, {}
    cur, prev, movw = None, [], {}
    for line in lines:
        m = FUNC.match(line)
        if m:
            cur, prev = int(m.group(1), 16), []
            names[cur], frame[cur], calls[cur], indirect[cur] = m.group(2), 0, set(), []
            consts[cur], movw, insns[cur] = set(), {}, []
            continue
        m = INSN.match(line)
        if cur is None or not m:
            continue
        addr, op, args = int(m.group(1), 16), m.group(2), m.group(3)
        # Every instruction with the function's stack depth before it (bytes below
        # the entry sp): the callers' argument stores are read from these.
        insns[cur].append((addr, op, args.split("@")[0].strip(), frame[cur]))
        # Addresses the function builds (movw/movt pairs): function pointers it may call.
        mm = re.match(r"(r\d+|ip|lr), #(\d+)", args)
        if op in ("movw", "mov.w") and mm:
            movw[mm.group(1)] = int(mm.group(2))
        elif op == "movt" and mm and mm.group(1) in movw:
            consts[cur].add(movw[mm.group(1)] | int(mm.group(2)) << 16)
        # The frame pointer of the AAPCS prologue (`push {.., r7, lr}; add r7, sp,
        # #K`): r7 - entry sp, so that r7-relative loads are read as the stack
        # loads they are.
        mm = re.match(r"r7, sp, #(\d+)$", args)
        if op in ("add", "add.w", "addw") and mm and cur not in fp:
            fp[cur] = int(mm.group(1)) - frame[cur]
        d = sp_decrement(op, args, prev)
        if d is None:
            unknown_sub[cur] = addr
        else:
            frame[cur] += d
        m = re.match(r"([0-9a-f]+) <", args)
        if op in ("bl", "blx", "b", "b.w", "b.n") and m:
            calls[cur].add(int(m.group(1), 16))
        elif op in ("blx", "bx") and re.match(r"(r\d+|ip|sb|sl|fp)$", args):
            reg = args
            slot = arg = None
            for p in reversed(prev[-6:]):
                mm = re.match(r"ldr(?:\.w)?\s+%s, \[(r\d+|ip|sp|sb|sl|fp), #(\d+)\]" % reg, p)
                if mm:
                    base, off = mm.group(1), int(mm.group(2))
                    if base == "r7" and cur in fp:
                        # A frame-pointer load: a spill or a stack argument, never a
                        # vtable slot. An argument (at or above the entry sp) is a
                        # function pointer the callers pass (`passed`).
                        arg = off + fp[cur] if off + fp[cur] >= 0 else None
                    elif base != "sp":
                        slot = off
                    break
                # Another write of the register ends the search; a store, compare
                # or test names the register first without writing it, a pair or
                # multiple load (ldrd, ldm, pop) may write it in any position.
                if re.match(r"\S+\s+%s," % reg, p) and not re.match(r"(str|stm|push|cmp|cmn|tst|teq|vstr|vcmp)", p):
                    break
                if re.match(r"(ldrd|ldm|pop)", p) and re.search(r"\b%s\b" % reg, p.split("[")[0]):
                    break
            indirect[cur].append((addr, slot, arg))
        prev.append(f"{op} {args}")
        prev = prev[-8:]
    return names, frame, calls, indirect, unknown_sub, consts, insns


def vtables(data, starts):
    """Rust vtables in the data: [drop or 0, size, align, method...]. Returns
    {slot offset: set of functions} and the addresses of the method words."""
    fn = lambda w: w & 1 and (w - 1) in starts
    slots, words, tables = {}, set(), []
    for a in sorted(data):
        if a % 4 or not (data[a] == 0 or fn(data[a])):
            continue
        size, align = data.get(a + 4), data.get(a + 8)
        if size is None or align not in (1, 2, 4, 8, 16) or size > 0x20000 or (size and size % align):
            continue
        off, table = 12, []
        while fn(data.get(a + off, 0)):
            slots.setdefault(off, set()).add(data[a + off] - 1)
            words.add(a + off)
            table.append(data[a + off] - 1)
            off += 4
        tables.append(table)
    return slots, words, tables


class Graph:
    def __init__(self, elf, methods=False):
        lines = disassemble(elf)
        self.names, self.frame, self.calls, self.indirect, self.unknown_sub, consts, self.insns = analyse(lines)
        # Function pointers each function builds; the spawner of each task (it builds
        # the address of the task's poll) names the task.
        self.pointers = {a: {c - 1 for c in cs if c & 1 and (c - 1) in self.names} for a, cs in consts.items()}
        starts = set(self.names)
        data = words_of(elf, [".rodata", ".data"])
        self.slots, vt_words, tables = vtables(data, starts)
        # Every function whose address lies in the data (vtables, waker tables, fn
        # pointers) or is built in code: what an unresolved indirect call may reach.
        taken = {w - 1 for w in data.values() if w & 1 and (w - 1) in starts}
        for ps in self.pointers.values():
            taken |= ps
        self.tasks = sorted(a for a in starts if "TaskStorage" in self.names[a] and self.names[a].endswith("::poll"))
        sites = [site for a in self.indirect for site, slot, _ in self.indirect[a] if slot]
        self.methods = called_methods(elf, sites) if methods else {}
        self.taken = taken - set(self.tasks)
        # Plain function pointers: functions whose address is built in code or
        # lies in the data outside a vtable's methods. A pointer loaded from
        # memory is a vtable's method or one of these.
        plain = {w - 1 for a, w in data.items() if w & 1 and (w - 1) in starts and a not in vt_words}
        for ps in self.pointers.values():
            plain |= ps
        self.plain = plain - set(self.tasks)
        self.wide = not methods
        # Method names of every symbol at a function's address (functions merged
        # into one body are aliases: each name counts).
        nm = subprocess.run(["arm-none-eabi-nm", "-C", elf], check=True, stdout=subprocess.PIPE, text=True).stdout
        aliases = {}
        for line in nm.splitlines():
            p = line.split(" ", 2)
            if len(p) == 3 and p[1] in "tTwW" and p[1]:
                aliases.setdefault(int(p[0], 16) & ~1, set()).add(p[2])
        self.method_names = {a: {method_name(n) for n in aliases.get(a, set()) | {self.names[a]}} for a in self.names}
        # A function whose name may not be the method of the slot it fills: one
        # body serving several methods (LLVM merges identical functions, keeping
        # one name), seen at more than one slot offset or in a vtable of another
        # Self type than its name's (`<X as T>::m` in a vtable of Y's methods),
        # or a trait's default method (named `T::m`, no Self type). A call
        # narrowed by name keeps these always.
        offsets = {}
        for o, fs in self.slots.items():
            for f in fs:
                offsets.setdefault(f, set()).add(o)
        self.unnamed = {f for f, os in offsets.items() if len(os) > 1}
        for table in tables:
            selfs = [self_type(self.names[f]) for f in table]
            known = [t for t in selfs if t]
            major = max(set(known), key=known.count) if known else None
            self.unnamed |= {f for f, t in zip(table, selfs) if t is None or t != major}
        self.cdepth = {}

    def narrowed(self, site, fns):
        """The functions a call at `site` through a slot holding `fns` can
        reach: the slot's functions and the plain function pointers (the load
        may be of a struct's `fn` field, not a vtable's); with `--methods`, of
        the slot's functions those named as a method called on the call's
        source line, and the plain pointers and the closures only if a
        function value is called on that line. A line that cannot be read, or
        that names none of them, keeps them all."""
        everything = fns | self.plain
        names = self.methods.get(site)
        if self.wide or not names:
            return everything
        if CORE_FMT in names:
            # core::fmt calls `Write` methods on its `dyn Write` and `fmt` on its
            # `dyn Debug` entries and `Argument` formatters (fn pointers, or a
            # closure for the no-op Debug): nothing else (see `called_methods`).
            return {f for f in everything if self.method_names[f] & (CORE_FMT_METHODS | {None})}
        kept = {f for f in fns if self.method_names[f] & names}
        if CLOSURE in names:
            # A closure or fn called through `dyn Fn*` or a `fn` pointer on that line.
            kept |= self.plain | {f for f in fns if self.method_names[f] & {None, "call", "call_mut", "call_once"}}
        return kept | (fns & self.unnamed) if kept else everything

    def passed(self, f, arg):
        """The functions a pointer passed to `f` in its stack argument at `arg`
        (bytes above its entry sp) may be; None when a caller cannot be read
        (the call then stays unresolved).

        LLVM passes a `&dyn Trait` argument's method, or a closure's body, as a
        plain function pointer when it knows every caller (argument promotion):
        the callee then calls through a stack argument. A stack argument is
        stored by the call sequence, in the basic block of the call (the
        outgoing area is shared by every call of the caller, so no store to it
        leaves its call's block): each `bl f` of each caller is read back to the
        store into `[sp, #arg]` at the call's depth, and that store's register
        back to its definition, both within the call's block — no branch, call
        or branch target in between. The definition must be a `movw`/`movt`
        pair naming a function, a load from a vtable slot (the whole slot, as
        for a call through it) or a `mov` from a register that is one. A tail
        call into `f` (its arguments are the caller's own), a caller that does
        not read so, or a callee called other than by `bl` (no caller known)
        leaves the call unresolved: listed, never guessed."""
        if not hasattr(self, "callers"):
            self.callers = {}
            for c, cs in self.calls.items():
                for x in cs:
                    self.callers.setdefault(x, set()).add(c)
        out = set()
        callers = self.callers.get(f, set())
        if not callers or f in self.taken:
            return None
        for c in callers:
            ins, labels = self.insns[c], self.labels(c)
            for i, (_, op, args, depth) in enumerate(ins):
                if not (re.match(r"[0-9a-f]+ <", args) and int(args.split()[0], 16) == f):
                    continue
                if op != "bl":
                    return None  # a tail call: f's arguments are c's own
                fns = None
                for j in range(i - 1, max(-1, i - 40), -1):
                    if ins[j + 1][0] in labels or ends_block(ins[j][1], ins[j][2]):
                        break
                    regs = stored_at(ins[j][1], ins[j][2], arg) if ins[j][3] == depth else []
                    if regs:
                        fns = self.defined(ins, labels, j, regs[0])
                        break
                if fns is None:
                    return None
                out |= fns
        return out

    def labels(self, c):
        """Addresses inside function `c` that its branches go to."""
        found = set()
        for _, op, args, _ in self.insns[c]:
            mm = re.match(r"([0-9a-f]+) <", args.split(", ")[-1])
            if mm and (op.startswith("b") or op.startswith("cb")) and not op.startswith("bl"):
                found.add(int(mm.group(1), 16))
        return found

    def defined(self, ins, labels, i, reg, hops=0):
        """The functions register `reg` holds before instruction `i` of a
        function's `ins`, by its definition in the same block (see `passed`);
        None if not one of those read."""
        lo = None
        for j in range(i - 1, max(-1, i - 40), -1):
            _, op, args, _ = ins[j]
            if ins[j + 1][0] in labels or ends_block(op, args):
                return None
            if not args.startswith(reg + ",") or op.startswith(("str", "cmp", "cmn", "tst", "teq", "stm", "vst")):
                continue
            mm = re.match(r"%s, #(\d+)$" % reg, args)
            if op == "movt" and mm and lo is None:
                lo = int(mm.group(1)) << 16
                continue
            if op in ("movw", "mov.w") and mm and lo is not None:
                v = lo | int(mm.group(1))
                return {v - 1} if v & 1 and (v - 1) in self.names else None
            mm = re.match(r"%s, \[(r\d+|ip), #(\d+)\]$" % reg, args)
            if op in ("ldr", "ldr.w") and mm and lo is None and mm.group(1) != "r7" and int(mm.group(2)) >= 12:
                return set(self.slots.get(int(mm.group(2)), ())) | self.plain
            mm = re.match(r"%s, (r\d+|ip)$" % reg, args)
            if op == "mov" and mm and lo is None and hops < 4:
                return self.defined(ins, labels, j, mm.group(1), hops + 1)
            return None
        return None

    def edges(self, a):
        """Direct and vtable-resolved callees of `a`, and its unresolved indirect calls."""
        out = {c for c in self.calls[a] if c in self.names and c != a}
        unresolved = []
        for site, slot, arg in self.indirect[a]:
            if slot is not None and slot >= 12 and slot in self.slots:
                out |= self.narrowed(site, self.slots[slot])
            elif arg is not None:
                fns = self.passed(a, arg)
                if fns is None:
                    unresolved.append(site)
                else:
                    out |= fns
            elif "embassy_executor" in self.names[a] and "TaskStorage" not in self.names[a]:
                pass  # the executor polls a task: the tasks are roots of their own
            elif self.pointers[a] - set(self.tasks):
                out |= self.pointers[a] - set(self.tasks)  # a pointer it built itself
            else:
                unresolved.append(site)
        return out, unresolved

    def condense(self):
        """Strongly connected components (recursion) of the call graph, Tarjan's
        algorithm without recursion; each component's worst depth."""
        succ = {a: self.edges(a) for a in self.names}
        index, low, on, stack, comp = {}, {}, set(), [], {}
        n = 0
        for root in self.names:
            if root in index:
                continue
            work = [(root, iter(succ[root][0]))]
            index[root] = low[root] = n; n += 1; stack.append(root); on.add(root)
            while work:
                v, it = work[-1]
                for w in it:
                    if w not in index:
                        index[w] = low[w] = n; n += 1; stack.append(w); on.add(w)
                        work.append((w, iter(succ[w][0])))
                        break
                    if w in on:
                        low[v] = min(low[v], index[w])
                else:
                    work.pop()
                    if work:
                        low[work[-1][0]] = min(low[work[-1][0]], low[v])
                    if low[v] == index[v]:
                        members = []
                        while True:
                            w = stack.pop(); on.discard(w); comp[w] = v; members.append(w)
                            if w == v:
                                break
                        self.members[v] = members
        # Depth per component, successors first (Tarjan emits them in that order).
        self.comp = comp
        for c, members in self.members.items():
            frames = sum(self.frame[m] for m in members)
            best, via = 0, None
            unres = set()
            for m in members:
                unres |= {(self.names[m], s) for s in succ[m][1]}
                if m in self.unknown_sub:
                    unres.add((self.names[m], self.unknown_sub[m]))
                for w in succ[m][0]:
                    cw = comp[w]
                    if cw == c:
                        continue
                    d = self.cdepth[cw][0]
                    unres |= self.cdepth[cw][2]
                    if d > best:
                        best, via = d, cw
            self.cdepth[c] = (frames + best, via, unres)

    def depth(self, a):
        """(bytes, deepest path, unresolved call sites, recursive groups) under `a`."""
        if not self.cdepth:
            self.members, self.cdepth = {}, {}
            self.condense()
        c = self.comp[a]
        d, _, unres = self.cdepth[c]
        path, rec = [], set()
        while c is not None:
            ms = self.members[c]
            path.append(max(ms, key=lambda m: self.frame[m]))
            if len(ms) > 1 or c in self.edges(c)[0]:
                rec.add(tuple(sorted(self.names[m][:50] for m in ms))[:4] + ((f"... {len(ms)} functions",) if len(ms) > 4 else ()))
            c = self.cdepth[c][1]
        return d, path, frozenset(unres), frozenset(rec)


def ends_block(op, args):
    """Whether an instruction ends a basic block or calls (branches, calls,
    returns, table branches, `it` blocks' conditional execution aside)."""
    return (op.split(".")[0] in ("b", "bl", "blx", "bx", "cbz", "cbnz", "tbb", "tbh")
            or re.match(r"b(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al)(\.[nw])?$", op) is not None
            or (op.startswith(("pop", "ldm")) and "pc" in args) or (op.startswith(("ldr", "mov")) and args.startswith("pc,")))


def stored_at(op, args, off):
    """Registers an instruction stores at `[sp, #off]`."""
    mm = re.match(r"(r\d+|ip|lr|fp|sl), \[sp(?:, #(\d+))?\]$", args)
    if op in ("str", "str.w") and mm:
        return [mm.group(1)] if int(mm.group(2) or 0) == off else []
    mm = re.match(r"(r\d+|ip|lr|fp|sl), (r\d+|ip|lr|fp|sl), \[sp(?:, #(\d+))?\]$", args)
    if op in ("strd", "strd.w") and mm:
        b = int(mm.group(3) or 0)
        return [mm.group(1)] if off == b else [mm.group(2)] if off == b + 4 else []
    mm = re.match(r"sp, \{(.*)\}$", args)
    if op in ("stmia", "stmia.w", "stm", "stm.w", "stmea", "stmea.w") and mm:
        regs = [r.strip() for r in mm.group(1).split(",")]
        if any("-" in r for r in regs):
            return ["?"] if off < 4 * 16 else []
        return [regs[off // 4]] if off % 4 == 0 and off // 4 < len(regs) else []
    return []


def vector_table(elf):
    words = words_of(elf, [".vector_table"])
    base = min(words)
    return [(i, words[base + 4 * i]) for i in range(len(words))]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("elf")
    ap.add_argument("--task-limit", type=int, default=None)
    ap.add_argument("--isr-limit", type=int, default=None)
    ap.add_argument("--slots", action="store_true", help="do not narrow vtable calls by the method named on the call's source line")
    ap.add_argument("--methods", action="store_true", help="(the default now; kept for old command lines)")
    args = ap.parse_args()
    # The stack region (memory.x): from the end of the statics down from the SRAM's top.
    nm = subprocess.run(["arm-none-eabi-nm", args.elf], check=True, stdout=subprocess.PIPE, text=True).stdout
    syms = {p[2]: int(p[0], 16) for p in (l.split() for l in nm.splitlines()) if len(p) == 3}
    args.stack = syms["_stack_start"] - syms["_stack_end"]
    # The controller's static (`firmware::CTL`, or `CTL_SLOT` in the F405's CCM): no
    # function on the boot path may have a frame that could hold it (half its size is
    # far above any other frame): the controller is built in place, never on the stack
    # and copied.
    nm_c = subprocess.run(["arm-none-eabi-nm", "-S", "-C", args.elf], check=True, stdout=subprocess.PIPE, text=True).stdout
    ctl = [int(p[1], 16) for p in (l.split() for l in nm_c.splitlines())
           if len(p) == 4 and p[3] in ("firmware::CTL", "firmware::CTL_SLOT")]
    ctl_size = max(ctl, default=0)
    sys.setrecursionlimit(100000)
    g = Graph(args.elf, not args.slots)
    failed = []

    def show(label, a, extra=0):
        d, p, unres, rec = g.depth(a)
        print(f"{label}: {d + extra} bytes")
        for x in p:
            if g.frame[x] >= 512:
                print(f"    {g.frame[x]:6d}  {g.names[x][:100]}")
        for name, site in sorted(unres)[:8]:
            print(f"    unresolved indirect call at {site:#010x} in {name[:90]}")
        for group in sorted(rec)[:8]:
            print(f"    recursion (counted once round): {' / '.join(group)}")
        return d + extra, unres, rec

    # Thread mode: Reset -> main -> executor; the executor polls the tasks.
    vt = vector_table(args.elf)
    reset = vt[1][1] - 1
    base, _, _ = show("thread mode up to the executor (Reset, init, executor loop)", reset)
    worst_task = 0
    print("tasks (the poll of each embassy task, its whole call tree; the executor's own frames come on top):")
    for a in g.tasks:
        name = g.names[a]
        d, p, unres, rec = g.depth(a)
        # The control task is the one whose tree holds the controller's line handling.
        under = " ".join(g.names[x] for x in reach(g, a))
        control = "Controller<_,_,_,_>::handle_lines" in under
        boot = "shell::build" in under or "motion::start" in under
        label = "control (interpreter, planner feed)" if control else "boot (main)" if boot else "link/usb/heartbeat"
        d, unres, rec = show(f"  task {label}, poll at {a:#010x}", a)
        if control and args.task_limit and d > args.task_limit:
            failed.append(f"the control task needs {d} bytes > {args.task_limit}")
        if boot and ctl_size:
            big = max(reach(g, a), key=lambda x: g.frame[x])
            print(f"    controller {ctl_size} bytes; largest frame on the boot path {g.frame[big]} ({g.names[big][:70]})")
            if 2 * g.frame[big] >= ctl_size:
                failed.append(f"{g.names[big][:70]} has a {g.frame[big]}-byte frame, half the {ctl_size}-byte "
                              "controller or more: it is built on the stack, not in place")
        worst_task = max(worst_task, d)
    # Interrupts: every vector that is not the default handler.
    default = max(set(w for _, w in vt[2:]), key=[w for _, w in vt[2:]].count)
    isr_worst = {}
    print(f"interrupts (+{EXCEPTION_FRAME} bytes exception frame each):")
    for i, w in vt[2:]:
        if w == default or w == 0 or (w - 1) not in g.names:
            continue
        d, unres, rec = show(f"  vector {i} ({g.names[w - 1][:60]})", w - 1, EXCEPTION_FRAME)
        isr_worst[i] = d
        if args.isr_limit and d > args.isr_limit:
            failed.append(f"interrupt {i} needs {d} bytes > {args.isr_limit}")
    # Nesting: one handler per priority level at most (the ISR bounds are per vector;
    # the levels are P0 step/index, P1 period/encoder, P3 serial/time/USB): the worst
    # of each level, taken as the three largest handlers.
    nested = sum(sorted(isr_worst.values())[-3:])
    total = base + worst_task + nested
    print(f"whole stack: thread {base} + deepest task {worst_task} + nested interrupts {nested} = {total} bytes")
    if args.stack:
        print(f"stack region {args.stack} bytes: {args.stack - total} bytes to spare")
        if total > args.stack:
            failed.append(f"the whole stack needs {total} bytes > the {args.stack}-byte region")
    for f in failed:
        print(f"stack-bound: FAIL: {f}")
    return 1 if failed else 0


def method_name(demangled):
    """`<T as a::Trait>::step` -> `step` (generic arguments and closures left off)."""
    depth, cut = 0, len(demangled)
    for i in range(len(demangled) - 1, -1, -1):
        ch = demangled[i]
        if ch in ">)":
            depth += 1
        elif ch in "<(":
            depth -= 1
        elif ch == ":" and depth == 0 and i > 0 and demangled[i - 1] == ":":
            name = demangled[i + 1:cut]
            return None if "{{" in name else name.split("<")[0]
    return demangled.split("<")[0]


def self_type(demangled):
    """`<X as a::T>::m` -> `X`; None for a name of another form."""
    if not demangled.startswith("<"):
        return None
    depth = 0
    for i, ch in enumerate(demangled):
        depth += ch == "<"
        depth -= ch == ">"
        if depth == 1 and demangled.startswith(" as ", i):
            return demangled[1:i]
        if depth == 0:
            return None
    return None


CALLED = re.compile(r"(?:\.|::)\s*([A-Za-z_][A-Za-z0-9_]*)\s*(?:::<[^()]*>)?\s*\(")


PLAIN_CALL = re.compile(r"(?<![\w.:])([a-z_][a-z0-9_]*)\s*\(")
KEYWORDS = {"if", "match", "while", "for", "return", "in", "as", "move", "loop", "let", "fn", "where", "unsafe"}
CLOSURE = "(a closure)"
MACRO = re.compile(r"[A-Za-z_]\w*!\s*[(\[{]")
CORE_FMT = "(core::fmt)"
CORE_FMT_METHODS = {"write_str", "write_char", "write_fmt", "fmt"}


def called_methods(elf, sites):
    """{site: set of method names called on the source line of the call at site}
    from the ELF's line tables (the innermost inlined frame); sites whose line
    cannot be read are left out."""
    if not sites:
        return {}
    out = subprocess.run(["arm-none-eabi-addr2line", "-e", elf, "-i", "-a"],
                         input="\n".join(f"{s:#x}" for s in sites), check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    found, site, cache = {}, None, {}
    for line in out.splitlines():
        if line.startswith("0x"):
            site = int(line, 16)
            continue
        if site is None or site in found:
            continue
        path, _, num = line.rpartition(":")
        num = num.split()[0] if num else ""
        if path.startswith("/rustc/") and "/library/core/src/fmt/" in path:
            # Inside core::fmt (its source is not at hand: a path of the
            # toolchain's build): see CORE_FMT_METHODS.
            found[site] = {CORE_FMT}
            site = None
            continue
        if not num.isdigit() or not path:
            site = None
            continue
        if path not in cache:
            try:
                with open(path, encoding="utf-8", errors="replace") as f:
                    cache[path] = f.read().splitlines()
            except OSError:
                cache[path] = None
        text = cache[path]
        if text and 0 < int(num) <= len(text):
            src = text[int(num) - 1]
            names = set(CALLED.findall(src))
            if set(PLAIN_CALL.findall(src)) - KEYWORDS or "|" in src or ")(" in src:
                names.add(CLOSURE)
            # A macro's call (`write!` is `.write_fmt(`) is not named on the
            # line that invokes it: such a line narrows nothing.
            if names and not MACRO.search(src):
                found[site] = names
        site = None
    return found


def reach(g, a):
    seen, todo = {a}, [a]
    while todo:
        for c in g.edges(todo.pop())[0]:
            if c not in seen:
                seen.add(c)
                todo.append(c)
    return seen


if __name__ == "__main__":
    sys.exit(main())
