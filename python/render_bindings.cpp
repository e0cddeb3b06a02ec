// Scene.render: the engine runs with the GIL released while the calling thread polls for progress
// and for signals (Ctrl-C cancels the pass and raises KeyboardInterrupt); the result owns its arrays.
#include <pybind11/stl.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "core/image/image_io.h"
#include "core/math/argument_checks.h"
#include "core/render/engine.h"
#include "core/render/memory_estimate.h"
#include "python/arguments.h"
#include "python/bindings.h"
#include "python/interrupt.h"
#include "python/text.h"

namespace penumbra::python {

namespace {

struct RenderResult {
  py::array_t<float> mean, standardError;
  uint32_t spp = 0;
  double seconds = 0;
  uint64_t samples = 0, badSamples = 0;
  int threads = 0;
  ImageMetadata metadata;
};

void drawBar(uint32_t spp, double seconds, uint32_t target, double limitSeconds) {
  double fraction = target > 0 ? double(spp) / target : (limitSeconds > 0 ? seconds / limitSeconds : 0.0);
  fraction = std::min(fraction, 1.0);
  int filled = int(fraction * 30);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %u spp  %.1f s", filled,
               "==============================", 30 - filled, "", int(fraction * 100), spp, seconds);
  std::fflush(stderr);
}

RenderResult render(const PyScene& s, std::optional<int64_t> spp, std::optional<double> time, Seed seed,
                    std::optional<int64_t> threads, const py::object& progress) {
  if (spp) checkedCount(*spp, 1, kMaxRenderSpp, "spp");
  if (time) checkedSeconds(*time, "time");
  const int threadCount = checkedThreads(threads);
  bool bar = py::isinstance<py::bool_>(progress) && progress.cast<bool>();
  bool callback = !bar && !progress.is_none() && !py::isinstance<py::bool_>(progress);
  if (callback && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected a callable (spp, seconds), True or None");

  const std::string scenePath = s.loaded.path;  // what the GIL-released render reads is copied
  const CameraDesc& camera = s.loaded.settings.camera;
  checkRenderFitsInMemory(camera.width, camera.height, scenePath.empty() ? "render" : scenePath);
  RenderSettings settings = s.loaded.settings;
  settings.seed = seed.value;
  RenderLimits limits;
  limits.seconds = time.value_or(0.0);
  limits.targetSpp = spp ? uint32_t(*spp) : (time ? 0u : settings.sampleCount);
  // Stratified and zsobol take the run's count, as render --spp does (a warning when they cannot).
  const auto job = std::make_shared<const RenderJob>(s.loaded.scene, settings, limits);
  if (!job->samplerNote.empty())
    if (PyErr_WarnEx(PyExc_RuntimeWarning, job->samplerNote.c_str(), 1) != 0) throw py::error_already_set();

  Engine engine;
  {
    py::gil_scoped_release release;
    engine.start(job, limits, threadCount);
  }
  uint32_t reported = 0;
  bool done = false;
  while (!done) {
    {
      py::gil_scoped_release release;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      done = engine.progress().finished;
    }
    if (PyErr_CheckSignals() != 0) {  // Ctrl-C: abandon the pass, keep the process usable
      py::gil_scoped_release release;
      engine.cancel();
      done = true;
    }
    if (PyErr_Occurred()) throw py::error_already_set();
    RenderProgress p = engine.progress();
    if ((callback || bar) && (p.spp != reported || done)) {
      reported = p.spp;
      if (bar) {
        drawBar(p.spp, p.seconds, limits.targetSpp, limits.seconds);
      } else {
        try {
          progress(p.spp, p.seconds);
        } catch (...) {
          py::gil_scoped_release release;
          engine.cancel();
          throw;
        }
      }
    }
  }
  if (bar) std::fprintf(stderr, "\n");

  RenderResult r;
  Image mean, error;
  {
    py::gil_scoped_release release;
    engine.wait();
    RenderProgress p = engine.progress();
    r.spp = p.spp;
    r.seconds = p.seconds;
    r.samples = p.samples;
    r.badSamples = p.badSamples;
    r.threads = engine.threadCount();
    mean = engine.film().mean(p.spp);
    error = engine.film().standardError(p.spp);
  }
  for (auto& [k, v] : describeSettings(job->settings)) r.metadata.add(k, v);
  r.metadata.add("spp", std::to_string(r.spp));
  r.metadata.add("seconds", std::to_string(r.seconds));
  r.metadata.add("scene", scenePath.empty() ? "<built-in>" : scenePath);
  r.metadata.add("badSamples", std::to_string(r.badSamples));
  r.mean = imageToArray(std::move(mean));
  r.standardError = imageToArray(std::move(error));
  return r;
}

void save(const RenderResult& r, const py::object& path, const py::object& image) {
  std::string file = pathArgument(path, "path");
  Image pixels = arrayToImage(image.is_none() ? py::object(r.mean) : image, "image");
  py::gil_scoped_release release;
  writeImage(file, pixels, r.metadata);
}

}  // namespace

void bindRender(py::module_& m) {
  py::class_<RenderResult>(m, "RenderResult",
                           "What Scene.render() returns. The arrays are writeable NumPy arrays that "
                           "own their pixels (they outlive the scene).")
      .def_readonly("mean", &RenderResult::mean,
                    "The estimate: H x W x 3 float32, linear RGB, top row first.")
      .def_readonly("stderr", &RenderResult::standardError,
                    "Standard error of the mean per pixel and channel: H x W x 3 float32.")
      .def_readonly("spp", &RenderResult::spp, "Samples per pixel rendered (completed passes).")
      .def_readonly("seconds", &RenderResult::seconds, "Rendering time in seconds.")
      .def_readonly("samples", &RenderResult::samples, "Camera samples accumulated.")
      .def_readonly("bad_samples", &RenderResult::badSamples,
                    "NaN, Inf or negative camera samples (dropped and counted).")
      .def_readonly("threads", &RenderResult::threads, "Worker threads used.")
      .def_property_readonly(
          "metadata",
          [](const RenderResult& r) {
            py::dict d;
            for (auto& [k, v] : r.metadata.entries) d[text(k)] = text(v);
            return d;
          },
          "What save() stores in an EXR: the settings, spp, seconds, scene, badSamples.")
      .def("save", &save, py::arg("path"), py::arg("image") = py::none(),
           "Write the mean (or `image`, an H x W x 3 array) as the CLI does: .exr (float, with the "
           "metadata), .pfm (float) or .png (sRGB 8-bit), atomically. path: str, bytes or os.PathLike.")
      .def("__repr__", [](const RenderResult& r) {
        return "<penumbra.RenderResult " + std::to_string(r.spp) + " spp, " + std::to_string(r.seconds) +
               " s>";
      });

  auto scene = py::reinterpret_borrow<py::class_<PyScene>>(m.attr("Scene"));
  scene.def("render", &render, py::arg("spp") = py::none(), py::arg("time") = py::none(),
            py::arg("seed") = Seed{0}, py::arg("threads") = py::none(), py::arg("progress") = py::none(),
            "Render progressively and return a RenderResult.\n\n"
            "spp: samples per pixel (default: the scene's sampleCount unless time is given); time: seconds "
            "(whole passes); both: whichever comes first. The stratified and zsobol samplers take spp as "
            "their count, as `penumbra render --spp` does (a RuntimeWarning says what they do when they "
            "cannot). seed: the random seed (the same seed gives the "
            "same image for any thread count). threads: worker threads (default: all cores). progress: a "
            "callable(spp, seconds) called after each pass, or True for a bar on stderr.\n\n"
            "The GIL is released while rendering. Ctrl-C abandons the pass and raises KeyboardInterrupt. "
            "Raises ValueError for time NaN, infinite or <= 0 (as the CLI), MemoryError (the CLI's "
            "message) when the render's estimated memory (108 B/pixel) exceeds what the process can "
            "still get, and a worker's failure (MemoryError, RuntimeError) on this thread.");
}

}  // namespace penumbra::python
