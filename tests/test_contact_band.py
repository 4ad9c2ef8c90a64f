"""The P1- multiplier groups from the gathered crack band (issue 40,
cracklip/contact/band.py): the same on any number of processes, and built
from complete data."""
import numpy as np
import pytest

import cracklip as cl
from cracklip.contact.frictionless import create_contact_system
from cracklip.model.model import create_model

from conftest import ROOT
from test_contact_3d import P, _penny_scene, _pressed_scene


def _same_groups(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two labellings (group of every full multiplier) make the same partition."""
    pairs = np.unique(np.column_stack([a, b]), axis=0)
    return len(pairs) == len(np.unique(a)) == len(np.unique(b))


@pytest.mark.parametrize("dim", [2, 3])
def test_gathered_band_reproduces_the_local_space(dim, monkeypatch):
    """The P1- groups come from the crack band gathered in input order
    (contact/band.py, the same on any number of processes). Keyed by the
    local node and cell indices instead, the band must give exactly the
    groups of the space built on the local mesh (the unchanged C++ on the
    model's own arrays): then every piece, level set, reference point and
    enriched-node flag the band carries is complete and right (the block of
    paper 5.1 with a tip cell in 2D; the pressed penny with front P0
    multipliers in 3D: 9 groups of 111 full multipliers), and in input
    order the same 9 (the groups do not depend on the order:
    multiplier_groups.h; before, input order gave 7)."""
    from cracklip.contact import band
    if dim == 2:
        sf = cl.load_scene_file(str(ROOT / "demos" / "scenes" / "block_uniform_pressure.toml"), ["mesh.h=0.1"])
        model = create_model(sf.scene)
    else:
        model = create_model(_pressed_scene(0.1, _penny_scene(0.1, "stable").cracks[0], -P * np.eye(3),
                                            enrichment="vector"))
    canonical = create_contact_system(model)
    monkeypatch.setattr(band, "_node_keys", lambda m: np.arange(len(m.x)))
    monkeypatch.setattr(band, "_cell_keys", lambda m: np.arange(len(m.cells)))
    local_order = create_contact_system(model)
    space = local_order.space
    assert local_order.R.nnz == space.num_full == canonical.R.nnz    # every full multiplier in one group
    assert local_order.num_multipliers == space.num_reduced
    assert _same_groups(local_order.R.indices, np.asarray(space.full_to_reduced))
    assert np.array_equal(np.asarray(local_order.band.vital_edges).shape, np.asarray(space.vital_edges).shape)
    if dim == 3:
        assert (space.num_full, space.num_reduced, canonical.num_multipliers) == (111, 9, 9)
