// The pybind11 module cracklip._cracklip: one declare_* per area.
#include <pybind11/pybind11.h>

namespace cracklip_wrappers
{
void declare_geometry(pybind11::module& m);
void declare_geometry_3d(pybind11::module& m);
void declare_enrichment(pybind11::module& m);
void declare_assembly(pybind11::module& m);
void declare_fields(pybind11::module& m);
void declare_fracture(pybind11::module& m);
void declare_contact(pybind11::module& m);
void declare_contact_band(pybind11::module& m);
void declare_loads(pybind11::module& m);
void declare_life(pybind11::module& m);
} // namespace cracklip_wrappers

PYBIND11_MODULE(_cracklip, m)
{
  m.doc() = "cracklip C++ kernels: crack geometry, enrichment, enriched assembly, fields, tip functions, SIFs, fatigue life";
  cracklip_wrappers::declare_geometry(m);
  cracklip_wrappers::declare_geometry_3d(m);
  cracklip_wrappers::declare_enrichment(m);
  cracklip_wrappers::declare_assembly(m);
  cracklip_wrappers::declare_fields(m);
  cracklip_wrappers::declare_fracture(m);
  cracklip_wrappers::declare_contact(m);
  cracklip_wrappers::declare_contact_band(m);
  cracklip_wrappers::declare_loads(m);
  cracklip_wrappers::declare_life(m);
}
