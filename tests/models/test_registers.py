"""The register table and the command set: consistency, and every file made from them."""
import shutil
import subprocess
from dataclasses import replace

import pytest

from models import instructions as isa
from models import register_docs
from models import registers as regmap
from models.card_model import RegisterModel
from rtl.convert import C_HEADER, GEN_DIR, ROOT, write_c_header


def test_table_is_consistent():
    regmap.check_table()
    assert regmap.IO_BAR_BITS == 8  # 0x90 is the last offset: a 256-byte I/O BAR, the most PCI allows


@pytest.mark.parametrize("change, message", [
    (dict(offset=0x06), "misaligned"),
    (dict(access="RX"), "unknown access"),
    (dict(reset=1 << 20), "reset value"),
])
def test_bad_table_entries_are_refused(change, message):
    bad = replace(regmap.register("LOW_WATER"), **change)
    with pytest.raises(ValueError, match=message):
        regmap.check_table(tuple(bad if r.name == "LOW_WATER" else r for r in regmap.REGISTERS))


def test_a_number_the_host_writes_declares_its_range():
    """Without a range a write too large for the field would be cut to its width
    (WATCHDOG 2**24 read 0: off) instead of clamped and flagged."""
    unbounded = replace(regmap.register("WATCHDOG"), minimum=None, maximum=None)
    with pytest.raises(ValueError, match="declares its range"):
        regmap.check_table(tuple(unbounded if r.name == "WATCHDOG" else r for r in regmap.REGISTERS))
    model = RegisterModel()
    assert model.write("WATCHDOG", 1 << regmap.WATCHDOG_BITS), "clamped, and INT_STATUS.CLAMPED says so"
    assert model.honour(regmap.register("WATCHDOG"), 0x1001388) == ((1 << regmap.WATCHDOG_BITS) - 1, True)


def test_duplicate_offset_is_refused():
    twin = replace(regmap.register("LOW_WATER"), name="TWIN")
    with pytest.raises(ValueError, match="used twice"):
        regmap.check_table(regmap.REGISTERS + (twin,))


# What the registers the hardware sets say right after reset (their descriptions in
# docs/registers.md): nothing has happened yet.
RESET_MEANING = {
    "ID": 0xDDAC << 16 | regmap.VERSION,
    "COMMAND": 0,  # one-shot actions read as 0
    "STATUS": 1 << 8,  # idle, not done, no error, FIFO_EMPTY, level 0
    "INT_STATUS": 0,
    "MARK_TAG": 0,
    "POS_X": 0,
    "POS_Y": 0,
    "PULSE_COUNT_X": 0,  # no direct pulse to go
    "PULSE_COUNT_Y": 0,
}


def test_reset_values_mean_what_the_registers_say():
    """sim/card/test_card_e2e.py reads the same values from the card after RST#."""
    assert {name: regmap.register(name).reset for name in RESET_MEANING} == RESET_MEANING
    assert regmap.field_value("STATUS", "FIFO_EMPTY", RESET_MEANING["STATUS"]) == 1
    for reg in regmap.REGISTERS:
        if reg.minimum is not None:
            assert reg.minimum <= regmap.field_value(reg.name, reg.fields[0].name, reg.reset) <= reg.maximum


def test_field_helpers_round_trip():
    word = regmap.field_of("STATUS", BUSY=1, ERROR=3, FIFO_LEVEL=300)
    assert word == 1 | 3 << 4 | 300 << 16
    assert regmap.field_value("STATUS", "FIFO_LEVEL", word) == 300
    assert regmap.field_value("POS_X", "STEPS", 0xFFFFFFFE) == -2
    with pytest.raises(ValueError, match="no field"):
        regmap.field_of("STATUS", SPEED=1)
    with pytest.raises(ValueError, match="no register"):
        regmap.offset("NOPE")


def test_encode_checks_its_input():
    assert isa.encode("ARC", 1, 2, 3, 4, CCW=1, VARIANT=2) == [0x2 << 28 | 1 | 2 << 1, 1, 2, 3, 4]
    assert isa.encode("LINE", -1, 2)[1] == 0xFFFFFFFF
    with pytest.raises(ValueError, match="takes 2 operands"):
        isa.encode("LINE", 1)
    with pytest.raises(ValueError, match="does not fit"):
        isa.encode("MARK", TAG=1 << 16)
    with pytest.raises(ValueError, match="unknown command"):
        isa.encode("JUMP")


def test_docs_are_generated_from_the_tables():
    docs = ROOT / "docs"
    assert (docs / "registers.md").read_text() == register_docs.markdown() + "\n", \
        "docs/registers.md is stale: run python -m models.register_docs"
    guide = (docs / "instructions.md").read_text()
    assert guide == register_docs.refreshed_instructions_doc(guide), \
        "docs/instructions.md is stale: run python -m models.register_docs"


def test_c_header_compiles_and_matches_the_table(tmp_path):
    header = write_c_header(tmp_path)
    assert (GEN_DIR / C_HEADER).read_text() == header.read_text(), \
        "gen/dda_card.h is stale: run python -m rtl.top --convert"
    compiler = shutil.which("gcc") or shutil.which("cc")
    if compiler is None:
        pytest.skip("no C compiler")
    probe = tmp_path / "probe.c"
    checks = [f'_Static_assert(DDA_{r.name} == {r.offset}u, "{r.name}");' for r in regmap.REGISTERS]
    checks.append(f"_Static_assert(DDA_STATUS_FIFO_LEVEL_MASK == {regmap.register('STATUS').field('FIFO_LEVEL').mask}u, \"mask\");")
    checks.append(f"_Static_assert(DDA_CMD_ARC == {isa.BY_NAME['ARC'].code}u, \"opcode\");")
    probe.write_text(f'#include "{header.name}"\n' + "\n".join(checks) + "\nint main(void) { return 0; }\n")
    result = subprocess.run([compiler, "-std=c11", "-Wall", "-Werror", "-I", str(tmp_path), str(probe),
                             "-o", str(tmp_path / "probe")], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


# The per-axis blocks as docs/pci.md lays them out: axis i at 0x100 + 0x40 * i in BAR2 (4 KiB),
# POS, PULSE_PERIOD, PULSE_COUNT first in each; written out, not computed from the table.
BLOCK_LAYOUT = {("POS", 0): 0x100, ("PULSE_PERIOD", 0): 0x104, ("PULSE_COUNT", 0): 0x108,
                ("POS", 1): 0x140, ("PULSE_COUNT", 1): 0x148, ("POS", 2): 0x180, ("PULSE_PERIOD", 2): 0x184,
                ("PULSE_COUNT", 2): 0x188, ("POS", 5): 0x240, ("PULSE_COUNT", 5): 0x248}


@pytest.mark.parametrize("name, axis", sorted(BLOCK_LAYOUT))
def test_per_axis_offsets_follow_the_documented_layout(name, axis):
    assert regmap.axis_offset(name, axis) == BLOCK_LAYOUT[name, axis]


def test_x_and_y_blocks_are_bar0_registers_and_the_others_their_own():
    assert [regmap.axis_register(name, 0).name for name in ("POS", "PULSE_PERIOD", "PULSE_COUNT")] == [
        "POS_X", "PULSE_PERIOD_X", "PULSE_COUNT_X"]
    assert regmap.axis_register("PULSE_COUNT", 1).offset == 0x50   # BAR0's PULSE_COUNT_Y
    assert regmap.axis_registers(2) == ()
    assert [(r.name, r.offset) for r in regmap.axis_registers(3)] == [
        ("POS_Z", 0x180), ("PULSE_PERIOD_Z", 0x184), ("PULSE_COUNT_Z", 0x188)]
    assert len(regmap.axis_registers(6)) == 12
    assert regmap.axis_aliases() == {0x100: 0x20, 0x104: 0x44, 0x108: 0x4C, 0x140: 0x24, 0x144: 0x48, 0x148: 0x50}
    # the I/O BAR stays within PCI's 256 bytes, BAR2 is 4 KiB with the blocks after BAR0's registers
    assert (1 << regmap.IO_BAR_BITS, 1 << regmap.REG_BAR_BITS) == (256, 4096)
    with pytest.raises(ValueError, match="axis 6"):
        regmap.axis_offset("POS", 6)


def test_a_changed_meaning_bumps_the_major_version():
    # 3.0: a helical ARC's lead operands changed meaning (ITERATIONS to AREA_LO, AREA_HI)
    (major, minor), (old_major, old_minor) = divmod(regmap.VERSION, 256), divmod(regmap.VERSIONS[-2][0], 256)
    assert (major, minor) == (old_major + 1, 0) == (3, 0)


@pytest.mark.parametrize("change, message", [
    (dict(offset=0x40), "outside its block"),
    (dict(set_index=9), "SET index"),
    (dict(minimum=0), "not the register"),     # X's and Y's block registers are BAR0's: same range
])
def test_a_block_register_that_does_not_fit_is_refused(change, message):
    bad = replace(regmap.AXIS_REGISTERS[1], **change)
    with pytest.raises(ValueError, match=message):
        regmap.check_axis_block((regmap.AXIS_REGISTERS[0], bad, regmap.AXIS_REGISTERS[2]))


# The encoder registers as docs/encoders.md lays them out: in every axis's block after POS, PULSE_PERIOD,
# PULSE_COUNT and the place kept for AXIS_HOME; written out, not computed from the table.
ENCODER_BLOCK = {"ENC_COUNT": 0x10, "ENC_STATUS": 0x14, "ENC_CONTROL": 0x18, "ENC_INDEX_LATCH": 0x1C, "ENC_TIME": 0x20,
                 "ENC_SCALE": 0x24, "FERROR_LIMIT": 0x28, "ENC_FERROR": 0x2C, "PROBE_ENC": 0x30, "PROBE_POS": 0x34}


@pytest.mark.parametrize("axis", range(6))
def test_encoder_registers_are_every_blocks_own_named_after_the_axis(axis):
    suffix = "XYZABC"[axis]
    for name, inside in ENCODER_BLOCK.items():
        reg = regmap.axis_register(name, axis)
        assert (reg.name, reg.offset, reg.option) == (f"{name}_{suffix}", 0x100 + 0x40 * axis + inside, "encoders")


def test_encoder_registers_exist_only_on_a_build_with_encoders():
    assert regmap.axis_registers(2) == ()
    with_encoders = regmap.axis_registers(2, {"encoders": 1})
    assert [r.name for r in with_encoders] == [f"{name}_{axis}" for axis in "XY" for name in ENCODER_BLOCK]
    assert len(regmap.axis_registers(3, {"encoders": 1})) == 3 + 3 * len(ENCODER_BLOCK)
    # X's and Y's block-only registers get no alias: BAR0 has no ENC_COUNT_X
    assert regmap.axis_aliases() == {0x100: 0x20, 0x104: 0x44, 0x108: 0x4C, 0x140: 0x24, 0x144: 0x48, 0x148: 0x50}
    assert [r.name for r in regmap.bar0_registers({"encoders": 1})][-2:] == ["TIMESTAMP", "PROBE_CONTROL"]
    assert "TIMESTAMP" not in [r.name for r in regmap.bar0_registers()]
    assert (regmap.offset("TIMESTAMP"), regmap.offset("PROBE_CONTROL"), 1 << regmap.IO_BAR_BITS) == (0xA4, 0xA8, 256)
    assert regmap.field_value("BUILD", "ENCODERS", regmap.build_word(regmap.register("BUILD"), {"encoders": 1})) == 1


def test_stop_reason_names_the_following_error_and_its_axis_clear_of_the_limits():
    reason = regmap.register("STOP_REASON")
    assert regmap.STOP_REASONS.index("FOLLOWING_ERROR") == 4
    assert (reason.field("AXIS").lsb, reason.field("AXIS").width) == (16, 3)
    # LIMITS has bits 15:4 (two per axis of the largest build), AXIS lies above it
    assert (reason.field("LIMITS").lsb, reason.field("LIMITS").width) == (4, 12)
    assert not reason.field("AXIS").mask & reason.field("LIMITS").mask
    assert regmap.field_value("STOP_REASON", "REASON", regmap.field_of("STOP_REASON", REASON=4, AXIS=1)) == 4


@pytest.mark.parametrize("change, message", [
    (dict(offset=0x0C), "kept free"),
    (dict(name="POS_Q", offset=0x38), None),   # a block-only register BAR0 lacks: allowed
])
def test_a_block_only_register_is_allowed_but_not_on_the_free_place(change, message):
    spec = replace(regmap.axis_spec("ENC_COUNT"), **change)
    if message is None:
        regmap.check_axis_block(regmap.AXIS_REGISTERS + (spec,))
        return
    with pytest.raises(ValueError, match=message):
        regmap.check_axis_block(regmap.AXIS_REGISTERS[:3] + (spec,))

