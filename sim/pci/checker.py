"""Passive PCI protocol checker: plain Python, fed by any simulator.

``ProtocolChecker.step(sample, in_reset)`` takes one ``BusSample`` of the
segment per rising clock edge (resolved lines and who drove them) and checks
the rules below (PCI 2.3 chapter 3 and Appendix C).  ``sim.pci.monitor``
runs it in a MyHDL bench.  Two modes:

* ``mode="stop"`` (default): raise ``ProtocolViolation`` naming the rule, the
  time and the clock at the first violation;
* ``mode="record"``: keep going; every violation is kept in ``violations``
  (``Violation``: rule, time, clock, detail and the bus lines and their
  drivers at that edge); ``summary()`` counts them by rule and
  ``raise_recorded()`` raises one ``ProtocolViolation`` for them all.

A four-state front end's X/Z report (``BusSample.unknown``) is rule 19,
except X or Z on AD at an edge where the master takes read data (a read,
IRDY#, TRDY# and DEVSEL# asserted): that is data corruption, rule 20 (a
two-state master reads the X as 0 or 1 and goes on).

The checker also snoops configuration writes to the Command register of the
watched device (Parity Error Response, SERR# Enable) to know when PERR# and
SERR# are due, and keeps a summary of every transaction (``transactions``)
for figures.

Parity errors are violations unless ``allow_parity_errors`` is set (a bench
that injects them on purpose); then only their reporting is checked.
Fast back-to-back transactions are reported under rule 4: the benches have
one master, which always leaves an idle clock between transactions.

Timing the checker holds the target to (edges counted from the one that
samples the address): DEVSEL# by edge 4, first TRDY#/STOP# by edge 16, later
ones at most 8 edges after the previous data phase completed; PERR# sampled
two edges after a data phase that moved data with bad parity (write: when the
target's Parity Error Response is set; read: when the master's is), SERR#
two edges after a bad address when the target's SERR# Enable and Parity
Error Response are set, each for exactly one clock per error.
"""
from models.pci import COMMAND_PARITY_RESPONSE as PARITY_RESPONSE
from models.pci import COMMAND_SERR_ENABLE as SERR_ENABLE
from models.pci import CONFIG_COMMAND as COMMAND_REGISTER
from models.pci import CONFIG_WRITE
from sim.pci.lines import OPEN_DRAIN, SUSTAINED_TRISTATE, even_parity
from sim.pci.records import RULES, ProtocolViolation, TransactionRecord, Violation, hex_word

MASTER_ABORT_EDGE = 4


def _asserted(value):
    return value == 0


class ProtocolChecker:
    """The rules of ``RULES`` over a stream of samples.

    target_device: device number whose IDSEL is AD[16+n] (for Command
    register snooping); master_parity_response: the master's own Parity
    Error Response bit (PERR# on read data errors).
    """

    def __init__(self, target_device=0, master_parity_response=True, allow_parity_errors=False,
                 mode="stop"):
        if mode not in ("stop", "record"):
            raise ValueError(f"monitor mode must be 'stop' or 'record', not {mode!r}")
        self.mode = mode
        self.violations = []
        self.unknown_clocks = 0   # edges with an X/Z report (rules 19 and 20)
        self.corrupt_read_clocks = 0   # of them, edges whose read data was X/Z (rule 20)
        self.target_device = target_device
        self.master_parity_response = master_parity_response
        self.allow_parity_errors = allow_parity_errors
        self.transactions = []
        self.parity_errors = []
        self.edges = 0
        self._reset_state()

    def _reset_state(self):
        self.target_command = 0
        self.current = None
        self.previous = None
        self.previous_info = None
        self.expected_perr = set()
        self.expected_serr = set()

    def fail(self, rule, detail):
        """Report a violation: raise (stop mode) or record it and go on."""
        sample = self.sample
        if self.mode == "stop":
            raise ProtocolViolation(rule, sample.time, detail, self.edges)
        self.violations.append(Violation(rule, sample.time, self.edges, detail, dict(sample.values),
                                         dict(sample.drivers)))

    def summary(self):
        """Recorded violations by rule: one line per rule (count, first and
        last clock), or a line saying there were none."""
        if not self.violations:
            return f"PCI monitor: no violation in {self.edges} clocks"
        lines = [f"PCI monitor: {len(self.violations)} violations in {self.edges} clocks"]
        for rule in sorted({v.rule for v in self.violations}):
            seen = [v for v in self.violations if v.rule == rule]
            lines.append(f"  rule {rule} ({RULES[rule]}): {len(seen)}, clocks {seen[0].clock}"
                         f"..{seen[-1].clock}; first: {seen[0].detail}")
        return "\n".join(lines)

    def raise_recorded(self):
        """Raise one ``ProtocolViolation`` (the first, with the summary) if any were recorded."""
        if self.violations:
            first = self.violations[0]
            raise ProtocolViolation(first.rule, first.time, f"{first.detail}\n{self.summary()}",
                                    first.clock, self.violations)

    def step(self, sample, in_reset=False):
        self.edges += 1
        self.sample = sample
        if sample.unknown:
            self._report_unknown(sample, in_reset)
        if in_reset:
            self._check_reset(sample)
            self._reset_state()
            self.previous = sample
            return
        previous = self.previous
        if previous is not None:
            self._check_drivers(previous, sample)
        info = self._track(previous, sample)
        if previous is not None and self.previous_info is not None:
            self._check_master(previous, self.previous_info, sample)
            self._check_target(previous, self.previous_info, sample, info)
            self._check_parity(previous, self.previous_info, sample)
        self._check_latency(sample, info)
        self._check_reports(sample)
        self.previous, self.previous_info = sample, info

    def _report_unknown(self, sample, in_reset):
        """Rule 20 for X/Z on AD that the master takes as read data, rule 19
        for every other X/Z report."""
        self.unknown_clocks += 1
        current = self.current
        lines = set(sample.unknown)
        if "ad" in lines and not in_reset and current is not None and not current.ended \
                and not current.write and all(_asserted(sample.values[line]) for line in ("irdy", "trdy", "devsel")):
            self.corrupt_read_clocks += 1
            lines.discard("ad")
            self.fail(20, f"AD X or Z taken as read data ({current.command:#x} at {current.address:#x}, "
                          f"data phase {current.data_phases + 1})")
        if lines:
            self.fail(19, f"{', '.join(sorted(line.upper() for line in lines))} X or Z while driven")

    # ----- transaction tracking --------------------------------------------------
    def _track(self, previous, sample):
        """Update the current transaction with ``sample``; return its view of it."""
        current = self.current
        if current is not None and current.ended:
            current = self.current = None
        frame_starts = _asserted(sample.frame) and (previous is None or not _asserted(previous.frame))
        address_phase = frame_starts and current is None
        if address_phase:
            if previous is not None and _asserted(previous.irdy):
                self.fail(4, "FRAME# asserted while IRDY# of the last transaction is asserted")
            if sample.ad is None or sample.cbe is None:
                self.fail(14, "address phase with AD or C/BE# floating")
                return {"transaction": None, "address": False, "data": False, "completion": False,
                        "transfer": False, "ended": False}
            current = self.current = TransactionRecord(sample.time, sample.cbe, sample.ad,
                                                       start_edge=self.edges,
                                                       phase_start_edge=self.edges)
            self.transactions.append(current)
        info = {"transaction": current, "address": address_phase, "data": False,
                "completion": False, "transfer": False, "ended": False}
        if current is None or address_phase:
            return info
        info["data"] = True
        clock = self.edges - current.start_edge
        if _asserted(sample.devsel) and current.devsel_clock is None:
            current.devsel_clock = clock
            if clock > MASTER_ABORT_EDGE:
                self.fail(15, f"DEVSEL# first asserted {clock} clocks after the address phase")
        master_abort = current.devsel_clock is None and clock >= MASTER_ABORT_EDGE
        irdy = _asserted(sample.irdy)
        target_ends = _asserted(sample.trdy) or _asserted(sample.stop)
        info["completion"] = irdy and (target_ends or master_abort)
        info["transfer"] = irdy and _asserted(sample.trdy) and _asserted(sample.devsel)
        if _asserted(sample.stop) and not _asserted(sample.devsel) and current.devsel_clock is not None:
            current.target_abort = True
        if info["transfer"]:
            current.data_phases += 1
            self._snoop_config_write(current, sample)
        if info["completion"]:
            current.last_completion_edge = self.edges
            current.phase_start_edge = self.edges
            current.completions.append(self.edges)
            if not _asserted(sample.frame):
                current.ended = info["ended"] = True
                current.end, current.end_edge = sample.time, self.edges
        return info

    def _snoop_config_write(self, current, sample):
        if sample.ad is None or sample.cbe is None:
            return
        address = current.address
        if current.command != CONFIG_WRITE or address & 0x3 or (address >> 8) & 0x7:
            return
        if not address >> (16 + self.target_device) & 1:
            return
        if (address & 0xFC) + 4 * (current.data_phases - 1) != COMMAND_REGISTER:
            return
        for byte in range(2):
            if not sample.cbe >> byte & 1:
                mask = 0xFF << (8 * byte)
                self.target_command = (self.target_command & ~mask) | (sample.ad & mask)

    # ----- rules 1-8: master ------------------------------------------------------
    def _check_master(self, previous, before, sample):
        current = before["transaction"]
        if not _asserted(previous.irdy) and _asserted(sample.irdy) and not _asserted(previous.frame):
            self.fail(5, "IRDY# asserted although FRAME# was deasserted in the clock before")
        if _asserted(previous.frame) and not _asserted(sample.frame) and not _asserted(sample.irdy):
            self.fail(6, "FRAME# deasserted while IRDY# is deasserted")
        if not before["data"] or before["completion"]:
            return
        if _asserted(previous.irdy):
            if sample.frame != previous.frame:
                self.fail(7, "FRAME# changed after IRDY# was asserted, before the data phase completed")
            if not _asserted(sample.irdy):
                self.fail(8, "IRDY# deasserted before the data phase completed")
            if current.write and sample.ad != previous.ad:
                self.fail(1, f"AD changed from {hex_word(previous.ad)} to {hex_word(sample.ad)} "
                             "in a write wait state")
        if sample.cbe != previous.cbe:
            self.fail(3, f"C/BE# changed from {hex_word(previous.cbe)} to {hex_word(sample.cbe)} within a data phase")

    # ----- rules 2, 9-13: target ----------------------------------------------------
    def _check_target(self, previous, before, sample, now_info):
        current = before["transaction"]
        in_transaction = before["data"] and not before["ended"]
        stop_then, frame_then = _asserted(previous.stop), _asserted(previous.frame)
        if stop_then and frame_then and in_transaction and not _asserted(sample.stop):
            self.fail(9, "STOP# deasserted while FRAME# was still asserted")
        if stop_then and not frame_then and _asserted(sample.stop):
            self.fail(10, "STOP# still asserted after FRAME# was deasserted and the transaction ended")
        if in_transaction and not _asserted(previous.irdy) and (
                _asserted(previous.trdy) or stop_then):
            for line in ("devsel", "trdy", "stop"):
                if sample.values[line] != previous.values[line]:
                    self.fail(11, f"{line.upper()}# changed while TRDY#/STOP# waited for IRDY#")
            if not current.write and _asserted(previous.trdy) and sample.ad != previous.ad:
                self.fail(2, f"AD changed from {hex_word(previous.ad)} to {hex_word(sample.ad)} in a read wait state")
        self._check_devsel(previous, before, sample, now_info)

    def _check_devsel(self, previous, before, sample, now_info):
        current = now_info["transaction"]
        claimed_before = current is not None and current.devsel_clock is not None and \
            current.devsel_clock < self.edges - current.start_edge
        if _asserted(sample.trdy) and not _asserted(sample.devsel):
            self.fail(12, "TRDY# asserted without DEVSEL#")
        if _asserted(sample.stop) and not _asserted(sample.devsel) and not (
                now_info["data"] and claimed_before):
            self.fail(12, "STOP# asserted without DEVSEL# outside a target abort")
        in_transaction = before["data"] and not before["ended"]
        if in_transaction and _asserted(previous.devsel) and not _asserted(sample.devsel) and not (
                _asserted(sample.stop) and not _asserted(sample.trdy)):
            self.fail(13, "DEVSEL# deasserted before the last data phase (not a target abort)")
        if not now_info["data"] and not now_info["address"]:
            for line, rule in (("devsel", 13), ("trdy", 12), ("stop", 10)):
                if _asserted(sample.values[line]):
                    self.fail(rule, f"{line.upper()}# asserted after the transaction ended")

    # ----- rule 14: parity and its reports ---------------------------------------------
    def _check_parity(self, previous, before, sample):
        current = before["transaction"]
        if before["address"]:
            kind = "address"
        elif before["data"]:
            if current.write and _asserted(previous.irdy):
                kind = "write data"
            elif not current.write and _asserted(previous.trdy):
                kind = "read data"
            else:
                return
        else:
            return
        if previous.ad is None or previous.cbe is None:
            self.fail(14, f"AD or C/BE# floating in a {kind} phase")
            return
        if sample.par is None:
            self.fail(14, f"PAR not driven the clock after a {kind} phase")
            return
        if sample.par == even_parity(previous.ad, previous.cbe):
            return
        self.parity_errors.append((previous.time, kind))
        if not self.allow_parity_errors:
            self.fail(14, f"PAR wrong for the {kind} phase at t={previous.time}")
        due = self.edges + 1
        if kind == "address":
            if self.target_command & SERR_ENABLE and self.target_command & PARITY_RESPONSE:
                self.expected_serr.add(due)
        elif before["transfer"]:
            enabled = (self.target_command & PARITY_RESPONSE if kind == "write data"
                       else self.master_parity_response)
            if enabled:
                self.expected_perr.add(due)

    def _check_reports(self, sample):
        for line, expected in (("perr", self.expected_perr), ("serr", self.expected_serr)):
            due = self.edges in expected
            expected.discard(self.edges)
            asserted = _asserted(sample.values[line])
            if due and not asserted:
                self.fail(14, f"{line.upper()}# missing two clocks after a parity error")
            if asserted and not due:
                self.fail(14, f"{line.upper()}# asserted but no parity error was due")

    # ----- rule 15: latency ---------------------------------------------------------------
    def _check_latency(self, sample, info):
        current = info["transaction"]
        if not info["data"]:
            return
        clock = self.edges - current.start_edge
        since_phase = self.edges - current.phase_start_edge
        if info["completion"]:
            since_phase = 0
        if not _asserted(sample.irdy) and since_phase >= 8:
            self.fail(15, f"IRDY# not asserted {since_phase} clocks into a data phase (limit 8)")
        target_ends = _asserted(sample.trdy) or _asserted(sample.stop)
        if target_ends:
            if current.first_trdy_clock is None and _asserted(sample.trdy):
                current.first_trdy_clock = clock
            if current.first_stop_clock is None and _asserted(sample.stop):
                current.first_stop_clock = clock
        if current.devsel_clock is None:
            return
        first = current.last_completion_edge is None
        limit = 16 if first else 8
        waited = clock if first else self.edges - current.last_completion_edge
        if not target_ends and waited >= limit and not current.ended:
            self.fail(15, f"no TRDY#/STOP# {waited} clocks into the {'first' if first else 'next'}"
                          f" data phase (limit {limit})")

    # ----- rules 16-18: drivers ------------------------------------------------------------
    def _check_drivers(self, previous, sample):
        for line, names in sample.drivers.items():
            if line in OPEN_DRAIN:
                continue
            if len(names) > 1:
                self.fail(16, f"{line.upper()} driven by {sorted(names)} at once")
            before = previous.drivers[line]
            if names and before and names != before:
                self.fail(16, f"{line.upper()} taken over by {sorted(names)} right after "
                              f"{sorted(before)} without a turnaround clock")
            if line in SUSTAINED_TRISTATE and before - names and previous.values[line] != 1:
                self.fail(17, f"{line.upper()}# released by {sorted(before - names)} while asserted")

    def _check_reset(self, sample):
        for line, names in sample.drivers.items():
            if names:
                self.fail(18, f"{line.upper()} driven by {sorted(names)} during reset")
