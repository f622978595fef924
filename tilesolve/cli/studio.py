"""``tilesolve studio``: the local web page over every family (:mod:`tilesolve.studio`)."""

from __future__ import annotations

import ipaddress
import os
import socket

import click

from tilesolve.cli import options as opt
from tilesolve.cli.common import say
from tilesolve.errors import InvalidProblem

__all__ = ["studio", "is_loopback", "listen"]


def is_loopback(host: str) -> bool:
    """True for ``localhost`` and loopback addresses (127.0.0.0/8, ::1)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def listen(host: str, port: int) -> socket.socket:
    """A socket listening on ``host:port``; an unknown host or a port in use is
    :class:`InvalidProblem` (exit 2), before the server starts."""
    try:
        family, _, _, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM,
                                                      flags=socket.AI_PASSIVE)[0]
    except (socket.gaierror, UnicodeError) as exc:
        raise InvalidProblem(f"--host {host}: unknown host ({getattr(exc, 'strerror', None) or exc})") from None
    try:
        return socket.create_server(address[:2], family=family)
    except OSError as exc:
        why = os.strerror(exc.errno) if exc.errno else str(exc)  # create_server appends the address
        raise InvalidProblem(f"cannot listen on {host} port {port}: {why.lower()}") from None


@click.command(context_settings=opt.CONTEXT_SETTINGS, short_help="The studio: a local web page to design, solve, "
               "check and export tilings.")
@click.option("--port", type=click.IntRange(0, 65535), default=8765, show_default=True, metavar="P",
              help="TCP port (0: any free port).")
@click.option("--host", default="127.0.0.1", show_default=True, metavar="H",
              help="Address to listen on; anything but loopback makes the studio reachable from other machines. The "
                   "server answers only requests addressed to this host (or localhost, on loopback) and port.")
@click.option("--no-browser", is_flag=True, help="Do not open the page in a web browser.")
@click.option("--exit-after", type=opt.Seconds(), default=None, metavar="S",
              help="Stop the server after S seconds (scripts and smoke tests); by default it runs until Ctrl-C.")
def studio(port, host, no_browser, exit_after) -> None:
    """Serve the studio page: pick a family, fill its form, solve, edit by clicking, pan over
    infinite walls and tilings, export the CLI's files and the command that reproduces them.

    Run it as `tilesolve studio` and the page opens at http://127.0.0.1:8765/; Ctrl-C stops
    the server, and its solver processes end with it. Only the studio's own page may start
    solves (other pages' requests are refused), and a solve may use 2 GiB of memory: larger
    problems are refused with an estimate. Needs the studio extra: pip install 'tilesolve[studio]'.

    \b
    Example:
      tilesolve studio --port 0 --no-browser --exit-after 3     # serves on a free port for 3 s
    """
    try:
        import uvicorn

        from tilesolve.studio.app import create_app
    except ImportError as exc:
        raise InvalidProblem(f"the studio needs {exc.name}: pip install 'tilesolve[studio]'") from None
    sock = listen(host, port)
    if not is_loopback(host):
        say(f"tilesolve: warning: --host {host} serves the studio to other machines; it has no login")
    try:
        ipaddress.ip_address(host)
        names = ()
    except ValueError:
        names = (host,)  # a name: requests may address the server by it
    config = uvicorn.Config(create_app(names=names), log_level="warning")
    server = uvicorn.Server(config)

    def _announce() -> None:
        """Once the server listens: say where, and open the page unless --no-browser."""
        import threading

        while not server.started:
            if server.should_exit:
                return
            threading.Event().wait(0.05)
        bound = sock.getsockname()[1]
        shown = {"0.0.0.0": "127.0.0.1", "::": "::1"}.get(host, host)
        url = f"http://{'[' + shown + ']' if ':' in shown else shown}:{bound}/"
        say(f"tilesolve studio on {url} (Ctrl-C stops it)")
        if not no_browser:
            import webbrowser

            webbrowser.open(url)

    import threading

    threading.Thread(target=_announce, daemon=True).start()
    if exit_after is not None:
        timer = threading.Timer(exit_after, lambda: setattr(server, "should_exit", True))
        timer.daemon = True
        timer.start()
    server.run(sockets=[sock])
