"""The DDA setup stage's sequence: which phase it is in, and how far."""
from myhdl import always_comb, block, enum

# the setup stage's states (``rtl/dda/dda_setup.py``) and the clocks of its fixed phases
t_setup = enum("S_IDLE", "S_LINE", "S_PRE", "S_SQUARE", "S_LIMIT", "S_POST", "S_DONE")
PRE_STEPS, LIMIT_STEPS, POST_STEPS = 7, 5, 13


@block
def dda_sequence(cmd, plan, sequence):
    """The next state, step and square of the setup stage (``rtl/dda/dda_setup.py``).

    Ports: ``cmd`` (``DdaPort``: ``start`` and ``line`` read), ``plan``
    (``DdaPlan``: ``taken`` read), ``sequence`` (``SetupSequence``: the
    stage's registers in, their next values out; the stage's carry register
    is set from the next values).  Parameters: none; the squares take
    ``cmd.coord_width`` (W) clocks each.

        state   IDLE  PRE x7  SQUARE x4W  LIMIT x5  POST x13  DONE ... IDLE
        start   _/~\\_______________________________________________________
        taken   _______________________________________________________/~\\_
    A line goes IDLE, LINE, DONE.
    """
    width = cmd.coord_width
    state, step, square = sequence.state, sequence.step, sequence.square
    next_state, next_step, next_square = sequence.next_state, sequence.next_step, sequence.next_square

    @always_comb
    def advance():
        next_state.next = state
        next_step.next = 0
        next_square.next = square
        if state == t_setup.S_IDLE:
            next_square.next = 0
            if cmd.start:
                next_state.next = t_setup.S_PRE
                if cmd.line:
                    next_state.next = t_setup.S_LINE
        elif state == t_setup.S_LINE:
            next_state.next = t_setup.S_DONE
        elif state == t_setup.S_PRE:
            if step == PRE_STEPS - 1:
                next_state.next = t_setup.S_SQUARE
            else:
                next_step.next = step + 1
        elif state == t_setup.S_SQUARE:
            if step == width - 1:
                next_square.next = square + 1
                if square == 3:
                    next_state.next = t_setup.S_LIMIT
            else:
                next_step.next = step + 1
        elif state == t_setup.S_LIMIT:
            if step == LIMIT_STEPS - 1:
                next_state.next = t_setup.S_POST
            else:
                next_step.next = step + 1
        elif state == t_setup.S_POST:
            if step == POST_STEPS - 1:
                next_state.next = t_setup.S_DONE
            else:
                next_step.next = step + 1
        elif plan.taken:
            next_state.next = t_setup.S_IDLE

    return advance
