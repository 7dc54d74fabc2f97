#!/usr/bin/env python3
"""Worst-case stack bound of a firmware ELF by static analysis of its machine code
(arm-none-eabi-objdump), per embassy task and per interrupt handler, and the gate CI
runs on it (issue 22).

How the bound is found:
- Frame of a function: every stack decrement anywhere in its body (push, vpush,
  `sub sp`, `str rX, [sp, #-N]!`), added up. Branches that restore sp are not
  subtracted, so the frame is an upper bound of what the function holds at once.
- Calls: `bl`/`blx` to a label and tail branches (`b`/`b.w`) into another function.
- Indirect calls (`blx rN`, `bx rN`; objdump names r9-r11 `sb`, `sl`, `fp`: they are
  indirect calls too, and were missed until 28 November 2026): a call through a slot of a Rust vtable
  (`ldr rN, [rM, #off]` just before it, off >= 12) may reach the function in that
  slot of *any* vtable in .rodata/.data (class-hierarchy analysis by slot offset: an
  over-approximation, never an under-one). The executor's poll of a task through its
  function pointer is split off: each task's `TaskStorage::poll` is a root of its own,
  and the thread-mode bound is the executor's own depth plus the deepest task.
  Any other indirect call (a plain function pointer) is listed as unresolved: the
  bound cannot see below it.
- Recursion: a call back into a function already on the path is listed and not
  followed (the bound then holds for one level of it only).
- An interrupt adds the Cortex-M4F exception frame (26 words with the FPU's lazy
  state, aligned: 108 bytes) to its handler's depth. Interrupts nest by priority, so
  the whole stack needs the thread bound plus one handler per priority level in use.

Usage: firmware/stack-bound.py ELF [--task-limit BYTES] [--isr-limit BYTES]
Exits non-zero when the control task's bound is over --task-limit, an interrupt's
over --isr-limit, or the whole (thread + deepest task + one handler per priority
level) over the ELF's stack region (`_stack_start - _stack_end`, memory.x).

What it cannot see (listed in its output, per task): calls through core::fmt's
`&mut dyn Write`, wakers (RawWakerVTable: embassy's wake is a few dozen bytes),
closures polled through `PollFn`, embassy-usb's handler pointers. None of them
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
    cur, prev, movw = None, [], {}
    for line in lines:
        m = FUNC.match(line)
        if m:
            cur, prev = int(m.group(1), 16), []
            names[cur], frame[cur], calls[cur], indirect[cur] = m.group(2), 0, set(), []
            consts[cur], movw = set(), {}
            continue
        m = INSN.match(line)
        if cur is None or not m:
            continue
        addr, op, args = int(m.group(1), 16), m.group(2), m.group(3)
        # Addresses the function builds (movw/movt pairs): function pointers it may call.
        mm = re.match(r"(r\d+|ip|lr), #(\d+)", args)
        if op in ("movw", "mov.w") and mm:
            movw[mm.group(1)] = int(mm.group(2))
        elif op == "movt" and mm and mm.group(1) in movw:
            consts[cur].add(movw[mm.group(1)] | int(mm.group(2)) << 16)
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
            slot = None
            for p in reversed(prev[-6:]):
                mm = re.match(r"ldr(?:\.w)?\s+%s, \[(r\d+|ip|sp|sb|sl|fp), #(\d+)\]" % reg, p)
                if mm:
                    if mm.group(1) != "sp":
                        slot = int(mm.group(2))
                    break
                # Another write of the register ends the search; a store, compare
                # or test names the register first without writing it, a pair or
                # multiple load (ldrd, ldm, pop) may write it in any position.
                if re.match(r"\S+\s+%s," % reg, p) and not re.match(r"(str|stm|push|cmp|cmn|tst|teq|vstr|vcmp)", p):
                    break
                if re.match(r"(ldrd|ldm|pop)", p) and re.search(r"\b%s\b" % reg, p.split("[")[0]):
                    break
            indirect[cur].append((addr, slot))
        prev.append(f"{op} {args}")
        prev = prev[-8:]
    return names, frame, calls, indirect, unknown_sub, consts


def vtables(data, starts):
    """Rust vtables in the data: [drop or 0, size, align, method...]. Returns
    {slot offset: set of functions}."""
    fn = lambda w: w & 1 and (w - 1) in starts
    slots = {}
    for a in sorted(data):
        if a % 4 or not (data[a] == 0 or fn(data[a])):
            continue
        size, align = data.get(a + 4), data.get(a + 8)
        if size is None or align not in (1, 2, 4, 8, 16) or size > 0x20000 or (size and size % align):
            continue
        off = 12
        while fn(data.get(a + off, 0)):
            slots.setdefault(off, set()).add(data[a + off] - 1)
            off += 4
    return slots


class Graph:
    def __init__(self, elf):
        lines = disassemble(elf)
        self.names, self.frame, self.calls, self.indirect, self.unknown_sub, consts = analyse(lines)
        # Function pointers each function builds; the spawner of each task (it builds
        # the address of the task's poll) names the task.
        self.pointers = {a: {c - 1 for c in cs if c & 1 and (c - 1) in self.names} for a, cs in consts.items()}
        starts = set(self.names)
        data = words_of(elf, [".rodata", ".data"])
        self.slots = vtables(data, starts)
        # Every function whose address lies in the data (vtables, waker tables, fn
        # pointers) or is built in code: what an unresolved indirect call may reach.
        taken = {w - 1 for w in data.values() if w & 1 and (w - 1) in starts}
        for ps in self.pointers.values():
            taken |= ps
        self.tasks = sorted(a for a in starts if "TaskStorage" in self.names[a] and self.names[a].endswith("::poll"))
        self.taken = taken - set(self.tasks)
        self.cdepth = {}

    def edges(self, a):
        """Direct and vtable-resolved callees of `a`, and its unresolved indirect calls."""
        out = {c for c in self.calls[a] if c in self.names and c != a}
        unresolved = []
        for site, slot in self.indirect[a]:
            if slot is not None and slot >= 12 and slot in self.slots:
                out |= self.slots[slot]
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


def vector_table(elf):
    words = words_of(elf, [".vector_table"])
    base = min(words)
    return [(i, words[base + 4 * i]) for i in range(len(words))]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("elf")
    ap.add_argument("--task-limit", type=int, default=None)
    ap.add_argument("--isr-limit", type=int, default=None)
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
    g = Graph(args.elf)
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
