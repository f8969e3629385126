"""Runs PyPI's pygcode over one G-code file and prints the number of motion blocks, for
scripts/bench-peers.sh. Usage: python3 pygcode_run.py FILE (PYTHONPATH must find pygcode)."""
import json
import sys

from pygcode import Line, Machine
from pygcode.exceptions import MachineInvalidState

machine = Machine()
moves = 0
errors = 0
with open(sys.argv[1], encoding="utf-8", errors="replace") as source:
    for text in source:
        try:
            block = Line(text).block
            before = machine.pos
            machine.process_block(block)
            if machine.pos != before:
                moves += 1
        except (MachineInvalidState, Exception):  # pygcode rejects what it cannot read
            errors += 1
print(json.dumps({"moves": moves, "errors": errors}))
