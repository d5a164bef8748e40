"""The PCI target's flip-flops at the bus: the input registers every bus line
but PAR passes first, and the output registers every driven line and
output enable but PAR comes from (``rtl/pci_slave.py``'s timing
architecture).

With ``io_registers`` the I/O cells (``rtl/pci/pci_pads.py``) hold AD,
C/BE#, IDSEL on the way in and AD, TRDY#, STOP#, DEVSEL#, PERR# on the way
out: the pins then carry the next values, the AD register's next value
one LUT per bit after IRDY# (``pin_lut``).  The AD register keeps its dword
while TRDY# is asserted and the master is not ready::

    edge         k     k+1   k+2
    IRDY#      ~~~~~~~~~~\\_______
    TRDY#      ~~~\\_____________      (trdy_q)
    AD out       X D0 ======X D1       D0 held until IRDY# takes it
"""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, instances, intbv

from rtl.pci.pin_lut import pin_lut


@block
def pci_boundary(clock, reset, pci, boundary, *, device, io_registers):
    """Ports: ``pci`` the target's ``PciBus``; ``boundary`` a
    ``TargetBoundary`` (the next values in, the registers out).
    Parameters: ``device`` (how the AD register's one-LUT paths are written,
    ``rtl/pci/pin_lut.py``), ``io_registers`` (True: the pads hold the
    boundary registers, see the module docstring).

        clock     _/~\\_/~\\_/~\\_
        trdy_next ==X=0===X=1===
        trdy_q    ======X=0===X=1     (io_registers: TRDY# out = trdy_next)
    """
    b = boundary
    # with io_registers the I/O cells register ad_out_next and have no enable:
    # one LUT per bit after IRDY# (``ad_output_luts``)
    ad_out_bits = [Signal(bool(0)) for _ in range(32)] if io_registers else []
    ad_out_next = ConcatSignal(*reversed(ad_out_bits)) if io_registers else Signal(intbv(0)[32:])

    if not io_registers:
        @always_seq(clock.posedge, reset=reset)
        def input_register():
            b.ad.next = pci.ad_in
            b.cbe.next = pci.cbe_in
            b.idsel.next = pci.idsel_in

    @always_seq(clock.posedge, reset=reset)
    def control_input_register():
        b.frame_q.next = pci.frame_in
        b.frame_qq.next = b.frame_q
        b.irdy_q.next = pci.irdy_in

    # The AD register takes new data unless the master has yet to take the
    # data on the bus (fast path: one LUT from IRDY#, as the register's
    # enable or, for the I/O cells, per bit).
    if io_registers:
        ad_output_luts = [
            pin_lut(ad_out_bits[bit], lambda irdy, trdy, held, fresh: int(
                held if irdy and not trdy else fresh),
                pci.irdy_in, b.trdy_q, b.ad_out(bit), b.read_source(bit), device=device) for bit in range(32)]
    else:
        @always_comb
        def ad_output():
            if pci.irdy_in and not b.trdy_q:   # TRDY# asserted, the master not ready
                ad_out_next.next = b.ad_out
            else:
                ad_out_next.next = b.read_source

    @always_seq(clock.posedge, reset=reset)
    def bus_registers():
        b.trdy_q.next = b.trdy_next
        b.stop_q.next = b.stop_next
        b.devsel_q.next = b.devsel_next
        b.ad_out.next = ad_out_next
        b.perr_q.next = b.perr_next
        b.ad_parity_q.next = b.ad_out_parity
        pci.trdy_oe.next = b.drive_next
        pci.stop_oe.next = b.drive_next
        pci.devsel_oe.next = b.drive_next
        pci.ad_oe.next = b.ad_oe_next
        pci.par_oe.next = pci.ad_oe
        pci.perr_oe.next = b.perr_oe_next
        pci.serr_out.next = False
        pci.serr_oe.next = b.serr_oe_next
        b.parity_error_q.next = b.parity_error_next
        pci.inta_out.next = False
        pci.inta_oe.next = b.irq and not b.interrupt_disable

    if io_registers:
        @always_comb
        def pins():
            pci.trdy_out.next = b.trdy_next
            pci.stop_out.next = b.stop_next
            pci.devsel_out.next = b.devsel_next
            pci.ad_out.next = ad_out_next
            pci.perr_out.next = b.perr_next
    else:
        @always_comb
        def pins():
            pci.trdy_out.next = b.trdy_q
            pci.stop_out.next = b.stop_q
            pci.devsel_out.next = b.devsel_q
            pci.ad_out.next = b.ad_out
            pci.perr_out.next = b.perr_q

    return instances()
