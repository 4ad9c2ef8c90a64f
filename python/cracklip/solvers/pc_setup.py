"""A PETSc preconditioner set up from a dictionary of options (GAMG's, the
outer block's) under a prefix of its own, and the product setting every
such set-up runs under."""
from __future__ import annotations

import contextlib
import itertools
import typing

from petsc4py import PETSc


_prefixes = itertools.count()


def set_up_pc(A: PETSc.Mat, name: str, options: dict[str, typing.Any]) -> PETSc.PC:
    """A PC on A set up from `options` (PETSc option names without the
    prefix) under a prefix of its own (cracklip_<name><k>_), which is
    cleared again from PETSc's options database afterwards (GAMG's and the
    outer block's)."""
    prefix = f"cracklip_{name}{next(_prefixes)}_"
    pc = PETSc.PC().create(A.getComm())
    pc.setOptionsPrefix(prefix)
    pc.setOperators(A)
    db = PETSc.Options()
    for k, v in options.items():
        db[prefix + k] = v
    try:
        pc.setFromOptions()
        with product_data_cleared():
            pc.setUp()
    finally:
        for k in options:
            db.delValue(prefix + k)
    return pc


@contextlib.contextmanager
def product_data_cleared() -> typing.Iterator[None]:
    """Within it, a distributed matrix product (PtAP) frees the data it
    keeps for recomputing the product with new values (PETSc's
    -mat_product_clear), which cracklip never does: the parallel PtAP of
    the phantom transform and of GAMG's coarse levels otherwise hold about
    as much again as their results. The penny at 2.9e5 dofs on 2 processes:
    2.53 -> 1.69 GB peak over both after GAMG's set-up (serial products
    keep nothing of the kind: 0.96 GB either way); the numbers are the
    same. A value the user set is left as it is."""
    db = PETSc.Options()
    mine = not db.hasName("mat_product_clear")
    if mine:
        db["mat_product_clear"] = 1
    try:
        yield
    finally:
        if mine:
            db.delValue("mat_product_clear")
