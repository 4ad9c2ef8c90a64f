"""glibc's malloc on transparent huge pages: the solves' memory in 2 MB pages.

Where the kernel gives transparent huge pages on request only
(/sys/kernel/mm/transparent_hugepage/enabled: ``madvise``, the default of
many distributions and clouds), glibc's malloc asks for them only when told
by the tunable ``GLIBC_TUNABLES=glibc.malloc.hugetlb=1`` (glibc 2.35 or
later; Debian 12 has 2.36), read when a process starts. On the 2-core VM of
docs/speed.md it made the solves 1.4-4.8x faster with the same answers (3D
friction at 4.9e5 dofs: 32.4 s against 154.5 s; the 1e6-dof answer the same
to every digit) and stopped their slowing as a process ages.

The command line (``python3 -m cracklip``) starts itself again with the
tunable when it would help and is not set (reexec_with_huge_pages, before
anything heavy is loaded); ``CRACKLIP_HUGE_PAGES=0`` keeps the process as it
is. A script that imports cracklip sets the tunable itself, before Python
starts (docs/speed.md). results.json's ``versions.malloc`` says which pages a run had (pages()).
"""
from __future__ import annotations

import os
import sys

TUNABLE = "glibc.malloc.hugetlb"
#: The environment variable that turns the command line's restart off ("0").
OPT_OUT = "CRACKLIP_HUGE_PAGES"
THP_ENABLED = "/sys/kernel/mm/transparent_hugepage/enabled"
#: The first glibc whose malloc knows TUNABLE.
FIRST_GLIBC = (2, 35)


def in_use(environ: dict | None = None) -> bool:
    """Whether this process's malloc was told to use huge pages."""
    environ = os.environ if environ is None else environ
    return any(item.strip() == f"{TUNABLE}=1" for item in environ.get("GLIBC_TUNABLES", "").split(":"))


def pages(environ: dict | None = None, mode: str | None = None) -> str:
    """Which pages malloc's memory gets, as results.json's versions.malloc
    says it: huge pages because the kernel gives them always, or because
    it gives them on request and the tunable asks; else default pages."""
    mode = thp_mode() if mode is None else mode
    if mode == "always":
        return "huge pages (kernel THP always)"
    return "huge pages (GLIBC_TUNABLES)" if mode == "madvise" and in_use(environ) else "default pages"


def thp_mode(path: str = THP_ENABLED) -> str:
    """The kernel's transparent huge page mode: "always", "madvise",
    "never", or "" where it cannot be read (not Linux, no THP)."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        return ""
    start, end = text.find("["), text.find("]")
    return text[start + 1:end] if 0 <= start < end else ""


def glibc_version() -> tuple[int, ...] | None:
    """(major, minor) of the C library if it is glibc, else None."""
    try:
        name, version = os.confstr("CS_GNU_LIBC_VERSION").split()
        return tuple(int(p) for p in version.split(".")[:2]) if name == "glibc" else None
    except (AttributeError, ValueError, OSError):
        return None


def restart_wanted(environ: dict, mode: str, glibc: tuple[int, ...] | None) -> bool:
    """Whether a process with this environment should start again with the
    tunable: the kernel gives huge pages on request only, glibc knows the
    tunable, it is not set yet, and the user did not opt out."""
    return (mode == "madvise" and glibc is not None and glibc >= FIRST_GLIBC and not in_use(environ)
            and environ.get(OPT_OUT, "1") != "0")


def with_tunable(environ: dict) -> dict:
    """A copy of environ with TUNABLE=1 added to GLIBC_TUNABLES (kept
    otherwise)."""
    env = dict(environ)
    old = env.get("GLIBC_TUNABLES", "")
    env["GLIBC_TUNABLES"] = f"{old}:{TUNABLE}=1" if old else f"{TUNABLE}=1"
    return env


def started_as_module(orig_argv: list[str]) -> bool:
    """Whether the interpreter's own command line was ``... -m cracklip
    ...`` (so that running it again runs the same; not a wrapper that runs
    the module in a prepared process, as runpy does)."""
    args = list(orig_argv[1:])
    i = 0
    while i < len(args) - 1:
        if args[i] == "-m":
            return args[i + 1] == "cracklip"
        if args[i] == "-c" or not args[i].startswith("-"):
            return False
        i += 2 if args[i] in ("-W", "-X") else 1  # (the options that take a value)
    return False


def reexec_with_huge_pages() -> None:
    """Replace this process by the same command (the same interpreter, flags
    and arguments, the same process id: under mpirun every process does so
    alike) with the tunable when restart_wanted and the process was started
    as ``python3 -m cracklip``; else return."""
    orig_argv = list(getattr(sys, "orig_argv", []))
    if not started_as_module(orig_argv) or not restart_wanted(dict(os.environ), thp_mode(), glibc_version()):
        return
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(sys.executable, [sys.executable, *orig_argv[1:]], with_tunable(dict(os.environ)))
