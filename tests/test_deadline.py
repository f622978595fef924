"""The run clock of tilesolve.deadline: a process's start as the origin of a command's time limit."""

import subprocess
import sys


def test_process_start_is_before_the_interpreter_ran_any_code():
    """A process that sleeps 0.3 s before asking has been running at least that long."""
    code = ("import time\ntime.sleep(0.3)\nfrom tilesolve.deadline import process_start\n"
            "print(time.perf_counter() - process_start())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    assert float(out.stdout) >= 0.3
