// Convergence runs (the measurements `penumbra converge` writes to convergence.csv, as NumPy
// arrays) and the closed forms a render can be checked against without a reference file.
#include <pybind11/stl.h>

#include <optional>

#include "core/analysis/closed_forms.h"
#include "core/analysis/convergence.h"
#include "core/analysis/reference.h"
#include "core/math/error.h"
#include "core/sampling/sampler_table.h"
#include "python/bindings.h"

namespace penumbra::python {

namespace {

std::string joinNames(const py::object& names, const char* argument) {
  if (py::isinstance<py::str>(names)) return names.cast<std::string>();
  std::string out;
  try {
    for (auto n : names.cast<py::iterable>()) (out += out.empty() ? "" : ",") += n.cast<std::string>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(argument) + ": expected a str or a list of str");
  }
  return out;
}

// Files are checked as they are read (readReference); arrays here, before anything renders.
Reference chooseReference(const PyScene& s, const py::object& reference, int threads) {
  if (py::hasattr(reference, "mean") && py::hasattr(reference, "stderr")) {  // a RenderResult: with its noise
    Reference ref{arrayToImage(reference.attr("mean"), "reference.mean"),
                  arrayToImage(reference.attr("stderr"), "reference.stderr"), "render result"};
    checkReferenceValues(ref, "reference");
    return ref;
  }
  if (!reference.is_none() && !py::isinstance<py::str>(reference)) {
    Reference ref{arrayToImage(reference, "reference"), {}, "array"};
    checkReferenceValues(ref, "reference");
    return ref;
  }
  ReferenceRequest rq;
  if (!reference.is_none()) rq.path = reference.cast<std::string>();
  rq.threads = threads;
  py::gil_scoped_release release;
  return obtainReference(s.loaded, rq);
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
  d["label"] = r.strategy;
  d["final_image"] = imageToArray(Image(r.finalImage));
  return d;
}

py::dict converge(const PyScene& s, const py::object& strategies, const py::object& samplers,
                  std::optional<double> time, std::optional<int64_t> spp, const py::object& reference,
                  int64_t seed, std::optional<int> threads) {
  if (!time && !spp)
    throw py::value_error("time or spp: give one (seconds, or samples per pixel per strategy)");
  if (time && !(*time > 0)) throw py::value_error("time: expected seconds > 0");
  if (spp && (*spp < 1 || *spp > (int64_t(1) << 24))) throw py::value_error("spp: expected 1 .. 2^24");
  if (seed < 0) throw py::value_error("seed: expected an integer >= 0");
  if (uint64_t(seed) == kReferenceSeed) throw py::value_error("seed: must differ from the reference's seed");
  if (threads && (*threads < 1 || *threads > 1024)) throw py::value_error("threads: expected 1 .. 1024");
  std::vector<IntegratorDesc> list =
      parseStrategies(s.loaded.settings.integrator, joinNames(strategies, "strategies"));
  std::vector<SamplerKind> kinds;
  if (!samplers.is_none()) {
    std::string names = joinNames(samplers, "samplers");
    size_t at = 0;
    while (at <= names.size()) {
      size_t comma = names.find(',', at);
      std::string name = names.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
      SamplerKind k;
      if (!parseSamplerKind(name, k))
        throw py::value_error("samplers: unknown sampler '" + name +
                              "' (expected one of: " + acceptedSamplerNames() + ")");
      kinds.push_back(k);
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
  }
  Reference ref = chooseReference(s, reference, threads.value_or(0));
  if (ref.mean.width != s.loaded.settings.camera.width || ref.mean.height != s.loaded.settings.camera.height)
    throw py::value_error("reference: expected a " + std::to_string(s.loaded.settings.camera.height) + " x " +
                          std::to_string(s.loaded.settings.camera.width) + " x 3 image");
  std::vector<uint8_t> mask;
  ConvergenceOptions co;
  co.seconds = time.value_or(0.0);
  co.spp = spp ? uint32_t(*spp) : 0u;
  co.threads = threads.value_or(0);
  co.seed = uint64_t(seed);

  py::dict out;
  auto runAll = [&](const LoadedScene& scene, const char* sampler) {
    for (const IntegratorDesc& d : list) {
      ConvergenceRun run;
      {
        py::gil_scoped_release release;
        run = runConvergence(scene, d, ref, mask, co);
      }
      py::dict measured = runToDict(run);
      std::string name = strategyShortName(d);
      if (sampler) {
        measured["sampler"] = sampler;
        out[py::make_tuple(name, sampler)] = measured;
      } else {
        out[py::str(name)] = measured;
      }
    }
  };
  {
    py::gil_scoped_release release;
    mask = emitterMask(s.loaded);
  }
  if (kinds.empty()) {
    runAll(s.loaded, nullptr);
  } else {
    for (SamplerKind k : kinds) {
      LoadedScene withSampler = s.loaded;
      withSampler.settings.samplerKind = k;
      runAll(withSampler, samplerKindName(k));
    }
  }
  return out;
}

}  // namespace

void bindAnalysis(py::module_& m) {
  m.def("converge", &converge, py::arg("scene"), py::arg("strategies") = "all",
        py::arg("samplers") = py::none(), py::arg("time") = py::none(), py::arg("spp") = py::none(),
        py::arg("reference") = py::none(), py::arg("seed") = 0, py::arg("threads") = py::none(),
        "Error against time (time=seconds per strategy) or samples (spp=N) from a cold start, as "
        "`penumbra converge` measures it.\n\n"
        "strategies: 'all' or names (a str 'area,solid-angle' or a list) of the scene integrator's "
        "strategies (see strategies()). samplers: None (the scene's) or names (see samplers()): every "
        "strategy runs with each. reference: None (closed form for analytic scenes, else the cached or a "
        "freshly rendered one), a path to an EXR/PFM, 'closed-form', an H x W x 3 array, or a RenderResult "
        "(its stderr is then "
        "subtracted from the measured error as the CLI does for rendered references).\n\n"
        "Returns {short_name: measurements} (with samplers: {(short_name, sampler): measurements}); "
        "measurements is a dict of NumPy arrays, one entry per measured point, with the columns of "
        "convergence.csv: seconds, cpu_seconds, spp, samples, mse, rmse, rel_mse, mse_stderr, "
        "ref_variance, mse_nolight, rmse_nolight, rel_mse_nolight, mse_stderr_nolight; plus label and "
        "final_image (the mean at the end).");

  py::module_ cf = m.def_submodule("closed_form",
                                   "Closed-form truths (double precision, numerically careful evaluations).");
  cf.def("sphere_light_irradiance_factor",
         py::vectorize(static_cast<double (*)(double, double)>(&sphereLightIrradianceFactor)),
         py::arg("cos_theta"), py::arg("sin_alpha"),
         "I(theta, alpha): irradiance from a uniform sphere light of radiance Le with nothing in the way is "
         "E = Le * I. theta: angle between the normal and the direction to the centre; sin(alpha) = r / d. "
         "Vectorised over NumPy arrays.");
  cf.def(
      "sphere_light_irradiance_factor_at",
      [](std::array<double, 3> x, std::array<double, 3> n, std::array<double, 3> c, double r, bool twoSided) {
        return sphereLightIrradianceFactor(glm::dvec3(x[0], x[1], x[2]), glm::dvec3(n[0], n[1], n[2]),
                                           glm::dvec3(c[0], c[1], c[2]), r, twoSided);
      },
      py::arg("x"), py::arg("n"), py::arg("center"), py::arg("radius"), py::arg("two_sided") = false,
      "I for shading point x with normal n (need not be normalised) and a sphere light at center with "
      "radius; handles points on and inside the sphere.");
  cf.def("ao_plane_with_sphere", py::vectorize(static_cast<double (*)(double, double)>(&aoPlaneWithSphere)),
         py::arg("cos_theta"), py::arg("sin_alpha"),
         "Ambient occlusion of a point on an infinite plane with one sphere as the only occluder: 1 - I/pi.");
  cf.def("ao_plane_near_resting_sphere", py::vectorize(&aoPlaneNearRestingSphere), py::arg("rho"),
         py::arg("radius"),
         "AO of a plane point at horizontal distance rho from the contact point of a sphere of that "
         "radius resting on the plane: 1 - R^3 / (rho^2 + R^2)^(3/2).");
  cf.def(
      "ao_on_resting_convex_body", py::vectorize(&aoOnRestingConvexBody), py::arg("psi"),
      "AO on a convex body resting on an infinite plane, psi = angle of the normal from up: cos^2(psi/2).");
}

}  // namespace penumbra::python
