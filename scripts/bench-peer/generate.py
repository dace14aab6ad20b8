#!/usr/bin/env python3
"""Writes the seven benchmark programs of issue 20 into a folder.

Deterministic: every coordinate is a fixed formula of the line index (no
randomness), so two runs write byte-identical files. Every program is
accepted by both gcodec and the peer (nc-gcode-interpreter 0.2.8): R
parameters need no DEF in either, labels and `GOTOB` are read by both,
and axis values are plain numbers or `=R1`.

Usage: generate.py DIR
"""

import sys
from pathlib import Path

MILLION = 1_000_000


def xy(i: int) -> str:
    # Three digits before the point and three after: 27 bytes a line, as
    # the 27 MB million-line program.
    x = 100 + (i * 37 % 100_000) / 1000
    y = 200 + (i * 53 % 100_000) / 1000
    return f"X{x:.3f} Y{y:.3f}"


def z(i: int) -> str:
    return f"Z{10 + (i * 11 % 10_000) / 1000:.3f}"


def flood(n: int) -> str:
    return "".join(f"G1 {xy(i)} F1000\n" for i in range(n))


def numbered(n: int) -> str:
    return "".join(f"N{10 * (i + 1)} G1 {xy(i)} {z(i)} F1000\n" for i in range(n))


def write(dir_: Path, name: str, text: str) -> None:
    (dir_ / name).write_text(text, encoding="ascii")


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: generate.py DIR", file=sys.stderr)
        return 2
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    write(out, "flood_200k.mpf", flood(200_000) + "M30\n")
    write(out, "flood_1m.mpf", flood(MILLION) + "M30\n")
    body = numbered(MILLION)
    write(out, "numbered_1m.mpf", body + "M30\n")
    # One conditional block in front of the numbered program: a forward
    # jump that is never taken (R1 is 0), so both sides run every line.
    write(out, "if_1m.mpf", "R1=0\nIF R1>0 GOTOF DONE\n" + body + "DONE:\nM30\n")
    # The loops count in R1; the motion follows the counter so that every
    # pass moves.
    write(
        out,
        "while_1m.mpf",
        "R1=0\nG1 F1000\nWHILE R1<1000000\nG1 X=R1 Y=R1*0.5\nR1=R1+1\nENDWHILE\nM30\n",
    )
    write(
        out,
        "while_nomotion_1m.mpf",
        "R1=0\nR2=0\nWHILE R1<1000000\nR2=R2+R1*0.5\nR1=R1+1\nENDWHILE\nM30\n",
    )
    write(
        out,
        "gotob_1m.mpf",
        "R1=0\nG1 F1000\nPASS:\nG1 X=R1 Y=R1*0.5\nR1=R1+1\nIF R1<1000000 GOTOB PASS\nM30\n",
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
