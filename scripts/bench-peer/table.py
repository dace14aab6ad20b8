#!/usr/bin/env python3
"""Prints run.sh's measurements as markdown tables.

Usage: table.py RESULTS.tsv EXAMPLES.tsv KEPT_COUNT EXCLUDED.tsv
  RESULTS.tsv   program, side, round, wall seconds, peak RSS KB, exit status
  EXAMPLES.tsv  side, round, total wall seconds of all kept examples
  EXCLUDED.tsv  example file name, reason
Wall times are medians over the rounds, peak RSS the largest of the rounds.
"""

import csv
import sys
from collections import defaultdict
from statistics import median

PROGRAMS = {
    "flood_200k": "200,000 lines `G1 X Y F`",
    "flood_1m": "1,000,000 lines `G1 X Y F`",
    "numbered_1m": "the same with block numbers and Z",
    "if_1m": "the same with one `IF` in front",
    "while_1m": "`WHILE` of 1,000,000 passes with a motion each",
    "while_nomotion_1m": "the same loop without motion",
    "gotob_1m": "`GOTOB` loop of 1,000,000 passes",
}
SIDES = ("peer", "gcodec_jsonl", "gcodec_csv")


def rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f, delimiter="\t"))


def mb(kb):
    return f"{kb / 1024:.0f} MB" if kb >= 1024 * 10 else f"{kb / 1024:.1f} MB"


def ratio(peer, ours):
    return f"{peer / ours:.1f}×" if ours > 0 else "n/a"


def main():
    results, examples, kept, excluded = sys.argv[1:5]
    wall = defaultdict(list)
    rss = defaultdict(int)
    failed = set()
    for program, side, _round, seconds, kb, status in rows(results):
        wall[program, side].append(float(seconds))
        rss[program, side] = max(rss[program, side], int(kb))
        if status != "0":
            failed.add((program, side))

    print(
        "| program | peer wall | gcodec JSONL wall | gcodec CSV wall "
        "| peer / gcodec JSONL | peer / gcodec CSV "
        "| peer peak | gcodec JSONL peak | gcodec CSV peak |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for program, title in PROGRAMS.items():
        if not wall[program, "peer"]:
            continue
        med = {side: median(wall[program, side]) for side in SIDES}
        cells = [
            f"{med[side]:.3f} s" + (" (failed)" if (program, side) in failed else "")
            for side in SIDES
        ]
        print(
            f"| {title} | {' | '.join(cells)} "
            f"| {ratio(med['peer'], med['gcodec_jsonl'])} "
            f"| {ratio(med['peer'], med['gcodec_csv'])} "
            f"| {' | '.join(mb(rss[program, side]) for side in SIDES)} |"
        )

    totals = defaultdict(list)
    for side, _round, seconds in rows(examples):
        totals[side].append(float(seconds))
    if totals:
        peer = median(totals["peer"])
        ours = median(totals["gcodec_jsonl"])
        print(
            f"| the peer's {kept} example programs both accept, one process each "
            f"(total) | {peer:.3f} s | {ours:.3f} s | | {ratio(peer, ours)} | | | | |"
        )

    left_out = rows(excluded)
    if left_out:
        print()
        print("Example programs left out (not accepted by both, exit status ≠ 0):")
        print()
        for name, reason in left_out:
            print(f"- `{name}`: {reason}")


if __name__ == "__main__":
    main()
