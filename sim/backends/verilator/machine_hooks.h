// The simulated machine's hooks in the card's clock loop: the machine
// (sim_machine.h) clocked on the card's STEP/DIR pins after each edge, its
// switch and E-stop inputs and its motors' encoder pins driven into the
// card's ports, every change recorded.  models/sim_machine.py is its
// definition, clock for clock.
#ifndef MACHINE_HOOKS_H
#define MACHINE_HOOKS_H

#include <cstdint>

#include "card.h"

namespace {

// The machine's inputs to the card's ports (the next rising edge takes
// them); a change of them or of DRIVE_ENABLE (bit kDriveBit) is recorded.
void Card::drive_inputs(bool enabled) {
    Machine& m = machine;
    uint32_t word = m.word() | (enabled ? 1u << kDriveBit : 0u);
    for (int input = 0; input < m.input_count; ++input)
        if (m.inputs[input] >= 0) set(m.inputs[input], (word >> input) & 1);
    if (word != m.pins) {
        m.change_clocks.push_back(clocks);
        m.change_pins.push_back(word);
        m.pins = word;
    }
}

// The motors' encoder pins to the card's ports; a change is recorded.
void Card::drive_encoders() {
    Machine& m = machine;
    uint32_t word = m.encoder_word();
    for (int axis = 0; axis < m.axes; ++axis)
        for (int pin = 0; pin < 3; ++pin)
            if (m.motors[axis].ports[pin] >= 0) set(m.motors[axis].ports[pin], (word >> (3 * axis + pin)) & 1);
    if (word != m.encoder_pins) {
        m.encoder_clocks.push_back(clocks);
        m.encoder_words.push_back(word);
        m.encoder_pins = word;
    }
}

// One clock of models/sim_machine.py's SimMachine on the pins after an edge
// (axis i's STEP at bit 2i of `state`, its DIR at 2i + 1).
void Card::machine_clock(unsigned state) {
    Machine& m = machine;
    bool enabled = m.drive >= 0 && get(m.drive);
    ++m.clocks;
    for (int axis = 0; axis < m.axes; ++axis) {
        Motor& motor = m.motors[axis];
        bool step = (state >> (2 * axis)) & 1;
        bool dir = (state >> (2 * axis + 1)) & 1;
        bool rose = step && !m.step_before[axis];
        m.step_before[axis] = step;
        bool turns = !motor.present || !motor.stalled(m.clocks);
        int delta = dir == m.dir_positive[axis] ? 1 : -1;
        if (rose && enabled && turns) {
            m.position[axis] += delta;
            motor.steps += delta;
        } else if (rose) {
            ++m.lost[axis];
        }
        if (motor.present) motor.follow();
    }
    for (int input = 1; input < m.input_count; ++input)
        if (m.contacts[input].present) m.contacts[input].clock(m.position[m.input_axis[input]]);
    drive_inputs(enabled);
    drive_encoders();
}

}  // namespace

#endif  // MACHINE_HOOKS_H
