// alignset._sampler: the sampler library (<alignset/aligned_sampler.h>,
// <alignset/set_table.h>) for a renderer prototyped in NumPy. The same
// objects and the same four calls; points and values are NumPy arrays.
// alignset/sampler.py is the module users import.
#include <alignset/aligned_sampler.h>
#include <alignset/set_table.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
using alignset::AlignedSampler;
using alignset::AlignedSamplerOptions;
using alignset::PixelPlan;
using alignset::Point2;
using alignset::SetTable;

namespace {

// A refused call raises ValueError (bad input), LookupError (a key or file
// not found) or OSError (a damaged file), with the library's message.
[[noreturn]] void Raise(const alignset::Status& s) {
  switch (s.code()) {
    case alignset::Status::Code::kNotFound: throw py::key_error(s.message());
    case alignset::Status::Code::kDataLoss: throw std::runtime_error(s.message());
    default: throw py::value_error(s.message());
  }
}

py::array_t<double> PointsArray(const std::vector<Point2>& p) {
  py::array_t<double> out({static_cast<py::ssize_t>(p.size()), py::ssize_t{2}});
  auto a = out.mutable_unchecked<2>();
  for (size_t i = 0; i < p.size(); ++i) {
    a(i, 0) = p[i].x;
    a(i, 1) = p[i].y;
  }
  return out;
}

std::vector<double> Values(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 1) throw py::value_error("values must be a 1-D array");
  return std::vector<double>(a.data(), a.data() + a.size());
}

// The Python object: a sampler with its own Scratch (Python calls it from
// one thread at a time).
struct PySampler {
  AlignedSampler sampler;
  AlignedSampler::Scratch scratch;
};

const char* ChoiceName(alignset::SetChoice::Kind k) {
  switch (k) {
    case alignset::SetChoice::Kind::kFallback: return "fallback";
    case alignset::SetChoice::Kind::kOne: return "one";
    case alignset::SetChoice::Kind::kTwo: return "two";
  }
  return "?";
}

}  // namespace

PYBIND11_MODULE(_sampler, m) {
  m.doc() = "The sampler library: table files and the per-pixel recipe (see alignset.sampler).";

  py::class_<SetTable, std::shared_ptr<SetTable>>(m, "SetTable")
      .def_static("load", [](const std::string& path) {
        auto t = SetTable::Load(path);
        if (!t.ok()) Raise(t.status());
        return std::const_pointer_cast<SetTable>(*t);
      }, py::arg("path"))
      .def("sections", [](const SetTable& t) {
        py::list out;
        for (const auto& s : t.sections()) {
          // The keys the section holds: its space's, or a partial section's list.
          const size_t held = s.keys.empty() ? alignset::TableSpaceKeys(s.space) : s.keys.size();
          out.append(py::make_tuple(s.n, s.construction, alignset::TableSpaceName(s.space), held));
        }
        return out;
      })
      .def("point_counts", &SetTable::PointCounts, py::arg("construction"));

  py::class_<PixelPlan>(m, "PixelPlan")
      .def_readonly("x", &PixelPlan::x)
      .def_readonly("y", &PixelPlan::y)
      .def_readonly("directions", &PixelPlan::directions)
      .def_readonly("theta1_deg", &PixelPlan::theta1_deg)
      .def_readonly("theta2_deg", &PixelPlan::theta2_deg)
      .def_readonly("pair_fell_back", &PixelPlan::pair_fell_back)
      .def_property_readonly("choice", [](const PixelPlan& p) {
        return py::make_tuple(ChoiceName(p.choice.kind), p.choice.a, p.choice.b);
      })
      .def_property_readonly("lattice_generator", [](const PixelPlan& p) { return p.set.lattice_generator; });

  py::class_<PySampler>(m, "AlignedSampler")
      .def(py::init([](std::shared_ptr<SetTable> table, uint32_t n, const std::string& construction,
                       const std::string& domain, uint32_t image_width, uint64_t seed, uint32_t prepass_samples,
                       const std::string& reuse, bool two_directions) {
             AlignedSamplerOptions o;
             o.n = n;
             o.construction = construction;
             if (domain != "footprint" && domain != "shared") throw py::value_error("domain must be 'footprint' or 'shared'");
             o.domain = domain == "shared" ? alignset::PixelDomain::kShared : alignset::PixelDomain::kFootprint;
             o.image_width = image_width;
             o.seed = seed;
             o.prepass_samples = prepass_samples;
             if (reuse != "unbiased" && reuse != "continue") throw py::value_error("reuse must be 'unbiased' or 'continue'");
             o.reuse = reuse == "continue" ? alignset::PrepassReuse::kContinue : alignset::PrepassReuse::kUnbiased;
             o.two_directions = two_directions;
             auto s = AlignedSampler::Create(table, o);
             if (!s.ok()) Raise(s.status());
             return std::make_unique<PySampler>(PySampler{*s, {}});
           }),
           py::arg("table"), py::arg("n"), py::arg("construction") = "lattice", py::arg("domain") = "footprint",
           py::arg("image_width"), py::arg("seed") = 1, py::arg("prepass_samples") = 0,
           py::arg("reuse") = "unbiased", py::arg("two_directions") = true)
      .def_property_readonly("n", [](const PySampler& s) { return s.sampler.n(); })
      .def_property_readonly("prepass_samples", [](const PySampler& s) { return s.sampler.prepass_samples(); })
      .def_property_readonly("block_radius", [](const PySampler& s) { return s.sampler.block_radius(); })
      .def_property_readonly("prepass_weight", [](const PySampler& s) { return s.sampler.PrepassWeight(); })
      .def("prepass_points", [](const PySampler& s, uint32_t x, uint32_t y) {
        std::vector<Point2> p(s.sampler.prepass_samples());
        s.sampler.PrepassPoints(x, y, p);
        return PointsArray(p);
      }, py::arg("x"), py::arg("y"))
      .def("plan", [](PySampler& s, uint32_t x, uint32_t y, const py::list& block) {
        std::vector<std::vector<double>> values;
        for (const py::handle& h : block) {
          values.push_back(h.is_none() ? std::vector<double>() : Values(py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h)));
        }
        std::vector<std::span<const double>> spans(values.begin(), values.end());
        auto plan = s.sampler.Plan(x, y, spans, s.scratch);
        if (!plan.ok()) Raise(plan.status());
        return *plan;
      }, py::arg("x"), py::arg("y"), py::arg("block"),
         "block: the (2R+1)^2 pixels around (x, y) row by row from (x-R, y-R), each its pre-pass values, "
         "None outside the image")
      .def("main_points", [](const PySampler& s, const PixelPlan& plan) {
        std::vector<Point2> p(s.sampler.n());
        s.sampler.MainPoints(plan, p);
        return PointsArray(p);
      }, py::arg("plan"))
      .def("estimate", [](const PySampler& s, const PixelPlan& plan,
                          const py::array_t<double, py::array::c_style | py::array::forcecast>& pre,
                          const py::array_t<double, py::array::c_style | py::array::forcecast>& main) {
        if (pre.size() != s.sampler.prepass_samples() || main.size() != s.sampler.n()) {
          throw py::value_error("estimate needs prepass_samples pre-pass values and n main values");
        }
        return s.sampler.Estimate(plan, Values(pre), Values(main));
      }, py::arg("plan"), py::arg("prepass_values"), py::arg("main_values"));
}
