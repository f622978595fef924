"""The studio's server: a Starlette app over the family registry.

Endpoints (JSON in and out; every user mistake is HTTP 400 ``{"error": "<the CLI's one-line
message>"}``):

``GET /``                           the page (``static/index.html``)
``GET /api/families``               every family with a form: name, title, methods, fields, view,
                                    the picture formats it draws; and the pictures' tile palette
``POST /api/check``                 ``{family, values}`` -> the problem's description, the
                                    painted grids' extents, the CLI command, and the tile's
                                    sides for the live edge editor (``sketch``, or null)
``POST /api/solve``                 ``{family, values, method, time_limit}`` -> ``{id}`` (a job)
``GET /api/jobs/{id}?wait=S``       the job: state, elapsed time, progress, and when done its
                                    result (status, method, verdict, picture, solution JSON, command)
``GET /api/jobs/{id}/events``       the job's progress as Server-Sent Events: the job's state
                                    without its result (``data: {...}``), sent when its progress
                                    changes and at least every :data:`EVENT_EVERY_S` seconds,
                                    the last one when it has ended
``POST /api/jobs/{id}/cancel``      end a running solve
``GET /api/jobs/{id}/solution.json|picture.svg|picture.png``  the exports (the CLI's files)
``GET /api/view/{family}.png?values=JSON&x=&y=&n=&palette=&look=``  one n x n window of an
                                    infinite procedural view (pan and zoom), x/y its bottom-left
                                    cell; ``palette`` (``RRGGBB,...``, optional): the page's chosen
                                    colours; ``look``: ``picture`` (default) or ``texture``
``GET /api/webgl/{family}?values=JSON&palette=&look=``  the shaders with which the page draws
                                    that view itself (WebGL2: the procedural wall, in those colours;
                                    the texture look), or ``{"kind": null}``

The page sends values, never paths: no endpoint reads or writes a file named by a request.
Only requests addressed to the server's own socket are answered, and only the studio's own
page may post (:mod:`tilesolve.studio.origin`, 403 otherwise). Request bodies are limited to
:data:`MAX_BODY` bytes while they are read (413 beyond), every size in a form is checked
against its field's limit before anything is allocated, and a solve whose encoding is
estimated to need more memory than a solve may use is refused with the estimate
(:mod:`tilesolve.studio.sizing`). Error messages are the CLI's, never a Python class name.
"""

from __future__ import annotations

import contextlib
import ctypes
import functools
import gc
import json
import os
import sys
import threading
import traceback

import anyio
from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response, StreamingResponse
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from tilesolve import family
from tilesolve.errors import InvalidProblem, TilesolveError
from tilesolve.io.svg import FREE_COLOUR, tile_colour
from tilesolve.studio import sizing, worker
from tilesolve.studio.jobs import Jobs, TooBusy
from tilesolve.studio.origin import OwnOrigin
from tilesolve.studio.views import Views

__all__ = ["create_app", "MAX_BODY", "MAX_VIEW_CELLS", "STATIC"]

#: Largest request body (bytes): a painted 1024 x 1024 grid fits.
MAX_BODY = 8 << 20
#: Largest window side of a procedural view tile (cells).
MAX_VIEW_CELLS = 128
#: Most seconds between two events of a job's event stream (the elapsed time moves on).
EVENT_EVERY_S = 1.0
#: Requests read, parsed and posed at once (a painted 1024 x 1024 grid takes tens of MiB while
#: posed); the others wait with their bodies unread.
POSING = 2
#: Bodies from this size on are followed by :func:`_release_memory`.
LARGE_BODY = 1 << 20

STATIC = os.path.join(os.path.dirname(__file__), "static")

#: The tile colours of every picture (:func:`tilesolve.io.svg.tile_colour`, the SVG and PNG
#: writers' palette) for the page's editor: ``tiles`` for tiles ``0 ..``, ``free`` for ``-1``.
PALETTE = {"tiles": [tile_colour(k) for k in range(256)], "free": FREE_COLOUR}


def _error(message: str, status: int = 400) -> JSONResponse:
    return JSONResponse({"error": " ".join(str(message).split())}, status_code=status)


async def _body(request: Request) -> bytearray:
    """The body of a request, at most :data:`MAX_BODY` bytes: a larger ``Content-Length`` is
    refused before reading, and a body without one is refused as soon as it grows past."""
    length = request.headers.get("content-length")
    if length is not None and (not length.isdigit() or int(length) > MAX_BODY):
        raise InvalidProblem(f"request too large (at most {MAX_BODY:,} bytes)")
    data = bytearray()
    async for chunk in request.stream():
        data += chunk
        if len(data) > MAX_BODY:
            raise InvalidProblem(f"request too large (at most {MAX_BODY:,} bytes)")
    request.state.large_body = len(data) >= LARGE_BODY
    return data


def _json(data: bytearray) -> dict:
    """The JSON object of a request body."""
    try:
        doc = json.loads(data or b"{}")
    except (ValueError, UnicodeDecodeError):
        raise InvalidProblem("the request is not JSON") from None
    if not isinstance(doc, dict):
        raise InvalidProblem("the request must be a JSON object")
    return doc


def _release_memory() -> None:
    """Free what a large request left behind and give it back to the system. A refused request's
    error keeps, through its traceback's frames, the parsed body in a reference cycle, which
    only Python's cyclic collector frees (and, for objects that large, only at its rare full
    collections): without a collection here the server's resident size kept the memory of
    every large request it had refused. Then glibc's ``malloc_trim`` returns the freed pages."""
    gc.collect()
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None).malloc_trim(0)


#: Messages for errors Python raises on odd requests (never the class's name).
_PYTHON_ERRORS = {RecursionError: "the request is nested too deeply", MemoryError: "out of memory for this request",
                  OverflowError: "a number is too large"}


def _guard(handler):
    """Turn library errors into HTTP 400 ``{"error": ...}`` (413 for a large body, 429 when busy,
    500 ``internal error`` for a bug, whose traceback goes to the server's standard error);
    after a large body, once the handler has dropped it, :func:`_release_memory`."""

    @functools.wraps(handler)
    async def wrapped(request: Request) -> Response:
        try:
            return await handler(request)
        except TooBusy as exc:
            return _error(str(exc), 429)
        except InvalidProblem as exc:
            return _error(str(exc), 413 if str(exc).startswith("request too large") else 400)
        except TilesolveError as exc:
            return _error(str(exc), 400)
        except (RecursionError, MemoryError, OverflowError) as exc:
            return _error(f"bad request: {_PYTHON_ERRORS[type(exc)]}", 400)
        except ValueError as exc:
            return _error(f"bad request: {exc}", 400)
        except Exception:  # noqa: BLE001 - a bug: one line to the page, the traceback to the log
            traceback.print_exc(file=sys.stderr)
            return _error("internal error in the studio server (a bug; its log has the details)", 500)
        finally:
            if getattr(request.state, "large_body", False):
                await anyio.to_thread.run_sync(_release_memory)

    return wrapped


def _family_json(fam: family.Family) -> dict:
    return {"name": fam.name, "title": fam.title, "methods": list(fam.methods),
            "route_help": dict(fam.route_help), "fields": [f.public() for f in fam.form.fields],
            "view": fam.form.window is not None, "pictures": list(fam.pictures), "texture": _has_texture(fam.name)}


@functools.lru_cache(maxsize=None)
def _has_texture(name: str) -> bool:
    """Whether a family's view has the texture look (:meth:`tilesolve.studio.views.Views.has_texture`)."""
    return Views().has_texture(name)


# ----------------------------------------------------------------------------- handlers
# Each handler finds the server's state in ``request.app.state`` (:func:`create_app`): ``jobs``,
# ``views`` and ``posing``.
async def index(request: Request) -> Response:
    return FileResponse(os.path.join(STATIC, "index.html"))


@_guard
async def families(request: Request) -> Response:
    return JSONResponse({"families": [_family_json(f) for f in family.families() if f.form is not None],
                         "palette": PALETTE})


def _check(doc: dict) -> dict:
    """What ``POST /api/check`` answers for a request's JSON (bad input raises)."""
    fam, vals, problem, _ = worker.pose(doc.get("family"), doc.get("values"))
    method, time_limit = worker.check_run(fam, doc.get("method", "auto"), doc.get("time_limit"))
    sizing.refuse_oversized(fam, problem, method)
    grids = {f.name: list(f.extent(vals)) for f in fam.form.fields if f.kind == "cells"}
    return {"describe": problem.describe() if hasattr(problem, "describe") else fam.name, "cells": grids,
            "seed": vals["seed"], "command": worker.command_line(fam, vals, method, vals["seed"], time_limit),
            "sketch": fam.form.sketch(vals) if fam.form.sketch is not None else None}


def _posed(data: bytearray) -> tuple[dict, dict]:
    doc = _json(data)
    return doc, _check(doc)


async def _read_and_pose(request: Request) -> tuple[dict, dict]:
    """The request's JSON and :func:`_check`'s answer (:data:`POSING` requests at once)."""
    async with request.app.state.posing:
        return await anyio.to_thread.run_sync(_posed, await _body(request))


@_guard
async def check(request: Request) -> Response:
    return JSONResponse((await _read_and_pose(request))[1])


@_guard
async def solve(request: Request) -> Response:
    # bad input: 400 now, not in the job
    doc, checked = await _read_and_pose(request)
    values = dict(doc.get("values") or {}, seed=checked["seed"])
    job = request.app.state.jobs.start(doc["family"], values, doc.get("method", "auto"), doc.get("time_limit"))
    return JSONResponse({"id": job.id, "seed": checked["seed"]})


def _job(request: Request):
    try:
        return request.app.state.jobs.get(request.path_params["id"])
    except KeyError:
        raise InvalidProblem(f"no job {request.path_params['id']!r} (finished jobs are kept a while)") from None


@_guard
async def job_state(request: Request) -> Response:
    job = _job(request)
    try:
        wait = min(max(float(request.query_params.get("wait", 0)), 0.0), 10.0)
    except ValueError:
        raise InvalidProblem("wait must be a number of seconds") from None
    if wait and not job.done.is_set():
        await anyio.to_thread.run_sync(job.done.wait, wait)
    return JSONResponse(job.public())


@_guard
async def job_events(request: Request) -> Response:
    job = _job(request)

    async def events():
        version = -1
        while True:
            version = await anyio.to_thread.run_sync(job.wait_change, version, EVENT_EVERY_S)
            state = job.public()
            state.pop("result", None)  # the page fetches it once (GET /api/jobs/ID)
            yield f"data: {json.dumps(state)}\n\n"
            if state["state"] != "running":
                return

    return StreamingResponse(events(), media_type="text/event-stream", headers={"Cache-Control": "no-cache"})


@_guard
async def cancel(request: Request) -> Response:
    job = _job(request)
    await anyio.to_thread.run_sync(request.app.state.jobs.cancel, job.id)
    return JSONResponse(job.public())


def _export(job, what: str) -> tuple[bytes | str, str]:
    if job.result is None:
        raise InvalidProblem(f"job {job.id} has no solution ({job.state})")
    text = job.result["json"]
    if what == "solution.json":
        return text, "application/json"
    fmt = what.rsplit(".", 1)[1]
    fam, codec = family.codec_of(json.loads(text)["format"])
    problem, sol = codec.read(json.loads(text), "solution.json")
    if sol.answer is None:
        raise InvalidProblem(f"status {sol.status.value}: no tiling to draw")
    data = family.render(problem, sol, fmt)
    return data, "image/svg+xml" if fmt == "svg" else "image/png"


@_guard
async def export(request: Request) -> Response:
    job = _job(request)
    what = request.path_params["what"]
    if what not in ("solution.json", "picture.svg", "picture.png"):
        raise InvalidProblem(f"no export {what!r}; exports are solution.json, picture.svg, picture.png")
    data, media = await anyio.to_thread.run_sync(_export, job, what)
    name = f"{job.family}-{job.result['seed']}.{what.rsplit('.', 1)[1]}"
    return Response(data, media_type=media, headers={"Content-Disposition": f'attachment; filename="{name}"'})


@_guard
async def view(request: Request) -> Response:
    q = request.query_params
    try:
        x, y, n = int(q.get("x", 0)), int(q.get("y", 0)), int(q.get("n", 32))
    except ValueError:
        raise InvalidProblem("x, y and n must be whole numbers") from None
    if not 1 <= n <= MAX_VIEW_CELLS:
        raise InvalidProblem(f"a view window is 1..{MAX_VIEW_CELLS} cells wide, got {n}")
    raw = _view_values(request)
    views, name = request.app.state.views, request.path_params["family"]
    if _view_look(request) == "texture":
        data = await anyio.to_thread.run_sync(views.texture_png, name, raw, x, y, n)
    else:
        data = await anyio.to_thread.run_sync(views.png, name, raw, x, y, n, _view_colours(request))
    return Response(data, media_type="image/png", headers={"Cache-Control": "max-age=3600"})


#: Most colours of a view's chosen palette (``palette=RRGGBB,RRGGBB,...``).
MAX_VIEW_COLOURS = 256


def _view_colours(request: Request) -> list[tuple[int, int, int]] | None:
    """The palette chosen on the page for a view (``palette``: comma-separated ``RRGGBB``), or None."""
    raw = request.query_params.get("palette", "")
    if not raw:
        return None
    items = raw.split(",")
    if len(items) > MAX_VIEW_COLOURS:
        raise InvalidProblem(f"a view palette has at most {MAX_VIEW_COLOURS} colours, got {len(items)}")
    out = []
    for item in items:
        item = item.strip().removeprefix("#")
        if len(item) != 6 or any(c not in "0123456789abcdefABCDEF" for c in item):
            raise InvalidProblem(f"palette colours are RRGGBB hex, got {item[:20]!r}")
        out.append((int(item[0:2], 16), int(item[2:4], 16), int(item[4:6], 16)))
    return out


def _view_look(request: Request) -> str:
    """How a view is drawn (``look``: :data:`tilesolve.studio.views.LOOKS`, ``picture`` by default)."""
    from tilesolve.studio.views import LOOKS

    look = request.query_params.get("look", "picture")
    if look not in LOOKS:
        raise InvalidProblem(f"look must be one of {', '.join(LOOKS)}, got {look[:20]!r}")
    return look


def _view_values(request: Request) -> str:
    """The form values (JSON text) of a view request."""
    raw = request.query_params.get("values", "{}")
    if len(raw) > 100_000:
        raise InvalidProblem("values too long")
    return raw


@_guard
async def webgl(request: Request) -> Response:
    doc = await anyio.to_thread.run_sync(request.app.state.views.webgl, request.path_params["family"],
                                         _view_values(request), _view_colours(request), _view_look(request))
    return JSONResponse(doc)


# ----------------------------------------------------------------------------- the app
def _routes() -> list:
    """The endpoints of the module docstring."""
    return [
        Route("/", index),
        Route("/api/families", families),
        Route("/api/check", check, methods=["POST"]),
        Route("/api/solve", solve, methods=["POST"]),
        Route("/api/jobs/{id}", job_state),
        Route("/api/jobs/{id}/cancel", cancel, methods=["POST"]),
        Route("/api/jobs/{id}/events", job_events),
        Route("/api/jobs/{id}/{what}", export),
        Route("/api/view/{family}.png", view),
        Route("/api/webgl/{family}", webgl),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]


def _lifespan(warm: bool):
    """Start-up and shut-down: with ``warm``, start the solve forkserver and warm the views in
    the background; at the end, stop every job."""

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette):
        if warm:
            threading.Thread(target=app.state.jobs.warm, daemon=True).start()
            threading.Thread(target=app.state.views.warm, daemon=True).start()
        yield
        app.state.jobs.close()

    return lifespan


def create_app(*, warm: bool = True, names=()) -> Starlette:
    """The studio app. ``warm`` starts the solve forkserver (and compiles the view routes) in
    the background at start-up; ``names`` are host names it answers besides the listening
    address (:class:`~tilesolve.studio.origin.OwnOrigin`)."""
    app = Starlette(routes=_routes(), lifespan=_lifespan(warm), middleware=[Middleware(OwnOrigin, names=names)])
    app.state.jobs = Jobs()
    app.state.views = Views()
    app.state.posing = anyio.Semaphore(POSING)
    return app
