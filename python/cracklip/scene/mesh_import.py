"""gmsh model -> DOLFINx mesh with its facet tags, the short way.

dolfinx.io.gmshio.model_to_mesh (0.5.2) also builds and distributes the
cell tags of every physical surface, which cracklip never uses, and routes
the facet markers through the parallel entity-distribution path: on a 60k-cell
mesh that is about half of its 0.4 s. Here the triangles and nodes go straight
to dolfinx.mesh.create_mesh, and the physical curves' line elements are
matched to the mesh's facets by their two vertices (original node indices,
through geometry.input_global_indices). First-order triangles in 2D or
tetrahedra in 3D (cracklip's meshes; mesh.check_mesh enforces it); in 3D
the physical surfaces' triangles tag the facets. Under mpirun rank 0
(where gmsh meshes: scene.mesh.gmsh_on_rank0) passes the whole mesh and
DOLFINx distributes it.
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


#: Per dimension: gmsh's cell element type, nodes per cell, its facet element
#: type, nodes per facet, and the names used in messages.
_GMSH_TYPES = {2: (2, 3, 1, 2, "3-node triangles", "2-node boundary lines", "curves"),
               3: (4, 4, 2, 3, "4-node tetrahedra", "3-node boundary triangles", "surfaces")}


def model_to_mesh(model, comm, surfaces: typing.Sequence[int] | None = None, dim: int = 2
                  ) -> tuple[typing.Any, typing.Any, dict[str, int]]:
    """(mesh, facet_tags, names) of the current gmsh model: its first-order
    cells of dimension dim (triangles in 2D, tetrahedra in 3D; of the given
    entities of that dimension only, `surfaces`, if given), facet tags from
    its physical groups of dimension dim - 1 (curves in 2D, surfaces in 3D;
    value = the physical tag, names from the physical names)."""
    import dolfinx.cpp.mesh
    import dolfinx.mesh
    from dolfinx.io import gmshio
    if comm.size > 1:
        return _model_to_distributed_mesh(model, comm, surfaces, dim)
    if dim not in _GMSH_TYPES:
        raise MeshError(f"cracklip meshes are 2D or 3D, not {dim}D")
    cell_type, _, _, _, cell_name, _, group_name = _GMSH_TYPES[dim]
    x, cells, names, lines, line_values = _read_model(model, surfaces, dim)
    shape = "triangle" if dim == 2 else "tetrahedron"
    msh = dolfinx.mesh.create_mesh(comm, cells, x, gmshio.ufl_mesh(cell_type, dim), partitioner=_serial_partitioner)
    assert msh.topology.cell_type.name == shape
    n = np.int64(x.shape[0])

    def key(sorted_nodes: np.ndarray) -> np.ndarray:
        k = sorted_nodes[:, 0].astype(np.int64)
        for j in range(1, sorted_nodes.shape[1]):
            k = k * n + sorted_nodes[:, j]
        return k
    tdim = msh.topology.dim
    msh.topology.create_entities(tdim - 1)
    msh.topology.create_connectivity(tdim - 1, tdim)
    num_facets = msh.topology.index_map(tdim - 1).size_local
    facets = np.arange(num_facets, dtype=np.int32)
    geo = dolfinx.cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)
    original = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)[geo]
    original.sort(axis=1)
    facet_keys = key(original)
    if len(lines):
        line_keys = key(lines)
        key_order = np.argsort(facet_keys)
        pos = np.searchsorted(facet_keys[key_order], line_keys)
        pos = np.minimum(pos, num_facets - 1)
        found = facet_keys[key_order][pos] == line_keys
        if not found.all():
            raise MeshError(f"{np.count_nonzero(~found)} boundary element(s) of the gmsh model's physical "
                            f"{group_name} are not facets of its {cell_name}")
        marked = key_order[pos]
        # One value per facet (the last physical group wins, as in gmshio).
        uniq, last = np.unique(marked[::-1], return_index=True)
        idx, val = uniq.astype(np.int32), line_values[::-1][last]
    else:
        idx, val = np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int32)
    facet_tags = dolfinx.mesh.meshtags(msh, tdim - 1, idx, val)
    return msh, facet_tags, names


def _read_model(model, surfaces, dim: int):
    """(x, cells, names, facets, values) of the current gmsh model: node
    coordinates (rows in gmsh tag order), cells and the physical groups'
    boundary elements (node rows, vertices sorted) as those rows, the
    elements' physical tags."""
    cell_type, npc, facet_type, npf, cell_name, facet_name, _ = _GMSH_TYPES[dim]
    tags, coords, _ = model.mesh.getNodes()
    order = np.argsort(tags, kind="stable")
    sorted_tags = tags[order]
    x = np.ascontiguousarray(coords.reshape(-1, 3)[order, :dim])
    entities = [(dim, -1)] if surfaces is None else [(dim, s) for s in surfaces]
    types, elem_nodes = [], []
    for d, e in entities:
        t, _, n = model.mesh.getElements(d, e)
        types += list(t)
        elem_nodes += list(n)
    if len(types) == 0:
        raise MeshError(f"the gmsh model has no {dim}D elements")
    if any(t != cell_type for t in types):
        raise MeshError(f"only {cell_name} are supported; mesh with Mesh.ElementOrder = 1 and "
                        "without recombination")
    cells = np.concatenate([_node_index(np.asarray(n), sorted_tags).reshape(-1, npc) for n in elem_nodes])
    names: dict[str, int] = {}
    facets, values = [np.zeros((0, npf), dtype=np.int64)], [np.zeros(0, dtype=np.int32)]
    for gdim, tag in model.getPhysicalGroups(dim - 1):
        names[model.getPhysicalName(gdim, tag) or str(tag)] = tag
        for entity in model.getEntitiesForPhysicalGroup(gdim, tag):
            ltypes, _, lnodes = model.mesh.getElements(dim - 1, entity)
            for t, nodes in zip(ltypes, lnodes):
                if t != facet_type:
                    raise MeshError(f"only {facet_name} are supported (first-order mesh)")
                groups = np.sort(_node_index(np.asarray(nodes), sorted_tags).reshape(-1, npf), axis=1)
                facets.append(groups.astype(np.int64))
                values.append(np.full(len(groups), tag, dtype=np.int32))
    return x, cells.astype(np.int64), names, np.concatenate(facets), np.concatenate(values)


def _model_to_distributed_mesh(model, comm, surfaces, dim: int):
    """model_to_mesh on several processes (mpirun): rank 0 reads the gmsh
    model and passes every cell, node and tagged boundary element to
    DOLFINx, the other processes pass none; DOLFINx partitions the mesh and
    sends each process its cells with their vertex patches
    (scene.partition), and the boundary elements to the processes that hold
    them (distribute_entity_data, as gmshio does).
    Every process returns the same names; an error on rank 0 is raised on
    all (scene.processes.agree). model (and dim) matter on rank 0 only."""
    import dolfinx.cpp.io
    import dolfinx.cpp.graph
    import dolfinx.mesh
    from dolfinx.io import gmshio
    from .partition import vertex_patch_partitioner
    from .processes import agree
    read, error = None, None
    if comm.rank == 0:
        try:
            if dim not in _GMSH_TYPES:
                raise MeshError(f"cracklip meshes are 2D or 3D, not {dim}D")
            read = _read_model(model, surfaces, dim)
        except MeshError as e:
            error = e
    agree(error, comm)
    dim = comm.bcast(dim, root=0)  # (the other processes have no gmsh model: scene.mesh.gmsh_on_rank0)
    cell_type, npc, _, npf, cell_name, _, group_name = _GMSH_TYPES[dim]
    if comm.rank == 0:
        x, cells, names, facets, values = read
        # One value per boundary element (the last physical group wins, as in serial).
        uniq, last = np.unique(facets[::-1], axis=0, return_index=True)
        facets, values = uniq, values[::-1][last]
    else:
        x, cells = np.zeros((0, dim)), np.zeros((0, npc), dtype=np.int64)
        names, facets, values = None, np.zeros((0, npf), dtype=np.int64), np.zeros(0, dtype=np.int32)
    names = comm.bcast(names, root=0)
    num_marked = comm.bcast(len(facets), root=0)
    msh = dolfinx.mesh.create_mesh(comm, cells, x, gmshio.ufl_mesh(cell_type, dim),
                                   partitioner=vertex_patch_partitioner)
    tdim = msh.topology.dim
    msh.topology.create_entities(tdim - 1)
    msh.topology.create_connectivity(tdim - 1, tdim)
    entities, local_values = dolfinx.cpp.io.distribute_entity_data(msh._mesh, tdim - 1, facets, values)
    msh.topology.create_connectivity(tdim - 1, 0)
    facet_tags = dolfinx.mesh.meshtags_from_entities(
        msh, tdim - 1, dolfinx.cpp.graph.AdjacencyList_int32(entities), local_values.astype(np.int32))
    owned = np.count_nonzero(facet_tags.indices < msh.topology.index_map(tdim - 1).size_local)
    found = comm.allreduce(int(owned))
    if found != num_marked:
        agree(MeshError(f"{num_marked - found} boundary element(s) of the gmsh model's physical {group_name} "
                        f"are not facets of its {cell_name}"), comm)
    return msh, facet_tags, names
