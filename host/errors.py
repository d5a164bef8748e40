"""The error a bad program or drawing raises: what is wrong and where."""


class ProgramError(ValueError):
    """A program line or drawing element the host cannot run.

    ``where`` names the place in the input (``part.ngc:12``, ``drawing.svg#c1``);
    ``str()`` gives ``where: message``.
    """

    def __init__(self, where, message):
        super().__init__(f"{where}: {message}")
        self.where = where
        self.message = message
