"""PCI target figures: ``python -m bench.pci_figures [--target verilog] [--no-synth]``.

Runs the standard bench (host, bus model, monitor, zero-latency back end, no
master wait states) and prints

* memory burst throughput for 1, 4, 16 and 64 dwords, writes and reads:
  bytes per clock and MB/s at 33 MHz, counting the clocks from the address
  phase to the last data phase (both included) and, in brackets, with the
  idle clock a following transaction needs after it;
* for configuration, I/O and memory reads and writes: the edges from the one
  that samples the address (FRAME# asserted) to the ones that sample DEVSEL#
  and the first TRDY#;
* the same on the whole card, whose I/O space is its function registers
  (``sim/card/register_latency.py``: ``gen/card.v`` and ``gen/top.v`` in
  Icarus, the MyHDL card);
* ``pci_slave`` alone on iCE40 HX8K (``fpgaflow``): logic cells, flip-flops
  and fmax (from ``gen/pci_slave.v``).
"""
import argparse
import sys

from fpgaflow import synthesize
from sim.card import register_latency
from sim.pci.bench import PciBench
from sim.pci.host import COMMAND_IO, COMMAND_MEMORY, MEM_READ, MEM_READ_MULTIPLE

PCI_MHZ = 33
IO_BASE, MEM_BASE = 0x1000, 0x80000000
BURSTS = (1, 4, 16, 64)
BYTES_PER_DWORD = 4


def measure(target):
    """Run the accesses; return (bursts, latencies) from the host's and the
    monitor's records."""
    results = {}

    def scenario(bench):
        host = bench.host
        yield from host.config_write(0, 0x10, IO_BASE)
        yield from host.config_write(0, 0x14, MEM_BASE)
        yield from host.config_write(0, 0x04, COMMAND_IO | COMMAND_MEMORY, be=0x3)
        for length in BURSTS:
            results[("write", length)] = yield from host.mem_write(MEM_BASE, list(range(length)))
            command = MEM_READ if length == 1 else MEM_READ_MULTIPLE
            results[("read", length)] = yield from host.mem_read(MEM_BASE, length, command=command)
        results["configuration read"] = yield from host.config_read(0, 0x00)
        results["configuration write"] = yield from host.config_write(0, 0x3C, 0x0B, be=0x1)
        results["I/O read"] = yield from host.io_read(IO_BASE)
        results["I/O write"] = yield from host.io_write(IO_BASE, 0x12345678)
        results["memory read"] = yield from host.mem_read(MEM_BASE)
        results["memory write"] = yield from host.mem_write(MEM_BASE, [0x9ABCDEF0])

    bench = PciBench(target=target)
    bench.run(scenario, f"pci_figures_{target}")
    records = {r.start: r for r in bench.checker.transactions}
    bursts = {}
    for key, result in results.items():
        if isinstance(key, tuple):
            (transaction,) = result.transactions
            if not result.complete or len(transaction.data) != key[1]:
                raise RuntimeError(f"{key} did not complete in one transaction")
            record = records[transaction.start]
            bursts[key] = record.end_edge - record.start_edge + 1
    latencies = {name: (r.transactions[0].devsel_clock, r.transactions[0].first_trdy_clock)
                 for name, r in results.items() if isinstance(name, str)}
    return bursts, latencies


def print_bursts(bursts):
    print("Memory bursts (zero wait states in the host and the back end):")
    print(f"  {'':11}{'dwords':>4}{'clocks':>8}{'bytes/clock':>14}{'MB/s @33MHz':>14}"
          f"{'% of 132':>10}")
    for (direction, length), clocks in sorted(bursts.items()):
        for label, count in (("", clocks), (" +idle", clocks + 1)):
            rate = BYTES_PER_DWORD * length / count
            print(f"  {direction + label:<11}{length:>4}{count:>8}{rate:>14.2f}"
                  f"{rate * PCI_MHZ:>14.1f}{100 * rate / BYTES_PER_DWORD:>9.1f}%")


def print_latencies(latencies):
    print("pci_slave, zero-latency back end: clocks from FRAME# asserted to DEVSEL# / first TRDY#"
          " asserted (= edges after the address edge at which they are sampled):")
    for name, (devsel, trdy) in latencies.items():
        print(f"  {name:<22} DEVSEL# {devsel}   TRDY# {trdy}")


def print_card_latencies(kinds):
    print("The card: clocks after the address phase to DEVSEL# / first TRDY# "
          "(I/O: STATUS read, FEED_RATE written; memory: the FIFO window):")
    figures = {kind: register_latency.measure(kind) for kind in kinds}
    print(f"  {'':22}" + "".join(f"{kind:>12}" for kind in kinds))
    for access in register_latency.ACCESSES:
        print(f"  {access:<22}" + "".join(f"{'A+%d / A+%d' % figures[kind][access]:>12}" for kind in kinds))


def print_synthesis(freq):
    figures = synthesize("pci_slave", freq=freq)
    print(f"pci_slave alone on iCE40 HX8K (placed for {freq:g} MHz): "
          f"{figures['lcs']} logic cells, {figures['fabric_ffs']} flip-flops in fabric "
          f"+ {figures['io_ffs']} in I/O cells, fmax {figures['fmax_mhz']} MHz")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.pci_figures",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", choices=("myhdl", "verilog"), default="myhdl",
                        help="simulate the MyHDL design or gen/pci_slave.v (default: myhdl)")
    parser.add_argument("--no-synth", action="store_true", help="skip the iCE40 figures")
    parser.add_argument("--card", nargs="*", choices=register_latency.KINDS, default=list(register_latency.KINDS),
                        help="the card's builds whose access latency to measure (default: all; none: skip)")
    parser.add_argument("--synth-freq", type=float, default=100.0,
                        help="clock nextpnr places for, MHz (default: 100)")
    args = parser.parse_args(argv)
    bursts, latencies = measure(args.target)
    print_bursts(bursts)
    print_latencies(latencies)
    if args.card:
        print_card_latencies(args.card)
    if not args.no_synth:
        print_synthesis(args.synth_freq)
    return 0


if __name__ == "__main__":
    sys.exit(main())
