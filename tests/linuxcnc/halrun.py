"""halrun scripts on simulated cards, for the driver's tests.

A script runs as LinuxCNC's user on one or more card servers (one a card,
``run/NAME.sock`` and its record ``run/NAME.json``); pins are waited for by
``until.sh`` (halcmd polled) and noted by ``note.sh`` (``note PIN=value`` in
the output).
"""
import json
import socket

from tests.linuxcnc.session import as_user, card_server

HELPERS = {
    # until.sh PIN VALUE: wait (at most 60 s) until halcmd getp PIN prints VALUE (not:VALUE: anything else)
    "until.sh": '#!/bin/sh\nfor i in $(seq 3000); do v=$(halcmd getp "$1"); case "$2" in\n'
                '  not:*) [ "$v" != "${2#not:}" ] && exit 0;; *) [ "$v" = "$2" ] && exit 0;; esac; sleep 0.02\n'
                'done\necho "until: $1 is $(halcmd getp "$1"), not $2" >&2; exit 1\n',
    # note.sh PIN...: print PIN=value for each
    "note.sh": '#!/bin/sh\nfor pin; do echo "note $pin=$(halcmd getp "$pin")"; done\n',
}


def listening_socket(path):
    """A Unix socket at ``path`` waiting for one client, 30 s at most; anyone may connect
    (LinuxCNC runs as another user)."""
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(str(path))
    path.chmod(0o666)
    listener.listen(1)
    listener.settimeout(30)
    return listener


def until(pin, value):
    return f"loadusr -w ./until.sh {pin} {value}\n"


def note(*pins):
    return f"loadusr -w ./note.sh {' '.join(pins)}\n"


def write_scripts(run, scripts):
    """Each of ``scripts`` ({file name: shell text}) into ``run``, executable by LinuxCNC's user."""
    for name, text in scripts.items():
        (run / name).write_text(text)
        (run / name).chmod(0o755)


def run_halrun(run, script, servers):
    """halrun ``script`` with a card server per entry of ``servers`` ({name: server options});
    (output, notes {pin: [values]}, records {name: the server's record})."""
    write_scripts(run, HELPERS)
    (run / "test.hal").write_text(script)
    (run / "test.hal").chmod(0o666)
    started = {}
    try:
        for name, options in servers.items():
            started[name] = card_server(run, *options, name=name)
        result = as_user(["halrun", "-f", str(run / "test.hal")], run, 300)
        for server in started.values():
            server.wait(timeout=60)
    finally:
        for server in started.values():
            server.kill()
    output = result.stdout + result.stderr
    assert result.returncode == 0, output[-3000:]
    notes = {}
    for line in output.splitlines():
        if line.startswith("note "):
            pin, _, value = line[5:].partition("=")
            notes.setdefault(pin, []).append(value)
    return output, notes, {name: json.loads((run / f"{name}.json").read_text()) for name in servers}
