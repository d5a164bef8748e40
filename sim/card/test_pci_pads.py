"""``rtl/pci/pci_pads.py``: both pad builds give the bus the same timing, clock for clock.

A stand-in core registers every input and drives every output from a
flip-flop, as the PCI target does.  With ``io_registers=False`` those are its
own flip-flops behind plain buffers; with ``io_registers=True`` the core hands
the pads the flip-flops' D values and takes the pads' input registers.  The
same seeded random traffic runs through both; the lines and what each core
samples must match on every clock.  The expected values come from the
stimulus itself (what was driven one clock earlier), not from the pads.
"""
import random
import re

import pytest
from myhdl import Signal, StopSimulation, always, always_seq, block, instance, intbv

from rtl.convert import convert_block
from rtl.interfaces import PciBus, PciPins, card_reset
from rtl.pci.pci_pads import pci_pads, pci_pads_ports
from sim.backends.clocking import clock_source

CLOCKS = 200


@block
def stand_in_core(clock, reset, pci, drive_value, drive_enable, sampled, *, io_registers):
    """Outputs ``drive_value`` (AD, TRDY#) from a flip-flop, samples AD and C/BE#."""
    ad_q = Signal(intbv(0)[32:])
    trdy_q = Signal(bool(1))

    @always_seq(clock.posedge, reset=reset)
    def output_flops():
        ad_q.next = drive_value
        trdy_q.next = drive_value[0]
        pci.ad_oe.next = drive_enable
        pci.trdy_oe.next = drive_enable
        pci.serr_oe.next = drive_enable

    @always(drive_value, ad_q, trdy_q)
    def outputs():
        pci.ad_out.next = drive_value if io_registers else ad_q
        pci.trdy_out.next = drive_value[0] if io_registers else trdy_q
        pci.serr_out.next = 0

    if io_registers:
        @always(pci.ad_in, pci.cbe_in)
        def inputs():
            sampled["ad"].next = pci.ad_in
            sampled["cbe"].next = pci.cbe_in
    else:
        @always_seq(clock.posedge, reset=reset)
        def inputs():
            sampled["ad"].next = pci.ad_in
            sampled["cbe"].next = pci.cbe_in

    return output_flops, outputs, inputs


def make_stimulus(seed):
    """Per clock: (target drives, target value, host AD or None, C/BE#, FRAME# or None).

    The host leaves AD alone whenever the target's enable of this clock or
    the one before is set, so the two never drive AD at once.
    """
    rng = random.Random(seed)
    stimulus, target_before = [], False
    for _ in range(CLOCKS):
        target = rng.random() < 0.5
        host = None if target or target_before or rng.random() < 0.2 else rng.getrandbits(32)
        frame = None if rng.random() < 0.3 else rng.getrandbits(1)
        stimulus.append((target, rng.getrandbits(32), host, rng.getrandbits(4), frame))
        target_before = target
    return stimulus


@block
def pads_bench(log, stimulus):
    """Both pad builds with their stand-in cores, one clock, one stimulus."""
    clock, reset = Signal(bool(0)), card_reset()
    drive_value = Signal(intbv(0)[32:])
    drive_enable = Signal(bool(0))
    host_drivers = []  # the master's drivers of AD, C/BE#, FRAME# on each ring
    rings = {}
    blocks = []
    for io_registers in (False, True):
        pins, bus = PciPins(), PciBus()
        sampled = {"ad": Signal(intbv(0)[32:]), "cbe": Signal(intbv(0)[4:])}
        rings[io_registers] = (pins, bus, sampled)
        blocks += [pci_pads(clock, pins, bus, io_registers=io_registers),
                   stand_in_core(clock, reset, bus, drive_value, drive_enable, sampled,
                                 io_registers=io_registers)]
        host_drivers.append((pins.ad.driver(), pins.cbe.driver(), pins.frame.driver()))

    tick = clock_source(clock, 2 * 15)

    @instance
    def apply():
        reset.next = 0
        yield clock.negedge
        reset.next = 1
        for target, value, host, cbe, frame in stimulus:
            yield clock.negedge
            _record(log, rings)
            drive_enable.next = target
            drive_value.next = value
            for ad, cbe_lines, frame_line in host_drivers:
                ad.next = host
                cbe_lines.next = cbe
                frame_line.next = frame
        raise StopSimulation

    return tick, apply, blocks


def _record(log, rings):
    for io_registers, (pins, bus, sampled) in rings.items():
        lines = tuple(None if pin.val is None else int(pin.val) for pin in (pins.ad, pins.trdy, pins.serr))
        log[io_registers].append(lines + (int(sampled["ad"]), int(sampled["cbe"]), int(bus.frame_in)))


def _run(stimulus):
    log = {False: [], True: []}
    bench = pads_bench(log, stimulus)
    try:
        bench.run_sim()
    finally:
        bench.quit_sim()
    return log


@pytest.mark.parametrize("seed", [1, 2])
def test_both_builds_show_the_same_bus_every_clock(seed):
    log = _run(make_stimulus(seed))
    assert len(log[False]) == CLOCKS
    # From the second clock on: the I/O-cell registers have no reset, the core's do.
    for clock_index in range(2, CLOCKS):
        plain, registered = log[False][clock_index], log[True][clock_index]
        assert plain == registered, f"clock {clock_index}: plain {plain} != registered {registered}"


def test_lines_follow_the_stimulus():
    """Independent of the pads: what each line and sample must be, from the stimulus alone.

    Log entry i is taken at the falling edge before stimulus i is applied;
    the rising edge just before it registered stimulus i-1 in the core.
    """
    stimulus = make_stimulus(3)
    log = _run(stimulus)
    for registered in (False, True):
        for index in range(2, CLOCKS):
            ad, trdy, serr, sampled_ad, sampled_cbe, frame_in = log[registered][index]
            target, value, host, _, _ = stimulus[index - 1]
            if target:
                assert (ad, trdy, serr) == (value, value & 1, 0), f"clock {index}"
            else:
                assert (ad, trdy, serr) == (host, None, None), f"clock {index}"
            before, before_value, _, _, _ = stimulus[index - 2]
            line_ad = before_value if before else host
            assert sampled_ad == (line_ad or 0), f"clock {index}: AD sampled"
            assert sampled_cbe == stimulus[index - 1][3], f"clock {index}: C/BE# sampled"
            frame = stimulus[index - 1][4]
            assert frame_in == (1 if frame is None else frame), f"clock {index}: FRAME# (pull-up)"


PCI_LINES = {"ad": 32, "cbe": 4, "par": 1, "frame": 1, "irdy": 1, "idsel": 1, "trdy": 1, "devsel": 1,
             "stop": 1, "perr": 1, "serr": 1, "inta": 1}
TARGET_DRIVES = ("ad", "par", "trdy", "devsel", "stop", "perr", "serr", "inta")
TARGET_READS = ("ad", "cbe", "par", "frame", "irdy", "idsel")


def expected_ports(io_registers):
    """(direction, width) of every port of a build, from the PCI lines and
    ``rtl/pci/pci_pads.py``'s account of them: a pin the target drives is inout; a
    pin it only reads is an input, except that the registered build samples
    C/BE# and IDSEL in I/O cells, whose package pin is inout; the core's side
    is split into ``_in`` (from the pads), ``_out`` and ``_oe`` (to them)."""
    ports = {"clock": ("input", 1)}
    for line, width in PCI_LINES.items():
        in_io_cell = io_registers and line in ("cbe", "idsel")
        ports[f"pins_{line}"] = ("inout" if line in TARGET_DRIVES or in_io_cell else "input", width)
        if line in TARGET_READS:
            ports[f"pci_{line}_in"] = ("output", width)
        if line in TARGET_DRIVES:
            ports[f"pci_{line}_out"] = ("input", width)
            ports[f"pci_{line}_oe"] = ("input", 1)
    return ports


def converted_ports(io_registers, folder):
    """(direction, width) of every port of the converted build."""
    ports = pci_pads_ports(io_registers=io_registers)
    verilog = convert_block("pci_pads", pci_pads(**ports, io_registers=io_registers), folder).read_text()
    declared = re.findall(r"^\s*(input|output|inout)\s+(?:\[(\d+):0\]\s+)?(\w+);", verilog, re.M)
    return {name: (direction, int(msb) + 1 if msb else 1) for direction, msb, name in declared}


@pytest.mark.parametrize("io_registers", [False, True], ids=["plain", "registered"])
def test_each_build_has_the_ports_its_pads_need(io_registers, tmp_path):
    assert converted_ports(io_registers, tmp_path) == expected_ports(io_registers)


def test_both_builds_fit_the_same_top(tmp_path):
    """Same port names and widths: the top swaps one build for the other."""
    plain, registered = converted_ports(False, tmp_path / "plain"), converted_ports(True, tmp_path / "registered")
    assert {n: w for n, (_, w) in plain.items()} == {n: w for n, (_, w) in registered.items()}


SB_IO_BENCH = """\
`timescale 1ns/1ps
module tb;
  reg clock = 0;
  always #15 clock = ~clock;
  wire [31:0] pins_ad;
  wire [3:0] pins_cbe;
  wire pins_par, pins_frame, pins_irdy, pins_idsel, pins_trdy, pins_devsel, pins_stop, pins_perr,
       pins_serr, pins_inta;
  reg [31:0] host_ad = 0;
  reg host_ad_en = 0, host_frame = 1, host_idsel = 0;
  reg [3:0] host_cbe = 0;
  assign pins_ad = host_ad_en ? host_ad : 32'bz;
  assign pins_cbe = host_cbe;
  assign pins_frame = host_frame;
  assign pins_irdy = 1'b1;
  assign pins_idsel = host_idsel;
  reg [31:0] ad_out = 0;
  reg ad_oe = 0, trdy_out = 1, trdy_oe = 0, serr_oe = 0, par_out = 0, par_oe = 0;
  wire [31:0] ad_in;
  wire [3:0] cbe_in;
  wire par_in, frame_in, irdy_in, idsel_in;
  pci_pads dut(.clock(clock), .pins_ad(pins_ad), .pins_cbe(pins_cbe), .pins_par(pins_par),
    .pins_frame(pins_frame), .pins_irdy(pins_irdy), .pins_idsel(pins_idsel), .pins_trdy(pins_trdy),
    .pins_devsel(pins_devsel), .pins_stop(pins_stop), .pins_perr(pins_perr), .pins_serr(pins_serr),
    .pins_inta(pins_inta), .pci_ad_in(ad_in), .pci_ad_out(ad_out), .pci_ad_oe(ad_oe),
    .pci_cbe_in(cbe_in), .pci_par_in(par_in), .pci_par_out(par_out), .pci_par_oe(par_oe),
    .pci_frame_in(frame_in), .pci_irdy_in(irdy_in), .pci_idsel_in(idsel_in),
    .pci_trdy_out(trdy_out), .pci_trdy_oe(trdy_oe), .pci_devsel_out(1'b1), .pci_devsel_oe(1'b0),
    .pci_stop_out(1'b1), .pci_stop_oe(1'b0), .pci_perr_out(1'b1), .pci_perr_oe(1'b0),
    .pci_serr_out(1'b0), .pci_serr_oe(serr_oe), .pci_inta_out(1'b0), .pci_inta_oe(1'b0));
  task check(input ok, input [8*40-1:0] what);
    if (ok) $display("PASS %0s", what); else $display("FAIL %0s", what);
  endtask
  initial begin
    @(negedge clock);
    ad_out = 32'h12345678; ad_oe = 1; trdy_out = 0; trdy_oe = 1; #1;
    check(pins_ad !== 32'h12345678, "AD waits for the clock edge");
    @(negedge clock);
    check(pins_ad === 32'h12345678, "AD shows the value of the last edge");
    check(pins_trdy === 1'b0, "TRDY# shows the value of the last edge");
    ad_out = 32'h0; #1;
    check(pins_ad === 32'h12345678, "AD holds between edges");
    ad_oe = 0; trdy_oe = 0; #1;
    check(pins_ad === 32'bz, "AD released at once");
    check(pins_trdy === 1'bz, "TRDY# released at once");
    host_ad = 32'hCAFEF00D; host_ad_en = 1; host_cbe = 4'h6; host_frame = 0; host_idsel = 1; #1;
    check(ad_in !== 32'hCAFEF00D, "AD input waits for the clock edge");
    check(idsel_in !== 1'b1, "IDSEL waits for the clock edge");
    check(cbe_in !== 4'h6, "C/BE# waits for the clock edge");
    check(frame_in === 1'b0, "FRAME# passes straight through");
    @(negedge clock);
    check(ad_in === 32'hCAFEF00D, "AD input registered at the edge");
    check(idsel_in === 1'b1, "IDSEL registered at the edge");
    check(cbe_in === 4'h6, "C/BE# registered at the edge");
    par_out = 1; par_oe = 1; #1;
    check(pins_par === 1'b1, "PAR follows the core at once");
    par_oe = 0; #1;
    check(pins_par === 1'bz, "PAR released at once");
    serr_oe = 1; #1;
    check(pins_serr === 1'b0, "SERR# pulled low at once");
    serr_oe = 0; #1;
    check(pins_serr === 1'bz, "SERR# released at once");
    $finish;
  end
endmodule
"""


@pytest.mark.synth
def test_registered_pads_match_the_ice40_cell_model(tmp_path):
    """The converted SB_IO pads against yosys's own SB_IO simulation model, in Icarus."""
    import shutil
    import subprocess

    from rtl.convert import convert_unit
    from sim.card.top_harness import ICE40_DEFINES, ice40_cell_model

    source = convert_unit("pci_pads", {"io_registers": True}, tmp_path)
    (tmp_path / "tb.v").write_text(SB_IO_BENCH)
    defines = [f"-D{name}" for name in ICE40_DEFINES]
    compiled = subprocess.run([shutil.which("iverilog"), "-g2012", *defines, "-s", "tb",
                               "-o", str(tmp_path / "tb.vvp"), str(tmp_path / "tb.v"), str(source),
                               str(ice40_cell_model())],
                              capture_output=True, text=True, timeout=300)
    assert compiled.returncode == 0, compiled.stderr
    run = subprocess.run(["vvp", "-n", str(tmp_path / "tb.vvp")], capture_output=True, text=True, timeout=300)
    results = [line for line in run.stdout.splitlines() if line.startswith(("PASS", "FAIL"))]
    assert len(results) == 17 and all(line.startswith("PASS") for line in results), run.stdout
