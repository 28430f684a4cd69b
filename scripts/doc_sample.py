#!/usr/bin/env python3
"""Samples public numerical routines of core and says which document their
method, accuracy and source (issue: docs that state method, accuracy and source).

A routine is a `pub fn` of core/src (not in a test module, not in the
non-numerical modules `named.rs` and `validation.rs`) whose body spans at
least 12 lines. Its documentation is the `///` block above it plus, for
methods, nothing else: the routine's own doc must state
- a method (what is computed and how: `**Method**`, "by", "algorithm", a formula),
- its accuracy (`**Accuracy**`, `**Error**`, "error", "bound", "exact", "rounding",
  "ulp", "stable"),
- its source (`seed`, `eq`, a paper or book: "et al", a year, "Higham",
  "scipy", "Unser", "Farouki", "de Boor", ...).
The check is by keywords, so it is a reviewer's aid, not a proof: read the
sampled docs it prints.

Usage: scripts/doc_sample.py [--seed N] [--count K] [--all]
"""
import argparse
import pathlib
import random
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent / "core" / "src"
METHOD = re.compile(r"\*\*Method\*\*|\bby\b|algorithm|recursion|formula|`[^`]*[=Σ∑][^`]*`|computes|evaluates|solves", re.I)
ACCURACY = re.compile(r"\*\*Accuracy\*\*|\*\*Error\*\*|error|bound|exact|rounding|ulp|stable|γ_|within", re.I)
SOURCE = re.compile(r"seed 00\d|\beq\b|\beqs?\s*\d|Higham|scipy|Unser|Thévenaz|Farouki|de Boor|Boehm|Marco|Volk|Golub|Ogita|Rump|Kahan|Piegl|Kuriyama|Takayama|Maeno|Honda|Miura|\(\d{4}\)|\b(19|20)\d\d\b|paper", re.I)


# Modules of no numerical content: string and argument handling.
NOT_NUMERICAL = {"named.rs", "validation.rs"}


def routines():
    for path in sorted(ROOT.rglob("*.rs")):
        if path.name in NOT_NUMERICAL:
            continue
        lines = path.read_text().split("\n")
        in_tests = False
        for i, line in enumerate(lines):
            if re.match(r"\s*#\[cfg\(test\)\]", line):
                in_tests = True
            if in_tests:
                continue
            m = re.match(r"\s*pub fn (\w+)", line)
            if not m:
                continue
            length = body_length(lines, i)
            if length < 12:
                continue
            doc = doc_block(lines, i)
            yield f"{path.relative_to(ROOT.parent.parent)}:{i + 1}", m.group(1), length, doc


def body_length(lines, start):
    depth, seen = 0, False
    for j in range(start, len(lines)):
        code = re.sub(r"//.*", "", lines[j])
        depth += code.count("{") - code.count("}")
        seen |= "{" in code
        if seen and depth <= 0:
            return j - start + 1
        if not seen and code.rstrip().endswith(";"):
            return 0
    return 0


def doc_block(lines, i):
    doc = []
    j = i - 1
    while j >= 0 and (lines[j].strip().startswith("///") or lines[j].strip().startswith("#[")):
        if lines[j].strip().startswith("///"):
            doc.append(lines[j].strip()[3:])
        j -= 1
    text = "\n".join(reversed(doc))
    # doc examples do not count as statements of method/accuracy/source
    return re.sub(r"```.*?```", "", text, flags=re.S)


def verdict(doc):
    return bool(METHOD.search(doc)), bool(ACCURACY.search(doc)), bool(SOURCE.search(doc))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=25)
    ap.add_argument("--count", type=int, default=12)
    ap.add_argument("--all", action="store_true", help="list every routine and its verdict")
    a = ap.parse_args()
    every = list(routines())
    chosen = every if a.all else random.Random(a.seed).sample(every, min(a.count, len(every)))
    ok = 0
    for where, name, length, doc in chosen:
        m, acc, src = verdict(doc)
        ok += m and acc and src
        flags = "".join(c if f else "-" for c, f in zip("MAS", (m, acc, src)))
        print(f"{flags}  {name:32} {length:4} lines  {where}")
    print(f"{ok} of {len(chosen)} state method, accuracy and source ({len(every)} routines of >= 12 lines)")


if __name__ == "__main__":
    main()
