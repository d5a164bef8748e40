"""The PCI target's parity: PAR on reads, PERR# and SERR# on errors.

PCI Local Bus 2.3, section 3.7: PAR is even parity over AD[31:0] and
C/BE#[3:0], driven one clock after the AD it covers (3.7.1); a target
asserts PERR# two clocks after a write data phase with a parity error
(3.7.4.1) and SERR# two clocks after an address phase with one (3.7.4.2),
when Parity Error Response (and for SERR#, SERR# Enable) is set.

PAR comes straight from its pin, with no clock for a register in between:
the parity of the input registers is folded first, and one LUT per register
that needs the pin in this clock (PERR#, its driver, SERR#, the claim's
abort, the Status bit) compares them (``rtl/pci/pin_lut.py``)::

    edge        k        k+1      k+2
    AD, C/BE#   <data>
    PAR                  <par>              checked at k+1 against the
    PERR#                         \\___/     registered AD, C/BE# of k
"""
from myhdl import Signal, always_comb, block, instances, intbv

from rtl.pci.pin_lut import pin_lut


@block
def pci_parity(par_pin, parity, *, device):
    """Ports: ``par_pin`` PAR as it arrives; ``parity`` a ``TargetParity``.

    Parameters: ``device``, how the LUTs after the PAR pin are written
    (``rtl/pci/pin_lut.py``).
    """
    bus_parity = Signal(bool(0))      # parity of the AD and C/BE# input registers
    serr_armed = Signal(bool(0))      # SERR# follows an address parity error
    perr_armed = Signal(bool(0))      # PERR# follows a write data parity error

    @always_comb
    def parity_check():
        # PAR sampled now covers the AD and C/BE# in the input register.
        fold = intbv(0)[32:]
        fold[:] = parity.ad
        fold[4:] = fold[4:] ^ parity.cbe
        fold[16:] = fold[16:] ^ fold[32:16]
        fold[8:] = fold[8:] ^ fold[16:8]
        fold[4:] = fold[4:] ^ fold[8:4]
        fold[2:] = fold[2:] ^ fold[4:2]
        fold[1:] = fold[1:] ^ fold[2:1]
        bus_parity.next = fold[0]

    @always_comb
    def parity_errors():
        # what a wrong PAR at this edge would report (``parity_luts``)
        parity.address_phase.next = parity.frame_qq and not parity.frame_q
        serr_armed.next = (parity.frame_qq and not parity.frame_q and parity.serr_enable
                           and parity.parity_response)
        perr_armed.next = parity.write_done and parity.parity_response

    # PAR comes straight from its pin: one LUT from it to each register that
    # needs it in this clock (PERR#, SERR#, the claim's abort, the status).
    parity_luts = [
        pin_lut(parity.perr_next, lambda par, expected, armed: int(not (armed and par != expected)),
                par_pin, bus_parity, perr_armed, device=device),
        pin_lut(parity.perr_oe_next, lambda par, expected, armed, perr: int(
            (armed and par != expected) or not perr),   # asserted, then high one clock
            par_pin, bus_parity, perr_armed, parity.perr_q, device=device),
        pin_lut(parity.serr_oe_next, lambda par, expected, armed: int(armed and par != expected),
                par_pin, bus_parity, serr_armed, device=device),
        pin_lut(parity.address_fault_next, lambda par, expected, phase, response: int(
            phase and response and par != expected),
            par_pin, bus_parity, parity.address_phase, parity.parity_response, device=device),
        pin_lut(parity.parity_error_next, lambda par, expected, phase, written: int(
            (phase or written) and par != expected),
            par_pin, bus_parity, parity.address_phase, parity.write_done, device=device)]

    @always_comb
    def parity_output():
        # PAR covers the AD and C/BE# of the clock before (both now registered)
        cbe = parity.cbe
        parity.par_out.next = parity.ad_out_parity_q ^ cbe[0] ^ cbe[1] ^ cbe[2] ^ cbe[3]

    @always_comb
    def ad_out_parity_tree():
        fold = intbv(0)[32:]
        fold[:] = parity.ad_out
        fold[16:] = fold[16:] ^ fold[32:16]
        fold[8:] = fold[8:] ^ fold[16:8]
        fold[4:] = fold[4:] ^ fold[8:4]
        fold[2:] = fold[2:] ^ fold[4:2]
        fold[1:] = fold[1:] ^ fold[2:1]
        parity.ad_out_parity.next = fold[0]

    return instances()
