#!/usr/bin/env python3
"""Checks the manual's structure and links; CI runs it beside `mdbook build docs`.

- Every page docs/*.md is listed in docs/SUMMARY.md (outside HTML comments), so no page
  is left out of the book. (A page SUMMARY.md lists that does not exist already fails
  `mdbook build docs`: docs/book.toml has create-missing = false.)
- Every relative link and image of README.md and docs/*.md points to a file or
  directory that exists, and every #anchor to a heading (or an id/name) of its
  target page: mdBook checks neither.
- Every {{#include FILE}} of a page names a file that exists.

Anchors are the headings' slugs as GitHub and mdBook make them (lower case, spaces to
'-', punctuation dropped; repeated headings get -1, -2, …).
Usage: python3 tools/check-docs.py   (exit 1 and one line per problem)
"""
import os
import re
import sys
import unicodedata

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DOCS = os.path.join(ROOT, "docs")

FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_ATTR = re.compile(r"""\b(?:href|src)\s*=\s*["']([^"']+)["']""")
HTML_ID = re.compile(r"""\b(?:id|name)\s*=\s*["']([^"']+)["']""")
INCLUDE = re.compile(r"\{\{#include\s+([^}:\s]+)(?::[^}]*)?\}\}")
COMMENT = re.compile(r"<!--.*?-->", re.S)
INLINE_CODE = re.compile(r"(`+)(.+?)\1")


def prose_lines(text):
    """The lines outside fenced code blocks, with their numbers."""
    fence = None
    for n, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if m:
            if fence is None:
                fence = m.group(1)
            elif m.group(1) == fence:
                fence = None
            continue
        if fence is None:
            yield n, line


def heading_text(raw):
    """A heading's text as rendered: links to their text, code and emphasis marks dropped."""
    t = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", raw)
    t = INLINE_CODE.sub(lambda m: m.group(2), t)
    t = re.sub(r"<[^>]+>", "", t)
    return t


def slugs(text):
    """Both GitHub's and mdBook's anchor for a heading."""
    gh = "".join(c for c in text.lower() if c in "-_ " or unicodedata.category(c)[0] in "LN")
    gh = gh.replace(" ", "-")
    mdb = "".join(
        (c.lower() if c.isascii() else c) if (c.isalnum() or c in "_-") else ("-" if c.isspace() else "")
        for c in text
    )
    return {gh, mdb}


_anchors = {}


def anchors(path):
    if path not in _anchors:
        found, seen = set(), {}
        text = open(path, encoding="utf-8").read()
        for _, line in prose_lines(COMMENT.sub("", text)):
            m = HEADING.match(line)
            if m:
                for s in slugs(heading_text(m.group(2))):
                    k = seen.get(s, 0)
                    seen[s] = k + 1
                    found.add(s if k == 0 else f"{s}-{k}")
            found.update(HTML_ID.findall(line))
        _anchors[path] = found
    return _anchors[path]


def check_links(path, problems):
    rel = os.path.relpath(path, ROOT)
    text = COMMENT.sub(lambda m: "\n" * m.group(0).count("\n"), open(path, encoding="utf-8").read())
    base = os.path.dirname(path)
    for n, line in prose_lines(text):
        for m in INCLUDE.finditer(line):
            if not os.path.isfile(os.path.normpath(os.path.join(base, m.group(1)))):
                problems.append(f"{rel}:{n}: {{{{#include {m.group(1)}}}}}: no such file")
        line = INLINE_CODE.sub("", line)
        for target in LINK.findall(line) + HTML_ATTR.findall(line):
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("//"):
                continue  # http:, https:, mailto: …
            file, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(base, file)) if file else path
            if not os.path.exists(dest):
                problems.append(f"{rel}:{n}: link {target}: no such file {os.path.relpath(dest, ROOT)}")
                continue
            if anchor and dest.endswith(".md") and anchor not in anchors(dest):
                problems.append(f"{rel}:{n}: link {target}: no heading #{anchor} in {os.path.relpath(dest, ROOT)}")


def main():
    problems = []
    pages = sorted(f for f in os.listdir(DOCS) if f.endswith(".md"))
    summary = COMMENT.sub("", open(os.path.join(DOCS, "SUMMARY.md"), encoding="utf-8").read())
    listed = {os.path.normpath(t.partition("#")[0]) for t in LINK.findall(summary)}
    for p in pages:
        if p != "SUMMARY.md" and p not in listed:
            problems.append(f"docs/{p}: not in docs/SUMMARY.md (add it where it belongs in the book)")
    for p in ["README.md"] + [os.path.join("docs", f) for f in pages]:
        check_links(os.path.join(ROOT, p), problems)
    for line in problems:
        print(line)
    if problems:
        print(f"check-docs: {len(problems)} problem(s)")
        return 1
    print(f"check-docs: {len(pages)} pages in docs/, all in SUMMARY.md; every relative link and anchor resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
