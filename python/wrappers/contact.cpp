// Bindings: multiplier spaces, contact coupling, lip term of the interaction integral.
#include "array.h"

#include "contact/contact_kernels_2d.h"
#include "contact/contact_kernels_3d.h"
#include "contact/multiplier_space_2d.h"
#include "contact/multiplier_space_3d.h"
#include "solvers/saddle_matrix.h"
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;
using Cracks3D = std::vector<const CrackGeometry3D*>;

namespace
{
MultiplierKind multiplier_kind(const std::string& kind)
{
  if (kind != "naive" and kind != "stable")
    throw std::invalid_argument("multiplier space must be 'stable' or 'naive', got '" + kind + "'");
  return kind == "naive" ? MultiplierKind::naive : MultiplierKind::stable;
}

/// The restriction's properties (multiplier_groups.h), shared by the 2D and 3D spaces.
template <class Space>
void def_restriction(py::class_<Space>& c)
{
  auto vec = [](const std::vector<std::int32_t>& v) { return carray<std::int32_t>(v.size(), v.data()); };
  c.def_property_readonly("kind", [](const Space& s) { return s.kind == MultiplierKind::naive ? "naive" : "stable"; })
      .def_property_readonly("num_full", &Space::num_full)
      .def_property_readonly("num_reduced", [](const Space& s) { return s.num_reduced; })
      .def_property_readonly("full_to_reduced", [vec](const Space& s) { return vec(s.full_to_reduced); },
                             "(num_full) reduced index of every full multiplier (the prolongation R)")
      .def_property_readonly("reduced_offsets", [vec](const Space& s) { return vec(s.reduced_offsets); },
                             "(num_reduced + 1) CSR offsets of the members of every reduced multiplier")
      .def_property_readonly("reduced_full", [vec](const Space& s) { return vec(s.reduced_full); },
                             "(num_full) members (full multipliers, ascending) of every reduced multiplier")
      .def_property_readonly("full_node", [vec](const Space& s) { return vec(s.full_node); })
      .def_property_readonly("full_cell", [vec](const Space& s) { return vec(s.full_cell); })
      .def_property_readonly("full_crack", [vec](const Space& s) { return vec(s.full_crack); })
      .def_property_readonly("vital_edges", [](const Space& s)
                             {
                               return carray<std::int32_t>({py::ssize_t(s.vital_edges.size() / 2), py::ssize_t(2)},
                                                           s.vital_edges.data());
                             });
}

LipRule3D lip_rule(int n, double near_factor, bool signed_point_rule)
{
  if (n < 1)
    throw std::invalid_argument("contact points per direction must be >= 1, got " + std::to_string(n));
  return LipRule3D{n, near_factor, signed_point_rule};
}

py::tuple coo_tuple(Triplets& t)
{
  return py::make_tuple(as_pyarray(std::move(t.row)), as_pyarray(std::move(t.col)), as_pyarray(std::move(t.value)));
}
} // namespace

void declare_contact(py::module& m)
{
  py::class_<MultiplierSpace> space2(m, "MultiplierSpace", "Lagrange multipliers on the crack");
  def_restriction(space2);
  space2.def_property_readonly("num_segments", [](const MultiplierSpace& s) { return s.segments.size(); })
      .def_property_readonly("segment_crack", [](const MultiplierSpace& s)
                             {
                               std::vector<std::int32_t> c;
                               for (const auto& seg : s.segments)
                                 c.push_back(seg.crack);
                               return as_pyarray(std::move(c));
                             });

  m.def(
      "create_multiplier_space",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks& cracks,
         const EnrichmentLayout& layout, const std::string& kind, bool with_tip_segments)
      {
        return create_multiplier_space(as_span(x), as_span(cells), cracks, layout, multiplier_kind(kind),
                                       with_tip_segments);
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("layout"), py::arg("kind"),
      py::arg("with_tip_segments"));

  m.def(
      "assemble_coupling",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const MultiplierSpace& space, int n, bool tangential)
      {
        Triplets B, M, Bt;
        assemble_coupling(as_span(x), as_span(cells), layout, cracks, space, n, B, M,
                          tangential ? &Bt : nullptr);
        auto out = py::make_tuple(as_pyarray(std::move(B.row)), as_pyarray(std::move(B.col)),
                                  as_pyarray(std::move(B.value)), as_pyarray(std::move(M.row)),
                                  as_pyarray(std::move(M.col)), as_pyarray(std::move(M.value)));
        if (!tangential)
          return out;
        return py::tuple(out + py::make_tuple(as_pyarray(std::move(Bt.row)), as_pyarray(std::move(Bt.col)),
                                              as_pyarray(std::move(Bt.value))));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("space"), py::arg("n"),
      py::arg("tangential") = false,
      "Coupling B (full multipliers x dofs) and multiplier mass M as COO triplets (B rows, cols, "
      "values, M rows, cols, values); with tangential, then the tangential coupling Bt's triplets.");

  m.def(
      "compute_segment_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks& cracks,
         const MultiplierSpace& space, int n)
      {
        SegmentPoints s = compute_segment_points(as_span(x), as_span(cells), cracks, space, n);
        const py::ssize_t np_ = s.weight.size();
        py::dict d;
        d["segment"] = as_pyarray(std::move(s.segment));
        d["cell"] = as_pyarray(std::move(s.cell));
        d["ref"] = as_pyarray(std::move(s.ref), {np_, 2});
        d["x"] = as_pyarray(std::move(s.x), {np_, 2});
        d["weight"] = as_pyarray(std::move(s.weight));
        d["normal"] = as_pyarray(std::move(s.normal), {np_, 2});
        d["entry_point"] = as_pyarray(std::move(s.entry_point));
        d["entry_mult"] = as_pyarray(std::move(s.entry_mult));
        d["entry_value"] = as_pyarray(std::move(s.entry_value));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("space"), py::arg("n"));

  m.def(
      "evaluate_multipliers",
      [](const MultiplierSpace& space, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& lambda_full)
      {
        return as_pyarray(evaluate_multipliers(space, crack, as_span(point_cells), as_span(ref),
                                               as_span(lambda_full)));
      },
      py::arg("space"), py::arg("crack"), py::arg("point_cells"), py::arg("ref"), py::arg("lambda_full"),
      "Values (n) of a full multiplier field at points (cell, reference) of a crack.");

  py::class_<MultiplierSpace3D> space3(m, "MultiplierSpace3D", "Lagrange multipliers on the lips of a 3D crack");
  def_restriction(space3);
  space3.def_property_readonly("num_pieces", [](const MultiplierSpace3D& s) { return s.pieces.size(); })
      .def_property_readonly("pieces", [](const MultiplierSpace3D& s)
                             {
                               std::vector<std::int32_t> crack, cell, offsets = {0}, mult, local;
                               std::vector<std::int8_t> front;
                               for (const LipPiece3D& p : s.pieces)
                               {
                                 crack.push_back(p.crack), cell.push_back(p.cell);
                                 front.push_back(p.front ? 1 : 0);
                                 mult.insert(mult.end(), p.mult.begin(), p.mult.end());
                                 local.insert(local.end(), p.local.begin(), p.local.end());
                                 offsets.push_back(static_cast<std::int32_t>(mult.size()));
                               }
                               py::dict d;
                               d["crack"] = as_pyarray(std::move(crack));
                               d["cell"] = as_pyarray(std::move(cell));
                               d["front"] = as_pyarray(std::move(front));
                               d["offsets"] = as_pyarray(std::move(offsets));
                               d["mult"] = as_pyarray(std::move(mult));
                               d["local"] = as_pyarray(std::move(local));
                               return d;
                             },
                             "Lip pieces: crack, cell, front (1: a front cell's) per piece; the full multipliers "
                             "of piece i are mult[offsets[i]:offsets[i + 1]], local their node in the cell (-1: P0).");

  m.def(
      "create_multiplier_space_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks3D& cracks,
         const EnrichmentLayout& layout, const std::string& kind, bool with_front_pieces)
      {
        return create_multiplier_space_3d(as_span(x), as_span(cells), cracks, layout, multiplier_kind(kind),
                                          with_front_pieces);
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("layout"), py::arg("kind"),
      py::arg("with_front_pieces"), "The multiplier space on the lip pieces of 3D cracks (contact/multiplier_space_3d.h).");

  m.def(
      "assemble_coupling_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks3D& cracks, const MultiplierSpace3D& space, int n, double near_factor, bool signed_point_rule,
         bool tangential, const std::optional<carray<double>>& tangent_reference)
      {
        Triplets B, M, T1, T2;
        ContactSinks3D sinks{coo_sink(B), coo_sink(M), tangential ? coo_sink(T1) : MatrixSink(),
                             tangential ? coo_sink(T2) : MatrixSink()};
        const std::span<const double> ref = tangent_reference ? as_span(*tangent_reference) : std::span<const double>();
        assemble_coupling_3d(as_span(x), as_span(cells), layout, cracks, space,
                             lip_rule(n, near_factor, signed_point_rule), sinks, ref);
        py::dict d;
        d["B"] = coo_tuple(B);
        d["M"] = coo_tuple(M);
        if (tangential)
        {
          d["Bt1"] = coo_tuple(T1);
          d["Bt2"] = coo_tuple(T2);
        }
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("space"), py::arg("n") = 6,
      py::arg("near_factor") = 1.0, py::arg("signed_point_rule") = true, py::arg("tangential") = false,
      py::arg("tangent_reference") = py::none(),
      "Coupling B (full multipliers x dofs), multiplier mass M and, with tangential, the tangential couplings "
      "Bt1, Bt2 as COO triplets (rows, cols, values) in a dict; tangent_reference: (num_cracks, 3) or None "
      "(contact/contact_kernels_3d.h).");

  m.def(
      "compute_contact_points_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks3D& cracks,
         const MultiplierSpace3D& space, int n, double near_factor, bool signed_point_rule,
         const std::optional<carray<double>>& tangent_reference)
      {
        const std::span<const double> ref = tangent_reference ? as_span(*tangent_reference) : std::span<const double>();
        ContactPoints3D s = compute_contact_points_3d(as_span(x), as_span(cells), cracks, space,
                                                      lip_rule(n, near_factor, signed_point_rule), ref);
        const py::ssize_t np_ = s.weight.size();
        py::dict d;
        d["piece"] = as_pyarray(std::move(s.piece));
        d["cell"] = as_pyarray(std::move(s.cell));
        d["ref"] = as_pyarray(std::move(s.ref), {np_, 3});
        d["x"] = as_pyarray(std::move(s.x), {np_, 3});
        d["weight"] = as_pyarray(std::move(s.weight));
        d["normal"] = as_pyarray(std::move(s.normal), {np_, 3});
        d["t1"] = as_pyarray(std::move(s.t1), {np_, 3});
        d["t2"] = as_pyarray(std::move(s.t2), {np_, 3});
        d["entry_point"] = as_pyarray(std::move(s.entry_point));
        d["entry_mult"] = as_pyarray(std::move(s.entry_mult));
        d["entry_value"] = as_pyarray(std::move(s.entry_value));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("space"), py::arg("n") = 6,
      py::arg("near_factor") = 1.0, py::arg("signed_point_rule") = true, py::arg("tangent_reference") = py::none(),
      "Quadrature points on the pieces of a 3D multiplier space with multiplier values (COO) and tangent bases.");

  m.def(
      "evaluate_multipliers_3d",
      [](const MultiplierSpace3D& space, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& lambda_full)
      {
        return as_pyarray(evaluate_multipliers_3d(space, crack, as_span(point_cells), as_span(ref),
                                                  as_span(lambda_full)));
      },
      py::arg("space"), py::arg("crack"), py::arg("point_cells"), py::arg("ref"), py::arg("lambda_full"),
      "Values (n) of a full multiplier field at points (cell, reference (n, 3)) of a 3D crack.");

  m.def(
      "tangent_basis_3d",
      [](const CrackGeometry3D& crack, const carray<double>& normals, const std::optional<carray<double>>& reference)
      {
        if (normals.ndim() != 2 or normals.shape(1) != 3)
          throw std::invalid_argument("tangent_basis_3d: normals must be (n, 3)");
        Point3 a;
        if (reference)
        {
          if (reference->size() != 3)
            throw std::invalid_argument("tangent_basis_3d: the reference must have 3 values");
          a = {reference->data()[0], reference->data()[1], reference->data()[2]};
        }
        else
          a = default_tangent_reference(crack);
        const py::ssize_t n = normals.shape(0);
        std::vector<double> t1(3 * n), t2(3 * n);
        const double* nv = normals.data();
        for (py::ssize_t i = 0; i < n; ++i)
        {
          Point3 a1, a2;
          tangent_basis({nv[3 * i], nv[3 * i + 1], nv[3 * i + 2]}, a, a1, a2);
          std::copy(a1.begin(), a1.end(), t1.begin() + 3 * i);
          std::copy(a2.begin(), a2.end(), t2.begin() + 3 * i);
        }
        return py::make_tuple(as_pyarray(std::move(t1), {n, py::ssize_t(3)}), as_pyarray(std::move(t2), {n, py::ssize_t(3)}));
      },
      py::arg("crack"), py::arg("normals"), py::arg("reference") = py::none(),
      "(t1, t2), each (n, 3): the contact coupling's tangent basis (contact/contact_kernels_3d.h) at points of a "
      "crack with unit normals (n, 3), from its reference direction (default: the crack's default_tangent_reference).");

  m.def(
      "saddle_csr",
      [](const carray<std::int32_t>& k_indptr, const carray<std::int32_t>& k_indices,
         const carray<double>& k_data, const carray<std::int32_t>& b_indptr,
         const carray<std::int32_t>& b_indices, const carray<double>& b_data,
         const carray<std::int8_t>& active, const carray<std::int32_t>& s_indptr,
         const carray<std::int32_t>& s_indices, const carray<double>& s_data)
      {
        SaddleCsr s = saddle_csr(as_span(k_indptr), as_span(k_indices), as_span(k_data), as_span(b_indptr),
                                 as_span(b_indices), as_span(b_data), as_span(active), as_span(s_indptr),
                                 as_span(s_indices), as_span(s_data));
        return py::make_tuple(as_pyarray(std::move(s.indptr)), as_pyarray(std::move(s.indices)),
                              as_pyarray(std::move(s.data)));
      },
      py::arg("k_indptr"), py::arg("k_indices"), py::arg("k_data"), py::arg("b_indptr"),
      py::arg("b_indices"), py::arg("b_data"), py::arg("active"), py::arg("s_indptr"), py::arg("s_indices"),
      py::arg("s_data"),
      "CSR (indptr, indices, data) of [K B_a^T; B_a D], D = -S on the active multipliers (S: empty arrays for none; "
      "cpp/solvers/saddle_matrix.h).");
}

} // namespace cracklip_wrappers
