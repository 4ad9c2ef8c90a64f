"""The input files of a fatigue life, read and checked before anything is
meshed or solved: turning points, block-load tables, da/dN tables and
tables of K (beta) against crack size. A bad value is an InputFileError
naming the scene key, the file, the line and the column.

Common rules: `#` starts a comment (a whole line or the rest of one), blank
lines are skipped, values are separated by commas or by white space (one
or the other on a line), a header row names the columns where a layout has
one.

Turning points (`spectrum.blocks[].file`), one of:

    plain            one value per line (a load factor), no header: the
                     spectrum's one load group (as test labs and other
                     codes write a sequence)
    named columns    a header naming the load group of each column, then one
                     row of factors per turning point
    block-load table a header `max, min, cycles` (any order), then one row
                     per load level: `cycles` cycles from `min` to `max` in
                     a row (a positive integer); the block stands for the
                     turning points min, max, min, max, ... it implies, and is
                     counted like any other (the spectrum's one load group)

da/dN tables (`material.fatigue.table_file`, `table_layout`):

    easigrow         (its `.dadn` files, read in easigrow's table.rs and its
                     barter14.dadn example) the first line holds the R of each
                     curve, every next line a rate and the Delta K giving it at
                     each R; white space
    csv              a header: a name for the rate column (dadn, da/dN,
                     rate) and one R per column (`0.1` or `R=0.1`), then rows
                     of a rate and one Delta K per R
    auto             easigrow if the first line holds only numbers, else csv

AFGROW's and NASGRO's own tabular file layouts are not supported: neither
is publicly documented in a source this project could read (their manuals
appear only as title pages in the indexes searched); a table from either
is read once converted to one of the layouts above.

Tables of K against crack size (`life.table`), one of:

    a, beta[_case] ...      beta = K / (S sqrt(pi a)) per load case (S: the
                            case's life.reference_stress, default 1)
    a, K[_case] ...         K per unit load factor
    a, c, beta_a, beta_c    (or K_a, K_c) a surface or corner crack: K at its
                            deepest point and at the surface, on a grid of
                            (a, c) (every a with every c)
    a beta (no header)      two columns, easigrow's beta file (one table)
    cracklip grow's beta_afgrow.txt  two columns per tip and load case, each
                            table after its '# tip: crack C end E; case: G'
                            line: the tables of one tip (life.tip), one beta
                            column per load group (beta at a contact level,
                            case G_at_<factor>, left out); its K_residual is
                            not in it (beta.csv has it). 3D beta_tables.txt
                            (deepest and surface point in one file) is refused:
                            beta_deepest.csv and beta_surface.csv are the
                            one-size tables
    cracklip grow's beta.csv  (columns step, crack, end, ..., a, K_I_<group>,
                            K_residual): the rows of one tip (life.tip), K_I of
                            each load group per unit factor, K_residual as a
                            steady case

The crack sizes must rise strictly; every value must be a finite number.
A beta table cracklip grow wrote has a `# reference_stress: <group> = S,
...` line (KTableData.reference_stress: life.reference_stress must give
the same S) and a `# units: length = mm, stress = MPa` line
(KTableData.units: the life scene's [units] must be these).
"""
from __future__ import annotations

import bisect
import dataclasses
import math
import pathlib
import re

import numpy as np

from ..errors import InputError, InputFileError


#: da/dN table layouts read, and the ones named but refused (why: module doc).
RATE_LAYOUTS = ("auto", "easigrow", "csv")
UNSUPPORTED_RATE_LAYOUTS = ("afgrow", "nasgro")

#: A block-load table expands into at most this many turning points per block.
MAX_BLOCK_POINTS = 20_000_000


@dataclasses.dataclass
class Row:
    """One data line of a table file: its line number and its fields, each
    with its 1-based column."""
    line: int
    fields: list[str]


def read_rows(path: str | pathlib.Path, where: str) -> list[Row]:
    """The data lines of a table file (comments and blank lines dropped);
    InputFileError for an unreadable or empty file."""
    path = pathlib.Path(path)
    try:
        text = path.read_text(errors="replace")
    except OSError as e:
        raise InputFileError(f"{where}: cannot read {path}: {e.strerror}", path) from None
    rows = []
    for k, line in enumerate(text.splitlines(), start=1):
        body = line.split("#", 1)[0].strip()
        if not body:
            continue
        fields = [f.strip() for f in body.split(",")] if "," in body else body.split()
        rows.append(Row(k, fields))
    if not rows:
        raise InputFileError(f"{where}: {path} is empty: it holds no data line (only comments or blank lines)", path)
    return rows


def _head(path: str | pathlib.Path, where: str) -> tuple[pathlib.Path, list[Row], list[str], bool]:
    """(path, the data lines, the first line's fields, whether they are all numbers: no header)."""
    path = pathlib.Path(path)
    rows = read_rows(path, where)
    return path, rows, rows[0].fields, all(_is_number(f) for f in rows[0].fields)


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def number(path, row: Row, j: int, where: str, what: str = "value") -> float:
    """Field j (0-based) of a row as a finite number (InputFileError naming the
    file, line and column otherwise)."""
    if j >= len(row.fields) or row.fields[j] == "":
        raise InputFileError(f"{where}: {path}, line {row.line}, column {j + 1}: the {what} is missing", path,
                             row.line, j + 1)
    text = row.fields[j]
    try:
        v = float(text)
    except ValueError:
        raise InputFileError(f"{where}: {path}, line {row.line}, column {j + 1}: {text!r} is not a number "
                             f"(the {what})", path, row.line, j + 1) from None
    if not math.isfinite(v):
        raise InputFileError(f"{where}: {path}, line {row.line}, column {j + 1}: the {what} is {text!r}, not a "
                             "finite number", path, row.line, j + 1)
    return v


def _width(path, rows: list[Row], n: int, where: str) -> None:
    for r in rows:
        if len(r.fields) != n:
            raise InputFileError(f"{where}: {path}, line {r.line} has {len(r.fields)} values, the table {n}", path,
                                 r.line)


def _rising(path, rows: list[Row], values: np.ndarray, column: int, where: str, what: str) -> None:
    """values (one per row) must rise strictly down the column."""
    bad = np.flatnonzero(np.diff(values) <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise InputFileError(f"{where}: {path}, line {rows[i + 1].line}, column {column}: the {what} must rise "
                             f"strictly down the table, but {values[i + 1]:g} follows {values[i]:g} (line "
                             f"{rows[i].line})", path, rows[i + 1].line, column)


# -- turning points ----------------------------------------------------------------------------------------

def read_turning_points(path: str | pathlib.Path, where: str, groups: list[str] | tuple[str, ...]) -> np.ndarray:
    """The turning points of a block file as (n, len(groups)) factors in the
    order of `groups` (module doc: plain, named columns or a block-load
    table; the plain and block forms need a spectrum of one load group)."""
    path, rows, head, numeric = _head(path, where)
    if numeric:
        # Plain: one value per line.
        if len(head) != 1:
            raise InputFileError(f"{where}: {path}, line {rows[0].line} has {len(head)} numbers and no header: a "
                                 "plain turning-point file has one value per line; with several load groups give "
                                 "a header naming the group of each column", path, rows[0].line)
        _one_group(path, groups, where, "a plain turning-point file")
        _width(path, rows, 1, where)
        return np.array([[number(path, r, 0, where, "load factor")] for r in rows])
    names = [f.strip() for f in head]
    lowered = [n.lower() for n in names]
    if sorted(lowered) == ["cycles", "max", "min"]:
        return _block_table(path, rows, lowered, where, groups)
    if not all(names) or len(set(names)) != len(names):
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: the header must name each column once, got "
                             f"{names}", path, rows[0].line)
    data = rows[1:]
    if not data:
        raise InputFileError(f"{where}: {path} has a header and no turning point", path, rows[0].line)
    missing = [g for g in groups if g not in names]
    if missing:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: no column for load group(s) {missing} of "
                             f"spectrum.groups (its columns: {names})", path, rows[0].line)
    _width(path, data, len(names), where)
    cols = [names.index(g) for g in groups]
    return np.array([[number(path, r, j, where, f"factor of group {names[j]!r}") for j in cols] for r in data])


def _one_group(path, groups, where: str, what: str) -> None:
    if len(groups) != 1:
        raise InputFileError(f"{where}: {path} is {what}: it gives one load factor per point, but spectrum.groups "
                             f"has {len(groups)} groups {list(groups)}; give a header naming the group of each "
                             "column", path)


def _block_table(path, rows: list[Row], names: list[str], where: str, groups) -> np.ndarray:
    """A block-load table (max, min, cycles per row) as the turning points it implies."""
    _one_group(path, groups, where, "a block-load table")
    data = rows[1:]
    if not data:
        raise InputFileError(f"{where}: {path} has a header and no load level", path, rows[0].line)
    _width(path, data, 3, where)
    jmax, jmin, jn = names.index("max"), names.index("min"), names.index("cycles")
    levels, total = [], 0
    for r in data:
        hi = number(path, r, jmax, where, "maximum")
        lo = number(path, r, jmin, where, "minimum")
        n = number(path, r, jn, where, "number of cycles")
        if n < 0:
            raise InputFileError(f"{where}: {path}, line {r.line}, column {jn + 1}: the number of cycles is negative "
                                 f"({r.fields[jn]}); it must be a positive integer", path, r.line, jn + 1)
        if n != int(n) or n < 1:
            raise InputFileError(f"{where}: {path}, line {r.line}, column {jn + 1}: the number of cycles must be a "
                                 f"positive integer, got {r.fields[jn]}", path, r.line, jn + 1)
        if not hi > lo:
            raise InputFileError(f"{where}: {path}, line {r.line}: max ({hi:g}) must be above min ({lo:g})", path,
                                 r.line, jmax + 1)
        total += 2 * int(n)
        if total > MAX_BLOCK_POINTS:
            raise InputFileError(f"{where}: {path}, line {r.line}: the table stands for more than "
                                 f"{MAX_BLOCK_POINTS // 2} cycles per block; split it into blocks repeated with "
                                 "spectrum.blocks[].repeat", path, r.line)
        levels.append((lo, hi, int(n)))
    return np.concatenate([np.tile([lo, hi], n) for lo, hi, n in levels])[:, None]


# -- da/dN tables --------------------------------------------------------------------------------------------

def read_rate_table(path: str | pathlib.Path, where: str, layout: str = "auto") -> tuple[list[float], list[list[float]]]:
    """A da/dN table file: (R of each curve, rows [da/dN, Delta K at each R])
    with the R ascending, the rates positive and rising, every Delta K
    column positive and rising (module doc)."""
    path = pathlib.Path(path)
    if layout in UNSUPPORTED_RATE_LAYOUTS:
        raise InputError(f"{where}: table_layout {layout!r} is not supported: {layout.upper()}'s own tabular da/dN "
                         "file layout is not publicly documented in any source cracklip could check; write the table "
                         "as 'csv' (a header: dadn, then one R per column; rows: a rate and the Delta K at each R) or "
                         "'easigrow' (first line: the R values; rows: a rate and the Delta K at each R)")
    if layout not in RATE_LAYOUTS:
        raise InputError(f"{where}: table_layout must be one of {RATE_LAYOUTS} (not supported: "
                         f"{UNSUPPORTED_RATE_LAYOUTS}), got {layout!r}")
    path, rows, head, numeric = _head(path, where)
    if layout == "auto":
        layout = "easigrow" if numeric else "csv"
    if layout == "easigrow":
        if not numeric:
            raise InputFileError(f"{where}: {path}, line {rows[0].line}: the easigrow layout starts with a line of "
                                 f"R values, got {head}", path, rows[0].line)
        R = [number(path, rows[0], j, where, "R") for j in range(len(head))]
        first = 0
    else:
        if numeric:
            raise InputFileError(f"{where}: {path}, line {rows[0].line}: the csv layout starts with a header (dadn, "
                                 "then one R per column)", path, rows[0].line)
        R = []
        for j, f in enumerate(head[1:], start=1):
            m = re.fullmatch(r"(?:R\s*=\s*)?([-+0-9.eE]+)", f.strip())
            if not m or not _is_number(m.group(1)):
                raise InputFileError(f"{where}: {path}, line {rows[0].line}, column {j + 1}: {f!r} is not an R "
                                     "(write 0.1 or R=0.1)", path, rows[0].line, j + 1)
            R.append(float(m.group(1)))
        first = 1
    if not R:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: no R value", path, rows[0].line)
    Rs = np.asarray(R)
    bad = np.flatnonzero(np.diff(Rs) <= 0)
    if bad.size:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}, column {int(bad[0]) + 2 + first}: the "
                             f"R values must rise from column to column, got {R}", path, rows[0].line,
                             int(bad[0]) + 2 + first)
    data = rows[1:]
    if len(data) < 2:
        raise InputFileError(f"{where}: {path}: a da/dN table needs at least two rows of rates", path)
    _width(path, data, len(R) + 1, where)
    table = [[number(path, r, 0, where, "rate da/dN")]
             + [number(path, r, j + 1, where, f"Delta K at R = {R[j]:g}") for j in range(len(R))] for r in data]
    arr = np.asarray(table)
    for i, r in enumerate(data):
        if not arr[i, 0] > 0:
            raise InputFileError(f"{where}: {path}, line {r.line}, column 1: the rate must be positive, got "
                                 f"{r.fields[0]}", path, r.line, 1)
    _rising(path, data, arr[:, 0], 1, where, "rates da/dN")
    for j in range(len(R)):
        for i, r in enumerate(data):
            if not arr[i, j + 1] > 0:
                raise InputFileError(f"{where}: {path}, line {r.line}, column {j + 2}: Delta K at R = {R[j]:g} must "
                                     f"be positive, got {r.fields[j + 1]}", path, r.line, j + 2)
        _rising(path, data, arr[:, j + 1], j + 2, where, f"Delta K at R = {R[j]:g} (a non-ascending Delta K column)")
    return R, table


def resolve_rate_table(fatigue: dict, base_dir: pathlib.Path) -> dict:
    """The [material.fatigue] values with table_file read into table_R and
    table (the file's errors name its line and column); the others as given."""
    f = dict(fatigue)
    layout = f.pop("table_layout", "auto")
    name = f.pop("table_file", None)
    if name is None:
        return f
    if "table" in f or "table_R" in f:
        raise InputError("material.fatigue: give table_file or table_R / table, not both")
    path = pathlib.Path(name)
    f["table_R"], f["table"] = read_rate_table(path if path.is_absolute() else pathlib.Path(base_dir) / path,
                                               "material.fatigue.table_file", layout)
    f.setdefault("source", f"da/dN table file {name}")
    return f


# -- tables of K against crack size ----------------------------------------------------------------------------

@dataclasses.dataclass
class KTableData:
    """A table of K against crack size as read from a file.

    Attributes:
        sizes: 1 (a) or 2 (a, c).
        a: the crack sizes (ascending); c: the second sizes (two sizes).
        values: one size: {case: values (n,)}; two sizes: {case: (na, nc, 2)}
            (point 0 the deepest, 1 the surface).
        kind: "beta" (beta = K / (S sqrt(pi a)), S per case) or "K" (K per unit
            load factor).
        steady: cases applied at factor 1 at every load state (grow's
            K_residual).
        source: what the table is (file, layout, tip).
    """
    sizes: int
    a: np.ndarray
    values: dict[str, np.ndarray]
    kind: str
    source: str
    c: np.ndarray | None = None
    steady: tuple[str, ...] = ()
    reference_stress: dict[str, float] | None = None
    units: dict[str, str] | None = None


#: The case name of a column without one (`beta`, `K`): the spectrum's one load group.
DEFAULT_CASE = ""


def read_k_table(path: str | pathlib.Path, where: str, tip: tuple[int, int] | None = None,
                 scale: float = 1.0) -> KTableData:
    """A table of K (or beta) against crack size (module doc); scale
    multiplies the crack sizes (easigrow's a/d tables: d). A beta table
    cracklip grow wrote gives S of each group on its '# reference_stress:'
    line (KTableData.reference_stress)."""
    comments = _comment_lines(pathlib.Path(path))
    data = _read_k_table(path, where, tip, scale, comments)
    if data.kind == "beta":
        data.reference_stress = _file_reference_stress(pathlib.Path(path), where, comments)
    data.units = _file_units(comments)
    return data


def _comment_lines(path: pathlib.Path) -> list[tuple[int, str]]:
    """The comment lines of a table file, (line number, text stripped): the
    '# tip', '# reference_stress' and '# units' lines cracklip grow writes."""
    return [(k, t) for k, line in enumerate(path.read_text(errors="replace").splitlines(), start=1)
            if (t := line.strip()).startswith("#")]


_UNITS_LINE = re.compile(r"#\s*units:\s*length\s*=\s*([^,\s]+)\s*,\s*stress\s*=\s*([^(]*?)\s*(?:\(|$)")


def _file_units(comments: list[tuple[int, str]]) -> dict[str, str] | None:
    """{length, stress} from the '# units: length = mm, stress = MPa' line of
    a table cracklip grow wrote (None without one)."""
    for _, line in comments:
        m = _UNITS_LINE.match(line)
        if m:
            return {"length": m.group(1), "stress": m.group(2)}
    return None


_REFERENCE_LINE = re.compile(r"#\s*reference_stress:\s*([^(]*)")


def _file_reference_stress(path: pathlib.Path, where: str, comments: list[tuple[int, str]]
                           ) -> dict[str, float] | None:
    """S per group from the '# reference_stress: g = S, ...' line of a beta
    table cracklip grow wrote (None without one)."""
    for k, line in comments:
        m = _REFERENCE_LINE.match(line)
        if not m:
            continue
        out = {}
        for pair in m.group(1).split(","):
            name, eq, value = pair.partition("=")
            S = float(value) if _is_number(value) else math.nan
            if not eq or not name.strip() or not math.isfinite(S):
                raise InputFileError(f"{where}: {path}, line {k}: the reference stress line must read "
                                     f"'# reference_stress: group = S, ...', got {line!r}", path, k)
            out[name.strip()] = S
        return out
    return None


def _read_k_table(path: str | pathlib.Path, where: str, tip: tuple[int, int] | None, scale: float,
                  comments: list[tuple[int, str]]) -> KTableData:
    path, rows, head, numeric = _head(path, where)
    if numeric:
        sections = _cracklip_sections(comments)
        if len(sections) > 1:
            return _sectioned_table(path, rows, sections, where, tip, scale)
        if len(head) != 2:
            raise InputFileError(f"{where}: {path}, line {rows[0].line}: a table without a header has two columns "
                                 f"(a beta), got {len(head)} values", path, rows[0].line)
        _width(path, rows, 2, where)
        a = np.array([number(path, r, 0, where, "crack size a") for r in rows]) * scale
        beta = np.array([number(path, r, 1, where, "beta") for r in rows])
        _sizes(path, rows, a, where, 1)
        return KTableData(1, a, {DEFAULT_CASE: beta}, "beta", f"{path} (two columns: a beta)")
    names = [f.strip() for f in head]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice or not all(names):
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: the header must name each column once, got "
                             f"{names}" + (f" ({twice[0]!r} twice)" if twice else ""), path, rows[0].line)
    data = rows[1:]
    if len(data) < 2:
        raise InputFileError(f"{where}: {path}: a table of K against crack size needs at least two rows", path)
    _width(path, data, len(names), where)
    col = {n: j for j, n in enumerate(names)}
    if "a" not in col:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: no column `a` (the crack size) in the header "
                             f"{names}", path, rows[0].line)
    if "crack" in col and "end" in col:
        return _grow_table(path, rows[0], data, col, where, tip, scale)
    if "c" in col:
        return _two_size_table(path, rows[0], data, col, where, scale)
    cases: dict[str, int] = {}
    kinds = set()
    for n, j in col.items():
        m = re.fullmatch(r"(beta|K)(?:_(.+))?", n)
        if m:
            kinds.add(m.group(1))
            cases[m.group(2) or DEFAULT_CASE] = j
    if not cases:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: no column of beta or K (beta, beta_<group>, K, "
                             f"K_<group>) in the header {names}", path, rows[0].line)
    if len(kinds) > 1:
        raise InputFileError(f"{where}: {path}, line {rows[0].line}: give beta or K columns, not both ({names})", path,
                             rows[0].line)
    a = np.array([number(path, r, col["a"], where, "crack size a") for r in data]) * scale
    _sizes(path, data, a, where, col["a"] + 1)
    values = {c: np.array([number(path, r, j, where, names[j]) for r in data]) for c, j in cases.items()}
    return KTableData(1, a, values, kinds.pop(), f"{path}")


#: The comment line that starts each table of cracklip grow's beta_afgrow.txt (2D: per tip and load case) and
#: beta_tables.txt (3D: per point and load case).
_TIP_MARK = re.compile(r"#\s*tip:\s*crack\s+(\S+)\s+end\s+(\S+);\s*case:\s*(\S+)\s*$")
_ROLE_MARK = re.compile(r"#\s*table:\s*(.+?);\s*case:\s*(\S+)\s*$")
#: A case of beta at one load level solved with contact (beta_<group>_at_<factor>): not a load group.
_LEVEL_CASE = re.compile(r".+_at_[-+0-9.eE]+$")


def _cracklip_sections(comments: list[tuple[int, str]]) -> list[tuple[int, tuple, str]]:
    """The tables of a two-column file cracklip grow wrote with several of
    them: (line of the marker, the table's key -- ("tip", crack, end) or
    ("point", role) --, its load case), in file order; [] for other files."""
    out = []
    for k, line in comments:
        m = _TIP_MARK.match(line)
        if m:
            out.append((k, ("tip", m.group(1), m.group(2)), m.group(3)))
            continue
        m = _ROLE_MARK.match(line)
        if m:
            out.append((k, ("point", m.group(1)), m.group(2)))
    return out


def _chosen_tip(path, tips: list[tuple[int, int]], tip, where: str) -> tuple[int, int]:
    """The (crack, end) of a grow table's tips a life reads: life.tip, or the
    only one; an error naming life.tip where it is needed or not there."""
    if tip is None:
        if len(tips) > 1:
            raise InputError(f"{where}: {path} holds the tips {[list(t) for t in tips]} (crack, end): choose one "
                             "with life.tip = [crack, end]")
        tip = tips[0]
    tip = (int(tip[0]), int(tip[1]))
    if tip not in tips:
        raise InputError(f"{where}: life.tip = {list(tip)} is not in {path}; its tips: {[list(t) for t in tips]}")
    return tip


def _sectioned_table(path, rows: list[Row], sections, where: str, tip, scale: float) -> KTableData:
    """cracklip grow's beta_afgrow.txt holding several tables (tips, load
    cases, beta at contact levels): the tables of one tip (life.tip when it
    has several), one beta column per load group; beta at a contact level
    (case <group>_at_<factor>) is not a load group and is left out. A
    beta_tables.txt (3D: the deepest and the surface point) is refused with
    the one-size tables to use instead."""
    tables: dict[tuple, dict[str, list[Row]]] = {}
    marks = [s[0] for s in sections]  # (in file order: rising)
    for r in rows:
        i = bisect.bisect_left(marks, r.line) - 1  # (the last marker above the row)
        if i < 0:
            raise InputFileError(f"{where}: {path}, line {r.line}: a data line before the first table's "
                                 "'# tip: ...' line", path, r.line)
        _, key, case = sections[i]
        tables.setdefault(key, {}).setdefault(case, []).append(r)
    keys = list(tables)
    if any(k[0] == "point" for k in keys):
        if len(keys) > 1:
            raise InputFileError(f"{where}: {path} holds the tables of several points ({', '.join(k[1] for k in keys)}"
                                 "; cracklip grow's beta_tables.txt): a one-size life reads one of them -- give "
                                 "beta_deepest.csv (a: the depth) or beta_surface.csv (a: the surface length c) of "
                                 "the same run", path)
        picked = keys[0]
        what = f"{picked[1]}"
    else:
        tip = _chosen_tip(path, sorted((int(k[1]), int(k[2])) for k in keys), tip, where)
        picked = next(k for k in keys if (int(k[1]), int(k[2])) == tip)
        what = f"crack {tip[0]} end {tip[1]}"
    cases = {c: rs for c, rs in tables[picked].items() if not _LEVEL_CASE.fullmatch(c)}
    if not cases:
        raise InputFileError(f"{where}: {path}: the tables of {what} are all beta at contact levels "
                             f"({sorted(tables[picked])}), no load group's", path)
    a_ref = None
    values = {}
    for c, rs in cases.items():
        _width(path, rs, 2, where)
        a = np.array([number(path, r, 0, where, "crack size a") for r in rs]) * scale
        _sizes(path, rs, a, where, 1)
        if a_ref is not None and (a.shape != a_ref.shape or not np.array_equal(a, a_ref)):
            raise InputFileError(f"{where}: {path}: the tables of {what} give beta at different crack sizes "
                                 f"(cases {sorted(cases)})", path, rs[0].line)
        a_ref = a
        values[c] = np.array([number(path, r, 1, where, "beta") for r in rs])
    if len(values) == 1:  # one table: the spectrum's one load group, whatever its name (as a plain 'a beta' file)
        values = {DEFAULT_CASE: next(iter(values.values()))}
    return KTableData(1, a_ref, values, "beta", f"{path} (cracklip grow's two-column tables, {what}: beta of "
                      f"{', '.join(sorted(cases))})")


def _sizes(path, rows: list[Row], a: np.ndarray, where: str, column: int) -> None:
    for i, r in enumerate(rows):
        if not a[i] > 0:
            raise InputFileError(f"{where}: {path}, line {r.line}, column {column}: the crack size must be positive, "
                                 f"got {a[i]:g}", path, r.line, column)
    _rising(path, rows, a, column, where, "crack sizes (non-monotonic crack sizes)")


def _grow_table(path, head: Row, data: list[Row], col: dict[str, int], where: str, tip, scale: float) -> KTableData:
    """cracklip grow's beta.csv: the rows of one tip, K_I per load group."""
    keys = [(int(number(path, r, col["crack"], where, "crack")), int(number(path, r, col["end"], where, "end")))
            for r in data]
    tip = _chosen_tip(path, sorted(set(keys)), tip, where)
    rows = [r for r, k in zip(data, keys) if k == tip]
    groups = {n[4:]: j for n, j in col.items() if n.startswith("K_I_")}
    if not groups:
        raise InputFileError(f"{where}: {path}, line {head.line}: no K_I_<group> column (a beta table cracklip grow "
                             "wrote has one per load group)", path, head.line)
    a = np.array([number(path, r, col["a"], where, "crack size a") for r in rows]) * scale
    _sizes(path, rows, a, where, col["a"] + 1)
    values = {g: np.array([number(path, r, j, where, f"K_I_{g}") for r in rows]) for g, j in groups.items()}
    steady: tuple[str, ...] = ()
    if "K_residual" in col:
        values["residual"] = np.array([number(path, r, col["K_residual"], where, "K_residual") for r in rows])
        steady = ("residual",)
    return KTableData(1, a, values, "K", f"{path} (cracklip grow's beta table, crack {tip[0]} end {tip[1]}: K_I "
                      "per unit factor of each load group)", steady=steady)


def _two_size_table(path, head: Row, data: list[Row], col: dict[str, int], where: str, scale: float) -> KTableData:
    """a, c, beta_a, beta_c (or K_a, K_c) on a full grid of (a, c)."""
    if {"beta_a", "beta_c"} <= set(col):
        kind, ja, jc = "beta", col["beta_a"], col["beta_c"]
    elif {"K_a", "K_c"} <= set(col):
        kind, ja, jc = "K", col["K_a"], col["K_c"]
    else:
        raise InputFileError(f"{where}: {path}, line {head.line}: a table of two crack sizes needs columns a, c and "
                             f"beta_a, beta_c (or K_a, K_c), got {list(col)}", path, head.line)
    a = np.array([number(path, r, col["a"], where, "crack depth a") for r in data]) * scale
    c = np.array([number(path, r, col["c"], where, "crack length c") for r in data]) * scale
    for i, r in enumerate(data):
        for v, j in ((a[i], col["a"]), (c[i], col["c"])):
            if not v > 0:
                raise InputFileError(f"{where}: {path}, line {r.line}, column {j + 1}: the crack size must be "
                                     f"positive, got {v:g}", path, r.line, j + 1)
    A, C = np.unique(a), np.unique(c)
    if A.size < 2 or C.size < 2 or A.size * C.size != len(data):
        raise InputFileError(f"{where}: {path}: the rows must cover a grid of (a, c), every a with every c: {A.size} "
                             f"values of a and {C.size} of c make {A.size * C.size} rows, the file has {len(data)}",
                             path)
    K = np.full((A.size, C.size, 2), np.nan)
    for i, r in enumerate(data):
        p, q = int(np.searchsorted(A, a[i])), int(np.searchsorted(C, c[i]))
        if not np.isnan(K[p, q, 0]):
            raise InputFileError(f"{where}: {path}, line {r.line}: (a, c) = ({a[i]:g}, {c[i]:g}) comes twice", path,
                                 r.line)
        K[p, q] = number(path, r, ja, where, "deepest-point value"), number(path, r, jc, where, "surface value")
    return KTableData(2, A, {DEFAULT_CASE: K}, kind, f"{path} (two sizes, {A.size} x {C.size} grid)", c=C)


__all__ = ["RATE_LAYOUTS", "UNSUPPORTED_RATE_LAYOUTS", "read_rows", "read_turning_points", "read_rate_table",
           "resolve_rate_table",
           "KTableData", "DEFAULT_CASE", "read_k_table"]
