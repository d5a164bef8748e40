// The simulated machine of the compiled harness (harness.cpp runs it in its
// clock loop): models/sim_machine.py is its definition, clock for clock.
#ifndef SIM_MACHINE_H
#define SIM_MACHINE_H

#include <cstdint>
#include <vector>

namespace {

// The machine inputs, in the order of models/registers.py's INPUT_NAMES.
enum Input { ESTOP, LIMIT_POS_X, LIMIT_NEG_X, LIMIT_POS_Y, LIMIT_NEG_Y, HOME_X, HOME_Y, INPUTS };
const int kInputAxis[INPUTS] = {-1, 0, 0, 1, 1, 0, 1};

// One switch of models/sim_machine.py (Switch, _Contact): closed from
// `position` on towards its side, open again `hysteresis` + 1 steps back,
// `bounce` clocks of xorshift-timed chatter after each change.
struct Contact {
    bool present = false;
    int64_t position = 0;
    bool positive = true, active_low = false;
    int64_t hysteresis = 0, bounce = 0, longest_run = 2;
    uint32_t state = 1;
    bool closed = false, level = false;
    int64_t chatter_left = 0, run_left = 0;

    bool reads_closed(int64_t at, bool before) const {
        int64_t into = positive ? at - position : position - at;
        return into >= (before ? -hysteresis : 0);
    }
    int64_t next_run() {
        uint32_t x = state;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        state = x;
        return 1 + static_cast<int64_t>(x % static_cast<uint64_t>(longest_run));
    }
    void clock(int64_t at) {
        bool now = reads_closed(at, closed);
        if (now != closed) {
            closed = now;
            chatter_left = bounce;
            run_left = 0;
            level = !now;
        }
        if (chatter_left) {
            --chatter_left;
            if (!run_left) {
                level = !level;
                run_left = next_run();
            }
            --run_left;
        } else {
            level = closed;
        }
    }
    bool pin() const { return level != active_low; }
};

struct Machine {
    bool on = false;
    int inputs[INPUTS] = {-1, -1, -1, -1, -1, -1, -1};
    int drive = -1;
    Contact contacts[INPUTS];
    int64_t position[2] = {0, 0};
    uint64_t lost[2] = {0, 0};
    bool dir_positive[2] = {true, true};
    bool estop = false, estop_active_low = false;
    bool step_before[2] = {false, false};
    unsigned pins = 0;
    std::vector<uint64_t> change_clocks;
    std::vector<uint8_t> change_pins;

    unsigned word() const {
        unsigned value = estop != estop_active_low ? 1u : 0u;
        for (int input = 1; input < INPUTS; ++input)
            if (contacts[input].present && contacts[input].pin()) value |= 1u << input;
        return value;
    }
};

}  // namespace

#endif  // SIM_MACHINE_H
