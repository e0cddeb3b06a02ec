#include "core/render/row_renderer.h"

#include "core/render/strategy_table.h"

namespace penumbra {

RowRenderer makeRowRenderer(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  const StrategyRow& row = strategyRow(d.strategy);
  // A light-share job of a row without that output renders radiance (callers check offersLightShare).
  if (job.output == RenderOutput::MisLightShare && row.makeLightShareRows)
    return row.makeLightShareRows(job, d);
  return row.makeRows(job, d);
}

}  // namespace penumbra
