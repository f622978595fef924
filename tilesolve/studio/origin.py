"""The studio answers only requests addressed to it, and changes state only for its own page.

:class:`OwnOrigin` is an ASGI middleware with three rules, each a 403 ``{"error": ...}``:

1. **Host.** The ``Host`` header must name the listening socket the request arrived on: its
   port, and its address (``127.0.0.1``, ``[::1]``), ``localhost`` when that address is a
   loopback one, or a name the server was started with (``tilesolve studio --host NAME``).
   A page of another site whose name was pointed at 127.0.0.1 (DNS rebinding) sends its own
   name, so it can neither start solves nor read a job's result.
2. **State changes** (every method but GET, HEAD and OPTIONS) must come from the studio's own
   page: ``Origin`` equal to ``http://`` and the ``Host``, ``Sec-Fetch-Site: same-origin`` when
   the browser sends that header, and ``Content-Type: application/json``. Another page can post
   ``text/plain`` forms and fetches without asking (no CORS preflight), never JSON.
3. **Reads of the API** (``/api/...``) flagged ``Sec-Fetch-Site: cross-site`` or ``same-site``
   are refused, so that another page's ``<img>`` cannot make the server draw views. The page
   itself (``/``) may be opened from a link anywhere.

Starlette's ``TrustedHostMiddleware`` checks the name but not the port, and wants the names
when the app is made, before a server started with ``--port 0`` knows its port; the socket in
the request's scope (``scope["server"]``) gives both.
"""

from __future__ import annotations

import ipaddress

from starlette.datastructures import Headers
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Receive, Scope, Send

__all__ = ["OwnOrigin"]

#: Methods that change nothing.
_SAFE = frozenset({"GET", "HEAD", "OPTIONS"})


def _bracketed(address: str) -> str:
    """An address as written in a ``Host`` header (IPv6 in brackets)."""
    return f"[{address}]" if ":" in address else address


def _is_loopback(address: str) -> bool:
    try:
        return ipaddress.ip_address(address).is_loopback
    except ValueError:
        return False


class OwnOrigin:
    """ASGI middleware enforcing the module's rules.

    Parameters
    ----------
    app : ASGI app
    names : iterable of str
        Host names accepted besides the listening address (and ``localhost`` for loopback).
    """

    def __init__(self, app: ASGIApp, names=()) -> None:
        self.app = app
        self.names = frozenset(n.lower() for n in names)

    def _hosts(self, scope: Scope) -> tuple[str, ...]:
        """The ``Host`` values accepted on the socket of this request, e.g. ``127.0.0.1:8765``."""
        server = scope.get("server")
        if not server or server[1] is None:
            return ()
        address, port = str(server[0]).lower(), int(server[1])
        names = {_bracketed(address), *self.names} | ({"localhost"} if _is_loopback(address) else set())
        hosts = {f"{n}:{port}" for n in names} | (names if port == 80 else set())
        return tuple(sorted(hosts))

    def refusal(self, scope: Scope) -> str | None:
        """Why the request is refused (one line), or None."""
        headers = Headers(scope=scope)
        host = headers.get("host", "").lower()
        hosts = self._hosts(scope)
        if host not in hosts:
            return (f"refused: this server answers requests for {' or '.join(hosts) or 'no host'}, not for "
                    f"host {headers.get('host', '(none)')[:100]!r}")
        site = headers.get("sec-fetch-site")
        if scope["method"] in _SAFE:
            if site in ("cross-site", "same-site") and scope["path"].startswith("/api/"):
                return f"refused: the studio's API answers its own page only, not a {site} request"
            return None
        origin = headers.get("origin")
        if origin is None or origin.lower() != f"http://{host}" or site not in (None, "same-origin"):
            sender = repr(origin[:100]) if origin else "a request without an Origin header"
            return f"refused: a change must come from the studio's own page (origin http://{host}), not from {sender}"
        media = headers.get("content-type", "").split(";", 1)[0].strip().lower()
        if media != "application/json":
            return "refused: a change must be sent as JSON (Content-Type: application/json)"
        return None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            why = self.refusal(scope)
            if why is not None:
                await JSONResponse({"error": why}, status_code=403)(scope, receive, send)
                return
        await self.app(scope, receive, send)
