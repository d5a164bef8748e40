"""The proof groups: which harness, which generated files, which properties,
which engine and depth.

A group keeps the assertions whose names start with one of its prefixes and
drops the others (each property is proved in exactly one group; the covers
run in their own group).  The PCI and card groups read the generated Verilog
of ``gen_dir`` (what users synthesise); the DDA group converts a small-width
build into the work folder.  ``Group`` itself is in ``formal/proof_group.py``.
"""
from dataclasses import replace
from functools import partial

from formal.axes_props import (axes_inputs, axis_register_names, card_axes, ferror_axes, ferror_models,
                               ferror_registers, harness_parameters, machine_axes, regs_fifo_axes)
from formal.builds import GENERATED, built_unit
from formal.card_props import card_constants
from formal.isa_props import instruction_table
from formal.pci_props import pci_constants
from formal.proof_group import Group
from formal.regs_props import register_offsets, table_properties
from models import registers as regmap
from models.dda_build import DDA_MIN_WIDTH as NARROW_WIDTH
from models.encoder_model import ERROR_COUNT_MAX, FILTER_MAX
from models.parameters import Build
from rtl.convert import convert_narrow_dda, convert_unit
from rtl.pci.pci_slave_build import alias_bar_bits, local_addr_width


def pci_harness_parameters(build):
    """`chparam` settings of pci_target_harness for a target of ``build`` (its BARs and IDs)."""
    return dict(IO_BITS=build.io_bar_bits, MEM_BITS=build.mem_bar_bits,
                LOCAL_WIDTH=local_addr_width(build.io_bar_bits, build.mem_bar_bits, build.reg_bar_bits),
                ID_WORD=build.device_id << 16 | build.vendor_id,
                CLASS_WORD=build.class_code << 8 | build.revision_id,
                SUBSYSTEM_WORD=build.subsystem_id << 16 | build.subsystem_vendor_id)


# Includes the harnesses share (docs/formal.md): harness_reset.vh (RST# in the
# first clock, `judged`) in every harness on gen/; the PCI lines, pins and bus
# model (pci_bus_lines.vh, pci_pins.vh, pci_bus_model.vh, with pci_table.vh
# generated from models/pci.py) in the PCI target's and the card's.
RESET_FILES = ["harness_reset.vh"]
PCI_BUS_FILES = [*RESET_FILES, "pci_bus_lines.vh", "pci_pins.vh", "pci_bus_model.vh"]
PCI_TABLE = {"pci_table.vh": pci_constants}
# pci_target_local.vh: the harness's local-side properties, included by it
PCI_FILES = ["pci_rules.sv", "local_bus_rules.sv", *PCI_BUS_FILES, "pci_target_local.vh", "pci_target_harness.sv"]
PCI_PARAMETERS = pci_harness_parameters(Build())  # the unit as `python -m rtl.top --convert` writes gen/
# registers of pci_slave the helper invariants (props/pci_slave_invariants.vh) read
# the configuration header's own registers carry the instance name the
# converter gives them (``pci_config0_``, rtl/pci/pci_config.py)
PCI_SLAVE_REGISTERS = ("state", "trdy_q", "stop_q", "devsel_q", "wait_count", "initial_wait_over",
                       "subsequent_wait_over", "first_phase", "is_read", "is_config", "space_mem",
                       "io_enable", "mem_enable", "parity_response", "serr_enable",
                       "interrupt_disable", "bar0", "bar1", "bar2", "config_write_q", "phase_addr",
                       "at_last", "before_last", "h_valid", "s_valid", "wq_valid", "b_valid",
                       "fetching", "first_pending", "req_addr_stale", "single", "frame_q",
                       "pci_config0_signaled_target_abort", "pci_config0_signaled_system_error",
                       "pci_config0_detected_parity_error", "parity_error_q",
                       "pci_config0_interrupt_line", "h_data", "spare_data", "ad_q", "h_be", "s_be",
                       "cbe_q", "req_addr", "ad_out_q")
# regs_fifo_env.vh, regs_fifo_ports.vh: the environment and ports of regs_fifo
# both its harnesses share, with the register names (regs_offsets.vh) and
# models (regs_table.vh) generated from models/registers.py
# (regs_fifo_axes.vh: its per-axis ports, generated for the build's axes by formal/axes_props.py)
REGS_ENV_FILES = [*RESET_FILES, "regs_fifo_env.vh", "regs_fifo_ports.vh"]
ISA_TABLE = {"isa_table.vh": instruction_table}   # the opcode table (models/instructions.py)
REGS_FILES = ["local_bus_rules.sv", "pulse_rules.sv", *REGS_ENV_FILES, "regs_fifo_harness.sv"]


def regs_tables(values=None):
    """The includes regs_fifo's harnesses read, generated for the build ``values``:
    register names and models (models/registers.py), its per-axis ports."""
    return {"regs_offsets.vh": partial(register_offsets, values), "regs_table.vh": partial(table_properties, values),
            "regs_fifo_axes.vh": partial(regs_fifo_axes, values)}


def regs_fifo_registers(values=None):
    """Registers of regs_fifo the back end's harness makes ports: the FIFO's pop, flush and
    output, the SET port, the guard's stop, every axis's direct-pulse request."""
    axes = harness_parameters(values)["AXES"]
    return ("fifo_pop", "fifo_flush", "fifo_dout", "set_strobe", "set_index", "set_value", "guard_stopped",
            *axis_register_names(axes)["direct_request"])


REGS_FIFO_REGISTERS = regs_fifo_registers()
REGS_FIFO_TABLES = {**regs_tables(), **ISA_TABLE}
REGS_FIFO_HELPERS = ("sync_fifo0_count", "sync_fifo0_is_empty", "sync_fifo0_is_full", "io_written",
                     "read_waited")

# signals of gen/card.v the card harness reads: where the sequencer takes a
# word from the FIFO (rtl/regs/sequencer.py fifo.pop, the FIFO's empty flag and
# output register), under the instance names the converter gives them
CARD_SIGNALS = ("card_core0_regs_fifo1_fifo_pop", "card_core0_regs_fifo1_fifo_empty",
                "card_core0_regs_fifo1_fifo_dout")


# the card's BAR0 and BAR2 (rtl/card.py: BAR2 holds BAR0's registers, then the per-axis blocks)
CARD_BARS = dict(IO_BITS=regmap.IO_BAR_BITS, REG_BITS=alias_bar_bits(regmap.IO_BAR_BITS, regmap.REG_BAR_BITS))


def card(values=None):
    """The settings the card groups share, for the build ``values``."""
    return dict(expose=CARD_SIGNALS, parameters=dict(harness_parameters(values), **CARD_BARS), mode="bmc",
                generated={"card_table.vh": card_constants, "card_axes.vh": partial(card_axes, values), **ISA_TABLE,
                           **PCI_TABLE})


CARD = card()
CARD_FILES = ["pci_rules.sv", *PCI_BUS_FILES, "card_harness.sv"]
CARD_ORDER_DEPTH, CARD_STATUS_DEPTH, CARD_ERROR_DEPTH = 18, 20, 28

# the machine side (props/machine_harness.sv): the guard's, the filter's, the
# feed rate's and the homing unit's own registers and ports, and the step
# requests before and after the guard's gate
MACHINE_FILES = ["local_bus_rules.sv", *REGS_ENV_FILES, "machine_harness.sv"]


def machine_registers(values=None):
    """Registers and wires of regs_fifo the machine harness makes ports (the per-axis ones
    for every axis of the build ``values``: machine_axes.vh, regs_fifo_axes.vh)."""
    names = axis_register_names(harness_parameters(values)["AXES"])
    return ("fifo_pop", "fifo_flush", "set_strobe", "set_index", "set_value", "guard_stopped", "guard_stopping",
            "settled", "conditioning_active", "machine_guard0_guard_reason", "machine_guard0_guard_limits",
            "feed_rate0_rate", "homing0_state", "homing0_axis", "homing0_refused", "homing0_not_found", "home_zero",
            "ramp_step", "machine_control", "feed_held", "step_mode", "sync_fifo0_count", "sync_fifo0_is_empty",
            "sync_fifo0_is_full", "io_written", "watchdog_left",
            *(name for kind in ("direct_request", "request_step", "request_dir", "granted_step", "pulse",
                                "direct_pending") for name in names[kind]))


def machine(values=None):
    """The settings the machine groups share, for the build ``values``."""
    return dict(expose=machine_registers(values), parameters=harness_parameters(values),
                generated={**regs_tables(values), "machine_axes.vh": partial(machine_axes, values),
                           "axes_inputs.vh": partial(axes_inputs, values)})


MACHINE_REGISTERS = machine_registers()
MACHINE = machine()


def narrow_dda():
    """``dda_arc.v`` of the narrowest build (NARROW_WIDTH-bit coordinates, the
    default variants), converted from rtl/ into the work folder; its path."""
    return convert_narrow_dda(GENERATED / f"dda_w{NARROW_WIDTH}")


DDA = dict(convert=narrow_dda, parameters=dict(W=NARROW_WIDTH))


def encoder_unit(unit):
    """A function writing ``unit`` of rtl/encoder/ (not in gen/ yet), converted
    alone, into the work folder; it returns the path."""
    return lambda: convert_unit(unit, {}, GENERATED / "encoder")


# the encoder's filtered levels and the samples its decoder and index latch compare them with
ENCODER_SIGNALS = ("conditioner_a_level", "conditioner_b_level", "conditioner_index_level", "decoder_seen_a",
                   "decoder_seen_b", "index_latch_seen")
ENCODER = dict(convert=encoder_unit("encoder"), expose=ENCODER_SIGNALS)
ENCODER_PARAMETERS = dict(ERROR_MAX=ERROR_COUNT_MAX)
ENCODER_FILES = [*RESET_FILES, "encoder_harness.sv"]
FERROR_FILES = [*RESET_FILES, "following_error_harness.sv"]
PROBE_FILES = [*RESET_FILES, "probe_harness.sv"]
PCI_HELPERS = dict(expose=PCI_SLAVE_REGISTERS, includes=("pci_slave_invariants.vh",),
                   defines={"PCI_SLAVE_INVARIANTS": None}, generated=PCI_TABLE)

GROUPS = [
    Group("pci_protocol", "pci_slave", PCI_FILES, "pci_target_harness", ("t_", "lb_", "inv_"),
          parameters=PCI_PARAMETERS, **PCI_HELPERS,
          text="PCI 2.3 target rules (pci_rules.sv) and the LocalBus requester rules"),
    Group("pci_parity", "pci_slave", PCI_FILES, "pci_target_harness", ("tp_", "inv_"),
          parameters=PCI_PARAMETERS, **PCI_HELPERS, fast=False,   # over a minute; the benches drive parity errors
          text="PAR, PERR#, SERR# (pci_rules.sv)"),
    Group("pci_config", "pci_slave", PCI_FILES, "pci_target_harness",
          ("config_", "inta_", "target_abort_", "inv_"), parameters=PCI_PARAMETERS, **PCI_HELPERS, fast=False,
          text="configuration space, decode, INTA#, target-abort causes"),
    Group("pci_local", "pci_slave", PCI_FILES, "pci_target_harness", ("write_", "read_", "inv_"),
          parameters=PCI_PARAMETERS, **PCI_HELPERS, fast=False,
          text="the local side carries exactly the PCI transaction"),
    Group("pci_fifo_path", "pci_slave", PCI_FILES, "pci_target_harness",
          ("acknowledged_", "io_not_retried", "inv_"), parameters=PCI_PARAMETERS, **PCI_HELPERS, fast=False,
          depth=24,   # the basecase reaches the overfill of a target without the write credit (step 19)
          text="nothing acknowledged is dropped; I/O never waits behind the FIFO"),
    Group("regs_fifo_path", "regs_fifo", REGS_FILES, "regs_fifo_harness",
          ("lb_", "rf_registers", "rf_level", "rf_push", "rf_full", "rf_status", "inv_"),
          expose=REGS_FIFO_REGISTERS + REGS_FIFO_HELPERS, includes=("regs_fifo_invariants.vh",),
          defines={"REGS_FIFO_INVARIANTS": None}, generated=REGS_FIFO_TABLES,
          text="back end: LocalBus answers, registers never wait, FIFO level, STATUS, nothing lost"),
    Group("regs_fifo_table", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("reg_",), mode="bmc",
          depth=10, expose=REGS_FIFO_REGISTERS, generated=REGS_FIFO_TABLES,
          defines={"STEP_MODES_FREE": None},   # STEP_MODE written too (the pins are judged elsewhere)
          text="every register as models/registers.py says (bounded)"),
    Group("regs_fifo_pulses", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("pulse_",), mode="bmc",
          depth=20, fast=False, expose=REGS_FIFO_REGISTERS, generated=REGS_FIFO_TABLES,
          defines={"PULSE_TIMING_BY_SET": None, "POSITION_WITHOUT_HOMING": None},
          text="STEP widths, DIR set-up and hold (bounded)"),
    Group("regs_fifo_pulse_progress", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("pulse_request_leaves",),
          mode="bmc", depth=20, fast=False, expose=REGS_FIFO_REGISTERS,
          generated=REGS_FIFO_TABLES,
          defines={"PULSE_TIMING_BY_SET": None, "PULSE_PACED": None, "PULSE_QUEUE_CLOCKS": 4,
                   "MACHINE_RUNNING": None},
          text="every step request leaves on its pin within a step period (bounded)"),
    Group("regs_fifo_direct", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("direct_",), mode="bmc",
          depth=20, fast=False, expose=REGS_FIFO_REGISTERS, generated=REGS_FIFO_TABLES,
          defines={"DIRECT_COUNTS": None, "MACHINE_RUNNING": None},
          text="direct mode: a PULSE_COUNT write of n gives no more than |n| pulses of its axis, every axis (bounded)"),
    Group("regs_fifo_order", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("rf_fifo_in_order",),
          mode="bmc", depth=12, expose=REGS_FIFO_REGISTERS, generated=REGS_FIFO_TABLES,
          text="FIFO words reach the sequencer in order, none twice (bounded)"),
    Group("regs_fifo_commands", "regs_fifo", REGS_FILES, "regs_fifo_harness", ("cmd_",), mode="bmc",
          depth=14, fast=False, expose=REGS_FIFO_REGISTERS, generated=REGS_FIFO_TABLES,
          defines={"COMMANDS_WITHOUT_CLEAR": None, "MACHINE_RUNNING": None},
          text="LINE, ARC, SET and DWELL executed as the FIFO words say, in order (bounded)"),
    Group("machine_stop", "regs_fifo", MACHINE_FILES, "machine_harness", ("ms_", "minv_"), **MACHINE,
          text="E-stop, limits and the stop latch (docs/machine.md)"),
    Group("machine_reaction", "regs_fifo", MACHINE_FILES, "machine_harness", ("mr_",), mode="bmc", depth=20,
          **MACHINE, text="the input filter's reaction, E-stop pin to STEP and DRIVE_ENABLE (bounded)"),
    Group("machine_watchdog", "regs_fifo", MACHINE_FILES, "machine_harness", ("mw_",), mode="bmc",
          depth=16, defines={"WATCHDOG_SMALL": 8}, **MACHINE,
          text="the watchdog stops in time, never early (bounded, timeouts below 8)"),
    Group("machine_watchdog_write", "regs_fifo", MACHINE_FILES, "machine_harness", ("mwl_",), mode="bmc",
          depth=12, **MACHINE,
          text="a WATCHDOG write loads its value clamped to 24 bits: only 0 turns it off (bounded)"),
    Group("machine_drive", "regs_fifo", MACHINE_FILES, "machine_harness", ("md_", "minv_"), **MACHINE,
          text="no counted STEP outside DRIVE_ENABLE; only a new write re-energises after a stop"),
    Group("machine_hold", "regs_fifo", MACHINE_FILES, "machine_harness", ("fh_", "minv_"), **MACHINE,
          defines={"PATH_ONLY": None},
          text="feed hold and the decelerated stop (docs/machine.md)"),
    Group("machine_homing", "regs_fifo", MACHINE_FILES, "machine_harness", ("hm_", "minv_"), **MACHINE,
          text="homing: zero only at the release, refusals, one axis (docs/machine.md)"),
    Group("machine_homing_pins", "regs_fifo", MACHINE_FILES, "machine_harness", ("hp_",), mode="bmc", depth=20,
          **MACHINE, text="homing: no STEP on the other axis's pin (bounded)"),
    Group("encoder_count", "encoder", ENCODER_FILES, "encoder_harness", ("enc_count_",), depth=8,
          parameters=ENCODER_PARAMETERS, **ENCODER,
          text="no count without a legal transition of the filtered A, B; errors flagged and counted"),
    Group("encoder_index", "encoder", ENCODER_FILES, "encoder_harness", ("idx_",), depth=8, **ENCODER,
          text="the index latches the count at an armed rise, once per arm"),
    Group("encoder_pins", "encoder", ENCODER_FILES, "encoder_harness", ("enc_pins_",), mode="bmc",
          depth=24, defines={"ENCODER_PINS": None}, parameters=dict(ENCODER_PARAMETERS, PINS_FILTER_MAX=3),
          **ENCODER,
          text="legal pin transitions at every spacing the filter passes all counted (bounded, ENC_FILTER <= 3)"),
    Group("encoder_pins_wide", "encoder", ENCODER_FILES, "encoder_harness", ("enc_pins_",), mode="bmc",
          depth=48, defines={"ENCODER_PINS": None}, fast=False, **ENCODER,
          parameters=dict(ENCODER_PARAMETERS, PINS_FILTER_MAX=FILTER_MAX),
          text="the same at every ENC_FILTER 0 .. 15 (bounded)"),
    Group("following_error", "following_error", FERROR_FILES, "following_error_harness", ("fe_",), depth=4,
          convert=encoder_unit("following_error"),
          text="the following-error stop never within the limit, always beyond it; the error follows the count"),
    Group("probe_latch", "probe", PROBE_FILES, "probe_harness", ("prb_",), depth=8, convert=encoder_unit("probe"),
          expose=("level", "seen"), text="the probe latches every axis's count and POS at an armed rise, once per arm"),
    Group("dda_lines", "dda_arc", ["dda_harness.sv"], "dda_harness", ("dda_",), mode="bmc", depth=20,
          defines={"DDA_LINES": None, "DDA_FULL_SPEED": None}, **DDA,
          text="lines of the 6-bit DDA: steps, end point, end counters, finishing (bounded)"),
    Group("dda_arcs", "dda_arc", ["dda_harness.sv"], "dda_harness", ("dda_",), mode="bmc", depth=53,
          defines={"DDA_ARCS": None}, fast=False, **DDA,
          text="arcs of the 6-bit DDA: set-up and first iteration, refusals (bounded)"),
    Group("card_fifo_order", "card", CARD_FILES, "card_harness", ("card_fifo_",), depth=CARD_ORDER_DEPTH,
          **CARD, text="the whole card: bus dwords into BAR1 reach the sequencer in order, none twice (bounded)"),
    Group("card_status", "card", CARD_FILES, "card_harness",
          ("card_status_level", "card_status_empty", "card_status_full"), depth=CARD_STATUS_DEPTH, **CARD,
          text="the whole card: STATUS read on the bus tells the FIFO level, empty and full (bounded)"),
    Group("card_status_error", "card", CARD_FILES, "card_harness", ("card_status_error_",),
          depth=CARD_ERROR_DEPTH, defines={"MACHINE_RUNNING": None}, fast=False, **CARD,
          text="the whole card: STATUS.ERROR for the first command, as docs/instructions.md says (bounded)"),
    Group("card_covers", "card", CARD_FILES, "card_harness", ("card_cover_",), depth=CARD_ERROR_DEPTH,
          **dict(CARD, mode="cover"), fast=False,
          text="the whole card: the sequences the card groups judge are reachable within their depths"),
    Group("pci_covers", "pci_slave", PCI_FILES, "pci_target_harness", (), mode="cover", depth=24,
          parameters=PCI_PARAMETERS, generated=PCI_TABLE, text="each kind of transaction is reachable"),
]

# The card and machine properties on a build of more axes than gen/'s: the
# same harnesses, looping over the build's axes (formal/axes_props.py), on
# its regs_fifo.v or card.v converted into build/formal/generated/axes<N>/
# (the default suite keeps gen/'s groups; these run in the slow set)
MORE_AXES = {"axes": 3}
ON_MORE_AXES = ("regs_fifo_table", "regs_fifo_pulses", "regs_fifo_pulse_progress", "regs_fifo_direct",
                "machine_stop", "machine_reaction", "machine_watchdog", "machine_drive", "machine_hold",
                "machine_homing", "machine_homing_pins", "card_fifo_order", "card_status")


def on_build(item, values):
    """Group ``item`` on the build ``values`` (its unit converted, its includes generated for it)."""
    if item.unit == "card":
        settings = card(values)
    elif item.harness[-1] == "machine_harness.sv":
        settings = machine(values)
    else:
        helpers = tuple(name for name in item.expose if name in REGS_FIFO_HELPERS)   # its invariants' registers
        settings = dict(expose=regs_fifo_registers(values) + helpers, parameters=harness_parameters(values),
                        generated={**regs_tables(values), **ISA_TABLE})
    if "axes" in values:
        label, build_text = f"{values['axes']}axes", f"on a {values['axes']}-axis build, every axis"
    else:
        label, build_text = values["device"], f"on the {values['device']} build"
    return replace(item, **settings, name=f"{item.name}_{label}", build=dict(values), fast=False,
                   convert=partial(built_unit, item.unit, values), text=f"{item.text}; {build_text}")


GROUPS += [on_build(item, MORE_AXES) for item in GROUPS if item.name in ON_MORE_AXES]

# The FIFO's words into the sequencer on the ECP5 build, whose FIFO delivers its word
# from a fabric register (rtl/regs/sync_fifo.py, output_register); gen/'s reads the RAM's
ECP5_BUILD = {"device": "ecp5"}
GROUPS += [on_build(item, ECP5_BUILD) for item in GROUPS if item.name in ("regs_fifo_order", "regs_fifo_path")]

# The guard's FOLLOWING_ERROR stop on a build with encoders (two axes), through
# the real following-error units of regs_fifo, every encoder pin free
ENCODERS = {"encoders": 1}


def following_error_guard(**settings):
    """The settings of the groups of the following-error stop (machine_harness.sv, FERROR_GUARD)."""
    shared = machine(ENCODERS)
    return dict(shared, expose=shared["expose"] + ferror_registers(ENCODERS), build=dict(ENCODERS),
                generated={**shared["generated"], "ferror_axes.vh": partial(ferror_axes, ENCODERS),
                           "ferror_models.vh": partial(ferror_models, ENCODERS)},
                includes=("machine_following_error.vh",), defines={"FERROR_GUARD": None},
                convert=partial(built_unit, "regs_fifo", ENCODERS), fast=False,
                **settings)


FERROR_GUARD_DEPTH = 20
GROUPS += [
    Group("machine_following_error", "regs_fifo", MACHINE_FILES, "machine_harness", ("fg_",), mode="bmc",
          **following_error_guard(depth=FERROR_GUARD_DEPTH),
          text="encoders build: the FOLLOWING_ERROR stop only beyond the limit, always then, its AXIS, "
               "DRIVE_ENABLE low (bounded)"),
    Group("machine_following_error_covers", "regs_fifo", MACHINE_FILES, "machine_harness", ("fg_cover",),
          mode="cover", **following_error_guard(depth=FERROR_GUARD_DEPTH),
          text="encoders build: a FOLLOWING_ERROR stop of Y is reachable within the depth"),
]


def group(name):
    for item in GROUPS:
        if item.name == name:
            return item
    raise ValueError(f"no proof group {name!r}; groups: {', '.join(g.name for g in GROUPS)}")
