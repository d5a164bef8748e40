/* dda_card: LinuxCNC HAL driver of the PCI DDA card, position mode.
 *
 * Copyright the PCI DDA card authors.  GPL-2.0-or-later (see COPYING here).
 *
 *   loadrt dda_card [sim=/path/to/socket] [keep_ahead=4] [period_overhead=8]
 *   addf dda-card.0.read servo-thread      (first in the thread)
 *   addf dda-card.0.write servo-thread     (after motion)
 *
 * Each servo period `write` turns the change of every axis's position-cmd
 * (in steps: round(position-cmd * position-scale), so rounding is never
 * carried as error) into one LINE by (dx, dy) steps at one iteration per
 * p clocks (the power of two that covers steplen + stepspace, at least 2)
 * followed by a DWELL that fills the rest of the period, so the card's
 * motion for a period takes exactly that period's card clocks.  The queue
 * is kept `keep_ahead` periods ahead: the position asked for in period k
 * is reached at the end of period k + keep_ahead - 1.  `read` gives position-fb from
 * the card's step counters and STATUS's FIFO level and error.  A FIFO found
 * empty while running, a card error or the card's own stop (its E-stop
 * input, watchdog or a limit) sets `error`, stops the queue and needs enable
 * to fall and rise again.
 *
 * Machine I/O: `drive-enable` goes to MACHINE_CONTROL.DRIVE_ENABLE (the
 * card's DRIVE_ENABLE pin, which the card itself drops when it stops and
 * keeps low after COMMAND.CLEAR_STOP: the restart writes it again);
 * while the queue runs, every period rewrites WATCHDOG with
 * `watchdog.timeout-ns` in card clocks, so a PC that stops driving the card
 * has it stop on its own within that time.  `input.<name>` (estop,
 * limit-pos-x .. limit-neg-y, home-x, home-y) are the card's filtered
 * inputs (MACHINE_STATUS.ACTIVE), read every period: LinuxCNC's home-sw-in
 * and limit pins take them.  A watchdog stop sets
 * `watchdog.has-bit`, which holds the card stopped (and `error` high) until
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

MODULE_AUTHOR("PCI DDA card authors");
MODULE_DESCRIPTION("HAL driver of the PCI DDA card");
MODULE_LICENSE("GPL");

static char *sim = "";
RTAPI_MP_STRING(sim, "Unix socket of python -m sim.card.card_server (empty: the real card on PCI)");
static int keep_ahead = 4;
RTAPI_MP_INT(keep_ahead, "servo periods queued ahead in the card's FIFO");
static int period_overhead = 8;
RTAPI_MP_INT(period_overhead, "card clocks a period's LINE and DWELL take beyond their own");

static const uint32_t POS_REGS[AXES] = {DDA_POS_X, DDA_POS_Y};
/* the input.<name> pins, bit n of MACHINE_STATUS.ACTIVE (INPUT_POLARITY's order) */
static const char *const INPUT_PINS[DDA_INPUTS] = {"estop", "limit-pos-x", "limit-neg-x", "limit-pos-y",
                                                   "limit-neg-y", "home-x", "home-y"};
static int comp_id;
static struct card *card;

static int clocks_of_ns(uint32_t ns)
{
    return (int)(((uint64_t)ns * card->clock_hz + 999999999u) / 1000000000u);
}

/* WATCHDOG's count: the timeout in whole card clocks (rounded up), at most what the register holds. */
static uint32_t watchdog_clocks(struct card *c)
{
    uint64_t clocks = ((uint64_t)c->watchdog_timeout_ns * c->clock_hz + 999999999u) / 1000000000u;
    return clocks > DDA_WATCHDOG_CLOCKS_MASK ? DDA_WATCHDOG_CLOCKS_MASK : (uint32_t)clocks;
}

/* The queue stops now: nothing more leaves the FIFO, the watchdog is off. */
static void halt_card(struct card *c)
{
    c->running = 0;
    *c->drift_trim = 0;
    dda_write32(&c->transport, DDA_CONTROL, 0);
    dda_write32(&c->transport, DDA_COMMAND, DDA_COMMAND_SOFT_RESET_MASK);
    dda_write32(&c->transport, DDA_WATCHDOG, 0);
}

/* The nearest step: the rounding of each period is made afresh from the absolute position. */
static int32_t steps_of(double position)
{
    return (int32_t)floor(position + 0.5);
}

static void stop(struct card *c, int code)
{
    *c->error = 1;
    *c->error_code = code;
    halt_card(c);
}

static const char *reason_name(int reason)
{
    switch (reason) {
    case DDA_STOP_ESTOP: return "its E-stop input";
    case DDA_STOP_WATCHDOG: return "its watchdog (the servo thread stopped writing it in time)";
    case DDA_STOP_LIMIT: return "a limit switch";
    default: return "an unknown reason";
    }
}

/* The card's guard holds it stopped (STATUS.STOPPED): why, on stop-reason.  When that
 * stops the machine (`stopping`): error -3, and a watchdog stop sets has-bit. */
static void card_stopped(struct card *c, int stopping)
{
    uint32_t why = 0;
    dda_read32(&c->transport, DDA_STOP_REASON, &why);
    *c->stop_reason = (int32_t)((why & DDA_STOP_REASON_REASON_MASK) >> DDA_STOP_REASON_REASON_SHIFT);
    if (!stopping)
        return;
    if (*c->stop_reason == DDA_STOP_WATCHDOG)
        *c->watchdog_has_bit = 1;
    stop(c, -3);
    rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: the card stopped the machine: %s\n", reason_name(*c->stop_reason));
}

/* The card's crystal and the PC's timer differ (~100 ppm): left alone the queue
 * would slowly drain or fill.  The whole periods still in the FIFO at the read
 * (its level against the words of each period queued, newest first) are held
 * where they stood at the first read after start: fewer, the card runs fast and
 * each DWELL is lengthened by a step; more, it runs slow and each is shortened.
 * The count moves only when the card's period boundary crosses the read, so the
 * queue stays within a period of where it started.  */
static void trim_drift(struct card *c, int32_t level)
{
    int32_t words = 0;
    int depth = 0;
    while (depth < TRIM_RING && (uint32_t)depth < c->periods_queued) {
        words += c->period_words[(c->periods_queued - 1 - depth) % TRIM_RING];
        if (words > level)
            break;
        depth++;
    }
    if (c->depth_start < 0)
        c->depth_start = depth;
    c->trim_sign = depth < c->depth_start ? 1 : depth > c->depth_start ? -1 : 0;
}

static void read_card(void *arg, long period)
{
    struct card *c = arg;
    uint32_t status, machine, pos;
    int i;
    (void)period;
    if (dda_read32(&c->transport, DDA_STATUS, &status) < 0
        || dda_read32(&c->transport, DDA_MACHINE_STATUS, &machine) < 0) {
        *c->error = 1;
        return;
    }
    *c->fifo_level = (int32_t)((status & DDA_STATUS_FIFO_LEVEL_MASK) >> DDA_STATUS_FIFO_LEVEL_SHIFT);
    *c->estop_active = ((machine & DDA_MACHINE_STATUS_ACTIVE_MASK) >> DDA_MACHINE_STATUS_ACTIVE_SHIFT
                        & DDA_INPUT_POLARITY_ESTOP_MASK) != 0;
    for (i = 0; i < DDA_INPUTS; i++)
        *c->inputs[i] = ((machine & DDA_MACHINE_STATUS_ACTIVE_MASK) >> DDA_MACHINE_STATUS_ACTIVE_SHIFT >> i) & 1;
    if (c->running)
        trim_drift(c, *c->fifo_level);
    if (status & DDA_STATUS_STOPPED_MASK)
        card_stopped(c, c->running);
    else
        *c->stop_reason = 0;
    if (c->running && (status & DDA_STATUS_ERROR_MASK)) {
        stop(c, (int)((status & DDA_STATUS_ERROR_MASK) >> DDA_STATUS_ERROR_SHIFT));
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: the card stopped with error %d\n", *c->error_code);
    } else if (c->running && !(status & DDA_STATUS_BUSY_MASK)) {
        (*c->underruns)++;
        stop(c, -1);
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: the FIFO ran dry: the servo thread fell behind\n");
    }
    for (i = 0; i < AXES; i++) {
        struct stepgen *s = &c->axis[i];
        double scale = s->position_scale != 0.0 ? s->position_scale : 1.0;
        int32_t counts;
        if (dda_read32(&c->transport, POS_REGS[i], &pos) < 0) {
            *c->error = 1;
            return;
        }
        counts = (int32_t)pos + s->offset;
        *s->counts = counts;
        *s->position_fb = counts / scale;
        *s->velocity_fb = (counts - s->last_counts) / scale / (period * 1e-9);
        s->last_counts = counts;
    }
}

/* Set up and start the queue: 0; -1 the card cannot be reached; 1 the card holds
 * itself stopped (its E-stop input is active): error, nothing started. */
static int start(struct card *c)
{
    uint32_t words[DDA_CMD_SET_WORDS * 4];
    uint32_t status = 0;
    unsigned n = 0;
    int i;
    /* release a stop of the card's own; it holds while its E-stop input is active */
    if (dda_write32(&c->transport, DDA_COMMAND, DDA_COMMAND_CLEAR_STOP_MASK) < 0
        || dda_read32(&c->transport, DDA_STATUS, &status) < 0)
        return -1;
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
    c->iteration = FASTEST_ITERATION;
    while (c->iteration < 65536u
           && c->iteration < (uint32_t)(clocks_of_ns(c->axis[0].steplen) + clocks_of_ns(c->axis[0].stepspace)))
        c->iteration *= 2;
    n += dda_cmd_set(&words[n], 65536 / c->iteration, DDA_FEED_RATE_SET_INDEX);
    n += dda_cmd_set(&words[n], clocks_of_ns(c->axis[0].steplen), DDA_STEP_WIDTH_SET_INDEX);
    n += dda_cmd_set(&words[n], clocks_of_ns(c->axis[0].dirsetup), DDA_DIR_SETUP_SET_INDEX);
    n += dda_cmd_set(&words[n], clocks_of_ns(c->axis[0].dirhold), DDA_DIR_HOLD_SET_INDEX);
    for (i = 0; i < AXES; i++) {
        struct stepgen *s = &c->axis[i];
        s->sent = steps_of(*s->position_cmd * s->position_scale);
        s->forward = 0;  /* the soft reset before start put the DIR pins back */
        s->offset = s->sent - (*s->counts - s->offset);
    }
    c->depth_start = -1;
    c->trim_sign = 0;
    /* no ramp: the trajectory planner has shaped the motion, and a stop is immediate */
    if (dda_write32(&c->transport, DDA_RAMP_STEP, 0) < 0 || dda_fifo_write(&c->transport, words, n) < 0
        || dda_write32(&c->transport, DDA_WATCHDOG, watchdog_clocks(c)) < 0)
        return -1;
    c->running = 1;
    return 0;
}

/* One period of motion: LINE by the change in steps and a DWELL for the rest of
 * `clocks`, or a DWELL of `clocks` alone when nothing moves.  What the card's
 * sequencer spends around them (measured on the generated card, see
 * docs/linuxcnc.md): a LINE of N iterations of p clocks and its DWELL d take
 * p * N + d + period_overhead clocks, one more at the fastest rate (p = 2),
 * plus DIR_SETUP when a direction pin changes; a DWELL alone takes d. */
static int queue_period(struct card *c, uint32_t clocks)
{
    uint32_t words[DDA_CMD_LINE_WORDS + DDA_CMD_DWELL_WORDS];
    int32_t delta[AXES];
    int32_t longest = 0;
    int64_t dwell = clocks;
    int32_t step = (int32_t)(clocks >> TRIM_SHIFT) > 1 ? (int32_t)(clocks >> TRIM_SHIFT) : 1;
    int reversal = 0;
    unsigned n = 0;
    int i;
    for (i = 0; i < AXES; i++) {
        struct stepgen *s = &c->axis[i];
        delta[i] = steps_of(*s->position_cmd * s->position_scale) - s->sent;
        if ((delta[i] < 0 ? -delta[i] : delta[i]) > longest)
            longest = delta[i] < 0 ? -delta[i] : delta[i];
        if (delta[i] != 0 && (delta[i] > 0) != s->forward)
            reversal = 1;
    }
    if (longest > 0) {
        dwell -= (int64_t)c->iteration * longest + period_overhead + (c->iteration == FASTEST_ITERATION)
                 + (reversal ? clocks_of_ns(c->axis[0].dirsetup) : 0);
        n = dda_cmd_line(words, delta[0], delta[1], 0);
    }
    *c->drift_trim = c->trim_sign * step;
    dwell += *c->drift_trim;
    if (dwell < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %d steps in one period is more than the card makes in "
                        "%u clocks: lower maxvel or position-scale\n", longest, clocks);
        return -1;
    }
    n += dda_cmd_dwell(&words[n], (uint32_t)dwell);
    if (dda_fifo_write(&c->transport, words, n) < 0)
        return -1;
    c->period_words[c->periods_queued++ % TRIM_RING] = (uint8_t)n;
    for (i = 0; i < AXES; i++) {
        c->axis[i].sent += delta[i];
        if (delta[i] != 0)
            c->axis[i].forward = delta[i] > 0;
    }
    return 0;
}

static void write_card(void *arg, long period)
{
    struct card *c = arg;
    uint64_t ticks = c->fraction + (uint64_t)period * c->clock_hz;
    uint32_t clocks = (uint32_t)(ticks / 1000000000u);
    uint32_t now = 0;
    int enabled = *c->axis[0].enable && *c->axis[1].enable && *c->estop_in && !*c->watchdog_has_bit;
    int drive = *c->drive_enable != 0;
    int i, started;
    c->fraction = ticks % 1000000000u;
    if (drive != c->drive_written
        && dda_write32(&c->transport, DDA_MACHINE_CONTROL,
                       drive ? DDA_MACHINE_CONTROL_DRIVE_ENABLE_MASK : 0) == 0)
        c->drive_written = drive;
    if (!enabled) {
        if (c->running)
            halt_card(c);
        /* a watchdog stop holds the error until has-bit is written false */
        *c->error = *c->watchdog_has_bit;
        *c->error_code = *c->watchdog_has_bit ? -3 : 0;
    } else if (!c->running && !*c->error) {
        started = start(c);
        if (started < 0) {
            stop(c, -2);
        } else if (started == 0) {
            for (i = 0; i < keep_ahead && c->running; i++)
                if (queue_period(c, clocks) < 0)
                    stop(c, -2);
            if (c->running)
                dda_write32(&c->transport, DDA_CONTROL, DDA_CONTROL_ENABLE_MASK);
        }
    } else if (c->running && dda_write32(&c->transport, DDA_WATCHDOG, watchdog_clocks(c)) < 0) {
        stop(c, -2);
    } else if (c->running && queue_period(c, clocks) < 0) {
        stop(c, -2);
    }
    if (dda_advance(&c->transport, clocks, &now) < 0)
        *c->error = 1;
    *c->clock = now;
}

static int export_card(struct card *c)
{
    const char *p = "dda-card.0";
    int r = 0, i;
    for (i = 0; i < AXES; i++)
        r |= dda_export_axis(comp_id, &c->axis[i], i);
    r |= hal_pin_s32_newf(HAL_OUT, &c->fifo_level, comp_id, "%s.fifo-level", p);
    r |= hal_pin_u32_newf(HAL_OUT, &c->underruns, comp_id, "%s.underruns", p);
    r |= hal_pin_bit_newf(HAL_OUT, &c->error, comp_id, "%s.error", p);
    r |= hal_pin_s32_newf(HAL_OUT, &c->error_code, comp_id, "%s.error-code", p);
    r |= hal_pin_u32_newf(HAL_OUT, &c->clock, comp_id, "%s.clock", p);
    r |= hal_pin_s32_newf(HAL_OUT, &c->drift_trim, comp_id, "%s.drift-trim", p);
    r |= hal_pin_bit_newf(HAL_IN, &c->estop_in, comp_id, "%s.estop-in", p);
    r |= hal_pin_bit_newf(HAL_IN, &c->drive_enable, comp_id, "%s.drive-enable", p);
    r |= hal_pin_bit_newf(HAL_OUT, &c->estop_active, comp_id, "%s.estop-active", p);
    for (i = 0; i < DDA_INPUTS; i++)
        r |= hal_pin_bit_newf(HAL_OUT, &c->inputs[i], comp_id, "%s.input.%s", p, INPUT_PINS[i]);
    r |= hal_pin_s32_newf(HAL_OUT, &c->stop_reason, comp_id, "%s.stop-reason", p);
    r |= hal_pin_bit_newf(HAL_IO, &c->watchdog_has_bit, comp_id, "%s.watchdog.has-bit", p);
    r |= hal_param_u32_newf(HAL_RW, &c->watchdog_timeout_ns, comp_id, "%s.watchdog.timeout-ns", p);
    c->watchdog_timeout_ns = 5000000;
    *c->estop_in = 1;
    r |= hal_export_funct("dda-card.0.read", read_card, c, 1, 0, comp_id);
    r |= hal_export_funct("dda-card.0.write", write_card, c, 1, 0, comp_id);
    return r;
}

int rtapi_app_main(void)
{
    uint32_t id;
    comp_id = hal_init("dda_card");
    if (comp_id < 0)
        return comp_id;
    card = hal_malloc(sizeof *card);
    if (!card) {
        hal_exit(comp_id);
        return -ENOMEM;
    }
    memset(card, 0, sizeof *card);
    if ((sim[0] ? dda_sim_open(&card->transport, sim) : dda_pci_open(&card->transport)) < 0) {
        hal_exit(comp_id);
        return -ENODEV;
    }
    if (dda_read32(&card->transport, DDA_ID, &id) < 0
        || (id & DDA_ID_MAGIC_MASK) != (DDA_ID_RESET & DDA_ID_MAGIC_MASK)
        || dda_read32(&card->transport, DDA_CLOCK_HZ, &card->clock_hz) < 0 || card->clock_hz == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "dda_card: %s does not identify as the DDA card (ID %08x)\n",
                        card->transport.name, id);
        dda_transport_close(&card->transport);
        hal_exit(comp_id);
        return -ENODEV;
    }
    /* whatever a previous session left queued stops here, its drives off */
    if (dda_write32(&card->transport, DDA_CONTROL, 0) < 0
        || dda_write32(&card->transport, DDA_COMMAND, DDA_COMMAND_SOFT_RESET_MASK) < 0
        || dda_write32(&card->transport, DDA_WATCHDOG, 0) < 0
        || dda_write32(&card->transport, DDA_MACHINE_CONTROL, 0) < 0
        || export_card(card) < 0) {
        dda_transport_close(&card->transport);
        hal_exit(comp_id);
        return -EINVAL;
    }
    rtapi_print_msg(RTAPI_MSG_INFO, "dda_card: %s, %u Hz\n", card->transport.name, card->clock_hz);
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    halt_card(card);
    dda_write32(&card->transport, DDA_MACHINE_CONTROL, 0);
    dda_transport_close(&card->transport);
    hal_exit(comp_id);
}
