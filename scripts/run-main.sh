#!/usr/bin/env bash
# Set up (packages + build), then run the main job: the demos, writing figures,
# results.json and results.md into the output folder (default: results/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
PYTHONPATH=python MPLBACKEND=Agg /usr/bin/python3 demos/paper_figures.py "$@"
