"""Fixtures of the studio's browser tests: a studio server on a free loopback port, Debian's
headless Chromium driven by Playwright, and a page of the studio opened and ready."""

from __future__ import annotations

import os
import threading
import time

import pytest

CHROMIUM = "/usr/bin/chromium"


@pytest.fixture(scope="module")
def server():
    import uvicorn

    from tilesolve.studio.app import create_app

    config = uvicorn.Config(create_app(), host="127.0.0.1", port=0, log_level="warning")
    srv = uvicorn.Server(config)
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    while not srv.started:
        time.sleep(0.05)
    port = srv.servers[0].sockets[0].getsockname()[1]
    yield f"http://127.0.0.1:{port}"
    srv.should_exit = True
    thread.join(30)


@pytest.fixture(scope="module")
def browser():
    from playwright import sync_api as playwright

    assert os.path.exists(CHROMIUM), f"the browser tests need Debian's chromium at {CHROMIUM} (.ci/run installs it)"
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        yield b
        b.close()


@pytest.fixture
def page(browser, server):
    ctx = browser.new_context(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
    pg = ctx.new_page()
    pg.goto(server + "/")
    pg.wait_for_selector("body[data-ready='1']", timeout=120_000)  # a loaded machine starts its workers slowly
    yield pg
    ctx.close()
