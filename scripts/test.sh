#!/usr/bin/env bash
# The test command (README.md, "Running the tests"): installs what the tests need and runs the
# whole suite on every core.
#
#   scripts/test.sh                  # the full suite, pytest-xdist on every core
#   scripts/test.sh -m "not slow"    # the fast tier; any other pytest arguments go through too
#
# 1. System packages, with apt-get (as root, or through sudo) when missing: Python >= 3.11 with
#    venv, EGL + Mesa for the headless moderngl context (the GPU path runs on llvmpipe) and
#    Debian's chromium for the studio's browser tests (Playwright's own browser download is
#    not used), and groff to render the man page. Without root, sudo or apt-get it stops with one
#    line naming what is missing.
# 2. A virtual environment, $VENV (default .venv), made when missing, with tilesolve and its
#    test extra installed into it (pip install ".[test]": a real install, as a user gets).
# 3. python -m pytest -q -n auto --dist loadscope, in that environment: pytest-xdist on every
#    core, each test module in one worker (its module fixtures built once; the README tour runs
#    in order in one folder).
set -euo pipefail

cd "$(dirname "$0")/.."
VENV="${VENV:-.venv}"
if [ -z "${PYTHON:-}" ]; then
    PYTHON=python3.11
    command -v "$PYTHON" >/dev/null 2>&1 || PYTHON=python3
fi

need=()
if ! command -v "$PYTHON" >/dev/null 2>&1; then
    need+=(python3 python3-venv)
elif ! "$PYTHON" -c 'import sys; assert sys.version_info >= (3, 11)' 2>/dev/null; then
    echo "scripts/test.sh: $PYTHON is $("$PYTHON" -V 2>&1); tilesolve needs Python >= 3.11 (set PYTHON=...)" >&2
    exit 1
elif [ ! -x "$VENV/bin/python" ] && ! "$PYTHON" -c 'import ensurepip, venv' 2>/dev/null; then
    need+=(python3-venv)
fi
ldconfig="$(command -v ldconfig || echo /sbin/ldconfig)"  # /sbin is not on a user's PATH
for lib in libEGL.so.1 libEGL_mesa.so.0 libGL.so.1; do
    "$ldconfig" -p | grep "$lib" >/dev/null || need+=(libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri)
done
ls /usr/lib/*/dri/swrast_dri.so >/dev/null 2>&1 || need+=(libgl1-mesa-dri)
command -v chromium >/dev/null 2>&1 || need+=(chromium)
command -v groff >/dev/null 2>&1 || need+=(groff-base)  # renders the man page in tests/test_docs.py
if [ "${#need[@]}" -gt 0 ]; then
    packages="$(printf '%s\n' "${need[@]}" | sort -u | tr '\n' ' ')"
    if [ "$(id -u)" -eq 0 ]; then
        sudo=()
    elif command -v sudo >/dev/null 2>&1; then
        sudo=(sudo)
    else
        sudo=(missing)
    fi
    if [ "${sudo[*]-}" = missing ] || ! command -v apt-get >/dev/null 2>&1; then
        echo "scripts/test.sh: missing system packages: ${packages}(install them as root, e.g. apt-get install ${packages% })" >&2
        exit 1
    fi
    echo "scripts/test.sh: installing system packages: ${packages% }" >&2
    "${sudo[@]}" apt-get update -qq
    # shellcheck disable=SC2086
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $packages
    if ! command -v "$PYTHON" >/dev/null 2>&1; then
        PYTHON=python3
    fi
fi

if [ ! -x "$VENV/bin/python" ]; then
    "$PYTHON" -m venv "$VENV"
fi
# shellcheck disable=SC1091
source "$VENV/bin/activate"
python -m pip install -q ".[test]"

# Exit code 5 means "no tests collected": a failure here.
status=0
python -m pytest -q -n auto --dist loadscope "$@" || status=$?
if [ "$status" -eq 5 ]; then
    echo "scripts/test.sh: pytest collected no tests" >&2
    exit 1
fi
exit "$status"
