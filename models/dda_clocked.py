"""Clock-level golden model of the DDA unit: ``ClockedDda``."""
from models.dda_build import ALL_VARIANTS, left_width
from models.dda_model import iterations_left_bound, iterator_for
from models.dda_plan import LineCommand, setup_clocks


class ClockedDda:
    """Clock-level model of ``rtl/dda_arc.py``: call ``clock()`` once per rising edge.

    ``clock(start, advance, command)`` takes the inputs sampled at the edge
    (``command``: the ``ArcCommand``/``LineCommand`` on the cmd lines, read
    when ``start`` is taken) and returns the registered outputs after it.

    Two stages, as in the hardware.  The setup stage takes a ``start`` while
    it is free (``ready``), counts the setup clocks and then offers the
    checked move.  An iteration takes two clocks: at the edge of its
    ``advance`` it makes its step outputs (and ``done`` with the last one);
    at the next edge it is applied (``quadrant`` follows then) and an
    ``advance`` there is ignored.  The run takes the offered move at an edge
    where it is idle or applies its running move's last iteration, so the
    next ``advance`` already iterates the new move.  A rejected move
    (``error``) or a line of length 0 (``done``) is handed over at the same
    edges only.  ``stop_left`` after an edge is, for the running move as the
    last applied iteration (or the handover) up to that edge left it,
    ``iterations_left_bound`` minus one (not below 0): in the second clock of
    an iteration it still counts the iteration under way, so the minus one
    keeps it a lower bound at every clock; the all-ones value while no move
    runs or the running one blends.  ``busy`` falls with the last ``done``.
    Every started move gets a number (0, 1, ...); ``step_move``,
    ``done_move`` and ``error_move`` say which move the outputs of the last
    edge belong to.  ``variants``: those the card was built with (a command
    for another is rejected).
    """

    def __init__(self, coord_width=24, variants=ALL_VARIANTS):
        self.coord_width = coord_width
        self.variants = variants
        self.all_ones = (1 << left_width(coord_width)) - 1
        self.started = 0
        self.setup = None       # [command, number, setup clocks left]
        self.run = None         # (iterator, command, number)
        self.pending = False    # an iteration was taken at the last edge: applied at this one
        self.left = None        # (blend, bound - 1) of the running move as last applied
        self.step_move = self.done_move = self.error_move = None
        self.outputs = dict(busy=False, ready=True, done=False, error=False, step_x=False,
                            step_y=False, dir_x=False, dir_y=False, quadrant=0,
                            stop_left=self.all_ones)

    def _stop_left(self):
        if self.left is None or self.left[0]:
            return self.all_ones
        return max(self.left[1], 0)

    def _applied(self, iterator, command):
        self.left = (command.blend, iterations_left_bound(iterator) - 1)

    def clock(self, start, advance, command):
        out = self.outputs
        out.update(done=False, step_x=False, step_y=False)
        self.step_move = self.done_move = self.error_move = None
        was_running = self.run is not None
        finishing = False
        if self.pending:
            self.pending = False
            iterator, run_command, _ = self.run
            out["quadrant"] = iterator.quadrant
            self._applied(iterator, run_command)
            if iterator.finished:
                finishing = True
                self.run = None
                self.left = None
        elif was_running and advance:
            self._iterate()
            self.pending = True
        self._setup_edge(start, command, was_running, finishing)
        ending = self.pending and self.run[0].finished
        out.update(stop_left=self._stop_left(), ready=self.setup is None,
                   busy=self.setup is not None or (self.run is not None and not ending))
        return dict(out)

    def _iterate(self):
        """The first clock of an iteration of the running move: its outputs."""
        out = self.outputs
        iterator, _, number = self.run
        step = iterator.step()
        self.step_move = number
        out.update(step_x=step.step_x, step_y=step.step_y, dir_x=step.dir_x, dir_y=step.dir_y)
        if iterator.finished:
            self.done_move = number
            out["done"] = True

    def _setup_edge(self, start, command, was_running, finishing):
        out = self.outputs
        if self.setup is None:
            if start:
                out["error"] = False
                self.setup = [command, self.started, setup_clocks(self.coord_width,
                                                                  isinstance(command, LineCommand))]
                self.started += 1
            return
        if self.setup[2] > 1:
            self.setup[2] -= 1
            return
        if was_running and not finishing:
            return
        command, number, _ = self.setup
        self.setup = None
        try:
            iterator = iterator_for(command, self.coord_width, self.variants)
        except ValueError:
            self.error_move = number
            out["error"] = True
            return
        if iterator.finished:
            self.done_move = number
            out.update(done=True, quadrant=iterator.quadrant)
            return
        self.run = (iterator, command, number)
        out["quadrant"] = iterator.quadrant
        self._applied(iterator, command)
