"""Helpers of the studio's browser tests: pick a family, fill a field, solve and wait, pan the view, cancel."""

from __future__ import annotations


def pick(page, name):
    page.select_option("#family", name)
    page.wait_for_function("document.getElementById('describe').textContent.length > 0")


def fill(page, field, value):
    page.fill(f"#field-{field}", str(value))
    page.dispatch_event(f"#field-{field}", "change")


def solve(page, timeout=60_000):
    page.click("#solve")
    page.wait_for_function("document.getElementById('solve').disabled === false && studio.job === null",
                           timeout=timeout)
    return page.evaluate("studio.result")


def pan_view(page, dx, dy, steps=8):
    """Drag the infinite view by ``(dx, dy)`` CSS px from its centre; the pointer stays there."""
    box = page.locator("#viewport").bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(cx, cy)
    page.mouse.down()
    page.mouse.move(cx + dx, cy + dy, steps=steps)
    page.mouse.up()


def cancel_a_long_search(page):
    """Start a search that runs for minutes (a corner packing, C = 4, by plain SAT; class notes
    §5.5), wait for its streamed progress, cancel it and wait for the page to say so."""
    page.select_option("#field-kind", "corner")
    fill(page, "colors", 4)
    page.select_option("#method", "sat")
    page.fill("#seed", "1")
    page.click("#solve")
    page.wait_for_function("document.getElementById('status').textContent.startsWith('solving')")
    # the solve's progress, streamed by the server: the route's task, with its elapsed time
    page.wait_for_function("document.getElementById('status').textContent.includes(\"packing: solving with 'sat'\")")
    page.click("#cancel")
    page.wait_for_function("document.getElementById('status').textContent.startsWith('cancelled')", timeout=20_000)
