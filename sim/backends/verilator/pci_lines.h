// The PCI lines of the bus segment the harness resolves (card_bus.h) and
// their electrical rules: width, pulled up when nobody drives, open drain.
#ifndef PCI_LINES_H
#define PCI_LINES_H

namespace {

// PCI lines, in the order of sim/pci/bus.py's LINE_WIDTHS.
enum Line { AD, CBE, PAR, FRAME, IRDY, TRDY, DEVSEL, STOP, PERR, SERR, INTA, LINES };
const int kLineWidth[LINES] = {32, 4, 1, 1, 1, 1, 1, 1, 1, 1, 1};
const bool kPulledUp[LINES] = {false, false, false, true, true, true, true, true, true, true, true};
const bool kOpenDrain[LINES] = {false, false, false, false, false, false, false, false, false, true, true};

}  // namespace

#endif  // PCI_LINES_H
