#include "core/integrators/integrator_desc.h"

namespace penumbra {

const char* integratorTypeName(IntegratorType type) {
  switch (type) {
    case IntegratorType::Normals:
      return "normals";
    case IntegratorType::Simple:
      return "simple";
    case IntegratorType::Ao:
      return "ao";
    case IntegratorType::Direct:
      return "direct";
  }
  return "?";
}

const char* directMeasureName(DirectMeasure measure) {
  switch (measure) {
    case DirectMeasure::Hemisphere:
      return "hemisphere";
    case DirectMeasure::Area:
      return "area";
    case DirectMeasure::SolidAngle:
      return "solid-angle";
  }
  return "?";
}

const char* hemisphereWarpName(HemisphereWarp warp) {
  return warp == HemisphereWarp::Uniform ? "uniform-hemisphere" : "cosine-hemisphere";
}

bool parseIntegratorType(const std::string& name, IntegratorType& out) {
  for (IntegratorType t :
       {IntegratorType::Normals, IntegratorType::Simple, IntegratorType::Ao, IntegratorType::Direct}) {
    if (name == integratorTypeName(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

bool parseDirectMeasure(const std::string& name, DirectMeasure& out) {
  if (name == "hemisphere")
    out = DirectMeasure::Hemisphere;
  else if (name == "area")
    out = DirectMeasure::Area;
  else if (name == "solid-angle" || name == "solidAngle")
    out = DirectMeasure::SolidAngle;
  else
    return false;
  return true;
}

bool parseHemisphereWarp(const std::string& name, HemisphereWarp& out) {
  if (name == "uniform" || name == "uniform-hemisphere")
    out = HemisphereWarp::Uniform;
  else if (name == "cosine" || name == "cosine-hemisphere")
    out = HemisphereWarp::Cosine;
  else
    return false;
  return true;
}

std::string strategyLabel(const IntegratorDesc& desc) {
  std::string label = integratorTypeName(desc.type);
  if (desc.type == IntegratorType::Ao) {
    label += desc.warp == HemisphereWarp::Uniform ? "/uniform" : "/cosine";
  } else if (desc.type == IntegratorType::Direct) {
    if (desc.measure == DirectMeasure::Hemisphere)
      label += desc.warp == HemisphereWarp::Uniform ? "/uniform-hemisphere" : "/cosine-hemisphere";
    else
      label += std::string("/") + directMeasureName(desc.measure);
  }
  return label;
}

}  // namespace penumbra
