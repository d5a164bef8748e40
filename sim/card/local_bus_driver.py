"""Bus-functional driver of the PCI target's back-end bus (``LocalBus``), for unit benches.

Requests are driven after the falling edge and held until ``ready`` or
``retry`` is seen at a rising edge, as ``rtl.interfaces.LocalBus`` says.
Every write is a handshake (like the target's first data phase), so the
driver needs no room; it checks the back end's promise instead: a memory
write refused while ``room`` was high raises ``AssertionError``.
Every method is a generator to be delegated to with ``yield from``.
"""
from myhdl import delay

IO_SPACE, MEMORY_SPACE = 0, 1
SETTLE = 1  # time units after the falling edge for combinational answers


class LocalBusDriver:
    def __init__(self, clock, local):
        self.clock = clock
        self.local = local
        self.retries = 0
        self.transfer_clocks = []

    def _request(self, space, addr, be, wdata, write):
        local = self.local
        local.space.next = space
        local.addr.next = addr
        local.be.next = be
        local.wdata.next = wdata
        local.we.next = write
        local.re.next = not write
        local.write.next = write

    def _check_promise(self, space, write):
        local = self.local
        if write and space == MEMORY_SPACE and bool(local.retry) and bool(local.room):
            raise AssertionError("the back end refused a memory write while it showed room")

    def _idle(self):
        self.local.we.next = 0
        self.local.re.next = 0

    def transfer(self, space, addr, data=0, be=0xF, write=True, give_up_on_retry=False):
        """One transfer; returns (read data, accepted).  On retry the request is
        dropped for a clock and made again, unless ``give_up_on_retry``."""
        while True:
            self._request(space, addr, be, data, write)
            yield delay(SETTLE)
            ready, retry, rdata = bool(self.local.ready), bool(self.local.retry), int(self.local.rdata)
            self._check_promise(space, write)
            yield self.clock.negedge
            if ready:
                self._idle()
                return rdata, True
            if retry:
                self.retries += 1
                self._idle()
                if give_up_on_retry:
                    return 0, False
                yield self.clock.negedge

    def io_write(self, offset, data, be=0xF):
        yield from self.transfer(IO_SPACE, offset, data, be, write=True)

    def io_read(self, offset):
        """Generator returning the word read."""
        data, _ = yield from self.transfer(IO_SPACE, offset, write=False)
        return data

    def burst(self, words):
        """Memory-BAR writes on consecutive clocks, the way a PCI burst arrives;
        returns how many were accepted before the first retry."""
        local = self.local
        for index, word in enumerate(words):
            self._request(MEMORY_SPACE, (4 * index) & 0xFFF, 0xF, word, True)
            while True:  # a wait state holds the word
                yield delay(SETTLE)
                self._check_promise(MEMORY_SPACE, True)
                if bool(local.retry):
                    self.retries += 1
                    self._idle()
                    yield self.clock.negedge
                    return index
                accepted = bool(local.ready)
                yield self.clock.negedge
                if accepted:
                    break
        self._idle()
        return len(words)

    def push_all(self, words):
        """Every word into the FIFO, bursting and retrying until all are taken."""
        sent = 0
        while sent < len(words):
            sent += yield from self.burst(words[sent:])
