"""PCI pads: the card's only tri-states, joining ``PciPins`` to the core's ``PciBus``.

Two builds, chosen by ``io_registers`` (the top passes the same value to
``pci_slave``; it is the top's ``device``: ``models/parameters.py``):

- ``False`` (``generic``): plain tri-state buffers.  The core's
  boundary flip-flops are logic-cell flops; any vendor flow infers the I/O
  buffers.
- ``True`` (``ice40``): iCE40 ``SB_IO`` cells (``rtl/ice40.py``) whose input
  and output registers ARE the
  core's boundary flip-flops, so those PCI set-up and clock-to-output paths
  never cross the fabric.  AD, C/BE# and IDSEL are sampled in the I/O cell;
  AD, TRDY#, DEVSEL#, STOP# and PERR# leave from the I/O cell's output
  register, fed with the value the core wants on the pin after the next
  edge.  Output enables are not registered here: they come straight from
  the core's flip-flops, which have the asynchronous reset that iCE40 I/O
  registers lack, so RST# still floats the bus at once.  FRAME#, IRDY# and
  PAR reach the core unregistered: it needs them in the clock they arrive
  (fast path; PERR# two clocks after a data phase needs the PAR of the
  next clock).  PAR passes an ``SB_IO`` cell without registers: the core
  forms it from its AD and C/BE# registers, one LUT level before the pin.

Bus timing is the same in both builds.  SERR# and INTA# are open-drain
(driven low or released) in both.

Every pad is user-defined Verilog with a behavioural model for simulation.
A line nobody drives reads as its pull-up value (FRAME#, IRDY#: 1) or 0.
"""
from myhdl import Signal, always, block

from rtl.ice40 import PIN_PLAIN_IO, PIN_REGISTERED_INPUT, PIN_REGISTERED_IO, PIN_REGISTERED_OUTPUT, sb_io
from rtl.interfaces import PciBus, PciPins


def _line_value(pin, undriven):
    """What the core reads from ``pin``: its value, or ``undriven`` when released."""
    return undriven if pin.val is None else pin.val


@block
def tristate_pad(pin, from_pin, to_pin, enable, *, label=None, clock=None):
    """A plain tri-state buffer: ``pin`` shows ``to_pin`` while ``enable``.

    ``from_pin`` (None for a line the target never reads) follows the pin.
    No clock: the core's own flip-flops sit right behind it.  With
    ``label`` the buffer is written as iCE40 ``SB_IO`` cells without
    registers (``PIN_PLAIN_IO``, named ``<label>_<bit>``) instead of being
    left to inference: the same circuit, with cells a harness can look into.
    Their clock ports take ``clock``: unused without registers, but the two
    cells of an I/O tile share one clock net.

        enable    __/~~~~~~~~\\____
        to_pin    --< A >< B >----
        pin       zz< A >< B >zzzz
    """
    driver = pin.driver()

    @always(to_pin, enable)
    def drive():
        driver.next = int(to_pin.val) if enable else None

    code = f"assign $pin = $enable ? $to_pin : {{{len(pin)}{{1'bz}}}};\n"
    instances = [drive]
    if from_pin is not None:
        @always(pin)
        def sample():
            from_pin.next = _line_value(pin, 0)

        instances.append(sample)
        code += "assign $from_pin = $pin;\n"
        from_pin.driven = "wire"
    if label is not None:
        code = "".join(sb_io(label, index, len(pin), PIN_PLAIN_IO, from_pin is not None, True)
                       for index in range(len(pin)))
        pin.read = True
        clock.read = True
    pin.driven = "wire"
    to_pin.read = True
    enable.read = True
    tristate_pad.verilog_code = code
    return instances


@block
def input_pad(pin, from_pin, *, undriven):
    """A plain input: ``from_pin`` follows ``pin`` (``undriven`` when released).

        pin       --< A >< B >zzzz
        from_pin  --< A >< B >< undriven >
    """
    @always(pin)
    def follow():
        from_pin.next = _line_value(pin, undriven)

    from_pin.driven = "wire"
    pin.read = True
    input_pad.verilog_code = "assign $from_pin = $pin;\n"
    return follow


@block
def registered_pad(clock, pin, from_pin, to_pin, enable, *, label):
    """iCE40 ``SB_IO`` cells, one per bit of ``pin``, with I/O-cell registers.

    ``from_pin`` (None: not read) is the pin sampled at each ``clock`` edge in
    the input register.  With
    ``to_pin`` (None: input only) the pin shows, while ``enable``, the value
    ``to_pin`` had at the last edge (output register).  ``label`` prefixes
    the cell instance names.

        clock     _/~\\_/~\\_/~\\_
        to_pin    --< A >< B >--
        pin       -------< A >< B >    (while enable)
        pin       --< C >< D >------
        from_pin  -------< C >< D >
    """
    instances = []
    if to_pin is not None:
        driver = pin.driver()
        held = [0]  # the I/O cell's output register (not a Signal: nothing to convert)

        @always(clock.posedge)
        def output_cell():
            held[0] = int(to_pin.val)
            driver.next = held[0] if enable else None

        @always(enable)
        def drive():
            driver.next = held[0] if enable else None

        instances += [output_cell, drive]
        to_pin.read = True
        enable.read = True
    if from_pin is not None:
        @always(clock.posedge)
        def input_cell():
            from_pin.next = _line_value(pin, 0)

        instances.append(input_cell)
        from_pin.driven = "wire"
    # The cell's PACKAGE_PIN is an inout: the port must be one too.
    pin.driven = "wire"
    pin.read = True
    clock.read = True
    width = len(pin)
    if to_pin is None:
        pin_type = PIN_REGISTERED_INPUT
    else:
        pin_type = PIN_REGISTERED_IO if from_pin is not None else PIN_REGISTERED_OUTPUT
    registered_pad.verilog_code = "".join(
        sb_io(label, index, width, pin_type, from_pin is not None, to_pin is not None)
        for index in range(width))
    return instances


@block
def pci_pads(clock, pins, pci, *, io_registers=False):
    """The PCI pad ring of the card.

    Ports: ``clock`` PCI CLK (clocks the I/O cells with ``io_registers``),
    ``pins`` ``PciPins`` (the top level's ports), ``pci`` ``PciBus`` (the
    core's side).  Parameter: ``io_registers`` (bool), see the module text.

    ``io_registers=False`` (no clock in the path)::

        pci.ad_out    --< A >--      pins.ad  --< A >--   (while pci.ad_oe)
        pins.frame    --< F >--      pci.frame_in --< F >--

    ``io_registers=True`` (one I/O-cell register, which replaces the core's)::

        clock         _/~\\_/~\\_/~\\_
        pci.ad_out    --< A >-------      (the core's next value)
        pins.ad       -------< A >--      (while pci.ad_oe)
        pins.idsel    --< I >-------      (likewise AD, C/BE#)
        pci.idsel_in  -------< I >--
    """
    _check_io_registers(io_registers)
    unregistered = [
        tristate_pad(pins.serr, None, pci.serr_out, pci.serr_oe),
        tristate_pad(pins.inta, None, pci.inta_out, pci.inta_oe),
        input_pad(pins.frame, pci.frame_in, undriven=1),
        input_pad(pins.irdy, pci.irdy_in, undriven=1),
    ]
    if io_registers:
        return unregistered + [
            registered_pad(clock, pins.ad, pci.ad_in, pci.ad_out, pci.ad_oe, label="pad_ad"),
            tristate_pad(pins.par, pci.par_in, pci.par_out, pci.par_oe, label="pad_par", clock=clock),
            registered_pad(clock, pins.trdy, None, pci.trdy_out, pci.trdy_oe, label="pad_trdy"),
            registered_pad(clock, pins.devsel, None, pci.devsel_out, pci.devsel_oe, label="pad_devsel"),
            registered_pad(clock, pins.stop, None, pci.stop_out, pci.stop_oe, label="pad_stop"),
            registered_pad(clock, pins.perr, None, pci.perr_out, pci.perr_oe, label="pad_perr"),
            registered_pad(clock, pins.cbe, pci.cbe_in, None, None, label="pad_cbe"),
            registered_pad(clock, pins.idsel, pci.idsel_in, None, None, label="pad_idsel"),
        ]
    return unregistered + [
        tristate_pad(pins.ad, pci.ad_in, pci.ad_out, pci.ad_oe),
        tristate_pad(pins.par, pci.par_in, pci.par_out, pci.par_oe),
        tristate_pad(pins.trdy, None, pci.trdy_out, pci.trdy_oe),
        tristate_pad(pins.devsel, None, pci.devsel_out, pci.devsel_oe),
        tristate_pad(pins.stop, None, pci.stop_out, pci.stop_oe),
        tristate_pad(pins.perr, None, pci.perr_out, pci.perr_oe),
        input_pad(pins.cbe, pci.cbe_in, undriven=0),
        input_pad(pins.idsel, pci.idsel_in, undriven=0),
    ]


def _check_io_registers(io_registers):
    if not isinstance(io_registers, bool):
        raise ValueError(f"pci_pads: io_registers must be True or False, not {io_registers!r}")


def pci_pads_ports(io_registers=False):
    """Fresh ports of ``pci_pads`` (the same for both builds, so that the top
    takes either; ``io_registers`` is checked)."""
    _check_io_registers(io_registers)
    return {"clock": Signal(bool(0)), "pins": PciPins(), "pci": PciBus()}
