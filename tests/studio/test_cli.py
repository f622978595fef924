"""``tilesolve studio``: loopback by default, a warning for any other --host, the browser
opened unless --no-browser, a clean stop, and one error line (exit 2) for a port in use or an
unknown host."""

from __future__ import annotations

import socket
import subprocess

import pytest
from click.testing import CliRunner

from tests.clitools import one_line_error, run
from tilesolve.cli.main import main_group  # noqa: E402
from tilesolve.cli.studio import is_loopback  # noqa: E402
from clitools import SCRIPT


@pytest.mark.parametrize("host, loop", [("127.0.0.1", True), ("localhost", True), ("::1", True), ("127.8.0.1", True),
                                        ("0.0.0.0", False), ("192.168.1.2", False), ("example.org", False)])
def test_loopback(host, loop):
    assert is_loopback(host) is loop


@pytest.mark.slow
def test_other_hosts_are_warned_about():
    proc = subprocess.run([SCRIPT, "studio", "--host", "0.0.0.0", "--port", "0", "--no-browser",
                           "--exit-after", "1"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "warning: --host 0.0.0.0 serves the studio to other machines" in proc.stderr
    assert "tilesolve studio on http://127.0.0.1:" in proc.stderr


def test_the_page_opens_in_a_browser_unless_told_not_to(monkeypatch):
    opened = []
    monkeypatch.setattr("webbrowser.open", opened.append)
    result = CliRunner().invoke(main_group, ["studio", "--port", "0", "--exit-after", "1"])
    assert result.exit_code == 0, result.output
    assert len(opened) == 1 and opened[0].startswith("http://127.0.0.1:")
    assert "warning" not in result.output


def test_a_port_in_use_is_one_error_line(tmp_path):
    with socket.create_server(("127.0.0.1", 0)) as busy:
        port = busy.getsockname()[1]
        line = one_line_error(run("studio", "--no-browser", "--port", str(port), cwd=tmp_path))
    assert line == f"tilesolve: error: cannot listen on 127.0.0.1 port {port}: address already in use"


def test_an_unknown_host_is_one_error_line(tmp_path):
    line = one_line_error(run("studio", "--no-browser", "--host", "no-such-host.invalid", cwd=tmp_path))
    assert line.startswith("tilesolve: error: --host no-such-host.invalid: unknown host (")
