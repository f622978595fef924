"""Run many ``tilesolve`` command lines in one process, as the console script would run each.

The fuzz tests (tests/test_fuzz_readers.py) start this once and send it one JSON request per
line on stdin, ``{"argv": [...], "cwd": DIR}``; it answers one JSON line per request,
``{"rc": exit code, "stdout": ..., "stderr": ..., "seconds": ...}``. Each request runs the
console script's entry point (``tilesolve.cli.main:main``, pyproject's ``[project.scripts]``)
with its standard output and error redirected at the file-descriptor level; an exception that
escapes it is printed as the interpreter prints it and answers exit 1, as the console script
would. Starting Python once instead of once per input makes thousands of inputs affordable.

``python tests/fuzz_driver.py [MEMORY_MIB]`` caps the address space (default 4096 MiB), so a
reader that allocates without bound fails fast instead of filling the machine.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import tempfile
import time
import traceback


def _run(argv: list[str], cwd: str) -> dict:
    from tilesolve.cli.main import main

    out = tempfile.TemporaryFile()
    err = tempfile.TemporaryFile()
    saved = os.dup(1), os.dup(2)
    here = os.getcwd()
    sys.stdout.flush()
    sys.stderr.flush()
    os.dup2(out.fileno(), 1)
    os.dup2(err.fileno(), 2)
    start = time.perf_counter()
    try:
        os.chdir(cwd)
        try:
            rc = main(argv)
        except SystemExit as exc:
            rc = exc.code if isinstance(exc.code, int) else 1
        except BaseException:  # noqa: BLE001 - what the interpreter does for the console script
            traceback.print_exc()
            rc = 1
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])
        os.chdir(here)
    seconds = time.perf_counter() - start
    texts = []
    for f in (out, err):
        f.seek(0)
        texts.append(f.read(1 << 16).decode("utf-8", "replace"))
        f.close()
    return {"rc": rc, "stdout": texts[0], "stderr": texts[1], "seconds": seconds}


def main() -> None:
    limit = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    resource.setrlimit(resource.RLIMIT_AS, (limit << 20, limit << 20))
    answers = os.fdopen(os.dup(1), "w")
    for line in sys.stdin:
        request = json.loads(line)
        answers.write(json.dumps(_run(request["argv"], request["cwd"])) + "\n")
        answers.flush()


if __name__ == "__main__":
    main()
