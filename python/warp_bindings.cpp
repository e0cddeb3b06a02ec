// The sample warps and their pdfs over NumPy arrays (C++ loops over chunks, GIL released, signals
// checked between chunks), the chi-square test `penumbra warp` runs, and the samplers' 2-D point sets.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>

#include "core/materials/bsdf_warp.h"
#include "core/math/argument_checks.h"
#include "core/math/error.h"
#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/sampling/warp_params.h"
#include "python/arguments.h"
#include "python/bindings.h"
#include "python/interrupt.h"
#include "python/text.h"

namespace penumbra::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Points per chunk of the warp loops: about a millisecond, so Ctrl-C acts at once.
constexpr int64_t kPointsPerChunk = 1 << 16;
// The largest k of sample_points' dims (2k, 2k + 1): each point draws k + 1 pairs.
constexpr int kMaxSampleDraw = 4095;

struct WarpChoice {
  WarpType type;
  float param;
};

// Name and parameter as the CLI checks them; errors are ValueErrors naming the argument.
WarpChoice choose(const std::string& name, const std::optional<double>& param) {
  checkNoNul(name, "name");
  WarpType type;
  if (!parseWarpType(name, type))
    throw py::value_error("name: unknown warp '" + quoted(name) + "' (expected one of: " + warpTypeList() +
                          ")");
  try {
    return {type, checkedWarpParam(type, param.has_value(), param.value_or(0.0), "param")};
  } catch (const Error& e) {
    throw py::value_error(e.what());
  }
}

FloatArray points(const py::handle& input, const char* argument, py::ssize_t minColumns,
                  py::ssize_t maxColumns) {
  const std::string expected = std::string(argument) + ": expected an (N, 2) or (N, 3) array of numbers";
  if (input.is_none()) throw py::type_error(expected);
  py::object converted;  // numpy's own conversion: its MemoryError stays one
  try {
    converted = py::module_::import("numpy").attr("ascontiguousarray")(input, py::arg("dtype") = "float32");
  } catch (py::error_already_set& e) {
    if (e.matches(PyExc_MemoryError)) throw;
    throw py::type_error(expected);
  }
  FloatArray a = FloatArray::ensure(converted);  // already float32 and contiguous: no copy
  if (a.ndim() != 2 || a.shape(1) < minColumns || a.shape(1) > maxColumns)
    throw py::value_error(std::string(argument) + ": expected shape (N, " + std::to_string(minColumns) +
                          (maxColumns > minColumns ? " or " + std::to_string(maxColumns) : std::string()) +
                          "), got " + py::str(converted.attr("shape")).cast<std::string>());
  return a;
}

// The output array: a new one, or `out` (NumPy's convention: a float32 C-contiguous array of the
// result's shape, reused so that repeated calls do not fault in fresh pages every time).
py::array_t<float> outputArray(const py::object& out, std::vector<py::ssize_t> shape, const char* function) {
  if (out.is_none()) {
    uint64_t bytes = sizeof(float);
    for (py::ssize_t n : shape) bytes *= uint64_t(n);
    checkAllocation(bytes, std::string(function) + ": the float32 result");
    return py::array_t<float>(shape);
  }
  auto a = py::array_t<float, py::array::c_style>::ensure(out);
  if (!a || !py::isinstance<py::array_t<float>>(out) || !a.writeable() ||
      !(py::cast<py::array>(out).flags() & py::array::c_style))
    throw py::type_error("out: expected a writeable C-contiguous float32 array");
  bool same = a.ndim() == py::ssize_t(shape.size());
  for (size_t i = 0; same && i < shape.size(); ++i) same = a.shape(i) == shape[i];
  if (!same) throw py::value_error("out: expected the result's shape");
  return py::reinterpret_borrow<py::array_t<float>>(out);
}

// Whether two arrays' memory overlaps (numpy.may_share_memory: their byte extents intersect).
bool overlaps(const py::array& a, const py::array& b) {
  const auto* a0 = static_cast<const char*>(a.data());
  const auto* b0 = static_cast<const char*>(b.data());
  return a.nbytes() > 0 && b.nbytes() > 0 && a0 < b0 + b.nbytes() && b0 < a0 + a.nbytes();
}

// The input as the loops read it: a copy when the output overlaps it (as NumPy's ufuncs do), so
// writing a point never changes an input point not yet read.
FloatArray separateFrom(FloatArray in, const py::array& out) {
  if (!overlaps(in, out)) return in;
  return FloatArray::ensure(py::array(in).attr("copy")());
}

// One loop per warp, its function called directly (the type is resolved once, not per point).
// A point with a NaN or infinite coordinate gives NaN (the warps assume [0, 1)^2).
template <typename F>
void warpLoop(F f, const float* src, float* dst, py::ssize_t n, py::ssize_t dims) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Vec2 u(src[2 * i], src[2 * i + 1]);
    const Vec3 v = std::isfinite(u.x) && std::isfinite(u.y) ? f(u) : Vec3(kNaN);
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
  const py::ssize_t dims = warpIsSpherical(w.type) ? 3 : 2;
  py::array_t<float> result = outputArray(out, {n, dims}, "warp");
  in = separateFrom(in, result);
  const float* src = in.data();
  float* dst = result.mutable_data();
  forEachChunk(n, kPointsPerChunk, [&](int64_t begin, int64_t end) {
    warpAll(w, src + 2 * begin, dst + dims * begin, end - begin);
  });
  return result;
}

py::array_t<float> pdfArray(const std::string& name, const py::handle& v, std::optional<double> param,
                            const py::object& out) {
  WarpChoice w = choose(name, param);
  FloatArray in = points(v, "v", 2, 3);
  const py::ssize_t n = in.shape(0), cols = in.shape(1);
  py::array_t<float> result = outputArray(out, {n}, "pdf");
  in = separateFrom(in, result);
  const float* src = in.data();
  float* dst = result.mutable_data();
  forEachChunk(n, kPointsPerChunk, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const float* p = src + cols * i;
      const Vec3 v(p[0], p[1], cols == 3 ? p[2] : 0.f);
      dst[i] = std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)
                   ? Warp::pdf(w.type, v, w.param)
                   : std::numeric_limits<float>::quiet_NaN();
    }
  });
  return result;
}

struct Chi2Report {
  std::string warp;
  std::optional<float> param;
  double pValue = 0, chi2 = 0, alpha = 0;
  double rejected = 0, expectedRejected = 0;  // a BSDF's failed draws (0 for the warps)
  int dof = 0, pooledCells = 0;
  bool accepted = false, inconclusive = false;
  std::string verdict, message;
  py::array_t<double> observed, expected;
};

Chi2Report reportOf(const Chi2Result& r) {
  Chi2Report out;
  out.pValue = r.pValue;
  out.chi2 = r.chi2;
  out.dof = r.dof;
  out.alpha = r.alphaEffective;
  out.accepted = r.accepted;
  out.inconclusive = r.inconclusive;
  out.verdict = chi2Verdict(r);
  out.message = r.message;
  out.pooledCells = r.pooledCells;
  out.observed = py::array_t<double>({py::ssize_t(r.resY), py::ssize_t(r.resX)}, r.observed.data());
  out.expected = py::array_t<double>({py::ssize_t(r.resY), py::ssize_t(r.resX)}, r.expected.data());
  out.rejected = r.observedRejected;
  out.expectedRejected = r.expectedRejected;
  return out;
}

// The test as `penumbra warp` runs it, with the module's argument checks; Ctrl-C cancels it.
Chi2Result runChi2(const Chi2Domain& domain, const SampleFunction& sample, const PdfFunction& pdf,
                   int64_t samples, Seed seed, int64_t res, int64_t testCount, bool rejectedDraws) {
  checkedCount(samples, kMinChi2Samples, kMaxChi2Samples, "samples");
  checkedCount(res, kMinChi2Resolution, kMaxChi2Resolution, "res");
  checkedCount(testCount, 1, std::numeric_limits<int>::max(), "test_count");
  Chi2Options opt;
  opt.sampleCount = uint64_t(samples);
  opt.resolution = int(res);
  opt.seed = seed.value;
  opt.testCount = int(testCount);
  opt.rejectedDraws = rejectedDraws;
  return runInterruptibly([&](CancelFlag cancel) {
    Chi2Options o = opt;
    o.cancel = cancel;
    return chi2Test(domain, sample, pdf, o);
  });
}

Chi2Report chi2(const std::string& name, int64_t samples, Seed seed, int64_t res, std::optional<double> param,
                int64_t testCount) {
  WarpChoice w = choose(name, param);
  Chi2Result r = runChi2(chi2DomainFor(w.type, w.param), warpSampleFunction(w.type, w.param),
                         warpPdfFunction(w.type, w.param), samples, seed, res, testCount, false);
  Chi2Report out = reportOf(r);
  out.warp = warpTypeName(w.type);
  if (warpHasParameter(w.type)) out.param = w.param;
  return out;
}

// ---- a BSDF's sampling at a fixed incident angle (core/materials/bsdf_warp.h) ----

// The BSDF as `penumbra warp microfacet|roughconductor` takes it; errors are ValueErrors naming the
// Python argument.
BsdfWarp chooseBsdf(const std::string& name, double alpha, double incident, double kd,
                    const std::string& distribution, double intIor, double extIor) {
  checkNoNul(name, "name");
  checkNoNul(distribution, "distribution");
  if (!isBsdfWarpName(name))
    throw py::value_error("name: unknown BSDF '" + quoted(name) +
                          "' (expected one of: " + bsdfWarpTypeList() + ")");
  const BsdfWarpInputs in{.type = name,
                          .distribution = distribution,
                          .alpha = alpha,
                          .kd = kd,
                          .incidentDegrees = incident,
                          .intIOR = intIor,
                          .extIOR = extIor};
  const BsdfInputNames names{.alpha = "alpha",
                             .incident = "incident",
                             .kd = "kd",
                             .intIOR = "int_ior",
                             .extIOR = "ext_ior",
                             .distribution = "distribution"};
  try {
    return checkedBsdfWarp(in, names);
  } catch (const Error& e) {
    throw py::value_error(e.what());
  }
}

py::array_t<float> bsdfSampleArray(const std::string& name, const py::handle& u, double alpha,
                                   double incident, double kd, const std::string& distribution, double intIor,
                                   double extIor, const py::object& out) {
  const BsdfWarp w = chooseBsdf(name, alpha, incident, kd, distribution, intIor, extIor);
  FloatArray in = points(u, "u", 2, 2);
  const py::ssize_t n = in.shape(0);
  py::array_t<float> result = outputArray(out, {n, 3}, "bsdf_sample");
  in = separateFrom(in, result);
  const float* src = in.data();
  float* dst = result.mutable_data();
  forEachChunk(n, kPointsPerChunk, [&](int64_t begin, int64_t end) {
    warpLoop([&](Vec2 p) { return w.sample(p); }, src + 2 * begin, dst + 3 * begin, end - begin, 3);
  });
  return result;
}

py::array_t<float> bsdfPdfArray(const std::string& name, const py::handle& v, double alpha, double incident,
                                double kd, const std::string& distribution, double intIor, double extIor,
                                const py::object& out) {
  const BsdfWarp w = chooseBsdf(name, alpha, incident, kd, distribution, intIor, extIor);
  FloatArray in = points(v, "v", 3, 3);
  const py::ssize_t n = in.shape(0);
  py::array_t<float> result = outputArray(out, {n}, "bsdf_pdf");
  in = separateFrom(in, result);
  const float* src = in.data();
  float* dst = result.mutable_data();
  forEachChunk(n, kPointsPerChunk, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Vec3 d(src[3 * i], src[3 * i + 1], src[3 * i + 2]);
      dst[i] = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)
                   ? w.pdf(d)
                   : std::numeric_limits<float>::quiet_NaN();
    }
  });
  return result;
}

Chi2Report bsdfChi2(const std::string& name, int64_t samples, Seed seed, int64_t res, double alpha,
                    double incident, double kd, const std::string& distribution, double intIor, double extIor,
                    int64_t testCount) {
  const BsdfWarp w = chooseBsdf(name, alpha, incident, kd, distribution, intIor, extIor);
  Chi2Result r = runChi2(bsdfChi2Domain(), bsdfSampleFunction(w), bsdfPdfFunction(w), samples, seed, res,
                         testCount, true);
  Chi2Report report = reportOf(r);
  report.warp = describeBsdfWarp(w);
  report.param = w.bsdf.alpha;
  return report;
}

py::array_t<float> samplePoints(const std::string& samplerName, int64_t n, std::pair<int64_t, int64_t> pixel,
                                std::pair<int64_t, int64_t> dims, Seed seed,
                                std::optional<int64_t> sampleCount) {
  checkNoNul(samplerName, "sampler");
  SamplerKind kind;
  if (!parseSamplerKind(samplerName, kind))
    throw py::value_error("sampler: unknown sampler '" + quoted(samplerName) +
                          "' (expected one of: " + acceptedSamplerNames() + ")");
  checkedCount(n, 1, int64_t(1) << 30, "n");
  if (dims.first < 0 || dims.first % 2 != 0 || dims.second != dims.first + 1 ||
      dims.first / 2 > kMaxSampleDraw)
    throw py::value_error("dims: expected a pair (2k, 2k + 1) with 0 <= k <= " +
                          std::to_string(kMaxSampleDraw) + ", the k-th 2-D draw of each pixel sample");
  if (pixel.first < 0 || pixel.second < 0 || pixel.first > std::numeric_limits<int>::max() ||
      pixel.second > std::numeric_limits<int>::max())
    throw py::value_error("pixel: expected (x, y) with 0 <= x, y <= 2^31 - 1");
  const int64_t count = checkedCount(sampleCount.value_or(n), 1, int64_t(1) << 30, "sample_count");
  py::array_t<float> out = outputArray(py::none(), {py::ssize_t(n), py::ssize_t(2)}, "sample_points");
  float* dst = out.mutable_data();
  Sampler sampler(kind, uint32_t(count), seed.value);
  const int skip = int(dims.first / 2);
  const IVec2 p(int(pixel.first), int(pixel.second));
  forEachChunk(n, std::max<int64_t>(1, kPointsPerChunk / (skip + 1)), [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      sampler.startPixelSample(p, uint32_t(i));
      for (int k = 0; k < skip; ++k) sampler.next2D();
      Vec2 v = sampler.next2D();
      dst[2 * i] = v.x;
      dst[2 * i + 1] = v.y;
    }
  });
  return out;
}

// The uniform stream `penumbra warp --dump` and the chi-square test draw: PCG32(mix64(seed), seed).
py::array_t<float> randomPoints(int64_t n, Seed seed, const py::object& out) {
  checkedCount(n, 0, int64_t(1) << 40, "n");
  py::array_t<float> result = outputArray(out, {py::ssize_t(n), py::ssize_t(2)}, "random_points");
  float* dst = result.mutable_data();
  Rng rng(mix64(seed.value), seed.value);
  forEachChunk(n, kPointsPerChunk, [&](int64_t begin, int64_t end) {
    for (int64_t i = 2 * begin; i < 2 * end; ++i) dst[i] = rng.nextFloat();
  });
  return result;
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
  m.def("random_points", &randomPoints, py::arg("n"), py::arg("seed") = Seed{1}, py::arg("out") = py::none(),
        "n uniform points in [0, 1)^2, float32 (n, 2): the PCG32 stream `penumbra warp --dump N --seed "
        "SEED` and chi2_test() draw, so warp(name, random_points(n, seed)) equals the CLI's dump. out: "
        "as for warp().");
  m.def("warp", &warpArray, py::arg("name"), py::arg("u"), py::arg("param") = py::none(),
        py::arg("out") = py::none(),
        "Warp uniform points u, an (N, 2) array in [0, 1)^2, with warp `name` (see warp_names()). "
        "Returns float32 (N, 2) for planar warps, (N, 3) for warps onto the sphere. param: "
        "uniform-cone cos(theta_max) in [-1, 1) (default 0.5), beckmann alpha > 0 (default 0.2). out: "
        "a float32 array of the result's shape to write into (and return), as NumPy's out=; it may "
        "overlap u (u is then copied first, as NumPy does). Points with a NaN or infinite coordinate "
        "give NaN. Ctrl-C "
        "raises KeyboardInterrupt within milliseconds (out then holds the points done so far).");
  m.def("pdf", &pdfArray, py::arg("name"), py::arg("v"), py::arg("param") = py::none(),
        py::arg("out") = py::none(),
        "The density of warp `name` at points v, (N, 2) or (N, 3) (z = 0 for planar warps): per unit "
        "area on the plane, per steradian on the sphere. Returns float32 (N,); points with a NaN or "
        "infinite coordinate give NaN. out: as for warp().");

  py::class_<Chi2Report>(m, "Chi2Result", "The outcome of chi2_test(), as `penumbra warp` prints it.")
      .def_readonly("warp", &Chi2Report::warp)
      .def_readonly("param", &Chi2Report::param, "The warp's parameter (None for warps without one).")
      .def_readonly("p_value", &Chi2Report::pValue)
      .def_readonly("chi2", &Chi2Report::chi2)
      .def_readonly("dof", &Chi2Report::dof)
      .def_readonly("alpha", &Chi2Report::alpha, "The Sidak-corrected significance level of this test.")
      .def_readonly("accepted", &Chi2Report::accepted)
      .def_readonly("inconclusive", &Chi2Report::inconclusive,
                    "Too few samples to test: pooling the cells that expect fewer than 5 samples left "
                    "fewer than two cells (dof 0). accepted is then False, p_value NaN.")
      .def_readonly("verdict", &Chi2Report::verdict, "'accept', 'REJECT' or 'inconclusive', the CLI's word.")
      .def_property_readonly(
          "message", [](const Chi2Report& r) { return text(r.message); },
          "Why it was rejected or is inconclusive ('' when accepted).")
      .def_readonly("pooled_cells", &Chi2Report::pooledCells)
      .def_readonly(
          "rejected", &Chi2Report::rejected,
          "bsdf_chi2_test(): the draws the BSDF rejected (reflected below the surface); 0 for warps.")
      .def_readonly("expected_rejected", &Chi2Report::expectedRejected,
                    "bsdf_chi2_test(): the rejected draws the pdf's missing mass expects; 0 for warps.")
      .def_readonly("observed", &Chi2Report::observed,
                    "Observed counts per cell (rows: y or w; columns: x or phi).")
      .def_readonly("expected", &Chi2Report::expected, "Expected counts per cell.")
      .def("__repr__", [](const Chi2Report& r) {
        return "<penumbra.Chi2Result " + r.warp + " chi2 " + std::to_string(r.chi2) + " dof " +
               std::to_string(r.dof) + " p " + std::to_string(r.pValue) + " " + r.verdict + ">";
      });
  m.def("chi2_test", &chi2, py::arg("name"), py::arg("samples") = 1'000'000, py::arg("seed") = Seed{1},
        py::arg("res") = 51, py::arg("param") = py::none(), py::arg("test_count") = 1,
        "Pearson chi-square test of warp `name` against its pdf, exactly as `penumbra warp NAME "
        "--samples --seed --res` runs it (PCG32 samples, adaptive quadrature, low-expectation cells "
        "pooled). samples: 100 .. 1e9; res: 2 .. 1000. test_count > 1 applies the Sidak correction for "
        "that many tests. Returns Chi2Result: verdict 'accept', 'REJECT', or 'inconclusive' when too "
        "few samples leave no two cells to compare. Ctrl-C raises KeyboardInterrupt at once.");

  m.def(
      "bsdf_names",
      [] {
        return std::vector<std::string>{"microfacet", "roughconductor"};
      },
      "The BSDFs bsdf_sample(), bsdf_pdf() and bsdf_chi2_test() accept.");
  m.def("bsdf_sample", &bsdfSampleArray, py::arg("name"), py::arg("u"), py::arg("alpha") = 0.1,
        py::arg("incident") = 30.0, py::arg("kd") = 0.5, py::arg("distribution") = "beckmann",
        py::arg("int_ior") = 1.5046, py::arg("ext_ior") = 1.000277, py::arg("out") = py::none(),
        "Directions wi (N, 3) float32 a BSDF's sampling draws from uniform points u (N, 2), with wo = "
        "(sin, 0, cos) of `incident` degrees in the local frame (normal +z); (0, 0, 0) where the BSDF "
        "rejects the draw (a direction below the surface), as `penumbra warp NAME --dump` prints. name: "
        "microfacet (alpha, kd, int_ior, ext_ior) or roughconductor (alpha, distribution beckmann|ggx). "
        "out: as for warp().");
  m.def("bsdf_pdf", &bsdfPdfArray, py::arg("name"), py::arg("v"), py::arg("alpha") = 0.1,
        py::arg("incident") = 30.0, py::arg("kd") = 0.5, py::arg("distribution") = "beckmann",
        py::arg("int_ior") = 1.5046, py::arg("ext_ior") = 1.000277, py::arg("out") = py::none(),
        "The solid-angle density with which bsdf_sample() draws each direction of v (N, 3); it integrates "
        "to 1 minus the rejected mass. Returns float32 (N,).");
  m.def("bsdf_chi2_test", &bsdfChi2, py::arg("name"), py::arg("samples") = 1'000'000,
        py::arg("seed") = Seed{1}, py::arg("res") = 51, py::arg("alpha") = 0.1, py::arg("incident") = 30.0,
        py::arg("kd") = 0.5, py::arg("distribution") = "beckmann", py::arg("int_ior") = 1.5046,
        py::arg("ext_ior") = 1.000277, py::arg("test_count") = 1,
        "Pearson chi-square test of a BSDF's sampling against its pdf, exactly as `penumbra warp NAME` "
        "runs it: the upper hemisphere in (phi, cos theta), the rejected draws as a cell expecting the "
        "mass the pdf misses. Returns Chi2Result (its rejected and expected_rejected fields filled).");
  m.def("sample_points", &samplePoints, py::arg("sampler"), py::arg("n"),
        py::arg("pixel") = std::pair<int64_t, int64_t>(0, 0),
        py::arg("dims") = std::pair<int64_t, int64_t>(0, 1), py::arg("seed") = Seed{0},
        py::arg("sample_count") = py::none(),
        "The 2-D points a render sampler (see samplers()) gives one pixel over sample indices 0..n-1: "
        "dims (2k, 2k+1) is its k-th 2-D draw (k = 0: the pixel filter's). sample_count: the scene's "
        "sampleCount the sampler is built with (stratified: its strata; default n). Returns float32 "
        "(n, 2). n: 1 .. 2^30; k: 0 .. 4095.");
}

}  // namespace penumbra::python
