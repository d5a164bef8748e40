"""The simulated machine (``models/sim_machine.py``) on each back end, and one handle to it.

* Verilator: the compiled harness runs it in its clock loop
  (``VerilatedCard.start_machine``): no Python per clock.
* MyHDL and Icarus: ``machine_process`` runs the golden model itself, at each
  falling edge on the pins after the rising edge before it, and sets the
  input pins (and a card with encoders: the motors' encoder pins) for the
  next rising edge.

``MachineHandle`` is what a session, the host's simulated transport and the
card server hand to a user's test: ``press_estop``, ``release_estop``,
``stall(axis)``, ``state()`` (positions, steps lost, the input pins, the
motors' encoder counts).
"""
from dataclasses import dataclass

from myhdl import block, delay, instance

from models.sim_machine import INPUTS, MOTOR_AXES


@dataclass(frozen=True)
class MachineState:
    """The simulated machine now, per axis of the card: ``positions`` (steps
    its axes moved to), ``lost`` (STEP rises per axis the axis did not follow:
    DRIVE_ENABLE low, or its motor stalled), ``inputs`` (the pins, bit n:
    ``INPUT_NAMES[n]``), ``estop`` (pressed) and ``counts`` (per axis its
    motor's encoder count, None without a motor)."""
    positions: tuple
    lost: tuple
    inputs: int
    estop: bool
    counts: tuple = (None, None)

    def pin(self, name):
        return bool(self.inputs >> INPUTS.index(name) & 1)


@block
def machine_process(clock, pins, machine, encoder_changes=None):
    """``machine`` (a ``SimMachine`` of the card's axes) on ``pins`` (``MotorPins``);
    ``encoder_changes``: a list that gets (clock, word) of each change of its
    encoder word (``SimMachine.encoder_pins``; clock: the machine's, the pin
    log's numbering), the first word when it starts."""
    inputs = [getattr(pins, name.lower()) for name in machine.inputs]
    axes = MOTOR_AXES[:machine.axes]
    outputs = [getattr(pins, f"{kind}_{name.lower()}") for name in axes for kind in ("step", "dir")]
    outputs.append(pins.drive_enable)
    encoders = [getattr(pins, f"{pin}_{name.lower()}", None) for name in axes
                for pin in ("enc_a", "enc_b", "enc_index")]
    if machine.config.motors and encoders[0] is None:
        raise ValueError("the machine's motors drive encoder inputs: the card must be built with encoders")

    @instance
    def run():
        while True:
            yield clock.negedge
            word = machine.clock(*(bool(pin) for pin in outputs))
            encoder_word = machine.encoder_pins
            if encoder_changes is not None and (not encoder_changes or encoder_changes[-1][1] != encoder_word):
                encoder_changes.append((machine.clocks, encoder_word))
            yield delay(1)
            for bit, pin in enumerate(inputs):
                pin.next = bool(word >> bit & 1)
            for bit, pin in enumerate(encoders):
                if pin is not None:
                    pin.next = bool(encoder_word >> bit & 1)

    return run


class MachineHandle:
    """The machine of a simulated card: on Verilator ``model`` (a
    ``VerilatedModel`` running it), else ``machine`` (the ``SimMachine`` a
    ``machine_process`` runs)."""

    def __init__(self, config, model=None, machine=None, encoder_changes=None):
        self.config, self._model, self._machine = config, model, machine
        self._encoder_changes = encoder_changes   # machine_process's record (MyHDL, Icarus)
        self._taken = []
        self._estop = False

    def press_estop(self, pressed=True):
        """Press (or release) the E-stop: the pin changes before the next rising edge."""
        self._estop = bool(pressed)
        if self._model is not None:
            self._model.press_estop(pressed)
        else:
            self._machine.press_estop(pressed)

    def release_estop(self):
        self.press_estop(False)

    def stall(self, axis, stalled=True):
        """Stall (or free) the motor of ``axis`` (0: X): from the next clock on it no longer turns."""
        if not 0 <= axis < len(MOTOR_AXES) or MOTOR_AXES[axis] not in self.config.motors:
            raise ValueError(f"axis {axis} has no motor")
        if self._model is not None:
            self._model.stall(axis, stalled)
        else:
            self._machine.stall(axis, stalled)

    def state(self):
        if self._model is not None:
            positions, lost, inputs = self._model.machine_state()
            counts = self._model.machine_encoders()[0]
        else:
            positions, lost, inputs = tuple(self._machine.positions), tuple(self._machine.lost), self._machine.pins
            counts = [motor.counts if motor else None for motor in self._machine.motors]
        counts = tuple(c if name in self.config.motors else None for c, name in zip(counts, MOTOR_AXES))
        return MachineState(tuple(positions), tuple(lost), int(inputs), self._estop, counts)

    def encoder_changes(self):
        """[(clock, word)] of every change of the motors' encoder word so far
        (``SimMachine.encoder_pins``, set after the rising edge ``clock``; the
        first: the word the machine started with)."""
        if self._model is not None:
            clocks, words = self._model.take_encoder_changes()
            self._taken += zip(clocks.tolist(), words.tolist())
            return list(self._taken)
        return list(self._encoder_changes)
