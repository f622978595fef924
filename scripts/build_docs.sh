#!/usr/bin/env bash
# Build the documentation site (mkdocs.yml) into build/site, offline, failing on any warning.
#
#   pip install ".[docs]"          # once: MkDocs, Material, mkdocstrings
#   scripts/build_docs.sh          # then open build/site/index.html
#
# While it builds, docs/hooks/tilesolve_docs.py runs every command shown on the pages (through
# the installed `tilesolve`) and draws the gallery, and generates the command-line reference and
# the man page (build/site/man/tilesolve.1). Arguments go to `mkdocs build` (e.g. -d DIR).
# TILESOLVE_DOCS_WORK=DIR keeps the folder the commands ran in.
set -euo pipefail

cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python}"
if ! "$PYTHON" -c 'import mkdocs, material, mkdocstrings_handlers.python' 2>/dev/null; then
    echo "scripts/build_docs.sh: the docs extra is missing: pip install \".[docs]\"" >&2
    exit 1
fi
export NO_MKDOCS_2_WARNING=1   # Material's notice about its successor, printed on every build
start=$SECONDS
"$PYTHON" -m mkdocs build --strict "$@"
echo "scripts/build_docs.sh: site built in $((SECONDS - start)) s (by default in build/site: index.html, man/tilesolve.1)" >&2
