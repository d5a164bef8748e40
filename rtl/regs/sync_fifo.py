"""Synchronous FIFO whose storage maps to block RAM (the card's data FIFO)."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv

from rtl.interfaces import LocalBus, card_reset


@block
def sync_fifo(clock, reset, push, din, pop, dout, flush, level, empty, full, room, *, depth,
              room_places=LocalBus.ROOM_PLACES, output_register=False):
    """First-in first-out buffer of ``depth`` words as wide as ``din``.

    Ports: ``push`` writes ``din`` (ignored when ``full``); ``pop`` reads the
    oldest word into ``dout`` at the clock edge (ignored when ``empty``), so
    ``dout`` is valid the clock after ``pop``; ``flush`` (synchronous) empties
    it; ``level`` counts the words held, ``empty``/``full`` follow it;
    ``room`` (from a flip-flop) is high while at least ``room_places`` places
    are free.  Push and pop in the same clock keep the level.  The storage
    and the read register sit in a process without reset so that they
    become block RAM.
    Parameters: ``depth`` (a power of two above ``room_places``; ``level``
    counts 0..depth), ``room_places`` (2 or more), ``output_register``:
    ``dout`` is a fabric flip-flop, not the block RAM's read register (the
    same words at the same clocks), so that the reader's logic on ``dout``
    starts at a flip-flop and not after the RAM's clock-to-output (5.8 ns on
    ECP5).  The RAM then reads the head word every clock (``head``, at the
    address the read pointer takes at that edge), and a word written where
    the head is read (into an empty FIFO, or one word left and popped)
    comes from ``written``, ``din`` registered, the clock after: ``dout``,
    ``written`` and ``fresh`` in the fabric (on the four-axis ECP5 build 33
    flip-flops more than without, docs/synthesis.md).

        clock  _/~\\_/~\\_/~\\_/~\\_
        push   _/~~~\\__________
        pop    _______/~~~\\____
        level  ==0==X=1=X==0===
        room   ~~~~~\\___/~~~~~~     (three places free at first)
        dout   ==========X=W0==
    """
    levels = room_places
    if levels < 2:
        raise ValueError(f"FIFO room_places must be 2 or more, got {levels}")
    if depth <= levels or depth & (depth - 1):
        raise ValueError(f"FIFO depth must be a power of two above room_places ({levels}), got {depth}")
    if len(dout) != len(din) or level.max != depth + 1:
        raise ValueError(f"sync_fifo: dout must be as wide as din and level count 0..{depth}")
    width = len(din)
    addr_bits = depth.bit_length() - 1
    all_free = (1 << levels) - 1   # ``free`` of the empty FIFO
    storage = [Signal(intbv(0)[width:]) for _ in range(depth)]
    write_addr = Signal(modbv(0)[addr_bits:])
    read_addr = Signal(modbv(0)[addr_bits:])
    count = Signal(intbv(0, min=0, max=depth + 1))
    # count == 0 and the free places as flip-flops (a thermometer: bit k set
    # while more than k places are free), so that the back end's answers to
    # the PCI target start at registers, not at compares; they follow push
    # and pop by shifting, and only the compares of the present count (one
    # word from empty, exactly levels + 1 places free) feed them, which do
    # not wait for push and pop
    is_empty = Signal(bool(1))
    free = Signal(intbv(all_free)[levels:])
    free_beyond = Signal(bool(1))   # more than ``levels`` places free
    one_word = Signal(bool(0))
    last_beyond = Signal(bool(0))   # exactly levels + 1 places free
    do_write = Signal(bool(0))
    do_read = Signal(bool(0))

    @always_comb
    def enables():
        do_write.next = push and free[0]
        do_read.next = pop and not is_empty

    @always_comb
    def near_ends():
        one_word.next = count == 1
        last_beyond.next = count == depth - levels - 1

    @always(clock.posedge)
    def memory():
        if do_write:
            storage[write_addr].next = din
        if do_read:
            dout.next = storage[read_addr]

    head = Signal(intbv(0)[width:])      # the RAM's read register: the word at read_addr, but see ``fresh``
    written = Signal(intbv(0)[width:])   # din at the last edge
    fresh = Signal(bool(0))              # the last edge wrote the word at read_addr: ``head`` holds the old one
    head_addr = Signal(modbv(0)[addr_bits:])

    @always_comb
    def head_address():
        # where read_addr is after this edge: the RAM reads the next head word as it is popped
        if do_read:
            head_addr.next = read_addr + 1
        else:
            head_addr.next = read_addr

    @always(clock.posedge)
    def head_memory():
        if do_write:
            storage[write_addr].next = din
        head.next = storage[head_addr]

    @always_seq(clock.posedge, reset=reset)
    def freshness():
        # the word written at this edge is the head after it: the FIFO was empty, or its one word is read
        fresh.next = do_write and not flush and (is_empty or (one_word and do_read))

    @always(clock.posedge)
    def deliver():
        written.next = din
        if do_read:
            if fresh:
                dout.next = written
            else:
                dout.next = head

    @always_seq(clock.posedge, reset=reset)
    def pointers():
        following = intbv(0, min=0, max=depth + 1)
        following[:] = count
        if flush:
            write_addr.next = 0
            read_addr.next = 0
            following[:] = 0
        else:
            if do_write:
                write_addr.next = write_addr + 1
            if do_read:
                read_addr.next = read_addr + 1
            if do_write and not do_read:
                following[:] = count + 1
            elif do_read and not do_write:
                following[:] = count - 1
        count.next = following
        only_read = do_read and not do_write
        only_write = do_write and not do_read
        is_empty.next = flush or (is_empty and not do_write) or (one_word and only_read)
        if flush:
            free.next = all_free
            free_beyond.next = True
        elif only_write:   # one place fewer: each bit takes the one above
            free.next = concat(free_beyond, free[levels:1])
            free_beyond.next = free_beyond and not last_beyond
        elif only_read:    # one place more
            free.next = concat(free[levels - 1:0], True)
            free_beyond.next = free[levels - 1]

    @always_comb
    def flags():
        level.next = count
        empty.next = is_empty
        full.next = not free[0]
        room.next = free[levels - 1]

    if output_register:
        return enables, near_ends, head_address, head_memory, freshness, deliver, pointers, flags
    return enables, near_ends, memory, pointers, flags


def sync_fifo_ports(depth, width=32):
    """Fresh ports of ``sync_fifo`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), push=Signal(bool(0)),
                din=Signal(intbv(0)[width:]), pop=Signal(bool(0)), dout=Signal(intbv(0)[width:]),
                flush=Signal(bool(0)), level=Signal(intbv(0, min=0, max=depth + 1)),
                empty=Signal(bool(1)), full=Signal(bool(0)), room=Signal(bool(0)))
