"""The per-axis wiring of the back end's, the machine side's and the whole
card's harnesses, generated for a build's axes (``models/registers.py``:
the machine inputs of ``input_names``, the limit bits of STOP_REASON.LIMITS;
``models/axes.py``: the axis names), so the harnesses loop over the axes the
build has (vectors indexed by axis: 0 X, 1 Y, 2 Z, ...) instead of naming X
and Y.

Each function takes the build (``values``: build parameters, the defaults
for the rest) and returns the text of one include:

* ``regs_fifo_axes``: the per-axis ports of ``regs_fifo`` (step requests,
  STEP/DIR pins, machine inputs, every axis's direct-pulse request made a
  port by ``expose``), included inside its instance;
* ``machine_axes``: the per-axis registers of ``regs_fifo`` the machine
  harness exposes (merged requests, the guard's grants, the pulse outputs'
  pulses, the direct pulses' loads);
* ``axes_inputs``: which machine input is which axis's limit or home
  switch, which STOP_REASON.LIMITS bit is which limit, the inputs that stop
  the card;
* ``card_axes``: the per-axis pins of ``card``;
* ``ferror_axes``: on a build with encoders, each axis's following-error
  check as the guard's harness reads it (ENC_FERROR, its limit, align and
  clear strobes; the flags the guard takes).

The netlist names of a unit's per-axis registers come from the converter:
X's and Y's merged requests and direct requests are named at the top of
``rtl/regs_fifo.py``, the other axes' inside the guard and the direct-pulse
units (``axis_register_names``).
"""
from models import registers as regmap
from models.axes import AXIS_NAMES
from models.parameters import PARAMETERS

NAMED_AXES = 2   # X and Y: rtl/regs_fifo.py names their requests at its top


def build_axes(values=None):
    """The number of axes of the build ``values``."""
    return dict(values or {}).get("axes", PARAMETERS["axes"].default)


def has_encoders(values=None):
    """Whether the build ``values`` has encoders (and the following-error stop)."""
    return bool(dict(values or {}).get("encoders", PARAMETERS["encoders"].default))


def axis_register_names(axes):
    """{kind: [netlist name of axis 0, 1, ...]} of the per-axis registers and
    wires of ``regs_fifo`` the harnesses make ports (``expose``)."""
    names = [name.lower() for name in AXIS_NAMES[:axes]]
    return dict(
        request_step=[f"requests_step_{n}" if a < NAMED_AXES else f"machine_guard0_grant_{n}_request_step"
                      for a, n in enumerate(names)],
        request_dir=[f"requests_dir_{n}" if a < NAMED_AXES else f"machine_guard0_grant_{n}_request_dir"
                     for a, n in enumerate(names)],
        direct_request=[f"direct_request_{n}" if a < NAMED_AXES else f"direct_pulse{a}_out_step"
                        for a, n in enumerate(names)],
        granted_step=[f"machine_guard0_grant_{n}_granted_step" for n in names],
        pulse=[f"pulse_out0_axis_{n}_pulse" for n in names],
        direct_pending=[f"direct_pulse{a}_pending" for a in range(axes)],
        ferror_error=[f"encoder_block0_axis_{n}_check_error" for n in names],
        ferror_limit=[f"encoder_block0_axis_{n}_check_limit" for n in names],
        ferror_align=[f"encoder_block0_axis_{n}_check_align" for n in names],
        ferror_clear=[f"encoder_block0_axis_{n}_check_clear_stop" for n in names])


FERROR_VECTORS = ("ferror_error", "ferror_limit", "ferror_align", "ferror_clear")
FERROR_FLAGS = "encoder_block0_regs_ferror"   # the following-error flags the guard takes (bit i: axis i)
GUARD_AXIS = "machine_guard0_guard_axis"      # STOP_REASON.AXIS as the guard latches it


def ferror_registers(values=None):
    """The registers and wires of regs_fifo the following-error groups make ports."""
    names = axis_register_names(build_axes(values))
    return (FERROR_FLAGS, GUARD_AXIS, *(name for kind in FERROR_VECTORS for name in names[kind]))


def harness_parameters(values=None):
    """`chparam` settings of the harnesses for the build: AXES, INPUTS (machine inputs)."""
    axes = build_axes(values)
    return dict(AXES=axes, INPUTS=len(regmap.input_names(axes)))


def _connections(pairs):
    return "".join(f"        , .{port}({signal})\n" for port, signal in pairs)


def _pins(axes, step, direction, inputs):
    pairs = []
    for axis, name in enumerate(AXIS_NAMES[:axes]):
        pairs += [(f"pins_step_{name.lower()}", f"{step}[{axis}]"),
                  (f"pins_dir_{name.lower()}", f"{direction}[{axis}]")]
    pairs += [(f"pins_{name.lower()}", f"{inputs}[{bit}]") for bit, name in enumerate(regmap.input_names(axes))]
    return pairs


def _header(users):
    return (f"// Generated from models/registers.py and models/axes.py by formal/axes_props.py; do not edit.\n"
            f"// Included into {users}.\n")


def regs_fifo_axes(values=None):
    """The per-axis ports of ``regs_fifo`` (inside its instance, after regs_fifo_ports.vh)."""
    axes = build_axes(values)
    pairs = []
    for axis, name in enumerate(AXIS_NAMES[:axes]):
        pairs += [(f"steps_step_{name.lower()}", f"steps_step[{axis}]"),
                  (f"steps_dir_{name.lower()}", f"steps_dir[{axis}]")]
    pairs += _pins(axes, "pins_step", "pins_dir", "machine_in")
    pairs += [(name, f"direct_request[{axis}]")
              for axis, name in enumerate(axis_register_names(axes)["direct_request"])]
    if has_encoders(values):   # free encoder pins and probe (regs_fifo_env.vh)
        for axis, name in enumerate(AXIS_NAMES[:axes]):
            pairs += [(f"pins_enc_{pin}_{name.lower()}", f"enc_{pin}[{axis}]") for pin in ("a", "b", "index")]
        pairs.append(("pins_probe", "probe"))
    return _header("the regs_fifo instance of regs_fifo_harness and machine_harness") + _connections(pairs)


MACHINE_VECTORS = ("request_step", "request_dir", "granted_step", "pulse", "direct_pending")


def machine_axes(values=None):
    """The per-axis registers of ``regs_fifo`` the machine harness reads (inside its instance)."""
    names = axis_register_names(build_axes(values))
    pairs = [(name, f"{kind}[{axis}]") for kind in MACHINE_VECTORS for axis, name in enumerate(names[kind])]
    return _header("the regs_fifo instance of machine_harness") + _connections(pairs)


def axes_inputs(values=None):
    """Wires from the filtered inputs (``conditioning_active``): each axis's
    limits and home switch; ``limit_bits`` (a request towards each limit, in
    STOP_REASON.LIMITS's order) from ``towards_pos``/``towards_neg``; the
    inputs that stop the card (E-stop and the limits)."""
    axes = build_axes(values)
    inputs = regmap.input_names(axes)
    text = _header("machine_harness")

    def vector(name, bits):   # axis 0 rightmost
        return f"    wire [AXES-1:0] {name} = {{{', '.join(bits[::-1])}}};\n"

    text += vector("limit_pos_active", [f"conditioning_active[{regmap.limit_input(a, True)}]" for a in range(axes)])
    text += vector("limit_neg_active", [f"conditioning_active[{regmap.limit_input(a, False)}]" for a in range(axes)])
    text += vector("home_active", [f"conditioning_active[{regmap.home_input(a)}]" for a in range(axes)])
    order = {regmap.limit_bit(a, positive): f"towards_{'pos' if positive else 'neg'}[{a}]"
             for a in range(axes) for positive in (True, False)}
    text += f"    wire [2*AXES-1:0] limit_bits = {{{', '.join(order[bit] for bit in sorted(order, reverse=True))}}};\n"
    stopping = sum(1 << bit for bit, name in enumerate(inputs) if name == "ESTOP" or name.startswith("LIMIT_"))
    text += f"    localparam [INPUTS-1:0] STOPPING_INPUTS = {len(inputs)}'h{stopping:X};   // E-stop and the limits\n"
    return text


def ferror_axes(values=None):
    """On a build with encoders: each axis's following-error check (the unit's ENC_FERROR,
    limit, align and clear strobes, 32 bits an axis for the words), the flags the guard
    takes, STOP_REASON.AXIS as latched (inside the regs_fifo instance of machine_harness)."""
    names = axis_register_names(build_axes(values))
    pairs = [(FERROR_FLAGS, "ferror_flags"), (GUARD_AXIS, "guard_axis")]
    for kind in FERROR_VECTORS:
        wide = kind in ("ferror_error", "ferror_limit")
        pairs += [(name, f"{kind}[{32 * axis + 31}:{32 * axis}]" if wide else f"{kind}[{axis}]")
                  for axis, name in enumerate(names[kind])]
    return _header("the regs_fifo instance of machine_harness (FERROR_GUARD)") + _connections(pairs)


def ferror_models(values=None):
    """On a build with encoders: FERROR_LIMIT of every axis as the register table's models
    hold it (``model_ferror_limit_<axis>``, regs_table.vh), 32 bits an axis."""
    axes = build_axes(values)
    width = regmap.axis_spec("FERROR_LIMIT").width
    pad = f"{32 - width}'h0, " if width < 32 else ""
    words = [f"{{{pad}model_ferror_limit_{name.lower()}}}" for name in AXIS_NAMES[:axes]]
    return (_header("machine_harness (FERROR_GUARD)")
            + f"    wire [32*AXES-1:0] ferror_limit_model = {{{', '.join(words[::-1])}}};\n")


def card_axes(values=None):
    """The per-axis pins of ``card`` (inside its instance)."""
    return _header("the card instance of card_harness") + _connections(
        _pins(build_axes(values), "step", "dir", "machine_in"))
