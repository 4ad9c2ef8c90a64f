"""gmsh model -> DOLFINx mesh with its facet tags, the short way.

dolfinx.io.gmshio.model_to_mesh (0.5.2) also builds and distributes the
cell tags of every physical surface, which cracklip never uses, and routes
the facet markers through the parallel entity-distribution path: on a 60k-cell
mesh that is about half of its 0.4 s. Here the triangles and nodes go straight
to dolfinx.mesh.create_mesh, and the physical curves' line elements are
matched to the mesh's facets by their two vertices (original node indices,
through geometry.input_global_indices). Serial only, first-order triangles
(cracklip's meshes; mesh.check_mesh enforces it).
"""
from __future__ import annotations

import typing

import numpy as np

from ..errors import MeshError


def _node_index(tags: np.ndarray, sorted_tags: np.ndarray) -> np.ndarray:
    """Positions (in the node array sorted by tag) of gmsh node tags."""
    pos = np.searchsorted(sorted_tags, tags)
    pos = np.minimum(pos, sorted_tags.size - 1)
    if not np.array_equal(sorted_tags[pos], tags):
        raise MeshError("the gmsh model refers to a node it does not define")
    return pos


def _serial_partitioner(comm, nparts, tdim, cells, *args):
    """Every cell to process 0. DOLFINx's default partitioner builds the dual
    graph to partition it even on one process (0.03-0.1 s of 0.15 s at 60k
    cells); the mesh made is the same (its cells are reordered afterwards
    either way)."""
    import dolfinx.cpp.graph
    return dolfinx.cpp.graph.AdjacencyList_int32(np.zeros(cells.num_nodes, dtype=np.int32))


def model_to_mesh(model, comm, surfaces: typing.Sequence[int] | None = None
                  ) -> tuple[typing.Any, typing.Any, dict[str, int]]:
    """(mesh, facet_tags, names) of the current gmsh model: the 3-node
    triangles of its 2D elements (of the given surfaces only, if given),
    facet tags from its physical curves (value = the physical tag, names
    from the physical names)."""
    import dolfinx.cpp.mesh
    import dolfinx.mesh
    from dolfinx.io import gmshio
    tags, coords, _ = model.mesh.getNodes()
    coords = coords.reshape(-1, 3)
    order = np.argsort(tags, kind="stable")
    sorted_tags = tags[order]
    x = np.ascontiguousarray(coords[order, :2])
    if surfaces is None:
        types, _, elem_nodes = model.mesh.getElements(2)
    else:
        types, elem_nodes = [], []
        for s in surfaces:
            t, _, n = model.mesh.getElements(2, s)
            types += list(t)
            elem_nodes += list(n)
    if len(types) == 0:
        raise MeshError("the gmsh model has no 2D elements")
    if any(t != 2 for t in types):
        raise MeshError("only 3-node triangles are supported; mesh with Mesh.ElementOrder = 1 and "
                        "without recombination")
    cells = np.concatenate([_node_index(np.asarray(n), sorted_tags).reshape(-1, 3) for n in elem_nodes])
    serial = {"partitioner": _serial_partitioner} if comm.size == 1 else {}
    msh = dolfinx.mesh.create_mesh(comm, cells.astype(np.int64), x, gmshio.ufl_mesh(2, 2), **serial)

    names: dict[str, int] = {}
    keys, values = [], []
    for dim, tag in model.getPhysicalGroups(1):
        names[model.getPhysicalName(dim, tag) or str(tag)] = tag
        for entity in model.getEntitiesForPhysicalGroup(dim, tag):
            ltypes, _, lnodes = model.mesh.getElements(1, entity)
            for t, nodes in zip(ltypes, lnodes):
                if t != 1:
                    raise MeshError("only 2-node boundary lines are supported (first-order mesh)")
                pairs = np.sort(_node_index(np.asarray(nodes), sorted_tags).reshape(-1, 2), axis=1)
                keys.append(pairs[:, 0].astype(np.int64) * x.shape[0] + pairs[:, 1])
                values.append(np.full(len(pairs), tag, dtype=np.int32))
    tdim = msh.topology.dim
    msh.topology.create_entities(tdim - 1)
    msh.topology.create_connectivity(tdim - 1, tdim)
    num_facets = msh.topology.index_map(tdim - 1).size_local
    facets = np.arange(num_facets, dtype=np.int32)
    geo = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    original = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)[geo]
    original.sort(axis=1)
    facet_keys = original[:, 0] * x.shape[0] + original[:, 1]
    if keys:
        line_keys, line_values = np.concatenate(keys), np.concatenate(values)
        key_order = np.argsort(facet_keys)
        pos = np.searchsorted(facet_keys[key_order], line_keys)
        pos = np.minimum(pos, num_facets - 1)
        found = facet_keys[key_order][pos] == line_keys
        if not found.all():
            raise MeshError(f"{np.count_nonzero(~found)} boundary line element(s) of the gmsh model are not "
                            "edges of its triangles")
        marked = key_order[pos]
        # One value per facet (the last physical group wins, as in gmshio).
        uniq, last = np.unique(marked[::-1], return_index=True)
        idx, val = uniq.astype(np.int32), line_values[::-1][last]
    else:
        idx, val = np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int32)
    facet_tags = dolfinx.mesh.meshtags(msh, tdim - 1, idx, val)
    return msh, facet_tags, names
