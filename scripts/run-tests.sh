#!/usr/bin/env bash
# Set up (packages + build), then run the C++ unit tests (ctest) and pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# glibc's malloc on transparent huge pages (docs/speed.md): 1.4-4.8x faster solves on VMs whose
# kernel gives huge pages on request only; the same answers.
export GLIBC_TUNABLES="${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1"
status=0
(cd build && ctest --output-on-failure) || status=$?
PYTHONPATH=python /usr/bin/python3 -m pytest "$@" || status=$?
exit $status
