// The simulated machine of the compiled harness (harness.cpp runs it in its
// clock loop): models/sim_machine.py is its definition, clock for clock.
#ifndef SIM_MACHINE_H
#define SIM_MACHINE_H

#include <cstdint>
#include <vector>

namespace {

// Room for the largest build: models/axes.py's six axes, models/registers.py's
// INPUT_NAMES (the E-stop, then each axis's limits and home).  A machine uses
// the card's `axes` and the inputs of its build (vc_machine_start says which).
const int kMaxAxes = 6;
const int kMaxInputs = 19;
const int kDriveBit = 31;   // DRIVE_ENABLE's bit in a recorded input word

// The seeded xorshift32 step of models/sim_machine.py: `state` moves on, its new value returned.
inline uint32_t xorshift32(uint32_t& state) {
    uint32_t x = state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    state = x;
    return x;
}

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
        return 1 + static_cast<int64_t>(xorshift32(state) % static_cast<uint64_t>(longest_run));
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

// A motor with an encoder, models/motor_model.py's MotorModel (the machine
// moves its axis and counts lost steps; the motor keeps its own steps, from 0):
// the target count round(steps * numerator / denominator) of `lag` clocks
// before (a ring of the last `lag` step positions), walked one count at a
// time, `spacing` - 1 clocks (plus xorshift jitter) between two counts.
struct Motor {
    bool present = false;
    int64_t numerator = 4, denominator = 1;
    int64_t spacing = 3, jitter = 0, index_period = 0, stall_at = -1;
    uint32_t state = 1;
    bool asked_stall = false;
    std::vector<int64_t> history;
    size_t head = 0;
    int64_t steps = 0, counts = 0, wait = 0;
    int ports[3] = {-1, -1, -1};  // A, B, index

    bool stalled(uint64_t clock) const {
        return asked_stall || (stall_at >= 0 && clock >= static_cast<uint64_t>(stall_at));
    }
    int64_t target(int64_t at) const {
        __int128 a = 2 * static_cast<__int128>(at) * numerator + denominator, b = 2 * static_cast<__int128>(denominator);
        __int128 q = a / b;
        if (a % b != 0 && a < 0) --q;  // floor (b is positive)
        return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(q)));
    }
    int64_t draw() {
        return static_cast<int64_t>(xorshift32(state) % static_cast<uint64_t>(jitter + 1));
    }
    void follow() {
        int64_t then = steps;
        if (!history.empty()) {
            then = history[head];
            history[head] = steps;
            head = (head + 1) % history.size();
        }
        int64_t goal = target(then);
        if (wait) {
            --wait;
        } else if (goal != counts) {
            counts += goal > counts ? 1 : -1;
            wait = spacing - 1 + (jitter ? draw() : 0);
        }
    }
    // bit 0 A, 1 B, 2 index (models/encoder_model.py's GRAY: A leads B forwards)
    unsigned pins() const {
        static const unsigned kGray[4] = {0, 1, 3, 2};
        unsigned word = kGray[((counts % 4) + 4) % 4];
        if (index_period && counts % index_period == 0) word |= 4;
        return word;
    }
};

// The machine of a card of `axes` axes: input 0 is the E-stop, input n > 0
// a switch on axis input_axis[n]; encoder word bit 3n: axis n's A, 3n + 1: B,
// 3n + 2: index.
struct Machine {
    bool on = false;
    int axes = 0, input_count = 0;
    int inputs[kMaxInputs], input_axis[kMaxInputs];
    int drive = -1;
    Contact contacts[kMaxInputs];
    int64_t position[kMaxAxes] = {};
    uint64_t lost[kMaxAxes] = {};
    bool dir_positive[kMaxAxes] = {};
    bool estop = false, estop_active_low = false;
    bool step_before[kMaxAxes] = {};
    uint32_t pins = 0;
    std::vector<uint64_t> change_clocks;
    std::vector<uint32_t> change_pins;
    Motor motors[kMaxAxes];
    uint64_t clocks = 0;       // clocks since the machine started (1 the first)
    uint32_t encoder_pins = 0;
    std::vector<uint64_t> encoder_clocks;
    std::vector<uint32_t> encoder_words;

    Machine() {
        for (int input = 0; input < kMaxInputs; ++input) inputs[input] = input_axis[input] = -1;
    }

    uint32_t encoder_word() const {
        uint32_t value = 0;
        for (int axis = 0; axis < axes; ++axis)
            if (motors[axis].present) value |= motors[axis].pins() << (3 * axis);
        return value;
    }

    uint32_t word() const {
        uint32_t value = estop != estop_active_low ? 1u : 0u;
        for (int input = 1; input < input_count; ++input)
            if (contacts[input].present && contacts[input].pin()) value |= 1u << input;
        return value;
    }
};

}  // namespace

#endif  // SIM_MACHINE_H
