/* dda_card: LinuxCNC HAL driver of the PCI DDA card, position (or velocity) mode.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 *
 *   loadrt dda_card [sim=/path/a.sock[,/path/b.sock...]] [keep_ahead=4] [period_overhead=8] [sim_timeout_ms=5000]
 *   addf dda-card.0.read servo-thread      (first in the thread; each card K its own dda-card.K.read)
 *   addf dda-card.0.write servo-thread     (after motion; dda-card.K.write)
 *
 * One driver serves several cards (dda_cards.h): the simulated cards named by
 * `sim`, or every card on the PCI bus; each card K is `dda-card.K` with its own
 * pins, state, faults and functions, and as many stepgens as its BUILD.AXES.
 * Each servo period `write` turns the change of every enabled axis's
 * commanded position (position-cmd, or velocity-cmd integrated when
 * control-type is 1, followed within maxvel and maxaccel: dda_math.h) into
 * one LINE by (dx, dy) steps at one iteration per p clocks (the power of
 * two that covers the card's step cycle, dda_step_cycle) followed by a
 * DWELL that fills the rest of the period, so the card's motion for a
 * period takes exactly that period's card clocks.  The queue is kept
 * `keep_ahead` periods ahead: the position asked for in period k is
 * reached at the end of period k + keep_ahead - 1.  `read` gives
 * position-fb from the card's step counters (unwrapped into 64 bits) and
 * STATUS's FIFO level and error.  A FIFO found empty while running, a card
 * error or the card's own stop (its E-stop input, watchdog or a limit)
 * sets `error`, stops the queue and needs enable to fall and rise again;
 * so do a failed transport and a card that reads all-ones (gone from the
 * bus), which also freeze position-fb.  A position-cmd that is no position
 * raises `error` and holds that axis.  error-code: dda_state.h.
 *
 * Machine I/O: `drive-enable` goes to MACHINE_CONTROL.DRIVE_ENABLE (the
 * card's DRIVE_ENABLE pin, which the card itself drops when it stops and
 * keeps low after COMMAND.CLEAR_STOP: the restart writes it again);
 * while the queue runs, every period rewrites WATCHDOG with
 * `watchdog.timeout_ns` in card clocks, so a PC that stops driving the card
 * has it stop on its own within that time.  `input.<name>` (estop,
 * limit-pos-x .. home-y, and limit-pos-z .. home-z and on of each further
 * axis) are the card's filtered inputs (INPUT_ACTIVE), read every period:
 * LinuxCNC's home-sw-in and limit pins take them.  On a card built with
 * encoders, `encoder.NN.*` are hostmot2's encoder pins (dda_encoder.h), and
 * its following-error stop is set at enable.  A watchdog stop sets
 * `watchdog.has_bit`, which holds the card stopped (and `error` high) until
 * it is written false.  Each period's DWELL is trimmed from the FIFO level
 * so that the card's crystal, some ppm off the PC's timer, neither drains
 * nor fills the queue.  See docs/linuxcnc.md.
 */
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_math.h"
#include "hal.h"
#include "dda_transport.h"
#include "dda_state.h"
#include "dda_pins.h"
#include "dda_checks.h"
#include "dda_faults.h"
#include "dda_axis.h"
#include "dda_drift.h"
#include "dda_cards.h"
#include "dda_encoder.h"
#include "dda_unload.h"

MODULE_AUTHOR("PCI DDA card authors");
MODULE_DESCRIPTION("HAL driver of the PCI DDA card");
MODULE_LICENSE("GPL");

static char *sim = "";
RTAPI_MP_STRING(sim, "Unix sockets of python -m sim.card.card_server, one a card, comma-separated "
                "(empty: every card on PCI)");
static int sim_timeout_ms = 5000;
RTAPI_MP_INT(sim_timeout_ms, "simulation: the longest wait (ms) for the card server to answer");
static int keep_ahead = 4;
RTAPI_MP_INT(keep_ahead, "servo periods queued ahead in the card's FIFO (1..63)");
static int period_overhead = 8;
RTAPI_MP_INT(period_overhead, "card clocks a period's LINE and DWELL take beyond their own");

static int comp_id;
static struct card *cards[CARDS_MAX];
static int card_count;

/* WATCHDOG's count: the timeout in whole card clocks (rounded up), at most what the register holds. */
static uint32_t watchdog_clocks(struct card *c)
{
    uint64_t clocks = dda_clocks_of_ns(c->watchdog_timeout_ns, c->clock_hz);
    return clocks > DDA_WATCHDOG_CLOCKS_MASK ? DDA_WATCHDOG_CLOCKS_MASK : (uint32_t)clocks;
}

static void read_pass(void *arg, long period)
{
    struct card *c = arg;
    uint32_t raw[DDA_AXES_MAX], status = 0, active = 0;
    int i = 0, level;
    while (i < c->axes && dda_read32(&c->transport, pos_reg(i), &raw[i]) == 0)
        i++;
    if (i < c->axes || dda_read32(&c->transport, DDA_STATUS, &status) < 0
        || dda_read32(&c->transport, DDA_INPUT_ACTIVE, &active) < 0
        || (!card_gone(c, status) && dda_read_encoders(c) < 0)) {
        if (!*c->error || *c->error_code != FAULT_TRANSPORT)
            stop(c, FAULT_TRANSPORT);  /* position-fb keeps its last good value */
        return;
    }
    if (card_gone(c, status)) {
        if (!c->gone)
            rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s reads all-ones: it has left the bus (removed, or its "
                            "slot lost power); position-fb holds its last value\n", c->transport.name);
        c->gone = 1;
        if (!*c->error || *c->error_code != FAULT_CARD_GONE)
            stop(c, FAULT_CARD_GONE);
        return;
    }
    c->gone = 0;
    level = (int32_t)FIELD(status, DDA_STATUS_FIFO_LEVEL);
    *c->fifo_level = level;
    c->room = (uint32_t)level < c->fifo_size ? c->fifo_size - (uint32_t)level : 0;
    *c->estop_active = (active & DDA_INPUT_ACTIVE_ESTOP_MASK) != 0;
    for (i = 0; i < c->inputs_count; i++)
        *c->inputs[i] = (active >> i) & 1;
    if (c->running)
        trim_drift(c, level);
    if (status & DDA_STATUS_STOPPED_MASK)
        card_stopped(c, c->running);
    else
        *c->stop_reason = 0;
    if (c->running && (status & DDA_STATUS_ERROR_MASK)) {
        stop(c, (int)FIELD(status, DDA_STATUS_ERROR));
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the card stopped with error %d\n", c->transport.name,
                        *c->error_code);
    } else if (c->running && !(status & DDA_STATUS_BUSY_MASK)) {
        (*c->underruns)++;
        stop(c, FAULT_FIFO_DRY);
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the FIFO ran dry: the servo thread fell behind\n",
                        c->transport.name);
    }
    for (i = 0; i < c->axes; i++) {
        struct stepgen *s = &c->axis[i];
        int64_t card_steps = dda_unwrap(s->card, raw[i]);
        check_scale(c, i);
        *s->velocity_fb = (double)(card_steps - s->card) / s->position_scale / (period * 1e-9);
        s->card = card_steps;
        *s->counts = (int32_t)(uint32_t)(uint64_t)(card_steps + s->offset);  /* low 32 bits, as hostmot2's */
        *s->position_fb = (double)(card_steps + s->offset) / s->position_scale;
    }
}

/* `count` words into the FIFO if it has room for them (it never makes the bus wait). */
static int queue_words(struct card *c, const uint32_t *words, unsigned count)
{
    if (count > c->room) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: the card's FIFO has room for %u words, not the %u of this "
                        "period: the card is not taking commands\n", c->transport.name, c->room, count);
        return FAULT_FIFO_FULL;
    }
    if (dda_fifo_write(&c->transport, words, count) < 0)
        return FAULT_TRANSPORT;
    c->room -= count;
    return 0;
}

/* Set up and start the queue: 0; a fault code < 0 (said); 1 the card holds itself
 * stopped (its E-stop input is active): error, nothing started. */
static int start(struct card *c)
{
    uint32_t words[START_WORDS];
    uint32_t status = 0, *t = c->timing_clocks;
    unsigned n = 0;
    int i, problem = dda_check_settings(c);
    if (!problem)
        problem = dda_align_encoders(c);  /* re-aligns the following error: before CLEAR_STOP */
    if (problem)
        return problem;
    /* release a stop of the card's own; it holds while its E-stop input is active */
    if (dda_write32(&c->transport, DDA_COMMAND, DDA_COMMAND_CLEAR_STOP_MASK) < 0
        || dda_read32(&c->transport, DDA_STATUS, &status) < 0)
        return FAULT_TRANSPORT;
    if (status & DDA_STATUS_STOPPED_MASK) {
        card_stopped(c, 1);
        return 1;
    }
    /* a stop cleared MACHINE_CONTROL.DRIVE_ENABLE and CLEAR_STOP does not set it
     * again: the drives come back only with this new write of the HAL pin */
    c->drive_written = *c->drive_enable != 0;
    if (dda_write32(&c->transport, DDA_MACHINE_CONTROL,
                    c->drive_written ? DDA_MACHINE_CONTROL_DRIVE_ENABLE_MASK : 0) < 0)
        return -1;
    c->iteration = dda_iteration_clocks(dda_step_cycle(t[STEPLEN], t[STEPSPACE], HAS_STEP_SPACE));
    n += dda_cmd_set(&words[n], DDA_SLOWEST_ITERATION / c->iteration, DDA_FEED_RATE_SET_INDEX);
    n += dda_cmd_set(&words[n], t[STEPLEN], DDA_STEP_WIDTH_SET_INDEX);
#if HAS_STEP_SPACE
    n += dda_cmd_set(&words[n], t[STEPSPACE], DDA_STEP_SPACE_SET_INDEX);
#endif
    n += dda_cmd_set(&words[n], t[DIRSETUP], DDA_DIR_SETUP_SET_INDEX);
    n += dda_cmd_set(&words[n], t[DIRHOLD], DDA_DIR_HOLD_SET_INDEX);
    for (i = 0; i < c->axes; i++)
        c->axis[i].queued = 0;  /* each enabled axis is taken up at its first period */
    c->depth_start = -1;
    c->trim_sign = 0;
    /* no ramp: the trajectory planner has shaped the motion, and a stop is immediate */
    if (dda_write32(&c->transport, DDA_RAMP_STEP, 0) < 0)
        return FAULT_TRANSPORT;
#ifdef DDA_STEP_MODE
    if (dda_write32(&c->transport, DDA_STEP_MODE, c->axis[0].step_type) < 0)
        return FAULT_TRANSPORT;
#endif
    problem = queue_words(c, words, n);
    if (problem)
        return problem;
    if (dda_write32(&c->transport, DDA_WATCHDOG, watchdog_clocks(c)) < 0)
        return FAULT_TRANSPORT;
    c->running = 1;
    return 0;
}

/* One period of motion: LINE by the change in steps and a DWELL for the rest of
 * `clocks`, or a DWELL of `clocks` alone when nothing moves.  What the card's
 * sequencer spends around them (measured on the generated card, see
 * docs/linuxcnc.md): a LINE of N iterations of p clocks and its DWELL d take
 * p * N + d + period_overhead clocks, one more at the fastest rate (p = 2),
 * plus DIR_SETUP when a direction pin changes (or may: its level is not known
 * before an axis's first move after load); a DWELL alone takes d.
 * 0, or a fault code. */
static int queue_period(struct card *c, uint32_t clocks, double dt)
{
    uint32_t words[PERIOD_WORDS];
    int64_t delta[DDA_AXES_MAX], longest = 0, dwell = clocks;
    int32_t line[DDA_AXES_MAX];
    int32_t step = (int32_t)(clocks >> TRIM_SHIFT) > 1 ? (int32_t)(clocks >> TRIM_SHIFT) : 1;
    int reversal = 0, problem, i;
    unsigned n = 0;
    for (i = 0; i < c->axes; i++) {
        struct stepgen *s = &c->axis[i];
        delta[i] = axis_delta(c, i, dt);
        line[i] = (int32_t)delta[i];  /* within the coordinate width: checked against max_delta below */
        if ((delta[i] < 0 ? -delta[i] : delta[i]) > longest)
            longest = delta[i] < 0 ? -delta[i] : delta[i];
        if (delta[i] != 0 && (s->dir < 0 || (delta[i] > 0) != s->dir))
            reversal = 1;
    }
    if (longest > 0) {
        dwell -= (int64_t)c->iteration * longest + period_overhead + (c->iteration == DDA_FASTEST_ITERATION)
                 + (reversal ? c->timing_clocks[DIRSETUP] : 0);
        n = dda_cmd_line_axes(words, c->line_axes, line, 0);
    }
    *c->drift_trim = c->trim_sign * step;
    dwell += *c->drift_trim;
    if (dwell < 0 || longest > c->max_delta) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s: %lld steps in one period is more than the card makes in "
                        "%u clocks: lower maxvel or position-scale\n", c->transport.name, (long long)longest, clocks);
        return FAULT_TOO_FAST;
    }
    n += dda_cmd_dwell(&words[n], (uint32_t)dwell);
    problem = queue_words(c, words, n);
    if (problem)
        return problem;
    c->period_words[c->periods_queued++ % TRIM_RING] = (uint8_t)n;
    for (i = 0; i < c->axes; i++) {
        c->axis[i].sent += delta[i];
        if (delta[i] != 0)
            c->axis[i].dir = delta[i] > 0;
    }
    return 0;
}

/* Start the queue and fill it keep_ahead periods ahead. */
static void start_queue(struct card *c, uint32_t clocks, double dt)
{
    int i, problem = start(c);
    if (problem < 0)
        stop(c, problem);
    for (i = 0; i < keep_ahead && problem == 0 && c->running; i++) {
        problem = queue_period(c, clocks, dt);
        if (problem)
            stop(c, problem);
    }
    if (c->running && dda_write32(&c->transport, DDA_CONTROL, DDA_CONTROL_ENABLE_MASK) < 0)
        stop(c, FAULT_TRANSPORT);
}

static void write_pass(void *arg, long period)
{
    struct card *c = arg;
    uint64_t ticks = c->fraction + (uint64_t)period * c->clock_hz;
    uint32_t clocks = (uint32_t)(ticks / 1000000000u);
    uint32_t now = 0;
    double dt = period * 1e-9;
    int drive = *c->drive_enable != 0;
    int fault, on = 0, i;
    for (i = 0; i < c->axes; i++)
        on |= *c->axis[i].enable != 0;
    on = on && *c->estop_in && !*c->watchdog_has_bit;
    c->fraction = ticks % 1000000000u;
    if (drive != c->drive_written
        && dda_write32(&c->transport, DDA_MACHINE_CONTROL, drive ? DDA_MACHINE_CONTROL_DRIVE_ENABLE_MASK : 0) == 0)
        c->drive_written = drive;
    if (!on) {
        if (c->running)
            halt_card(c);
        /* what stands whatever enable does (has_bit is written false to go on) */
        fault = standing_fault(c);
        *c->error = fault != 0;
        *c->error_code = fault;
    } else if (!c->running && !*c->error) {
        start_queue(c, clocks, dt);
    } else if (c->running) {
        fault = dda_write32(&c->transport, DDA_WATCHDOG, watchdog_clocks(c)) < 0 ? FAULT_TRANSPORT
                                                                                  : queue_period(c, clocks, dt);
        if (fault)
            stop(c, fault);
    }
    dda_write_encoders(c);
    if (dda_advance(&c->transport, clocks, &now) < 0 && *c->error_code != FAULT_TRANSPORT)
        stop(c, FAULT_TRANSPORT);
    *c->clock = now;
}

/* The functions the servo thread calls: a pass, unless the driver is being unloaded. */
static void read_card(void *arg, long period) { dda_guarded(read_pass, arg, period); }
static void write_card(void *arg, long period) { dda_guarded(write_pass, arg, period); }

static int export_funct(void (*funct)(void *, long), int k, const char *what)
{
    char name[HAL_NAME_LEN + 1];
    rtapi_snprintf(name, sizeof name, "dda-card.%d.%s", k, what);
    return hal_export_funct(name, funct, cards[k], 1, 0, comp_id);
}

/* Each card's pins, parameters and functions: 0, or -EINVAL. */
static int export_cards(void)
{
    int k;
    for (k = 0; k < card_count; k++)
        if (dda_export_card(comp_id, cards[k]) < 0 || (cards[k]->encoders && dda_export_encoders(comp_id, cards[k]) < 0)
            || export_funct(read_card, k, "read") < 0 || export_funct(write_card, k, "write") < 0)
            return -EINVAL;
    return 0;
}

int rtapi_app_main(void)
{
    int problem, k;
    if (dda_check_keep_ahead(keep_ahead) < 0)
        return -EINVAL;
    if (sim[0] && sim_timeout_ms < 1) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: sim_timeout_ms=%d: give 1 ms or more\n", sim_timeout_ms);
        return -EINVAL;
    }
    comp_id = hal_init("dda_card");
    if (comp_id < 0)
        return comp_id;
    card_count = dda_open_cards(cards, sim, sim_timeout_ms, keep_ahead);
    problem = card_count < 0 ? card_count : export_cards();
    if (problem) {
        if (card_count > 0)
            dda_close_cards(cards, card_count);
        hal_exit(comp_id);
        return problem;
    }
    for (k = 0; k < card_count; k++)
        rtapi_print_msg(RTAPI_MSG_INFO, "dda_card: %s, %d axes, %u Hz, registers %s\n", cards[k]->transport.name,
                        cards[k]->axes, cards[k]->clock_hz, cards[k]->transport.regs ? "mapped"
                        : cards[k]->transport.sock >= 0 ? "on the socket" : "by pread/pwrite");
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    int k, limit_ms = 2 * sim_timeout_ms + 1000;
    if (dda_wait_outside(limit_ms) < 0)
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: a servo thread is still inside the driver after %d ms; "
                        "unloading anyway\n", limit_ms);
    for (k = 0; k < card_count; k++) {
        halt_card(cards[k]);
        dda_write32(&cards[k]->transport, DDA_MACHINE_CONTROL, 0);
    }
    dda_close_cards(cards, card_count);
    hal_exit(comp_id);
}
