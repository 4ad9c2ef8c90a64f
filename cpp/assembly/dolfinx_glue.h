// DOLFINx and PETSc glue (layer b).
#pragma once

#include "assembly/matrix_sink.h"

#include <cstdint>
#include <petscmat.h>
#include <vector>

namespace dolfinx::fem
{
class FunctionSpace;
}

namespace cracklip
{

/// The P1 "node mesh" of a DOLFINx P1 vector function space: one node per
/// dof block. x: (num_nodes, gdim) node coordinates, cells: (num_cells,
/// gdim + 1) node (= dof block) indices per cell in the reference vertex
/// order; gdim 2 (triangles) or 3 (tetrahedra). Under MPI the process's
/// local nodes (owned, then ghost: V's dof blocks) and local cells (owned,
/// then ghost). Throws unless V is a P1 vector space on triangles or
/// tetrahedra.
struct NodeMesh
{
  int gdim = 2;
  std::vector<double> x;
  std::vector<std::int32_t> cells;
};
NodeMesh extract_node_mesh(const dolfinx::fem::FunctionSpace& V);

/// A sink that adds blocks into a PETSc matrix with global scalar indices
/// (MatSetValues, ADD_VALUES; negative indices are skipped by PETSc).
MatrixSink petsc_add_sink(Mat A);

/// A sink that adds blocks into a PETSc matrix with this process's local
/// scalar indices, mapped to global ones by the matrix's local-to-global map
/// (MatSetValuesLocal, ADD_VALUES): the kernels keep their numbering under MPI.
MatrixSink petsc_add_local_sink(Mat A);

} // namespace cracklip
