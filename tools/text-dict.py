#!/usr/bin/env python3
"""Chooses the dictionary of canon/src/text.rs: the words whose packing saves most.

Reads the texts of every `text_table!` in canon/src/alarm.rs (the `=> "..."` rows),
packs them the way `canon::text::pack` does (at a word start the longest
dictionary entry that matches, `{}` an argument), and picks, one at a time, the
entry that saves most bytes (its uses minus its own length) until 127 are chosen.
Prints the Rust array and the packed size. Run it when the texts change a lot:
`python3 tools/text-dict.py [FILE.rs ...]`.
"""
import re
import sys

MAX = 127


def texts(paths):
    out = []
    for p in paths:
        src = open(p).read()
        for block in re.findall(r'text_table!\s*\{(.*?)\n\}', src, re.S):
            for m in re.finditer(r'=>\s*"((?:[^"\\]|\\.)*)"', block):
                out.append(m.group(1).replace('\\"', '"').replace('\\\\', '\\'))
    return out


def word_start(t, i):
    return i == 0 or not t[i - 1].isalnum()


def pack_len(t, words):
    """Length of `t` packed with `words` (as canon::text packs)."""
    n, i = 0, 0
    by_first = {}
    for w in words:
        by_first.setdefault(w[0], []).append(w)
    while i < len(t):
        if t.startswith('{}', i):
            n, i = n + 1, i + 2
            continue
        best = 0
        if word_start(t, i):
            for w in by_first.get(t[i], ()):
                if len(w) > best and t.startswith(w, i):
                    best = len(w)
        n, i = n + 1, i + (best or 1)
    return n


def candidates(ts):
    c = set()
    for t in ts:
        for m in re.finditer(r"(?<![A-Za-z0-9])[A-Za-z][A-Za-z0-9'/_-]*(?: [a-z]+)? ?", t):
            s = m.group(0)
            for cand in {s, s.split(' ')[0], s.split(' ')[0] + ' '}:
                if len(cand) >= 3:
                    c.add(cand)
    return c


def main():
    paths = sys.argv[1:] or ['canon/src/alarm.rs']
    ts = texts(paths)
    raw = sum(len(t) for t in ts)
    words = []
    cur = sum(pack_len(t, words) for t in ts)
    cands = candidates(ts)
    # Cheap pre-filter: only words used at least twice can pay for themselves.
    cands = {w for w in cands if sum(t.count(w) for t in ts) >= 2}
    now = [pack_len(t, words) for t in ts]
    users = {w: [i for i, t in enumerate(ts) if w in t] for w in cands}
    while len(words) < MAX:
        best, gain = None, 0
        for w in cands:
            g = sum(now[i] - pack_len(ts[i], words + [w]) for i in users[w]) - len(w)
            if g > gain:
                best, gain = w, g
        if not best:
            break
        words.append(best)
        cands.discard(best)
        now = [pack_len(t, words) for t in ts]
    cur = sum(now)
    print(f"// {len(ts)} texts, {raw} B as written, {cur} B packed + {sum(map(len, words))} B of words")
    print("const WORDS: [&str; %d] = [" % len(words))
    for w in words:
        print(f'    "{w}",')
    print("];")


if __name__ == '__main__':
    main()
