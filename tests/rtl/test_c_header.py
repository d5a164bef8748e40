"""``gen/dda_card.h`` as C sees it: the build's PCI identity and BAR sizes, and
command builders that give the words ``models.instructions.encode`` gives.

A C program (and the same as C++) built with every warning as an error calls
each builder, the two-axis ones (``dda_cmd_line``, ...) and the N-axis ones
(``dda_cmd_line_axes``, ``dda_cmd_arc_helix``, ``dda_cmd_pulse_axes``: an
array indexed by axis), with seeded random and edge operands and header
fields, and prints the words; every word is compared with the Python
encoder.  A header field that does not fit is refused by both (``encode``
raises, the builder returns 0 and writes nothing).
"""
import random
import shutil
import subprocess

import pytest

from models import instructions as isa
from models.axes import MAX_AXES, axes_of
from models.registers import IO_BAR_BITS
from rtl.card import MEM_BAR_BITS
from rtl.convert import write_c_header

COMPILERS = {"c": (shutil.which("gcc") or shutil.which("cc"), ["-std=c99"], "probe.c"),
             "c++": (shutil.which("g++") or shutil.which("c++"), ["-std=c++11"], "probe.cpp")}
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]
CALLS_PER_OPCODE = 300
SIGNED_EDGES = (-(1 << 31), -(1 << 23), -1, 0, 1, (1 << 23) - 1, (1 << 31) - 1)
UNSIGNED_EDGES = (0, 1, (1 << 31), (1 << 32) - 1)
BUILD = dict(vendor_id=0xABCD, device_id=0x0123, revision_id=0x7F, class_code=0x0B4000,
             subsystem_vendor_id=0xFEDC, subsystem_id=0x8001, fifo_depth=64)


def compile_and_run(kind, header, source, tmp_path):
    compiler, standard, name = COMPILERS[kind]
    if compiler is None:
        pytest.skip(f"no {kind} compiler")
    program = tmp_path / name
    program.write_text(source)
    built = subprocess.run([compiler, *standard, *WARNINGS, "-I", str(header.parent), str(program),
                            "-o", str(tmp_path / f"probe_{kind}")], capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
    return subprocess.run([str(tmp_path / f"probe_{kind}")], capture_output=True, text=True, check=True).stdout


def operand(rng, signed):
    if rng.random() < 0.3:
        return rng.choice(SIGNED_EDGES if signed else UNSIGNED_EDGES)
    return rng.randint(-(1 << 31), (1 << 31) - 1) if signed else rng.getrandbits(32)


def random_calls(seed):
    """(opcode, operands, header fields): edge and random values, some fields too wide."""
    rng = random.Random(seed)
    calls = []
    for op in isa.OPCODES:
        for index in range(CALLS_PER_OPCODE):
            operands = [operand(rng, name in isa.SIGNED_OPERANDS) for name in op.operands]
            fields = {}
            for name, _, width, _ in op.header_fields:
                limit = (1 << width) - 1
                fields[name] = rng.choice([0, limit, rng.randint(0, limit), rng.randint(0, limit)])
            if op.header_fields and index % 10 == 9:  # one field just too wide, or far too wide
                name, _, width, _ = rng.choice(op.header_fields)
                fields[name] = rng.choice([1 << width, (1 << 32) - 1])
            calls.append((op, operands, fields))
    return calls


def c_call(op, operands, fields):
    arguments = ["words"] + [c_literal(value, name in isa.SIGNED_OPERANDS)
                             for name, value in zip(op.operands, operands)]
    arguments += [f"{fields[name]}u" for name, _, _, _ in op.header_fields]
    return f"    report(dda_cmd_{op.name.lower()}({', '.join(arguments)}), words);"


def random_axis_calls(seed):
    """(opcode, fixed operands, array indexed by axis, header fields) for the N-axis builders."""
    rng = random.Random(seed)
    calls = []
    for op in (o for o in isa.OPCODES if o.axis_operands):
        spec = op.axis_operands
        for index in range(CALLS_PER_OPCODE):
            fixed = [operand(rng, name in isa.SIGNED_OPERANDS) for name in op.fixed_operands + spec.lead]
            array = [operand(rng, True) for _ in range(MAX_AXES)]
            fields = {}
            for name, _, width, _ in op.fields:
                limit = (1 << width) - 1
                fields[name] = rng.choice([0, limit, rng.randint(0, limit), rng.randint(0, limit)])
            if index % 10 == 9:
                name, _, width, _ = rng.choice(op.fields)
                fields[name] = rng.choice([1 << width, (1 << 32) - 1])
            calls.append((op, fixed, array, fields))
    return calls


def c_axis_call(op, fixed, array, fields):
    spec = op.axis_operands
    names = op.fixed_operands + spec.lead
    arguments = ["words"] + [c_literal(value, name in isa.SIGNED_OPERANDS) for name, value in zip(names, fixed)]
    arguments += [f"{fields[spec.field]}u", "axis_values"]
    arguments += [f"{fields[name]}u" for name, _, _, _ in op.fields if name != spec.field]
    values = ", ".join(c_literal(v, True) for v in array)
    return (f"    {{ const int32_t axis_values[DDA_AXES_MAX] = {{{values}}};\n"
            f"      report(dda_cmd_{spec.builder}({', '.join(arguments)}), words); }}")


def python_axis_words(op, fixed, array, fields):
    """``isa.encode``'s words for an N-axis builder's call: the fixed operands, the
    lead operands when the mask is not 0, the array's values of the mask's axes."""
    spec = op.axis_operands
    mask = fields[spec.field]
    operands = list(fixed[:len(op.fixed_operands)])
    if mask:
        operands += fixed[len(op.fixed_operands):]
    operands += [array[axis] for axis in axes_of(mask or spec.zero_mask)]
    return isa.encode(op.name, *operands, **fields)


def c_literal(value, signed):
    if not signed:
        return f"{value}u"
    # INT32_MIN has no literal of its own
    return f"(-{-value - 1} - 1)" if value < 0 else f"{value}"


@pytest.mark.parametrize("kind", sorted(COMPILERS))
def test_command_builders_give_the_words_of_the_python_encoder(kind, tmp_path):
    header = write_c_header(tmp_path)
    calls = random_calls(seed=13)
    source = "\n".join([
        '#include <stdio.h>', '#include <string.h>', '#include "dda_card.h"', "",
        "static void report(unsigned count, const uint32_t *words)", "{",
        '    printf("%u", count);',
        "    for (unsigned i = 0; i < count; i++)", '        printf(" %08lx", (unsigned long)words[i]);',
        '    printf("\\n");', "}", "",
        "int main(void)", "{", "    uint32_t words[8];",
        *[c_call(op, operands, fields) for op, operands, fields in calls],
        "    return 0;", "}", ""])
    lines = compile_and_run(kind, header, source, tmp_path).splitlines()
    assert len(lines) == len(calls)
    refused = 0
    for (op, operands, fields), line in zip(calls, lines):
        count, *words = line.split()
        try:
            wanted = isa.encode(op.name, *operands, **fields)
        except ValueError:
            assert count == "0" and not words, f"{op.name} {operands} {fields}: {line}"
            refused += 1
            continue
        assert [int(w, 16) for w in words] == wanted and int(count) == len(wanted), \
            f"{op.name} {operands} {fields}: C {line}, Python {[hex(w) for w in wanted]}"
    assert refused >= CALLS_PER_OPCODE // 10 * sum(1 for op in isa.OPCODES if op.header_fields)


@pytest.mark.parametrize("kind", sorted(COMPILERS))
def test_n_axis_builders_give_the_words_of_the_python_encoder(kind, tmp_path):
    header = write_c_header(tmp_path)
    calls = random_axis_calls(seed=26)
    source = "\n".join([
        '#include <stdio.h>', '#include "dda_card.h"', "",
        "static void report(unsigned count, const uint32_t *words)", "{",
        '    printf("%u", count);',
        "    for (unsigned i = 0; i < count; i++)", '        printf(" %08lx", (unsigned long)words[i]);',
        '    printf("\\n");', "}", "",
        "int main(void)", "{", "    uint32_t words[DDA_CMD_MAX_WORDS];",
        *[c_axis_call(*call) for call in calls],
        "    return 0;", "}", ""])
    lines = compile_and_run(kind, header, source, tmp_path).splitlines()
    assert len(lines) == len(calls)
    refused = 0
    for (op, fixed, array, fields), line in zip(calls, lines):
        count, *words = line.split()
        try:
            wanted = python_axis_words(op, fixed, array, fields)
        except ValueError:
            assert count == "0" and not words, f"{op.name} {fixed} {array} {fields}: {line}"
            refused += 1
            continue
        assert [int(w, 16) for w in words] == wanted and int(count) == len(wanted), \
            f"{op.name} {fixed} {array} {fields}: C {line}, Python {[hex(w) for w in wanted]}"
    assert refused >= CALLS_PER_OPCODE // 10 * 3


def test_a_refused_command_writes_nothing(tmp_path):
    header = write_c_header(tmp_path)
    source = "\n".join([
        '#include <stdio.h>', '#include "dda_card.h"', "",
        "int main(void)", "{",
        "    uint32_t words[5] = {1u, 2u, 3u, 4u, 5u};",
        "    unsigned count = dda_cmd_arc(words, 1, 2, 3, 4, 2u, 0u, 0u, 0u, 0u);",
        '    printf("%u %lu %lu %lu %lu %lu\\n", count, (unsigned long)words[0], (unsigned long)words[1],',
        "           (unsigned long)words[2], (unsigned long)words[3], (unsigned long)words[4]);",
        "    return 0;", "}", ""])
    assert compile_and_run("c", header, source, tmp_path).split() == ["0", "1", "2", "3", "4", "5"]


def test_pci_identity_and_bar_sizes_follow_the_build(tmp_path):
    """A build with other IDs: the header says what the converter was given, and
    the BAR sizes the card decodes (``rtl/card.py``: I/O from the register map,
    a 4 KiB memory window, 4 KiB of registers in memory space: BAR0's, then
    the per-axis blocks, docs/pci.md)."""
    header = write_c_header(tmp_path, **BUILD)
    checks = [f"_Static_assert(DDA_PCI_{name.upper()} == {value}u, \"{name}\");"
              for name, value in BUILD.items() if name != "fifo_depth"]
    checks += [f"_Static_assert(DDA_FIFO_DEPTH == {BUILD['fifo_depth']}u, \"fifo_depth\");",
               f"_Static_assert(DDA_BAR0_SIZE == {1 << IO_BAR_BITS}u, \"BAR0\");",
               "_Static_assert(DDA_BAR1_SIZE == 4096u, \"BAR1\");",
               f"_Static_assert(DDA_BAR1_SIZE == {1 << MEM_BAR_BITS}u, \"BAR1 of the card\");",
               # BAR2: BAR0's registers at 0x000..0x0FF, the six axes' blocks from 0x100 (docs/pci.md)
               "_Static_assert(DDA_BAR2_SIZE == 4096u, \"BAR2\");",
               "_Static_assert(DDA_BAR0_SIZE <= DDA_AXIS_BLOCK_BASE, \"the blocks after BAR0's registers\");",
               "_Static_assert(DDA_AXIS_POS_OFFSET(5) + 4u <= DDA_BAR2_SIZE, \"six blocks in BAR2\");"]
    compiler = COMPILERS["c"][0]
    if compiler is None:
        pytest.skip("no C compiler")
    probe = tmp_path / "ids.c"
    probe.write_text('#include "dda_card.h"\n' + "\n".join(checks) + "\nint main(void) { return 0; }\n")
    built = subprocess.run([compiler, "-std=c11", *WARNINGS, "-I", str(tmp_path), str(probe),
                            "-o", str(tmp_path / "ids")], capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
