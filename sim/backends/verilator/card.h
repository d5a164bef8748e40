// The card of the compiled harness: the Verilated model, its ports bound to
// roles (clock, PCI lines, IDSEL, STEP/DIR pins, the machine's inputs), the
// clock loop with its STEP/DIR edge record, and the trace it dumps into.
// Its PCI bus driving is in card_bus.h, the simulated machine's hooks in the
// clock loop in machine_hooks.h (harness.cpp includes all three).
//
// One clock (tick): clock high, eval (the rising edge), pins sampled,
// machine clock, clock low, eval.
#ifndef CARD_H
#define CARD_H

#include <cstdint>
#include <memory>
#include <vector>

#include "verilated.h"
#include "vc_ports.h"
#include "pci_lines.h"
#include "ports.h"
#include "sim_machine.h"
#if VC_TRACE == 1
#include "verilated_vcd_c.h"
typedef VerilatedVcdC TraceFile;
#elif VC_TRACE == 2
#include "verilated_fst_c.h"
typedef VerilatedFstC TraceFile;
#endif

namespace {

enum Pin { STEP_X, DIR_X, STEP_Y, DIR_Y, PINS = 12 };   // axis i: STEP at bit 2i, DIR at 2i + 1
const unsigned kStepBits = 0x555;

struct Card {
    std::unique_ptr<VerilatedContext> context;
    std::unique_ptr<VC_MODEL> model;
    std::vector<Port> ports;
    int clock = -1;
    int line_in[LINES], line_out[LINES], line_oe[LINES];
    int idsel = -1, idsel_bit = 0;
    int pins[PINS];
    uint64_t clocks = 0;
    uint64_t step_rises = 0;
    unsigned pin_state = 0;
    std::vector<uint64_t> edge_clocks;
    std::vector<uint16_t> edge_states;
    Machine machine;
#if VC_TRACE
    std::unique_ptr<TraceFile> trace;
    uint64_t trace_from = 0, trace_to = 0, half_period = 15;
#endif

    Card() {
        for (int line = 0; line < LINES; ++line) line_in[line] = line_out[line] = line_oe[line] = -1;
        for (int pin = 0; pin < PINS; ++pin) pins[pin] = -1;
    }

    uint64_t get(int index) const { return read_port(ports[index]); }
    void set(int index, uint64_t value) { write_port(ports[index], value); }

    // The PCI bus (card_bus.h).
    bool card_drive(int line, uint64_t* value) const;
    bool interrupt_asserted() const;
    bool drives_bus() const;
    void resolve(const uint64_t* host_out, const uint64_t* host_oe, uint64_t* values, uint64_t* drivers,
                 uint64_t* floating);

    // The simulated machine's hooks (machine_hooks.h).
    void drive_inputs(bool enabled);
    void drive_encoders();
    void machine_clock(unsigned state);

    void dump(uint64_t time) {
#if VC_TRACE
        if (trace && clocks >= trace_from && clocks < trace_to) trace->dump(time);
#else
        (void)time;
#endif
    }

    unsigned sample_pins() const {
        unsigned state = 0;
        for (int pin = 0; pin < PINS; ++pin)
            if (pins[pin] >= 0 && get(pins[pin])) state |= 1u << pin;
        return state;
    }

    void tick() {
        set(clock, 1);
        model->eval();
        ++clocks;
#if VC_TRACE
        dump(2 * half_period * (clocks - 1) + half_period);
#endif
        unsigned state = sample_pins();
        if (state != pin_state) {
            unsigned rose = state & ~pin_state;
            step_rises += __builtin_popcount(rose & kStepBits);
            edge_clocks.push_back(clocks);
            edge_states.push_back(static_cast<uint16_t>(state));
            pin_state = state;
        }
        if (machine.on) machine_clock(state);
        set(clock, 0);
        model->eval();
#if VC_TRACE
        dump(2 * half_period * clocks);
#endif
    }
};

}  // namespace

#endif  // CARD_H
