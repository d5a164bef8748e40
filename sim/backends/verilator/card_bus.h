// The card's side of the PCI bus segment the harness resolves each clock:
// which lines the card drives, INTA#, and the segment from the host's drive
// and the card's (the rules of sim/pci/bus.py, pci_lines.h's constants).
#ifndef CARD_BUS_H
#define CARD_BUS_H

#include <cstdint>

#include "card.h"

namespace {

// The card's drive of a line: true when enabled, its value in *value.
bool Card::card_drive(int line, uint64_t* value) const {
    if (line_out[line] < 0 || line_oe[line] < 0 || !get(line_oe[line])) return false;
    *value = get(line_out[line]);
    return true;
}

bool Card::interrupt_asserted() const {
    uint64_t value = 1;
    return card_drive(INTA, &value) && value == 0;
}

// Whether the card drives any line but INTA# (nothing may move on a quiet bus).
bool Card::drives_bus() const {
    uint64_t value;
    for (int line = 0; line < LINES; ++line)
        if (line != INTA && card_drive(line, &value)) return true;
    return false;
}

// Resolve the segment from the host's drive and the card's (the rules of
// sim/pci/bus.py); feed the card's inputs.  values[l], driven[l] (bit 0
// host, bit 1 card), floating[l].
void Card::resolve(const uint64_t* host_out, const uint64_t* host_oe, uint64_t* values, uint64_t* drivers,
                   uint64_t* floating) {
    for (int line = 0; line < LINES; ++line) {
        uint64_t card_value = 0;
        bool card = card_drive(line, &card_value);
        bool host = host_oe[line] != 0;
        uint64_t host_value = host_out[line] & mask(kLineWidth[line]);
        drivers[line] = (host ? 1 : 0) | (card ? 2 : 0);
        floating[line] = 0;
        if (kOpenDrain[line]) {
            values[line] = ((host && host_value == 0) || (card && card_value == 0)) ? 0 : 1;
        } else if (host || card) {
            values[line] = (host ? host_value : 0) | (card ? card_value : 0);
        } else if (kPulledUp[line]) {
            values[line] = 1;
        } else {
            values[line] = 0;
            floating[line] = 1;
        }
        if (line_in[line] >= 0) set(line_in[line], values[line]);
    }
    if (idsel >= 0) set(idsel, (values[AD] >> idsel_bit) & 1);
}

}  // namespace

#endif  // CARD_BUS_H
