"""Static timing over nextpnr's SDF: the delays nextpnr itself uses, every path.

nextpnr's report keeps the worst path of each clock pair only; the pin
figures and the path lists of the flow need every path, so they come from
a pass of the flow's own over the SDF nextpnr writes (``TimingGraph``).
Delays are the SDF's maximum figures, in ps.
"""
import re
from collections import defaultdict

# Clock inputs of registers and memories (iCE40 logic cells, I/O cells and
# RAM; ECP5 flip-flops, block and distributed RAM): arcs from them are
# clock-to-output, not logic.
CLOCK_PINS = {"CLK", "RCLK", "WCLK", "INPUT_CLK", "OUTPUT_CLK", "CLOCK", "CLKA", "CLKB", "WCK"}

_SDF_CELL = re.compile(r"\(CELL\s*\(CELLTYPE \"([^\"]+)\"\)\s*\(INSTANCE ([^)]*)\)")
_SDF_INTERCONNECT = re.compile(r"\(INTERCONNECT (\S+) (\S+) \((\d+):(\d+):(\d+)\)")
_SDF_IOPATH = re.compile(r"\(IOPATH (\S+) (\S+) \((\d+):(\d+):(\d+)\)")
_SDF_SETUP = re.compile(r"\(SETUPHOLD \((?:posedge|negedge) (\S+)\) \((?:posedge|negedge) (\S+)\) \((\d+):(\d+):(\d+)\)")


def _unescape(name):
    return name.replace("\\", "")


def _split_pin(path):
    instance, _, port = _unescape(path).rpartition("/")
    return instance, port


class TimingGraph:
    """Delays from nextpnr's SDF (ps): nets, cell arcs and set-up checks."""

    def __init__(self, sdf_text):
        self.fanout = defaultdict(list)
        self.fanin = defaultdict(list)
        self.arcs_to = defaultdict(list)
        self.arcs_from = defaultdict(list)
        self.clock_to_q = {}
        self.setup = {}
        self.cell_type = {}
        self._parse(sdf_text)

    def _parse(self, text):
        cells = _SDF_CELL.split(text)
        top = cells[0]
        for match in _SDF_INTERCONNECT.finditer(top):
            src, dst, delay = _split_pin(match[1]), _split_pin(match[2]), int(match[5])
            self.fanout[src].append((dst, delay))
            self.fanin[dst].append((src, delay))
        for index in range(1, len(cells), 3):
            kind, instance, body = cells[index], _unescape(cells[index + 1].strip()), cells[index + 2]
            self.cell_type[instance] = kind
            if instance == "":
                for match in _SDF_INTERCONNECT.finditer(body):
                    src, dst, delay = _split_pin(match[1]), _split_pin(match[2]), int(match[5])
                    self.fanout[src].append((dst, delay))
                    self.fanin[dst].append((src, delay))
                continue
            for match in _SDF_IOPATH.finditer(body):
                src, dst, delay = match[1], match[2], int(match[5])
                if src in CLOCK_PINS:
                    self.clock_to_q[(instance, dst)] = (src, delay)
                else:
                    self.arcs_from[(instance, src)].append(((instance, dst), delay))
                    self.arcs_to[(instance, dst)].append(((instance, src), delay))
            for match in _SDF_SETUP.finditer(body):
                node = (instance, match[1])
                self.setup[node] = max(self.setup.get(node, 0), int(match[5]))

    def worst_to_register(self, start):
        """Longest path from ``start`` to a register's set-up: (ps, cells passed), or None."""
        worst = None
        stack, best = [(start, 0, 0)], {}
        while stack:
            node, arrival, cells = stack.pop()
            if best.get(node, -1) >= arrival:
                continue
            best[node] = arrival
            if node in self.setup and node != start:
                total = (arrival + self.setup[node], cells)
                worst = total if worst is None else max(worst, total)
                continue
            for nxt, delay in self.fanout.get(node, ()):
                stack.append((nxt, arrival + delay, cells))
            for nxt, delay in self.arcs_from.get(node, ()):
                stack.append((nxt, arrival + delay, cells + 1))
        return worst

    def worst_from_register(self, end, inputs):
        """Longest path (ps) from a clock edge at the global buffer to ``end``.

        It includes the global net to the register's clock pin; a path from an
        unregistered input pin in ``inputs`` counts from 0.
        """
        memo = {}

        def arrival(node):
            if node in memo:
                return memo[node]
            memo[node] = None
            if node in self.clock_to_q:
                clock_pin, delay = self.clock_to_q[node]
                clock_net = [d for _, d in self.fanin.get((node[0], clock_pin), [])]
                value = delay + max(clock_net, default=0)
            elif node in inputs:
                value = 0
            else:
                edges = self.fanin.get(node, []) + self.arcs_to.get(node, [])
                candidates = [arrival(src) for src, _ in edges]
                candidates = [a + d for a, (_, d) in zip(candidates, edges) if a is not None]
                value = max(candidates) if candidates else None
            memo[node] = value
            return value

        return arrival(end)

    def register_paths(self):
        """Worst path from any register's clock edge to each set-up check.

        A static timing pass over the whole SDF (nextpnr's report keeps only
        the worst path of each clock pair).  Clock insertion is left out, as
        in nextpnr's own figure.  Returns ``{end node: (ps, steps)}`` where
        ``steps`` lists the path's ``(node, kind)`` from the start register's
        output, ``kind`` being "register", "net" or "cell".
        """
        edges = defaultdict(list)
        for src, outs in self.fanout.items():
            edges[src] += [(dst, delay, "net") for dst, delay in outs]
        for src, outs in self.arcs_from.items():
            edges[src] += [(dst, delay, "cell") for dst, delay in outs]
        arrival = {node: delay for node, (_, delay) in self.clock_to_q.items()}
        came_from = {node: (None, "register") for node in arrival}
        indegree, seen, stack = defaultdict(int), set(arrival), list(arrival)
        while stack:
            for dst, _, _ in edges.get(stack.pop(), ()):
                if dst in self.clock_to_q:
                    continue
                indegree[dst] += 1
                if dst not in seen:
                    seen.add(dst)
                    stack.append(dst)
        ready = list(arrival)
        while ready:
            node = ready.pop()
            for dst, delay, kind in edges.get(node, ()):
                if dst in self.clock_to_q:
                    continue
                if arrival[node] + delay > arrival.get(dst, -1):
                    arrival[dst] = arrival[node] + delay
                    came_from[dst] = (node, kind)
                indegree[dst] -= 1
                if indegree[dst] == 0:
                    ready.append(dst)
        paths = {}
        for end, setup in self.setup.items():
            if end in arrival and indegree[end] == 0:
                steps, node = [], end
                while node is not None:
                    previous, kind = came_from[node]
                    steps.append((node, kind))
                    node = previous
                paths[end] = (arrival[end] + setup, steps[::-1])
        return paths


def ns(picoseconds):
    """ps -> ns, rounded to 10 ps; None stays None."""
    return None if picoseconds is None else round(picoseconds / 1000.0, 2)
