// Scenes: load from a file or a string with overrides, read and change settings, list the
// strategy axes and the samplers of their tables.
#include <pybind11/stl.h>

#include <filesystem>

#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/scene_writer.h"
#include "core/scene/xml_parser.h"
#include "python/bindings.h"
#include "python/text.h"

namespace penumbra::python {

namespace {

py::dict axisRow(const Spellings& spellings, std::string_view description) {
  py::dict d;
  d["name"] = text(std::string(spellings.canonical()));
  py::list aliases;
  for (std::string_view a : spellings.list().subspan(1)) aliases.append(text(std::string(a)));
  d["aliases"] = aliases;
  d["description"] = text(std::string(description));
  return d;
}

template <class Row, size_t N>
py::list axisRows(const std::array<Row, N>& table, Spellings Row::*spellings) {
  py::list out;
  for (const Row& r : table) out.append(axisRow(r.*spellings, r.description));
  return out;
}

py::dict sceneAxes(const PyScene& s) {
  const IntegratorDesc& d = s.loaded.settings.integrator;
  py::dict out;
  const auto put = [&](const char* axis, std::string_view name) { out[axis] = text(std::string(name)); };
  put("integrator", nameOf(d.type));
  if (d.usesEstimator()) put("measure", measureName(d));
  if (d.usesWarp()) put("warp", nameOf(d.warp));
  if (d.usesLightSelection()) put("light_selection", nameOf(d.lightSelection));
  if (d.usesMisAxes()) put("light_measure", nameOf(d.lightMeasure)), put("heuristic", nameOf(d.heuristic));
  return out;
}

// "True"/"False" for bools (the scene syntax), str() for everything else.
std::string overrideValue(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) || py::isinstance<py::str>(value))
    return textArgument(py::str(value), "value of '" + key + "'");
  throw py::type_error("value of '" + key + "': expected str, int, float or bool, got " +
                       py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

std::vector<std::pair<std::string, std::string>> overrideList(const py::object& overrides) {
  std::vector<std::pair<std::string, std::string>> out;
  if (overrides.is_none()) return out;
  if (!py::isinstance<py::dict>(overrides))
    throw py::type_error("overrides: expected a dict {'tag.property': value}");
  for (auto [k, v] : overrides.cast<py::dict>()) {
    if (!py::isinstance<py::str>(k)) throw py::type_error("overrides: keys must be str 'tag.property'");
    std::string key = textArgument(k, "overrides");
    out.emplace_back(key, overrideValue(v, key));
  }
  return out;
}

PyScene loadFile(const py::object& path, const py::object& overrides) {
  std::string file = pathArgument(path, "path");
  auto list = overrideList(overrides);
  py::gil_scoped_release release;
  return PyScene{loadScene(file, list)};
}

PyScene loadString(const std::string& xml, const py::object& baseDir, const std::string& name,
                   const py::object& overrides) {
  checkNoNul(name, "name");  // the XML's own NUL bytes are the parser's (file and line)
  auto list = overrideList(overrides);
  const bool none =
      baseDir.is_none() ||
      ((py::isinstance<py::str>(baseDir) || py::isinstance<py::bytes>(baseDir)) && py::len(baseDir) == 0);
  std::string dir = none ? std::filesystem::current_path().string() : pathArgument(baseDir, "base_dir");
  py::gil_scoped_release release;
  return PyScene{loadSceneFromString(xml, name, dir, list)};
}

// Scene.set: applies the override to the description, then rebuilds what it can change (only the
// settings for camera, sampler, integrator and filter; the whole world otherwise).
void setProperty(PyScene& s, const std::string& key, const py::handle& value) {
  checkNoNul(key, "key");
  std::string text = overrideValue(value, key);
  SceneNode desc = s.loaded.desc;
  applyOverride(desc, key, text);
  std::string tag = key.substr(0, key.find('.'));
  if (tag == "camera" || tag == "sampler" || tag == "integrator" || tag == "rfilter") {
    std::vector<std::string> warnings;
    RenderSettings settings = buildSettings(desc, &warnings, s.loaded.scene->areaLightCount());
    s.loaded.desc = std::move(desc);
    s.loaded.settings = settings;
    s.loaded.warnings.insert(s.loaded.warnings.end(), warnings.begin(), warnings.end());
  } else {
    std::string path = s.loaded.path;
    LoadedScene rebuilt = buildScene(std::move(desc));
    rebuilt.path = path;
    s.loaded = std::move(rebuilt);
  }
}

py::dict settingsDict(const PyScene& s) {
  py::dict d;
  for (auto& [k, v] : describeSettings(s.loaded.settings)) d[text(k)] = text(v);
  return d;
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      "A loaded scene: its description (editable with set()), the built geometry and "
                      "lights, and the render settings it asks for. Create with load_scene() or "
                      "scene_from_string().")
      .def("set", &setProperty, py::arg("key"), py::arg("value"),
           "Change a property as --set does: key 'tag.property' (e.g. 'sampler.sampleCount', "
           "'integrator.measure', 'camera.fov'), value str/int/float/bool. Raises SceneError for an "
           "unknown key or a bad value (the scene is left unchanged).")
      .def_property_readonly("settings", &settingsDict,
                             "The render settings as the image metadata spells them: integrator and its "
                             "properties, sampler, sampleCount, seed, rfilter, resolution.")
      .def_property_readonly(
          "strategy", [](const PyScene& s) { return text(strategyLabel(s.loaded.settings.integrator)); },
          "The strategy label, e.g. 'direct/solid-angle'.")
      .def_property_readonly("axes", &sceneAxes,
                             "The integrator's axes that apply, e.g. {'integrator': 'direct', 'measure': "
                             "'area', 'light_selection': 'bvh'} (names as axes() spells them).")
      .def_property_readonly(
          "sampler", [](const PyScene& s) { return text(samplerKindName(s.loaded.settings.samplerKind)); },
          "The sampler's canonical name, e.g. 'independent'.")
      .def_property_readonly(
          "sample_count", [](const PyScene& s) { return s.loaded.settings.sampleCount; },
          "The scene's samples per pixel (what render() uses without spp or time).")
      .def_property_readonly(
          "seed", [](const PyScene& s) { return s.loaded.settings.seed; }, "The scene's random seed.")
      .def_property_readonly(
          "width", [](const PyScene& s) { return s.loaded.settings.camera.width; }, "Image width in pixels.")
      .def_property_readonly(
          "height", [](const PyScene& s) { return s.loaded.settings.camera.height; },
          "Image height in pixels.")
      .def_property_readonly(
          "path", [](const PyScene& s) { return pathText(s.loaded.path); },
          "The file it came from ('' for a string).")
      .def_property_readonly(
          "warnings", [](const PyScene& s) { return textList(s.loaded.warnings); },
          "Warnings of loading (e.g. unused properties).")
      .def(
          "to_xml", [](const PyScene& s) { return text(writeScene(s.loaded.desc, s.loaded.settings)); },
          "The description, overrides and set() applied, with its settings in canonical spelling (the "
          "integrator's properties, the sampler's type), as scene XML.")
      .def("__repr__", [](const PyScene& s) {
        return py::str("<penumbra.Scene {} {}x{} {}>")
            .format(s.loaded.path.empty() ? py::str("<string>") : pathText(s.loaded.path),
                    s.loaded.settings.camera.width, s.loaded.settings.camera.height,
                    text(strategyLabel(s.loaded.settings.integrator)));
      });

  m.def("load_scene", &loadFile, py::arg("path"), py::arg("overrides") = py::none(),
        "Load a scene file (Nori-style XML, UTF-8). path: str, bytes or os.PathLike. overrides: "
        "{'tag.property': value} applied as --set does, e.g. {'integrator.measure': 'area', "
        "'sampler.sampleCount': 64}. Raises SceneError with .file and .line (also for bytes that are "
        "not UTF-8 text).");
  m.def("scene_from_string", &loadString, py::arg("xml"), py::arg("base_dir") = "",
        py::arg("name") = "<string>", py::arg("overrides") = py::none(),
        "Load a scene from XML text. base_dir resolves relative paths (OBJ files; default: the "
        "current directory); name is the file name in error messages.");

  m.def(
      "axes",
      [] {
        py::dict out;
        out["integrator"] = axisRows(kIntegratorTypes, &IntegratorTypeRow::xmlType);
        py::list measures;
        for (const EstimatorRow& e : kEstimators)
          if (e.estimator == Estimator::Light)
            for (py::handle row : axisRows(kLightMeasures, &LightMeasureRow::spellings)) measures.append(row);
          else
            measures.append(axisRow(e.measure, e.description));
        out["measure"] = measures;
        out["warp"] = axisRows(kWarps, &WarpRow::spellings);
        out["light_selection"] = axisRows(kLightSelections, &LightSelectionRow::spellings);
        out["light_measure"] = axisRows(kLightMeasures, &LightMeasureRow::spellings);
        out["heuristic"] = axisRows(kHeuristics, &HeuristicRow::spellings);
        return out;
      },
      "The axes a strategy is composed of, each {axis: [{name, aliases, description}]} in table "
      "order: integrator (the XML type), measure (direct: hemisphere, each light measure, mis), warp "
      "(ao, and the hemisphere measure), light_selection (the light measures), light_measure and "
      "heuristic (mis).");
  m.def(
      "samplers",
      [] {
        py::list out;
        for (const SamplerRow& r : samplerTable()) {
          py::dict d;
          d["name"] = text(samplerKindName(r.kind));
          d["label"] = text(std::string(r.label));
          d["description"] = text(std::string(r.description));
          d["uses_sample_count"] = r.usesSampleCount();
          out.append(d);
        }
        return out;
      },
      "Every sampler of the sampler table, in table order: name, label, description, "
      "uses_sample_count.");
}

}  // namespace penumbra::python
