#!/usr/bin/env bash
# Set up (packages + build), then run the main job: the demos, writing figures,
# results.json and results.md into the output folder (default: results/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# glibc's malloc on transparent huge pages (docs/speed.md): 1.4-4.8x faster solves on VMs whose
# kernel gives huge pages on request only; the same answers.
export GLIBC_TUNABLES="${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1"
PYTHONPATH=python MPLBACKEND=Agg /usr/bin/python3 demos/paper_figures.py "$@"
