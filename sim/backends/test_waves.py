"""The waveforms a user opens: file names, GTKWave's names, windows and markers.

Every kind of view the benches write (PCI, PCI on the generated Verilog, the
card end to end, the card core's motion, the DDA, a bench's default view) is
made by a short bench here.  The fast test reads each save file and its VCD
with its own parser and GTKWave's naming rule as observed in GTKWave 3.3
(written out below); the GTKWave test loads each save file in GTKWave under
Xvfb and fails when GTKWave shows fewer signals than the file lists (GTKWave
drops a name it cannot find without a word), knows a variable under another
name than the rule's, or opens on another window or marker.
"""
import math
import os
import re
import shutil
import signal
import subprocess
from pathlib import Path

import pytest
from myhdl import Signal, StopSimulation, always_seq, block, instance, intbv

from models import instructions as isa
from models import registers as regmap
from models.dda_model import ArcCommand, LineCommand
from models.parameters import Build
from rtl.card import card, card_ports
from rtl.dda_arc import dda_arc_ports
from rtl.interfaces import card_reset
from sim.backends import waves
from sim.backends.clocking import clock_source
from sim.card.card_bench import PinLog, pin_capture, run_core, wait_idle, write_motion_view
from sim.card.dda_bench import Record, dda_bench, write_view
from sim.pci.bench import WAVE_GROUPS, PciBench

LINE = LineCommand(9, -4)


# ----- GTKWave's names -------------------------------------------------------------
# (kind, size, reference, range written after it) -> the name GTKWave 3.3.118 lists
OBSERVED_NAMES = [
    ("reg", 1, "s", None, "s"),
    ("reg", 8, "v", None, "v[7:0]"),
    ("wire", 8, "w", None, "w[7:0]"),
    ("reg", 32, "storage(3)", None, "storage(3)[31:0]"),
    ("integer", 32, "i", None, "i"),
    ("parameter", 8, "p", None, "p"),
    ("real", 64, "r", None, "r"),
    ("string", 4, "state", None, "state"),
    ("event", 1, "e", None, "e"),
    ("reg", 8, "rr", (7, 0), "rr[7:0]"),
    ("reg", 4, "lo", (4, 1), "lo[4:1]"),
    ("reg", 1, "one", (0, 0), "one[0]"),
    ("wire", 1, "b", 3, "b[3]"),
]
HANDWRITTEN_VCD = "\n".join(
    ["$timescale 1ns $end", "$scope module top $end"]
    + [f"$var {kind} {size} {chr(33 + n)} {ref}"
       + ("" if index is None else f" [{index}]" if isinstance(index, int) else f" [{index[0]}:{index[1]}]")
       + " $end" for n, (kind, size, ref, index, _) in enumerate(OBSERVED_NAMES)]
    + ["$upscope $end", "$enddefinitions $end", "#0", "#10", ""])


@pytest.mark.parametrize("kind, size, reference, bit_index, name", OBSERVED_NAMES)
def test_gtkwave_naming_rule(kind, size, reference, bit_index, name):
    assert waves.gtkwave_name(kind, size, reference, bit_index) == name


def test_declarations_read_every_variable(tmp_path):
    vcd = tmp_path / "kinds.vcd"
    vcd.write_text(HANDWRITTEN_VCD)
    assert [v.gtkwave_name for v in waves.declarations(vcd)] == [f"top.{n[-1]}" for n in OBSERVED_NAMES]


# ----- the views -------------------------------------------------------------------
def pci_view(target):
    def scenario(bench):
        yield from bench.host.config_write(0, 0x10, 0x1000)
        yield from bench.host.config_write(0, 0x04, 0x1, be=0x3)
        yield from bench.host.io_write(0x1000, 0xCAFE0123)
        yield from bench.host.io_read(0x1000)

    return PciBench(target=target).run(scenario, f"view_pci_{target}", trace=True)


def card_view():
    log = PinLog()

    def target(bench):
        ports = card_ports()
        ports["clock"], ports["reset"] = bench.clock, bench.reset
        return ports["pci"], [(card, (), dict(ports, build=Build(fifo_depth=16))),
                              (pin_capture, (bench.clock, ports["pins"], log))]

    def scenario(bench):
        device = (yield from bench.host.enumerate_bus(devices=[0]))[0]
        bars = {"io": device.bar(0)["base"], "mem": device.bar(1)["base"]}
        yield from bench.host.io_write(bars["io"] + regmap.offset("FEED_RATE"), regmap.RATE_MAX)
        yield from bench.host.io_write(bars["io"] + regmap.offset("CONTROL"), 1)
        yield from bench.host.mem_write(bars["mem"], isa.encode("LINE", LINE.dx, LINE.dy))
        yield from bench.clocks(80)

    vcd = PciBench(target=target).run(scenario, "view_card", trace=True)
    assert log.rises, "the card made no step"
    write_motion_view(vcd, WAVE_GROUPS)
    return vcd


def core_view():
    def scenario(driver):
        yield from driver.io_write(regmap.offset("FEED_RATE"), regmap.RATE_MAX)
        yield from driver.io_write(regmap.offset("CONTROL"), 1)
        yield from driver.push_all(isa.encode("LINE", LINE.dx, LINE.dy))
        yield from wait_idle(driver)

    _, wave = run_core("view_core", scenario, trace=True)
    return wave.path


def dda_view():
    ports = dda_arc_ports()
    vcd = waves.run_traced(dda_bench(ports, [ArcCommand(12, 0, 0, 12), LINE], Record(), advance_rate=0.9),
                           "view_dda", trace=True)
    write_view(vcd)
    return vcd


@block
def counter_bench(clock, count):
    reset = card_reset()
    ticking = clock_source(clock, 10)

    @always_seq(clock.posedge, reset=reset)
    def counting():
        count.next = count + 1

    @instance
    def stop():
        for _ in range(20):
            yield clock.posedge
        raise StopSimulation

    return ticking, counting, stop


def default_view():
    return waves.run_traced(counter_bench(Signal(bool(0)), Signal(intbv(0)[6:])), "view_default", trace=True)


VIEWS = {
    "pci": lambda: pci_view("myhdl"),
    "pci_verilog": lambda: pci_view("verilog"),
    "card": card_view,
    "core": core_view,
    "dda": dda_view,
    "default": default_view,
}
_made = {}


def made(view):
    """The VCD of ``view``, made once per process (the two tests below read the same run)."""
    if view not in _made:
        _made[view] = VIEWS[view]()
    return _made[view]
# names each view must show (the end of the GTKWave name, instance numbers left out),
# beyond "every name is found"
MUST_SHOW = {
    "pci": ["bus_ad_view[31:0]", "bus_cbe[3:0]", "local_addr[11:0]", "local_wdata[31:0]", ".state"],
    "pci_verilog": ["bus_ad_view[31:0]", "bus_cbe[3:0]", "local_rdata[31:0]"],
    "card": ["bus_ad_view[31:0]", "bus_cbe[3:0]", "pins_step_x", "pins_dir_x", "pins_step_y", "pins_dir_y",
             "axis_x.position[31:0]", "axis_y.position[31:0]", "sequencer.opcode[3:0]", "sequencer.header[16:0]"],
    "core": ["local_addr[15:0]", "pins_step_x", "pins_dir_y", "axis_x.position[31:0]", "sequencer.state",
             "sequencer.operand_0[31:0]", "feed_rate.rate[15:0]"],
    "dda": ["cmd_xs[23:0]", "cmd_ye[23:0]", "dda_setup.state", "step_mag_x[23:0]", "step_mag_y[23:0]",
            "acc_x[29:0]", "error_term[26:0]", "steps_step_x"],
    "default": ["clock", "count[5:0]"],
}
VAR = re.compile(r"^\s*\$var\s+(\S+)\s+(\d+)\s+\S+\s+(\S+)(?:\s+\[(-?\d+)(?::(-?\d+))?\])?\s+\$end", re.M)


def vcd_names(vcd):
    """GTKWave's names of every variable, from the VCD text (its own parser)."""
    text = Path(vcd).read_text().split("$enddefinitions", 1)[0]
    names, scope = set(), []
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["$scope"]:
            scope.append(words[2])
        elif words[:1] == ["$upscope"]:
            scope.pop()
        elif words[:1] == ["$var"]:
            kind, size, reference, msb, lsb = VAR.match(line).groups()
            if msb is not None:
                suffix = f"[{msb}]" if lsb is None or lsb == msb else f"[{msb}:{lsb}]"
            elif kind in ("integer", "parameter", "real", "realtime", "string", "event") or size == "1":
                suffix = ""
            else:
                suffix = f"[{int(size) - 1}:0]"
            names.add(".".join(scope + [reference + suffix]))
    return names


def save_file_settings(gtkw):
    text = Path(gtkw).read_text()
    dumpfile = re.search(r'^\[dumpfile\] "(.*)"$', text, re.M).group(1)
    start = int(re.search(r"^\[timestart\] (\d+)$", text, re.M).group(1))
    zoom, marker = re.search(r"^\*(-?[\d.]+) (-?\d+)", text, re.M).groups()
    traces = [line for line in text.splitlines() if line and line[0] not in "[*@-^#!"]
    return Path(dumpfile), start, float(zoom), int(marker), traces


def last_time(vcd):
    return max(int(t) for t in re.findall(r"^#(\d+)", Path(vcd).read_text(), re.M))


@pytest.mark.parametrize("view", sorted(VIEWS))
def test_save_file_names_signals_of_its_vcd(view):
    vcd = made(view)
    gtkw = vcd.with_name(vcd.name[:-len(".vcd")] + ".gtkw")
    dumpfile, start, zoom, marker, traces = save_file_settings(gtkw)
    assert dumpfile == vcd.resolve()
    known = vcd_names(vcd)
    unknown = [t for t in traces if t not in known]
    assert traces and not unknown, f"not in the VCD under GTKWave's names: {unknown}"
    plain = [re.sub(r"(?<=[a-z])\d+(_\d+)*\.", ".", t) for t in traces]
    for wanted in MUST_SHOW[view]:
        assert any(t.endswith(wanted) for t in plain), f"{wanted} missing from the {view} view"
    # the whole run in view, and not much more
    shown = 2 ** -zoom * (waves.WINDOW_SIZE[0] - waves.SIGNALS_WIDTH - waves.WAVE_MARGIN) / 200
    assert start == 0 and last_time(vcd) <= shown <= 1.1 * last_time(vcd)
    if view in ("card", "core"):  # the marker on the first STEP pulse
        wave = waves.Waveform(vcd)
        rises = [t for pin in ("pins_step_x", "pins_step_y") for t in wave.edges(pin, "1")]
        assert rises and marker == min(rises)
    if view == "dda":  # the marker on the first command
        assert marker == waves.Waveform(vcd).edges("cmd_start", "1")[0]


def test_a_bare_vector_name_is_caught(tmp_path):
    vcd = default_view()
    gtkw = vcd.with_name(vcd.name[:-len(".vcd")] + ".gtkw")
    assert waves.missing_traces(gtkw) == []
    bare = gtkw.read_text().replace("count[5:0]", "count")
    broken = tmp_path / "bare.gtkw"
    broken.write_text(bare)
    assert waves.missing_traces(broken) == ["view_default.count"]
    with pytest.raises(KeyError, match="no_such_signal"):
        waves.write_gtkw(vcd, {"g": ["clock", "no_such_signal"]})


def test_files_are_named_after_the_test():
    first, second = default_view(), default_view()
    folder = waves.waves_dir() / "sim" / "backends" / "test_waves"
    assert first == folder / "test_files_are_named_after_the_test.vcd"
    assert second == folder / "test_files_are_named_after_the_test.2.vcd"
    assert second.with_name("test_files_are_named_after_the_test.2.gtkw").exists()


@pytest.mark.parametrize("label", ["14 PERR# missing"])
def test_unsafe_characters_become_underscores(label):
    vcd = default_view()
    assert vcd.name == "test_unsafe_characters_become_underscores[14_PERR__missing].vcd"


# ----- in GTKWave ------------------------------------------------------------------
GTKWAVE = shutil.which("gtkwave") and shutil.which("xvfb-run")
TCL = """\
set out [open {%(report)s} w]
if {[catch {
    puts $out "window [gtkwave::getWindowStartTime] [gtkwave::getWindowEndTime]"
    puts $out "marker [gtkwave::getMarker]"
    for {set i 0} {$i < [gtkwave::getNumFacs]} {incr i} { puts $out "fac [gtkwave::getFacName $i]" }
    foreach name [gtkwave::getDisplayedSignals] { puts $out "shown $name" }
    foreach name {%(probes)s} {
        puts $out "value $name\t[gtkwave::getTraceValueAtMarkerFromName $name]"
    }
} message]} {
    puts $out "error $message"
}
close $out
gtkwave::/File/Quit
"""


def gtkwave_report(files, tmp_path, probes=()):
    """What GTKWave shows for ``files`` (a save file, or a VCD alone): window,
    marker, facilities, displayed traces and the value of each probe at the
    marker.  A script error is reported, and GTKWave always quits."""
    report, script, rc = tmp_path / "report.txt", tmp_path / "report.tcl", tmp_path / "empty.rc"
    rc.write_text("")  # GTKWave's defaults, whatever the user's ~/.gtkwaverc says
    script.write_text(TCL % dict(report=report, probes=" ".join(f"{{{name}}}" for name in probes)))
    run = subprocess.Popen(["xvfb-run", "-a", "gtkwave", "-r", str(rc), "-S", str(script), *map(str, files)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           start_new_session=True)
    try:
        output = run.communicate(timeout=120)[0]
    except subprocess.TimeoutExpired:
        os.killpg(run.pid, signal.SIGKILL)  # xvfb-run, its Xvfb and GTKWave
        run.communicate()
        raise
    assert report.exists(), f"GTKWave did not run the script: {output}"
    result = {"fac": [], "shown": [], "value": {}}
    for line in report.read_text().splitlines():
        key, _, rest = line.partition(" ")
        assert key != "error", f"GTKWave script: {rest}"
        if key == "value":
            name, value = rest.split("\t")
            result["value"][name] = value
        elif key in ("fac", "shown"):
            result[key].append(rest)
        else:
            result[key] = [int(float(x)) for x in rest.split()]
    return result


@pytest.mark.skipif(not GTKWAVE, reason="needs gtkwave and xvfb-run (.ci/run installs them)")
def test_gtkwave_knows_the_variables_by_the_rule(tmp_path):
    vcd = tmp_path / "kinds.vcd"
    vcd.write_text(HANDWRITTEN_VCD)
    report = gtkwave_report([vcd], tmp_path)
    assert sorted(report["fac"]) == sorted(f"top.{n[-1]}" for n in OBSERVED_NAMES)


@pytest.mark.skipif(not GTKWAVE, reason="needs gtkwave and xvfb-run (.ci/run installs them)")
@pytest.mark.parametrize("view", sorted(VIEWS))
def test_gtkwave_shows_every_signal_of_the_save_file(view, tmp_path):
    vcd = made(view)
    gtkw = vcd.with_name(vcd.name[:-len(".vcd")] + ".gtkw")
    _, start, _, marker, traces = save_file_settings(gtkw)
    probes = [t for t in traces if re.search(r"(pins_step_x|sequencer\d+\.opcode\[3:0\])$", t)]
    report = gtkwave_report([gtkw], tmp_path, probes)
    assert sorted(report["fac"]) == sorted(v.gtkwave_name for v in waves.declarations(vcd))
    assert report["shown"] == traces, f"GTKWave did not find {sorted(set(traces) - set(report['shown']))}"
    window_start, window_end = report["window"]
    end = last_time(vcd)
    assert window_start == start and end <= window_end <= start + math.ceil(1.1 * end)
    assert report["marker"] == [marker]
    for name in probes:
        wanted = "1" if name.endswith("pins_step_x") or name.endswith("pins_step_y") else "LINE"
        assert report["value"][name] == wanted, name
