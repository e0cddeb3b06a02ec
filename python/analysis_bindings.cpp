// Convergence runs (the measurements `penumbra converge` writes to convergence.csv, as NumPy
// arrays) and the closed forms a render can be checked against without a reference file.
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <optional>
#include <tuple>

#include "core/analysis/closed_forms.h"
#include "core/analysis/convergence.h"
#include "core/analysis/reference.h"
#include "core/math/argument_checks.h"
#include "core/math/error.h"
#include "core/render/memory_estimate.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"
#include "python/arguments.h"
#include "python/bindings.h"
#include "python/interrupt.h"
#include "python/text.h"

namespace penumbra::python {

namespace {

// A str of comma-separated names or an iterable of str, as one comma-separated str; ValueError for
// no names at all (an empty str or list would otherwise mean "the default"), saying what `argument`
// expects instead.
std::string joinNames(const py::object& names, const char* argument, const std::string& expected) {
  std::string out;
  if (py::isinstance<py::str>(names)) {
    out = textArgument(names, argument);
  } else {
    if (!py::isinstance<py::iterable>(names))
      throw py::type_error(std::string(argument) + ": expected a str or a list of str");
    for (auto n : names) {
      if (!py::isinstance<py::str>(n))
        throw py::type_error(std::string(argument) + ": expected a str or a list of str");
      (out += out.empty() ? "" : ",") += textArgument(n, argument);
    }
  }
  if (out.find_first_not_of(", ") == std::string::npos)
    throw py::value_error(std::string(argument) + ": expected " + expected + ", got none");
  return out;
}

// A core parse error as a ValueError naming the argument.
template <class F>
auto parsedArgument(const char* argument, F&& parse) {
  try {
    return parse();
  } catch (const Error& e) {
    throw py::value_error(std::string(argument) + ": " + quoted(e.what()));
  }
}

// The reference as converge() was given it: an image, or the request obtainReference() serves (the
// caller runs it interruptibly, without the GIL) for None and paths.
struct ReferenceChoice {
  std::optional<Reference> given;  // a RenderResult or an array
  ReferenceRequest request;        // otherwise
};

ReferenceChoice chooseReference(const py::object& reference, int threads) {
  ReferenceChoice c;
  if (py::hasattr(reference, "mean") && py::hasattr(reference, "stderr")) {  // a RenderResult: with its noise
    c.given = Reference{arrayToImage(reference.attr("mean"), "reference.mean"),
                        arrayToImage(reference.attr("stderr"), "reference.stderr"), "render result"};
    checkReferenceValues(*c.given, "reference");
  } else if (py::isinstance<py::str>(reference) || py::isinstance<py::bytes>(reference) ||
             py::hasattr(reference, "__fspath__")) {
    c.request.path = pathArgument(reference, "reference");
  } else if (!reference.is_none()) {
    c.given = Reference{arrayToImage(reference, "reference"), {}, "array"};
    checkReferenceValues(*c.given, "reference");
  }
  c.request.threads = threads;
  return c;
}

py::dict runToDict(const ConvergenceRun& r) {
  const size_t n = r.points.size();
  auto column = [&](auto field) {
    py::array_t<double> a{py::ssize_t(n)};
    double* d = a.mutable_data();
    for (size_t i = 0; i < n; ++i) d[i] = double(field(r.points[i]));
    return a;
  };
  py::dict d;
  d["seconds"] = column([](const ConvergencePoint& p) { return p.seconds; });
  d["cpu_seconds"] = column([](const ConvergencePoint& p) { return p.cpuSeconds; });
  py::array_t<int64_t> spp{py::ssize_t(n)}, samples{py::ssize_t(n)};
  for (size_t i = 0; i < n; ++i) {
    spp.mutable_data()[i] = r.points[i].spp;
    samples.mutable_data()[i] = int64_t(r.points[i].samples);
  }
  d["spp"] = spp;
  d["samples"] = samples;
  d["mse"] = column([](const ConvergencePoint& p) { return p.error.all.mse; });
  d["rmse"] = column([](const ConvergencePoint& p) { return p.error.all.rmse; });
  d["rel_mse"] = column([](const ConvergencePoint& p) { return p.error.all.relMse; });
  d["mse_stderr"] = column([](const ConvergencePoint& p) { return p.error.all.mseStdErr; });
  d["ref_variance"] = column([](const ConvergencePoint& p) { return p.error.all.refVariance; });
  d["mse_nolight"] = column([](const ConvergencePoint& p) { return p.error.noLight.mse; });
  d["rmse_nolight"] = column([](const ConvergencePoint& p) { return p.error.noLight.rmse; });
  d["rel_mse_nolight"] = column([](const ConvergencePoint& p) { return p.error.noLight.relMse; });
  d["mse_stderr_nolight"] = column([](const ConvergencePoint& p) { return p.error.noLight.mseStdErr; });
  d["label"] = text(r.strategy);
  d["final_image"] = imageToArray(Image(r.finalImage));
  return d;
}

py::dict converge(const PyScene& s, const py::object& strategies, const py::object& samplers,
                  const py::object& lightSelection, const py::object& lightMeasure,
                  const py::object& heuristic, std::optional<double> time, std::optional<int64_t> spp,
                  const py::object& reference, Seed seed, std::optional<int64_t> threads) {
  if (!time && !spp)
    throw py::value_error("time or spp: give one (seconds, or samples per pixel per strategy)");
  if (time) checkedSeconds(*time, "time");
  if (spp) checkedCount(*spp, 1, kMaxConvergeSpp, "spp");
  if (seed.value == kReferenceSeed) throw py::value_error("seed: must differ from the reference's seed");
  const int threadCount = checkedThreads(threads);
  const LoadedScene scene = s.loaded;  // what the GIL-released runs read
  StrategyLists lists{joinNames(strategies, "strategies", "'all' or at least one name"), "", "", ""};
  parsedArgument("strategies", [&] {
    return parseStrategyLists(scene.settings.integrator, {lists.strategies, "", "", ""});
  });
  // Each axis's list alone first, so an error names its own argument. 'all' is no axis's "every
  // value" (light_selection's all is one selection), so an empty list asks for names.
  const auto axis = [&](const py::object& names, const char* argument, std::string StrategyLists::*field,
                        const std::string& accepted) {
    if (names.is_none()) return;
    StrategyLists one{"all", "", "", ""};
    one.*field = lists.*field = joinNames(names, argument, "at least one of " + accepted);
    parsedArgument(argument, [&] { return parseStrategyLists(scene.settings.integrator, one); });
  };
  axis(lightSelection, "light_selection", &StrategyLists::lightSelections, acceptedLightSelections(false));
  axis(lightMeasure, "light_measure", &StrategyLists::lightMeasures, acceptedLightMeasures(false));
  axis(heuristic, "heuristic", &StrategyLists::heuristics, acceptedHeuristics(false));
  std::vector<IntegratorDesc> list = parsedArgument("strategies", [&] {
    ParsedStrategies parsed = parseStrategyLists(scene.settings.integrator, lists);
    for (const std::string& notice : parsed.notices)
      PyErr_WarnEx(PyExc_DeprecationWarning, notice.c_str(), 1);
    return parsed.strategies;
  });
  std::vector<SamplerKind> kinds;
  if (!samplers.is_none())
    kinds = parsedArgument("samplers", [&] {
      return parseSamplers(scene.settings.samplerKind,
                           joinNames(samplers, "samplers", "'all' or at least one name"));
    });
  const CameraDesc& camera = scene.settings.camera;
  checkRenderFitsInMemory(camera.width, camera.height, scene.path.empty() ? "converge" : scene.path);
  ReferenceChoice choice = chooseReference(reference, threadCount);
  Reference ref = choice.given ? std::move(*choice.given) : runInterruptibly([&](CancelFlag cancel) {
    ReferenceRequest rq = choice.request;
    rq.cancel = cancel;
    return obtainReference(scene, rq);
  });
  if (ref.mean.width != camera.width || ref.mean.height != camera.height)
    throw py::value_error("reference: expected a " + std::to_string(camera.height) + " x " +
                          std::to_string(camera.width) + " x 3 image");
  std::vector<uint8_t> mask = runInterruptibly([&](CancelFlag cancel) { return emitterMask(scene, cancel); });
  ConvergenceOptions co;
  co.seconds = time.value_or(0.0);
  co.spp = spp ? uint32_t(*spp) : 0u;
  co.threads = threadCount;
  co.seed = seed.value;

  py::dict out;
  auto runAll = [&](const LoadedScene& withSampler, const char* sampler) {
    for (const IntegratorDesc& d : list) {
      ConvergenceRun run = runInterruptibly([&](CancelFlag cancel) {
        ConvergenceOptions o = co;
        o.cancel = cancel;
        return runConvergence(withSampler, d, ref, mask, o);
      });
      py::dict measured = runToDict(run);
      py::str name = text(strategyShortName(d));
      if (sampler) {
        measured["sampler"] = text(sampler);
        out[py::make_tuple(name, text(sampler))] = measured;
      } else {
        out[name] = measured;
      }
    }
  };
  if (samplers.is_none()) {
    runAll(scene, nullptr);
  } else {
    for (SamplerKind k : kinds) {
      LoadedScene withSampler = scene;
      withSampler.settings.samplerKind = k;
      runAll(withSampler, samplerKindName(k));
    }
  }
  return out;
}

// Closed-form arguments: finite (NaN would come back as a number) and within the form's domain, up
// to rounding.
double checkedArgument(double value, const char* argument, double lo, double hi) {
  constexpr double kSlack = 1e-9;  // a cosine from a dot product may exceed 1 by a few ulps
  if (!std::isfinite(value))
    throw py::value_error(std::string(argument) + ": expected a finite number, got " + std::to_string(value));
  if (value < lo - kSlack || value > hi + kSlack)
    throw py::value_error(std::string(argument) + ": expected a number in [" + std::to_string(lo) + ", " +
                          (std::isinf(hi) ? std::string("inf") : std::to_string(hi)) + "], got " +
                          std::to_string(value));
  return value;
}

constexpr double kInf = HUGE_VAL;

// f over the arguments broadcast as NumPy broadcasts a ufunc's (ValueError when their shapes do not
// broadcast, TypeError when they are not numbers): a float for scalars, else a float64 array.
template <size_t N, class F>
py::object broadcast(F f, const std::array<py::object, N>& args) {
  py::module_ np = py::module_::import("numpy");
  py::list arrays;
  bool scalars = true;
  for (const py::object& a : args) {
    py::object array;
    try {
      array = np.attr("asarray")(a, py::arg("dtype") = "float64");
    } catch (py::error_already_set& e) {
      if (e.matches(PyExc_MemoryError)) throw;
      throw py::type_error("expected numbers or arrays of numbers, got " +
                           py::str(py::type::handle_of(a).attr("__name__")).cast<std::string>());
    }
    scalars = scalars && array.attr("ndim").cast<int>() == 0;
    arrays.append(array);
  }
  py::list broadcast = np.attr("broadcast_arrays")(*arrays);  // ValueError for shapes that do not fit
  std::array<py::array_t<double, py::array::c_style | py::array::forcecast>, N> in;
  for (size_t i = 0; i < N; ++i) in[i] = np.attr("ascontiguousarray")(broadcast[i]);
  py::array_t<double> out(in[0].request().shape);
  double* dst = out.mutable_data();
  for (py::ssize_t k = 0; k < out.size(); ++k)
    dst[k] = std::apply([&](const auto&... a) { return f(a.data()[k]...); }, in);
  if (scalars) return py::float_(dst[0]);
  return out;
}

}  // namespace

void bindAnalysis(py::module_& m) {
  m.def("converge", &converge, py::arg("scene"), py::arg("strategies") = "all",
        py::arg("samplers") = py::none(), py::arg("light_selection") = py::none(),
        py::arg("light_measure") = py::none(), py::arg("heuristic") = py::none(),
        py::arg("time") = py::none(), py::arg("spp") = py::none(), py::arg("reference") = py::none(),
        py::arg("seed") = Seed{0}, py::arg("threads") = py::none(),
        "Error against time (time=seconds per strategy) or samples (spp=N) from a cold start, as "
        "`penumbra converge` measures it.\n\n"
        "strategies: 'all' or measures (a str 'area,solid-angle,mis' or a list; see axes()) of the "
        "scene integrator; an empty str or list is a ValueError. light_selection, light_measure, "
        "heuristic: None (the scene's) or names crossed with each light measure (light_selection) "
        "and with mis (light_measure, heuristic), as --light-selection, --light-measure, --heuristic. "
        "An old flattened name ('solid-angle-bvh') still works with a DeprecationWarning. samplers: "
        "None (the scene's), 'all' (every row of samplers(), as --samplers all) or names: every "
        "strategy runs with each. reference: None (closed form for analytic scenes, else the cached or a "
        "freshly rendered "
        "one), a path (str, bytes, os.PathLike) to an EXR/PFM, 'closed-form', an H x W x 3 array, or a "
        "RenderResult (its stderr is then subtracted from the measured error as the CLI does for "
        "rendered references). time: a finite number of seconds > 0 (as --time).\n\n"
        "Returns {short_name: measurements} (with samplers: {(short_name, sampler): measurements}); "
        "measurements is a dict of NumPy arrays, one entry per measured point, with the columns of "
        "convergence.csv: seconds, cpu_seconds, spp, samples, mse, rmse, rel_mse, mse_stderr, "
        "ref_variance, mse_nolight, rmse_nolight, rel_mse_nolight, mse_stderr_nolight; plus label and "
        "final_image (the mean at the end).\n\n"
        "The GIL is released while measuring; Ctrl-C raises KeyboardInterrupt within a fraction of a "
        "second, also while a reference is rendered (no cache file is then written).");

  py::module_ cf = m.def_submodule("closed_form",
                                   "Closed-form truths (double precision, numerically careful evaluations). "
                                   "Arguments must be finite and within each form's domain (ValueError).");
  cf.def(
      "sphere_light_irradiance_factor",
      [](py::object cosTheta, py::object sinAlpha) {
        return broadcast<2>(
            [](double c, double s) {
              return sphereLightIrradianceFactor(checkedArgument(c, "cos_theta", -1, 1),
                                                 checkedArgument(s, "sin_alpha", 0, 1));
            },
            {cosTheta, sinAlpha});
      },
      py::arg("cos_theta"), py::arg("sin_alpha"),
      "I(theta, alpha): irradiance from a uniform sphere light of radiance Le with nothing in the way is "
      "E = Le * I. theta: angle between the normal and the direction to the centre (cos_theta in "
      "[-1, 1]); sin(alpha) = r / d in [0, 1]. Vectorised over NumPy arrays (broadcast as a ufunc).");
  cf.def(
      "sphere_light_irradiance_factor_at",
      [](std::array<double, 3> x, std::array<double, 3> n, std::array<double, 3> c, double r, bool twoSided) {
        for (int i = 0; i < 3; ++i) {
          checkedArgument(x[i], "x", -kInf, kInf);
          checkedArgument(n[i], "n", -kInf, kInf);
          checkedArgument(c[i], "center", -kInf, kInf);
        }
        if (n[0] == 0 && n[1] == 0 && n[2] == 0) throw py::value_error("n: expected a non-zero normal");
        if (!(checkedArgument(r, "radius", 0, kInf) > 0))
          throw py::value_error("radius: expected a number > 0");
        return sphereLightIrradianceFactor(glm::dvec3(x[0], x[1], x[2]), glm::dvec3(n[0], n[1], n[2]),
                                           glm::dvec3(c[0], c[1], c[2]), r, twoSided);
      },
      py::arg("x"), py::arg("n"), py::arg("center"), py::arg("radius"), py::arg("two_sided") = false,
      "I for shading point x with normal n (non-zero; need not be normalised) and a sphere light at "
      "center with radius > 0; handles points on and inside the sphere.");
  cf.def(
      "ao_plane_with_sphere",
      [](py::object cosTheta, py::object sinAlpha) {
        return broadcast<2>(
            [](double c, double s) {
              return aoPlaneWithSphere(checkedArgument(c, "cos_theta", -1, 1),
                                       checkedArgument(s, "sin_alpha", 0, 1));
            },
            {cosTheta, sinAlpha});
      },
      py::arg("cos_theta"), py::arg("sin_alpha"),
      "Ambient occlusion of a point on an infinite plane with one sphere as the only occluder: 1 - I/pi.");
  cf.def(
      "ao_plane_near_resting_sphere",
      [](py::object rho, py::object radius) {
        return broadcast<2>(
            [](double p, double r) {
              checkedArgument(p, "rho", 0, kInf);
              if (!(checkedArgument(r, "radius", 0, kInf) > 0))
                throw py::value_error("radius: expected a number > 0");
              return aoPlaneNearRestingSphere(p, r);
            },
            {rho, radius});
      },
      py::arg("rho"), py::arg("radius"),
      "AO of a plane point at horizontal distance rho >= 0 from the contact point of a sphere of that "
      "radius (> 0) resting on the plane: 1 - R^3 / (rho^2 + R^2)^(3/2).");
  cf.def(
      "ao_on_resting_convex_body",
      [](py::object psi) {
        return broadcast<1>(
            [](double p) { return aoOnRestingConvexBody(checkedArgument(p, "psi", -kInf, kInf)); }, {psi});
      },
      py::arg("psi"),
      "AO on a convex body resting on an infinite plane, psi = angle of the normal from up: cos^2(psi/2).");
}

}  // namespace penumbra::python
