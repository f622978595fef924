"""Helpers of the studio's browser tests: pick a family, fill a field, solve and wait."""

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
