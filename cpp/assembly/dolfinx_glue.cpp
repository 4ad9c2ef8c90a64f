#include "assembly/dolfinx_glue.h"

#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/FiniteElement.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

NodeMesh extract_node_mesh(const dolfinx::fem::FunctionSpace& V)
{
  const auto mesh = V.mesh();
  const auto type = mesh->topology().cell_type();
  if (type != dolfinx::mesh::CellType::triangle and type != dolfinx::mesh::CellType::tetrahedron)
    throw std::invalid_argument("cracklip needs a triangle or a tetrahedron mesh, got cell type "
                                + dolfinx::mesh::to_string(type));
  const int gdim = type == dolfinx::mesh::CellType::triangle ? 2 : 3;
  if (mesh->geometry().dim() != gdim)
    throw std::invalid_argument("cracklip needs a mesh whose geometric dimension is its cells' ("
                                + std::to_string(gdim) + "), got " + std::to_string(mesh->geometry().dim()));
  const auto dofmap = V.dofmap();
  if (dofmap->index_map_bs() != gdim or static_cast<int>(dofmap->cell_dofs(0).size()) != gdim + 1)
    throw std::invalid_argument("cracklip needs a P1 vector function space (block size " + std::to_string(gdim)
                                + ", " + std::to_string(gdim + 1) + " dof blocks per cell)");

  NodeMesh out;
  out.gdim = gdim;
  // Under MPI: this process's owned nodes, then its ghost nodes (the dof
  // blocks of its ghost cells); in serial there are no ghosts.
  const std::int32_t num_nodes = dofmap->index_map->size_local() + dofmap->index_map->num_ghosts();
  // A P1 dof sits at a cell vertex: copy the mesh's vertex coordinates (the
  // geometry dofmap lists a cell's vertices first, in the same reference
  // order) rather than push the reference vertex forward through the cell map
  // (tabulate_dof_coordinates), whose round-off puts a corner at
  // -0.9999999999999999 on some meshes, depending on which cell maps it.
  const std::span<const double> xg = mesh->geometry().x(); // (num_geometry_nodes, 3)
  const auto& gdofs = mesh->geometry().dofmap();
  const auto& list = dofmap->list();
  const std::int32_t num_cells = list.num_nodes();
  out.x.resize(gdim * num_nodes);
  out.cells.resize((gdim + 1) * num_cells);
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    auto dofs = list.links(c);
    auto g = gdofs.links(c);
    for (int a = 0; a <= gdim; ++a)
    {
      out.cells[(gdim + 1) * c + a] = dofs[a];
      for (int d = 0; d < gdim; ++d)
        out.x[gdim * dofs[a] + d] = xg[3 * g[a] + d];
    }
  }
  return out;
}

namespace
{
/// A sink adding blocks through MatSetValues or MatSetValuesLocal (the same
/// signature); a failure names the call and what it means.
using SetValues = PetscErrorCode (*)(Mat, PetscInt, const PetscInt[], PetscInt, const PetscInt[], const PetscScalar[],
                                     InsertMode);
MatrixSink petsc_sink(Mat A, SetValues set, const char* name, const char* meaning)
{
  return [A, set, name, meaning](std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                                 std::span<const double> values)
  {
    PetscErrorCode ierr = set(A, static_cast<PetscInt>(rows.size()), rows.data(), static_cast<PetscInt>(cols.size()),
                              cols.data(), values.data(), ADD_VALUES);
    if (ierr != 0)
      throw std::runtime_error(std::string(name) + " failed (PETSc error " + std::to_string(ierr) + ")" + meaning);
  };
}
} // namespace

MatrixSink petsc_add_sink(Mat A)
{
  return petsc_sink(A, MatSetValues, "MatSetValues", ": the matrix sparsity misses an enriched coupling");
}

MatrixSink petsc_add_local_sink(Mat A)
{
  return petsc_sink(A, MatSetValuesLocal, "MatSetValuesLocal", "");
}

} // namespace cracklip
