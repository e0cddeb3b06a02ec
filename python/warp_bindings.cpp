// The sample warps and their pdfs over NumPy arrays (one C++ loop, GIL released), the chi-square
// test `penumbra warp` runs, and the samplers' 2-D point sets.
#include <pybind11/stl.h>

#include <optional>

#include "core/math/error.h"
#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/sampling/warp_params.h"
#include "python/bindings.h"

namespace penumbra::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

struct WarpChoice {
  WarpType type;
  float param;
};

// Name and parameter as the CLI checks them; errors are ValueErrors naming the argument.
WarpChoice choose(const std::string& name, const std::optional<double>& param) {
  WarpType type;
  if (!parseWarpType(name, type))
    throw py::value_error("name: unknown warp '" + name + "' (expected one of: " + warpTypeList() + ")");
  try {
    return {type, checkedWarpParam(type, param.has_value(), param.value_or(0.0), "param")};
  } catch (const Error& e) {
    throw py::value_error(e.what());
  }
}

FloatArray points(const py::handle& input, const char* argument, py::ssize_t minColumns,
                  py::ssize_t maxColumns) {
  FloatArray a;
  try {
    a = FloatArray::ensure(input);
  } catch (const py::error_already_set&) {
  }
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(argument) + ": expected an (N, 2) or (N, 3) array of numbers");
  }
  if (a.ndim() != 2 || a.shape(1) < minColumns || a.shape(1) > maxColumns)
    throw py::value_error(std::string(argument) + ": expected shape (N, " + std::to_string(minColumns) +
                          (maxColumns > minColumns ? " or " + std::to_string(maxColumns) : std::string()) +
                          "), got ndim " + std::to_string(a.ndim()));
  return a;
}

// The output array: a new one, or `out` (NumPy's convention: a float32 C-contiguous array of the
// result's shape, reused so that repeated calls do not fault in fresh pages every time).
py::array_t<float> outputArray(const py::object& out, std::vector<py::ssize_t> shape) {
  if (out.is_none()) return py::array_t<float>(shape);
  auto a = py::array_t<float, py::array::c_style>::ensure(out);
  if (!a || !py::isinstance<py::array_t<float>>(out) || !a.writeable() ||
      !(py::cast<py::array>(out).flags() & py::array::c_style))
    throw py::type_error("out: expected a writeable C-contiguous float32 array");
  bool same = a.ndim() == py::ssize_t(shape.size());
  for (size_t i = 0; same && i < shape.size(); ++i) same = a.shape(i) == shape[i];
  if (!same) throw py::value_error("out: expected the result's shape");
  return py::reinterpret_borrow<py::array_t<float>>(out);
}

// One loop per warp, its function called directly (the type is resolved once, not per point).
template <typename F>
void warpLoop(F f, const float* src, float* dst, py::ssize_t n, py::ssize_t dims) {
  for (py::ssize_t i = 0; i < n; ++i) {
    Vec3 v = f(Vec2(src[2 * i], src[2 * i + 1]));
    dst[dims * i] = v.x;
    dst[dims * i + 1] = v.y;
    if (dims == 3) dst[dims * i + 2] = v.z;
  }
}

void warpAll(WarpChoice w, const float* src, float* dst, py::ssize_t n) {
  const float p = w.param;
  auto flat = [](Vec2 (*f)(Vec2)) { return [f](Vec2 u) { return Vec3(f(u), 0.f); }; };
  switch (w.type) {
    case WarpType::UniformSquare:
      return warpLoop(flat(&Warp::squareToUniformSquare), src, dst, n, 2);
    case WarpType::Tent:
      return warpLoop(flat(&Warp::squareToTent), src, dst, n, 2);
    case WarpType::UniformDisk:
      return warpLoop(flat(&Warp::squareToUniformDisk), src, dst, n, 2);
    case WarpType::ConcentricDisk:
      return warpLoop(flat(&Warp::squareToConcentricDisk), src, dst, n, 2);
    case WarpType::UniformSphere:
      return warpLoop(&Warp::squareToUniformSphere, src, dst, n, 3);
    case WarpType::UniformHemisphere:
      return warpLoop(&Warp::squareToUniformHemisphere, src, dst, n, 3);
    case WarpType::CosineHemisphere:
      return warpLoop(&Warp::squareToCosineHemisphere, src, dst, n, 3);
    case WarpType::UniformCone:
      return warpLoop([p](Vec2 u) { return Warp::squareToUniformCone(u, p); }, src, dst, n, 3);
    case WarpType::Beckmann:
      return warpLoop([p](Vec2 u) { return Warp::squareToBeckmann(u, p); }, src, dst, n, 3);
  }
}

py::array_t<float> warpArray(const std::string& name, const py::handle& u, std::optional<double> param,
                             const py::object& out) {
  WarpChoice w = choose(name, param);
  FloatArray in = points(u, "u", 2, 2);
  const py::ssize_t n = in.shape(0);
  py::array_t<float> result = outputArray(out, {n, warpIsSpherical(w.type) ? 3 : 2});
  const float* src = in.data();
  float* dst = result.mutable_data();
  {
    py::gil_scoped_release release;
    warpAll(w, src, dst, n);
  }
  return result;
}

py::array_t<float> pdfArray(const std::string& name, const py::handle& v, std::optional<double> param,
                            const py::object& out) {
  WarpChoice w = choose(name, param);
  FloatArray in = points(v, "v", 2, 3);
  const py::ssize_t n = in.shape(0), cols = in.shape(1);
  py::array_t<float> result = outputArray(out, {n});
  const float* src = in.data();
  float* dst = result.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      const float* p = src + cols * i;
      dst[i] = Warp::pdf(w.type, Vec3(p[0], p[1], cols == 3 ? p[2] : 0.f), w.param);
    }
  }
  return result;
}

struct Chi2Report {
  std::string warp;
  std::optional<float> param;
  double pValue = 0, chi2 = 0, alpha = 0;
  int dof = 0, pooledCells = 0;
  bool accepted = false;
  std::string message;
  py::array_t<double> observed, expected;
};

Chi2Report chi2(const std::string& name, int64_t samples, int64_t seed, int res, std::optional<double> param,
                int testCount) {
  WarpChoice w = choose(name, param);
  if (samples < 100 || samples > 1'000'000'000) throw py::value_error("samples: expected 100 .. 1e9");
  if (res < 2 || res > 1000) throw py::value_error("res: expected 2 .. 1000");
  if (seed < 0) throw py::value_error("seed: expected an integer >= 0");
  if (testCount < 1) throw py::value_error("test_count: expected >= 1");
  Chi2Options opt;
  opt.sampleCount = uint64_t(samples);
  opt.resolution = res;
  opt.seed = uint64_t(seed);
  opt.testCount = testCount;
  Chi2Result r;
  {
    py::gil_scoped_release release;
    r = chi2Test(chi2DomainFor(w.type, w.param), warpSampleFunction(w.type, w.param),
                 warpPdfFunction(w.type, w.param), opt);
  }
  Chi2Report out;
  out.warp = warpTypeName(w.type);
  if (warpHasParameter(w.type)) out.param = w.param;
  out.pValue = r.pValue;
  out.chi2 = r.chi2;
  out.dof = r.dof;
  out.alpha = r.alphaEffective;
  out.accepted = r.accepted;
  out.message = r.message;
  out.pooledCells = r.pooledCells;
  out.observed = py::array_t<double>({py::ssize_t(r.resY), py::ssize_t(r.resX)}, r.observed.data());
  out.expected = py::array_t<double>({py::ssize_t(r.resY), py::ssize_t(r.resX)}, r.expected.data());
  return out;
}

py::array_t<float> samplePoints(const std::string& samplerName, int64_t n, std::pair<int, int> pixel,
                                std::pair<int, int> dims, int64_t seed, std::optional<int64_t> sampleCount) {
  SamplerKind kind;
  if (!parseSamplerKind(samplerName, kind))
    throw py::value_error("sampler: unknown sampler '" + samplerName +
                          "' (expected one of: " + acceptedSamplerNames() + ")");
  if (n < 1 || n > (int64_t(1) << 30)) throw py::value_error("n: expected 1 .. 2^30");
  if (dims.first < 0 || dims.first % 2 != 0 || dims.second != dims.first + 1)
    throw py::value_error("dims: expected a pair (2k, 2k + 1), the k-th 2-D draw of each pixel sample");
  if (pixel.first < 0 || pixel.second < 0) throw py::value_error("pixel: expected (x, y) >= 0");
  if (seed < 0) throw py::value_error("seed: expected an integer >= 0");
  int64_t count = sampleCount.value_or(n);
  if (count < 1 || count > (int64_t(1) << 30)) throw py::value_error("sample_count: expected 1 .. 2^30");
  py::array_t<float> out({py::ssize_t(n), py::ssize_t(2)});
  float* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    Sampler sampler(kind, uint32_t(count), uint64_t(seed));
    const int skip = dims.first / 2;
    for (int64_t i = 0; i < n; ++i) {
      sampler.startPixelSample(IVec2(pixel.first, pixel.second), uint32_t(i));
      for (int k = 0; k < skip; ++k) sampler.next2D();
      Vec2 p = sampler.next2D();
      dst[2 * i] = p.x;
      dst[2 * i + 1] = p.y;
    }
  }
  return out;
}

// The uniform stream `penumbra warp --dump` and the chi-square test draw: PCG32(mix64(seed), seed).
py::array_t<float> randomPoints(int64_t n, int64_t seed) {
  if (n < 0 || n > (int64_t(1) << 34)) throw py::value_error("n: expected 0 .. 2^34");
  if (seed < 0) throw py::value_error("seed: expected an integer >= 0");
  py::array_t<float> out({py::ssize_t(n), py::ssize_t(2)});
  float* dst = out.mutable_data();
  py::gil_scoped_release release;
  Rng rng(mix64(uint64_t(seed)), uint64_t(seed));
  for (int64_t i = 0; i < 2 * n; ++i) dst[i] = rng.nextFloat();
  return out;
}

}  // namespace

void bindWarp(py::module_& m) {
  m.def(
      "warp_names",
      [] {
        std::vector<std::string> names;
        for (int i = 0; i < kWarpTypeCount; ++i) names.push_back(warpTypeName(static_cast<WarpType>(i)));
        return names;
      },
      "The warp names warp(), pdf() and chi2_test() accept.");
  m.def("random_points", &randomPoints, py::arg("n"), py::arg("seed") = 1,
        "n uniform points in [0, 1)^2, float32 (n, 2): the PCG32 stream `penumbra warp --dump N --seed "
        "SEED` and chi2_test() draw, so warp(name, random_points(n, seed)) equals the CLI's dump.");
  m.def("warp", &warpArray, py::arg("name"), py::arg("u"), py::arg("param") = py::none(),
        py::arg("out") = py::none(),
        "Warp uniform points u, an (N, 2) array in [0, 1)^2, with warp `name` (see warp_names()). "
        "Returns float32 (N, 2) for planar warps, (N, 3) for warps onto the sphere. param: "
        "uniform-cone cos(theta_max) in [-1, 1) (default 0.5), beckmann alpha > 0 (default 0.2). out: "
        "a float32 array of the result's shape to write into (and return), as NumPy's out=.");
  m.def("pdf", &pdfArray, py::arg("name"), py::arg("v"), py::arg("param") = py::none(),
        py::arg("out") = py::none(),
        "The density of warp `name` at points v, (N, 2) or (N, 3) (z = 0 for planar warps): per unit "
        "area on the plane, per steradian on the sphere. Returns float32 (N,). out: as for warp().");

  py::class_<Chi2Report>(m, "Chi2Result", "The outcome of chi2_test(), as `penumbra warp` prints it.")
      .def_readonly("warp", &Chi2Report::warp)
      .def_readonly("param", &Chi2Report::param, "The warp's parameter (None for warps without one).")
      .def_readonly("p_value", &Chi2Report::pValue)
      .def_readonly("chi2", &Chi2Report::chi2)
      .def_readonly("dof", &Chi2Report::dof)
      .def_readonly("alpha", &Chi2Report::alpha, "The Sidak-corrected significance level of this test.")
      .def_readonly("accepted", &Chi2Report::accepted)
      .def_property_readonly(
          "verdict", [](const Chi2Report& r) { return std::string(r.accepted ? "accept" : "REJECT"); },
          "'accept' or 'REJECT', the CLI's word.")
      .def_readonly("message", &Chi2Report::message, "Why it was rejected ('' when accepted).")
      .def_readonly("pooled_cells", &Chi2Report::pooledCells)
      .def_readonly("observed", &Chi2Report::observed,
                    "Observed counts per cell (rows: y or w; columns: x or phi).")
      .def_readonly("expected", &Chi2Report::expected, "Expected counts per cell.")
      .def("__repr__", [](const Chi2Report& r) {
        return "<penumbra.Chi2Result " + r.warp + " chi2 " + std::to_string(r.chi2) + " dof " +
               std::to_string(r.dof) + " p " + std::to_string(r.pValue) + " " +
               (r.accepted ? "accept" : "REJECT") + ">";
      });
  m.def("chi2_test", &chi2, py::arg("name"), py::arg("samples") = 1'000'000, py::arg("seed") = 1,
        py::arg("res") = 51, py::arg("param") = py::none(), py::arg("test_count") = 1,
        "Pearson chi-square test of warp `name` against its pdf, exactly as `penumbra warp NAME "
        "--samples --seed --res` runs it (PCG32 samples, adaptive quadrature, low-expectation cells "
        "pooled). test_count > 1 applies the Sidak correction for that many tests. Returns Chi2Result.");

  m.def("sample_points", &samplePoints, py::arg("sampler"), py::arg("n"),
        py::arg("pixel") = std::pair<int, int>(0, 0), py::arg("dims") = std::pair<int, int>(0, 1),
        py::arg("seed") = 0, py::arg("sample_count") = py::none(),
        "The 2-D points a render sampler (see samplers()) gives one pixel over sample indices 0..n-1: "
        "dims (2k, 2k+1) is its k-th 2-D draw (k = 0: the pixel filter's). sample_count: the scene's "
        "sampleCount the sampler is built with (stratified: its strata; default n). Returns float32 "
        "(n, 2).");
}

}  // namespace penumbra::python
