// Compiled harness around a Verilated card: the clock loop, the PCI segment
// resolution, the STEP/DIR capture and the simulated machine (drives, motors
// with encoders, switches, E-stop: models/sim_machine.py is its definition,
// clock for clock), behind a C interface for ctypes.
//
// The model's ports come from vc_ports.h, written by build.py from
// the model's own header (name, width, direction, address).  Nothing here
// knows the card's internals: Python binds ports to roles by index (clock,
// each PCI line's in / out / oe, IDSEL, the STEP and DIR pins of up to six
// axes: X, Y, Z, A, B, C, the ones the card lacks unbound).
//
// One clock (vc_tick): clock high, eval (the rising edge), pins sampled,
// clock low, eval.  The clock count is the number of rising edges so far; an
// edge record (clock, pins) is kept whenever the pins differ after an edge.
//
//     clock  _/~~\__/~~\__/~~\_
//     count    1     2     3
//     pins     <p1 ><p2  ><p3   (sampled after each rising edge)
//
// The card (card.h: ports, clock loop, trace), its PCI bus (card_bus.h) and
// the simulated machine's hooks (machine_hooks.h, the machine in
// sim_machine.h) are headers of this one translation unit; here is the C
// interface.
#include <cstdint>
#include <cstring>

#include "card.h"
#include "card_bus.h"
#include "machine_hooks.h"

namespace {

// Why vc_run returned.
enum Reason { LIMIT = 0, INTERRUPT = 1, STEPS = 2, BUS = 3 };

}  // namespace

extern "C" {

void* vc_new() {
    Card* card = new Card;
    card->context.reset(new VerilatedContext);
#if VC_TRACE
    card->context->traceEverOn(true);
#endif
    card->model.reset(new VC_MODEL{card->context.get(), VC_TOP_NAME});
#define VC_ADD_PORT(name, width, direction) \
    card->ports.push_back(Port{#name, width, direction, static_cast<void*>(&card->model->name)});
    VC_PORTS(VC_ADD_PORT)
#undef VC_ADD_PORT
    // Settle once with every input at 0: the first rising edge is then an edge
    // (the model's first eval only records the clock's level).
    card->model->eval();
    return card;
}

void vc_free(void* handle) {
    Card* card = static_cast<Card*>(handle);
#if VC_TRACE
    if (card->trace) card->trace->close();
#endif
    card->model->final();
    delete card;
}

int vc_trace_kind() { return VC_TRACE; }

int vc_port_count(void* handle) { return static_cast<int>(static_cast<Card*>(handle)->ports.size()); }

const char* vc_port_name(void* handle, int index) { return static_cast<Card*>(handle)->ports[index].name; }

int vc_port_width(void* handle, int index) { return static_cast<Card*>(handle)->ports[index].width; }

int vc_port_direction(void* handle, int index) { return static_cast<Card*>(handle)->ports[index].direction; }

uint64_t vc_get(void* handle, int index) { return static_cast<Card*>(handle)->get(index); }

void vc_set(void* handle, int index, uint64_t value) { static_cast<Card*>(handle)->set(index, value); }

void vc_eval(void* handle) { static_cast<Card*>(handle)->model->eval(); }

uint64_t vc_clocks(void* handle) { return static_cast<Card*>(handle)->clocks; }

uint64_t vc_step_rises(void* handle) { return static_cast<Card*>(handle)->step_rises; }

void vc_bind_clock(void* handle, int clock) { static_cast<Card*>(handle)->clock = clock; }

void vc_bind_pins(void* handle, const int* pins) {
    Card* card = static_cast<Card*>(handle);
    for (int pin = 0; pin < PINS; ++pin) card->pins[pin] = pins[pin];
    card->pin_state = card->sample_pins();
}

void vc_bind_bus(void* handle, const int* line_in, const int* line_out, const int* line_oe, int idsel, int idsel_bit) {
    Card* card = static_cast<Card*>(handle);
    for (int line = 0; line < LINES; ++line) {
        card->line_in[line] = line_in[line];
        card->line_out[line] = line_out[line];
        card->line_oe[line] = line_oe[line];
    }
    card->idsel = idsel;
    card->idsel_bit = idsel_bit;
}

// Set every input in `inputs` (port indices, count of them) to `values`,
// then tick once (tick != 0) or only settle; read `outputs` into `out`.
void vc_io(void* handle, int count, const int* inputs, const uint64_t* values, int tick, int out_count,
           const int* outputs, uint64_t* out) {
    Card* card = static_cast<Card*>(handle);
    for (int i = 0; i < count; ++i) card->set(inputs[i], values[i]);
    if (tick) card->tick();
    else card->model->eval();
    for (int i = 0; i < out_count; ++i) out[i] = card->get(outputs[i]);
}

// One bus clock: the host's drive of the clock now ending (host_out/host_oe,
// per line) meets the card's; the card's inputs settle (its outputs may
// follow its inputs within the clock, so resolve until nothing changes), the
// segment as sampled at the rising edge goes to values/drivers/floating, then
// the edge.  Returns the rounds the resolution took, or -1 if it never settled.
int vc_step_bus(void* handle, const uint64_t* host_out, const uint64_t* host_oe, uint64_t* values,
                uint64_t* drivers, uint64_t* floating) {
    Card* card = static_cast<Card*>(handle);
    card->resolve(host_out, host_oe, values, drivers, floating);
    card->model->eval();
    for (int rounds = 1; rounds <= 8; ++rounds) {
        uint64_t again[LINES], again_drivers[LINES], again_floating[LINES];
        card->resolve(host_out, host_oe, again, again_drivers, again_floating);
        bool settled = std::memcmp(again, values, sizeof again) == 0 &&
                       std::memcmp(again_drivers, drivers, sizeof again_drivers) == 0;
        std::memcpy(values, again, sizeof again);
        std::memcpy(drivers, again_drivers, sizeof again_drivers);
        std::memcpy(floating, again_floating, sizeof again_floating);
        if (settled) {
            card->tick();
            return rounds;
        }
        card->model->eval();
    }
    return -1;
}

// `count` clocks with the inputs as they are, whatever happens.
void vc_tick(void* handle, uint64_t count) {
    Card* card = static_cast<Card*>(handle);
    for (uint64_t i = 0; i < count; ++i) card->tick();
}

// Run with the inputs as they are (a quiet bus) until an event; `done` gets
// the clocks run.  Each condition is judged on the state before an edge and
// the run stops after that edge, as a per-clock waiter sampling at the edge
// does: INTA# driven low in the clock before the edge, `steps` STEP rises
// (0: no such condition) recorded before it, or the card driving a line other
// than INTA# (BUS: leave it to the per-clock bus path and its monitor).
int vc_run(void* handle, uint64_t limit, int until_interrupt, uint64_t steps, uint64_t* done) {
    Card* card = static_cast<Card*>(handle);
    uint64_t start_rises = card->step_rises;
    int reason = LIMIT;
    uint64_t count = 0;
    while (count < limit) {
        bool interrupt = until_interrupt && card->interrupt_asserted();
        bool enough = steps && card->step_rises - start_rises >= steps;
        card->tick();
        ++count;
        if (interrupt) { reason = INTERRUPT; break; }
        if (enough) { reason = STEPS; break; }
        if (card->drives_bus()) { reason = BUS; break; }
    }
    *done = count;
    return reason;
}

// The simulated machine of a card of `axes` axes: `input_count` inputs,
// `inputs` their ports (-1 where absent), `input_axis` the axis of each
// switch input (input 0 is the E-stop), the DRIVE_ENABLE port; `start` the
// axes' positions; dir_positive: bit n, the DIR level that moves axis n
// forward.  Switches and motors are added with vc_machine_switch and
// vc_machine_motor before; the inputs are driven from now on.  Returns -1 if
// the counts exceed the harness's room.
int vc_machine_start(void* handle, int axes, int input_count, const int* inputs, const int* input_axis, int drive,
                     const int64_t* start, int dir_positive, int estop_active_low) {
    Card* card = static_cast<Card*>(handle);
    Machine& m = card->machine;
    if (axes < 1 || axes > kMaxAxes || input_count < 1 || input_count > kMaxInputs) return -1;
    m.axes = axes;
    m.input_count = input_count;
    for (int input = 0; input < input_count; ++input) {
        m.inputs[input] = inputs[input];
        m.input_axis[input] = input_axis[input];
        if (input && (input_axis[input] < 0 || input_axis[input] >= axes)) return -1;
    }
    m.drive = drive;
    for (int axis = 0; axis < axes; ++axis) {
        m.position[axis] = start[axis];
        m.dir_positive[axis] = (dir_positive >> axis) & 1;
        m.step_before[axis] = (card->pin_state >> (2 * axis)) & 1;
    }
    m.estop_active_low = estop_active_low;
    for (int input = 1; input < input_count; ++input) {
        Contact& c = m.contacts[input];
        if (c.present) c.level = c.closed = c.reads_closed(m.position[m.input_axis[input]], false);
    }
    m.on = true;
    m.pins = m.encoder_pins = ~0u;   // the first words are recorded
    card->drive_inputs(m.drive >= 0 && card->get(m.drive));
    card->drive_encoders();
    return 0;
}

// A motor on `axis` (before vc_machine_start): models/sim_machine.py's Motor;
// `ports`: the card's A, B and index inputs of the axis (-1 where absent);
// stall_at -1: none.
void vc_machine_motor(void* handle, int axis, int64_t numerator, int64_t denominator, int64_t lag, int64_t spacing,
                      int64_t jitter, uint32_t seed, int64_t index_period, int64_t stall_at, const int* ports) {
    if (axis < 0 || axis >= kMaxAxes) return;
    Motor& motor = static_cast<Card*>(handle)->machine.motors[axis];
    motor = Motor();
    motor.present = true;
    motor.numerator = numerator;
    motor.denominator = denominator;
    motor.history.assign(static_cast<size_t>(lag), 0);
    motor.spacing = spacing;
    motor.jitter = jitter;
    motor.state = seed ? seed : 1;
    motor.index_period = index_period;
    motor.stall_at = stall_at;
    for (int pin = 0; pin < 3; ++pin) motor.ports[pin] = ports[pin];
}

// Stall (or free) the motor of `axis` from the next clock on.
void vc_machine_stall(void* handle, int axis, int stalled) {
    if (axis >= 0 && axis < kMaxAxes) static_cast<Card*>(handle)->machine.motors[axis].asked_stall = stalled;
}

// The motors' counts (kMaxAxes; 0 without a motor), the machine's clocks,
// the encoder word, the encoder changes recorded.
void vc_machine_encoders(void* handle, int64_t* counts, uint64_t* state) {
    Machine& m = static_cast<Card*>(handle)->machine;
    for (int axis = 0; axis < kMaxAxes; ++axis) counts[axis] = m.motors[axis].counts;
    state[0] = m.clocks;
    state[1] = m.encoder_pins;
    state[2] = m.encoder_clocks.size();
}

// Move the recorded encoder changes out: (clock, word the next edge takes).
void vc_machine_take_encoder_changes(void* handle, uint64_t* clocks, uint32_t* words) {
    Machine& m = static_cast<Card*>(handle)->machine;
    std::memcpy(clocks, m.encoder_clocks.data(), m.encoder_clocks.size() * sizeof(uint64_t));
    std::memcpy(words, m.encoder_words.data(), m.encoder_words.size() * sizeof(uint32_t));
    m.encoder_clocks.clear();
    m.encoder_words.clear();
}

void vc_machine_switch(void* handle, int input, int64_t position, int positive, int64_t hysteresis,
                       int64_t bounce, int64_t longest_run, int active_low, uint32_t seed) {
    if (input < 1 || input >= kMaxInputs) return;
    Contact& c = static_cast<Card*>(handle)->machine.contacts[input];
    c.present = true;
    c.position = position;
    c.positive = positive;
    c.hysteresis = hysteresis;
    c.bounce = bounce;
    c.longest_run = longest_run;
    c.active_low = active_low;
    c.state = seed ? seed : 1;
    c.chatter_left = c.run_left = 0;
}

void vc_machine_estop(void* handle, int pressed) {
    Card* card = static_cast<Card*>(handle);
    Machine& m = card->machine;
    m.estop = pressed;
    if (m.on) card->drive_inputs(m.drive >= 0 && card->get(m.drive));
}

// positions (kMaxAxes), lost steps (kMaxAxes), the input word, the changes recorded.
void vc_machine_state(void* handle, int64_t* position, uint64_t* lost, uint64_t* pins) {
    Machine& m = static_cast<Card*>(handle)->machine;
    for (int axis = 0; axis < kMaxAxes; ++axis) {
        position[axis] = m.position[axis];
        lost[axis] = m.lost[axis];
    }
    pins[0] = m.pins & ~(1u << kDriveBit);
    pins[1] = m.change_clocks.size();
}

// Move the recorded changes out: (clock, word the next edge takes | DRIVE_ENABLE
// as sampled after edge `clock`, bit kDriveBit).
void vc_machine_take_changes(void* handle, uint64_t* clocks, uint32_t* words) {
    Machine& m = static_cast<Card*>(handle)->machine;
    std::memcpy(clocks, m.change_clocks.data(), m.change_clocks.size() * sizeof(uint64_t));
    std::memcpy(words, m.change_pins.data(), m.change_pins.size() * sizeof(uint32_t));
    m.change_clocks.clear();
    m.change_pins.clear();
}

uint64_t vc_edge_count(void* handle) { return static_cast<Card*>(handle)->edge_clocks.size(); }

// Move the recorded edges into the caller's arrays (room for vc_edge_count()).
void vc_take_edges(void* handle, uint64_t* clocks, uint16_t* states) {
    Card* card = static_cast<Card*>(handle);
    std::memcpy(clocks, card->edge_clocks.data(), card->edge_clocks.size() * sizeof(uint64_t));
    std::memcpy(states, card->edge_states.data(), card->edge_states.size() * sizeof(uint16_t));
    card->edge_clocks.clear();
    card->edge_states.clear();
}

// Trace the clocks from `first` (a count of rising edges) up to `last` into `path`.
int vc_trace_open(void* handle, const char* path, uint64_t first, uint64_t last, uint64_t half_period) {
#if VC_TRACE
    Card* card = static_cast<Card*>(handle);
    card->trace.reset(new TraceFile);
    card->model->trace(card->trace.get(), 99);
    card->trace->open(path);
    card->trace_from = first;
    card->trace_to = last;
    card->half_period = half_period;
    return 0;
#else
    (void)handle; (void)path; (void)first; (void)last; (void)half_period;
    return -1;
#endif
}

void vc_trace_close(void* handle) {
#if VC_TRACE
    Card* card = static_cast<Card*>(handle);
    if (card->trace) card->trace->close();
    card->trace.reset();
#else
    (void)handle;
#endif
}

}  // extern "C"
