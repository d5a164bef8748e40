"""Verification IP figures: ``python bench/vip_figures.py [--core]``.

``--core``: the cost of one ``HostCore.step`` while bursts run, the host
engine alone: 256-dword memory reads and writes against lines that show a
target claiming at once and completing every data phase (TRDY# and DEVSEL#
asserted), so that every edge does a data phase's work.  Prints edges per
second and microseconds per edge.
"""
import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from sim.pci_host_core import MEM_READ, MEM_WRITE, HostCore, Request  # noqa: E402

BURST = 256


def core_speed(bursts=400):
    """(edges, seconds) of ``bursts`` alternating 256-dword writes and reads."""
    core = HostCore()
    drive = core.drive
    edges = 0
    start = time.perf_counter()
    for number in range(bursts):
        command = MEM_WRITE if number % 2 else MEM_READ
        request = core.submit(Request(command, 0x1000, [(0xF, number)] * BURST))
        while not request.done:
            edges += 1
            frame = drive.frame_out if drive.frame_oe else 1
            irdy = drive.irdy_out if drive.irdy_oe else 1
            core.step(30 * edges, 0x5A5A5A5A, 0, frame, irdy, 0, 0, 1)
    return edges, time.perf_counter() - start


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python bench/vip_figures.py",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--core", action="store_true", help="host engine cost per edge")
    parser.parse_args(argv)
    edges, seconds = core_speed()
    print(f"HostCore.step during {BURST}-dword bursts: {edges / seconds:,.0f} edges/s, "
          f"{1e6 * seconds / edges:.2f} us per edge ({edges:,} edges)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
