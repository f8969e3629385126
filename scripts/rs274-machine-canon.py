#!/usr/bin/env python3
"""Corrects standalone rs274's canonical output where its stand-in canon layer differs from a machine.

    rs274-machine-canon.py < rs274.canon > machine.canon

Standalone rs274 sends its canonical calls to a stand-in canon layer (saicanon) that records the
last commanded position but ignores tool length offsets. After a tool change the interpreter
re-reads its position from that record (Interp::synch). When the tool length offset changed since
the last move (G49, or a new G43, before M6), the position it reads is off by the change, and the
moves that keep Z after it inherit the error: `G28 G91 Z0` with H1, `G49`, `T2 M6`, `G0 X.. Y..`
traverses 12.98 mm below machine zero. On a machine, LinuxCNC's canon layer (emccanon) reports the
position with the current tool offset removed, so the tool stays where it is. This filter adds the
offset change back to the Z of those moves, until a move programs a Z of its own.
"""
import re
import sys

CALL = re.compile(r"([A-Z_0-9]+)\((.*)\)\s*$")
STRAIGHT = ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "STRAIGHT_PROBE")


def fix(lines):
    tlo = 0.0  # the tool length offset (Z) in effect
    tlo_moved = 0.0  # the offset in effect at the last move
    plane = "XY"
    resynced = False  # a tool change re-read the position since the offset changed
    stale = None  # (the Z the interpreter re-read, the Z the machine is at), as printed
    out = []
    for raw in lines:
        m = CALL.search(raw)
        if not m:
            out.append(raw)
            continue
        name, args = m.group(1), m.group(2)
        if name == "SELECT_PLANE":
            plane = "XY" if "XY" in args else ("XZ" if "XZ" in args else "YZ")
        elif name == "USE_TOOL_LENGTH_OFFSET":
            first = args.split(",")[0].split()
            try:
                tlo = float(first[2] if len(first) >= 3 else first[-1])
            except (ValueError, IndexError):
                pass
        elif name == "CHANGE_TOOL":
            resynced = abs(tlo - tlo_moved) > 1e-9
            stale = None
        elif name in STRAIGHT or (name == "ARC_FEED" and plane == "XY"):
            parts = [p.strip() for p in args.split(",")]
            k = 2 if name in STRAIGHT else 5
            if resynced:
                stale = (parts[k], f"{float(parts[k]) + tlo_moved - tlo:.4f}")
                resynced = False
            if stale is not None and parts[k] == stale[0]:
                parts[k] = stale[1]
                raw = raw[: m.start(2)] + ", ".join(parts) + raw[m.end(2) :]
            else:
                stale = None
            tlo_moved = tlo
        elif name == "ARC_FEED":
            resynced = False
            stale = None
            tlo_moved = tlo
        out.append(raw)
    return out


if __name__ == "__main__":
    sys.stdout.writelines(fix(sys.stdin.readlines()))
