#!/usr/bin/env bash
# Set up (packages + build), then run the C++ unit tests (ctest) and pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
status=0
(cd build && ctest --output-on-failure) || status=$?
PYTHONPATH=python /usr/bin/python3 -m pytest "$@" || status=$?
exit $status
