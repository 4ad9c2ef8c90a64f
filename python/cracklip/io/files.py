"""Writing files safely: atomic writes (no half-written file) and JSON."""
from __future__ import annotations

import contextlib
import json
import os
import pathlib
import typing


@contextlib.contextmanager
def atomic_path(path: str | pathlib.Path) -> typing.Iterator[pathlib.Path]:
    """A temporary path in the same folder, renamed to `path` when the block
    ends without error (removed otherwise). The temporary name keeps the
    suffix, so writers that infer the format from it still work."""
    path = pathlib.Path(path)
    tmp = path.with_name(f".{path.stem}.tmp{os.getpid()}{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()


def write_json(path: str | pathlib.Path, data: typing.Any) -> pathlib.Path:
    """Write data as JSON (indent 2), creating parent folders; the file
    appears complete or not at all (atomic_path)."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(data, indent=2))
    return path
