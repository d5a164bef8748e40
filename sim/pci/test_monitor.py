"""The monitor itself: scripted agents play legal traffic (the monitor must
stay quiet) and then the same traffic broken in one place (the monitor must
name the rule that was broken)."""
import pytest
from myhdl import Signal, StopSimulation, block, instance

from rtl.interfaces import card_reset
from sim.backends.clocking import clock_source
from sim.backends.waves import run_traced
from sim.pci.bus import PciAgent, PciSegment, even_parity, pci_segment, scripted_agent
from sim.pci.monitor import ProtocolChecker, ProtocolViolation, pci_monitor

RESET_CLOCKS = 2
A, D, X = 0x1000, 0x12345678, 0xCAFEF00D
READ, WRITE, CONFIG_WRITE = 0x6, 0x7, 0xB


def par(ad, cbe):
    return even_parity(ad, cbe)


@block
def scripted_bench(clock, reset, segment, checker, master, target):
    """Two scripted agents after ``RESET_CLOCKS`` clocks of reset."""
    lines = segment.lines  # named before any instance so that the VCD shows them
    bus_frame, bus_irdy, bus_ad_view, bus_cbe, bus_par = (
        lines.frame, lines.irdy, lines.ad_view, lines.cbe, lines.par)
    bus_devsel, bus_trdy, bus_stop, bus_perr, bus_serr = (
        lines.devsel, lines.trdy, lines.stop, lines.perr, lines.serr)
    done_master, done_target = Signal(bool(0)), Signal(bool(0))
    players = [scripted_agent(clock, segment.agents["master"], master, done_master),
               scripted_agent(clock, segment.agents["target"], target, done_target)]
    bus = pci_segment(clock, segment)
    monitor = pci_monitor(clock, reset, segment, checker)

    clock_driver = clock_source(clock, 2 * 15)

    @instance
    def control():
        reset.next = reset.active
        for _ in range(RESET_CLOCKS):
            yield clock.posedge
        reset.next = not reset.active
        while not (done_master and done_target):
            yield clock.posedge
        raise StopSimulation()

    return players, bus, monitor, clock_driver, control


def play(master, target, name, during_reset=False, **checker_options):
    """Run the two scripts after the reset clocks (``during_reset``: from the
    first clock on); return the checker."""
    clock, reset = Signal(bool(0)), card_reset()
    segment = PciSegment({"master": PciAgent(), "target": PciAgent()})
    checker = ProtocolChecker(**checker_options)
    idle = [] if during_reset else [{}] * RESET_CLOCKS
    bench = scripted_bench(clock, reset, segment, checker, idle + master, idle + target)
    # the save file is written also when the monitor stops the bench
    run_traced(bench, f"monitor_{name}", groups={"PCI": ["clock", "reset"] + [f"bus_{line}" for line in (
        "frame", "irdy", "ad_view", "cbe", "par", "devsel", "trdy", "stop", "perr", "serr")]})
    return checker


def end_master():
    return [{"irdy": 1, "ad": None, "cbe": None},
            {"frame": None, "irdy": None, "par": None}, {}, {}]


def end_target(par_value=None):
    release = {"devsel": None, "trdy": None, "stop": None}
    if par_value is None:
        return [{"devsel": 1, "trdy": 1, "stop": 1}, dict(release, par=None), {}, {}]
    return [{"devsel": 1, "trdy": 1, "stop": 1, "ad": None, "par": par_value},
            dict(release, par=None), {}, {}]


def read_single():
    """Memory read, medium DEVSEL#, data in the first clock it may come."""
    master = [{"frame": 0, "irdy": 1, "ad": A, "cbe": READ},
              {"frame": 1, "irdy": 0, "ad": None, "cbe": 0, "par": par(A, READ)},
              {"par": None}] + end_master()
    target = [{}, {}, {"devsel": 0, "trdy": 0, "stop": 1, "ad": X}] + end_target(par(X, 0))
    return master, target


def write_with_target_wait():
    """Memory write, the target inserts one wait state."""
    master = [{"frame": 0, "irdy": 1, "ad": A, "cbe": WRITE},
              {"frame": 1, "irdy": 0, "ad": D, "cbe": 0, "par": par(A, WRITE)},
              {"par": par(D, 0)}, {},
              {"irdy": 1, "ad": None, "cbe": None},
              {"frame": None, "irdy": None, "par": None}, {}, {}]
    target = [{}, {}, {"devsel": 0, "trdy": 1, "stop": 1}, {"trdy": 0}] + end_target()
    return master, target


def read_with_master_wait():
    """Memory read burst start: TRDY# waits for a late IRDY#."""
    master = [{"frame": 0, "irdy": 1, "ad": A, "cbe": READ},
              {"ad": None, "cbe": 0, "par": par(A, READ)},
              {"par": None},
              {"frame": 1, "irdy": 0}] + end_master()
    target = [{}, {}, {"devsel": 0, "trdy": 0, "stop": 1, "ad": X},
              {"par": par(X, 0)}] + end_target(par(X, 0))
    return master, target


def burst_read_retry():
    """Burst read answered with retry (STOP# without TRDY#)."""
    master = [{"frame": 0, "irdy": 1, "ad": A, "cbe": READ},
              {"irdy": 0, "ad": None, "cbe": 0, "par": par(A, READ)},
              {"par": None},
              {"frame": 1}] + end_master()
    target = [{}, {}, {"devsel": 0, "trdy": 1, "stop": 0, "ad": X},
              {"par": par(X, 0)}] + end_target(par(X, 0))
    return master, target


def read_devsel_at(edge):
    """Single read whose DEVSEL# is sampled ``edge`` edges after the address
    (TRDY# and AD not before the second: AD needs its turnaround clock)."""
    master, _ = read_single()
    data_edge = max(edge, 2)
    master = master[:3] + [{}] * (data_edge - 2) + master[3:]
    target = [{}] * edge + [{"devsel": 0, "trdy": 1, "stop": 1}] * (data_edge - edge) + [
        {"devsel": 0, "trdy": 0, "stop": 1, "ad": X}] + end_target(par(X, 0))
    return master, target


def write_target_abort():
    """Memory write claimed, then target abort (STOP# with DEVSEL# deasserted)."""
    master = [{"frame": 0, "irdy": 1, "ad": A, "cbe": WRITE},
              {"frame": 1, "irdy": 0, "ad": D, "cbe": 0, "par": par(A, WRITE)},
              {"par": par(D, 0)}, {}] + end_master()
    target = [{}, {}, {"devsel": 0, "trdy": 1, "stop": 1}, {"devsel": 1, "stop": 0},
              {"stop": 1}, {"devsel": None, "trdy": None, "stop": None}, {}, {}]
    return master, target


LEGAL = {"read": read_single, "write_wait": write_with_target_wait,
         "read_master_wait": read_with_master_wait, "retry": burst_read_retry,
         "fast_devsel": lambda: read_devsel_at(1), "slow_devsel": lambda: read_devsel_at(3),
         "subtractive_devsel": lambda: read_devsel_at(4), "target_abort": write_target_abort}


@pytest.mark.parametrize("name", sorted(LEGAL))
def test_legal_traffic_passes(name):
    master, target = LEGAL[name]()
    checker = play(master, target, f"legal_{name}")
    assert len(checker.transactions) == 1 and checker.transactions[0].ended


def with_step(script, index, **changes):
    script = [dict(step) for step in script]
    script[index].update(changes)
    return script


def broken_cases():
    """rule -> (master, target, checker options): one break per rule."""
    read_m, read_t = read_single()
    write_m, write_t = write_with_target_wait()
    wait_m, wait_t = read_with_master_wait()
    retry_m, retry_t = burst_read_retry()
    late_irdy = [{"frame": 0, "irdy": 1, "ad": A, "cbe": WRITE},
                 {"ad": D, "cbe": 0, "par": par(A, WRITE)}, {"par": par(D, 0)}] + [{}] * 9
    slow_target = [{}, {}, {"devsel": 0, "trdy": 1, "stop": 1}] + [{}] * 20
    write_burst = with_step(write_m, 1, frame=0)
    config_enable = [{"frame": 0, "irdy": 1, "ad": 1 << 16 | 0x04, "cbe": CONFIG_WRITE},
                     {"frame": 1, "irdy": 0, "ad": 0x140, "cbe": 0xC,
                      "par": par(1 << 16 | 0x04, CONFIG_WRITE)},
                     {"par": par(0x140, 0xC)}, {}]
    config_target = [{}, {}, {"devsel": 0, "trdy": 1, "stop": 1}, {"trdy": 0}]
    bad_address = [{"irdy": 1, "ad": None, "cbe": None},
                   {"frame": None, "irdy": None, "par": None}, {},
                   {"frame": 0, "irdy": 1, "ad": A, "cbe": READ},
                   {"frame": 1, "irdy": 0, "ad": None, "cbe": 0, "par": 1 - par(A, READ)},
                   {"par": None}, {}, {"irdy": 1}, {"frame": None, "irdy": None}, {}, {}]
    return {
        1: (with_step(write_m, 3, ad=D ^ 1, par=par(D ^ 1, 0)), write_t, {}),
        2: (wait_m, with_step(wait_t, 3, ad=X ^ 1, par=par(X ^ 1, 0)), {}),
        3: (with_step(write_m, 3, cbe=0xC), write_t, {}),
        4: (write_m[:4] + [{"frame": 0, "irdy": 1, "ad": A, "cbe": WRITE}, {}, {}], write_t, {}),
        5: ([{}, {"irdy": 0}, {"irdy": 1}, {"irdy": None}], [{}], {}),
        6: (with_step(with_step(write_m, 1, irdy=1, frame=0), 2, frame=1), write_t, {}),
        7: (with_step(write_burst, 2, frame=1), write_t, {}),
        8: (with_step(write_m, 2, irdy=1), write_t, {}),
        9: (retry_m, with_step(retry_t, 3, stop=1), {}),
        10: (retry_m, with_step(retry_t, 4, stop=0), {}),
        11: (wait_m, with_step(wait_t, 3, trdy=1), {}),
        12: (read_m, with_step(read_t, 2, devsel=1), {}),
        13: (write_burst, with_step(write_t, 3, devsel=1, trdy=1), {}),
        "14 PAR": (read_m, with_step(read_t, 3, par=1 - par(X, 0)), {}),
        "14 PERR# missing": (read_m, with_step(read_t, 3, par=1 - par(X, 0)),
                             {"allow_parity_errors": True}),
        "14 false PERR#": (with_step(read_m, 4, perr=0), read_t, {}),
        "14 SERR# missing": (config_enable + bad_address, config_target + end_target(),
                             {"allow_parity_errors": True}),
        "15 IRDY#": (late_irdy, slow_target, {}),
        "15 TRDY#": (read_m[:3] + [{}] * 20, slow_target, {}),
        16: (read_m, with_step(read_t, 1, ad=X), {}),
        "16 contention": (read_m, with_step(read_t, 0, frame=0), {}),
        17: (read_m, with_step(read_t, 3, devsel=None, trdy=None, stop=None), {}),
        18: ([{}] * 4, [{"devsel": 1}] + [{}] * 3, {"during_reset": True}),
        "15 DEVSEL# after clock 5": (
            [{"frame": 0, "irdy": 1, "ad": A, "cbe": READ},
             {"irdy": 0, "ad": None, "cbe": 0, "par": par(A, READ)}, {"par": None}, {}, {},
             {"frame": 1}] + end_master(),
            [{}] * 5 + [{"devsel": 0, "trdy": 1, "stop": 1}] + end_target(), {}),
        "12 abort without a claim": (write_m, [{}, {}, {"devsel": 1, "stop": 0},
                                               {"stop": 1}, {"stop": None}, {}], {}),
        "14 false SERR#": (read_m, with_step(read_t, 3, serr=0), {}),
    }


CASES = broken_cases()


@pytest.mark.parametrize("case", list(CASES), ids=str)
def test_each_rule_fires(case):
    master, target, options = CASES[case]
    rule = case if isinstance(case, int) else int(case.split()[0])
    with pytest.raises(ProtocolViolation) as caught:
        play(master, target, f"rule_{str(case).replace(' ', '_').replace('#', '')}", **options)
    assert caught.value.rule == rule, str(caught.value)
    assert f"rule {rule} " in str(caught.value) and "t=" in str(caught.value)


@pytest.mark.parametrize("case", list(CASES), ids=str)
def test_record_mode_keeps_going_and_reports_the_same_first_rule(case):
    master, target, options = CASES[case]
    rule = case if isinstance(case, int) else int(case.split()[0])
    checker = play(master, target, f"record_{str(case).replace(' ', '_').replace('#', '')}",
                   mode="record", **options)
    first = checker.violations[0]
    assert first.rule == rule and first.clock > 0 and set(first.values) >= {"ad", "frame", "trdy"}
    assert f"rule {rule} " in checker.summary()
    with pytest.raises(ProtocolViolation) as caught:
        checker.raise_recorded()
    assert caught.value.rule == rule and caught.value.violations == checker.violations


def test_record_mode_records_every_clock_of_a_lasting_violation():
    read_m, read_t = read_single()
    master = with_step(with_step(read_m, 4, perr=0), 6, perr=1)   # PERR# low for two clocks, no error
    checker = play(master, read_t, "record_lasting", mode="record")
    clocks = [v.clock for v in checker.violations if v.rule == 14]
    assert len(clocks) == 2 and clocks[1] == clocks[0] + 1
    assert checker.summary().startswith("PCI monitor: 2 violations")


def test_a_quiet_run_records_nothing():
    checker = play(*read_single(), "record_quiet", mode="record")
    assert checker.violations == [] and "no violation" in checker.summary()
    checker.raise_recorded()
